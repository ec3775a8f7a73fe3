/// \file hopper2d.cpp
/// Discharge of a flat-bottomed 2D silo through a central orifice, compared with Beverloo's law.
///
/// Scenario: a silo 66 mm wide (two side walls and two floor segments, all `walls::Segment`s)
/// with a central orifice D = 15 mm wide (about 7 mean disk diameters), closed from below by a
/// horizontal gate segment 0.25 mm under the floor. 902 glass disks (radii 1.0-1.2 mm, drawn
/// from a fixed seed so every run is identical) are poured: they are all added up front, but
/// with staggered creation times (`ParticleSpec::creation_time`), so that rows of 22 disks appear
/// one after another 100 mm above the floor, every 3 ms, falling at 1 m/s. The bed settles; at
/// t_open = 0.35 s the gate (a group of one wall) slides sideways at 0.5 m/s for 40 ms
/// (`fix_velocity` with a `VectorTimeFunction` active over [t_open, t_open + 40 ms]; a wall stands
/// still while its function is inactive) and the grains run out. A sink 30 mm below the floor
/// removes the discharged disks; a bounding box removes any disk that escapes the domain.
///
/// Models: Hertz normal force with Tsuji damping (restitution 0.5) and Mindlin tangential spring
/// with Coulomb friction (0.5), `presets::HertzMindlin`; linked-cell neighbour search, velocity
/// Verlet, automatic time step. The Young's modulus is softened to 5e6 Pa (glass: about 6e10 Pa)
/// so that the time step is about 100 times larger. Disks have the mass and inertia of spheres
/// (`Disk{.sphere_mass = true}`): the bed is a monolayer of beads, like the quasi-2D silos of the
/// experiments, and masses and flow rates are those of that monolayer (kg, kg/s).
///
/// The steady discharge rate W (a linear fit of the discharged mass over time, from 0.1 s after
/// the gate has gone until 60 % of the poured mass has left or the run ends) is compared with
/// the 2D form of Beverloo's law (Beverloo, Leniger & van de Velde 1961, Chem. Eng. Sci.
/// 15:260; in 2D the exponent is 3/2, see Mankoc et al. 2007, Granular Matter 9:407):
///     W = C rho_b sqrt(g) (D - k d)^(3/2),   C = 1.0, k = 1.5,
/// with d the mean disk diameter and rho_b the bulk density of the settled bed as a mass per unit
/// area [kg/m^2] (its mass over its width times its height, measured when the gate opens).
///
/// Usage: hopper2d [end_time_s] [output_dir]
///   end_time_s  simulated time [s] (default 1.0: pour, settle, open, about half discharged)
///   output_dir  folder for the output (default out/hopper2d)
///
/// Output: every 0.05 s a line with the active and removed disks, the discharged mass, the mean
/// speed and the contacts; the time history output_dir/hopper2d_history.csv (active, removed,
/// discharged mass, mean speed, contacts) every 5 ms; VTK files
/// output_dir/hopper2d_particles_NNNNNN.vtk and hopper2d_walls_NNNNNN.vtk every 0.02 s (with
/// their ParaView series files). At the end: the measured and the Beverloo discharge rates and
/// their ratio, and, with Python and matplotlib (Debian python3-matplotlib), graphs drawn by
/// scripts/grain_plot.py of the discharged mass (hopper2d_discharge.png) and of the other
/// columns (hopper2d_history.png), and a picture of the last frame coloured by speed
/// (hopper2d_final.png).
///
/// Exit status: 1 if a disk left the silo other than through the orifice (or has a non-finite
/// position); in a run that reached 0.1 s after the gate had gone, also if nothing was
/// discharged; in a run long enough for the fit, also if the ratio of the measured rate to
/// Beverloo's is outside [0.3, 3]. A short run that ends before the gate opens (the smoke test)
/// checks only that no disk left the silo.

#include <grain/grain.hpp>

#include "example_support.hpp"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <string>
#include <utility>
#include <vector>

using namespace grain;

using Sim = Simulation<Disk, search::CellList, presets::HertzMindlin, integrate::VelocityVerlet>;

