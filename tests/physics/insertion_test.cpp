// Insertion of particles during a run (include/grain/setup/insertion.hpp, docs/insertion.md),
// against closed forms.
//
// Semantics under test: at the end of every step, at t = n dt, an insertion with a number rate
// has placed N(t) = floor(rate (min(t, t_end) - t_begin) + 1e-9) particles (fewer only when the
// region is blocked); one with a mass rate the longest prefix of its particle sequence whose mass
// is at most rate (t - t_begin), which lags that by less than one particle's mass. No inserted
// particle overlaps any other at the step it appears (|x_i - x_j| >= r_i + r_j, exactly: the
// positions are those tested). Where a count is checked exactly the placement never fails (a
// region much larger than what is in it, particles leaving it at 1 m/s): N(t) is then the count.
#include "../errors.hpp"
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <doctest/doctest.h>
#include <filesystem>
#include <grain/grain.hpp>
#include <limits>
#include <numbers>
#include <set>
#include <string>
#include <vector>

using namespace grain;
using grain::test::error_of;
using grain::test::has;

namespace {

using Sim3 = Simulation<Sphere, search::CellList, presets::HertzMindlin>;
using Sim2 = Simulation<Disk, search::CellList, presets::HertzMindlin>;

constexpr double g0 = 9.81; // [m/s^2]
constexpr double dt = 1e-5; // [s], far below the Rayleigh time (~4e-4 s) of these particles

Material soft() {
  return Material{.name = "soft", .density = 2500, .young = 1e7, .poisson = 0.3, .friction = 0.5};
}

template <class Sim>
typename Sim::Params params(const Vec<Sim::dimension>& gravity, double step = dt) {
  typename Sim::Params p;
  p.time_step = step;
  p.gravity = gravity;
  return p;
}

/// The number rate's count at time t (the docs' formula).
std::uint64_t due_count(double rate, double t, double t_begin) {
  const double q = rate * (t - t_begin);
  return q <= 0 ? 0 : static_cast<std::uint64_t>(std::floor(q + 1e-9));
}

/// Checks the particles that are new since the last call (ids not in `seen`): none overlaps any
/// other particle, each has the velocity `v` (no spread), is in `group` and was made now.
/// Returns the number of new particles.
template <class Sim>
std::size_t check_new(const Sim& sim, std::set<std::int64_t>& seen, const Vec<Sim::dimension>& v,
                      const std::string& group, std::size_t& overlaps, std::size_t& wrong) {
  const auto& p = sim.particles();
  const auto& members = sim.group(group).ids;
  std::size_t fresh = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (seen.count(p.id[i])) continue;
    ++fresh;
    for (std::size_t j = 0; j < p.size(); ++j) {
      if (j == i) continue;
      const double s = p.radius[i] + p.radius[j];
      if ((p.position[i] - p.position[j]).squaredNorm() < s * s) ++overlaps;
    }
    if (p.velocity[i] != v || !std::binary_search(members.begin(), members.end(), p.id[i])) ++wrong;
  }
  for (std::size_t i = 0; i < p.size(); ++i)
    seen.insert(p.id[i]);
  return fresh;
}

} // namespace

