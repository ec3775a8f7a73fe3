// Neighbour searches: same contact set as brute force, and no contact ever detected late.
#include "../errors.hpp"
#include <algorithm>
#include <doctest/doctest.h>
#include <grain/grain.hpp>
#include <limits>
#include <map>
#include <random>
#include <set>
#include <utility>

using namespace grain;

namespace {

using Contact = Interaction<normal::LinearSpringDashpot, tangent::SpringDashpotSlider>;
using Key = std::pair<std::int64_t, std::int64_t>; // (id, id) or (id, -1 - wall)

/// Touching pairs found by the simulation's own neighbour list.
template <class Sim>
std::set<Key> listed_contacts(const Sim& sim) {
  std::set<Key> out;
  const auto& ids = sim.particles().id;
  sim.for_each_contact([&](std::size_t i, std::size_t j, bool wall, const auto&, const auto&) {
    if (wall)
      out.insert({ids[i], -1 - static_cast<std::int64_t>(j)});
    else
      out.insert({std::min(ids[i], ids[j]), std::max(ids[i], ids[j])});
  });
  return out;
}

/// Touching pairs by brute force over all pairs and walls.
template <class Sim>
std::set<Key> brute_contacts(const Sim& sim) {
  std::set<Key> out;
  const auto& p = sim.particles();
  for (std::size_t i = 0; i < p.size(); ++i) {
    for (std::size_t j = i + 1; j < p.size(); ++j) {
      const double rs = p.radius[i] + p.radius[j];
      if ((p.position[i] - p.position[j]).squaredNorm() < rs * rs)
        out.insert({std::min(p.id[i], p.id[j]), std::max(p.id[i], p.id[j])});
    }
    for (std::size_t w = 0; w < sim.walls().size(); ++w)
      if (sim.walls()[w].proximity(p.position[i]).distance < p.radius[i])
        out.insert({p.id[i], -1 - static_cast<std::int64_t>(w)});
  }
  return out;
}

/// Any overlap at the start and any speed are allowed: the random packings below overlap deeply
/// and fire particles apart, to stress the searches.
constexpr double unchecked = std::numeric_limits<double>::infinity();

/// Dense random polydisperse packing in a box [0, L]^D with walls, size ratio up to `ratio`.
template <class Sim>
void fill(Sim& sim, int n, double ratio, unsigned seed, double speed) {
  constexpr int D = Sim::dimension;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double rmin = 1e-3 / ratio, rmax = 1e-3;
  const double L = D == 2 ? 0.03 : 0.012;
  auto m = sim.add_material({.density = 2500, .young = 1e6, .poisson = 0.3, .restitution = 0.9});
  for (int k = 0; k < n; ++k) {
    Vec<D> x, v;
    for (int d = 0; d < D; ++d) {
      x[d] = L * (0.05 + 0.9 * u(rng));
      v[d] = speed * (2 * u(rng) - 1);
    }
    const double r = rmin * std::pow(rmax / rmin, u(rng));
    sim.add_particle({.position = x, .radius = r, .material = m, .velocity = v});
  }
  if constexpr (D == 2) {
    sim.add_wall(walls::Segment{Vec2(0, 0), Vec2(L, 0)}, {.material = m});
    sim.add_wall(walls::Segment{Vec2(0, L), Vec2(L, L)}, {.material = m});
    sim.add_wall(walls::Segment{Vec2(0, 0), Vec2(0, L)}, {.material = m});
    sim.add_wall(walls::Circle{Vec2(L, 0.5 * L), 0.2 * L}, {.material = m});
  } else {
    sim.add_wall(walls::Plane{Vec3::Zero(), Vec3::UnitZ()}, {.material = m});
    sim.add_wall(walls::Plane{Vec3(L, L, L), -Vec3::UnitX()}, {.material = m});
    sim.add_wall(walls::Triangle{Vec3(0, 0, L), Vec3(L, 0, L), Vec3(0, L, 0.5 * L)},
                 {.material = m});
  }
}

template <class SearchT, class Shape>
void check_search(int n, double ratio, unsigned seed, typename SearchT::Params sp = {}) {
  using Sim = Simulation<Shape, SearchT, Contact>;
  constexpr int D = Shape::dimension;
  Vec<D> g = Vec<D>::Zero();
  g[D - 1] = -9.81;
  // the random packing overlaps deeply at the start, on purpose (soft springs)
  Sim sim({.time_step = 2e-5,
           .gravity = g,
           .contact = {.normal = {.stiffness = 50.0}},
           .search = sp,
           .max_start_overlap = unchecked,
           .max_step_travel = unchecked});
  fill(sim, n, ratio, seed, 0.5);
  sim.initialize();
  const auto initial = brute_contacts(sim);
  CHECK(initial.size() > static_cast<std::size_t>(n / 4)); // a dense configuration
  CHECK(listed_contacts(sim) == initial);
  // dynamics: at every step the list holds every touching pair (no contact detected late)
  std::size_t missed = 0, checked = 0;
  for (int s = 0; s < 300; ++s) {
    sim.step();
    const auto brute = brute_contacts(sim);
    const auto listed = listed_contacts(sim);
    missed += brute.size() - std::min(brute.size(), listed.size());
    if (listed != brute) ++missed;
    checked += brute.size();
  }
  CHECK(missed == 0);
  CHECK(checked > 0);
  CHECK(sim.counters().rebuilds >= 1);
}

} // namespace

