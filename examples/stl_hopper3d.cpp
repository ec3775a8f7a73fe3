/// \file stl_hopper3d.cpp
/// Spheres poured into a hopper read from an STL file (3D).
///
/// The program first draws a square hopper in millimetres, as a CAD program would: four sloped
/// faces from a 80 mm x 80 mm top at z = 140 mm down to a 24 mm x 24 mm outlet at z = 60 mm,
/// two triangles each, and writes it as a binary STL file, hopper.stl, in the output folder. It
/// then reads that file back in metres (io::read_stl with scale 1e-3) into a fixed obstacle.
/// 800 glass spheres (radii uniform in 1.5-2.5 mm, from a fixed seed) are poured in through a
/// 60 mm x 60 mm face 60 mm above the hopper, 4000 a second at 0.5 m/s downwards, never
/// overlapping the spheres already there (an insertion, docs/insertion.md); they fall into the
/// hopper and run out through the outlet onto the floor (a plane at z = 0).
///
/// Models: Hertz-Mindlin with Tsuji damping (restitution 0.4, friction 0.3); Young's modulus
/// softened to 5e7 Pa for a longer time step. Linked cells; velocity Verlet.
///
/// Usage: stl_hopper3d [end_time_s] [output_dir]
///   end_time_s  simulated time [s] (default 0.6)
///   output_dir  folder for hopper.stl and the VTK series (default out/stl_hopper3d)
///
/// Output: every 0.05 s the spheres poured so far, and how many are above the hopper, in it
/// (between the outlet and the top) and below it; VTK files of the particles and of the hopper's triangles every
/// 0.05 s. At the end, with Python, VTK and matplotlib installed, a 3D picture of the last frame
/// (scripts/grain_plot.py), stl_hopper3d_final.png. Exits with status 1 if the file read back
/// differs from the mesh written, or a sphere is not finite or below the floor.

#include <grain/grain.hpp>

#include "example_support.hpp"

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>

using namespace grain;

using Sim = Simulation<Sphere, search::CellList, presets::HertzMindlin>;

namespace {

/// The four sloped faces of a square hopper [mm]: top half-width `top` at height `z_top`, outlet
/// half-width `out` at height `z_out`, centred on the z axis.
walls::TriangleMesh hopper_mm(double top, double z_top, double out, double z_out) {
  walls::TriangleMesh m;
  const double sx[4] = {1, -1, -1, 1}, sy[4] = {1, 1, -1, -1};
  for (int k = 0; k < 4; ++k) // top corners 0..3, outlet corners 4..7
    m.vertices.push_back(Vec3(top * sx[k], top * sy[k], z_top));
  for (int k = 0; k < 4; ++k)
    m.vertices.push_back(Vec3(out * sx[k], out * sy[k], z_out));
  for (std::uint32_t k = 0; k < 4; ++k) {
    const std::uint32_t n = (k + 1) % 4;
    m.triangles.push_back({k, n, 4 + n});
    m.triangles.push_back({k, 4 + n, 4 + k});
  }
  return m;
}

} // namespace

int main(int argc, char** argv) {
  double end_time = 0.6; // [s]
  std::filesystem::path out_dir = "out/stl_hopper3d";
  if (!example::parse_arguments(argc, argv, "stl_hopper3d", end_time, out_dir)) return 2;

  // the hopper as a CAD file: drawn in mm, written as binary STL, read back in m
  const walls::TriangleMesh drawn = hopper_mm(40.0, 140.0, 12.0, 60.0);
  const std::string stl = (out_dir / "hopper.stl").string();
  io::write_stl(drawn, stl, /*binary=*/true, "square hopper, mm");
  const walls::TriangleMesh hopper = io::read_stl(stl, {.scale = 1e-3});
  bool same = hopper.triangles.size() == drawn.triangles.size() &&
              hopper.vertices.size() == drawn.vertices.size();
  for (std::size_t t = 0; same && t < hopper.triangles.size(); ++t) // corner by corner
    for (int c = 0; c < 3; ++c)
      same = same && (hopper.vertices[hopper.triangles[t][c]] -
                      1e-3 * drawn.vertices[drawn.triangles[t][c]])
                             .norm() < 1e-9; // single precision in the file
  std::printf("stl_hopper3d: %s holds %zu triangles, %zu vertices (read back %s)\n", stl.c_str(),
              hopper.triangles.size(), hopper.vertices.size(), same ? "unchanged" : "CHANGED");

  Sim::Params params;
  params.gravity = Vec3(0, 0, -9.81);
  Sim sim(params);
  const auto glass = sim.add_material({.name = "glass (softened)",
                                       .density = 2500.0,
                                       .young = 5e7,
                                       .poisson = 0.25,
                                       .restitution = 0.4,
                                       .friction = 0.3});
  add_obstacle(sim, hopper, {.name = "hopper", .material = glass});
  sim.add_wall(walls::Plane{{0, 0, 0}, {0, 0, 1}}, {.name = "floor", .material = glass});

  // the spheres enter through a horizontal face above the hopper
  const auto pour =
      sim.add_insertion({.name = "pour",
                         .region = insertion::RectangleFace{Vec3(-0.03, -0.03, 0.2),
                                                            Vec3(0.06, 0, 0), Vec3(0, 0.06, 0)},
                         .size = generate::Uniform{1.5e-3, 2.5e-3},
                         .material = glass,
                         .number_rate = 4000.0,
                         .total_count = 800,
                         .velocity = Vec3(0, 0, -0.5),
                         .group = "poured",
                         .seed = 7});

  constexpr double z_out = 0.06, z_top = 0.14;
  std::printf("      t [s]   poured   above   in hopper   out below\n");
  auto log = [&](const Sim& s) {
    std::size_t above = 0, in = 0, below = 0;
    for (const auto& x : s.particles().position)
      (x.z() > z_top ? above : x.z() > z_out ? in : below) += 1;
    std::printf("  %8.3f   %6llu   %5zu   %9zu   %9zu\n", s.time(),
                static_cast<unsigned long long>(s.insertion_status(pour).inserted), above, in,
                below);
  };
  const std::string prefix = (out_dir / "stl_hopper3d").string();
  sim.run(end_time, io::summary(), io::every(0.05, log), io::every(0.05, io::vtk(prefix, 0.1)),
          io::progress());

  std::size_t bad = 0, below = 0;
  for (const auto& x : sim.particles().position) {
    bad += !(x.allFinite() && x.z() > 0.0);
    below += x.z() < z_out;
  }
  const auto& status = sim.insertion_status(pour);
  std::printf("\nstl_hopper3d: after %.3f s %llu spheres poured (%llu still due), %zu of them have "
              "run out of the hopper; %zu not finite or below the floor\n",
              sim.time(), static_cast<unsigned long long>(status.inserted),
              static_cast<unsigned long long>(status.shortfall), below, bad);
  const std::string last = example::last_file(out_dir, "stl_hopper3d_particles_");
  const bool picture =
      !last.empty() &&
      example::plot("spheres '" + (out_dir / last).string() + "' -f velocity -o '" +
                    (out_dir / "stl_hopper3d_final.png").string() + "'");
  std::printf(
      "  output in %s: hopper.stl, VTK series stl_hopper3d_{particles,walls}.vtk.series%s\n",
      std::filesystem::absolute(out_dir).lexically_normal().string().c_str(),
      picture ? "; 3D picture of the last frame stl_hopper3d_final.png"
              : " (no picture: scripts/grain_plot.py needs python3-vtk9 and "
                "python3-matplotlib)");
  return same && bad == 0 ? 0 : 1;
}
