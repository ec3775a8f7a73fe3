/// \file compare_conduction.cpp
/// The direct conduction models, and the contact-area corrections, compared on one heated packed
/// bed of disks (2D), with io::compare.
///
/// The bed: 154 aluminium disks (radii 0.8-1.2 mm from a fixed seed, cylinders 2 mm long) fall
/// from a loose lattice into a box 30 mm wide and settle under gravity (a mechanical run of
/// 0.3 s with a softened Young's modulus of 1e8 Pa against the real 7e10 Pa, Hertz with
/// spring-dashpot-slider friction). The settled positions are kept, so every variant heats the
/// same packing: a thermal analysis (disks at rest, contacts and conductances computed once) of
/// disks at 300 K on a bottom wall held at 400 K; the side walls are insulated.
///
/// The variants (each an Interaction type; io::compare instantiates one Simulation per type):
/// - direct conduction with the Hertz contact radius of the simulated overlap (area::None):
///   conduction::BatchelorOBrien, conduction::ThermalPipe, conduction::Collisional;
/// - Batchelor-O'Brien with the area corrections area::Geometric, area::ZhouYuZulli,
///   area::MorrisPannalaMaHrenya and area::LuMorrisLiBenyahia.
/// In a bed at rest no contact starts with an impact, so the collisional model conducts as
/// Batchelor-O'Brien throughout: its row must equal that one (a check of the program). Likewise
/// Lu-Morris-Li-Benyahia, which differs from Morris-Pannala-Ma-Hrenya by the damping part of the
/// normal force only, gives the same radius at rest.
///
/// Figures per variant: the mean temperature at the end, T_mean [K]; heat_flow_pp and
/// heat_flow_pw (io::heat_flow_columns) [W]; the time [s] at which T_mean reaches 310 K; the
/// lowest and highest temperatures T_min, T_max [K]; and the speed (particle-steps per second,
/// the fastest of five runs). The whole program takes about 7 s, most of it to settle the bed.
///
/// Usage: compare_conduction [end_time_s] [output_dir]
///   end_time_s  simulated heating time of each variant [s] (default 60)
///   output_dir  folder for the output (default out/compare_conduction)
///
/// Output: the table on the console and as compare_conduction.csv, a history of the figures per
/// variant (history_<variant>.csv, every 0.5 s) and, with Python and matplotlib, the graph
/// compare_conduction_mean_temperature.png of the mean temperature of every variant. Exits with
/// status 1 if a temperature leaves [300, 400] K, if the collisional row differs from the
/// Batchelor-O'Brien one, or if the Zhou-Yu-Zulli correction (which scales every contact radius
/// by (E/E_real)^(1/5) < 1) does not heat the bed more slowly than the uncorrected radius.

#include <grain/grain.hpp>

#include "example_support.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <type_traits>
#include <vector>

using namespace grain;