TEST_CASE("insertion: a number rate gives floor(rate (t - t_begin)) particles, none overlapping") {
  // 3D: a box 0.1 m wide, 2000 spheres/s of radius 2 mm leaving it downwards at 1 m/s. Every
  // particle present at the end stays far from the box (no blockage), so the count is exact.
  Sim3 sim(params<Sim3>(Vec3(0, 0, -g0)));
  const auto k = sim.add_material(soft());
  const double rate = 2000.0, t_begin = 0.00123;
  const Vec3 v(0, 0, -1);
  const auto ins = sim.add_insertion({.name = "feed",
                                      .region = regions::Box<3>{{0, 0, 0.5}, {0.1, 0.1, 0.6}},
                                      .size = generate::Constant{2e-3},
                                      .material = k,
                                      .number_rate = rate,
                                      .velocity = v,
                                      .t_begin = t_begin,
                                      .group = "poured",
                                      .seed = 7});
  CHECK(sim.size() == 0);
  std::set<std::int64_t> seen;
  std::size_t overlaps = 0, wrong = 0, miscount = 0, new_total = 0;
  for (int n = 0; n < 5000; ++n) {
    sim.step();
    new_total += check_new(sim, seen, v, "poured", overlaps, wrong);
    const auto want = due_count(rate, sim.time(), t_begin);
    const auto& st = sim.insertion_status(ins);
    miscount += sim.size() != want || st.inserted != want || st.due != want || st.shortfall != 0;
  }
  const double t = sim.time();
  CHECK(t == doctest::Approx(0.05).epsilon(1e-12));
  // premise: rate (t - t_begin) is not within 1e-9 of a whole number at the end
  CHECK(sim.size() == 97); // floor(2000 x 0.04877) = floor(97.54)
  CHECK(std::abs(double(sim.size()) - rate * (t - t_begin)) < 1.0);
  CHECK(miscount == 0);
  CHECK(overlaps == 0);
  CHECK(wrong == 0);
  CHECK(new_total == 97);
  CHECK(sim.group("poured").ids.size() == 97);
  CHECK(sim.insertion_status(ins).blocked_steps == 0);
  CHECK(sim.insertion_status(ins).warnings == 0);
  CHECK_FALSE(sim.insertion_status(ins).finished);
  // the mass is the sum of the particles'
  double m = 0.0;
  for (double mi : sim.particles().mass)
    m += mi;
  CHECK(sim.insertion_status(ins).mass == doctest::Approx(m).epsilon(1e-12));
}

TEST_CASE("insertion: a face in 2D, the end time and the total count stop it") {
  // disks of radius 1 mm enter through a segment 0.1 m long at 0.5 m/s downwards
  Sim2 sim(params<Sim2>(Vec2(0, -g0)));
  const auto k = sim.add_material(soft());
  const Vec2 v(0.0, -0.5);
  const double rate = 1500.0;
  const auto a = sim.add_insertion({.name = "slot",
                                    .region = insertion::SegmentFace{{0, 0.2}, {0.1, 0.2}},
                                    .size = generate::Uniform{0.8e-3, 1.2e-3},
                                    .material = k,
                                    .number_rate = rate,
                                    .velocity = v,
                                    .t_end = 0.02,
                                    .group = "a",
                                    .seed = 3});
  const auto b = sim.add_insertion({.name = "limited",
                                    .region = regions::Box<2>{{0.3, 0.0}, {0.4, 0.1}},
                                    .size = generate::Constant{1e-3},
                                    .material = k,
                                    .number_rate = rate,
                                    .total_count = 25,
                                    .velocity = v,
                                    .group = "b",
                                    .seed = 4});
  std::set<std::int64_t> seen;
  std::size_t overlaps = 0, wrong_a = 0, wrong_b = 0, miscount = 0;
  for (int n = 0; n < 4000; ++n) {
    sim.step();
    // the new particles of each group: the other group's members count as seen
    std::set<std::int64_t> seen_a = seen, seen_b = seen;
    for (auto id : sim.group("b").ids)
      seen_a.insert(id);
    for (auto id : sim.group("a").ids)
      seen_b.insert(id);
    check_new(sim, seen_a, v, "a", overlaps, wrong_a);
    check_new(sim, seen_b, v, "b", overlaps, wrong_b);
    seen = seen_a;
    const double t = sim.time();
    miscount += sim.insertion_status(a).inserted != due_count(rate, std::min(t, 0.02), 0.0);
    miscount +=
        sim.insertion_status(b).inserted != std::min<std::uint64_t>(25, due_count(rate, t, 0));
  }
  CHECK(miscount == 0);
  CHECK(overlaps == 0);
  CHECK(wrong_a == 0);
  CHECK(wrong_b == 0);
  CHECK(sim.insertion_status(a).inserted == 30); // floor(1500 x 0.02)
  CHECK(sim.insertion_status(a).finished);
  CHECK(sim.insertion_status(b).inserted == 25);
  CHECK(sim.insertion_status(b).finished);
  CHECK(sim.group("a").ids.size() == 30);
  CHECK(sim.group("b").ids.size() == 25);
  CHECK(sim.size() == 55);
  // on the face: the centres of group a started on the segment, at least r from its ends, and
  // fell straight down (x unchanged)
  for (auto i : sim.group_indices("a")) {
    const auto& p = sim.particles();
    CHECK(p.position[i].x() >= p.radius[i]);
    CHECK(p.position[i].x() <= 0.1 - p.radius[i]);
  }
}

