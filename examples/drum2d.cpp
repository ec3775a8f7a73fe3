/// \file drum2d.cpp
/// A hot rotating drum heats a bed of cold copper disks (2D, thermo-mechanical).
///
/// A drum of radius 40 mm (a `walls::Circle`, held at 400 K) turns at 3 rad/s about its centre;
/// 312 copper disks (radii 1.0-1.5 mm, drawn from a fixed seed so every run is identical) start
/// at 300 K on a loose lattice in its lower half, fall, and are carried up the drum wall. Heat
/// enters the bed through the contacts with the wall and spreads through the contacts between
/// disks, helped by the mixing of the tumbling bed.
///
/// Models: Hertz normal force with Tsuji damping, Mindlin tangential spring with Coulomb
/// friction, constant rolling resistance, Batchelor-O'Brien conduction through the contact
/// area, and the Zhou-Yu-Zulli correction of the contact radius for the softened Young's modulus
/// (1e7 Pa simulated, 1.2e11 Pa real: the time step is about 100 times larger, and the
/// correction keeps the conductances those of real copper contacts). Disks have the mass and
/// inertia of spheres (`Disk{.sphere_mass = true}`).
///
/// Usage: drum2d [end_time_s] [output_dir]
///   end_time_s  simulated time [s] (default 3)
///   output_dir  folder for the VTK series (default out/drum2d)
///
/// Output: every 0.1 s a line with the mean, lowest and highest disk temperature and the heat
/// flow from the drum; VTK files output_dir/drum2d_particles_NNNNNN.vtk (fields temperature,
/// heat_rate, velocity, ...), drum2d_walls_NNNNNN.vtk and the contact network
/// drum2d_contacts_NNNNNN.vtk (forces, contact radii, heat rates) every 0.05 s, with their
/// ParaView series files drum2d_*.vtk.series; the time history
/// output_dir/drum2d_history.csv (energies, contacts, mean temperature, heat content, heat
/// inflow, lowest and highest temperature) every 0.01 s. At the end, with Python and matplotlib
/// (Debian python3-matplotlib), scripts/grain_plot.py draws two graphs of the history
/// (drum2d_temperatures.png, drum2d_mechanics.png) and a picture of the last frame coloured by
/// temperature (drum2d_final.png). The program exits with
/// status 1 if a disk has left the drum or a temperature leaves [300 K, 400 K].

#include <grain/grain.hpp>

#include "example_support.hpp"
#include <grain/models/area/zhou_yu_zulli.hpp>
#include <grain/models/conduction/batchelor_obrien.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

using namespace grain;

using Contact = Interaction<normal::Hertz<normal::TsujiDamping>, // normal force
                            tangent::Mindlin,                    // tangential force
                            rolling::Constant,                   // rolling resistance
                            conduction::BatchelorOBrien,         // heat through the contact
                            area::ZhouYuZulli>;                  // contact-radius correction
using Sim = Simulation<Disk, search::CellList, Contact, integrate::VelocityVerlet>;

namespace {

/// Graphs of the history and a picture of the last frame, drawn by scripts/grain_plot.py (its
/// location is known at build time). Returns false if Python with matplotlib is missing.
bool draw_pictures(const std::filesystem::path& dir) {
  const std::string d = dir.string();
  const std::string last = example::last_file(dir, "drum2d_particles_");
  return !last.empty() &&
         example::plot("history '" + d +
                       "/drum2d_history.csv' -y mean_temperature -y min_temperature "
                       "-y max_temperature -y heat_inflow -o '" +
                       d + "/drum2d_temperatures.png'") &&
         example::plot("history '" + d +
                       "/drum2d_history.csv' -y kinetic_energy -y contacts_pp "
                       "-y contacts_pw -o '" +
                       d + "/drum2d_mechanics.png'") &&
         example::plot("disks '" + d + "/" + last + "' -f temperature -o '" + d +
                       "/drum2d_final.png'");
}

} // namespace

