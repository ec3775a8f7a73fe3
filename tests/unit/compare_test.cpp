// Comparing model variants (io/compare.hpp): one row per variant, figures equal to those of the
// same simulation run by hand, the table as CSV, the histories, and the input errors.
#include "../approx.hpp"
#include "../support/csv_files.hpp"
#include <doctest/doctest.h>
#include <grain/grain.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <type_traits>
#include <vector>

using namespace grain;

namespace {

using grain::test::lines_of;
using grain::test::scratch;
using grain::test::split;

using BOB = Interaction<normal::Hertz<>, tangent::None, rolling::None, conduction::BatchelorOBrien>;
using BOBZhou = Interaction<normal::Hertz<>, tangent::None, rolling::None,
                            conduction::BatchelorOBrien, area::ZhouYuZulli>;
using Pipe = Interaction<normal::Hertz<>, tangent::None, rolling::None, conduction::ThermalPipe>;

template <class Contact>
using Column = Simulation<Disk, search::AllPairs, Contact>;

constexpr double R = 1e-3;          // [m]
constexpr double overlap = 1e-5;    // between two disks [m]
constexpr double hot = 400.0;       // [K]
constexpr double threshold = 310.0; // [K]
constexpr double duration = 2.0;    // [s]

/// Three aluminium disks stacked on a hot floor, thermal analysis (the contacts never change).
template <class Sim>
Sim make_column(double time_step = 0.01) {
  typename Sim::Params p;
  p.analysis = Analysis::thermal;
  p.time_step = time_step;
  p.initial_temperature = 300.0;
  Sim sim(p, Disk{.thickness = 2 * R});
  const auto alu = sim.add_material({.name = "aluminium",
                                     .density = 2700,
                                     .young = 7e10,
                                     .poisson = 0.33,
                                     .conductivity = 200,
                                     .heat_capacity = 900});
  for (int k = 0; k < 3; ++k)
    sim.add_particle({.position = Vec2(0, R - overlap / 2 + k * (2 * R - overlap)),
                      .radius = R,
                      .material = alu});
  sim.add_wall(walls::Segment{Vec2(-0.01, 0), Vec2(0.01, 0)},
               {.name = "floor", .material = alu, .temperature = TimeFunction(hot)});
  return sim;
}

const auto column_scenario = []<class Sim>(std::type_identity<Sim>) { return make_column<Sim>(); };

auto mean_temperature() {
  return io::column("mean_temperature [K]", [](const auto& s) { return s.mean_temperature(); });
}
auto time_to_threshold() {
  return io::time_to_reach("t_310 [s]", threshold,
                           [](const auto& s) { return s.mean_temperature(); });
}

/// The figures of a variant run by hand: mean temperature, heat_flow_pp, heat_flow_pw and the
/// time at which the mean temperature reaches the threshold (stepping one step at a time).
template <class Sim>
std::vector<double> by_hand() {
  Sim sim = make_column<Sim>();
  sim.initialize();
  double t_prev = sim.time(), v_prev = sim.mean_temperature();
  double reached = std::nan("");
  const long n = static_cast<long>(std::ceil(duration / sim.time_step() - 1e-9));
  for (long k = 0; k < n; ++k) {
    sim.step();
    const double t = sim.time(), v = sim.mean_temperature();
    if (std::isnan(reached) && v >= threshold)
      reached = t_prev + (threshold - v_prev) / (v - v_prev) * (t - t_prev);
    t_prev = t;
    v_prev = v;
  }
  std::vector<double> out{sim.mean_temperature()};
  io::heat_flow_columns().values(sim, out);
  out.push_back(reached);
  return out;
}

/// A column set that gives no columns.
struct NoColumns {
  template <class Sim>
  void names(const Sim&, std::vector<std::string>&) const {}
  template <class Sim>
  void values(const Sim&, std::vector<double>&) const {}
};

/// A figure with one name but two values.
struct TwoValues {
  template <class Sim>
  void names(const Sim&, std::vector<std::string>& out) const {
    out.push_back("x");
  }
  template <class Sim>
  void values(const Sim&, std::vector<double>& out) const {
    out.push_back(1.0);
    out.push_back(2.0);
  }
};

/// A column whose name depends on the conduction model: differs between variants.
struct NamedByModel {
  template <class Sim>
  void names(const Sim&, std::vector<std::string>& out) const {
    out.push_back(Sim::contact_type::conduction_model::name);
  }
  template <class Sim>
  void values(const Sim& sim, std::vector<double>& out) const {
    out.push_back(sim.mean_temperature());
  }
};

} // namespace

