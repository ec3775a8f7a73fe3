/// \file thermal_packing2d.cpp
/// Heat conduction through a static packing of disks between a hot and a cold wall (2D, thermal
/// analysis: particles never move; contacts and conductances are computed once).
///
/// 234 equal aluminium disks (R = 1 mm, 2 mm long cylinders) on a triangular lattice, 12 rows of
/// alternately 20 and 19 disks, each touching its six neighbours with an overlap of 10 um, fill
/// the space between a hot wall (left, 350 K) and a cold wall (right, 300 K); the top and bottom
/// walls are insulated. Conduction is Batchelor-O'Brien,
/// H = 4 k* a, through the Hertz contact radius.
///
/// A triangular network of equal conductances H under a uniform gradient dT/dx carries H dT/dx
/// times the x-extent of every bond crossing a vertical line: one horizontal bond per row (extent
/// p, the pitch) and one diagonal bond per gap between rows (extent p/2), so this strip of 12 rows
/// carries
///   Q = H p (12 + 11/2) dT/dx   [W],
/// (an unbounded lattice: sqrt(3) H dT/dx per unit height). The program compares the heat flow
/// through the hot wall at the end with this value and the gradient between interior columns.
///
/// Usage: thermal_packing2d [end_time_s] [output_dir]
///   end_time_s  simulated time [s] (default 400)
///   output_dir  folder for the VTK series (default out/thermal_packing2d)
///
/// Output: a temperature profile (column means) every 40 s, VTK files every 40 s, and the
/// effective conductance at the end. Exits with status 1 if a temperature leaves [300, 350] K
/// or, once steady (the hot and cold walls' heat flows agree to 1e-4), the conductance differs
/// from the network value by more than 1e-3.

#include <grain/grain.hpp>

#include "example_support.hpp"
#include <grain/models/conduction/batchelor_obrien.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

using namespace grain;

using Contact =
    Interaction<normal::Hertz<>, tangent::None, rolling::None, conduction::BatchelorOBrien>;
using Sim = Simulation<Disk, search::CellList, Contact>;

