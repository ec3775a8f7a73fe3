// The solution loop: free flight, determinism across thread counts, walls that move.
#include "../approx.hpp"
#include <cstring>
#include <doctest/doctest.h>
#include <grain/grain.hpp>
#include <limits>
#include <random>
#ifdef _OPENMP
#include <omp.h>
#endif

using namespace grain;

namespace {
using Contact3 = Interaction<normal::Hertz<>, tangent::SpringDashpotSlider>;
using Contact2 = Interaction<normal::LinearSpringDashpot, tangent::SpringDashpotSlider>;
using Contact3Heat = Interaction<normal::Hertz<>, tangent::SpringDashpotSlider, rolling::None,
                                 conduction::BatchelorOBrien>;
const Material soft{.density = 2500,
                    .young = 1e7,
                    .poisson = 0.3,
                    .restitution = 0.5,
                    .friction = 0.5,
                    .conductivity = 1.0,
                    .heat_capacity = 840.0};

template <class Sim>
void settle_box(Sim& sim, int n, unsigned seed) {
  constexpr int D = Sim::dimension;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  auto m = sim.add_material(soft);
  const double L = D == 2 ? 0.04 : 0.012;
  for (int k = 0; k < n; ++k) {
    Vec<D> x, v;
    for (int d = 0; d < D; ++d) {
      x[d] = L * (0.05 + 0.9 * u(rng));
      v[d] = 0.1 * (2 * u(rng) - 1);
    }
    const double r = 4e-4 + 2e-4 * u(rng);
    if constexpr (Sim::thermal)
      sim.add_particle({.position = x,
                        .radius = r,
                        .material = m,
                        .velocity = v,
                        .temperature = 300.0 + 100.0 * u(rng)});
    else
      sim.add_particle({.position = x, .radius = r, .material = m, .velocity = v});
  }
  if constexpr (D == 2) {
    sim.add_wall(walls::Segment{Vec2(0, 0), Vec2(L, 0)}, {.material = m});
    sim.add_wall(walls::Segment{Vec2(0, 0), Vec2(0, L)}, {.material = m});
    sim.add_wall(walls::Segment{Vec2(L, 0), Vec2(L, L)}, {.material = m});
  } else {
    for (int d = 0; d < 3; ++d) {
      sim.add_wall(walls::Plane{Vec3::Zero(), Vec3::Unit(d)}, {.material = m});
      sim.add_wall(walls::Plane{Vec3::Constant(L), -Vec3::Unit(d)}, {.material = m});
    }
  }
}

template <class Sim>
std::vector<double> state_bits(const Sim& sim) {
  std::vector<double> out;
  const auto& p = sim.particles();
  for (std::size_t i = 0; i < p.size(); ++i) {
    out.push_back(static_cast<double>(p.id[i]));
    for (int d = 0; d < Sim::dimension; ++d) {
      out.push_back(p.position[i][d]);
      out.push_back(p.velocity[i][d]);
      out.push_back(p.force[i][d]);
    }
    if constexpr (Sim::dimension == 2)
      out.push_back(p.omega[i]);
    else
      for (int d = 0; d < 3; ++d)
        out.push_back(p.omega[i][d]);
    if constexpr (Sim::thermal) {
      out.push_back(p.temperature[i]);
      out.push_back(p.heat_rate[i]);
    }
  }
  return out;
}
} // namespace

TEST_CASE("run(duration): the number of steps is the quotient rounded up, rounding forgiven") {
  // 16.78 / 1e-6 is 16780000.000000002 in floating point: a fixed tolerance of 1e-9 steps gave
  // one step more than asked for above about 2^23 steps
  CHECK(detail::steps_for(16.78, 1e-6) == 16780000);
  CHECK(detail::steps_for(12.3, 5e-7) == 24600000);
  CHECK(detail::steps_for(0.3, 0.1) == 3); // 2.9999999999999996
  CHECK(detail::steps_for(1.0, 0.3) == 4);
  CHECK(detail::steps_for(0.9, 0.3) == 3);
  CHECK(detail::steps_for(1e-3, 1e-4) == 10);
  CHECK(detail::steps_for(1.0000001, 0.1) == 11); // a real excess is a step more
  CHECK(detail::steps_for(0.0, 0.1) == 0);
}

