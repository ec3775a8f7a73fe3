// The simulation's components on their own: the contact-history store (carry-over across a
// rebuild, a removal and an addition), the pair table, a neighbour search written by a program
// (plugged in through the Search concept), and the time-step limits of a run whose particles
// are all fixed.
#ifdef _OPENMP
#include <omp.h>
#endif
#include <grain/grain.hpp>

#include "../errors.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <utility>
#include <vector>

using namespace grain;

namespace {

/// A history with a value that shows whether it was mirrored.
struct Spring {
  double s = 0.0;
};

/// A CSR list from rows of partners (no walls unless given).
NeighborList make_list(const std::vector<std::vector<std::uint32_t>>& rows,
                       const std::vector<std::vector<std::uint32_t>>& wall_rows = {}) {
  NeighborList l;
  l.clear(rows.size());
  for (std::size_t i = 0; i < rows.size(); ++i) {
    for (auto j : rows[i]) {
      l.partners.push_back(j);
      l.max_span = std::max<std::uint32_t>(l.max_span, j - static_cast<std::uint32_t>(i));
    }
    l.offsets.push_back(static_cast<std::uint32_t>(l.partners.size()));
    if (i < wall_rows.size())
      for (auto w : wall_rows[i])
        l.walls.push_back(w);
    l.wall_offsets.push_back(static_cast<std::uint32_t>(l.walls.size()));
  }
  return l;
}

/// The history of the pair (i, j), i < j, in list l (NaN if the pair is not listed).
double history_of(const NeighborList& l, const ContactHistories<Spring>& h, std::uint32_t i,
                  std::uint32_t j) {
  for (const auto e : l.pair_entries(i))
    if (l.partners[e] == j) return h.pair[e].s;
  return std::nan("");
}

} // namespace

TEST_CASE("contact histories: blank entries, keep and restore") {
  using H = ContactHistories<Spring>;
  CHECK(H::blank(Spring{}));
  CHECK_FALSE(H::blank(Spring{1.0}));
  CHECK_FALSE(H::blank(Spring{-0.0})); // equal in value, not in bytes: kept, never lost
  H h;
  h.pair = {Spring{}, Spring{2.0}, Spring{}, Spring{3.0}};
  h.wall = {Spring{5.0}};
  const auto saved = h.save();
  CHECK(saved.pair.size() == 2);
  h.pair[0].s = 7.0;
  h.pair[1].s = 8.0;
  h.wall[0].s = 9.0;
  h.restore_all(saved);
  CHECK(h.pair[0].s == 0.0);
  CHECK(h.pair[1].s == 2.0);
  CHECK(h.pair[3].s == 3.0);
  CHECK(h.wall[0].s == 5.0);
  static_assert(ContactHistories<Interaction<normal::Hertz<>>::History<3>>::stateless);
}

TEST_CASE("contact histories: carry-over through a re-sorting, with mirrored pairs") {
  using H = ContactHistories<Spring>;
  // four particles; pairs (0,1) s=1, (0,3) s=3, (1,2) s=12, (2,3) untouched (blank); wall 0 at
  // particle 2 with s=20
  NeighborList old = make_list({{1, 3}, {2}, {3}, {}}, {{}, {}, {0}, {}});
  H h;
  h.pair = {Spring{1}, Spring{3}, Spring{12}, Spring{}};
  h.wall = {Spring{20}};
  h.shrink_to_contacts(old); // the blank entry (2,3) goes
  CHECK(old.partners.size() == 3);
  CHECK(h.pair.size() == 3);
  // the particles re-sorted: new k holds old perm[k]
  const std::vector<std::uint32_t> perm{3, 2, 1, 0};
  // new pairs: old (0,1) = new (3,2) -> (2,3); old (0,3) = new (3,0) -> (0,3); old (1,2) = new
  // (2,1) -> (1,2); a new pair (0,1) = old (3,2) was blank
  NeighborList now = make_list({{1, 3}, {2}, {3}, {}}, {{}, {0}, {}, {}});
  H carried;
  carried.carry_over(
      now, h, now, [](std::size_t) { return H::none; }, [](Spring& s) { s.s = -s.s; }, 1);
  CHECK(carried.pair.size() == 4); // nothing known: all blank
  for (const auto& x : carried.pair)
    CHECK(H::blank(x));
  carried.carry_over(
      old, h, now, [&](std::size_t k) { return perm[k]; }, [](Spring& s) { s.s = -s.s; }, 1);
  // a pair whose old row is the larger index has its roles swapped: mirrored
  CHECK(history_of(now, carried, 2, 3) == -1.0); // old (0,1): its row is now the larger index
  CHECK(history_of(now, carried, 0, 3) == -3.0);
  CHECK(history_of(now, carried, 1, 2) == -12.0);
  CHECK(history_of(now, carried, 0, 1) == 0.0);
  CHECK(carried.wall[0].s == 20.0); // the wall contact of old particle 2, now particle 1
}

