#pragma once
/// \file parallel.hpp
/// Helpers of the simulation's OpenMP loops: waiting on another thread's chunk, the static share
/// of a thread, and a maximum that keeps NaN.

#include <algorithm>
#include <atomic>
#include <limits>
#include <thread>
#include <utility>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace grain::detail {

/// Loops over fewer items than this run on one thread (a parallel region costs more).
inline constexpr long parallel_threshold = 1000;

/// Waits until another thread has set `flag` (release) to non-zero; its writes before are then
/// visible. Spins briefly, then yields (more threads than cores).
inline void wait_for(const std::atomic<int>& flag) {
  for (int spins = 0; flag.load(std::memory_order_acquire) == 0;) {
    if (spins < 64)
      ++spins;
    else
      std::this_thread::yield();
  }
}
/// The calling thread's share [lo, hi) of n items, contiguous and in thread order, as
/// schedule(static) splits them.
inline std::pair<long, long> static_share(long n) {
#ifdef _OPENMP
  const long threads = omp_get_num_threads(), t = omp_get_thread_num();
#else
  const long threads = 1, t = 0;
#endif
  const long q = n / threads, r = n % threads;
  const long lo = t * q + std::min(t, r);
  return {lo, lo + q + (t < r ? 1 : 0)};
}
/// x, or +inf if x is NaN: a maximum taken with std::max would drop a NaN.
inline double nan_as_inf(double x) { return x == x ? x : std::numeric_limits<double>::infinity(); }

} // namespace grain::detail