TEST_CASE("free flight under gravity is exact with velocity Verlet") {
  Simulation<Sphere, search::CellList, Contact3> sim(
      {.time_step = 1e-5, .gravity = Vec3(0, 0, -9.81)});
  auto m = sim.add_material(soft);
  sim.add_particle(
      {.position = Vec3(0, 0, 1), .radius = 1e-3, .material = m, .velocity = Vec3(1, 0, 2)});
  sim.steps(10000);
  const double t = sim.time();
  CHECK(t == grain::test::approx(0.1));
  const auto& p = sim.particles();
  CHECK(p.position[0].z() == grain::test::approx(1 + 2 * t - 0.5 * 9.81 * t * t).epsilon(1e-10));
  CHECK(p.position[0].x() == grain::test::approx(t).epsilon(1e-12));
  CHECK(p.velocity[0].z() == grain::test::approx(2 - 9.81 * t).epsilon(1e-10));
}

TEST_CASE("global damping decays the velocity exponentially") {
  // m dv/dt = -c v  ->  v = v0 exp(-c t/m)
  Simulation<Disk, search::AllPairs, Contact2, integrate::VelocityVerlet> sim(
      {.time_step = 1e-5, .damping_translational = 1e-4, .damping_rotational = 1e-9});
  auto m = sim.add_material(soft);
  sim.add_particle({.position = Vec2::Zero(),
                    .radius = 1e-3,
                    .material = m,
                    .velocity = Vec2(1, 0),
                    .omega = 10.0});
  sim.steps(1000);
  const auto& p = sim.particles();
  CHECK(p.velocity[0].x() ==
        grain::test::approx(std::exp(-1e-4 * sim.time() / p.mass[0])).epsilon(1e-6));
  CHECK(p.omega[0] ==
        grain::test::approx(10.0 * std::exp(-1e-9 * sim.time() / p.inertia[0])).epsilon(1e-6));
}

// A run of n steps without observers leaves the second half kick of each step but the last (and
// with conduction, the temperature update) to the next step's first pass over the particles: the
// same arithmetic, so the state must equal n single steps bit for bit; so must the state after
// an exception inside the run (here a damping that turns negative at t = 2.11e-4 s, which step
// 106 evaluates at its end, 2.12e-4 s).
template <class Integrator, class Contact = Contact3>
void check_runs_equal_single_steps() {
  using Sim = Simulation<Sphere, search::CellList, Contact, Integrator>;
  auto make = [] {
    Sim sim({.time_step = 2e-6,
             .gravity = Vec3(0, 0, -9.81),
             .max_start_overlap = std::numeric_limits<double>::infinity()}); // random, soft
    settle_box(sim, 500, 5);
    return sim;
  };
  Sim a = make(), b = make();
  a.steps(150);
  for (int k = 0; k < 150; ++k)
    b.step();
  CHECK(a.step_count() == 150);
  auto sa = state_bits(a), sb = state_bits(b);
  REQUIRE(sa.size() == sb.size());
  CHECK(std::memcmp(sa.data(), sb.data(), sa.size() * sizeof(double)) == 0);
  Sim c = make(), d = make();
  for (Sim* s : {&c, &d})
    s->set_damping(TimeFunction::linear(1e-7, -1e-7 / 2.11e-4));
  CHECK_THROWS_AS(c.steps(400), InputError);
  long k = 0;
  try {
    for (; k < 400; ++k)
      d.step();
  } catch (const InputError&) {
  }
  CHECK(k == 105);
  CHECK(c.step_count() == d.step_count());
  sa = state_bits(c);
  sb = state_bits(d);
  REQUIRE(sa.size() == sb.size());
  CHECK(std::memcmp(sa.data(), sb.data(), sa.size() * sizeof(double)) == 0);
}

TEST_CASE("a run of n steps equals n single steps bit for bit") {
  check_runs_equal_single_steps<integrate::VelocityVerlet>();
  check_runs_equal_single_steps<integrate::VelocityVerletHalfStep>();
  check_runs_equal_single_steps<integrate::VelocityVerletHalfStep, Contact3Heat>();
}