TEST_CASE("io::compare: one row per variant, figures bit-identical to runs by hand, CSV table "
          "and histories") {
  const auto dir = scratch("grain_compare_test_table");
  const auto table =
      io::compare<Column>(variants<BOB, Pipe>{}, column_scenario,
                          {.duration = duration,
                           .csv = (dir / "table.csv").string(),
                           .history = (dir / "history_").string(),
                           .history_interval = 0.5,
                           .out = nullptr},
                          mean_temperature(), io::heat_flow_columns(), time_to_threshold());

  REQUIRE(table.rows.size() == 2);
  CHECK(table.rows[0].name == "Batchelor-O'Brien");
  CHECK(table.rows[1].name == "thermal pipe");
  CHECK(table.figures == std::vector<std::string>{"mean_temperature [K]", "heat_flow_pp [W]",
                                                  "heat_flow_pw [W]", "t_310 [s]"});
  const std::vector<std::vector<double>> hand{by_hand<Column<BOB>>(), by_hand<Column<Pipe>>()};
  for (std::size_t v = 0; v < 2; ++v) {
    const auto& r = table.rows[v];
    CAPTURE(r.name);
    REQUIRE(r.figures.size() == 4);
    CHECK(r.figures[0] == hand[v][0]); // same runs: bit-identical
    CHECK(r.figures[1] == hand[v][1]);
    CHECK(r.figures[2] == hand[v][2]);
    CHECK(r.figures[3] == grain::test::approx(hand[v][3]).epsilon(1e-14));
    CHECK(r.figures[0] > threshold); // heated, and the threshold was crossed within the run
    CHECK(r.figures[0] < hot);
    CHECK(r.figures[2] > 0.0); // the floor heats the disks
    CHECK(r.figures[3] > 0.0);
    CHECK(r.figures[3] < duration);
    CHECK(r.time_step == 0.01);
    CHECK(r.steps == 200);
    CHECK(r.particles == 3);
    CHECK(r.seconds > 0.0);
    CHECK(r.particle_steps_per_second > 0.0);
    CHECK(r.particle_steps_per_second ==
          grain::test::approx(200.0 * 3.0 / r.seconds).epsilon(1e-12));
  }
  // the two models differ for this packing (not the same run twice)
  CHECK(table.rows[0].figures[0] != table.rows[1].figures[0]);
  CHECK(table.figure("thermal pipe", "mean_temperature [K]") == table.rows[1].figures[0]);
  CHECK_THROWS_AS((void)table["Voronoi"], InputError);
  CHECK_THROWS_AS((void)table.figure("thermal pipe", "nothing"), InputError);

  // the CSV table parses back to the same numbers
  const auto lines = lines_of(dir / "table.csv");
  REQUIRE(lines.size() == 3);
  CHECK(lines[0] == "variant,mean_temperature [K],heat_flow_pp [W],heat_flow_pw [W],t_310 [s],"
                    "time_step [s],steps,particles,wall_time [s],particle_steps_per_second [1/s]");
  for (std::size_t v = 0; v < 2; ++v) {
    const auto cells = split(lines[v + 1]);
    const auto& r = table.rows[v];
    REQUIRE(cells.size() == 10);
    CHECK(cells[0] == r.name);
    for (std::size_t k = 0; k < 4; ++k)
      CHECK(std::stod(cells[1 + k]) == r.figures[k]);
    CHECK(std::stod(cells[5]) == r.time_step);
    CHECK(std::stol(cells[6]) == r.steps);
    CHECK(std::stol(cells[7]) == 3);
    CHECK(std::stod(cells[8]) == r.seconds);
    CHECK(std::stod(cells[9]) == r.particle_steps_per_second);
  }
  // histories: rows at 0, 0.5, ..., 2 s; the last row holds the figures at the end
  for (std::size_t v = 0; v < 2; ++v) {
    const auto& r = table.rows[v];
    CHECK(r.history ==
          (dir / (v == 0 ? "history_batchelor_o_brien.csv" : "history_thermal_pipe.csv")).string());
    const auto h = lines_of(r.history);
    REQUIRE(h.size() == 6);
    CHECK(h[0] == "time [s],step,mean_temperature [K],heat_flow_pp [W],heat_flow_pw [W],t_310 [s]");
    CHECK(std::stod(split(h[1])[2]) == 300.0);
    CHECK(split(h[1])[5] == "nan"); // not reached at the start
    const auto last = split(h[5]);
    CHECK(std::stod(last[0]) == grain::test::approx(duration).epsilon(1e-12));
    for (std::size_t k = 0; k < 4; ++k)
      CHECK(std::stod(last[2 + k]) == r.figures[k]);
  }
  // the aligned text table: header, rule, one line per variant, all of one width
  const std::string text = table.table();
  std::istringstream in(text);
  std::vector<std::string> text_lines;
  for (std::string l; std::getline(in, l);)
    text_lines.push_back(l);
  REQUIRE(text_lines.size() == 4);
  CHECK(text_lines[0].rfind("variant", 0) == 0);
  CHECK(text_lines[1] == std::string(text_lines[0].size(), '-'));
  CHECK(text_lines[2].size() == text_lines[0].size());
  CHECK(text_lines[3].rfind("thermal pipe", 0) == 0);
  std::filesystem::remove_all(dir);
}

