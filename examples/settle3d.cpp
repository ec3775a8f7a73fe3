/// \file settle3d.cpp
/// A few thousand glass-like spheres settle under gravity in an open box of five planes.
///
/// Models: Hertz normal force with Tsuji damping, spring-dashpot-slider friction, linked-cell
/// neighbour search, velocity Verlet. The spheres (radii 0.8-1.2 mm, drawn from a fixed seed so
/// every run is identical) start on a loose lattice above the floor and fall into a 31.2 mm
/// square box; the run ends when the bed has come to rest.
///
/// Usage: settle3d [end_time_s] [output_dir]
///   end_time_s  simulated time [s] (default 0.3)
///   output_dir  folder for the VTK series (default out/settle3d)
///
/// Output: output_dir/settle3d_particles_NNNNNN.vtk and settle3d_walls_NNNNNN.vtk every 0.02 s
/// (open the series in ParaView; draw the particles with a Glyph filter scaled by "radius").
/// The program exits with status 1 if a sphere has left the box.

#include <grain/grain.hpp>

#include "example_support.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <numbers>
#include <string>
#include <vector>

using namespace grain;

using Contact = Interaction<normal::Hertz<>, tangent::SpringDashpotSlider>;
using Sim = Simulation<Sphere, search::CellList, Contact, integrate::VelocityVerlet>;

namespace {

/// Volume [m^3] of the part of a sphere (centre height zc, radius r) between heights z1 < z2.
double sphere_slab_volume(double zc, double r, double z1, double z2) {
  const double a = std::max(z1 - zc, -r), b = std::min(z2 - zc, r);
  if (a >= b) return 0.0;
  auto f = [r](double u) { return r * r * u - u * u * u / 3.0; };
  return std::numbers::pi * (f(b) - f(a));
}

} // namespace

