#pragma once
/// \file search.hpp
/// Neighbour searches: which pairs of particles, and which particle-wall pairs, are tested for
/// contact. All three produce the same `NeighborList` and never detect a contact late: a list
/// built with a skin s holds every pair closer than R_i + R_j + cutoff + s, and it is rebuilt
/// before any particle has moved s/2 (or a particle plus a wall have together moved s).
///
/// | type | build | rebuilt |
/// |---|---|---|
/// | `AllPairs` | test all pairs, O(N^2) | every step, no skin (the seed's "simple loop") |
/// | `VerletList` | test all pairs, O(N^2), keep those within the skin | every `frequency` steps, or earlier when the displacement demands it (the seed's "restricted loop") |
/// | `CellList` | linked cells of size >= 2 R_max + cutoff + skin, particles re-sorted by cell, O(N) | when the displacement demands it |
///
/// A search is a type with static members only (concept `Search`, docs/concepts.md): its
/// settings `Params`, `validate`, the skin, when a rebuild is due, and `build`, which fills the
/// list; optionally `order`, a permutation of the particles applied before each build (memory
/// locality). A program may define its own and give it to `Simulation` as its 2nd argument.

#include <algorithm>
#include <cmath>
#include <concepts>
#include <cstdint>
#include <grain/core/error.hpp>
#include <grain/particles/storage.hpp>
#include <grain/search/neighbor_list.hpp>
#include <grain/search/periodic.hpp>
#include <grain/walls/walls.hpp>
#include <limits>
#include <numeric>
#include <string>
#include <vector>

