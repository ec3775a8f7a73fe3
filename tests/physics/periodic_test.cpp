// Periodic boundaries and Lees-Edwards shear (docs/periodic.md).
//
// - A frictional pair colliding across the x boundary, one of them wrapping in mid-contact, moves
//   as the same pair inside the box: the relative motion, the spins (the tangential spring's
//   history) and the unwrapped positions agree with the unwrapped run to 1e-9.
// - Periodic lattices (3D simple cubic, 2D triangular, 3D cubic between two walls) have exactly
//   the contacts of the infinite lattice: 3 N (3D cubic, 2D triangular), n^2 (3m - 1) pairs plus
//   2 n^2 wall contacts between the walls; every particle has its full coordination.
// - A frictional granular gas in a fully periodic box keeps its total momentum to 1e-12 of
//   sum m |v|, and runs to the same bits on 1 and 2 threads.
// - Homogeneous cooling (Haff's law): a frictionless gas of restitution e cools as
//   T(t) = T0 / (1 + t/tau)^2, so 1/sqrt(T) grows linearly at the rate
//   A/2 = (2/3) sqrt(pi) n chi sigma^2 (1 - e^2) / sqrt(m)   (T = m <v^2>/3 [J]),
//   chi = (1 - phi/2)/(1 - phi)^3 (Carnahan-Starling pair correlation at contact); derived from
//   the Enskog collision rate (Brilliantov and Poeschel, Kinetic Theory of Granular Gases, 2004,
//   ch. 6; Haff, J. Fluid Mech. 134 (1983) 401). The fitted rate is within 5 % of it.
// - Lees-Edwards: a free particle leaving through the top re-enters through the bottom with
//   v_x - gamma L_y, its unwrapped path continuous; a sheared gas keeps the uniform shear profile
//   v_x = gamma y (slope within 5 %), which plain periodic boundaries lose.
// - A checkpoint of a sheared periodic gas continues bit for bit (image counts, shifts), and one
//   written without periodic boundaries is refused; the particle VTK files carry the image
//   counts and unwrapped positions.

#include "../support/materials.hpp"
#include <grain/grain.hpp>

#include <doctest/doctest.h>
#include <omp.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace {

using namespace grain;

using Frictional = Interaction<normal::LinearSpringDashpot, tangent::SpringSlider>;
using Frictionless = Interaction<normal::LinearSpringDashpot>;
using Sim3 = Simulation<Sphere, search::CellList, Frictional>;

/// Normal deviates from a seeded engine (Box-Muller on the engine's own 53-bit uniforms).
struct Normal {
  std::mt19937_64 engine;
  explicit Normal(std::uint64_t seed) : engine(seed) {}
  double uniform() { return (static_cast<double>(engine() >> 11) + 0.5) * 0x1.0p-53; }
  double operator()() {
    return std::sqrt(-2.0 * std::log(uniform())) * std::cos(2.0 * std::numbers::pi * uniform());
  }
};

/// A pair colliding obliquely with a common drift along x: in box [0, 1) periodic along x
/// (`periodic`), starting across the boundary, or shifted by -0.5 in an open space.
struct PairRun {
  std::vector<Vec3> relative, unwrapped;
  std::vector<Vec3> spin;
  bool wrapped_in_contact = false;
  int max_contacts = 0;
};

PairRun run_pair(bool periodic) {
  Sim3::Params prm;
  prm.contact.normal.stiffness = 1e3;
  prm.time_step = 1e-4;
  Sim3 sim(prm);
  const auto m = sim.add_material(test::material(0.6, 0.4));
  const double r = 0.05, shift = periodic ? 0.0 : -0.5;
  if (periodic) sim.set_periodic(0, 0.0, 1.0);
  ParticleSpec<3> a, b;
  a.radius = b.radius = r;
  a.material = b.material = m;
  a.position = Vec3(0.93 + shift, 0.5, 0.5);
  b.position = Vec3(0.93 + 0.105 + shift - (periodic ? 1.0 : 0.0), 0.52, 0.5);
  a.velocity = Vec3(2.3, 0.2, 0.0);
  b.velocity = Vec3(1.7, -0.2, 0.0);
  const auto ia = sim.add_particle(a), ib = sim.add_particle(b);
  PairRun out;
  for (int k = 0; k < 1500; ++k) {
    const auto before = sim.image(sim.index_of(ia))[0];
    int contacts_before = 0;
    if (k > 0)
      sim.for_each_contact(
          [&](auto, auto, bool, const auto&, const auto&, double) { ++contacts_before; });
    sim.step();
    int contacts = 0;
    sim.for_each_contact([&](auto, auto, bool, const auto&, const auto&, double) { ++contacts; });
    out.max_contacts = std::max(out.max_contacts, contacts);
    const auto i = sim.index_of(ia), j = sim.index_of(ib);
    if (sim.image(i)[0] != before && contacts_before == 1 && contacts == 1)
      out.wrapped_in_contact = true;
    out.relative.push_back(sim.separation(i, j));
    Vec3 u = sim.unwrapped_position(i);
    u[0] -= shift;
    out.unwrapped.push_back(u);
    out.spin.push_back(sim.particles().omega[i]);
  }
  return out;
}