TEST_CASE("searches find exactly the touching pairs, 2D polydisperse with walls") {
  check_search<search::AllPairs, Disk>(300, 3.0, 1);
  check_search<search::VerletList, Disk>(300, 3.0, 2);
  check_search<search::VerletList, Disk>(300, 3.0, 3, {.skin = 2e-4, .frequency = 25});
  check_search<search::CellList, Disk>(300, 3.0, 4);
  check_search<search::CellList, Disk>(300, 10.0, 5);
}

TEST_CASE("searches find exactly the touching pairs, 3D polydisperse with walls") {
  check_search<search::AllPairs, Sphere>(250, 3.0, 6);
  check_search<search::VerletList, Sphere>(250, 3.0, 7, {.skin = 1e-4, .frequency = 10});
  check_search<search::CellList, Sphere>(250, 3.0, 8);
  check_search<search::CellList, Sphere>(250, 10.0, 9, {.skin = 5e-5});
}

TEST_CASE("all three searches give the same contact set on the same configuration") {
  auto contacts = [](auto tag) {
    using SearchT = decltype(tag);
    Simulation<Sphere, SearchT, Contact> sim({.time_step = 1e-5,
                                              .contact = {.normal = {.stiffness = 50.0}},
                                              .max_start_overlap = unchecked,
                                              .max_step_travel = unchecked});
    fill(sim, 400, 10.0, 42, 0.0);
    sim.initialize();
    return listed_contacts(sim);
  };
  const auto a = contacts(search::AllPairs{});
  const auto v = contacts(search::VerletList{});
  const auto c = contacts(search::CellList{});
  CHECK(a.size() > 50);
  CHECK(a == v);
  CHECK(a == c);
}

TEST_CASE("the motion does not depend on the search (rows of any length)") {
  // a Verlet list with a skin larger than the box lists every pair: its rows hold up to 399
  // partners (the force loop takes rows longer than 64 entries in blocks); cell-list rows hold a
  // few. The loads are the same up to the order of the additions.
  auto run = [](auto tag, typename decltype(tag)::Params sp) {
    using SearchT = decltype(tag);
    Simulation<Sphere, SearchT, Contact> sim({.time_step = 1e-5,
                                              .gravity = Vec3(0, 0, -9.81),
                                              .contact = {.normal = {.stiffness = 50.0}},
                                              .search = sp,
                                              .max_start_overlap = unchecked,
                                              .max_step_travel = unchecked});
    fill(sim, 400, 10.0, 11, 0.5);
    sim.steps(40);
    std::map<std::int64_t, std::pair<Vec3, Vec3>> state; // id -> (velocity, angular velocity)
    const auto& p = sim.particles();
    for (std::size_t i = 0; i < p.size(); ++i)
      state[p.id[i]] = {p.velocity[i], p.omega[i]};
    return std::pair{state, listed_contacts(sim).size()};
  };
  const auto [a, na] = run(search::VerletList{}, {.skin = 0.05});
  const auto [c, nc] = run(search::CellList{}, {});
  CHECK(na > 50);
  CHECK(na == nc);
  REQUIRE(a.size() == c.size());
  double vmax = 0.0, wmax = 0.0, dv = 0.0, dw = 0.0;
  for (const auto& [id, s] : a) {
    const auto& t = c.at(id);
    vmax = std::max(vmax, s.first.norm());
    wmax = std::max(wmax, s.second.norm());
    dv = std::max(dv, (s.first - t.first).norm());
    dw = std::max(dw, (s.second - t.second).norm());
  }
  // rounding differences only (a load missed or counted twice changes them at order 1)
  CHECK(dv <= 1e-9 * vmax);
  CHECK(dw <= 1e-9 * wmax);
}

