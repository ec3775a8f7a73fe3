#pragma once
/// \file history.hpp
/// Per-contact history storage: one `History` per entry of a neighbour list (particle pairs and
/// particle-wall pairs), and how it survives a rebuild of the list. A history lives as long as
/// its contact: the contact pass blanks it when the pair stops touching, and a rebuild carries
/// every history that is not blank over to the new list by particle identity (through a
/// re-sorting, removals and additions), mirrored when the two partners swap roles.
///
/// A blank history is bytewise a value-initialised `History{}` (nothing to carry). Histories
/// must be trivially copyable; an empty `History` (stateless contact laws) stores nothing.

#include <grain/search/neighbor_list.hpp>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <type_traits>
#include <utility>
#include <vector>

namespace grain {
namespace detail {
/// Zero if a and b have the same bytes, without a branch (memcmp may branch after each word).
template <class T>
GRAIN_INLINE std::uint64_t byte_difference(const T& a, const T& b) {
  static_assert(std::is_trivially_copyable_v<T>);
  const auto* x = reinterpret_cast<const unsigned char*>(&a);
  const auto* y = reinterpret_cast<const unsigned char*>(&b);
  std::uint64_t diff = 0;
  std::size_t k = 0;
  for (; k + 8 <= sizeof(T); k += 8) {
    std::uint64_t u, v;
    std::memcpy(&u, x + k, 8);
    std::memcpy(&v, y + k, 8);
    diff |= u ^ v;
  }
  for (; k < sizeof(T); ++k)
    diff |= static_cast<std::uint64_t>(x[k] ^ y[k]);
  return diff;
}
/// Zero if every byte of a is zero, without a branch (byte_difference against a zero value
/// without reading one).
template <class T>
GRAIN_INLINE std::uint64_t any_bits(const T& a) {
  static_assert(std::is_trivially_copyable_v<T>);
  const auto* x = reinterpret_cast<const unsigned char*>(&a);
  std::uint64_t bits = 0;
  std::size_t k = 0;
  for (; k + 8 <= sizeof(T); k += 8) {
    std::uint64_t u;
    std::memcpy(&u, x + k, 8);
    bits |= u;
  }
  for (; k < sizeof(T); ++k)
    bits |= static_cast<std::uint64_t>(x[k]);
  return bits;
}
} // namespace detail

/// The histories of the contacts of one neighbour list: `pair[e]` for the particle-pair entry e
/// (NeighborList::partners), `wall[e]` for the particle-wall entry e (NeighborList::walls).
/// Empty (never allocated) when `History` is an empty struct.
template <class History>
struct ContactHistories {
  static_assert(std::is_trivially_copyable_v<History>,
                "grain: a model's per-contact History must be trivially copyable");
  /// True if the contact laws keep no state (nothing is stored).
  static constexpr bool stateless = std::is_empty_v<History>;
  /// An index that maps to no particle of the old list (a particle added since).
  static constexpr std::uint32_t none = std::numeric_limits<std::uint32_t>::max();

  std::vector<History> pair, wall;

  /// True if h is bytewise a value-initialised history: nothing to carry over. (A history equal
  /// in value but not in bytes, e.g. with -0.0, counts as not blank: it is merely kept.)
  static bool blank(const History& h) {
    static const History zero{};
    return detail::byte_difference(h, zero) == 0;
  }

  /// The entries of `hist` that are not blank, with their indices.
  static std::vector<std::pair<std::size_t, History>> keep(const std::vector<History>& hist) {
    std::vector<std::pair<std::size_t, History>> kept;
    if constexpr (!stateless)
      for (std::size_t e = 0; e < hist.size(); ++e)
        if (!blank(hist[e])) kept.emplace_back(e, hist[e]);
    return kept;
  }
  /// Sets `hist` to the entries kept by keep(), blank elsewhere.
  static void restore(std::vector<History>& hist,
                      const std::vector<std::pair<std::size_t, History>>& kept) {
    if constexpr (!stateless) {
      std::fill(hist.begin(), hist.end(), History{});
      for (const auto& [e, h] : kept)
        hist[e] = h;
    }
  }