TEST_CASE("insertion: a mass rate follows rate t within one particle's mass") {
  Sim3 sim(params<Sim3>(Vec3(0, 0, -g0)));
  const auto k = sim.add_material(soft());
  const double rate = 0.05; // [kg/s]
  const double r_max = 2.5e-3,
               m_max = 2500 * 4.0 / 3.0 * std::numbers::pi * r_max * r_max * r_max; // [kg]
  const Vec3 v(0, 0, -1);
  const auto ins = sim.add_insertion({.name = "mass",
                                      .region = generate::Cylinder{{0, 0, 0.5}, {0, 0, 0.6}, 0.05},
                                      .size = generate::Uniform{1.5e-3, r_max},
                                      .material = k,
                                      .mass_rate = rate,
                                      .velocity = v,
                                      .group = "m",
                                      .seed = 11});
  std::set<std::int64_t> seen;
  std::size_t overlaps = 0, wrong = 0, off = 0;
  double worst_lag = 0.0;
  for (int n = 0; n < 5000; ++n) {
    sim.step();
    check_new(sim, seen, v, "m", overlaps, wrong);
    const double target = rate * sim.time();
    const double m = sim.insertion_status(ins).mass;
    double sum = 0.0;
    for (double mi : sim.particles().mass)
      sum += mi;
    worst_lag = std::max(worst_lag, target - m);
    off += !(m <= target * (1 + 1e-12)) || !(target - m < m_max) ||
           std::abs(sum - m) > 1e-12 * std::max(m, 1e-30);
  }
  CHECK(off == 0);
  CHECK(worst_lag > 0.0);
  CHECK(worst_lag < m_max);
  CHECK(overlaps == 0);
  CHECK(wrong == 0);
  CHECK(sim.insertion_status(ins).blocked_steps == 0);
  // about rate t / mean mass particles (mean of r^3 over U[1.5, 2.5] mm)
  const double mean_r3 = (std::pow(2.5e-3, 4) - std::pow(1.5e-3, 4)) / (4 * 1e-3);
  const double expected = rate * 0.05 / (2500 * 4.0 / 3.0 * std::numbers::pi * mean_r3);
  CHECK(double(sim.size()) == doctest::Approx(expected).epsilon(0.25));
}

TEST_CASE("insertion: a total mass, a disk face and a velocity spread") {
  Sim3 sim(params<Sim3>(Vec3(0, 0, -g0)));
  const auto k = sim.add_material(soft());
  const double m1 = 2500 * 4.0 / 3.0 * std::numbers::pi * 8e-9; // one sphere of radius 2 mm [kg]
  const Vec3 v(0, 0, -1);
  const auto ins = sim.add_insertion({.region = insertion::DiskFace{{0, 0, 0.5}, {0, 0, 1}, 0.05},
                                      .size = generate::Constant{2e-3},
                                      .material = k,
                                      .mass_rate = 100 * m1, // 100 spheres per second
                                      .total_mass = 10.5 * m1,
                                      .velocity = v,
                                      .velocity_spread = 0.1,
                                      .seed = 5});
  sim.run(0.2);
  const auto& st = sim.insertion_status(ins);
  CHECK(st.inserted == 10); // the 11th would exceed the total mass
  CHECK(st.finished);
  CHECK(st.mass == doctest::Approx(10 * m1).epsilon(1e-12));
  // every velocity within the spread of the one given, and not all equal to it
  std::size_t outside = 0, equal = 0;
  for (const auto& u : sim.particles().velocity) {
    // premise: after 0.2 s of free fall the z component gained -g t_i (t_i <= 0.2 s)
    outside += std::abs(u.x() - v.x()) > 0.1 || std::abs(u.y() - v.y()) > 0.1;
    equal += u.x() == v.x() && u.y() == v.y();
  }
  CHECK(outside == 0);
  CHECK(equal == 0);
}