int main(int argc, char** argv) {
  double end_time = 400.0; // [s]
  std::filesystem::path out_dir = "out/thermal_packing2d";
  if (!example::parse_arguments(argc, argv, "thermal_packing2d", end_time, out_dir)) return 2;

  constexpr int columns = 20, rows = 12;
  constexpr double R = 1e-3, overlap = 1e-5;
  const double pitch = 2.0 * R - overlap; // centre distance [m]
  const double row_height = pitch * std::sqrt(3.0) / 2.0;
  const double hot = 350.0, cold = 300.0; // [K]

  Sim::Params params;
  params.analysis = Analysis::thermal;
  params.initial_temperature = cold;
  // time step 0.02 s, below the conduction limit C/(6H) = 0.09 s of a disk with six contacts
  // (the automatic choice, 0.1 R^2 rho c / k = 1.2 ms, is safe for any packing but slower)
  params.time_step = 0.02;
  Sim sim(params, Disk{.thickness = 2.0 * R});
  const auto alu = sim.add_material({.name = "aluminium",
                                     .density = 2700.0,
                                     .young = 7e10,
                                     .poisson = 0.33,
                                     .conductivity = 200.0,
                                     .heat_capacity = 900.0});

  // Rows alternate between 20 disks and 19 disks shifted by half a pitch. The walls touch the
  // outermost disks with half the overlap of two disks, which gives the same Hertz contact radius
  // sqrt(R* delta) and so the same conductance H.
  const double wall_overlap = overlap / 2.0;
  const double x_first = R - wall_overlap;
  const double x_right = x_first + (columns - 1) * pitch + R - wall_overlap;
  const double top = (rows - 1) * row_height + 2.0 * R;
  std::vector<int> column_of;
  for (int j = 0; j < rows; ++j)
    for (int i = 0; i < columns - (j % 2); ++i) {
      const double x = x_first + i * pitch + (j % 2) * pitch / 2.0;
      sim.add_particle({.position = Vec2(x, R + j * row_height), .radius = R, .material = alu});
      column_of.push_back(i);
    }
  sim.add_wall(walls::Segment{Vec2(0, 0), Vec2(0, top)},
               {.name = "hot", .material = alu, .temperature = TimeFunction(hot)});
  sim.add_wall(walls::Segment{Vec2(x_right, 0), Vec2(x_right, top)},
               {.name = "cold", .material = alu, .temperature = TimeFunction(cold)});
  sim.add_wall(walls::Segment{Vec2(0, 0), Vec2(x_right, 0)}, {.name = "bottom", .material = alu});
  sim.add_wall(walls::Segment{Vec2(0, top), Vec2(x_right, top)}, {.name = "top", .material = alu});
  sim.initialize();

  auto column_means = [&](const Sim& s) {
    std::vector<double> sum(columns, 0.0), count(columns, 0.0);
    const auto& p = s.particles();
    for (std::size_t i = 0; i < p.size(); ++i) {
      const int c = column_of[static_cast<std::size_t>(p.id[i])];
      sum[c] += p.temperature[i];
      count[c] += 1.0;
    }
    for (int c = 0; c < columns; ++c)
      sum[c] /= count[c];
    return sum;
  };
  std::printf(
      "thermal_packing2d: %zu aluminium disks between walls at %.0f K and %.0f K, time step "
      "%.3g s\n",
      sim.size(), hot, cold, sim.time_step());
  auto log = [&](const Sim& s) {
    const auto t = column_means(s);
    std::printf("  t = %6.0f s  column means [K]:", s.time());
    for (int c = 0; c < columns; c += 3)
      std::printf(" %7.3f", t[c]);
    std::printf("\n");
  };
  const std::string prefix = (out_dir / "thermal_packing2d").string();
  sim.run(end_time, io::every(40.0, log), io::every(40.0, io::vtk(prefix)));

  // conductance of the strip against the network value
  const auto& p = sim.particles();
  // heat through the hot wall: its conductance H to each disk of the first column of the long rows
  const double H = 4.0 * 100.0 * std::sqrt(R / 2.0 * overlap); // 4 k* a, k* = k/2
  double q_hot = 0.0, q_cold = 0.0;                            // [W] into the packing, out of it
  const double x_last = x_first + (columns - 1) * pitch;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.position[i].x() < x_first + 1e-9) q_hot += H * (hot - p.temperature[i]);
    if (p.position[i].x() > x_last - 1e-9) q_cold += H * (p.temperature[i] - cold);
  }
  const bool steady = std::abs(q_hot - q_cold) < 1e-4 * q_hot;
  const auto t = column_means(sim);
  const double gradient = (t[5] - t[14]) / (9.0 * pitch);       // [K/m]
  const double network = H * pitch * (rows + 0.5 * (rows - 1)); // [W m / K]
  const double measured = q_hot / gradient;
  bool ok = !steady || std::abs(measured / network - 1.0) < 1e-3;
  for (double T : p.temperature)
    ok = ok && T >= cold - 1e-9 && T <= hot + 1e-9;
  std::printf("\n  heat through the hot wall %.5g W, through the cold wall %.5g W (%s); interior "
              "gradient %.4g K/m\n",
              q_hot, q_cold, steady ? "steady" : "not steady yet: run longer for the comparison",
              gradient);
  std::printf("  conductance of the strip Q/(dT/dx) = %.6g W m/K; network value H p (12 + 11/2) = "
              "%.6g W m/K (ratio %.6f)\n",
              measured, network, measured / network);
  std::printf(
      "  per unit height %.5g W/K (an unbounded triangular lattice: sqrt(3) H = %.5g W/K)\n",
      measured / (rows * row_height), std::sqrt(3.0) * H);
  std::printf("  output: VTK series in %s\n",
              std::filesystem::absolute(out_dir).lexically_normal().string().c_str());
  return ok ? 0 : 1;
}