TEST_CASE("io::compare: a scenario that sets up a default simulation, step counts, repeats and "
          "names") {
  // thermo-mechanical (the default analysis), automatic time step
  auto scenario = [](auto& sim) {
    const auto steel = sim.add_material({.name = "steel",
                                         .density = 7800,
                                         .young = 2e9,
                                         .poisson = 0.3,
                                         .conductivity = 40,
                                         .heat_capacity = 500});
    sim.add_particle({.position = Vec2(0, 0),
                      .radius = R,
                      .material = steel,
                      .velocity = Vec2(0.05, 0),
                      .temperature = 350.0});
    sim.add_particle(
        {.position = Vec2(2 * R - 1e-6, 0), .radius = R, .material = steel, .temperature = 300.0});
  };
  std::FILE* console = std::tmpfile();
  REQUIRE(console != nullptr);
  auto x0 =
      io::column("x0 [m]", [](const auto& s) { return s.particles().position[s.index_of(0)].x(); });
  const auto table = io::compare<Column>(
      variants<BOB, BOBZhou>{}, scenario,
      {.steps = 50, .names = {"BOB", "BOB + ZYZ"}, .repeats = 2, .out = console},
      mean_temperature(), x0);
  REQUIRE(table.rows.size() == 2);
  CHECK(table.rows[0].name == "BOB");
  CHECK(table.rows[1].name == "BOB + ZYZ");
  auto by_hand_steps = [&]<class Sim>(std::type_identity<Sim>) {
    Sim sim;
    scenario(sim);
    sim.steps(50);
    return std::vector<double>{sim.mean_temperature(),
                               sim.particles().position[sim.index_of(0)].x()};
  };
  CHECK(table.rows[0].figures == by_hand_steps(std::type_identity<Column<BOB>>{}));
  CHECK(table.rows[1].figures == by_hand_steps(std::type_identity<Column<BOBZhou>>{}));
  for (const auto& r : table.rows) {
    CHECK(r.steps == 50);
    CHECK(r.particles == 2);
    CHECK(r.particle_steps_per_second > 0.0);
    CHECK(r.history.empty());
  }
  // the console: a line per variant, then the table (header, rule, rows)
  std::rewind(console);
  std::string printed;
  for (int ch; (ch = std::fgetc(console)) != EOF;)
    printed += static_cast<char>(ch);
  std::fclose(console);
  CHECK(printed.find("compare: 1/2 BOB: 50 steps of 2 particles") != std::string::npos);
  CHECK(printed.find("compare: 2/2 BOB + ZYZ: 50 steps") != std::string::npos);
  CHECK(printed.find(table.table()) != std::string::npos);
}

TEST_CASE("io::compare: default names are the models in which the variants differ") {
  using io::detail::default_names;
  CHECK(default_names<BOB, BOBZhou, Pipe>() ==
        std::vector<std::string>{"Batchelor-O'Brien, none", "Batchelor-O'Brien, Zhou-Yu-Zulli",
                                 "thermal pipe, none"});
  CHECK(default_names<BOB>() ==
        std::vector<std::string>{"normal Hertz with Tsuji damping, conduction Batchelor-O'Brien"});
  CHECK(default_names<BOB, Pipe, BOB>() ==
        std::vector<std::string>{"Batchelor-O'Brien #1", "thermal pipe", "Batchelor-O'Brien #2"});
  CHECK(io::detail::slug("Batchelor-O'Brien, Zhou-Yu-Zulli") == "batchelor_o_brien_zhou_yu_zulli");
  CHECK(io::detail::slug("--") == "variant");
}

