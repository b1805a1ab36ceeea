#pragma once
// The report: the table of all variants with the ratios of the same run, the per-sample CSV and
// the one-line-per-variant summary CSV the scaling study collects.

#include <string>
#include <vector>

#include "pinger.h"

namespace teleop::bench {

/// The table (one row per variant), then the ratios to bare Fast DDS and raw UDP, and security on/off.
void print_results(const std::vector<VariantResult>& results);

/// Every measured round trip: variant,index,seq,topic,rtt_ns (rtt_ns empty: lost).
void write_csv(const std::string& path, const std::vector<VariantResult>& results);

/// One line per variant (with a header when the file is new): the run's parameters, the
/// percentiles [us], the CPU per round trip [us] and the load average.
void append_summary_csv(const std::string& path, const Options& opt, size_t payload_bytes,
                        const std::vector<VariantResult>& results);

}  // namespace teleop::bench
