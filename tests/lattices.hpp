#pragma once
// Point sets and brute-force neighbour lists shared by the cell-size tests.
#include <grain/core/vector.hpp>
#include <grain/search/neighbor_list.hpp>

#include <cstdint>
#include <vector>

namespace grain::test {

/// Half neighbour list of all pairs closer than `cut` (brute force), no walls.
template <int D>
NeighborList pairs_within(const std::vector<Vec<D>>& x, double cut) {
  NeighborList nl;
  nl.clear(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) {
    for (std::size_t j = i + 1; j < x.size(); ++j)
      if ((x[i] - x[j]).norm() < cut) nl.partners.push_back(static_cast<std::uint32_t>(j));
    nl.offsets.push_back(static_cast<std::uint32_t>(nl.partners.size()));
    nl.wall_offsets.push_back(0);
  }
  return nl;
}

/// n x n square lattice of spacing s (row by row).
inline std::vector<Vec2> square_lattice(int n, double s) {
  std::vector<Vec2> x;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
      x.emplace_back(i * s, j * s);
  return x;
}

} // namespace grain::test