TEST_CASE("contact histories: carry-over across a removal and an addition") {
  using H = ContactHistories<Spring>;
  NeighborList old = make_list({{1, 2}, {2}, {}});
  H h;
  h.pair = {Spring{1}, Spring{2}, Spring{12}};
  // particle 0 removed, a new particle appended: new 0 = old 1, new 1 = old 2, new 2 = new
  const std::vector<std::uint32_t> origin{1, 2, H::none};
  NeighborList now = make_list({{1, 2}, {2}, {}});
  H carried;
  carried.carry_over(
      old, h, now, [&](std::size_t k) { return origin[k]; }, [](Spring& s) { s.s = -s.s; }, 1);
  CHECK(history_of(now, carried, 0, 1) == 12.0); // old (1,2), same roles
  CHECK(history_of(now, carried, 0, 2) == 0.0);  // with the new particle: blank
  CHECK(history_of(now, carried, 1, 2) == 0.0);
  // the same with threads on (threshold 0): the same result
  H par;
  par.carry_over(
      old, h, now, [&](std::size_t k) { return origin[k]; }, [](Spring& s) { s.s = -s.s; }, 0);
  CHECK(par.pair.size() == carried.pair.size());
  for (std::size_t e = 0; e < par.pair.size(); ++e)
    CHECK(par.pair[e].s == carried.pair[e].s);
}

TEST_CASE("pair table: mixing, overrides, per-pair parameters and their resolution") {
  using Contact = Interaction<normal::Hertz<>, tangent::Mindlin>;
  PairTable<Contact> t({}, 0.025);
  const Material glass{.name = "glass",
                       .density = 2500,
                       .young = 6e10,
                       .poisson = 0.25,
                       .restitution = 0.9,
                       .friction = 0.3};
  const Material steel{.name = "steel",
                       .density = 7800,
                       .young = 2e11,
                       .poisson = 0.3,
                       .restitution = 0.7,
                       .friction = 0.5};
  CHECK(t.add_material(glass) == 0);
  CHECK(t.add_material(steel) == 1);
  CHECK(t.size() == 2);
  // Johnson's mixing of E* and the mean restitution and friction, symmetric
  const double e_star = 1.0 / ((1 - 0.25 * 0.25) / 6e10 + (1 - 0.3 * 0.3) / 2e11);
  CHECK(t.properties(0, 1).young_eff == doctest::Approx(e_star).epsilon(1e-14));
  CHECK(t.properties(1, 0).young_eff == t.properties(0, 1).young_eff);
  CHECK(t.properties(0, 1).restitution == doctest::Approx(0.8).epsilon(1e-14));
  CHECK(t.properties(0, 1).friction == doctest::Approx(0.4).epsilon(1e-14));
  CHECK(t.properties(0, 1).fluid_conductivity == 0.025);
  t.set_override(0, 1, {.restitution = 0.5, .friction = 0.1});
  CHECK(t.properties(1, 0).restitution == 0.5);
  CHECK(t.properties(0, 1).friction == 0.1);
  CHECK(t.properties(0, 0).restitution == doctest::Approx(0.9).epsilon(1e-14));
  // a third material keeps the override and the first two pairs
  t.add_material(Material{.name = "ice", .density = 917, .young = 9e9, .poisson = 0.33});
  CHECK(t.properties(0, 1).restitution == 0.5);
  CHECK(t.index(2, 1) == 7);
  // per-pair parameters, resolved against the pair's properties (Tsuji's alpha from e)
  Contact::Params p{};
  t.set_parameters(1, 2, p);
  const auto k = t.index(2, 1);
  CHECK(t.parameters(2, 1).normal.damping.alpha < 0); // as given: alpha from the restitution
  const double alpha = normal::TsujiDamping::alpha(t.properties(k));
  CHECK(alpha > 0);
  CHECK(t.resolved(k).normal.damping.alpha == alpha);
  CHECK(t.resolved(t.index(1, 2)).normal.damping.alpha == alpha);
  t.set_per_particle(true); // variable contact properties: the parameters as given
  CHECK(t.resolved(k).normal.damping.alpha < 0);
  // bad input names the object, the value and the valid range
  CHECK(test::has(test::error_of([&] { t.check_material(3, "Wall 'floor'"); }),
                  "Wall 'floor': material = 3 is invalid; valid range: [0, 3)"));
  CHECK(test::has(test::error_of([&] { t.set_override(0, 1, {.restitution = 1.5}); }),
                  "restitution = 1.5 is invalid"));
  CHECK(test::has(test::error_of([&] { t.add_material(Material{.name = "air"}); }),
                  "Material 'air': density = 0 is invalid"));
}

