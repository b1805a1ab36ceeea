// ThreadSanitizer build only (TELEOP_TSAN): GCC 12's TSan runtime intercepts
// pthread_mutex_timedlock but not pthread_mutex_clocklock, which glibc's std::timed_mutex uses for
// try_lock_until on the steady clock, and which Fast DDS 2.9 calls on every send. TSan then sees
// those mutexes unlocked without a lock (reports in Fast DDS, races that are none in code they
// protect). Defined in the executable, this one takes the calls of Fast DDS and hands them to the
// intercepted pthread_mutex_timedlock with the same deadline on CLOCK_REALTIME.
#include <pthread.h>
#include <time.h>

#include <cstdint>

namespace {

int64_t to_ns(const timespec& t) { return int64_t{t.tv_sec} * 1'000'000'000 + t.tv_nsec; }

timespec from_ns(int64_t ns) {
  timespec t{};
  t.tv_sec = static_cast<time_t>(ns / 1'000'000'000);
  t.tv_nsec = static_cast<long>(ns % 1'000'000'000);
  return t;
}

}  // namespace

extern "C" int pthread_mutex_clocklock(pthread_mutex_t* mutex, clockid_t clock, const timespec* abstime) {
  if (clock == CLOCK_REALTIME) return pthread_mutex_timedlock(mutex, abstime);
  timespec now_clock{};
  timespec now_real{};
  clock_gettime(clock, &now_clock);
  clock_gettime(CLOCK_REALTIME, &now_real);
  const timespec deadline = from_ns(to_ns(now_real) + (to_ns(*abstime) - to_ns(now_clock)));
  return pthread_mutex_timedlock(mutex, &deadline);
}
