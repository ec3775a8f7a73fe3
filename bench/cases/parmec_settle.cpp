// parmec_settle benchmark case: the problem of the Parmec deck bench/parmec/settle.py written in
// C++ with the same compiled model as grain-parmec (spheres with GRANULAR's law,
// presets::LinearCoulomb with a damping ratio, triangle obstacles, the coupling stage of Parmec's
// bodies): NX x NY x NZ spheres (radius 0.05 m, 1000 kg/m^3) on a lattice of spacing 0.11 m
// settle under gravity in an open box of 10 triangles; spring 1e5 N/m, damping ratio 0.2,
// friction 0.3, k_t / k_n = 0.5; step 0.2 of the contact critical step; VTK files at the start and
// the end of each run, as the deck writes them.
//
// Usage: case_parmec_settle [NX NY NZ NWARM NRUN]  (default 25 25 16 200 1000)
// Prints "particle_steps_per_second X" for the NRUN timed steps. Threads: OMP_NUM_THREADS.
#include <grain/bodies.hpp>
#include <grain/grain.hpp>
#include <grain/walls/obstacle.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

int main(int argc, char** argv) {
  using namespace grain;
  using Sim =
      Simulation<Sphere, search::CellList, presets::LinearCoulomb, stages<bodies::Coupling>>;
  std::vector<long> a = {25, 25, 16, 200, 1000};
  if (argc == 6)
    for (int k = 0; k < 5; ++k)
      a[static_cast<std::size_t>(k)] = std::atol(argv[k + 1]);
  else if (argc != 1) {
    std::fprintf(stderr, "usage: case_parmec_settle [NX NY NZ NWARM NRUN]\n");
    return 2;
  }
  const long nx = a[0], ny = a[1], nz = a[2], nwarm = a[3], nrun = a[4];
  const double r = 0.05, s = 0.11;
  Sim::Params p;
  p.gravity = Vec3(0, 0, -9.81);
  p.time_step = 1.0;
  Sim sim(p);
  const auto mat = sim.add_material({.name = "sphere",
                                     .density = 1000.0,
                                     .young = 1e7,
                                     .poisson = 0.3,
                                     .restitution = 1.0,
                                     .friction = 0.0});
  const auto obs = sim.add_material({.name = "obstacle",
                                     .density = 1000.0,
                                     .young = 1e9,
                                     .poisson = 0.25,
                                     .restitution = 1.0,
                                     .friction = 0.0});
  for (long i = 0; i < nx; ++i)
    for (long j = 0; j < ny; ++j)
      for (long k = 0; k < nz; ++k)
        sim.add_particle({.position = Vec3(s * (i + 0.5), s * (j + 0.5), s * (k + 0.5)),
                          .radius = r,
                          .material = mat});
  const double X = s * nx, Y = s * ny, Z = s * (nz + 1);
  std::vector<walls::Triangle> box;
  auto face = [&](Vec3 q0, Vec3 q1, Vec3 q2, Vec3 q3) {
    box.push_back({q0, q1, q2});
    box.push_back({q0, q2, q3});
  };
  face({0, 0, 0}, {X, 0, 0}, {X, Y, 0}, {0, Y, 0});
  face({0, 0, 0}, {0, 0, Z}, {X, 0, Z}, {X, 0, 0});
  face({0, Y, 0}, {X, Y, 0}, {X, Y, Z}, {0, Y, Z});
  face({0, 0, 0}, {0, Y, 0}, {0, Y, Z}, {0, 0, Z});
  face({X, 0, 0}, {X, 0, Z}, {X, Y, Z}, {X, Y, 0});
  add_obstacle(sim, box, {.name = "box", .material = obs});
  // GRANULAR(0, 0, 1e5, 0.2, 0.3, kskn = 0.5) for the pairs sphere-sphere and sphere-obstacle
  presets::LinearCoulomb::Params law;
  law.normal.stiffness = 1e5;
  law.normal.damping_ratio = 0.2;
  law.tangent.stiffness_ratio = 0.5;
  law.tangent.damping_factor = 0.5;
  for (auto b : {mat, obs}) {
    sim.set_pair_parameters(mat, b, law);
    sim.set_pair(mat, b, {.friction = 0.3, .friction_static = 0.3});
  }
  // the step: 0.2 of the critical step of the stiffest contact on the lightest sphere (m/2)
  const double m = 1000.0 * 4.0 / 3.0 * std::acos(-1.0) * r * r * r;
  const double h = 0.2 * bodies::critical_step(std::sqrt(1e5 / (0.5 * m)), 0.2);
  sim.set_time_step(h);
  auto& sys = sim.stage<bodies::Coupling>().system();
  auto vtk = io::vtk("parmec_settle");
  auto bodies_vtk = bodies::body_vtk("parmec_settle");
  auto write = [&](const Sim& x) {
    vtk(x);
    if (sys.bodies().size() > 0) bodies_vtk(sys);
  };
  sim.run(nwarm * h, io::every(nwarm * h, write));
  const auto t0 = std::chrono::steady_clock::now();
  sim.run(nrun * h, io::every(nrun * h, write));
  const double t = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("particles %ld\nstep %.9g\n", nx * ny * nz, h);
  std::printf("particle_steps_per_second %.6g\n", static_cast<double>(nx * ny * nz * nrun) / t);
  return 0;
}