#ifdef _OPENMP
TEST_CASE("results are bit-identical with 1, 2 and 3 threads") {
  auto run3 = [](int threads) {
    omp_set_num_threads(threads);
    Simulation<Sphere, search::CellList, Contact3> sim(
        {.time_step = 2e-6,
         .gravity = Vec3(0, 0, -9.81),
         .max_start_overlap = std::numeric_limits<double>::infinity()}); // random, soft
    settle_box(sim, 1200, 3);
    sim.steps(300);
    return state_bits(sim);
  };
  auto run2 = [](int threads) {
    omp_set_num_threads(threads);
    Simulation<Disk, search::CellList, Contact2> sim(
        {.time_step = 2e-6,
         .gravity = Vec2(0, -9.81),
         .max_start_overlap = std::numeric_limits<double>::infinity()}); // random, soft
    settle_box(sim, 1200, 4);
    sim.steps(300);
    return state_bits(sim);
  };
  // a block large enough in all three directions for a list span at which the contact loop
  // prefetches rows ahead (the cell order makes the span about two planes of cells across the
  // shorter directions)
  auto block = [](int threads) {
    omp_set_num_threads(threads);
    using Sim = Simulation<Sphere, search::CellList, Contact3>;
    Sim sim({.time_step = 2e-6,
             .gravity = Vec3(0, 0, -9.81),
             .max_start_overlap = std::numeric_limits<double>::infinity()}); // random, soft
    auto m = sim.add_material(soft);
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    const int w = 34;
    for (int x = 0; x < w; ++x)
      for (int y = 0; y < w; ++y)
        for (int z = 0; z < w; ++z)
          sim.add_particle({.position = Vec3(x, y, z) * 1.02e-3 + Vec3::Constant(6e-4),
                            .radius = 5e-4,
                            .material = m,
                            .velocity = 0.1 * Vec3(u(rng), u(rng), u(rng))});
    sim.add_wall(walls::Plane{Vec3::Zero(), Vec3::UnitZ()}, {.material = m});
    sim.steps(100);
    const double span_bytes = sim.neighbor_list().max_span * Sim::row_bytes;
    CHECK(span_bytes > Sim::prefetch_span_bytes);
    return state_bits(sim);
  };
  const int saved = omp_get_max_threads();
  // 3 threads: a thread's run of contact chunks may start with an odd chunk, which waits for
  // the previous thread's last one
  const auto a3 = run3(1), b3 = run3(2), c3 = run3(3);
  const auto a2 = run2(1), b2 = run2(2), c2 = run2(3);
  const auto al = block(1), bl = block(2);
  omp_set_num_threads(saved);
  REQUIRE(al.size() == bl.size());
  CHECK(std::memcmp(al.data(), bl.data(), al.size() * sizeof(double)) == 0);
  REQUIRE(a3.size() == b3.size());
  CHECK(std::memcmp(a3.data(), b3.data(), a3.size() * sizeof(double)) == 0);
  REQUIRE(a2.size() == b2.size());
  CHECK(std::memcmp(a2.data(), b2.data(), a2.size() * sizeof(double)) == 0);
  REQUIRE(a3.size() == c3.size());
  CHECK(std::memcmp(a3.data(), c3.data(), a3.size() * sizeof(double)) == 0);
  REQUIRE(a2.size() == c2.size());
  CHECK(std::memcmp(a2.data(), c2.data(), a2.size() * sizeof(double)) == 0);
}
#endif

TEST_CASE("a moving wall pushes a particle; a rotating drum drags it") {
  // a piston moving at constant speed towards a resting disk: after the contact the disk moves
  // away faster than the piston (elastic rebound from a moving wall: v = 2 V for e = 1)
  Simulation<Disk, search::CellList, Interaction<normal::LinearSpringDashpot>> sim(
      {.time_step = 1e-6, .contact = {.normal = {.stiffness = 1e3}}});
  auto m = sim.add_material({.density = 2500, .young = 1e7, .poisson = 0.3, .restitution = 1.0});
  sim.add_particle({.position = Vec2(0.01, 0), .radius = 1e-3, .material = m});
  sim.add_wall(walls::Segment{Vec2(0, -0.01), Vec2(0, 0.01)},
               {.material = m, .velocity = Vec2(0.1, 0)});
  sim.run(0.1);
  CHECK(sim.particles().velocity[0].x() == grain::test::approx(0.2).epsilon(1e-6));

  // a disk resting on the inside bottom of a rotating drum is accelerated along the surface
  Simulation<Disk, search::CellList, Contact2> drum(
      {.time_step = 1e-6, .gravity = Vec2(0, -9.81), .contact = {.normal = {.stiffness = 1e4}}});
  m = drum.add_material(soft);
  drum.add_particle({.position = Vec2(0, -0.05 + 1e-3), .radius = 1e-3, .material = m});
  drum.add_wall(walls::Circle{Vec2::Zero(), 0.05}, {.material = m, .omega = 1.0});
  drum.run(0.02);
  CHECK(drum.particles().velocity[0].x() > 1e-3);
}

