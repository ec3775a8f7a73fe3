#pragma once
/// \file parallel.hpp
/// Helpers of the simulation's OpenMP loops: the deterministic schedule of the contact pass
/// (`run_paired_chunks`), waiting on another thread's chunk, the static share of a thread, and a
/// maximum that keeps NaN.

#include <algorithm>
#include <array>
#include <atomic>
#include <cstddef>
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
/// Runs `run(begin, end)` over the chunks [c chunk, (c + 1) chunk) of n rows (`parallel`: on the
/// threads of an OpenMP team), where the rows of chunk c write to chunks c and c + 1 only (chunk
/// >= the largest index distance of two rows that write the same item), and n / chunk <= 64.
///
/// An even chunk never waits; an odd chunk runs once the even chunks on both sides are done.
/// Every item thus receives the writes of the even chunk's rows before those of the odd chunk's,
/// whatever the number of threads (the same bits), and no two chunks that write the same item
/// run at once. The chunks go to the threads in contiguous runs of about equal work (`work(b, e)`
/// of rows [b, e)), in row order: a thread works on about the rows it has in static passes over
/// the rows, whose data stay in its caches (on some machines the two cores do not share a cache).
/// A thread runs its chunks from its last one down, each even chunk followed by the odd one above
/// it (..., 4, 5, 2, 3, 0, 1), while the data of both are still in the caches (at N = 1e6 the
/// data of a step do not fit, and running all even chunks before all odd ones read much of them
/// twice).
template <class Work, class Run>
void run_paired_chunks(long n, long chunk, const Work& work, const Run& run, bool parallel) {
  const long nchunks = (n + chunk - 1) / chunk;
  auto weight = [&](long c) { return work(c * chunk, std::min(n, (c + 1) * chunk)); };
  std::array<std::atomic<int>, 64> done{}; // at most 64 chunks
  double total = 0.0;
  for (long c = 0; c < nchunks; ++c)
    total += weight(c);
#pragma omp parallel if (parallel)
  {
    long thread = 0, threads = 1;
#ifdef _OPENMP
    thread = omp_get_thread_num();
    threads = omp_get_num_threads();
#endif
    // this thread's chunks [a, b)
    long a = nchunks, b = nchunks;
    double before = 0.0;
    for (long c = 0; c < nchunks; ++c) {
      const double w = weight(c);
      const auto owner = std::min(threads - 1, static_cast<long>(static_cast<double>(threads) *
                                                                 (before + 0.5 * w) / total));
      before += w;
      if (owner == thread) {
        a = std::min(a, c);
        b = c + 1;
      }
    }
    auto one = [&](long c) {
      if (c % 2 == 1) {
        wait_for(done[static_cast<std::size_t>(c - 1)]);
        if (c + 1 < nchunks) wait_for(done[static_cast<std::size_t>(c + 1)]);
      }
      run(c * chunk, std::min(n, (c + 1) * chunk));
      done[static_cast<std::size_t>(c)].store(1, std::memory_order_release);
    };
    // from the top down, each even chunk followed by the odd one above it; an odd last chunk
    // waits for the next thread's first one, which that thread runs last: it goes last too
    const long deferred = (b - 1) % 2 == 1 && b < nchunks && b - 1 >= a ? b - 1 : -1;
    for (long c = (b - 1) - (b - 1) % 2; c >= a; c -= 2) {
      one(c);
      if (c + 1 < b && c + 1 != deferred) one(c + 1);
    }
    if (a % 2 == 1 && a < b && a != deferred) one(a);
    if (deferred >= 0) one(deferred);
  }
}

/// x, or +inf if x is NaN: a maximum taken with std::max would drop a NaN.
inline double nan_as_inf(double x) { return x == x ? x : std::numeric_limits<double>::infinity(); }

} // namespace grain::detail
