// Output folders that cannot be made or written are refused before the first step, with the
// writer, the path and the reason; a negative step count is refused.
#include "../errors.hpp"
#include "../support/csv_files.hpp"
#include <doctest/doctest.h>
#include <grain/grain.hpp>

#include <filesystem>
#include <fstream>
#include <string>

using namespace grain;

namespace {

using Contact = Interaction<normal::Hertz<>, tangent::Mindlin>;
using Sim = Simulation<Sphere, search::CellList, Contact>;

/// Two spheres falling onto a plane.
Sim falling() {
  Sim sim({.time_step = 1e-6, .gravity = Vec3(0, 0, -9.81)});
  const auto m = sim.add_material(
      {.density = 2500, .young = 1e7, .poisson = 0.25, .restitution = 0.5, .friction = 0.5});
  sim.add_particle({.position = Vec3(0, 0, 2e-3), .radius = 1e-3, .material = m});
  sim.add_particle({.position = Vec3(3e-3, 0, 2e-3), .radius = 1e-3, .material = m});
  sim.add_wall(walls::Plane{Vec3::Zero(), Vec3::UnitZ()}, {.material = m});
  return sim;
}

/// A scratch folder holding a regular file named `blocker`: a path through it cannot be made.
std::filesystem::path blocked_folder() {
  const auto dir = test::scratch("grain_output_folder_test", test::Folder::empty);
  std::ofstream(dir / "blocker") << "a file, not a folder\n";
  return dir / "blocker" / "out";
}

} // namespace

TEST_CASE("an output folder that cannot be made stops the run before its first step") {
  const auto bad = blocked_folder();
  SUBCASE("io::vtk") {
    auto sim = falling();
    const auto msg =
        test::error_of([&] { sim.run(1e-4, io::every(1e-5, io::vtk((bad / "drop").string()))); });
    CHECK(test::has(msg, {"grain::io::vtk: path = '", "blocker", "' is invalid: the folder",
                          "cannot be made", "valid: a path in a folder"}));
    CHECK(sim.step_count() == 0);
  }
  SUBCASE("io::csv") {
    auto sim = falling();
    const auto msg = test::error_of([&] {
      sim.run(1e-4, io::every(1e-5, io::history((bad / "h.csv").string(),
                                                io::column("ke", [](const Sim& s) {
                                                  return s.kinetic_energy();
                                                }))));
    });
    CHECK(test::has(msg, {"grain::io::csv: path = '", "h.csv' is invalid", "cannot be made"}));
    CHECK(sim.step_count() == 0);
  }
  SUBCASE("io::print to a file") {
    auto sim = falling();
    const auto msg = test::error_of(
        [&] { sim.run(1e-4, io::every(1e-5, io::print((bad / "p.txt").string()))); });
    CHECK(test::has(msg, {"grain::io::print: path = '", "p.txt' is invalid", "cannot be made"}));
    CHECK(sim.step_count() == 0);
  }
  SUBCASE("io::save_checkpoint") {
    auto sim = falling();
    sim.steps(3);
    const auto msg = test::error_of([&] { io::save_checkpoint(sim, (bad / "c.bin").string()); });
    CHECK(test::has(msg, {"grain::io::save_checkpoint: path = '", "c.bin' is invalid"}));
  }
}

TEST_CASE("a writable output folder is made and left without a trace of the check") {
  const auto dir = test::scratch("grain_output_folder_ok") / "a" / "b";
  auto sim = falling();
  sim.run(1e-5, io::every(1e-5, io::vtk((dir / "drop").string())));
  CHECK(std::filesystem::is_directory(dir));
  CHECK_FALSE(std::filesystem::exists(dir / ".grain_write_test"));
  CHECK(std::filesystem::exists(dir / "drop_particles.vtk.series"));
}

TEST_CASE("a negative number of steps is refused") {
  auto sim = falling();
  const auto msg = test::error_of([&] { sim.steps(-3); });
  CHECK(test::has(msg, "Simulation::steps: n = -3 is invalid; valid range: [0, inf)"));
  CHECK(sim.step_count() == 0);
}