/// Number of pair and wall contacts, and the smallest and largest coordination.
struct Count {
  long pairs = 0, walls = 0;
  int least = 1 << 30, most = 0;
};
template <class S>
Count count_contacts(S& sim) {
  sim.initialize();
  Count c;
  std::vector<int> z(sim.size(), 0);
  sim.for_each_contact(
      [&](std::size_t i, std::size_t j, bool wall, const auto&, const auto&, double) {
        if (wall) {
          ++c.walls;
        } else {
          ++c.pairs;
          ++z[j];
        }
        ++z[i];
      });
  for (int v : z) {
    c.least = std::min(c.least, v);
    c.most = std::max(c.most, v);
  }
  return c;
}

/// The touching pairs the contact law sees (for_each_contact, from the neighbour list) and those
/// a brute-force test of every pair through its nearest image finds.
template <class S>
std::pair<long, long> listed_and_brute(const S& sim) {
  long listed = 0, brute = 0;
  sim.for_each_contact([&](std::size_t, std::size_t, bool wall, const auto&, const auto&, double) {
    listed += !wall;
  });
  const auto& p = sim.particles();
  for (std::size_t i = 0; i < p.size(); ++i)
    for (std::size_t j = i + 1; j < p.size(); ++j)
      brute += sim.separation(i, j).norm() < p.radius[i] + p.radius[j];
  return {listed, brute};
}

/// A gas of N = n^3 spheres of diameter 1 m at solid fraction phi, on a cubic lattice with
/// Maxwellian velocities of temperature m v0^2 (zero total momentum), in a box periodic along
/// every axis.
template <class S>
void fill_gas(S& sim, int n, double phi, double v0, std::uint64_t seed, bool lees_edwards = false,
              double shear = 0.0) {
  const double r = 0.5, volume = static_cast<double>(n * n * n) * std::numbers::pi / 6.0;
  const double side = std::cbrt(volume / phi), a = side / n;
  for (int d = 0; d < 3; ++d)
    sim.set_periodic(d, 0.0, side);
  if (lees_edwards) sim.set_lees_edwards(shear);
  Normal g(seed);
  std::vector<ParticleSpec<3>> specs;
  Vec3 mean = Vec3::Zero();
  for (int x = 0; x < n; ++x)
    for (int y = 0; y < n; ++y)
      for (int z = 0; z < n; ++z) {
        ParticleSpec<3> s;
        s.radius = r;
        s.material = 0;
        s.position = Vec3((x + 0.5) * a, (y + 0.5) * a, (z + 0.5) * a);
        s.velocity = Vec3(g(), g(), g()) * v0;
        mean += s.velocity;
        specs.push_back(s);
      }
  mean /= static_cast<double>(specs.size());
  for (auto& s : specs) {
    s.velocity -= mean;
    s.velocity[0] += shear * (s.position[1] - 0.5 * side);
    sim.add_particle(s);
  }
}

/// Granular temperature m <|v - <v>|^2> / 3 [J] of equal particles.
template <class S>
double temperature(const S& sim) {
  const auto& p = sim.particles();
  double sum = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i)
    sum += p.mass[i] * p.velocity[i].squaredNorm();
  return sum / (3.0 * static_cast<double>(p.size()));
}

} // namespace