namespace grain::search {

/// Appends the wall row of particle i to `list` (after its particle row): every wall whose
/// nearest point is closer to the centre than radius + reach. A search's `build` calls it once
/// per particle, in particle order.
template <int D>
void add_wall_row(const ParticleArrays<D>& p, const std::vector<Wall<D>>& walls, double reach,
                  NeighborList& list, std::size_t i) {
  for (std::uint32_t w = 0; w < walls.size(); ++w) {
    if (!walls[w].present) continue;                   // switched off, not yet created or removed
    const auto prox = walls[w].nearest(p.position[i]); // a mesh triangle's own nearest point
    if (prox.distance < p.radius[i] + reach) list.walls.push_back(w);
  }
  list.wall_offsets.push_back(static_cast<std::uint32_t>(list.walls.size()));
}

namespace detail {
template <int D>
void build_all_pairs(const ParticleArrays<D>& p, const std::vector<Wall<D>>& walls, double reach,
                     NeighborList& list, const PeriodicBox<D>* box = nullptr);
template <int D>
void build_cells(const ParticleArrays<D>& p, const std::vector<Wall<D>>& walls, double reach,
                 double r_max, NeighborList& list);
template <int D>
void build_periodic(const ParticleArrays<D>& p, const std::vector<Wall<D>>& walls, double reach,
                    double r_max, const PeriodicBox<D>& box, NeighborList& list);
template <int D>
std::vector<std::uint32_t> cell_order(const ParticleArrays<D>& p, double cell_size,
                                      const PeriodicBox<D>* box = nullptr);
} // namespace detail

/// Every pair tested at every step (reference search; O(N^2)).
struct AllPairs {
  static constexpr const char* name = "all pairs";
  struct Params {};
  static void validate(const Params&) {}
  static double skin(const Params&, double) { return 0.0; }
  static bool due(const Params&, long, bool) { return true; }
  template <int D>
  static void build(const Params&, const ParticleArrays<D>& p, const std::vector<Wall<D>>& walls,
                    double reach, double, NeighborList& list) {
    detail::build_all_pairs(p, walls, reach, list);
  }
  template <int D>
  static void build(const Params&, const ParticleArrays<D>& p, const std::vector<Wall<D>>& walls,
                    double reach, double, const PeriodicBox<D>& box, NeighborList& list) {
    detail::build_all_pairs(p, walls, reach, list, &box);
  }
};

/// Per-particle lists of partners within a skin (verlet distance), rebuilt at a set frequency
/// or automatically.
struct VerletList {
  static constexpr const char* name = "Verlet list";
  struct Params {
    double skin = 0.0; ///< extra search distance [m]; 0 = 0.5 R_max
    int frequency = 0; ///< rebuild every n steps; 0 = only when the displacement demands it
  };
  static void validate(const Params& p) {
    grain::detail::require_non_negative("search::VerletList", "skin", p.skin);
    grain::detail::require(p.frequency >= 0, "search::VerletList", "frequency", p.frequency,
                           "[0, inf) steps (0 = automatic)");
  }
  static double skin(const Params& p, double r_max) { return p.skin > 0 ? p.skin : 0.5 * r_max; }
  static bool due(const Params& p, long steps_since, bool moved_too_far) {
    return moved_too_far || (p.frequency > 0 && steps_since >= p.frequency);
  }
  template <int D>
  static void build(const Params&, const ParticleArrays<D>& p, const std::vector<Wall<D>>& walls,
                    double reach, double, NeighborList& list) {
    detail::build_all_pairs(p, walls, reach, list);
  }
  template <int D>
  static void build(const Params&, const ParticleArrays<D>& p, const std::vector<Wall<D>>& walls,
                    double reach, double, const PeriodicBox<D>& box, NeighborList& list) {
    detail::build_all_pairs(p, walls, reach, list, &box);
  }
};

/// Linked cells with a skin; particles are re-sorted by cell at every rebuild.
struct CellList {
  static constexpr const char* name = "cell list";
  struct Params {
    double skin = 0.0; ///< extra search distance [m]; 0 = 0.2 R_max
    bool sort = true;  ///< re-sort particles by cell at rebuilds (memory locality)
  };
  static void validate(const Params& p) {
    grain::detail::require_non_negative("search::CellList", "skin", p.skin);
  }
  static double skin(const Params& p, double r_max) { return p.skin > 0 ? p.skin : 0.2 * r_max; }
  static bool due(const Params&, long, bool moved_too_far) { return moved_too_far; }
  /// The particles sorted by cell (cells of 2 R_max + reach), unless `sort` is off.
  /// With periodic boundaries (`box`), the grid spans the box along the periodic axes.
  template <int D>
  static std::vector<std::uint32_t> order(const Params& prm, const ParticleArrays<D>& p,
                                          double reach, double r_max,
                                          const PeriodicBox<D>* box = nullptr) {
    if (!prm.sort || p.size() < 2) return {};
    return detail::cell_order(p, 2.0 * r_max + reach, box);
  }
  template <int D>
  static void build(const Params&, const ParticleArrays<D>& p, const std::vector<Wall<D>>& walls,
                    double reach, double r_max, NeighborList& list) {
    detail::build_cells(p, walls, reach, r_max, list);
  }
  template <int D>
  static void build(const Params&, const ParticleArrays<D>& p, const std::vector<Wall<D>>& walls,
                    double reach, double r_max, const PeriodicBox<D>& box, NeighborList& list) {
    if (box.on)
      detail::build_periodic(p, walls, reach, r_max, box, list);
    else
      detail::build_cells(p, walls, reach, r_max, list);
  }
};

/// A neighbour search for particles of dimension D (docs/concepts.md). With `prm` its Params,
/// `p` the particles, `walls` the walls, `reach` [m] the distance beyond contact within which
/// pairs must be listed (skin plus the largest conduction cut-off), `r_max` [m] the largest
/// radius present or to come:
/// - `S::validate(prm)` throws InputError for bad settings;
/// - `S::skin(prm, r_max)` is the skin [m] (0: the list is rebuilt every step);
/// - `S::due(prm, steps_since_rebuild, moved_too_far)` is true when the list must be rebuilt
///   (`moved_too_far`: the displacement since the last build reached the skin; a search must
///   then return true, or contacts are found late);
/// - `S::build(prm, p, walls, reach, r_max, list)` fills `list` (NeighborList: clear it first)
///   with every pair i < j whose gap is below `reach`, row i holding its partners j in ascending
///   order, then with add_wall_row(p, walls, reach, list, i) for each particle i in order, and
///   sets `list.max_span` to the largest j - i;
/// - optionally `S::order(prm, p, reach, r_max)` returns a permutation (new index k holds the
///   particle at old index perm[k]; empty = keep the order) that the simulation applies to every
///   particle array before `build`.
template <class S, int D = 3>
concept Search = requires(const typename S::Params& prm, const ParticleArrays<D>& p,
                          const std::vector<Wall<D>>& walls, NeighborList& list) {
  S::validate(prm);
  { S::skin(prm, 1.0) } -> std::convertible_to<double>;
  { S::due(prm, 1L, true) } -> std::convertible_to<bool>;
  S::build(prm, p, walls, 1.0, 1.0, list);
};

/// True if the search S builds lists across periodic boundaries: it has, besides `build`,
/// `S::build(prm, p, walls, reach, r_max, box, list)` with `box` the PeriodicBox, listing each
/// pair whose nearest image (PeriodicBox::separation) is within reach, once. grain's own
/// searches do.
template <class S, int D>
concept PeriodicSearch = requires(const typename S::Params& prm, const ParticleArrays<D>& p,
                                  const std::vector<Wall<D>>& walls, const PeriodicBox<D>& box,
                                  NeighborList& list) {
  S::build(prm, p, walls, 1.0, 1.0, box, list);
};

/// True if the search S re-orders the particles before it builds (`S::order`).
template <class S, int D>
concept Reorders = requires(const typename S::Params& prm, const ParticleArrays<D>& p) {
  { S::order(prm, p, 1.0, 1.0) } -> std::convertible_to<std::vector<std::uint32_t>>;
};

/// One of grain's own searches (their lists are known to be well formed).
template <class S>
inline constexpr bool builtin =
    std::same_as<S, AllPairs> || std::same_as<S, VerletList> || std::same_as<S, CellList>;

/// Throws InputError naming the search unless `list` is a well-formed list of n particles: n
/// rows, partners j > i ascending within each row, wall rows for every particle, `max_span` at
/// least the largest j - i. Checked after each build of a search that is not one of grain's.
inline void require_valid_list(const NeighborList& list, std::size_t n, const char* search) {
  auto fail = [&](const std::string& what) {
    throw InputError(std::string("search '") + search + "': the neighbour list it built " + what +
                     "; valid: the list of docs/concepts.md (rows of partners j > i, ascending, "
                     "and a wall row per particle)");
  };
  if (list.offsets.size() != n + 1 || list.wall_offsets.size() != n + 1)
    fail("has " + std::to_string(list.offsets.size() - 1) + " rows for " + std::to_string(n) +
         " particles");
  if (list.offsets[0] != 0 || list.offsets[n] != list.partners.size() ||
      list.wall_offsets[0] != 0 || list.wall_offsets[n] != list.walls.size())
    fail("has offsets that do not cover its entries");
  // all offsets first: ascending up to the ends checked above, no row reaches past its array
  for (std::size_t i = 0; i < n; ++i)
    if (list.offsets[i + 1] < list.offsets[i] || list.wall_offsets[i + 1] < list.wall_offsets[i])
      fail("has decreasing offsets at row " + std::to_string(i));
  for (std::size_t i = 0; i < n; ++i) {
    std::uint32_t prev = static_cast<std::uint32_t>(i);
    for (const auto e : list.pair_entries(i)) {
      const auto j = list.partners[e];
      if (j <= prev || j >= n)
        fail("has partner " + std::to_string(j) + " in row " + std::to_string(i) +
             " (not above the row and the previous partner, or not a particle)");
      if (j - i > list.max_span) fail("has a max_span below a pair's index distance");
      prev = j;
    }
  }
}

namespace detail {

/// Uniform grid over the particle bounding box (along a periodic axis: over the box, with a
/// whole number of cells of at least the size asked for). Cells are numbered with the axis of the
/// smallest extent fastest and that of the largest slowest: sorted by cell, the particles of
/// neighbouring slabs of cells along the slowest axis are then closest in memory (the list span,
/// about two slabs, is smallest).
template <int D>
struct Grid {
  Vec<D> lo;
  double cell = 1.0;
  std::array<double, 3> size{1.0, 1.0, 1.0}; ///< cell size along each axis [m]
  std::array<long, 3> dims{1, 1, 1};
  std::array<int, 3> axis{0, 1, 2};    ///< the axes from fastest to slowest
  std::array<long, 3> sorted{1, 1, 1}; ///< dims in that order (1 beyond D)

