// Console output (io/console.hpp): io::print's aligned text, the end-of-run summary with the
// particle lifecycle, and the progress line of runs with and without an end time.
#include "../approx.hpp"
#include "../support/csv_files.hpp"
#include <doctest/doctest.h>
#include <grain/grain.hpp>

#include <cstdio>
#include <filesystem>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

using namespace grain;

namespace {

using Sim3 = Simulation<Sphere, search::AllPairs, Interaction<normal::Hertz<>>>;

std::vector<std::string> lines_in(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);)
    lines.push_back(l);
  return lines;
}

/// Everything written to a temporary FILE*.
std::string read_back(std::FILE* f) {
  std::fflush(f);
  std::rewind(f);
  std::string text;
  char buf[4096];
  for (std::size_t n; (n = std::fread(buf, 1, sizeof buf, f)) > 0;)
    text.append(buf, n);
  return text;
}

std::vector<std::string> words(const std::string& line) {
  std::vector<std::string> w;
  std::istringstream in(line);
  for (std::string s; in >> s;)
    w.push_back(s);
  return w;
}

/// A simulation of two free particles without gravity (no contacts), one removed at t = 2.5e-3 s,
/// and one waiting until a time after the run.
Sim3 lifecycle_sim() {
  Sim3::Params p;
  p.time_step = 1e-4;
  Sim3 sim(p);
  const auto m = sim.add_material({.name = "glass", .density = 2500, .young = 1e5});
  sim.add_particle(
      {.position = {0, 0, 0}, .radius = 1e-3, .material = m, .velocity = {1, 0, 0}, .id = 0});
  sim.add_particle({.position = {1, 0, 0},
                    .radius = 1e-3,
                    .material = m,
                    .velocity = {0, 2, 0},
                    .destruction_time = 25e-4,
                    .id = 1});
  sim.add_particle(
      {.position = {2, 0, 0}, .radius = 1e-3, .material = m, .creation_time = 1.0, .id = 2});
  return sim;
}

} // namespace

TEST_CASE("io::print to a text file: a header line, then aligned rows with the chosen columns") {
  auto sim = lifecycle_sim();
  const auto dir = std::filesystem::temp_directory_path() / "grain_print_test";
  std::filesystem::remove_all(dir);
  const auto path = dir / "print.txt";
  sim.steps(40,
            io::every_steps(
                10, io::print(path.string(),
                              io::column("speed_0 [m/s]",
                                         [](const Sim3& s) {
                                           return s.particles().velocity[s.index_of(0)].norm();
                                         }),
                              io::lifecycle_columns(), io::particle_columns({1}, io::position))));
  const auto lines = grain::test::lines_of(path);
  REQUIRE(lines.size() == 6); // header + steps 0, 10, 20, 30, 40
  const std::vector<std::string> names = {"time [s]", "step",     "speed_0 [m/s]",
                                          "active",   "inactive", "removed",
                                          "x_1 [m]",  "y_1 [m]",  "z_1 [m]"};
  // every line has the same length and each column ends where its header ends
  std::vector<std::size_t> ends;
  std::size_t from = 0;
  for (const auto& n : names) {
    const auto at = lines[0].find(n, from);
    REQUIRE(at != std::string::npos);
    ends.push_back(at + n.size());
    from = at + n.size();
  }
  CHECK(ends.back() == lines[0].size());
  for (std::size_t k = 1; k < lines.size(); ++k) {
    CAPTURE(lines[k]);
    CHECK(lines[k].size() == lines[0].size());
    for (const auto e : ends) {
      CHECK(lines[k][e - 1] != ' ');
      CHECK((e == lines[k].size() || lines[k][e] == ' '));
    }
    const auto w = words(lines[k]);
    REQUIRE(w.size() == names.size());
    const double t = std::stod(w[0]);
    const long step = std::stol(w[1]);
    CHECK(step == 10 * static_cast<long>(k - 1));
    CHECK(t == grain::test::approx(1e-4 * static_cast<double>(step)).epsilon(1e-5));
    CHECK(std::stod(w[2]) == grain::test::approx(1.0).epsilon(1e-6));
    const bool alive1 = step < 25;
    CHECK(std::stod(w[3]) == (alive1 ? 2 : 1));
    CHECK(std::stod(w[4]) == 1);
    CHECK(std::stod(w[5]) == (alive1 ? 0 : 1));
    if (alive1) {
      CHECK(std::stod(w[6]) == 1.0);
      CHECK(std::stod(w[7]) == grain::test::approx(2 * t).epsilon(1e-5).scale(1e-12));
    } else {
      CHECK(w[6] == "nan"); // a removed particle
      CHECK(w[8] == "nan");
    }
  }
  std::filesystem::remove_all(dir);
}