TEST_CASE("io::compare: input errors name the value and the valid range, before any run") {
  const auto dir = scratch("grain_compare_test_errors");
  int made = 0; // simulations the scenario made
  auto counted = [&made]<class Sim>(std::type_identity<Sim>) {
    ++made;
    return make_column<Sim>();
  };
  auto message = [&](auto&& call) {
    try {
      call();
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no InputError");
  };
  const io::CompareOptions ok{.duration = 0.1, .out = nullptr};
  auto with = [&](io::CompareOptions o) {
    return message(
        [&] { io::compare<Column>(variants<BOB, Pipe>{}, counted, o, mean_temperature()); });
  };

  CHECK(message([&] { io::compare<Column>(variants<BOB>{}, counted, ok); }) ==
        "grain::io::compare: figures = {} (none) is invalid; valid: at least one figure, e.g. "
        "io::column(name, f)");
  CHECK(message([&] {
          io::compare<Column>(variants<>{}, counted, ok, mean_temperature());
        }).find("variants = <> (empty) is invalid") != std::string::npos);
  CHECK(with({.duration = -1.0, .out = nullptr}) ==
        "grain::io::compare: duration = -1 is invalid; valid range: (0, inf) s, with steps = 0 "
        "(or duration = 0 and steps >= 1)");
  CHECK(with({.duration = std::nan(""), .out = nullptr}).find("duration = nan is invalid") !=
        std::string::npos);
  CHECK(with({.out = nullptr}).find("duration = 0 is invalid") != std::string::npos);
  CHECK(with({.duration = 1.0, .steps = 10, .out = nullptr}).find("duration = 1 is invalid") !=
        std::string::npos);
  CHECK(with({.steps = -2, .out = nullptr}) ==
        "grain::io::compare: steps = -2 is invalid; valid range: [1, inf) (with duration = 0)");
  CHECK(with({.duration = 0.1, .repeats = 0, .out = nullptr}).find("repeats = 0 is invalid") !=
        std::string::npos);
  CHECK(with({.duration = 0.1, .names = {"one"}, .out = nullptr})
            .find("names has 1 entries, which is invalid; valid: one per variant (2)") !=
        std::string::npos);
  CHECK(with({.duration = 0.1, .names = {"a", "a"}, .out = nullptr})
            .find("names[1] = \"a\" is invalid") != std::string::npos);
  CHECK(with({.duration = 0.1, .names = {"", "b"}, .out = nullptr})
            .find("names[0] = \"\" is invalid") != std::string::npos);
  CHECK(with({.duration = 0.1, .history = (dir / "h_").string(), .out = nullptr})
            .find("history_interval = 0 is invalid") != std::string::npos);
  // a path below a regular file, and a folder, cannot be written
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "file") << "x";
  const std::string below = (dir / "file" / "table.csv").string();
  CHECK(with({.duration = 0.1, .csv = below, .out = nullptr}) ==
        "grain::io::compare (csv): path = \"" + below +
            "\" is invalid; valid: a file that can be written (its folder is made if needed)");
  CHECK(with({.duration = 0.1, .csv = dir.string(), .out = nullptr})
            .find("is invalid; valid: a file that can be written") != std::string::npos);
  CHECK(with({.duration = 0.1,
              .history = (dir / "file" / "h_").string(),
              .history_interval = 0.05,
              .out = nullptr})
            .find("grain::io::compare (history): path = ") != std::string::npos);
  CHECK(made == 0);
  // a figure without columns is found when the first variant is set up (the CSV would lose it)
  CHECK(message([&] {
          io::compare<Column>(variants<BOB>{}, counted, ok, mean_temperature(), NoColumns{});
        }) == "grain::io::compare: figure 1 gives no column, which is invalid; valid: at least one "
              "name per figure, e.g. io::column(name, f)");
  CHECK(made == 1);
  CHECK(message([&] { io::compare<Column>(variants<BOB, Pipe>{}, counted, ok, NamedByModel{}); }) ==
        "grain::io::compare: variant \"thermal pipe\" gives 1 figures that differ from those of "
        "the first variant; valid: the same figure names for every variant");
  CHECK(made == 3);
  // repeated names, and a name of a fixed column (the table lookups would find the wrong one)
  CHECK(message([&] {
          io::compare<Column>(variants<BOB>{}, counted, ok, mean_temperature(), mean_temperature());
        }).find("figure name \"mean_temperature [K]\" is repeated or names a fixed column") !=
        std::string::npos);
  CHECK(message([&] {
          io::compare<Column>(variants<BOB>{}, counted, ok,
                              io::column("steps", [](const auto&) { return 0.0; }));
        }).find("figure name \"steps\" is repeated or names a fixed column") != std::string::npos);
  CHECK(made == 5);
  // a figure with more values than names would shift the CSV columns
  CHECK(message([&] {
          io::compare<Column>(variants<BOB>{}, counted, ok, TwoValues{});
        }).find("\" gave 2 values for 1 names, which is invalid; valid: one value per name") !=
        std::string::npos);
  CHECK_THROWS_AS(io::time_to_reach("t", std::nan(""), [](const auto&) { return 0.0; }),
                  InputError);
  CHECK_THROWS_AS(io::time_to_reach("", 1.0, [](const auto&) { return 0.0; }), InputError);
  std::filesystem::remove_all(dir);
}
