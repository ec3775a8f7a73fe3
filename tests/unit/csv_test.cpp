// CSV time histories (io/csv.hpp): header, one flushed row per output, values equal to the
// simulation's own figures.
#include <doctest/doctest.h>
#include "../approx.hpp"
#include <grain/grain.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

using namespace grain;

namespace {

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> out;
  std::string cell;
  std::istringstream in(line);
  while (std::getline(in, cell, ',')) out.push_back(cell);
  return out;
}

std::vector<std::string> lines_of(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::vector<std::string> lines;
  for (std::string l; std::getline(in, l);) lines.push_back(l);
  return lines;
}

} // namespace

TEST_CASE("io::history writes the global quantities of a thermal simulation, flushed row by row") {
  using Contact = Interaction<normal::Hertz<>, tangent::None, rolling::None,
                              conduction::BatchelorOBrien>;
  using Sim = Simulation<Sphere, search::AllPairs, Contact>;
  Sim::Params p;
  p.gravity = {0, 0, -9.81};
  Sim sim(p);
  const auto m = sim.add_material({.name = "steel", .density = 7800, .young = 2e9, .poisson = 0.3,
                                   .conductivity = 40, .heat_capacity = 500});
  sim.add_wall(walls::Plane{{0, 0, 0}, {0, 0, 1}}, {.material = m, .temperature = 400.0});
  // resting on the wall near its static Hertz overlap (5.3e-7 m)
  sim.add_particle({.position = {0, 0, 0.005 - 5e-7}, .radius = 0.005, .material = m,
                    .temperature = 300});
  const auto dir = std::filesystem::temp_directory_path() / "grain_csv_test";
  std::filesystem::remove_all(dir);
  const auto path = dir / "history.csv";
  sim.initialize();
  const double interval = 20 * sim.time_step();
  std::size_t rows_seen_during_run = 0;
  auto probe = [&](const Sim&) { rows_seen_during_run = lines_of(path).size(); };
  sim.steps(200, io::every(interval,
                           io::history(path.string(),
                                       io::column("z [m]",
                                                  [](const Sim& s) {
                                                    return s.particles().position[0].z();
                                                  })),
                           probe));
  const auto lines = lines_of(path);
  // header + rows at steps 0, 20, ..., 200
  REQUIRE(lines.size() == 12);
  CHECK(lines[0] == "time [s],step,particles,contacts_pp,contacts_pw,kinetic_energy [J],"
                    "potential_energy [J],elastic_energy [J],mean_temperature [K],heat_content "
                    "[J],heat_inflow [W],z [m]");
  // the probe runs after the writer in the same output: each row is on disk when written
  CHECK(rows_seen_during_run == 12);
  const auto last = split(lines.back());
  REQUIRE(last.size() == 12);
  CHECK(std::stod(last[0]) == grain::test::approx(sim.time()).epsilon(1e-15));
  CHECK(std::stol(last[1]) == 200);
  CHECK(std::stol(last[2]) == 1);
  CHECK(std::stol(last[4]) == 1); // resting on the wall
  CHECK(std::stod(last[5]) == grain::test::approx(sim.kinetic_energy()).epsilon(1e-15));
  CHECK(std::stod(last[8]) == grain::test::approx(sim.mean_temperature()).epsilon(1e-15));
  CHECK(std::stod(last[9]) == grain::test::approx(sim.thermal_energy()).epsilon(1e-15));
  CHECK(std::stod(last[10]) == grain::test::approx(sim.particles().heat_rate[0]).epsilon(1e-15));
  CHECK(std::stod(last[10]) > 0.0); // the hot wall heats the sphere
  CHECK(std::stod(last[11]) == grain::test::approx(sim.particles().position[0].z()).epsilon(1e-15));
  for (std::size_t k = 2; k < lines.size(); ++k)
    CHECK(std::stod(split(lines[k])[0]) > std::stod(split(lines[k - 1])[0]));
  std::filesystem::remove_all(dir);
}

TEST_CASE("io::csv of a mechanical simulation: time, step and the chosen columns only") {
  using Sim = Simulation<Disk, search::AllPairs, Interaction<normal::Hertz<>>>;
  Sim sim;
  const auto m = sim.add_material({.name = "glass", .density = 2500, .young = 1e7});
  sim.add_particle({.position = {0, 0}, .radius = 1e-3, .material = m, .velocity = {1, 0}});
  const auto dir = std::filesystem::temp_directory_path() / "grain_csv_test2";
  std::filesystem::remove_all(dir);
  const auto path = (dir / "x.csv").string();
  sim.initialize();
  sim.steps(10, io::every(5 * sim.time_step(),
                          io::csv(path, io::column("x, centre [m]", [](const Sim& s) {
                                    return s.particles().position[0].x();
                                  }))));
  const auto lines = lines_of(path);
  REQUIRE(lines.size() == 4);
  CHECK(lines[0] == "time [s],step,\"x, centre [m]\"");
  CHECK(std::stod(split(lines[3])[2]) == grain::test::approx(10 * sim.time_step()).epsilon(1e-12));
  std::filesystem::remove_all(dir);
}