  /// A copy of the state that restore_all() puts back: the histories that are not blank.
  struct Saved {
    std::vector<std::pair<std::size_t, History>> pair, wall;
  };
  Saved save() const { return {keep(pair), keep(wall)}; }
  void restore_all(const Saved& s) {
    restore(pair, s.pair);
    restore(wall, s.wall);
  }

  /// Removes the entries with a blank history from a CSR list and its histories, in place, and
  /// frees the space (no histories: the list is left as it is).
  static void drop_blank_entries(std::vector<std::uint32_t>& offsets,
                                 std::vector<std::uint32_t>& entries, std::vector<History>& hist) {
    if (hist.size() != entries.size()) return; // no histories (first build)
    std::uint32_t out = 0, begin = offsets[0];
    for (std::size_t i = 0; i + 1 < offsets.size(); ++i) {
      const std::uint32_t end = offsets[i + 1];
      for (std::uint32_t e = begin; e < end; ++e)
        if (!blank(hist[e])) {
          entries[out] = entries[e];
          hist[out] = hist[e];
          ++out;
        }
      begin = end;
      offsets[i + 1] = out;
    }
    entries.resize(out);
    hist.resize(out);
    entries.shrink_to_fit();
    hist.shrink_to_fit();
  }

  /// Keeps only the contacts that have a history, in `old` and in these histories (before a
  /// rebuild: the peak memory of a rebuild holds both lists, and only these are looked up).
  void shrink_to_contacts(NeighborList& old) {
    if constexpr (!stateless) {
      drop_blank_entries(old.offsets, old.partners, pair);
      drop_blank_entries(old.wall_offsets, old.walls, wall);
    }
  }

  /// Blank histories for every entry of `list`.
  void reset(const NeighborList& list) {
    if constexpr (!stateless) {
      pair.assign(list.partners.size(), History{});
      wall.assign(list.walls.size(), History{});
    }
  }

  /// The histories of `list`, a new list, taken from `old` and `from` (the histories of `old`)
  /// by particle identity: `old_of(k)` is the row in `old` of the particle that is row k of
  /// `list`, or `none` for a particle `old` does not know. A pair whose partners swapped roles
  /// (the old row is the larger index) gets `reverse(h)` applied. Every other entry is blank.
  /// Rows run in parallel (OpenMP) above `threshold` rows; the result does not depend on it.
  /// Each row of `old` must hold its partners in ascending order (NeighborList's invariant).
  template <class OldOf, class Reverse>
  void carry_over(const NeighborList& old, const ContactHistories& from, const NeighborList& list,
                  OldOf&& old_of, Reverse&& reverse, long threshold) {
    if constexpr (stateless) {
      (void)old, (void)from, (void)list, (void)old_of, (void)reverse, (void)threshold;
    } else {
      reset(list);
      if (old.rows() == 0) return;
      const long n = static_cast<long>(list.rows());
#pragma omp parallel for schedule(static) if (n >= threshold)
      for (long i = 0; i < n; ++i) {
        const std::uint32_t a = old_of(static_cast<std::size_t>(i));
        if (a == none) continue;
        for (const auto e : list.pair_entries(i)) {
          const std::uint32_t b = old_of(list.partners[e]);
          if (b == none) continue;
          const std::uint32_t lo = std::min(a, b), hi = std::max(a, b);
          const auto first = old.partners.begin() + old.offsets[lo];
          const auto last = old.partners.begin() + old.offsets[lo + 1];
          const auto it = std::lower_bound(first, last, hi);
          if (it != last && *it == hi) {
            pair[e] = from.pair[static_cast<std::size_t>(it - old.partners.begin())];
            if (a > b) reverse(pair[e]);
          }
        }
        for (const auto e : list.wall_entries(i)) {
          for (const auto o : old.wall_entries(a))
            if (old.walls[o] == list.walls[e]) {
              wall[e] = from.wall[o];
              break;
            }
        }
      }
    }
  }
};

} // namespace grain
