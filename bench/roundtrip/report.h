#pragma once
// The report: the table of all variants with the ratios of the same run, and the per-sample CSV.

#include <string>
#include <vector>

#include "pinger.h"

namespace teleop::bench {

/// The table (one row per variant), then the ratios teleop/raw and security on/off.
void print_results(const std::vector<VariantResult>& results);

/// Every measured round trip: variant,index,seq,rtt_ns (rtt_ns empty: lost).
void write_csv(const std::string& path, const std::vector<VariantResult>& results);

}  // namespace teleop::bench
