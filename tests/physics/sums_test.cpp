// Sums by id (grain::sums<grain::by_id>): each particle sums its pair loads in ascending partner
// id, each pair evaluated with the lower id first. The final state must then be the same bits
// whatever the order of the neighbour list: another skin (other rebuild steps and cell size), no
// cell sort (the list in the order the particles were added), another thread count, a restart
// from a checkpoint. Against the default sums (list order) the runs agree to round-off over a
// short window (DEM is chaotic: only a short one).
#include "../support/materials.hpp"
#include <grain/grain.hpp>
#include <grain/models/conduction/batchelor_obrien.hpp>
#include <grain/models/conduction/surrounding_layer.hpp>
#include <grain/models/normal/jkr.hpp>
#include <grain/models/rolling/constant.hpp>
#include <grain/models/tangent/mindlin.hpp>

#include <doctest/doctest.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

namespace {

using namespace grain;

using Rolling = Interaction<normal::Hertz<>, tangent::Mindlin, rolling::Constant>;
using ById = Simulation<Sphere, search::CellList, Rolling, sums<by_id>>;
using ByList = Simulation<Sphere, search::CellList, Rolling>;
using Layer = Interaction<normal::Hertz<>, tangent::SpringDashpotSlider, rolling::None,
                          conduction::SurroundingLayer>;
using LayerById = Simulation<Sphere, search::CellList, Layer, sums<by_id>>;
using Sticky = Interaction<normal::Jkr, tangent::Mindlin>;
using StickyById = Simulation<Sphere, search::CellList, Sticky, sums<by_id>>;
using Frictional = Interaction<normal::LinearSpringDashpot, tangent::SpringSlider>;
using GasById = Simulation<Sphere, search::CellList, Frictional, sums<by_id>>;
using Static =
    Interaction<normal::Hertz<>, tangent::None, rolling::None, conduction::BatchelorOBrien>;
using StaticById = Simulation<Sphere, search::CellList, Static, sums<by_id>>;

/// How a run lists its pairs: the skin as a fraction of the largest radius, the cell sort, and
/// the number of threads.
struct Order {
  double skin;
  bool sort;
  int threads;
};

/// A box of side 12 x 2.6 mm open at the top, with 12 x 12 x 8 spheres of radii 0.8 to 1.2 mm on
/// a jittered lattice, thrown at up to 0.5 m/s under gravity (temperatures 300 to 400 K if
/// thermal): they fall, collide, roll and settle.
template <class S>
void fill_box(S& sim, std::uint64_t seed) {
  Material m = test::material(0.5, 0.5);
  m.rolling_friction = 0.05;
  if constexpr (S::thermal) {
    m.conductivity = 100.0; // a good conductor of little heat capacity: the heat spreads within
    m.heat_capacity = 10.0; // the run
  }
  sim.add_material(m);
  const double a = 2.6e-3, side = 12 * a;
  sim.add_wall(walls::Plane{Vec3(0, 0, 0), Vec3::UnitZ()});
  sim.add_wall(walls::Plane{Vec3(0, 0, 0), Vec3::UnitX()});
  sim.add_wall(walls::Plane{Vec3(side, 0, 0), -Vec3::UnitX()});
  sim.add_wall(walls::Plane{Vec3(0, 0, 0), Vec3::UnitY()});
  sim.add_wall(walls::Plane{Vec3(0, side, 0), -Vec3::UnitY()});
  std::mt19937_64 g(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int z = 0; z < 8; ++z)
    for (int y = 0; y < 12; ++y)
      for (int x = 0; x < 12; ++x) {
        ParticleSpec<3> s;
        s.radius = 1.0e-3 + 0.2e-3 * u(g);
        s.position = Vec3((x + 0.5) * a, (y + 0.5) * a, (z + 0.5) * a) +
                     Vec3(u(g), u(g), u(g)) * (0.5 * a - s.radius - 1e-5);
        s.velocity = Vec3(u(g), u(g), u(g)) * 0.3;
        s.omega = Vec3(u(g), u(g), u(g)) * 50.0;
        if constexpr (S::thermal) s.temperature = 350.0 + 50.0 * u(g);
        sim.add_particle(s);
      }
}

/// The state of every particle, by id: position, velocity, angular velocity (and temperature).
template <class S>
std::vector<double> state_by_id(const S& sim) {
  std::vector<double> out;
  const auto& p = sim.particles();
  std::vector<std::size_t> k(sim.size());
  for (std::size_t i = 0; i < k.size(); ++i)
    k[i] = i;
  std::sort(k.begin(), k.end(), [&](auto a, auto b) { return p.id[a] < p.id[b]; });
  for (const auto i : k) {
    for (int d = 0; d < 3; ++d) {
      out.push_back(p.position[i][d]);
      out.push_back(p.velocity[i][d]);
      out.push_back(p.omega[i][d]);
    }
    if constexpr (S::thermal) out.push_back(p.temperature[i]);
  }
  return out;
}

/// Byte equality of two states (NaN-safe, signed zeros told apart).
bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

/// Keeps the state of the first run of a series (returns true); checks every later one against it
/// bit for bit (returns false).
bool keep_or_compare(std::vector<double>& first, const std::vector<double>& s) {
  if (first.empty()) {
    first = s;
    return true;
  }
  CHECK(same_bits(s, first));
  return false;
}

template <class S>
typename S::Params params(const Order& o) {
  typename S::Params prm;
  prm.gravity = Vec3(0, 0, -9.81);
  prm.time_step = 1e-5; // a tenth of the Rayleigh time
  prm.search.skin = o.skin * 1.2e-3;
  prm.search.sort = o.sort;
  return prm;
}

struct Threads {
  int saved = omp_get_max_threads();
  explicit Threads(int n) { omp_set_num_threads(n); }
  ~Threads() { omp_set_num_threads(saved); }
};

const Order orders[] = {{0.2, true, 1}, {0.6, false, 2}, {0.05, true, 2}};

} // namespace