TEST_CASE("io::print to a stream with more digits, and a bad digits count") {
  auto sim = lifecycle_sim();
  std::FILE* f = std::tmpfile();
  REQUIRE(f != nullptr);
  auto out = io::print(f, io::particle_columns({0}, io::velocity));
  out.digits = 12;
  sim.steps(3, io::every_steps(3, out));
  const auto lines = lines_in(read_back(f));
  std::fclose(f);
  REQUIRE(lines.size() == 3);
  CHECK(words(lines[0]) == std::vector<std::string>{"time", "[s]", "step", "vx_0", "[m/s]", "vy_0",
                                                    "[m/s]", "vz_0", "[m/s]"});
  CHECK(words(lines[2]) == std::vector<std::string>{"0.0003", "3", "1", "0", "0"});
  auto bad = io::print(stderr, io::lifecycle_columns());
  bad.digits = 0;
  CHECK_THROWS_AS(sim.steps(1, io::every_steps(1, bad)), InputError);
  CHECK_THROWS_AS(io::print(std::string(), io::lifecycle_columns()), InputError);
}

TEST_CASE("print of io::summary: removed and waiting particles at the start and the end, none when "
          "there are none") {
  std::FILE* f = std::tmpfile();
  REQUIRE(f != nullptr);
  auto sim = lifecycle_sim();
  sim.run(40e-4, io::summary(f));
  const auto text = read_back(f);
  std::fclose(f);
  CAPTURE(text);
  CHECK(text.find("2 particles (1 more waiting for their creation time)") != std::string::npos);
  CHECK(text.find("t = 0 s -> 0.004 s (40 steps)") != std::string::npos);
  CHECK(text.find("particles: 1 active, 1 removed (1 in this run), 1 inactive (waiting for their "
                  "creation time)") != std::string::npos);

  std::FILE* g = std::tmpfile();
  REQUIRE(g != nullptr);
  Sim3 plain;
  const auto m = plain.add_material({.name = "glass", .density = 2500, .young = 1e7});
  plain.add_particle({.position = {0, 0, 0}, .radius = 1e-3, .material = m});
  plain.steps(5, io::summary(g)); // no end time: no "-> ..." span
  const auto quiet = read_back(g);
  std::fclose(g);
  CAPTURE(quiet);
  CHECK(quiet.find("1 particles,") != std::string::npos);
  CHECK(quiet.find("->") == std::string::npos);
  CHECK(quiet.find("removed") == std::string::npos);
  CHECK(quiet.find("finished at") != std::string::npos);
}

TEST_CASE("print of io::progress: share and time left in a run(), t and step only in steps(n)") {
  auto sim = lifecycle_sim();
  std::FILE* f = std::tmpfile();
  REQUIRE(f != nullptr);
  sim.run(10e-4, io::progress(0.0, f));
  const auto run_lines = lines_in(read_back(f));
  std::fclose(f);
  REQUIRE(!run_lines.empty());
  CHECK(run_lines.front().find("( 10.0 %), step 1,") != std::string::npos);
  CHECK(run_lines.back().find("(100.0 %), step 10,") != std::string::npos);
  CHECK(run_lines.back().find("time left 0.0 s") != std::string::npos);

  std::FILE* g = std::tmpfile();
  REQUIRE(g != nullptr);
  sim.steps(3, io::progress(0.0, g));
  const auto step_lines = lines_in(read_back(g));
  std::fclose(g);
  REQUIRE(step_lines.size() == 3); // after each step (the end is not printed twice)
  for (const auto& l : step_lines) {
    CHECK(l.find('%') == std::string::npos);
    CHECK(l.find("time left") == std::string::npos);
  }
  CHECK(step_lines.back().find("step 13,") != std::string::npos);
}
