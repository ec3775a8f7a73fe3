/// \file settle2d.cpp
/// Polydisperse disks settle under gravity in a 2D box made of three segments.
///
/// Models: linear spring-dashpot normal force (stiffness Hertz-equivalent at 1 m/s, damping
/// from the restitution coefficient), spring-dashpot-slider friction, linked-cell neighbour
/// search, velocity Verlet. 600 disks (radii 0.8-1.2 mm, drawn from a fixed seed so every run
/// is identical) start on a loose lattice and fall into a 39 mm wide box.
///
/// The disks carry the mass and moment of inertia of spheres of the same radius
/// (`Disk{.sphere_mass = true}`): a 2D picture of a bed of spheres, in which masses and contact
/// stiffnesses have the magnitudes of the 3D problem.
///
/// Usage: settle2d [end_time_s] [output_dir]
///   end_time_s  simulated time [s] (default 0.4)
///   output_dir  folder for the VTK series (default out/settle2d)
///
/// Output: output_dir/settle2d_particles_NNNNNN.vtk and settle2d_walls_NNNNNN.vtk every 0.02 s
/// (open the series in ParaView; draw the particles with a Glyph filter scaled by "radius").
/// The program exits with status 1 if a disk has left the box.

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

using Contact = Interaction<normal::LinearSpringDashpot, tangent::SpringDashpotSlider>;
using Sim = Simulation<Disk, search::CellList, Contact, integrate::VelocityVerlet>;

namespace {

/// Area [m^2] of the part of a disk (centre height yc, radius r) between heights y1 < y2.
double disk_band_area(double yc, double r, double y1, double y2) {
  const double a = std::max(y1 - yc, -r), b = std::min(y2 - yc, r);
  if (a >= b) return 0.0;
  auto f = [r](double u) {
    return u * std::sqrt(std::max(r * r - u * u, 0.0)) + r * r * std::asin(u / r);
  };
  return f(b) - f(a);
}

} // namespace

int main(int argc, char** argv) {
  // ------------------------------------------------------------------ command line
  double end_time = 0.4; // [s]
  std::filesystem::path out_dir = "out/settle2d";
  if (!example::parse_arguments(argc, argv, "settle2d", end_time, out_dir)) return 2;

  // ------------------------------------------------------------------ set-up
  constexpr int nx = 15, ny = 40;                  // lattice of starting positions: 600 disks
  constexpr double spacing = 2.6e-3;               // lattice spacing [m] (> largest diameter)
  constexpr double r_min = 0.8e-3, r_max = 1.2e-3; // radius range [m]
  constexpr double width = nx * spacing;           // inner width of the box [m]
  constexpr double height = 1.25 * ny * spacing;   // height of the side walls [m]

  Sim::Params params;
  params.gravity = Vec2(0.0, -9.81); // [m/s^2]
  // time step: automatic, 0.1 x min(Rayleigh time, contact limit)
  Sim sim(params, Disk{.sphere_mass = true});

  // A glass-like material with a softened Young's modulus (1e7 Pa instead of about 6e10 Pa): the
  // time step is about 80 times larger, and the overlaps stay small (the largest is printed at
  // the end).
  const auto glass = sim.add_material({.name = "glass (softened)",
                                       .density = 2500.0,
                                       .young = 1e7,
                                       .poisson = 0.25,
                                       .restitution = 0.5,
                                       .friction = 0.5});

  // The box: a floor and two side walls (the top is open).
  sim.add_wall(walls::Segment{Vec2(0.0, 0.0), Vec2(width, 0.0)},
               {.name = "floor", .material = glass});
  sim.add_wall(walls::Segment{Vec2(0.0, 0.0), Vec2(0.0, height)},
               {.name = "left", .material = glass});
  sim.add_wall(walls::Segment{Vec2(width, 0.0), Vec2(width, height)},
               {.name = "right", .material = glass});

  // Disks on a loose lattice, each shifted sideways by up to 0.09 mm so that the columns
  // collapse instead of stacking; radii uniform in [r_min, r_max].
  example::Random rng{2024};
  double solid_area = 0.0; // [m^2]
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const double r = rng.uniform(r_min, r_max);
      const Vec2 x((i + 0.5) * spacing + rng.uniform(-0.09e-3, 0.09e-3), (j + 0.5) * spacing);
      sim.add_particle({.position = x, .radius = r, .material = glass});
      solid_area += std::numbers::pi * r * r;
    }

  // ------------------------------------------------------------------ run
  const double interval = 0.02; // output interval [s]
  const std::string prefix = (out_dir / "settle2d").string();
  double ke_max = 0.0; // largest kinetic energy seen at an output time [J]
  int frames = 0;
  auto log = [&](const Sim& s) {
    const double ke = s.kinetic_energy();
    const auto [pp, pw] = s.contact_counts();
    ke_max = std::max(ke_max, ke);
    ++frames;
    std::printf("  t = %6.3f s   kinetic energy %.4e J   contacts %4zu particle-particle, %3zu "
                "particle-wall\n",
                s.time(), ke, pp, pw);
  };
  sim.run(end_time, io::summary(), io::every(interval, io::vtk(prefix), log), io::progress());

  // ------------------------------------------------------------------ results
  const auto& p = sim.particles();
  const std::size_t n = p.size();
  std::size_t outside = 0;
  double y_mean = 0.0, top = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2& x = p.position[i];
    const bool inside = x.allFinite() && x.x() > 0.0 && x.x() < width && x.y() > 0.0;
    outside += !inside;
    y_mean += x.y() / static_cast<double>(n);
    top = std::max(top, x.y() + p.radius[i]);
  }
  // Bed height H = 2 x mean centre height (exact for a bed of uniform density); the packing
  // (area) fraction is measured in the band 0.2 H < y < 0.8 H, away from the floor and the surface.
  const double bed = 2.0 * y_mean, y1 = 0.2 * bed, y2 = 0.8 * bed;
  double band_solid = 0.0;
  for (std::size_t i = 0; i < n; ++i)
    band_solid += disk_band_area(p.position[i].y(), p.radius[i], y1, y2);
  const double packing = band_solid / (width * (y2 - y1));
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

  std::printf("\nsettle2d: %zu disks in a %.1f mm wide box after %.3f s\n", n, width * 1e3,
              sim.time());
  std::printf("  disks outside the box          %zu\n", outside);
  std::printf("  mean centre height             %.3f mm\n", y_mean * 1e3);
  std::printf("  highest disk top               %.3f mm\n", top * 1e3);
  std::printf("  packing fraction (bed interior) %.3f  (solid fraction of the whole bed %.3f)\n",
              packing, solid_area / (width * bed));
  std::printf("  kinetic energy                 %.4e J  (%.2e of its largest output value)\n", ke,
              ke_max > 0 ? ke / ke_max : 0.0);
  std::printf("  particle speed                 median %.3g mm/s, largest %.3g mm/s\n",
              v_median * 1e3, v_max * 1e3);
  std::printf("  contacts                       %zu particle-particle, %zu particle-wall; "
              "coordination number %.2f\n",
              pp, pw, n > 0 ? (2.0 * static_cast<double>(pp) + static_cast<double>(pw)) / n : 0.0);
  std::printf("  largest overlap                %.3f %% of the smaller radius\n",
              100.0 * max_overlap);
  std::printf("  output: %d VTK frames in %s (settle2d_particles_*.vtk, settle2d_walls_*.vtk)\n",
              frames, std::filesystem::absolute(out_dir).lexically_normal().string().c_str());
  return outside == 0 ? 0 : 1;
}