TEST_CASE("sums by id: a settling bed of rolling spheres, the same bits for any list order") {
  std::vector<double> first;
  std::vector<long> rebuilds;
  for (const auto& o : orders) {
    Threads t(o.threads);
    ById sim(params<ById>(o));
    fill_box(sim, 11);
    sim.steps(8000);
    rebuilds.push_back(sim.counters().rebuilds);
    const auto [pairs, walls] = sim.contact_counts();
    CHECK(pairs > sim.size() / 2); // a bed in contact, not a gas
    CHECK(walls > 50);
    auto s = state_by_id(sim);
    for (std::size_t w = 0; w < 5; ++w) // the loads on the walls, summed in id order too
      for (int d = 0; d < 3; ++d)
        s.push_back(sim.wall_force(w)[d]);
    CHECK(sim.wall_force(0)[2] < 0.0); // the bed rests on the floor
    keep_or_compare(first, s);
  }
  // the three runs rebuilt their lists at different steps (and ordered them differently)
  CHECK(rebuilds[0] != rebuilds[1]);
  CHECK(rebuilds[0] != rebuilds[2]);
  CHECK(rebuilds[1] != rebuilds[2]);
}

TEST_CASE("sums by id: a restart from a checkpoint continues with the same bits") {
  const Order o{0.2, true, 2};
  Threads t(o.threads);
  ById a(params<ById>(o));
  fill_box(a, 5);
  a.steps(1500);
  const std::string path = (std::filesystem::temp_directory_path() / "grain_sums.ckp").string();
  io::save_checkpoint(a, path);
  ById b(params<ById>(o));
  fill_box(b, 5);
  io::load_checkpoint(b, path);
  std::filesystem::remove(path);
  a.steps(1500);
  b.steps(1500);
  CHECK(same_bits(state_by_id(a), state_by_id(b)));
}

TEST_CASE("sums by id: within round-off of the list-order sums over a short window") {
  // 1000 steps from the start: the two orders of summation differ by round-off only (1e-16
  // relative per sum), which the contacts amplify (3e-13 of the largest speed here); 1e-9 of the
  // largest speed is the bound
  const Order o{0.2, true, 1};
  ById a(params<ById>(o));
  ByList b(params<ByList>(o));
  fill_box(a, 3);
  fill_box(b, 3);
  a.steps(1000);
  b.steps(1000);
  REQUIRE(a.contact_counts().first > 50); // the bed is forming
  const auto sa = state_by_id(a), sb = state_by_id(b);
  double dv = 0.0, vmax = 0.0;
  for (std::size_t k = 1; k < sa.size(); k += 3) { // velocities (and angular velocities next)
    dv = std::max(dv, std::abs(sa[k] - sb[k]));
    vmax = std::max(vmax, std::abs(sb[k]));
  }
  CHECK(vmax > 0.1);
  CHECK(dv <= 1e-9 * vmax);
}

TEST_CASE("sums by id: adhesive spheres acting across gaps, the same bits for any list order") {
  std::vector<double> first;
  for (const auto& o : orders) {
    Threads t(o.threads);
    auto prm = params<StickyById>(o);
    prm.contact.normal.work_of_adhesion = 0.05; // J/m^2: pairs stick and pull across gaps
    prm.contact.normal.damping_ratio = 0.2;
    StickyById sim(prm);
    fill_box(sim, 23);
    sim.steps(6000);
    CHECK(sim.contact_counts().first > sim.size() / 2);
    const auto s = state_by_id(sim);
    keep_or_compare(first, s);
  }
}