TEST_CASE("insertion: a blocked region reports the shortfall and resumes when it clears") {
  // no gravity: particles placed at rest stay where they are and fill the box (random
  // sequential addition jams); then gravity pulls them out and insertion resumes
  Sim3 sim(params<Sim3>(Vec3(0, 0, 0)));
  const auto k = sim.add_material(soft());
  std::vector<std::string> warnings;
  const auto saved = warning_handler();
  warning_handler() = [&](const std::string& m) { warnings.push_back(m); };
  const double rate = 400.0;
  const auto ins = sim.add_insertion({.name = "hopper",
                                      .region = regions::Box<3>{{0, 0, 0}, {0.014, 0.014, 0.014}},
                                      .size = generate::Constant{3e-3},
                                      .material = k,
                                      .number_rate = rate,
                                      .group = "h",
                                      .seed = 9});
  sim.run(0.1);
  const auto full = sim.insertion_status(ins).inserted;
  CHECK(full > 0);
  CHECK(full < due_count(rate, sim.time(), 0.0)); // premise: the box is full
  const auto blocked = sim.insertion_status(ins).blocked_steps;
  CHECK(blocked > 0);
  sim.run(0.05); // blocked: nothing more, the shortfall grows with the rate
  const auto& st = sim.insertion_status(ins);
  CHECK(st.inserted == full);
  CHECK(st.due == due_count(rate, sim.time(), 0.0));
  CHECK(st.shortfall == st.due - full);
  CHECK(st.blocked_steps == blocked + 5000); // every step of the 0.05 s
  CHECK(st.warnings == 1);                   // the jam lasted more than warn_after = 1000 steps
  REQUIRE(warnings.size() == 1);
  CHECK(has(warnings[0], {"Simulation::add_insertion 'hopper'", "blocked", "carried over"}));
  // no particle overlaps another (the box holds particles at rest, exactly touching at most)
  const auto& p = sim.particles();
  std::size_t overlaps = 0;
  for (std::size_t i = 0; i < p.size(); ++i)
    for (std::size_t j = i + 1; j < p.size(); ++j) {
      const double s = p.radius[i] + p.radius[j];
      overlaps += (p.position[i] - p.position[j]).squaredNorm() < s * s;
    }
  CHECK(overlaps == 0);
  // the box clears under gravity: insertion resumes, the carried-over particles come
  sim.set_gravity(Vec3(0, 0, -g0));
  sim.run(0.3);
  CHECK(sim.insertion_status(ins).inserted > full + 20);
  CHECK(sim.insertion_status(ins).due == due_count(rate, sim.time(), 0.0));
  warning_handler() = saved;
}

TEST_CASE("insertion: an empty simulation takes its time step from the insertion's sizes") {
  typename Sim3::Params prm;
  prm.gravity = Vec3(0, 0, -g0);
  prm.auto_time_step_factor = 0.2;
  Sim3 sim(prm);
  const auto k = sim.add_material(soft());
  sim.add_insertion({.region = regions::Box<3>{{0, 0, 0}, {0.1, 0.1, 0.1}},
                     .size = generate::Uniform{1e-3, 3e-3},
                     .material = k,
                     .number_rate = 100});
  sim.initialize();
  // the Rayleigh time of the smallest radius, pi R sqrt(rho / G) / (0.1631 nu + 0.8766)
  const Material m = soft();
  const double rayleigh = std::numbers::pi * 1e-3 * std::sqrt(m.density / m.shear_modulus()) /
                          (0.1631 * m.poisson + 0.8766);
  CHECK(sim.rayleigh_time() == doctest::Approx(rayleigh).epsilon(1e-12));
  CHECK(sim.time_step() <= 0.2 * rayleigh * (1 + 1e-12));
  CHECK(sim.time_step() > 0.0);
  sim.run(0.05);
  CHECK(sim.size() == 5); // floor(100 x 0.05)
}

namespace {

Sim3 make_pour(double interval) {
  Sim3 sim(params<Sim3>(Vec3(0, 0, -g0), 2e-5));
  const auto k = sim.add_material(soft());
  sim.add_wall(walls::Plane{{0, 0, 0}, {0, 0, 1}}, {.material = k});
  sim.add_insertion({.name = "pour",
                     .region = regions::Box<3>{{0, 0, 0.01}, {0.03, 0.03, 0.04}},
                     .size = generate::Uniform{1.5e-3, 2.5e-3},
                     .material = k,
                     .number_rate = 3000,
                     .velocity = Vec3(0, 0, -0.3),
                     .velocity_spread = 0.05,
                     .group = "poured",
                     .seed = 21,
                     .interval = interval});
  sim.prescribe_force("poured", VectorTimeFunction<3>(Vec3(1e-4, 0, 0)));
  return sim;
}

} // namespace

