/// \file servo2d.cpp
/// A servo-controlled lid compresses a 2D packing of disks to a target stress.
///
/// 300 disks (radii 0.8-1.2 mm, with the mass of spheres, a fixed seed) fall into a 30 mm wide box
/// and are pressed by a lid, a segment driven by a user stage (servo_wall.hpp) that measures the
/// force on the lid after each force evaluation and sets its velocity from the stress error:
/// v = clamp(gain (sigma_target - sigma), -v_max, v_max). Stresses are forces per area of the lid
/// times a layer one mean diameter (2 mm) thick; the target, 20 kPa, is about 40 times the weight
/// of the bed per area of the floor. The lid reaches the bed after about 0.27 s and holds the
/// target from about 0.3 s.
///
/// Usage: servo2d [end_time_s] [output_dir]
///   end_time_s  simulated time [s] (default 0.4)
///   output_dir  folder for the VTK series and the stress history (default out/servo2d)
///
/// Output: the stress on the lid and its height every 0.01 s (console and
/// output_dir/servo2d_stress.csv), VTK files every 0.05 s. At the end the program compares the
/// stress with the target, and the sum of the forces on all walls with the weight of the bed;
/// it exits with status 1 if a full run (end time >= 0.35 s) misses the target by more than 2 %.

#include <grain/grain.hpp>

#include "example_support.hpp"
#include "servo_wall.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>

using namespace grain;

using Contact = Interaction<normal::LinearSpringDashpot, tangent::SpringDashpotSlider>;
using Sim = Simulation<Disk, search::CellList, Contact, stages<ServoWall<2>>>;

int main(int argc, char** argv) {
  double end_time = 0.4; // [s]
  std::filesystem::path out_dir = "out/servo2d";
  if (!example::parse_arguments(argc, argv, "servo2d", end_time, out_dir)) return 2;
  std::filesystem::create_directories(out_dir);

  // ------------------------------------------------------------------ set-up
  constexpr int nx = 12, ny = 25;               // lattice of starting positions: 300 disks
  constexpr double spacing = 2.5e-3;            // [m]
  constexpr double width = nx * spacing;        // inner width of the box [m]
  constexpr double height = (ny + 2) * spacing; // starting height of the lid [m]
  constexpr double target = 2e4;                // target stress on the lid [Pa]
  constexpr double layer = 2e-3;                // thickness of the layer (mean diameter) [m]

  Sim::Params params;
  params.gravity = Vec2(0.0, -9.81);
  Sim sim(params, Disk{.sphere_mass = true});
  const auto m = sim.add_material({.name = "soft glass",
                                   .density = 2500.0,
                                   .young = 5e7,
                                   .poisson = 0.25,
                                   .restitution = 0.3,
                                   .friction = 0.3});
  const auto floor =
      sim.add_wall(walls::Segment{Vec2(0, 0), Vec2(width, 0)}, {.name = "floor", .material = m});
  sim.add_wall(walls::Segment{Vec2(0, 0), Vec2(0, 2 * height)}, {.name = "left", .material = m});
  sim.add_wall(walls::Segment{Vec2(width, 0), Vec2(width, 2 * height)},
               {.name = "right", .material = m});
  const auto lid = sim.add_wall(walls::Segment{Vec2(0, height), Vec2(width, height)},
                                {.name = "lid", .material = m});
  example::Random rng{7};
  double weight = 0.0; // [N]
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const double r = rng.uniform(0.8e-3, 1.2e-3);
      sim.add_particle(
          {.position = Vec2((i + 0.5) * spacing + rng.uniform(-1e-4, 1e-4), (j + 0.5) * spacing),
           .radius = r,
           .material = m});
      weight += 2500.0 * 4.0 / 3.0 * std::numbers::pi * r * r * r * 9.81;
    }

  auto& servo = sim.stage<ServoWall<2>>();
  servo.wall = lid;
  servo.area = width * layer; // lid length x layer thickness [m^2]
  servo.target = target;
  servo.gain = 1e-5;     // [m/(s Pa)]: 1 kPa of error moves the lid at 10 mm/s
  servo.max_speed = 0.1; // [m/s]

  // ------------------------------------------------------------------ run
  std::ofstream csv(out_dir / "servo2d_stress.csv");
  csv << "time_s,stress_Pa,lid_height_m\n";
  auto lid_height = [&](const Sim& s) {
    return std::get<walls::Segment>(s.walls()[lid].geometry).a.y();
  };
  auto log = [&](const Sim& s) {
    const double sigma = s.stage<ServoWall<2>>().stress;
    csv << s.time() << ',' << sigma << ',' << lid_height(s) << '\n';
    std::printf("  t = %5.3f s   lid stress %9.1f Pa   lid height %.4f mm\n", s.time(), sigma,
                1e3 * lid_height(s));
  };
  const std::string prefix = (out_dir / "servo2d").string();
  sim.run(end_time, io::summary(), io::every(0.01, log), io::every(0.05, io::vtk(prefix)));

  // ------------------------------------------------------------------ results
  // at rest, the walls carry the weight of the bed: the sum of their forces is the weight
  Vec2 sum = Vec2::Zero();
  for (std::size_t w = 0; w < sim.walls().size(); ++w)
    sum += sim.wall_force(w);
  const double sigma = servo.stress;
  std::printf("lid stress %.1f Pa (target %.1f Pa, error %.2f %%); floor force %.4f N;\n"
              "sum of wall forces (%.3f, %.3f) N vs weight (0, %.3f) N; kinetic energy %.3e J\n",
              sigma, target, 100.0 * (sigma - target) / target, sim.wall_force(floor).y(), sum.x(),
              sum.y(), -weight, sim.kinetic_energy());
  if (end_time >= 0.35 && std::abs(sigma - target) > 0.02 * target) {
    std::printf("the lid did not reach the target stress\n");
    return 1;
  }
  return 0;
}