TEST_CASE("sums by id: a heated bed conducting across gaps, the same bits for any list order") {
  std::vector<double> first;
  for (const auto& o : orders) {
    Threads t(o.threads);
    auto prm = params<LayerById>(o);
    prm.dissipation_heating = 0.5;  // the pairs' dissipation heats them too
    prm.fluid.conductivity = 0.026; // air
    LayerById sim(prm);
    fill_box(sim, 17);
    auto spread = [&] { // standard deviation of the temperatures [K]
      double m = 0.0, m2 = 0.0;
      for (const double T : sim.particles().temperature) {
        m += T;
        m2 += T * T;
      }
      m /= static_cast<double>(sim.size());
      return std::sqrt(m2 / static_cast<double>(sim.size()) - m * m);
    };
    const double before = spread();
    sim.steps(3000);
    const auto s = state_by_id(sim);
    if (keep_or_compare(first, s)) {
      CHECK(spread() < 0.95 * before); // heat flowed between the particles (28.9 to 25.8 K)
    }
  }
}

TEST_CASE("sums by id: a periodic frictional gas, the same bits sorted or not, 1 or 2 threads") {
  std::vector<double> first;
  for (const Order o : {Order{0.2, true, 1}, Order{0.2, false, 2}}) {
    Threads t(o.threads);
    GasById::Params prm;
    prm.contact.normal.stiffness = 1e6;
    prm.search.skin = o.skin * 0.5;
    prm.search.sort = o.sort;
    GasById sim(prm);
    sim.add_material(test::material(0.7, 0.5));
    const int n = 11;
    const double side = n * 1.6;
    for (int d = 0; d < 3; ++d)
      sim.set_periodic(d, 0.0, side);
    std::mt19937_64 g(7);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    for (int x = 0; x < n; ++x)
      for (int y = 0; y < n; ++y)
        for (int z = 0; z < n; ++z) {
          ParticleSpec<3> s;
          s.radius = 0.5;
          s.position = Vec3(x + 0.5, y + 0.5, z + 0.5) * 1.6;
          s.velocity = Vec3(u(g), u(g), u(g)) * 2.0;
          sim.add_particle(s);
        }
    sim.steps(2000);
    CHECK(sim.counters().rebuilds > 10); // particles wrapped and the lists were made anew
    std::vector<double> s;
    for (std::int64_t id = 0; id < static_cast<std::int64_t>(sim.size()); ++id) {
      const auto k = sim.index_of(id);
      for (int d = 0; d < 3; ++d) {
        s.push_back(sim.unwrapped_position(k)[d]);
        s.push_back(sim.particles().velocity[k][d]);
        s.push_back(sim.particles().omega[k][d]);
      }
    }
    keep_or_compare(first, s);
  }
}

TEST_CASE("sums by id: a thermal analysis of a packing, the same bits sorted or not") {
  std::vector<double> first;
  for (const Order o : {Order{0.2, true, 1}, Order{0.6, false, 2}}) {
    Threads t(o.threads);
    StaticById::Params prm;
    prm.analysis = Analysis::thermal;
    prm.search.skin = o.skin * 1e-3;
    prm.search.sort = o.sort;
    StaticById sim(prm);
    sim.add_material(test::glass());
    std::mt19937_64 g(3);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    const int n = 12;
    for (int x = 0; x < n; ++x)
      for (int y = 0; y < n; ++y)
        for (int z = 0; z < 8; ++z) {
          ParticleSpec<3> s;
          s.radius = 1e-3 * (1.0 + 0.01 * u(g)); // overlapping neighbours on a 1.99 mm lattice
          s.position = Vec3(x, y, z) * 1.99e-3;
          s.temperature = 300.0 + 10.0 * z + u(g);
          sim.add_particle(s);
        }
    // the bottom layer (ids 0, 8, 16, ...: z = 0), before and after
    auto bottom = [&] {
      double sum = 0.0;
      for (std::int64_t id = 0; id < static_cast<std::int64_t>(sim.size()); id += 8)
        sum += sim.particles().temperature[sim.index_of(id)];
      return sum / (n * n);
    };
    const double before = bottom();
    sim.steps(500);
    std::vector<double> s;
    for (std::int64_t id = 0; id < static_cast<std::int64_t>(sim.size()); ++id)
      s.push_back(sim.particles().temperature[sim.index_of(id)]);
    if (keep_or_compare(first, s)) {
      CHECK(bottom() > before + 0.1); // heat came down from the layer above
    }
  }
}