  void setup(const std::vector<Vec<D>>& x, double min_cell, const PeriodicBox<D>* box = nullptr) {
    Vec<D> mn = Vec<D>::Constant(std::numeric_limits<double>::max());
    Vec<D> mx = Vec<D>::Constant(-std::numeric_limits<double>::max());
    for (const auto& p : x) {
      mn = mn.cwiseMin(p);
      mx = mx.cwiseMax(p);
    }
    if (x.empty()) mn = mx = Vec<D>::Zero();
    if (box)
      for (int d = 0; d < D; ++d)
        if (box->axis[d]) {
          mn[d] = box->lo[d];
          mx[d] = box->hi(d);
        }
    lo = mn;
    cell = min_cell;
    // keep the number of cells within a few times the number of particles
    const double max_cells = 8.0 * static_cast<double>(x.size()) + 64.0;
    for (;;) {
      double total = 1.0;
      for (int d = 0; d < D; ++d) {
        // at most 1e15 cells along an axis before the cast (a stray particle far away must not
        // overflow the integer; the loop then coarsens the grid)
        // (an extent beyond the largest double, from particles near +-1e308, is taken as it)
        const double extent = std::min(mx[d] - mn[d], std::numeric_limits<double>::max());
        if (box && box->axis[d]) { // whole cells over the box
          dims[d] = std::max<long>(1, static_cast<long>(std::min(std::floor(extent / cell), 1e15)));
          size[d] = extent / static_cast<double>(dims[d]);
        } else {
          dims[d] =
              std::max<long>(1, static_cast<long>(std::min(std::floor(extent / cell), 1e15)) + 1);
          size[d] = cell;
        }
        total *= static_cast<double>(dims[d]);
      }
      if (total <= max_cells) break;
      cell *= 1.5;
    }
    // stable: equal extents keep x fastest (periodic axes too: the pairs across the boundary of
    // the slowest one join the first rows to the last, which the force loop runs first)
    std::stable_sort(axis.begin(), axis.begin() + D,
                     [&](int a, int b) { return mx[a] - mn[a] < mx[b] - mn[b]; });
    for (int k = 0; k < D; ++k)
      sorted[k] = dims[axis[k]];
  }
  long coord(const Vec<D>& p, int d) const {
    // clamped before the cast: a particle outside the grid takes the nearest cell (and one
    // whose offset is not a number, inf / inf, the first)
    const double c = (p[d] - lo[d]) / size[d];
    if (!(c > 0.0)) return 0;
    return c < static_cast<double>(dims[d] - 1) ? static_cast<long>(c) : dims[d] - 1;
  }
  long index(const Vec<D>& p) const {
    long c = coord(p, axis[D - 1]);
    for (int k = D - 2; k >= 0; --k)
      c = c * sorted[k] + coord(p, axis[k]);
    return c;
  }
  /// Index of the cell with coordinates c[d] along the axes d = 0 .. D - 1.
  long index_of_coords(const std::array<long, 3>& c) const {
    long k = c[axis[D - 1]];
    for (int q = D - 2; q >= 0; --q)
      k = k * sorted[q] + c[axis[q]];
    return k;
  }
  /// Index of the cell with coordinates c along the sorted axes (fastest first).
  long index_sorted(long c0, long c1, long c2) const {
    return c0 + sorted[0] * (c1 + sorted[1] * c2);
  }
  long count() const {
    long n = 1;
    for (int d = 0; d < D; ++d)
      n *= dims[d];
    return n;
  }
};

/// O(N^2) build: partners j > i closer than r_i + r_j + reach (through the nearest image with
/// periodic boundaries).
template <int D>
void build_all_pairs(const ParticleArrays<D>& p, const std::vector<Wall<D>>& walls, double reach,
                     NeighborList& list, const PeriodicBox<D>* box) {
  const bool periodic = box && box->on;
  const std::size_t n = p.size();
  list.clear(n);
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i + 1; j < n; ++j) {
      const double rs = p.radius[i] + p.radius[j] + reach;
      const Vec<D> d = periodic ? box->separation(p.position[i], p.position[j])
                                : Vec<D>(p.position[j] - p.position[i]);
      if (d.squaredNorm() < rs * rs) {
        list.partners.push_back(static_cast<std::uint32_t>(j));
        list.max_span = std::max<std::uint32_t>(list.max_span, static_cast<std::uint32_t>(j - i));
      }
    }
    list.offsets.push_back(static_cast<std::uint32_t>(list.partners.size()));
    add_wall_row(p, walls, reach, list, i);
  }
}