TEST_CASE("periodic: a pair colliding across the boundary keeps its contact and history") {
  const PairRun per = run_pair(true), open = run_pair(false);
  CHECK(per.wrapped_in_contact); // the test covers a wrap in mid-contact
  CHECK(per.max_contacts == 1);
  double spin = 0.0, rel = 0.0, pos = 0.0, spin_max = 0.0;
  for (std::size_t k = 0; k < per.relative.size(); ++k) {
    rel = std::max(rel, (per.relative[k] - open.relative[k]).norm());
    pos = std::max(pos, (per.unwrapped[k] - open.unwrapped[k]).norm());
    spin = std::max(spin, (per.spin[k] - open.spin[k]).norm());
    spin_max = std::max(spin_max, open.spin[k].norm());
  }
  CHECK(spin_max > 1.0); // friction spun the particles (rad/s)
  CHECK(rel < 1e-9);     // m
  CHECK(pos < 1e-9);     // m
  CHECK(spin < 1e-9 * spin_max);
}

TEST_CASE("periodic: a lattice has exactly the contacts of the infinite lattice") {
  Material mat = test::material(0.5, 0.3);
  SUBCASE("3D simple cubic, every axis periodic, cell list and all pairs") {
    for (int n : {4, 5, 7}) {
      const double r = 0.01, a = 2.0 * r * 0.995, side = n * a;
      auto fill = [&](auto& sim) {
        sim.add_material(mat);
        for (int d = 0; d < 3; ++d)
          sim.set_periodic(d, -0.3 * side, 0.7 * side);
        for (int x = 0; x < n; ++x)
          for (int y = 0; y < n; ++y)
            for (int z = 0; z < n; ++z) {
              ParticleSpec<3> s;
              s.radius = r;
              s.position = Vec3(x * a - 0.3 * side, y * a, z * a); // from the lower bound
              sim.add_particle(s);
            }
      };
      Sim3 cells;
      fill(cells);
      Simulation<Sphere, search::AllPairs, Frictional> all;
      fill(all);
      for (const Count c : {count_contacts(cells), count_contacts(all)}) {
        CHECK(c.pairs == 3L * n * n * n);
        CHECK(c.least == 6);
        CHECK(c.most == 6);
      }
      // the force loop sees every contact across the boundaries: each particle's 6 equal
      // contact forces balance (a missed one would leave a net force of a whole contact)
      cells.step();
      double contact = 0.0, net = 0.0;
      cells.for_each_contact([&](auto, auto, bool, const auto&, const auto& r, double) {
        contact = std::max(contact, std::abs(r.normal.force));
      });
      for (const auto& f : cells.particles().force)
        net = std::max(net, f.norm());
      CHECK(contact > 0.0);
      CHECK(net < 1e-9 * contact);
    }
  }
  SUBCASE("2D triangular lattice, x and y periodic") {
    using Sim2 = Simulation<Disk, search::CellList, Frictional>;
    for (int n : {6, 10}) {
      const double r = 0.01, a = 2.0 * r * 0.995, h = a * std::sqrt(3.0) / 2.0;
      Sim2 sim;
      sim.add_material(mat);
      sim.set_periodic(0, 0.0, n * a);
      sim.set_periodic(1, 0.0, n * h); // n even: the rows alternate across the boundary too
      for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
          ParticleSpec<2> s;
          s.radius = r;
          s.position = Vec2((x + 0.5 * (y % 2)) * a, y * h);
          sim.add_particle(s);
        }
      const Count c = count_contacts(sim);
      CHECK(c.pairs == 3L * n * n);
      CHECK(c.least == 6);
      CHECK(c.most == 6);
    }
  }
  SUBCASE("3D cubic between two walls, x and y periodic") {
    const int n = 5, layers = 4;
    const double r = 0.01, a = 2.0 * r * 0.995;
    Sim3 sim;
    sim.add_material(mat);
    sim.set_periodic(0, 0.0, n * a);
    sim.set_periodic(1, 0.0, n * a);
    sim.add_wall(walls::Plane{Vec3(0, 0, -0.995 * r), Vec3::UnitZ()});
    sim.add_wall(walls::Plane{Vec3(0, 0, (layers - 1) * a + 0.995 * r), -Vec3::UnitZ()});
    for (int x = 0; x < n; ++x)
      for (int y = 0; y < n; ++y)
        for (int z = 0; z < layers; ++z) {
          ParticleSpec<3> s;
          s.radius = r;
          s.position = Vec3(x * a, y * a, z * a);
          sim.add_particle(s);
        }
    const Count c = count_contacts(sim);
    CHECK(c.pairs == static_cast<long>(n) * n * (3 * layers - 1));
    CHECK(c.walls == 2L * n * n);
    CHECK(c.least == 6);
    CHECK(c.most == 6);
  }
}