TEST_CASE("insertion: a checkpoint mid-insertion continues bit-identically") {
  const auto dir = std::filesystem::temp_directory_path() / "grain_insertion_test";
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "pour.ckpt").string();
  for (const double interval : {0.0, 3e-4}) { // every step; batches every 15 steps
    CAPTURE(interval);
    Sim3 whole = make_pour(interval);
    whole.run(0.12);
    Sim3 first = make_pour(interval);
    first.run(0.06);
    REQUIRE(first.insertion_status(0).inserted > 50);
    io::save_checkpoint(first, path);
    Sim3 resumed = make_pour(interval);
    io::load_checkpoint(resumed, path);
    CHECK(resumed.group("poured").ids == first.group("poured").ids);
    resumed.run(0.06);
    REQUIRE(resumed.size() == whole.size());
    CHECK(resumed.step_count() == whole.step_count());
    const auto& p = whole.particles();
    const auto& q = resumed.particles();
    std::size_t differ = 0;
    for (std::size_t i = 0; i < p.size(); ++i)
      differ += p.id[i] != q.id[i] || p.position[i] != q.position[i] ||
                p.velocity[i] != q.velocity[i] || p.omega[i] != q.omega[i] ||
                p.radius[i] != q.radius[i];
    CHECK(differ == 0);
    const auto &a = whole.insertion_status(0), &b = resumed.insertion_status(0);
    CHECK(a.inserted == b.inserted);
    CHECK(a.mass == b.mass);
    CHECK(a.attempts == b.attempts);
    CHECK(a.blocked_steps == b.blocked_steps);
    CHECK(whole.group("poured").ids == resumed.group("poured").ids);
    CHECK(a.inserted > first.insertion_status(0).inserted);
  }

  // a simulation without the insertion does not take the file
  Sim3 other(params<Sim3>(Vec3(0, 0, -g0), 2e-5));
  const auto k = other.add_material(soft());
  other.add_wall(walls::Plane{{0, 0, 0}, {0, 0, 1}}, {.material = k});
  CHECK(has(error_of([&] { io::load_checkpoint(other, path); }),
            {"insertions = 1 is invalid", "valid: 0"}));
  std::filesystem::remove_all(dir);
}

TEST_CASE("insertion: batches every interval") {
  // 2000 spheres/s in batches every 1 ms (100 steps): particles appear only at the first step of
  // each interval, in the number the rate gives then
  const double rate = 2000.0, interval = 1e-3;
  auto make = [&](double every) {
    Sim3 sim(params<Sim3>(Vec3(0, 0, -g0)));
    const auto k = sim.add_material(soft());
    sim.add_insertion({.region = regions::Box<3>{{0, 0, 0.5}, {0.1, 0.1, 0.6}},
                       .size = generate::Constant{2e-3},
                       .material = k,
                       .number_rate = rate,
                       .velocity = Vec3(0, 0, -1),
                       .seed = 7,
                       .interval = every});
    return sim;
  };
  Sim3 sim = make(interval);
  std::size_t wrong = 0, batches = 0;
  std::uint64_t tick = 0;
  for (int n = 0; n < 5000; ++n) {
    const std::size_t before = sim.size();
    sim.step();
    const double t = sim.time();
    const auto q = static_cast<std::uint64_t>(std::floor(t / interval + 1e-9));
    if (q > tick) { // a batch: the count the rate gives at t
      tick = q;
      ++batches;
      wrong += sim.size() != due_count(rate, t, 0.0);
    } else {
      wrong += sim.size() != before; // nothing between batches
    }
  }
  CHECK(batches == 50);
  CHECK(wrong == 0);
  CHECK(sim.size() == 100); // floor(2000 x 0.05)
  // insertion at every step gives the same count at the end
  Sim3 each = make(0.0);
  each.run(0.05);
  CHECK(each.size() == 100);
}

