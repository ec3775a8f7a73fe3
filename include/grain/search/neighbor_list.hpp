#pragma once
/// \file neighbor_list.hpp
/// The candidate list every search produces: a half neighbour list in CSR form (row i holds the
/// partners j > i, ascending) and a per-particle list of candidate walls.

#include <cstdint>
#include <vector>

namespace grain {

/// The entries [first, last) of one row of a NeighborList, as a range of entry indices:
/// `for (const auto e : list.pair_entries(i)) ... list.partners[e] ...`.
struct EntryRange {
  struct iterator {
    std::uint32_t e;
    std::uint32_t operator*() const { return e; }
    iterator& operator++() {
      ++e;
      return *this;
    }
    bool operator==(const iterator&) const = default;
  };
  std::uint32_t first, last;
  iterator begin() const { return {first}; }
  iterator end() const { return {last}; }
  std::uint32_t size() const { return last - first; }
};

struct NeighborList {
  std::vector<std::uint32_t> offsets{0};      ///< row i is partners[offsets[i], offsets[i+1])
  std::vector<std::uint32_t> partners;        ///< j > i
  std::vector<std::uint32_t> wall_offsets{0}; ///< row i is walls[wall_offsets[i], ...)
  std::vector<std::uint32_t> walls;           ///< wall indices
  std::uint32_t max_span = 0;                 ///< largest j - i in the list

  std::size_t rows() const { return offsets.size() - 1; }
  /// The particle-pair entries of row i (indices into `partners`).
  EntryRange pair_entries(std::size_t i) const { return {offsets[i], offsets[i + 1]}; }
  /// The particle-wall entries of row i (indices into `walls`).
  EntryRange wall_entries(std::size_t i) const { return {wall_offsets[i], wall_offsets[i + 1]}; }
  void clear(std::size_t n) {
    offsets.assign(1, 0);
    offsets.reserve(n + 1);
    partners.clear();
    wall_offsets.assign(1, 0);
    wall_offsets.reserve(n + 1);
    walls.clear();
    max_span = 0;
  }
};

} // namespace grain
