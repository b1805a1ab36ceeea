#include "teleop/can/bus_load.h"

namespace teleop::can {

BusLoad bus_load(std::span<const Traffic> traffic, double bitrate_bps) {
  BusLoad load;
  for (const Traffic& t : traffic) {
    const double frames_per_s = t.frames * t.rate_hz;
    load.frames_per_s += frames_per_s;
    load.bits_per_s_nominal += frames_per_s * frame_bits_nominal(t.data_bytes, t.format);
    load.bits_per_s_worst_case += frames_per_s * frame_bits_worst_case(t.data_bytes, t.format);
  }
  if (bitrate_bps > 0) {
    load.load_nominal = load.bits_per_s_nominal / bitrate_bps;
    load.load_worst_case = load.bits_per_s_worst_case / bitrate_bps;
  }
  return load;
}

}  // namespace teleop::can