int main(int argc, char** argv) {
  // ------------------------------------------------------------------ command line
  double end_time = 0.3; // [s]
  std::filesystem::path out_dir = "out/settle3d";
  if (!example::parse_arguments(argc, argv, "settle3d", end_time, out_dir)) return 2;

  // ------------------------------------------------------------------ set-up
  constexpr int nx = 12, ny = 12, nz = 21;         // lattice of starting positions: 3024 spheres
  constexpr double spacing = 2.6e-3;               // lattice spacing [m] (> largest diameter)
  constexpr double r_min = 0.8e-3, r_max = 1.2e-3; // radius range [m]
  constexpr double box = nx * spacing;             // inner width of the box in x and y [m]

  Sim::Params params;
  params.gravity = Vec3(0.0, 0.0, -9.81); // [m/s^2]
  // time step: automatic, 0.1 x min(Rayleigh time, contact limit)
  Sim sim(params);

  // A glass-like material with a softened Young's modulus (1e7 Pa instead of about 6e10 Pa): the
  // time step is about 80 times larger, and the overlaps stay small (the largest is printed at
  // the end).
  const auto glass = sim.add_material({.name = "glass (softened)",
                                       .density = 2500.0,
                                       .young = 1e7,
                                       .poisson = 0.25,
                                       .restitution = 0.5,
                                       .friction = 0.5});

  // Five planes (floor and four sides; the top is open). Each normal points into the box.
  const double mid = 0.5 * box;
  sim.add_wall(walls::Plane{Vec3(mid, mid, 0.0), Vec3(0, 0, 1)},
               {.name = "floor", .material = glass});
  sim.add_wall(walls::Plane{Vec3(0.0, mid, mid), Vec3(1, 0, 0)}, {.name = "x-", .material = glass});
  sim.add_wall(walls::Plane{Vec3(box, mid, mid), Vec3(-1, 0, 0)},
               {.name = "x+", .material = glass});
  sim.add_wall(walls::Plane{Vec3(mid, 0.0, mid), Vec3(0, 1, 0)}, {.name = "y-", .material = glass});
  sim.add_wall(walls::Plane{Vec3(mid, box, mid), Vec3(0, -1, 0)},
               {.name = "y+", .material = glass});

  // Spheres on a loose lattice, each shifted sideways by up to 0.09 mm so that the columns
  // collapse instead of stacking; radii uniform in [r_min, r_max].
  example::Random rng{2024};
  double solid_volume = 0.0; // [m^3]
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        const double r = rng.uniform(r_min, r_max);
        const Vec3 x((i + 0.5) * spacing + rng.uniform(-0.09e-3, 0.09e-3),
                     (j + 0.5) * spacing + rng.uniform(-0.09e-3, 0.09e-3), (k + 0.5) * spacing);
        sim.add_particle({.position = x, .radius = r, .material = glass});
        solid_volume += sim.shape().volume(r);
      }

  // ------------------------------------------------------------------ run
  const double interval = 0.02; // output interval [s]
  const std::string prefix = (out_dir / "settle3d").string();
  double ke_max = 0.0; // largest kinetic energy seen at an output time [J]
  int frames = 0;
  auto log = [&](const Sim& s) {
    const double ke = s.kinetic_energy();
    const auto [pp, pw] = s.contact_counts();
    ke_max = std::max(ke_max, ke);
    ++frames;
    std::printf("  t = %6.3f s   kinetic energy %.4e J   contacts %5zu particle-particle, %4zu "
                "particle-wall\n",
                s.time(), ke, pp, pw);
  };
  sim.run(end_time, io::summary(), io::every(interval, io::vtk(prefix, box), log), io::progress());

  // ------------------------------------------------------------------ results
  const auto& p = sim.particles();
  const std::size_t n = p.size();
  std::size_t outside = 0;
  double z_mean = 0.0, top = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3& x = p.position[i];
    const bool inside =
        x.allFinite() && x.x() > 0.0 && x.x() < box && x.y() > 0.0 && x.y() < box && x.z() > 0.0;
    outside += !inside;
    z_mean += x.z() / static_cast<double>(n);
    top = std::max(top, x.z() + p.radius[i]);
  }
  // Bed height H = 2 x mean centre height (exact for a bed of uniform density); the packing
  // fraction is measured in the slab 0.2 H < z < 0.8 H, away from the floor and the surface.
  const double bed = 2.0 * z_mean, z1 = 0.2 * bed, z2 = 0.8 * bed;
  double slab_solid = 0.0;
  for (std::size_t i = 0; i < n; ++i)
    slab_solid += sphere_slab_volume(p.position[i].z(), p.radius[i], z1, z2);
  const double packing = slab_solid / (box * box * (z2 - z1));
  const auto [pp, pw] = sim.contact_counts();
  double max_overlap = 0.0; // largest overlap / smaller radius of the pair
  sim.for_each_contact([&](auto, auto, bool, const auto& g, const auto&) {
    max_overlap = std::max(max_overlap, g.overlap / std::min(g.radius_i, g.radius_j));
  });
  const double ke = sim.kinetic_energy();
  std::vector<double> speed; // [m/s]
  for (const auto& v : p.velocity)
    speed.push_back(v.norm());
  std::sort(speed.begin(), speed.end());
  const double v_median = n > 0 ? speed[n / 2] : 0.0, v_max = n > 0 ? speed.back() : 0.0;

  std::printf("\nsettle3d: %zu spheres in a %.1f mm x %.1f mm box after %.3f s\n", n, box * 1e3,
              box * 1e3, sim.time());
  std::printf("  spheres outside the box        %zu\n", outside);
  std::printf("  mean centre height             %.3f mm\n", z_mean * 1e3);
  std::printf("  highest sphere top             %.3f mm\n", top * 1e3);
  std::printf("  packing fraction (bed interior) %.3f  (solid fraction of the whole bed %.3f)\n",
              packing, solid_volume / (box * box * bed));
  std::printf("  kinetic energy                 %.4e J  (%.2e of its largest output value)\n", ke,
              ke_max > 0 ? ke / ke_max : 0.0);
  std::printf("  particle speed                 median %.3g mm/s, largest %.3g mm/s\n",
              v_median * 1e3, v_max * 1e3);
  std::printf("  contacts                       %zu particle-particle, %zu particle-wall; "
              "coordination number %.2f\n",
              pp, pw, n > 0 ? (2.0 * static_cast<double>(pp) + static_cast<double>(pw)) / n : 0.0);
  std::printf("  largest overlap                %.3f %% of the smaller radius\n",
              100.0 * max_overlap);
  std::printf("  output: %d VTK frames in %s (settle3d_particles_*.vtk, settle3d_walls_*.vtk)\n",
              frames, std::filesystem::absolute(out_dir).lexically_normal().string().c_str());
  return outside == 0 ? 0 : 1;
}
