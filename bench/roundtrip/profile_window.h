#pragma once
// The measured window for callgrind (bench/roundtrip_profile.sh): statistics are zeroed when it
// opens and dumped when it closes, so a profile holds the round trips only, not the setup and
// discovery. Without valgrind's header, or outside valgrind, these do nothing.

#if defined(TELEOP_HAVE_CALLGRIND)
#include <valgrind/callgrind.h>
#endif

namespace teleop::bench {

inline void profile_window_open() {
#if defined(TELEOP_HAVE_CALLGRIND)
  CALLGRIND_ZERO_STATS;
#endif
}

inline void profile_window_close() {
#if defined(TELEOP_HAVE_CALLGRIND)
  CALLGRIND_DUMP_STATS_AT("window");
#endif
}

}  // namespace teleop::bench
