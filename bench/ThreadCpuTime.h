#pragma once
// This thread's CPU time: what the benchmarks time when "one core" is the
// question (other threads, e.g. the rawlog reader's decoder, do not count).
#include <time.h>

namespace srp::bench {

/// Seconds of CPU time this thread has used.
inline double threadCpu_s() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

}  // namespace srp::bench