/// The particles of a grid's cells: `members` holds the particle indices cell by cell, ascending
/// within a cell; those of cell c are members[start[c]] .. members[start[c + 1] - 1]. A counting
/// sort, O(N + cells): the grid has at most a few cells per particle.
struct CellMembers {
  std::vector<std::uint32_t> start;   ///< cells + 1 entries
  std::vector<std::uint32_t> members; ///< N entries
};

template <int D>
CellMembers cell_members(const Grid<D>& grid, const std::vector<Vec<D>>& x) {
  const std::size_t n = x.size();
  CellMembers out;
  // counts at c + 2, sums, then each particle at start[c + 1]++: start[c] ends as cell c's start
  out.start.assign(static_cast<std::size_t>(grid.count()) + 2, 0);
  std::vector<std::size_t> key(n);
  for (std::size_t i = 0; i < n; ++i) {
    key[i] = static_cast<std::size_t>(grid.index(x[i]));
    ++out.start[key[i] + 2];
  }
  for (std::size_t c = 2; c < out.start.size(); ++c)
    out.start[c] += out.start[c - 1];
  out.members.resize(n);
  for (std::size_t i = 0; i < n; ++i)
    out.members[out.start[key[i] + 1]++] = static_cast<std::uint32_t>(i);
  out.start.pop_back();
  return out;
}