TEST_CASE("insertion: bad parameters are refused by name") {
  Sim3 sim(params<Sim3>(Vec3(0, 0, -g0)));
  const auto k = sim.add_material(soft());
  const auto good = [&] {
    return Insertion<3>{.name = "feed",
                        .region = regions::Box<3>{{0, 0, 0}, {0.1, 0.1, 0.1}},
                        .size = generate::Constant{1e-3},
                        .material = k,
                        .number_rate = 100};
  };
  const std::string obj = "Simulation::add_insertion 'feed'";
  auto error = [&](auto change) {
    auto ins = good();
    change(ins);
    return error_of([&] { sim.add_insertion(ins); });
  };
  CHECK(has(error([](auto& i) { i.number_rate = 0; }),
            {obj.c_str(), "number_rate = 0", "mass_rate = 0", "one rate in (0, inf)"}));
  CHECK(has(error([](auto& i) { i.mass_rate = 1; }), {obj.c_str(), "valid: one rate"}));
  CHECK(has(error([](auto& i) { i.number_rate = -5; }),
            {obj.c_str(), "number_rate = -5 is invalid; valid range: (0, inf)"}));
  CHECK(has(error([](auto& i) { i.total_mass = -1; }), {obj.c_str(), "total_mass = -1"}));
  CHECK(has(error([](auto& i) { i.material = 3; }), {obj.c_str(), "material = 3", "[0, 1)"}));
  CHECK(has(error([](auto& i) { i.size = generate::Constant{-1e-3}; }),
            {obj.c_str(), "generate::Constant", "radius = -0.001"}));
  CHECK(has(error([](auto& i) { i.size = generate::Constant{0.06}; }),
            {obj.c_str(), "(Box)", "smallest side = 0.1", "[0.12, inf) m"}));
  CHECK(has(error([](auto& i) {
              i.region = regions::Box<3>{{0, 0, 0}, {0.1, -0.1, 0.1}};
            }),
            {obj.c_str(), "(Box)", "hi component = -0.1"}));
  CHECK(has(error([](auto& i) { i.t_end = 0; }),
            {obj.c_str(), "t_end = 0", "(t_begin, inf] = (0, inf] s"}));
  CHECK(has(error([](auto& i) { i.t_begin = -1; }),
            {obj.c_str(), "t_begin = -1", "[current time, inf) = [0, inf) s"}));
  CHECK(has(error([](auto& i) { i.velocity_spread = -0.1; }),
            {obj.c_str(), "velocity_spread = -0.1"}));
  CHECK(has(error([](auto& i) { i.max_attempts = 0; }), {obj.c_str(), "max_attempts = 0"}));
  CHECK(has(error([](auto& i) { i.warn_after = 0; }), {obj.c_str(), "warn_after = 0"}));
  CHECK(has(error([](auto& i) { i.interval = -1e-3; }), {obj.c_str(), "interval = -0.001"}));
  CHECK(has(error([](auto& i) { i.temperature = 300; }),
            {obj.c_str(), "temperature = 300", "no conduction model"}));
  CHECK(has(error([](auto& i) {
              i.region = insertion::RectangleFace{{0, 0, 0}, {0.1, 0, 0}, {0.05, 0.1, 0}};
              i.velocity = Vec3(0, 0, -1);
            }),
            {obj.c_str(), "(RectangleFace)", "cosine of the angle between edge1 and edge2"}));
  CHECK(has(error([](auto& i) {
              i.region = insertion::DiskFace{{0, 0, 0}, {0, 0, 1}, 0.1};
              i.velocity = Vec3(1, 0, 0);
            }),
            {obj.c_str(), "(DiskFace)", "velocity component normal to the face = 0",
             "particles must leave the face"}));
  CHECK(has(error([](auto& i) {
              i.region = generate::Cylinder{{0, 0, 0}, {0, 0, 0.1}, 0.0005};
            }),
            {obj.c_str(), "(Cylinder)", "radius = 0.0005", "[0.001, inf) m"}));
  CHECK(sim.insertion_count() == 0); // nothing refused was added
  CHECK(has(error_of([&] { (void)sim.insertion_status(0); }),
            {"Simulation::insertion_status", "insertion = 0 is invalid"}));
  CHECK(sim.add_insertion(good()) == 0);
}