namespace {

/// A search written by a program: every pair tested, rebuilt at every step.
struct BruteForce {
  static constexpr const char* name = "brute force";
  struct Params {};
  static void validate(const Params&) {}
  static double skin(const Params&, double) { return 0.0; }
  static bool due(const Params&, long, bool) { return true; }
  template <int D>
  static void build(const Params&, const ParticleArrays<D>& p, const std::vector<Wall<D>>& walls,
                    double reach, double, NeighborList& list) {
    list.clear(p.size());
    for (std::size_t i = 0; i < p.size(); ++i) {
      for (std::size_t j = i + 1; j < p.size(); ++j) {
        const double rs = p.radius[i] + p.radius[j] + reach;
        if ((p.position[j] - p.position[i]).squaredNorm() < rs * rs) {
          list.partners.push_back(static_cast<std::uint32_t>(j));
          list.max_span = std::max(list.max_span, static_cast<std::uint32_t>(j - i));
        }
      }
      list.offsets.push_back(static_cast<std::uint32_t>(list.partners.size()));
      search::add_wall_row(p, walls, reach, list, i);
    }
  }
};

/// A search that lists each particle as its own partner: refused with its name.
struct Backwards : BruteForce {
  static constexpr const char* name = "backwards";
  template <int D>
  static void build(const Params&, const ParticleArrays<D>& p, const std::vector<Wall<D>>& walls,
                    double reach, double, NeighborList& list) {
    list.clear(p.size());
    for (std::size_t i = 0; i < p.size(); ++i) {
      list.partners.push_back(static_cast<std::uint32_t>(i));
      list.offsets.push_back(static_cast<std::uint32_t>(list.partners.size()));
      search::add_wall_row(p, walls, reach, list, i);
    }
  }
};

static_assert(search::Search<BruteForce, 3> && search::Search<BruteForce, 2>);
static_assert(search::Reorders<search::CellList, 3> && !search::Reorders<BruteForce, 3>);

using Contact = Interaction<normal::Hertz<>, tangent::Mindlin>;

template <class S>
using Sim = Simulation<Sphere, S, Contact>;

/// A loose pile of spheres above a floor, the same for every search.
template <class S>
void pile(Sim<S>& sim) {
  const auto m = sim.add_material(
      {.density = 2500, .young = 1e7, .poisson = 0.25, .restitution = 0.5, .friction = 0.5});
  int k = 0;
  for (int z = 0; z < 4; ++z)
    for (int y = 0; y < 5; ++y)
      for (int x = 0; x < 5; ++x, ++k) {
        const double r = 1e-3 * (0.8 + 0.2 * ((k * 7) % 5) / 4.0);
        sim.add_particle(
            {.position = Vec3(2.1e-3 * x + 1e-4 * (z % 2), 2.1e-3 * y, 1.1e-3 + 1.95e-3 * z),
             .radius = r,
             .material = m});
      }
  sim.add_wall(walls::Plane{Vec3::Zero(), Vec3::UnitZ()}, {.material = m});
}

/// Touching pairs by particle id, and particle-wall contacts as (id, -1 - wall).
template <class S>
std::set<std::pair<std::int64_t, std::int64_t>> contacts_of(const Sim<S>& sim) {
  std::set<std::pair<std::int64_t, std::int64_t>> out;
  const auto& id = sim.particles().id;
  sim.for_each_contact([&](std::size_t i, std::size_t j, bool wall, const auto&, const auto&) {
    if (wall)
      out.insert({id[i], -1 - static_cast<std::int64_t>(j)});
    else
      out.insert({std::min(id[i], id[j]), std::max(id[i], id[j])});
  });
  return out;
}

} // namespace