TEST_CASE("periodic: a frictional gas keeps its momentum, the same bits on 1 and 2 threads") {
  auto run = [](int threads) {
    const int saved = omp_get_max_threads();
    omp_set_num_threads(threads);
    Sim3::Params prm;
    prm.contact.normal.stiffness = 1e6;
    Sim3 sim(prm);
    sim.add_material(test::material(0.7, 0.5));
    fill_gas(sim, 11, 0.15, 2.0, 7); // 1331 spheres: the parallel pass
    double scale = 0.0;
    for (std::size_t i = 0; i < sim.size(); ++i)
      scale += sim.particles().mass[i] * sim.particles().velocity[i].norm();
    for (int k = 0; k < 3; ++k) {
      sim.steps(1000);
      const auto [listed, brute] = listed_and_brute(sim); // every contact found, every side
      CHECK(listed == brute);
    }
    Vec3 momentum = Vec3::Zero();
    for (std::size_t i = 0; i < sim.size(); ++i)
      momentum += sim.particles().mass[i] * sim.particles().velocity[i];
    CHECK(momentum.norm() < 1e-12 * scale);
    std::vector<Vec3> state;
    for (std::size_t i = 0; i < sim.size(); ++i) {
      const auto k = sim.index_of(static_cast<std::int64_t>(i));
      state.push_back(sim.unwrapped_position(k));
      state.push_back(sim.particles().velocity[k]);
    }
    CHECK(sim.counters().rebuilds > 10); // particles wrapped and lists were rebuilt
    omp_set_num_threads(saved);
    return state;
  };
  const auto one = run(1), two = run(2);
  REQUIRE(one.size() == two.size());
  std::size_t differ = 0;
  for (std::size_t k = 0; k < one.size(); ++k)
    differ += one[k] != two[k];
  CHECK(differ == 0);
}

TEST_CASE("periodic: homogeneous cooling of a granular gas follows Haff's law") {
  using Sim = Simulation<Sphere, search::CellList, Frictionless>;
  const int n = 10;
  const double phi = 0.1, e = 0.8, v0 = 1.0;
  Material mat = test::material(e);
  mat.density = 1000.0;
  const double mass = mat.density * std::numbers::pi / 6.0; // diameter 1 m
  // contact time about 1/30 of the mean free time at the start, 40 steps a contact
  const double omega = 4.0 * std::sqrt(std::numbers::pi) * (phi / (std::numbers::pi / 6.0)) *
                       (1.0 - phi / 2.0) / std::pow(1.0 - phi, 3) * v0;
  const double tc = 1.0 / (30.0 * omega);
  Sim::Params prm;
  prm.contact.normal.stiffness = 0.5 * mass * std::pow(std::numbers::pi / tc, 2);
  prm.time_step = tc / 40.0;
  Sim sim(prm);
  sim.add_material(mat);
  fill_gas(sim, n, phi, v0, 11);
  const double number_density = phi / (std::numbers::pi / 6.0);
  const double chi = (1.0 - phi / 2.0) / std::pow(1.0 - phi, 3);
  const double rate = 2.0 / 3.0 * std::sqrt(std::numbers::pi) * number_density * chi *
                      (1.0 - e * e) / std::sqrt(mass); // d(1/sqrt(T))/dt [1/(s sqrt(J))]
  const double tau = 1.0 / (rate * std::sqrt(temperature(sim)));
  // the lattice melts over the first collisions; then 1/sqrt(T) is sampled up to t = 1.2 tau
  sim.run(0.15 * tau);
  std::vector<double> t, y;
  while (sim.time() < 1.2 * tau) {
    sim.run(0.02 * tau);
    t.push_back(sim.time());
    y.push_back(1.0 / std::sqrt(temperature(sim)));
  }
  double mt = 0, my = 0;
  for (std::size_t k = 0; k < t.size(); ++k) {
    mt += t[k];
    my += y[k];
  }
  mt /= static_cast<double>(t.size());
  my /= static_cast<double>(t.size());
  double sty = 0, stt = 0;
  for (std::size_t k = 0; k < t.size(); ++k) {
    sty += (t[k] - mt) * (y[k] - my);
    stt += (t[k] - mt) * (t[k] - mt);
  }
  const double fitted = sty / stt;
  MESSAGE("Haff: fitted rate / Enskog rate = ", fitted / rate,
          ", T(end)/T(start) = ", std::pow(y.front() / y.back(), 2));
  CHECK(fitted == doctest::Approx(rate).epsilon(0.05));
}