TEST_CASE("insertion: temperatures of a thermal simulation") {
  using Contact =
      Interaction<normal::Hertz<>, tangent::Mindlin, rolling::None, conduction::BatchelorOBrien>;
  using SimT = Simulation<Sphere, search::CellList, Contact>;
  typename SimT::Params prm;
  prm.time_step = dt;
  prm.gravity = Vec3(0, 0, -g0);
  prm.initial_temperature = 290.0;
  SimT sim(prm);
  Material m = soft();
  m.conductivity = 1.0;
  m.heat_capacity = 800.0;
  const auto k = sim.add_material(m);
  const auto base = Insertion<3>{.region = regions::Box<3>{{0, 0, 0.5}, {0.1, 0.1, 0.6}},
                                 .size = generate::Constant{2e-3},
                                 .material = k,
                                 .number_rate = 1000,
                                 .velocity = Vec3(0, 0, -1)};
  auto hot = base;
  hot.group = "hot";
  hot.temperature = 350.0;
  auto plain = base;
  plain.region = regions::Box<3>{{0.2, 0, 0.5}, {0.3, 0.1, 0.6}};
  plain.group = "plain";
  sim.add_insertion(hot);
  sim.add_insertion(plain);
  sim.run(0.01);
  REQUIRE(sim.group_indices("hot").size() == 10);
  REQUIRE(sim.group_indices("plain").size() == 10);
  // free flight, no contact: the temperatures are those given when the particles appeared
  for (auto i : sim.group_indices("hot"))
    CHECK(sim.particles().temperature[i] == 350.0);
  for (auto i : sim.group_indices("plain"))
    CHECK(sim.particles().temperature[i] == 290.0);
  // a material without heat capacity is refused for heated particles
  Material cold = soft();
  cold.name = "cold";
  const auto kc = sim.add_material(cold);
  auto bad = base;
  bad.material = kc;
  CHECK(has(error_of([&] { sim.add_insertion(bad); }),
            {"Simulation::add_insertion 2 (material 'cold')", "heat_capacity = 0"}));
}

namespace {

/// Runs `steps` steps of `sim` and checks each particle at the step it appears with
/// `where(x, r)` (true if it is where the insertion puts it); returns the number checked and adds
/// the misplaced ones to `bad`.
template <class Sim, class Where>
std::size_t check_places(Sim& sim, int steps, Where where, std::size_t& bad) {
  std::set<std::int64_t> seen;
  std::size_t checked = 0;
  for (int n = 0; n < steps; ++n) {
    sim.step();
    const auto& p = sim.particles();
    for (std::size_t i = 0; i < p.size(); ++i)
      if (seen.insert(p.id[i]).second) {
        ++checked;
        bad += !where(p.position[i], p.radius[i]);
      }
  }
  return checked;
}

} // namespace

TEST_CASE("insertion: every region and face puts the centres where it says") {
  // 20 particles per step (2e6 / s at dt = 1e-5 s) for 20 steps, no gravity: the centres are
  // those placed. Volumes: wholly inside (generate's `fits`, |x - c| <= R - r for a ball);
  // faces: on the plane (1e-12 m) and at least r from the edge.
  const Material m = soft();
  std::size_t bad = 0;
  SUBCASE("ball (3D)") {
    Sim3 sim(params<Sim3>(Vec3::Zero()));
    const auto k = sim.add_material(m);
    const regions::Ball<3> ball{{0.1, -0.2, 0.3}, 0.05};
    sim.add_insertion(
        {.region = ball, .size = generate::Uniform{1e-3, 2e-3}, .material = k, .number_rate = 2e6});
    CHECK(check_places(
              sim, 20,
              [&](const Vec3& x, double r) {
                return (x - ball.center).norm() <= ball.radius - r + 1e-15;
              },
              bad) == 400);
  }
  SUBCASE("cylinder along a slanted axis (3D)") {
    Sim3 sim(params<Sim3>(Vec3::Zero()));
    const auto k = sim.add_material(m);
    const generate::Cylinder cyl{{0, 0, 0}, {0.05, 0.02, 0.1}, 0.03};
    sim.add_insertion(
        {.region = cyl, .size = generate::Constant{1.5e-3}, .material = k, .number_rate = 2e6});
    CHECK(check_places(
              sim, 20, [&](const Vec3& x, double r) { return generate::detail::fits(cyl, x, r); },
              bad) == 400);
  }
  SUBCASE("rectangle face (3D)") {
    Sim3 sim(params<Sim3>(Vec3::Zero()));
    const auto k = sim.add_material(m);
    const insertion::RectangleFace f{{0, 0, 0.2}, {0.1, 0.1, 0}, {-0.05, 0.05, 0.0}};
    sim.add_insertion({.region = f,
                       .size = generate::Constant{1e-3},
                       .material = k,
                       .number_rate = 2e6,
                       .velocity = Vec3(0, 0, -1)});
    const Vec3 u1 = f.edge1.normalized(), u2 = f.edge2.normalized();
    CHECK(check_places(
              sim, 20,
              [&](const Vec3& x, double r) {
                const Vec3 w = x - f.corner;
                const double s1 = w.dot(u1), s2 = w.dot(u2);
                return std::abs(x.z() - 0.2) <= 1e-12 && s1 >= r - 1e-12 &&
                       s1 <= f.edge1.norm() - r + 1e-12 && s2 >= r - 1e-12 &&
                       s2 <= f.edge2.norm() - r + 1e-12;
              },
              bad) == 400);
  }
  SUBCASE("disk face (3D)") {
    Sim3 sim(params<Sim3>(Vec3::Zero()));
    const auto k = sim.add_material(m);
    const insertion::DiskFace f{{0.1, 0.1, 0.1}, {1, 1, 1}, 0.05};
    sim.add_insertion({.region = f,
                       .size = generate::Constant{1e-3},
                       .material = k,
                       .number_rate = 2e6,
                       .velocity = Vec3(1, 1, 1)});
    const Vec3 n = f.normal.normalized();
    CHECK(check_places(
              sim, 20,
              [&](const Vec3& x, double r) {
                const Vec3 w = x - f.center;
                return std::abs(w.dot(n)) <= 1e-12 && w.norm() <= f.radius - r + 1e-12;
              },
              bad) == 400);
  }
  SUBCASE("polygon (2D)") {
    Sim2 sim(params<Sim2>(Vec2::Zero()));
    const auto k = sim.add_material(m);
    const regions::Polygon poly{{{0, 0}, {0.1, 0}, {0.1, 0.1}, {0.05, 0.03}, {0, 0.1}}};
    sim.add_insertion(
        {.region = poly, .size = generate::Constant{1e-3}, .material = k, .number_rate = 2e6});
    CHECK(check_places(
              sim, 20, [&](const Vec2& x, double r) { return generate::detail::fits(poly, x, r); },
              bad) == 400);
  }
  SUBCASE("ball (2D)") {
    Sim2 sim(params<Sim2>(Vec2::Zero()));
    const auto k = sim.add_material(m);
    const regions::Ball<2> ball{{0.3, 0.1}, 0.04};
    sim.add_insertion(
        {.region = ball, .size = generate::Constant{1e-3}, .material = k, .number_rate = 2e6});
    CHECK(check_places(
              sim, 20,
              [&](const Vec2& x, double r) {
                return (x - ball.center).norm() <= ball.radius - r + 1e-15;
              },
              bad) == 400);
  }
  CHECK(bad == 0);
}