TEST_CASE("a search written in a program gets the contacts of search::CellList") {
  Sim<BruteForce> brute({.time_step = 2e-6, .gravity = Vec3(0, 0, -9.81)});
  Sim<search::CellList> cells({.time_step = 2e-6, .gravity = Vec3(0, 0, -9.81)});
  pile(brute);
  pile(cells);
  brute.initialize();
  cells.initialize();
  const auto c0 = contacts_of(cells);
  CHECK(c0.size() >= 10); // the pile touches: lower layers and the floor
  CHECK(contacts_of(brute) == c0);
  // 2000 steps of settling: the same contacts all along (the forces differ only in the order of
  // their sums, far below what changes a contact)
  for (int k = 0; k < 4; ++k) {
    brute.steps(500);
    cells.steps(500);
    CHECK(contacts_of(brute) == contacts_of(cells));
  }
  CHECK(brute.counters().rebuilds > 2000); // rebuilt every step, as it says
  CHECK(brute.kinetic_energy() == doctest::Approx(cells.kinetic_energy()).epsilon(1e-6));
}

TEST_CASE("a search whose list is not well formed is refused with its name") {
  Sim<Backwards> sim({.time_step = 2e-6});
  pile(sim);
  const auto msg = test::error_of([&] { sim.initialize(); });
  CHECK(test::has(msg, "search 'backwards': the neighbour list it built has partner 0 in row 0"));
}

TEST_CASE("a thermo-mechanical run whose particles are all fixed has the conduction step") {
  using Hot =
      Interaction<normal::Hertz<>, tangent::Mindlin, rolling::None, conduction::BatchelorOBrien>;
  auto make = [](bool one_free) {
    Simulation<Sphere, search::CellList, Hot> sim({.max_start_overlap = 0.2}); // 0.1 R
    const auto m = sim.add_material({.density = 2500,
                                     .young = 1e9,
                                     .poisson = 0.25,
                                     .conductivity = 1.0,
                                     .heat_capacity = 800});
    for (int k = 0; k < 4; ++k)
      sim.add_particle({.position = Vec3(1.9e-3 * k, 0, 0),
                        .radius = 1e-3,
                        .material = m,
                        .temperature = 300.0 + 10 * k,
                        .fixed = !(one_free && k == 3)});
    sim.initialize();
    return sim;
  };
  auto fixed = make(false);
  const double conduction = fixed.conduction_time_step();
  REQUIRE(std::isfinite(conduction));
  REQUIRE(fixed.mechanical_time_step() < 1e-3 * conduction); // stiff spheres: far below it
  CHECK_FALSE(fixed.forces_move());
  CHECK(fixed.critical_time_step() == conduction);
  CHECK(fixed.time_step() ==
        doctest::Approx(0.1 * std::min(conduction, fixed.thermal_time_step())));
  // heat flows as it did: the hottest particle cools
  const double t3 = fixed.particles().temperature[fixed.index_of(3)];
  fixed.steps(100);
  CHECK(fixed.particles().temperature[fixed.index_of(3)] < t3);
  auto one = make(true);
  CHECK(one.forces_move());
  CHECK(one.critical_time_step() == one.mechanical_time_step());
}