namespace {

constexpr double box_width = 0.030;                                // [m]
constexpr double r_min = 0.8e-3, r_max = 1.2e-3;                   // disk radii [m]
constexpr double thickness = 2e-3;                                 // disk (cylinder) length [m]
constexpr double bed_temperature = 300.0, hot_temperature = 400.0; // [K]
constexpr double threshold = 310.0;                                // [K]

/// Aluminium, softened for the simulation: young is the simulated modulus, young_real the real
/// one that the area corrections use.
const Material aluminium{.name = "aluminium (softened)",
                         .density = 2700.0, // [kg/m^3]
                         .young = 1e8,      // simulated [Pa]
                         .poisson = 0.33,
                         .young_real = 7e10, // real [Pa]
                         .restitution = 0.3,
                         .friction = 0.4,
                         .conductivity = 200.0,   // [W/(m K)]
                         .heat_capacity = 900.0}; // [J/(kg K)]

struct BedDisk {
  Vec2 position;
  double radius;
};

/// Settles the disks in the box (a mechanical run) and returns where they came to rest.
std::vector<BedDisk> settled_bed(double& kinetic_energy) {
  using Contact = Interaction<normal::Hertz<>, tangent::SpringDashpotSlider>;
  using Sim = Simulation<Disk, search::CellList, Contact>;
  Sim::Params params;
  params.gravity = Vec2(0.0, -9.81);   // [m/s^2]
  params.damping_translational = 2e-4; // [N s/m], helps the bed come to rest
  Sim sim(params, Disk{.thickness = thickness});
  const auto m = sim.add_material(aluminium);
  const double top = 0.05;
  sim.add_wall(walls::Segment{Vec2(0.0, 0.0), Vec2(box_width, 0.0)}, {.material = m});
  sim.add_wall(walls::Segment{Vec2(0.0, 0.0), Vec2(0.0, top)}, {.material = m});
  sim.add_wall(walls::Segment{Vec2(box_width, 0.0), Vec2(box_width, top)}, {.material = m});
  example::Random rng{11};
  constexpr double spacing = 2.6e-3; // [m]
  for (int j = 0; j < 14; ++j)
    for (int i = 0; i < 11; ++i)
      sim.add_particle(
          {.position = Vec2(1.6e-3 + i * spacing + (j % 2) * 0.3e-3, 1.3e-3 + j * spacing),
           .radius = rng.uniform(r_min, r_max),
           .material = m});
  sim.run(0.3);
  kinetic_energy = sim.kinetic_energy();
  std::vector<BedDisk> bed;
  const auto& p = sim.particles();
  for (std::size_t i = 0; i < p.size(); ++i)
    bed.push_back({p.position[i], p.radius[i]});
  return bed;
}

template <class Contact>
using Bed = Simulation<Disk, search::CellList, Contact>;

template <class Conduction, class Area = area::None>
using Heat = Interaction<normal::Hertz<>, tangent::None, rolling::None, Conduction, Area>;

/// A command-line argument in single quotes for the shell.
std::string quoted(const std::string& s) {
  std::string q = "'";
  for (char c : s)
    q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

} // namespace

int main(int argc, char** argv) {
  double end_time = 60.0; // [s]
  std::filesystem::path out_dir = "out/compare_conduction";
  if (!example::parse_arguments(argc, argv, "compare_conduction", end_time, out_dir)) return 2;

  // ------------------------------------------------------------------ the packing
  double settle_energy = 0.0;
  const std::vector<BedDisk> bed = settled_bed(settle_energy);
  double height = 0.0;
  for (const auto& d : bed)
    height = std::max(height, d.position.y() + d.radius);
  std::printf("compare_conduction: %zu aluminium disks settled in a box %.0f mm wide, %.1f mm "
              "high (kinetic energy left %.2g J); heated from below at %.0f K for %g s\n",
              bed.size(), box_width * 1e3, height * 1e3, settle_energy, hot_temperature, end_time);

  // ------------------------------------------------------------------ the variants
  // Every variant builds the same bed; thermal analysis with one time step for all, below the
  // conduction limit of the most conductive variant.
  auto scenario = [&bed]<class Sim>(std::type_identity<Sim>) {
    typename Sim::Params params;
    params.analysis = Analysis::thermal;
    params.time_step = 0.005; // [s]
    params.initial_temperature = bed_temperature;
    Sim sim(params, Disk{.thickness = thickness});
    const auto m = sim.add_material(aluminium);
    for (const auto& d : bed)
      sim.add_particle({.position = d.position, .radius = d.radius, .material = m});
    sim.add_wall(walls::Segment{Vec2(0.0, 0.0), Vec2(box_width, 0.0)},
                 {.name = "hot", .material = m, .temperature = TimeFunction(hot_temperature)});
    sim.add_wall(walls::Segment{Vec2(0.0, 0.0), Vec2(0.0, 0.05)}, {.material = m});
    sim.add_wall(walls::Segment{Vec2(box_width, 0.0), Vec2(box_width, 0.05)}, {.material = m});
    return sim;
  };
  auto mean_temperature = [](const auto& s) { return s.mean_temperature(); };
  std::filesystem::create_directories(out_dir);
  const auto table = io::compare<Bed>(
      variants<Heat<conduction::BatchelorOBrien>, Heat<conduction::ThermalPipe>,
               Heat<conduction::Collisional>, Heat<conduction::BatchelorOBrien, area::Geometric>,
               Heat<conduction::BatchelorOBrien, area::ZhouYuZulli>,
               Heat<conduction::BatchelorOBrien, area::MorrisPannalaMaHrenya>,
               Heat<conduction::BatchelorOBrien, area::LuMorrisLiBenyahia>>{},
      scenario,
      {.duration = end_time,
       .csv = (out_dir / "compare_conduction.csv").string(),
       .history = (out_dir / "history_").string(),
       .history_interval = 0.5,
       .repeats = 5},
      io::column("T_mean [K]", mean_temperature), io::heat_flow_columns(),
      io::time_to_reach("t(T_mean = 310 K) [s]", threshold, mean_temperature),
      io::column("T_min [K]",
                 [](const auto& s) {
                   const auto& t = s.particles().temperature;
                   return *std::min_element(t.begin(), t.end());
                 }),
      io::column("T_max [K]", [](const auto& s) {
        const auto& t = s.particles().temperature;
        return *std::max_element(t.begin(), t.end());
      }));

  // ------------------------------------------------------------------ checks and graph
  bool ok = true;
  for (const auto& r : table.rows) {
    const double lo = table.figure(r.name, "T_min [K]");
    const double hi = table.figure(r.name, "T_max [K]");
    if (!(lo >= bed_temperature - 1e-9 && hi <= hot_temperature + 1e-9)) {
      std::printf("  %s: temperatures [%g, %g] K leave [%g, %g] K\n", r.name.c_str(), lo, hi,
                  bed_temperature, hot_temperature);
      ok = false;
    }
  }
  const auto& bob = table["Batchelor-O'Brien, none"];
  const auto& collisional = table["collisional, none"].figures;
  bool same = collisional.size() == bob.figures.size();
  for (std::size_t k = 0; same && k < collisional.size(); ++k) // nan: a threshold not reached
    same = collisional[k] == bob.figures[k] ||
           (std::isnan(collisional[k]) && std::isnan(bob.figures[k]));
  if (!same) {
    std::printf("  the collisional model differs from Batchelor-O'Brien in a bed at rest\n");
    ok = false;
  }
  const double heated = bob.figures[0] - bed_temperature;
  const double heated_zyz =
      table.figure("Batchelor-O'Brien, Zhou-Yu-Zulli", "T_mean [K]") - bed_temperature;
  if (!(heated > 0.0 && heated_zyz > 0.0 && heated_zyz < heated)) {
    std::printf("  Zhou-Yu-Zulli does not heat the bed more slowly than the Hertz radius\n");
    ok = false;
  }

  std::string args = "lines";
  for (const auto& r : table.rows)
    args += " " + quoted(r.history);
  args += " -y T_mean";
  for (const auto& r : table.rows)
    args += " --label " + quoted(r.name);
  const std::string graph = (out_dir / "compare_conduction_mean_temperature.png").string();
  args += " --title " + quoted("mean temperature of the bed, heated from below at 400 K") + " -o " +
          quoted(graph);
  const bool drawn = example::plot(args);
  std::printf("\n  output in %s: compare_conduction.csv, history_*.csv%s\n",
              std::filesystem::absolute(out_dir).lexically_normal().string().c_str(),
              drawn ? ", compare_conduction_mean_temperature.png"
                    : " (no graph: scripts/grain_plot.py needs python3-matplotlib)");
  return ok ? 0 : 1;
}
