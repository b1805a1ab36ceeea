// A measuring aid, never for deployment: what Fast DDS 2.9's failing SO_SNDTIMEO costs.
//
// Fast DDS 2.9's UDP transport calls setsockopt(SO_SNDTIMEO) before every datagram with
// tv_sec = 0 and tv_usec = the whole send timeout; on the synchronous write path that timeout
// is RTPSMessageGroup's default, now + 24 h, so tv_usec = 86,399,999,99x and Linux answers EDOM
// (strace: one failed call per sample sent). The call changes nothing, but it is a system call.
// Preloaded (LD_PRELOAD=.../libteleop_sndtimeo_shim.so), this answers such calls with the same
// EDOM without entering the kernel, and passes every other call through; docs/benchmarks.md
// compares round trips with and without it.
#include <dlfcn.h>
#include <sys/socket.h>
#include <sys/time.h>

#include <cerrno>

using SetsockoptFn = int (*)(int, int, int, const void*, socklen_t);

extern "C" int setsockopt(int fd, int level, int name, const void* value, socklen_t length) noexcept {
  static const auto real = reinterpret_cast<SetsockoptFn>(dlsym(RTLD_NEXT, "setsockopt"));
  if (level == SOL_SOCKET && name == SO_SNDTIMEO && value != nullptr && length >= sizeof(timeval)) {
    const auto* tv = static_cast<const timeval*>(value);
    if (tv->tv_usec < 0 || tv->tv_usec >= 1'000'000) {
      errno = EDOM;  // what the kernel would answer
      return -1;
    }
  }
  return real(fd, level, name, value, length);
}