TEST_CASE("lifecycle: who leaves and who arrives at a time") {
  Lifecycle<2> life;
  CHECK_FALSE(life.active());
  life.bounding_box = TimedRegion<2>{regions::Box<2>{Vec2(0, 0), Vec2(1, 1)}};
  life.sinks.push_back(TimedRegion<2>{regions::Ball<2>{Vec2(0.9, 0.9), 0.05}, 1.0, 2.0});
  life.doomed = {{0.5, 11}, {3.0, 12}, {0.2, 40}}; // 40 is still waiting to be created
  life.pending.push_back(
      ParticleSpec<2>{.position = Vec2(0.5, 0.5), .radius = 0.01, .creation_time = 0.2, .id = 30});
  life.pending.push_back(
      ParticleSpec<2>{.position = Vec2(0.5, 0.6), .radius = 0.01, .creation_time = 0.1, .id = 40});
  CHECK(life.active());
  // particles 10 (inside), 11 (destruction time 0.5), 12 (outside the box), 13 (in the sink)
  const std::vector<Vec2> x{Vec2(0.5, 0.5), Vec2(0.2, 0.2), Vec2(1.5, 0.5), Vec2(0.9, 0.91)};
  const std::vector<std::int64_t> id{10, 11, 12, 13};
  int non_finite = 0;
  auto d = life.decide(0.3, x, id, [&] { ++non_finite; });
  CHECK(d.changed);
  CHECK(d.removed);
  CHECK(d.kept == std::vector<std::uint32_t>{0, 1, 3}); // 12 left the box; the sink is not active
  REQUIRE(d.born.size() == 1);
  CHECK(d.born[0].id == 30); // 40 reached its destruction time before it was created
  CHECK(life.removed_ids == std::vector<std::int64_t>{40, 12});
  CHECK(life.pending.empty());
  CHECK(life.doomed == std::vector<std::pair<double, std::int64_t>>{{0.5, 11}}); // 12 is gone
  // later: 11's time has come and the sink is active; nothing arrives
  d = life.decide(1.5, {x[0], x[1], x[3]}, {10, 11, 13}, [&] { ++non_finite; });
  CHECK(d.kept == std::vector<std::uint32_t>{0});
  CHECK(d.born.empty());
  CHECK(life.removed_ids == std::vector<std::int64_t>{40, 12, 11, 13});
  // nothing due: no change, and a particle with a NaN position outside the box is reported
  d = life.decide(1.6, {x[0]}, {10}, [&] { ++non_finite; });
  CHECK_FALSE(d.changed);
  CHECK(life.was_removed(13));
  CHECK_FALSE(life.was_removed(10));
  d = life.decide(1.7, {Vec2(std::nan(""), 0.5)}, {10}, [&] { ++non_finite; });
  CHECK(non_finite == 1);
}

TEST_CASE("variable properties: radii, masses and per-particle contact values") {
  // three disks of density 1000 (1 m long cylinders); the group {0, 2} grows with time, particle
  // 1 gets a friction that follows its speed
  ParticleArrays<2> p;
  const Disk disk{};
  for (int k = 0; k < 3; ++k) {
    const double r = 0.01, m = 1000 * disk.volume(r);
    p.id.push_back(k);
    p.position.push_back(Vec2(0.1 * k, 0));
    p.velocity.push_back(Vec2(0.5 * k, 0));
    p.omega.push_back(0.0);
    p.orientation.push_back(0.0);
    p.force.push_back(Vec2::Zero());
    p.torque.push_back(0.0);
    p.radius.push_back(r);
    p.mass.push_back(m);
    p.inv_mass.push_back(k == 2 ? 0.0 : 1 / m); // particle 2 is fixed
    p.inertia.push_back(0.5 * m * r * r);
    p.inv_inertia.push_back(k == 2 ? 0.0 : 1 / (0.5 * m * r * r));
    p.material.push_back(0);
  }
  const std::vector<std::vector<std::uint32_t>> members{{0, 1, 2}, {0, 2}, {1}};
  VariableProperties<2> vp;
  CHECK_FALSE(
      vp.add({"grow", Property::radius, Variable::time, Table({{0.0, 0.01}, {1.0, 0.02}})}, 1, 3));
  CHECK_FALSE(vp.per_particle);
  CHECK(vp.add({"slow", Property::friction, Variable::speed, Table({{0.0, 0.5}, {1.0, 0.1}}), 10},
               2, 3));
  CHECK(vp.per_particle);
  CHECK(std::isnan(vp.values[3][1]));
  // at t = 0.5 and step 5 only the radius is due (the friction every 10 steps)
  auto c = vp.apply(p, disk, members, 0.5, 5, false);
  CHECK(c.any);
  CHECK(c.radius);
  CHECK_FALSE(c.contact);
  CHECK(p.radius[0] == doctest::Approx(0.015).epsilon(1e-14));
  CHECK(p.radius[1] == 0.01);
  // the density is kept: m grows as r^2 for a disk; I = m r^2 / 2; fixed stays fixed
  const double m0 = 1000 * disk.volume(0.01);
  CHECK(p.mass[0] == doctest::Approx(m0 * 2.25).epsilon(1e-13));
  CHECK(p.inertia[0] == doctest::Approx(0.5 * p.mass[0] * 0.015 * 0.015).epsilon(1e-13));
  CHECK(p.inv_mass[0] == doctest::Approx(1 / p.mass[0]).epsilon(1e-13));
  CHECK(p.inv_mass[2] == 0.0);
  CHECK(p.inv_inertia[2] == 0.0);
  // all due: the friction of particle 1 at its speed 0.5 m/s is 0.3
  c = vp.apply(p, disk, members, 0.5, 7, true);
  CHECK(c.contact);
  CHECK(vp.values[3][1] == doctest::Approx(0.3).epsilon(1e-14));
  const Material base{.density = 1000, .young = 1e7, .friction = 0.5};
  CHECK(vp.material_of(1, base).friction == doctest::Approx(0.3).epsilon(1e-14));
  CHECK(vp.material_of(0, base).friction == 0.5);
  // the values follow the particles through a permutation
  vp.permute({1, 2, 0});
  CHECK(vp.values[3][0] == doctest::Approx(0.3).epsilon(1e-14));
  // bounds for the time step
  CHECK(vp.largest_radius() == 0.02);
  CHECK(vp.radius_bound().first == 0.01);
  CHECK(vp.radius_bound().second);
}