/// Permutation that sorts particles by cell (see Grid for the order of the axes); stable within
/// a cell.
template <int D>
std::vector<std::uint32_t> cell_order(const ParticleArrays<D>& p, double cell_size,
                                      const PeriodicBox<D>* box) {
  Grid<D> grid;
  grid.setup(p.position, cell_size, box && box->on ? box : nullptr);
  return cell_members(grid, p.position).members;
}

/// Linked-cell build: partners j > i closer than r_i + r_j + reach, rows ascending.
template <int D>
void build_cells(const ParticleArrays<D>& p, const std::vector<Wall<D>>& walls, double reach,
                 double r_max, NeighborList& list) {
  const std::size_t n = p.size();
  list.clear(n);
  Grid<D> grid;
  grid.setup(p.position, 2.0 * r_max + reach);
  const auto [head, members] = cell_members(grid, p.position);
  std::vector<std::uint32_t> row;
  for (std::size_t i = 0; i < n; ++i) {
    row.clear();
    // the cells around i, by coordinates along the sorted axes (fastest first)
    long lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
    for (int k = 0; k < D; ++k) {
      const long c = grid.coord(p.position[i], grid.axis[k]);
      lo[k] = std::max(c - 1, 0L);
      hi[k] = std::min(c + 1, grid.sorted[k] - 1);
    }
    for (long c2 = lo[2]; c2 <= hi[2]; ++c2)
      for (long c1 = lo[1]; c1 <= hi[1]; ++c1)
        for (long c0 = lo[0]; c0 <= hi[0]; ++c0) {
          const long cell = grid.index_sorted(c0, c1, c2);
          for (std::uint32_t k = head[cell]; k < head[cell + 1]; ++k) {
            const std::uint32_t j = members[k];
            if (j <= i) continue;
            const double rs = p.radius[i] + p.radius[j] + reach;
            if ((p.position[j] - p.position[i]).squaredNorm() < rs * rs) row.push_back(j);
          }
        }
    std::sort(row.begin(), row.end());
    for (auto j : row) {
      list.partners.push_back(j);
      list.max_span = std::max<std::uint32_t>(list.max_span, static_cast<std::uint32_t>(j - i));
    }
    list.offsets.push_back(static_cast<std::uint32_t>(list.partners.size()));
    add_wall_row(p, walls, reach, list, i);
  }
}