namespace {

/// Follows every disk by id, step by step, to tell the disks that were discharged (removed with
/// their centre below the floor, i.e. by the sink) from those that escaped (removed anywhere
/// else, i.e. by the bounding box), and adds up the discharged mass. A disk's last height and
/// mass are those of the step before its removal.
struct Ledger {
  double floor_y;                   ///< height of the silo floor [m]
  std::vector<double> mass, last_y; ///< by id [kg], [m]
  std::size_t seen = 0;             ///< removals already classified
  std::size_t discharged = 0, escaped = 0;
  double discharged_mass = 0.0; ///< [kg]

  void operator()(const Sim& s) {
    const auto& removed = s.removed_ids();
    for (; seen < removed.size(); ++seen) {
      const auto id = static_cast<std::size_t>(removed[seen]);
      if (last_y[id] < floor_y) {
        ++discharged;
        discharged_mass += mass[id];
      } else {
        ++escaped;
      }
    }
    const auto& p = s.particles();
    for (std::size_t i = 0; i < p.size(); ++i) {
      const auto id = static_cast<std::size_t>(p.id[i]);
      last_y[id] = p.position[i].y();
      mass[id] = p.mass[i];
    }
  }
};

/// Least-squares slope of y(x).
double slope(const std::vector<std::pair<double, double>>& xy) {
  const double n = static_cast<double>(xy.size());
  double sx = 0.0, sy = 0.0, sxx = 0.0, sxy = 0.0;
  for (const auto& [x, y] : xy) {
    sx += x;
    sy += y;
    sxx += x * x;
    sxy += x * y;
  }
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

/// Graphs of the history and a picture of the last frame, drawn by scripts/grain_plot.py (its
/// location is known at build time). Returns false if Python with matplotlib is missing.
bool draw_pictures(const std::filesystem::path& dir) {
  const std::string d = dir.string();
  const std::string last = example::last_file(dir, "hopper2d_particles_");
  return !last.empty() &&
         example::plot("history '" + d +
                       "/hopper2d_history.csv' -y discharged_mass -y removed "
                       "-o '" +
                       d + "/hopper2d_discharge.png'") &&
         example::plot("history '" + d +
                       "/hopper2d_history.csv' -y active -y mean_speed -y contacts_pp "
                       "-y contacts_pw -o '" +
                       d + "/hopper2d_history.png'") &&
         example::plot("disks '" + d + "/" + last + "' -f velocity -o '" + d +
                       "/hopper2d_final.png'");
}

} // namespace

int main(int argc, char** argv) {
  // ------------------------------------------------------------------ command line
  double end_time = 1.0; // [s]
  std::filesystem::path out_dir = "out/hopper2d";
  if (!example::parse_arguments(argc, argv, "hopper2d", end_time, out_dir)) return 2;

  // ------------------------------------------------------------------ set-up
  constexpr double r_min = 1.0e-3, r_max = 1.2e-3; // disk radii [m]
  constexpr double width = 66e-3;                  // inner width of the silo [m], x in [-w/2, w/2]
  constexpr double wall_height = 110e-3;           // height of the side walls [m]
  constexpr double orifice = 15e-3;                // width D of the orifice [m], x in [-D/2, D/2]
  constexpr double gate_gap = 0.25e-3;             // the gate runs this far under the floor [m]
  constexpr double gate_overlap = 2e-3;            // the gate reaches this far under each floor [m]
  constexpr double t_open = 0.35;                  // the gate starts to open [s]
  constexpr double gate_time = 0.04, gate_speed = 0.5;   // it slides 20 mm in 40 ms [s, m/s]
  constexpr double t_flowing = t_open + gate_time + 0.1; // the discharge is steady from here [s]
  constexpr int per_row = 22, rows = 41;                 // the pour: 902 disks
  constexpr double pour_height = 100e-3;                 // rows appear at this height [m] ...
  constexpr double row_interval = 3e-3;                  // ... one every 3 ms [s] ...
  constexpr double pour_speed = 1.0;                     // ... falling at 1 m/s [m/s]
  constexpr double sink_depth = 30e-3;                   // top of the sink below the floor [m]
  constexpr double g = 9.81;                             // [m/s^2]

  Sim::Params params;
  params.gravity = Vec2(0.0, -g);
  Sim sim(params, Disk{.sphere_mass = true});
  const auto glass = sim.add_material({.name = "glass (softened)",
                                       .density = 2500.0, // [kg/m^3]
                                       .young = 5e6,      // simulated [Pa]
                                       .poisson = 0.25,
                                       .restitution = 0.5,
                                       .friction = 0.5});

  // The silo: side walls, floor segments on either side of the orifice, and the gate below it.
  const Vec2 left_top(-width / 2, wall_height), right_top(width / 2, wall_height);
  const Vec2 left_corner(-width / 2, 0.0), right_corner(width / 2, 0.0);
  sim.add_wall(walls::Segment{left_corner, left_top}, {.name = "left", .material = glass});
  sim.add_wall(walls::Segment{right_corner, right_top}, {.name = "right", .material = glass});
  sim.add_wall(walls::Segment{left_corner, Vec2(-orifice / 2, 0.0)},
               {.name = "floor left", .material = glass});
  sim.add_wall(walls::Segment{Vec2(orifice / 2, 0.0), right_corner},
               {.name = "floor right", .material = glass});
  const auto gate = sim.add_wall(walls::Segment{Vec2(-orifice / 2 - gate_overlap, -gate_gap),
                                                Vec2(orifice / 2 + gate_overlap, -gate_gap)},
                                 {.name = "gate", .material = glass});

  // The pour: rows of disks spread across the silo, each shifted sideways by up to 0.2 mm,
  // appearing one row after another.
  example::Random rng{1961};
  const double pitch = width / per_row; // 3 mm between neighbours in a row
  std::int64_t last_id = -1;
  for (int j = 0; j < rows; ++j)
    for (int i = 0; i < per_row; ++i) {
      const double x = -width / 2 + (i + 0.5) * pitch + rng.uniform(-2e-4, 2e-4);
      last_id = sim.add_particle({.position = Vec2(x, pour_height),
                                  .radius = rng.uniform(r_min, r_max),
                                  .material = glass,
                                  .velocity = Vec2(0.0, -pour_speed),
                                  .creation_time = j * row_interval});
    }
  const std::size_t n_disks = static_cast<std::size_t>(per_row) * rows;

  // The gate slides sideways (to +x, under the right floor) while t_open <= t <= t_open + 40 ms.
  sim.add_group("gate", {}, {gate});
  sim.fix_velocity("gate",
                   VectorTimeFunction<2>(gate_speed, 0.0).active(t_open, t_open + gate_time));

  // The sink catches the disks that fell through the orifice; the bounding box (the silo, and
  // everything below it down past the sink) removes any disk that leaves the domain.
  sim.add_sink(regions::Box<2>{Vec2(-width, -sink_depth - 20e-3), Vec2(width, -sink_depth)});
  sim.set_bounding_box(regions::Box<2>{Vec2(-width / 2 - 2e-3, -sink_depth - 10e-3),
                                       Vec2(width / 2 + 2e-3, wall_height)});

  // ------------------------------------------------------------------ run
  const auto ids = static_cast<std::size_t>(last_id + 1);
  Ledger ledger{0.0, std::vector<double>(ids, 0.0),
                std::vector<double>(ids, std::numeric_limits<double>::infinity())};
  // The settled bed, measured once when the gate starts to open: its height (twice the mean
  // centre height), its bulk density as a mass per unit area [kg/m^2] (its mass over its width
  // times its height) and the mean disk diameter [m].
  double bulk_density = std::numeric_limits<double>::quiet_NaN(), bed_height = 0.0, d_mean = 0.0;
  auto measure_bed = [&](const Sim& s) {
    if (!std::isnan(bulk_density) || s.time() < t_open) return;
    const auto st = io::statistics(s);
    bed_height = 2.0 * st.height.mean;
    bulk_density = st.mass.total / (width * bed_height);
    d_mean = 2.0 * st.radius.mean;
  };
  std::vector<std::pair<double, double>> discharge; // (t [s], discharged mass [kg])
  auto record = [&](const Sim& s) { discharge.emplace_back(s.time(), ledger.discharged_mass); };

  const std::string prefix = (out_dir / "hopper2d").string();
  std::printf("hopper2d: %zu glass disks poured into a %.0f mm wide silo; the %.0f mm orifice "
              "opens at %.2f s\n",
              n_disks, width * 1e3, orifice * 1e3, t_open);
  std::printf("     t [s]   active   removed   discharged [g]   mean speed [m/s]   contacts\n");
  auto log = [&](const Sim& s) {
    const auto st = io::statistics(s);
    std::printf("  %8.3f   %6zu   %7zu   %14.3f   %16.4f   %4zu + %3zu\n", s.time(), st.active,
                st.removed, ledger.discharged_mass * 1e3, st.particles ? st.speed.mean : 0.0,
                st.contacts, st.wall_contacts);
  };
  sim.run(
      end_time, io::summary(), ledger, measure_bed, io::every(0.05, log),
      io::every(0.02, io::vtk(prefix)),
      io::every(
          5e-3, record,
          io::csv(
              prefix + "_history.csv", io::column("active", [](const Sim& s) { return s.size(); }),
              io::column("removed", [](const Sim& s) { return io::statistics(s).removed; }),
              io::column("discharged_mass [kg]",
                         [&](const Sim&) { return ledger.discharged_mass; }),
              io::column("mean_speed [m/s]",
                         [](const Sim& s) {
                           const auto st = io::statistics(s);
                           return st.particles ? st.speed.mean : 0.0;
                         }),
              io::column("contacts_pp", [](const Sim& s) { return s.contact_counts().first; }),
              io::column("contacts_pw", [](const Sim& s) { return s.contact_counts().second; }))),
      io::progress());

  // ------------------------------------------------------------------ results
  // Disks still present must be between the side walls, and above the gate while it is closed.
  const auto& p = sim.particles();
  const bool opened = sim.time() >= t_open;
  std::size_t astray = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Vec2& x = p.position[i];
    astray += !(x.allFinite() && std::abs(x.x()) < width / 2 && (opened || x.y() > -gate_gap));
  }
  if (!opened) astray += ledger.discharged; // nothing may have gone through the closed gate
  const std::size_t left_silo = ledger.escaped + astray;
  double poured_mass = 0.0; // [kg]
  for (double m : ledger.mass)
    poured_mass += m;