TEST_CASE("cell list re-sorts particles but keeps ids and contact histories") {
  using Sim = Simulation<Disk, search::CellList, Contact>;
  Sim sim({.time_step = 2e-5,
           .gravity = Vec2(0, -9.81),
           .contact = {.normal = {.stiffness = 50.0}},
           .search = {.skin = 1e-5},
           .max_start_overlap = unchecked,
           .max_step_travel = unchecked});
  fill(sim, 200, 2.0, 11, 0.3);
  sim.initialize();
  auto ids = sim.particles().id;
  std::sort(ids.begin(), ids.end());
  for (std::size_t k = 0; k < ids.size(); ++k)
    CHECK(ids[k] == static_cast<std::int64_t>(k));
  // run; after each rebuild, the tangential springs of continuing contacts are unchanged when
  // looked up by particle identity
  long rebuilds = sim.counters().rebuilds;
  int compared = 0;
  for (int s = 0; s < 400 && compared < 5; ++s) {
    // springs by identity before the step
    std::map<Key, Vec2> before;
    const auto& p = sim.particles();
    const auto& list = sim.neighbor_list();
    for (std::size_t i = 0; i < p.size(); ++i)
      for (auto e = list.offsets[i]; e < list.offsets[i + 1]; ++e) {
        const auto j = list.partners[e];
        Vec2 xi = load<2>(sim.histories()[e].tangent.spring);
        if (xi.squaredNorm() == 0) continue;
        if (p.id[i] > p.id[j]) xi = -xi;
        before[{std::min(p.id[i], p.id[j]), std::max(p.id[i], p.id[j])}] = xi;
      }
    sim.step();
    if (sim.counters().rebuilds == rebuilds || s < 50) continue;
    rebuilds = sim.counters().rebuilds;
    ++compared;
    // after the rebuild (which happens before the forces), springs moved by at most one
    // increment |v_t| dt; check that each continuing contact kept its spring direction
    const auto& q = sim.particles();
    const auto& nl = sim.neighbor_list();
    int matched = 0, close = 0;
    for (std::size_t i = 0; i < q.size(); ++i)
      for (auto e = nl.offsets[i]; e < nl.offsets[i + 1]; ++e) {
        const auto j = nl.partners[e];
        Vec2 xi = load<2>(sim.histories()[e].tangent.spring);
        if (xi.squaredNorm() == 0) continue;
        if (q.id[i] > q.id[j]) xi = -xi;
        auto it = before.find({std::min(q.id[i], q.id[j]), std::max(q.id[i], q.id[j])});
        if (it == before.end()) continue;
        ++matched;
        // a lost history would restart from a single increment |v_t| dt
        if ((xi - it->second).norm() < 0.5 * it->second.norm()) ++close;
      }
    CHECK(matched > 0);
    CHECK(close >= 0.8 * matched);
  }
  CHECK(compared > 0);
}

TEST_CASE("cell order sorts by cell and keeps the order of the particles within a cell") {
  // a jittered 3D lattice, several particles per cell, the points shuffled
  ParticleArrays<3> p;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> jitter(-0.3, 0.3);
  for (int k = 0; k < 6; ++k)
    for (int j = 0; j < 9; ++j)
      for (int i = 0; i < 14; ++i) {
        p.id.push_back(static_cast<std::int64_t>(p.id.size()));
        p.position.push_back(Vec3(0.5 * i + jitter(rng), 0.5 * j + jitter(rng), 0.5 * k));
        p.radius.push_back(0.2);
      }
  std::shuffle(p.position.begin(), p.position.end(), rng);
  const double cell = 1.0;
  const auto perm = search::detail::cell_order(p, cell);
  search::detail::Grid<3> grid;
  grid.setup(p.position, cell);
  REQUIRE(perm.size() == p.size());
  std::vector<std::uint32_t> seen(perm);
  std::sort(seen.begin(), seen.end());
  for (std::size_t k = 0; k < seen.size(); ++k)
    REQUIRE(seen[k] == k); // a permutation
  int ties = 0;
  for (std::size_t k = 1; k < perm.size(); ++k) {
    const long a = grid.index(p.position[perm[k - 1]]), b = grid.index(p.position[perm[k]]);
    CHECK(a <= b); // by cell
    if (a == b) {  // stable within a cell
      CHECK(perm[k - 1] < perm[k]);
      ++ties;
    }
  }
  CHECK(ties > static_cast<int>(p.size()) / 2); // the test has cells with several particles
}

TEST_CASE("a neighbour list whose offsets run backwards or past its entries is refused") {
  // row 0 claims 5 entries of a list of 1: every offset is checked before any row is read
  NeighborList list;
  list.offsets = {0, 5, 1};
  list.partners = {1};
  list.wall_offsets = {0, 0, 0};
  list.max_span = 1;
  const auto msg = test::error_of([&] { search::require_valid_list(list, 2, "mine"); });
  CHECK(
      test::has(msg, "search 'mine': the neighbour list it built has decreasing offsets at row 1"));
  list.offsets = {0, 1, 1};
  list.wall_offsets = {0, 3, 0};
  CHECK(test::has(test::error_of([&] { search::require_valid_list(list, 2, "mine"); }),
                  "decreasing offsets at row 1"));
  list.wall_offsets = {0, 0, 0};
  CHECK_NOTHROW(search::require_valid_list(list, 2, "mine"));
}
