/// \file hot_pour3d.cpp
/// Hot spheres poured onto a cold packed bed (3D, thermo-mechanical).
///
/// 396 copper spheres at 300 K (radii 1.8-2.2 mm, from a fixed seed) lie as a bed in a 30 mm x
/// 30 mm box; 216 spheres at 500 K start on a lattice above them and fall onto the bed, where
/// they cool through their contacts while warming the bed. The box walls are insulated, so the
/// heat content sum m c T stays constant (printed at the end with its relative change).
///
/// Models: Hertz-Mindlin with Tsuji damping, Batchelor-O'Brien conduction with the Zhou-Yu-Zulli
/// correction of the contact radius for the softened Young's modulus (1e8 Pa simulated, 1.2e11 Pa
/// real). Neighbour search by linked cells; velocity Verlet; temperatures by forward Euler.
///
/// Usage: hot_pour3d [end_time_s] [output_dir]
///   end_time_s  simulated time [s] (default 0.5)
///   output_dir  folder for the VTK series (default out/hot_pour3d)
///
/// Output: every 0.05 s the mean temperatures of the poured and of the bed spheres; VTK files of
/// particles (with temperature and heat_rate) and walls every 0.05 s. At the end, with Python, VTK
/// and matplotlib (Debian python3-vtk9, python3-matplotlib), scripts/grain_plot.py draws a 3D
/// picture of the last frame coloured by temperature, hot_pour3d_final.png, ray-traced by POV-Ray
/// (Debian povray) if it is installed, else a matplotlib scatter; without them the example only
/// says so. Exits with status 1 if a sphere has left the box or the heat content changed by more
/// than 1e-9 of itself.

#include <grain/grain.hpp>

#include "example_support.hpp"
#include <grain/models/area/zhou_yu_zulli.hpp>
#include <grain/models/conduction/batchelor_obrien.hpp>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

using namespace grain;

using Contact = Interaction<normal::Hertz<>, tangent::Mindlin, rolling::None,
                            conduction::BatchelorOBrien, area::ZhouYuZulli>;
using Sim = Simulation<Sphere, search::CellList, Contact>;

int main(int argc, char** argv) {
  double end_time = 0.5; // [s]
  std::filesystem::path out_dir = "out/hot_pour3d";
  if (!example::parse_arguments(argc, argv, "hot_pour3d", end_time, out_dir)) return 2;

  constexpr double side = 0.03, height = 0.08; // box [m]
  constexpr double spacing = 4.6e-3;           // lattice spacing [m]
  constexpr double cold = 300.0, hot = 500.0;  // [K]
  constexpr int per_layer = 6 * 6, bed_layers = 11, hot_layers = 6;

  Sim::Params params;
  params.gravity = Vec3(0, 0, -9.81);
  Sim sim(params);
  const auto copper = sim.add_material({.name = "copper (softened)",
                                        .density = 8900.0,
                                        .young = 1e8,
                                        .poisson = 0.34,
                                        .young_real = 1.2e11,
                                        .restitution = 0.5,
                                        .friction = 0.4,
                                        .conductivity = 400.0,
                                        .heat_capacity = 385.0});
  // Five planes, each given by the centre of its face of the box (where the VTK files draw it as
  // a square of side `side`) and a normal pointing into the box.
  constexpr double mid = 0.5 * side;
  sim.add_wall(walls::Plane{{mid, mid, 0}, {0, 0, 1}}, {.name = "floor", .material = copper});
  sim.add_wall(walls::Plane{{0, mid, mid}, {1, 0, 0}}, {.name = "x-", .material = copper});
  sim.add_wall(walls::Plane{{side, mid, mid}, {-1, 0, 0}}, {.name = "x+", .material = copper});
  sim.add_wall(walls::Plane{{mid, 0, mid}, {0, 1, 0}}, {.name = "y-", .material = copper});
  sim.add_wall(walls::Plane{{mid, side, mid}, {0, -1, 0}}, {.name = "y+", .material = copper});

  example::Random rng{11};
  std::int64_t id = 0;
  const std::int64_t first_hot = static_cast<std::int64_t>(per_layer) * bed_layers;
  for (int k = 0; k < bed_layers + hot_layers; ++k)
    for (int j = 0; j < 6; ++j)
      for (int i = 0; i < 6; ++i) {
        const bool is_hot = k >= bed_layers;
        const double z = 2.5e-3 + k * spacing + (is_hot ? 0.01 : 0.0);
        const Vec3 x(2.6e-3 + i * spacing + rng.uniform(-2e-4, 2e-4),
                     2.6e-3 + j * spacing + rng.uniform(-2e-4, 2e-4), z);
        sim.add_particle({.position = x,
                          .radius = rng.uniform(1.8e-3, 2.2e-3),
                          .material = copper,
                          .temperature = is_hot ? hot : cold,
                          .id = id++});
      }

  std::printf("hot_pour3d: %lld spheres at %.0f K fall onto %lld spheres at %.0f K\n",
              static_cast<long long>(id - first_hot), hot, static_cast<long long>(first_hot), cold);
  std::printf("      t [s]   poured mean T [K]   bed mean T [K]   contacts\n");
  auto means = [&](const Sim& s) {
    const auto& p = s.particles();
    double th = 0, tc = 0;
    for (std::size_t i = 0; i < p.size(); ++i)
      (p.id[i] >= first_hot ? th : tc) += p.temperature[i];
    return std::pair{th / double(id - first_hot), tc / double(first_hot)};
  };
  auto log = [&](const Sim& s) {
    const auto [th, tc] = means(s);
    std::printf("  %8.3f   %17.3f   %14.3f   %8zu\n", s.time(), th, tc, s.contact_counts().first);
  };
  const double heat0 = sim.thermal_energy();
  const std::string prefix = (out_dir / "hot_pour3d").string();
  sim.run(end_time, io::summary(), io::every(0.05, log), io::every(0.05, io::vtk(prefix, side)),
          io::progress());

  const auto& p = sim.particles();
  std::size_t outside = 0;
  for (const auto& x : p.position)
    outside += !(x.allFinite() && x.x() > 0 && x.x() < side && x.y() > 0 && x.y() < side &&
                 x.z() > 0 && x.z() < height + 0.05);
  const double drift = std::abs(sim.thermal_energy() - heat0) / heat0;
  const auto [th, tc] = means(sim);
  std::printf("\nhot_pour3d: after %.3f s poured spheres at %.3f K, bed at %.3f K\n", sim.time(),
              th, tc);
  std::printf("  heat content sum m c T changed by %.2e of itself (insulated box)\n", drift);
  std::printf("  spheres outside the box: %zu\n", outside);
  // a 3D picture of the last frame, drawn by scripts/grain_plot.py (its location is known at
  // build time): by POV-Ray, else by matplotlib; no Python, VTK or matplotlib is only reported
  const std::string last = example::last_file(out_dir, "hot_pour3d_particles_");
  const bool picture =
      !last.empty() &&
      example::plot("spheres '" + (out_dir / last).string() + "' -f temperature -o '" +
                    (out_dir / "hot_pour3d_final.png").string() + "'");
  std::printf("  output in %s: VTK series hot_pour3d_{particles,walls}.vtk.series%s\n",
              std::filesystem::absolute(out_dir).lexically_normal().string().c_str(),
              picture ? "; 3D picture of the last frame hot_pour3d_final.png"
                      : " (no picture: scripts/grain_plot.py needs python3-vtk9 and "
                        "python3-matplotlib)");
  return outside == 0 && drift < 1e-9 ? 0 : 1;
}