TEST_CASE("a fixed particle keeps its velocity") {
  Simulation<Sphere, search::AllPairs, Contact3> sim(
      {.time_step = 1e-6, .gravity = Vec3(0, 0, -9.81)});
  auto m = sim.add_material(soft);
  sim.add_particle({.position = Vec3::Zero(),
                    .radius = 1e-3,
                    .material = m,
                    .velocity = Vec3(0, 0.1, 0),
                    .fixed = true});
  sim.add_particle({.position = Vec3(0, 0, 2.0005e-3), .radius = 1e-3, .material = m});
  sim.steps(2000);
  const auto i = sim.index_of(0);
  CHECK(sim.particles().velocity[i] == Vec3(0, 0.1, 0));
  CHECK(sim.particles().position[i].y() == grain::test::approx(0.1 * sim.time()).epsilon(1e-12));
}

TEST_CASE("each integrator's free-fall update is the scheme's closed form") {
  // x_n for constant acceleration g after n steps of dt, from the update rules:
  // forward Euler x += v dt, v += g dt        -> x0 + n v0 dt + g dt^2 n(n-1)/2
  // symplectic Euler v += g dt, x += v dt     -> x0 + n v0 dt + g dt^2 n(n+1)/2
  // Taylor 2 and velocity Verlet (exact)      -> x0 + v0 t + g t^2 / 2
  const double dt = 5e-5, g = -9.81, v0 = 0.3;
  const int n = 500;
  auto fall = [&](auto integrator) {
    using I = decltype(integrator);
    Simulation<Disk, search::AllPairs, Contact2, I> sim({.time_step = dt, .gravity = Vec2(0, g)});
    auto m = sim.add_material(soft);
    sim.add_particle(
        {.position = Vec2::Zero(), .radius = 1e-3, .material = m, .velocity = Vec2(0, v0)});
    sim.steps(n);
    return sim.particles().position[0].y();
  };
  const double t = n * dt;
  CHECK(fall(integrate::ForwardEuler{}) ==
        grain::test::approx(n * v0 * dt + g * dt * dt * n * (n - 1) / 2.0).epsilon(1e-11));
  CHECK(fall(integrate::SymplecticEuler{}) ==
        grain::test::approx(n * v0 * dt + g * dt * dt * n * (n + 1) / 2.0).epsilon(1e-11));
  CHECK(fall(integrate::Taylor2{}) == grain::test::approx(v0 * t + 0.5 * g * t * t).epsilon(1e-11));
  CHECK(fall(integrate::VelocityVerlet{}) ==
        grain::test::approx(v0 * t + 0.5 * g * t * t).epsilon(1e-11));
}

TEST_CASE("rotation: a spinning sphere's orientation turns by omega t") {
  Simulation<Sphere, search::AllPairs, Contact3> sim({.time_step = 5e-5});
  auto m = sim.add_material(soft);
  sim.add_particle(
      {.position = Vec3::Zero(), .radius = 1e-3, .material = m, .omega = Vec3(0, 0, 2.0)});
  sim.steps(2000);
  const Eigen::AngleAxisd aa(sim.particles().orientation[0]);
  CHECK(aa.angle() == grain::test::approx(0.2).epsilon(1e-10));
  CHECK(aa.axis().isApprox(Vec3::UnitZ()));
}

TEST_CASE("adding a particle during a run continues the time, with the new time step") {
  using Sim = grain::Simulation<grain::Sphere, grain::search::CellList,
                                grain::Interaction<grain::normal::Hertz<>>>;
  Sim sim;
  const auto m = sim.add_material({.name = "glass", .density = 2500, .young = 1e7});
  sim.add_particle({.position = {0, 0, 0}, .radius = 2e-3, .material = m});
  sim.steps(10);
  const double dt1 = sim.time_step(), t1 = sim.time();
  CHECK(t1 == grain::test::approx(10 * dt1).epsilon(1e-14));
  // a smaller particle lowers the automatic time step
  sim.add_particle({.position = {0.01, 0, 0}, .radius = 1e-3, .material = m});
  sim.steps(5);
  const double dt2 = sim.time_step();
  CHECK(dt2 < dt1);
  CHECK(sim.step_count() == 15);
  CHECK(sim.time() == grain::test::approx(t1 + 5 * dt2).epsilon(1e-14));
}