TEST_CASE("insertion: two insertions with the same seed draw different particles") {
  // Two insertions of one region, both with the default seed and uniform radii: their streams
  // differ (each insertion's place among them is mixed into its seed), so the second never puts
  // its candidates where the first put its particles. 220 steps at 2000/s each: 2 x 4
  // particles (t = 0.0022 s), none overlapping, and the two sets of radii differ.
  Sim3 sim(params<Sim3>(Vec3(0, 0, -g0)));
  const auto k = sim.add_material(soft());
  auto spec = [&](const char* name) {
    return Insertion<3>{.name = name,
                        .region = regions::Box<3>{{0, 0, 0.5}, {0.1, 0.1, 0.6}},
                        .size = generate::Uniform{1e-3, 2e-3},
                        .material = k,
                        .number_rate = 2000.0,
                        .velocity = Vec3(0, 0, -1),
                        .group = name};
  };
  const auto a = sim.add_insertion(spec("a"));
  const auto b = sim.add_insertion(spec("b"));
  std::set<std::int64_t> seen;
  std::size_t overlaps = 0, wrong = 0;
  for (int n = 0; n < 220; ++n) {
    sim.step();
    check_new(sim, seen, Vec3(0, 0, -1), "a", overlaps, wrong); // (`wrong` counts b's too)
  }
  CHECK(sim.insertion_status(a).inserted == 4);
  CHECK(sim.insertion_status(b).inserted == 4);
  CHECK(sim.insertion_status(b).blocked_steps == 0);
  CHECK(overlaps == 0);
  std::vector<double> ra, rb;
  const auto& p = sim.particles();
  const auto& in_a = sim.group("a").ids;
  for (std::size_t i = 0; i < p.size(); ++i)
    (std::binary_search(in_a.begin(), in_a.end(), p.id[i]) ? ra : rb).push_back(p.radius[i]);
  std::sort(ra.begin(), ra.end());
  std::sort(rb.begin(), rb.end());
  CHECK(ra.size() == 4);
  CHECK(ra != rb);
}