  std::printf("\nhopper2d: after %.3f s, %zu of %zu disks poured, %zu discharged (%.3f g), "
              "%zu escaped, %zu out of place\n",
              sim.time(), n_disks - sim.inactive_count(), n_disks, ledger.discharged,
              ledger.discharged_mass * 1e3, ledger.escaped, astray);
  bool ok = left_silo == 0;
  if (sim.time() >= t_flowing && ledger.discharged == 0) {
    std::printf("  nothing was discharged although the gate opened at %.2f s\n", t_open);
    ok = false;
  }

  // The steady part: from t_flowing until 60 % of the poured mass has been discharged.
  std::vector<std::pair<double, double>> steady;
  for (const auto& [t, m] : discharge)
    if (t >= t_flowing && m <= 0.6 * poured_mass) steady.emplace_back(t, m);
  if (steady.size() >= 20) { // at least 0.1 s of flow
    constexpr double C = 1.0, k = 1.5;
    const double rate = slope(steady); // [kg/s]
    const double beverloo = C * bulk_density * std::sqrt(g) * std::pow(orifice - k * d_mean, 1.5);
    const double ratio = rate / beverloo;
    std::printf("  settled bed at %.2f s: height %.1f mm, bulk density %.3f kg/m^2 (mass per unit "
                "area)\n",
                t_open, bed_height * 1e3, bulk_density);
    std::printf("  steady discharge rate (linear fit over %.3f-%.3f s)   W = %.3f g/s\n",
                steady.front().first, steady.back().first, rate * 1e3);
    std::printf("  2D Beverloo law C rho_b sqrt(g) (D - k d)^(3/2) with C = %.1f, k = %.1f, "
                "D = %.1f mm, d = %.2f mm:   %.3f g/s\n",
                C, k, orifice * 1e3, d_mean * 1e3, beverloo * 1e3);
    std::printf("  ratio measured / Beverloo   %.3f  (sane range [0.3, 3])\n", ratio);
    ok = ok && ratio >= 0.3 && ratio <= 3.0;
  } else if (opened) {
    std::printf("  (too little steady flow for a discharge rate: run longer than %.2f s)\n",
                t_flowing + 0.1);
  } else {
    std::printf("  the gate opens at %.2f s: run longer for the discharge\n", t_open);
  }
  const bool pictures = draw_pictures(out_dir);
  std::printf("  output in %s: VTK series hopper2d_{particles,walls}.vtk.series; time history "
              "hopper2d_history.csv%s\n",
              std::filesystem::absolute(out_dir).lexically_normal().string().c_str(),
              pictures ? "; graphs hopper2d_discharge.png, hopper2d_history.png; picture "
                         "hopper2d_final.png"
                       : " (no graphs: scripts/grain_plot.py needs python3-matplotlib)");
  return ok ? 0 : 1;
}