TEST_CASE("periodic: Lees-Edwards images slide and keep a uniform shear") {
  SUBCASE("a free particle through the top") {
    Sim3 sim;
    sim.add_material(test::material(0.5));
    sim.set_periodic(0, 0.0, 1.0);
    sim.set_periodic(1, 0.0, 2.0);
    const double shear = 0.75; // the box above slides at 1.5 m/s
    sim.set_lees_edwards(shear);
    ParticleSpec<3> s;
    s.radius = 0.05;
    s.position = Vec3(0.3, 1.9, 0.0);
    s.velocity = Vec3(0.0, 1.0, 0.0);
    sim.add_particle(s);
    sim.run(0.5);
    CHECK(sim.image(0)[1] == 1);
    const double t = sim.time();
    CHECK(sim.particles().position[0][1] == doctest::Approx(1.9 + t - 2.0).epsilon(1e-9));
    CHECK(sim.particles().velocity[0][0] == doctest::Approx(-shear * 2.0).epsilon(1e-12));
    // the path as if unbounded: straight up, x unchanged
    const Vec3 u = sim.unwrapped_position(0);
    CHECK(u[0] == doctest::Approx(0.3).epsilon(1e-9));
    CHECK(u[1] == doctest::Approx(1.9 + t).epsilon(1e-9));
    // a new rate acts from now on: the images do not jump (the unwrapped path moves by at most
    // a step at the lab speed, 1.5 + 3 m/s), and the next crossing slides at the new rate
    const Vec3 before = sim.unwrapped_position(0);
    sim.set_lees_edwards(-2.0 * shear);
    sim.step();
    CHECK((sim.unwrapped_position(0) - before).norm() < 5.0 * sim.time_step());
    sim.run(2.5); // up through the top once more
    CHECK(sim.image(0)[1] == 2);
    CHECK(sim.particles().velocity[0][0] == doctest::Approx(-shear * 2.0 + 2.0 * shear * 2.0));
    CHECK(sim.unwrapped_position(0)[1] == doctest::Approx(1.9 + sim.time()).epsilon(1e-9));
  }
  SUBCASE("the search lists every touching pair across the sliding boundary") {
    using Sim = Simulation<Sphere, search::CellList, Frictionless>;
    Material mat = test::material(0.9);
    mat.density = 1000.0;
    Sim::Params prm;
    prm.contact.normal.stiffness = 1e6;
    Sim sim(prm);
    sim.add_material(mat);
    fill_gas(sim, 7, 0.45, 0.5, 9, true, 0.8); // dense: many contacts across every side
    long checked = 0;
    for (int k = 0; k < 20; ++k) {
      sim.steps(60);
      const auto [listed, brute] = listed_and_brute(sim);
      CHECK(listed == brute);
      checked += brute;
    }
    CHECK(checked > 1000);
    CHECK(sim.periodic().offset > 0.0);
  }
  SUBCASE("a sheared gas keeps the profile v_x = gamma y") {
    using Sim = Simulation<Sphere, search::CellList, Frictionless>;
    auto slope = [](bool lees_edwards) {
      Material mat = test::material(0.9);
      mat.density = 1000.0;
      Sim::Params prm;
      prm.contact.normal.stiffness = 1e6;
      Sim sim(prm);
      sim.add_material(mat);
      const double shear = 0.1;
      fill_gas(sim, 10, 0.2, 0.3, 5, lees_edwards, shear);
      sim.run(20.0);
      const auto& p = sim.particles();
      const double side = sim.periodic().length[1];
      double sy = 0, sv = 0, syy = 0, syv = 0;
      for (std::size_t i = 0; i < p.size(); ++i) {
        const double yy = p.position[i][1] - 0.5 * side, v = p.velocity[i][0];
        sy += yy;
        sv += v;
        syy += yy * yy;
        syv += yy * v;
      }
      const double n = static_cast<double>(p.size());
      return (syv - sy * sv / n) / (syy - sy * sy / n) / shear;
    };
    const double sheared = slope(true), plain = slope(false);
    MESSAGE("shear slope / gamma: Lees-Edwards ", sheared, ", plain periodic ", plain);
    CHECK(sheared == doctest::Approx(1.0).epsilon(0.05));
    CHECK(plain < 0.8);
  }
}