TEST_CASE("paired chunks: every chunk once, each item's writes in the same order on any team") {
  // rows [0, n) in chunks of `chunk`; the rows of chunk c write to the items of chunks c and
  // c + 1, as the contact pass does (partners at most a chunk ahead)
  const long n = 1000, chunk = 60;
  const long nchunks = (n + chunk - 1) / chunk;
  auto log_of = [&](bool parallel) {
    std::vector<std::vector<long>> log(static_cast<std::size_t>(n));
    std::vector<int> runs(static_cast<std::size_t>(nchunks), 0);
    grain::detail::run_paired_chunks(
        n, chunk, [](long b, long e) { return static_cast<double>(e - b); },
        [&](long b, long e) {
          const long c = b / chunk;
          ++runs[static_cast<std::size_t>(c)];
          for (long k = b; k < std::min(n, e + chunk); ++k)
            log[static_cast<std::size_t>(k)].push_back(c);
        },
        parallel);
    for (int r : runs)
      CHECK(r == 1);
    return log;
  };
  const auto serial = log_of(false), team = log_of(true);
  CHECK(serial == team);
#ifdef _OPENMP
  const int threads = omp_get_max_threads();
  for (const int t : {3, 4, 5}) { // more threads than cores: a waiting thread yields
    omp_set_num_threads(t);
    CHECK(serial == log_of(true));
  }
  omp_set_num_threads(threads);
#endif
  // an item of chunk k > 0 hears from chunks k - 1 and k, the even one first
  for (long k = chunk; k < n; ++k) {
    const long c = k / chunk;
    const auto& l = serial[static_cast<std::size_t>(k)];
    REQUIRE(l.size() == 2);
    CHECK(l[0] % 2 == 0);
    CHECK(std::set<long>(l.begin(), l.end()) == std::set<long>{c - 1, c});
  }
}

TEST_CASE("paired chunks: no rows (a simulation without particles) visit none") {
  long rows = 0;
  grain::detail::run_paired_chunks(
      0, 1, [](long b, long e) { return static_cast<double>(e - b); },
      [&](long b, long e) { rows += e - b; }, false);
  CHECK(rows == 0);
}

TEST_CASE("contacts are visited between a set-up change and the next run") {
  // particles added after a run have no row in the list until the next initialisation: the
  // visits cover the listed particles (the new one touches nothing yet)
  Sim<search::CellList> sim({.time_step = 2e-6, .gravity = Vec3(0, 0, -9.81)});
  pile(sim);
  sim.steps(10);
  const auto before = sim.contact_counts();
  REQUIRE(before.first + before.second > 0);
  sim.add_particle({.position = Vec3(0, 0, 1.0), .radius = 1e-3, .material = 0});
  CHECK(sim.contact_counts() == before);
  std::size_t visited = 0;
  sim.for_each_contact([&](auto, auto, bool, const auto&, const auto&) { ++visited; });
  CHECK(visited == before.first + before.second);
  sim.steps(1); // re-initialised: the new particle has its row
  CHECK(sim.neighbor_list().rows() == sim.size());
}
