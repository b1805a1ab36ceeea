#pragma once
// Any teleop sample as readable text: `teleop topic echo` prints these. Nested fields are YAML
// blocks, sequences of numbers flow lists, enums their names.

#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "teleop/transport/sample_types.h"

namespace teleop::tools {

/// The sample in `cdr` (its serialized bytes, encapsulation first) of `type` as YAML text.
/// `field` selects one field by its dotted path ("header.seq", "q_rad", "links[0].peer"): then
/// only its value is printed; "" prints the whole sample. Throws std::runtime_error when the
/// bytes do not hold a sample of the type or the field does not exist.
std::string sample_text(const transport::SampleType& type, const std::vector<uint8_t>& cdr,
                        std::string_view field = {});

/// The sample's fields flat, as the columns of a CSV row: (dotted path, value as text) in the
/// order of the type, a sequence's items as name[i] ("q_rad[0]", "links[1].peer"). Throws
/// std::runtime_error when the bytes do not hold a sample of the type.
std::vector<std::pair<std::string, std::string>> sample_fields(const transport::SampleType& type,
                                                               const std::vector<uint8_t>& cdr);

/// The header every teleop sample starts with, read from its serialized bytes (no full
/// deserialization): for tools that look at sequence numbers and stamps of any type.
struct HeaderView {
  uint64_t seq = 0;
  int64_t stamp_ns = 0;
  int64_t stamp_mono_ns = 0;
};
/// False when the bytes are too short or not CDR.
bool read_header(const std::vector<uint8_t>& cdr, HeaderView& header);
/// Overwrites the header's stamps in place (replay: the receivers' staleness checks see fresh
/// samples). False when the bytes are too short or not CDR.
bool restamp_header(std::vector<uint8_t>& cdr, int64_t stamp_ns, int64_t stamp_mono_ns);

}  // namespace teleop::tools