/// Linked-cell build across periodic boundaries (box.on): partners j > i whose nearest image is
/// closer than r_i + r_j + reach. The cells around i wrap along the periodic axes; with a
/// Lees-Edwards shear, the cells across the y boundary are those around x_i -+ offset. Rows
/// ascending, each pair once. The positions are inside the box along the periodic axes (the
/// simulation wraps them before it builds).
template <int D>
void build_periodic(const ParticleArrays<D>& p, const std::vector<Wall<D>>& walls, double reach,
                    double r_max, const PeriodicBox<D>& box, NeighborList& list) {
  const std::size_t n = p.size();
  list.clear(n);
  Grid<D> grid;
  grid.setup(p.position, 2.0 * r_max + reach, &box);
  const CellMembers cells = cell_members(grid, p.position);
  const auto& head = cells.start;
  const auto& members = cells.members;
  // the coordinates along axis d around coordinate c (wrapped on a periodic axis), each once
  auto around = [&](int d, long c, std::array<long, 3>& out) {
    int m = 0;
    for (long o = -1; o <= 1; ++o) {
      long q = c + o;
      if (box.axis[d])
        q = ((q % grid.dims[d]) + grid.dims[d]) % grid.dims[d];
      else if (q < 0 || q >= grid.dims[d])
        continue;
      bool seen = false;
      for (int k = 0; k < m; ++k)
        seen = seen || out[k] == q;
      if (!seen) out[m++] = q;
    }
    return m;
  };
  std::vector<std::uint32_t> row;
  for (std::size_t i = 0; i < n; ++i) {
    row.clear();
    const Vec<D>& xi = p.position[i];
    std::array<std::array<long, 3>, 3> near{};
    std::array<int, 3> count{1, 1, 1};
    for (int d = 0; d < D; ++d)
      count[d] = around(d, grid.coord(xi, d), near[d]);
    auto scan = [&](const std::array<long, 3>& c) {
      const long cell = grid.index_of_coords(c);
      for (std::uint32_t k = head[cell]; k < head[cell + 1]; ++k) {
        const std::uint32_t j = members[k];
        if (j <= i) continue;
        const double rs = p.radius[i] + p.radius[j] + reach;
        if (box.separation(xi, p.position[j]).squaredNorm() < rs * rs) row.push_back(j);
      }
    };
    // the rows of cells along y, each with its cells along x (shifted across a sheared boundary)
    const long cy = D >= 2 ? grid.coord(xi, 1) : 0;
    for (long oy = -1; oy <= (D >= 2 ? 1 : -1); ++oy) {
      std::array<long, 3> nx = near[0];
      int cx = count[0];
      long qy = 0;
      if constexpr (D >= 2) {
        qy = cy + oy;
        const long wy = qy < 0 ? -1 : (qy >= grid.dims[1] ? 1 : 0);
        if (!box.axis[1] && wy != 0) continue;
        qy -= wy * grid.dims[1];
        if (box.sheared() && wy != 0) {
          Vec<D> shifted = xi;
          shifted[0] -= static_cast<double>(wy) * box.offset;
          shifted[0] -= box.length[0] * std::floor((shifted[0] - box.lo[0]) / box.length[0]);
          cx = around(0, grid.coord(shifted, 0), nx);
        } else {
          // a y coordinate met twice (few cells along y) is scanned once
          bool seen = false;
          for (long o = -1; o < oy; ++o) {
            long q = cy + o;
            const long w = q < 0 ? -1 : (q >= grid.dims[1] ? 1 : 0);
            if (!box.axis[1] && w != 0) continue;
            if (box.sheared() && w != 0) continue;
            seen = seen || q - w * grid.dims[1] == qy;
          }
          if (seen) continue;
        }
      }
      for (int a = 0; a < cx; ++a) {
        if constexpr (D == 2) {
          scan({nx[a], qy, 0});
        } else {
          for (int b = 0; b < count[2]; ++b)
            scan({nx[a], qy, near[2][b]});
        }
      }
      if constexpr (D < 2) break;
    }
    std::sort(row.begin(), row.end());
    row.erase(std::unique(row.begin(), row.end()), row.end());
    for (auto j : row) {
      list.partners.push_back(j);
      list.max_span = std::max<std::uint32_t>(list.max_span, static_cast<std::uint32_t>(j - i));
    }
    list.offsets.push_back(static_cast<std::uint32_t>(list.partners.size()));
    add_wall_row(p, walls, reach, list, i);
  }
}

} // namespace detail
} // namespace grain::search