TEST_CASE("periodic: bad set-ups are refused") {
  Sim3 sim;
  sim.add_material(test::material(0.5));
  CHECK_THROWS_WITH_AS(sim.set_periodic(3, 0.0, 1.0), doctest::Contains("axis"), InputError);
  CHECK_THROWS_WITH_AS(sim.set_periodic(0, 1.0, 1.0), doctest::Contains("hi"), InputError);
  CHECK_THROWS_AS(sim.set_periodic(0, 0.0, std::nan("")), InputError);
  sim.set_periodic(0, 0.0, 0.15); // shorter than 2 (2 R + reach) for R = 0.05
  ParticleSpec<3> s;
  s.radius = 0.05;
  sim.add_particle(s);
  CHECK_THROWS_WITH_AS(sim.initialize(), doctest::Contains("box length along x"), InputError);
  Sim3 le;
  le.add_material(test::material(0.5));
  le.set_periodic(0, 0.0, 1.0);
  le.set_lees_edwards(1.0);
  le.add_particle(s);
  CHECK_THROWS_WITH_AS(le.initialize(), doctest::Contains("set_periodic along x and y"),
                       InputError);
  Sim3 none; // a shear without any periodic axis
  none.add_material(test::material(0.5));
  none.set_lees_edwards(1.0);
  none.add_particle(s);
  CHECK_THROWS_WITH_AS(none.initialize(), doctest::Contains("set_periodic along x and y"),
                       InputError);
}

TEST_CASE("periodic: a checkpoint continues bit for bit; the particle files carry the images") {
  auto setup = [](Sim3& sim) {
    sim.add_material(test::material(0.7, 0.5));
    fill_gas(sim, 6, 0.15, 2.0, 3, true, 0.5); // Lees-Edwards: the shifts are state too
  };
  Sim3::Params prm;
  prm.contact.normal.stiffness = 1e6;
  Sim3 a(prm);
  setup(a);
  a.steps(1500);
  const auto dir = std::filesystem::temp_directory_path();
  const std::string path = (dir / "grain_periodic.ckp").string();
  io::save_checkpoint(a, path);
  Sim3 b(prm);
  setup(b);
  io::load_checkpoint(b, path);
  a.steps(1500);
  b.steps(1500);
  long wrapped = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    CHECK(a.particles().position[i] == b.particles().position[i]);
    CHECK(a.particles().velocity[i] == b.particles().velocity[i]);
    CHECK(a.unwrapped_position(i) == b.unwrapped_position(i));
    CHECK(a.image(i) == b.image(i));
    wrapped += a.image(i) != std::array<std::int32_t, 3>{};
  }
  CHECK(wrapped > 0); // the state compared holds wraps
  // a checkpoint without periodic boundaries
  Sim3 plain(prm);
  plain.add_material(test::material(0.7, 0.5));
  ParticleSpec<3> s;
  s.radius = 0.5;
  plain.add_particle(s);
  plain.steps(1);
  io::save_checkpoint(plain, path);
  Sim3 periodic(prm);
  periodic.add_material(test::material(0.7, 0.5));
  periodic.set_periodic(0, -5.0, 5.0);
  periodic.add_particle(s);
  CHECK_THROWS_WITH_AS(io::load_checkpoint(periodic, path), doctest::Contains("periodic"),
                       InputError);
  std::filesystem::remove(path);
  // the particle file: unwrapped positions and image counts next to the wrapped points
  const std::string vtk = (dir / "grain_periodic.vtk").string();
  io::write_particles_vtk(a, vtk);
  std::ifstream in(vtk);
  std::stringstream text;
  text << in.rdbuf();
  const std::string file = text.str();
  CHECK(file.find("VECTORS unwrapped_position double") != std::string::npos);
  CHECK(file.find("VECTORS image double") != std::string::npos);
  std::filesystem::remove(vtk);
}