int main(int argc, char** argv) {
  // ------------------------------------------------------------------ command line
  double end_time = 3.0; // [s]
  std::filesystem::path out_dir = "out/drum2d";
  if (!example::parse_arguments(argc, argv, "drum2d", end_time, out_dir)) return 2;

  // ------------------------------------------------------------------ set-up
  constexpr double drum_radius = 0.04; // [m]
  constexpr double drum_speed = 3.0;   // angular velocity [rad/s] (about 29 rpm)
  constexpr double wall_temperature = 400.0, bed_temperature = 300.0; // [K]
  constexpr double r_min = 1.0e-3, r_max = 1.5e-3;                    // disk radii [m]
  constexpr double spacing = 3.2e-3; // starting lattice spacing [m]

  Sim::Params params;
  params.gravity = Vec2(0.0, -9.81); // [m/s^2]
  Sim sim(params, Disk{.sphere_mass = true});

  const auto copper = sim.add_material({.name = "copper (softened)",
                                        .density = 8900.0, // [kg/m^3]
                                        .young = 1e7,      // simulated [Pa]
                                        .poisson = 0.34,
                                        .young_real = 1.2e11, // real [Pa]
                                        .restitution = 0.6,
                                        .friction = 0.4,
                                        .rolling_friction = 0.02,
                                        .conductivity = 400.0,    // [W/(m K)]
                                        .heat_capacity = 385.0}); // [J/(kg K)]
  sim.add_wall(walls::Circle{Vec2(0.0, 0.0), drum_radius},
               {.name = "drum",
                .material = copper,
                .omega = drum_speed,
                .temperature = TimeFunction(wall_temperature)});

  // Disks on a lattice inside the lower part of the drum, shifted sideways by up to 0.1 mm.
  example::Random rng{7};
  const int n_side = static_cast<int>(drum_radius / spacing);
  for (int j = -n_side; j <= n_side; ++j)
    for (int i = -n_side; i <= n_side; ++i) {
      const Vec2 x(i * spacing + rng.uniform(-1e-4, 1e-4), j * spacing);
      if (x.norm() > drum_radius - 2.0 * r_max || x.y() > 0.35 * drum_radius) continue;
      sim.add_particle({.position = x,
                        .radius = rng.uniform(r_min, r_max),
                        .material = copper,
                        .temperature = bed_temperature});
    }

  // ------------------------------------------------------------------ run
  const std::string prefix = (out_dir / "drum2d").string();
  std::printf("drum2d: %zu copper disks at %.0f K in a drum of radius %.0f mm at %.0f K, "
              "turning at %.1f rad/s\n",
              sim.size(), bed_temperature, drum_radius * 1e3, wall_temperature, drum_speed);
  std::printf("       t [s]   mean T [K]    min T [K]    max T [K]   heat from drum [W]   "
              "contacts\n");
  auto log = [&](const Sim& s) {
    const auto& p = s.particles();
    double mean = 0.0, lo = 1e300, hi = -1e300, q = 0.0;
    for (std::size_t i = 0; i < p.size(); ++i) {
      mean += p.temperature[i];
      lo = std::min(lo, p.temperature[i]);
      hi = std::max(hi, p.temperature[i]);
      q += p.heat_rate[i]; // exchanges between disks cancel: the sum is the drum's heat flow
    }
    mean /= static_cast<double>(p.size());
    const auto [pp, pw] = s.contact_counts();
    std::printf("  %10.3f   %10.3f   %10.3f   %10.3f   %18.4f   %4zu + %3zu\n", s.time(), mean, lo,
                hi, q, pp, pw);
  };
  auto lowest = [](const Sim& s) {
    return *std::min_element(s.particles().temperature.begin(), s.particles().temperature.end());
  };
  auto highest = [](const Sim& s) {
    return *std::max_element(s.particles().temperature.begin(), s.particles().temperature.end());
  };
  sim.run(end_time, io::summary(), io::every(0.1, log),
          io::every(0.05, io::vtk(prefix, 1.0, /*contacts=*/true)),
          io::every(0.01,
                    io::history(prefix + "_history.csv", io::column("min_temperature [K]", lowest),
                                io::column("max_temperature [K]", highest))),
          io::progress());

  // ------------------------------------------------------------------ results
  const auto& p = sim.particles();
  std::size_t outside = 0, out_of_range = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    outside += !(p.position[i].allFinite() && p.position[i].norm() < drum_radius);
    out_of_range += !(p.temperature[i] >= bed_temperature - 1e-9 &&
                      p.temperature[i] <= wall_temperature + 1e-9);
  }
  std::printf("\ndrum2d: after %.3f s the mean disk temperature is %.3f K (from %.0f K)\n",
              sim.time(), sim.mean_temperature(), bed_temperature);
  std::printf("  disks outside the drum: %zu, temperatures outside [%.0f, %.0f] K: %zu\n", outside,
              bed_temperature, wall_temperature, out_of_range);
  const bool pictures = draw_pictures(out_dir);
  std::printf(
      "  output in %s: VTK series drum2d_{particles,walls,contacts}.vtk.series; time history "
      "drum2d_history.csv%s\n",
      std::filesystem::absolute(out_dir).lexically_normal().string().c_str(),
      pictures ? "; graphs drum2d_temperatures.png, drum2d_mechanics.png; picture "
                 "drum2d_final.png"
               : " (no graphs: scripts/grain_plot.py needs python3-matplotlib)");
  return outside == 0 && out_of_range == 0 ? 0 : 1;
}
