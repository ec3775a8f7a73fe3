// CSV time histories (io/csv.hpp): header, one flushed row per output, values equal to the
// simulation's own figures.
#include "../approx.hpp"
#include "../support/csv_files.hpp"
#include <doctest/doctest.h>
#include <grain/grain.hpp>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

using namespace grain;

namespace {

using grain::test::lines_of;
using grain::test::scratch;
using grain::test::split;

} // namespace

TEST_CASE("io::history writes the global quantities of a thermal simulation, flushed row by row") {
  using Contact =
      Interaction<normal::Hertz<>, tangent::None, rolling::None, conduction::BatchelorOBrien>;
  using Sim = Simulation<Sphere, search::AllPairs, Contact>;
  Sim::Params p;
  p.gravity = {0, 0, -9.81};
  Sim sim(p);
  const auto m = sim.add_material({.name = "steel",
                                   .density = 7800,
                                   .young = 2e9,
                                   .poisson = 0.3,
                                   .conductivity = 40,
                                   .heat_capacity = 500});
  sim.add_wall(walls::Plane{{0, 0, 0}, {0, 0, 1}}, {.material = m, .temperature = 400.0});
  // resting on the wall near its static Hertz overlap (5.3e-7 m)
  sim.add_particle(
      {.position = {0, 0, 0.005 - 5e-7}, .radius = 0.005, .material = m, .temperature = 300});
  const auto dir = std::filesystem::temp_directory_path() / "grain_csv_test";
  std::filesystem::remove_all(dir);
  const auto path = dir / "history.csv";
  sim.initialize();
  const double interval = 20 * sim.time_step();
  std::size_t rows_seen_during_run = 0;
  auto probe = [&](const Sim&) { rows_seen_during_run = lines_of(path).size(); };
  sim.steps(200,
            io::every(interval,
                      io::history(path.string(), io::column("z [m]",
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

// ------------------------------------------------------------------ per-particle histories
namespace {

using Sim3 = Simulation<Sphere, search::AllPairs, Interaction<normal::Hertz<>>>;
using Sim2 = Simulation<Disk, search::AllPairs, Interaction<normal::Hertz<>>>;

/// The rows of a CSV file (header excluded) as numbers ("nan" -> NaN).
std::vector<std::vector<double>> rows_of(const std::vector<std::string>& lines) {
  std::vector<std::vector<double>> rows;
  for (std::size_t k = 1; k < lines.size(); ++k) {
    std::vector<double> row;
    for (const auto& c : split(lines[k]))
      row.push_back(std::stod(c));
    rows.push_back(row);
  }
  return rows;
}

template <class S>
concept has_dissipated_energy = requires(const S& s) {
  s.dissipated_energy();
};

std::size_t column_of(const std::vector<std::string>& header, const std::string& name) {
  for (std::size_t k = 0; k < header.size(); ++k)
    if (header[k] == name) return k;
  FAIL("no column " << name);
  return 0;
}

} // namespace

TEST_CASE("io::particle_history: prescribed-velocity, free and fixed particles follow their closed "
          "forms") {
  Sim3::Params p;
  p.gravity = {0, 0, -9.81};
  Sim3 sim(p);
  const auto m = sim.add_material({.name = "glass", .density = 2500, .young = 1e7});
  // far apart: no contacts
  sim.add_particle({.position = {0, 0, 0}, .radius = 1e-3, .material = m, .id = 10});
  sim.add_particle({.position = {1, 0, 0},
                    .radius = 2e-3,
                    .material = m,
                    .velocity = {0.5, 0, 2},
                    .omega = Vec3(1, 2, 3),
                    .id = 11});
  sim.add_particle({.position = {2, 0, 0}, .radius = 1e-3, .material = m, .fixed = true, .id = 12});
  sim.add_group("g", {10});
  const Vec3 vg(0.1, -0.2, 0.3);
  sim.fix_velocity("g", vg);
  const auto dir = scratch("grain_csv_test_particles");
  const auto path = dir / "particles.csv";
  auto height = io::quantity(
      "height", "m", [](const Sim3& s, std::size_t i) { return s.particles().position[i].z(); });
  sim.steps(50, io::every_steps(10, io::particle_history(path.string(), {10, 11, 12}, io::position,
                                                         io::displacement, io::velocity,
                                                         io::acceleration, io::omega, io::force,
                                                         io::speed, io::radius, io::mass, height)));
  const auto lines = lines_of(path);
  REQUIRE(lines.size() == 7); // header + steps 0, 10, ..., 50
  const auto header = split(lines[0]);
  // 2 + 3 particles x (3 + 3 + 3 + 3 + 3 + 3 + 1 + 1 + 1 + 1) columns
  REQUIRE(header.size() == 2 + 3 * 22);
  CHECK(lines[0].rfind("time [s],step,x_10 [m],y_10 [m],z_10 [m],ux_10 [m],uy_10 [m],uz_10 [m],"
                       "vx_10 [m/s],vy_10 [m/s],vz_10 [m/s],ax_10 [m/s^2],ay_10 [m/s^2],"
                       "az_10 [m/s^2],omegax_10 [rad/s],omegay_10 [rad/s],omegaz_10 [rad/s],"
                       "fx_10 [N],fy_10 [N],fz_10 [N],speed_10 [m/s],radius_10 [m],mass_10 [kg],"
                       "height_10 [m],x_11 [m]",
                       0) == 0);
  CHECK(header.back() == "height_12 [m]");
  const double g = -9.81;
  const double m11 = 2500 * 4.0 / 3.0 * M_PI * 8e-9;
  const double m12 = 2500 * 4.0 / 3.0 * M_PI * 1e-9;
  const auto rows = rows_of(lines);
  for (std::size_t r = 0; r < rows.size(); ++r) {
    const auto& row = rows[r];
    const double t = row[0];
    CHECK(row[1] == 10.0 * static_cast<double>(r));
    CHECK(t == grain::test::approx(sim.time_step() * row[1]).epsilon(1e-12).scale(1e-12));
    auto at = [&](const std::string& name) { return row[column_of(header, name)]; };
    // 1e-12 relative, or absolute for values much below 1 (displacements lose digits to x - x0)
    const auto tol = [](double x) { return grain::test::approx(x).epsilon(1e-12).scale(1.0); };
    // prescribed velocity: x = x0 + v t
    CHECK(at("x_10 [m]") == tol(vg.x() * t));
    CHECK(at("y_10 [m]") == tol(vg.y() * t));
    CHECK(at("z_10 [m]") == tol(vg.z() * t));
    CHECK(at("uz_10 [m]") == tol(vg.z() * t));
    if (r > 0) CHECK(at("vy_10 [m/s]") == tol(vg.y())); // prescribed from the first step on
    CHECK(at("az_10 [m/s^2]") == tol(g));               // its forces (the weight) over its mass
    // free under gravity: x = x0 + v0 t + g t^2/2 (velocity Verlet is exact here)
    CHECK(at("x_11 [m]") == tol(1.0 + 0.5 * t));
    CHECK(at("z_11 [m]") == tol(2.0 * t + 0.5 * g * t * t));
    CHECK(at("ux_11 [m]") == tol(0.5 * t));
    CHECK(at("uz_11 [m]") == tol(2.0 * t + 0.5 * g * t * t));
    CHECK(at("height_11 [m]") == tol(2.0 * t + 0.5 * g * t * t));
    CHECK(at("vz_11 [m/s]") == tol(2.0 + g * t));
    CHECK(at("speed_11 [m/s]") == tol(std::hypot(0.5, 2.0 + g * t)));
    CHECK(at("ax_11 [m/s^2]") == 0.0);
    CHECK(at("az_11 [m/s^2]") == tol(g));
    CHECK(at("fz_11 [N]") == tol(m11 * g));
    CHECK(at("omegay_11 [rad/s]") == 2.0);
    CHECK(at("radius_11 [m]") == 2e-3);
    CHECK(at("mass_11 [kg]") == tol(m11));
    // fixed: it stays, its weight does not accelerate it
    CHECK(at("x_12 [m]") == 2.0);
    CHECK(at("uz_12 [m]") == 0.0);
    CHECK(at("az_12 [m/s^2]") == 0.0);
    CHECK(at("fz_12 [N]") == tol(m12 * g));
  }
  CHECK(rows.back()[0] == grain::test::approx(sim.time()).epsilon(1e-15));
  std::filesystem::remove_all(dir);
}

TEST_CASE("io::particle_history in 2D: x, y columns, one omega and torque column, vector user "
          "quantities") {
  Sim2 sim;
  const auto m = sim.add_material({.name = "glass", .density = 2500, .young = 1e7});
  sim.add_particle({.position = {0, 0},
                    .radius = 1e-3,
                    .material = m,
                    .velocity = {1, -2},
                    .omega = 3.0,
                    .id = 5});
  const auto dir = scratch("grain_csv_test_particles2d");
  const auto path = dir / "p.csv";
  auto momentum = io::quantity("p", "kg m/s", [](const Sim2& s, std::size_t i) {
    return Vec2(s.particles().mass[i] * s.particles().velocity[i]);
  });
  sim.steps(4, io::every_steps(2, io::particle_history(path.string(), {5}, io::position, io::omega,
                                                       io::torque, momentum)));
  const auto lines = lines_of(path);
  REQUIRE(lines.size() == 4);
  CHECK(lines[0] == "time [s],step,x_5 [m],y_5 [m],omega_5 [rad/s],torque_5 [N m],px_5 [kg m/s],"
                    "py_5 [kg m/s]");
  const auto last = rows_of(lines).back();
  const double mass = sim.particles().mass[0];
  CHECK(last[2] == grain::test::approx(sim.time()).epsilon(1e-12));
  CHECK(last[3] == grain::test::approx(-2 * sim.time()).epsilon(1e-12));
  CHECK(last[4] == 3.0);
  CHECK(last[5] == 0.0);
  CHECK(last[6] == grain::test::approx(mass).epsilon(1e-15));
  CHECK(last[7] == grain::test::approx(-2 * mass).epsilon(1e-15));
  std::filesystem::remove_all(dir);
}

TEST_CASE("io::particle_history: removed and waiting particles write nan, and a late particle's "
          "displacement starts when it appears") {
  Sim3::Params p;
  p.time_step = 1e-4;
  Sim3 s(p); // no gravity
  const auto mat = s.add_material({.name = "glass", .density = 2500, .young = 1e5});
  s.add_particle({.position = {0, 0, 0},
                  .radius = 1e-3,
                  .material = mat,
                  .velocity = {1, 0, 0},
                  .destruction_time = 25e-4,
                  .id = 0});
  s.add_particle({.position = {1, 0, 0},
                  .radius = 1e-3,
                  .material = mat,
                  .velocity = {0, 2, 0},
                  .creation_time = 15e-4,
                  .id = 1});
  const auto dir = scratch("grain_csv_test_removed");
  const auto path = dir / "p.csv";
  s.steps(40, io::every_steps(
                  5, io::particle_history(path.string(), {0, 1}, io::position, io::displacement)));
  const auto lines = lines_of(path);
  REQUIRE(lines.size() == 10); // steps 0, 5, ..., 40
  CHECK(lines[0] == "time [s],step,x_0 [m],y_0 [m],z_0 [m],ux_0 [m],uy_0 [m],uz_0 [m],x_1 [m],"
                    "y_1 [m],z_1 [m],ux_1 [m],uy_1 [m],uz_1 [m]");
  const auto rows = rows_of(lines);
  double first_seen = -1.0, y_first = 0.0;
  for (const auto& row : rows) {
    const double t = row[0];
    const bool alive0 = row[1] < 25; // removed at the end of step 25
    for (std::size_t c = 2; c < 8; ++c)
      CHECK(std::isnan(row[c]) == !alive0);
    if (alive0) {
      CHECK(row[2] == grain::test::approx(t).epsilon(1e-12).scale(1e-12));
      CHECK(row[5] == grain::test::approx(t).epsilon(1e-12).scale(1e-12));
    }
    const bool alive1 = row[1] >= 15; // created at the end of step 15
    for (std::size_t c = 8; c < 14; ++c)
      CHECK(std::isnan(row[c]) == !alive1);
    if (alive1) {
      if (first_seen < 0) {
        first_seen = t;
        y_first = row[9];
      }
      CHECK(row[8] == 1.0);
      CHECK(row[9] ==
            grain::test::approx(y_first + 2 * (t - first_seen)).epsilon(1e-12).scale(1e-12));
      CHECK(row[12] == grain::test::approx(2 * (t - first_seen)).epsilon(1e-12).scale(1e-12));
    }
  }
  CHECK(first_seen == grain::test::approx(15e-4).epsilon(1e-12));
  // the raw cells of a missing value
  CHECK(split(lines.back())[2] == "nan");
  std::filesystem::remove_all(dir);
}

TEST_CASE("io::particle_history and io::group_history reject unknown or repeated ids and unknown "
          "groups, before the file is made") {
  Sim3 sim;
  const auto m = sim.add_material({.name = "glass", .density = 2500, .young = 1e7});
  sim.add_particle({.position = {0, 0, 0}, .radius = 1e-3, .material = m, .id = 3});
  const auto dir = scratch("grain_csv_test_errors");
  const auto path = (dir / "p.csv").string();
  CHECK_THROWS_AS(io::particle_columns({3, 3}, io::position), InputError);
  CHECK_THROWS_AS(io::particle_columns({}, io::position), InputError);
  CHECK_THROWS_AS(io::quantity("", "m", [](const Sim3&, std::size_t) { return 0.0; }), InputError);
  CHECK_THROWS_AS(io::group_columns("", io::position), InputError);
  try {
    sim.steps(1, io::every_steps(1, io::particle_history(path, {3, 99}, io::position)));
    FAIL("an unknown id was accepted");
  } catch (const InputError& e) {
    CHECK(std::string(e.what()).find("id = 99 is invalid") != std::string::npos);
  }
  CHECK_THROWS_AS(sim.steps(1, io::every_steps(1, io::group_history(path, "nope", io::velocity))),
                  InputError);
  CHECK(!std::filesystem::exists(path));
}

TEST_CASE("io::group_history: count and means over the group's active particles") {
  Sim3::Params p;
  p.time_step = 1e-4;
  Sim3 sim(p); // no gravity
  const auto m = sim.add_material({.name = "glass", .density = 2500, .young = 1e5});
  for (int k = 0; k < 4; ++k)
    sim.add_particle({.position = {double(k), 0, 0},
                      .radius = 1e-3 * (k + 1),
                      .material = m,
                      .velocity = {double(k == 3 ? 10 : k + 1), 0, 0},
                      .destruction_time = k == 2 ? 25e-4 : std::numeric_limits<double>::infinity(),
                      .id = k});
  sim.add_group("hot", {0, 1, 2});
  sim.add_group("solo", {2});
  const auto dir = scratch("grain_csv_test_group");
  const auto path = dir / "g.csv";
  sim.steps(40, io::every_steps(10, io::csv(path.string(),
                                            io::group_columns("hot", io::velocity, io::displacement,
                                                              io::radius),
                                            io::group_columns("solo", io::speed),
                                            io::group_columns("all", io::mass))));
  const auto lines = lines_of(path);
  REQUIRE(lines.size() == 6);
  CHECK(lines[0] == "time [s],step,count_hot,mean_vx_hot [m/s],mean_vy_hot [m/s],mean_vz_hot "
                    "[m/s],mean_ux_hot [m],mean_uy_hot [m],mean_uz_hot [m],mean_radius_hot [m],"
                    "count_solo,mean_speed_solo [m/s],count_all,mean_mass_all [kg]");
  const double mass1 = 2500 * 4.0 / 3.0 * M_PI * 1e-9;
  for (const auto& row : rows_of(lines)) {
    const double t = row[0];
    const bool three = row[1] < 25;
    CHECK(row[2] == (three ? 3 : 2));
    CHECK(row[3] == grain::test::approx(three ? 2.0 : 1.5).epsilon(1e-15));
    CHECK(row[4] == 0.0);
    CHECK(row[6] == grain::test::approx((three ? 2.0 : 1.5) * t).epsilon(1e-12).scale(1e-12));
    CHECK(row[9] == grain::test::approx(three ? 2e-3 : 1.5e-3).epsilon(1e-15));
    CHECK(row[10] == (three ? 1 : 0));
    CHECK(std::isnan(row[11]) == !three); // the mean over an empty group
    if (three) CHECK(row[11] == grain::test::approx(3.0).epsilon(1e-15));
    CHECK(row[12] == (three ? 4 : 3));
    const double masses = three ? (1 + 8 + 27 + 64) / 4.0 : (1 + 8 + 64) / 3.0;
    CHECK(row[13] == grain::test::approx(masses * mass1).epsilon(1e-12));
  }
  std::filesystem::remove_all(dir);
}

// ------------------------------------------------------------------ global extras
TEST_CASE("io::history with contact-force, lifecycle and dissipated-energy columns") {
  Sim3::Params p;
  p.gravity = {0, 0, -9.81};
  Sim3 sim(p);
  const auto m = sim.add_material({.name = "steel", .density = 7800, .young = 2e9, .poisson = 0.3});
  sim.add_wall(walls::Plane{{0, 0, 0}, {0, 0, 1}}, {.material = m});
  sim.add_particle({.position = {0, 0, 0.005 - 5e-7}, .radius = 0.005, .material = m});
  sim.add_particle({.position = {1, 0, 1}, .radius = 0.005, .material = m, .creation_time = 1.0});
  const auto dir = scratch("grain_csv_test_extras");
  const auto path = dir / "h.csv";
  sim.steps(200, io::every_steps(50, io::history(path.string(), io::contact_force_columns(),
                                                 io::contact_force_columns(io::Contacts::particles),
                                                 io::contact_force_columns(io::Contacts::walls),
                                                 io::lifecycle_columns(),
                                                 io::dissipated_energy_column())));
  const auto lines = lines_of(path);
  REQUIRE(lines.size() == 6);
  constexpr bool has_dissipation = has_dissipated_energy<Sim3>;
  CHECK(lines[0] == std::string("time [s],step,particles,contacts_pp,contacts_pw,kinetic_energy "
                                "[J],potential_energy [J],elastic_energy [J],normal_force_total "
                                "[N],normal_force_mean [N],normal_force_total_pp [N],"
                                "normal_force_mean_pp [N],normal_force_total_pw [N],"
                                "normal_force_mean_pw [N],active,inactive,removed") +
                        (has_dissipation ? ",dissipated_energy [J]" : ""));
  const auto last = rows_of(lines).back();
  double total = 0.0;
  sim.for_each_contact([&](std::size_t, std::size_t, bool, const auto&, const auto& r) {
    total += std::abs(r.normal.force);
  });
  const double weight = 7800 * 4.0 / 3.0 * M_PI * 1.25e-7 * 9.81;
  CHECK(last[8] == grain::test::approx(total).epsilon(1e-15));
  CHECK(last[8] == grain::test::approx(weight).epsilon(0.2)); // resting, oscillating a little
  CHECK(last[9] == last[8]);                                  // one contact
  CHECK(last[10] == 0.0);
  CHECK(std::isnan(last[11])); // no particle-particle contact: no mean
  CHECK(last[12] == last[8]);
  CHECK(last[13] == last[8]);
  CHECK(last[14] == 1); // active
  CHECK(last[15] == 1); // waiting
  CHECK(last[16] == 0); // removed
  std::filesystem::remove_all(dir);
}

namespace {
/// Stands in for a simulation that has dissipated_energy().
struct WithDissipation {
  double time() const { return 0.25; }
  long step_count() const { return 7; }
  double dissipated_energy() const { return 1.5; }
};
} // namespace

TEST_CASE("io::csv dissipated_energy_column: present when the simulation has dissipated_energy()") {
  const auto dir = scratch("grain_csv_test_dissipation");
  const auto path = dir / "d.csv";
  auto w = io::csv(path.string(), io::dissipated_energy_column());
  WithDissipation s;
  w.start(s);
  w(s);
  const auto lines = lines_of(path);
  REQUIRE(lines.size() == 2);
  CHECK(lines[0] == "time [s],step,dissipated_energy [J]");
  CHECK(lines[1] == "0.25,7,1.5");
  std::filesystem::remove_all(dir);
}

TEST_CASE("io::history heat-flow columns and thermal particle columns match the contacts' heat "
          "rates") {
  using Contact =
      Interaction<normal::Hertz<>, tangent::None, rolling::None, conduction::BatchelorOBrien>;
  using Sim = Simulation<Sphere, search::AllPairs, Contact>;
  Sim::Params p;
  p.gravity = {0, 0, -9.81};
  Sim sim(p);
  const auto m = sim.add_material({.name = "steel",
                                   .density = 7800,
                                   .young = 2e9,
                                   .poisson = 0.3,
                                   .conductivity = 40,
                                   .heat_capacity = 500});
  sim.add_wall(walls::Plane{{0, 0, 0}, {0, 0, 1}}, {.material = m, .temperature = 400.0});
  sim.add_particle({.position = {0, 0, 0.005 - 5e-7},
                    .radius = 0.005,
                    .material = m,
                    .temperature = 300,
                    .id = 0});
  sim.add_particle({.position = {0, 0, 0.015 - 1.5e-6},
                    .radius = 0.005,
                    .material = m,
                    .temperature = 350,
                    .id = 1});
  const auto dir = scratch("grain_csv_test_heat");
  const auto path = dir / "h.csv";
  sim.steps(100, io::every_steps(
                     50, io::history(path.string(), io::heat_flow_columns(),
                                     io::particle_columns({1}, io::temperature, io::heat_rate))));
  const auto lines = lines_of(path);
  REQUIRE(lines.size() == 4);
  CHECK(lines[0] == "time [s],step,particles,contacts_pp,contacts_pw,kinetic_energy [J],"
                    "potential_energy [J],elastic_energy [J],mean_temperature [K],heat_content "
                    "[J],heat_inflow [W],heat_flow_pp [W],heat_flow_pw [W],temperature_1 [K],"
                    "heat_rate_1 [W]");
  const auto last = rows_of(lines).back();
  double pp = 0.0, pw = 0.0;
  std::size_t npp = 0, npw = 0;
  sim.for_each_contact(
      [&](std::size_t, std::size_t, bool wall, const auto&, const auto&, double q) {
        (wall ? pw : pp) += wall ? q : std::abs(q);
        ++(wall ? npw : npp);
      });
  REQUIRE(npp == 1);
  REQUIRE(npw == 1);
  CHECK(last[11] == grain::test::approx(pp).epsilon(1e-12));
  CHECK(last[12] == grain::test::approx(pw).epsilon(1e-12));
  CHECK(last[11] > 0.0);
  CHECK(last[12] > 0.0); // the hot wall heats the spheres
  const auto i1 = sim.index_of(1);
  CHECK(last[13] == grain::test::approx(sim.particles().temperature[i1]).epsilon(1e-15));
  CHECK(last[14] == grain::test::approx(sim.particles().heat_rate[i1]).epsilon(1e-15));
  CHECK(last[14] < 0.0); // the upper sphere is the warmer one: it loses heat to the lower
  std::filesystem::remove_all(dir);
}

// ------------------------------------------------------------------ flushed rows
TEST_CASE("csv rows are flushed: the file is valid CSV up to the last row at any time, even after "
          "a run that stops with an exception") {
  Sim3::Params p;
  p.gravity = {0, 0, -9.81};
  Sim3 sim(p);
  const auto m = sim.add_material({.name = "glass", .density = 2500, .young = 1e7});
  sim.add_particle({.position = {0, 0, 0}, .radius = 1e-3, .material = m, .id = 4});
  const auto dir = scratch("grain_csv_test_flushed");
  const auto path = dir / "f.csv";
  std::size_t rows_written = 0;
  struct Stop {};
  // runs right after the writer in the same output: reads the file as another program would
  auto probe = [&](const Sim3& s) {
    ++rows_written;
    std::ifstream in(path, std::ios::binary);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    REQUIRE(!text.empty());
    CHECK(text.back() == '\n'); // no partial row
    const auto lines = lines_of(path);
    REQUIRE(lines.size() == rows_written + 1);
    const auto width = split(lines[0]).size();
    for (std::size_t k = 1; k < lines.size(); ++k) {
      const auto cells = split(lines[k]);
      REQUIRE(cells.size() == width);
      for (const auto& c : cells)
        CHECK_NOTHROW((void)std::stod(c));
    }
    CHECK(std::stol(split(lines.back())[1]) == s.step_count());
    if (s.step_count() == 30) throw Stop{}; // the run stops here
  };
  CHECK_THROWS_AS(sim.steps(100, io::every_steps(10,
                                                 io::history(path.string(),
                                                             io::particle_columns({4}, io::position,
                                                                                  io::velocity)),
                                                 probe)),
                  Stop);
  const auto lines = lines_of(path);
  REQUIRE(lines.size() == 5); // steps 0, 10, 20, 30
  CHECK(std::stol(split(lines.back())[1]) == 30);
  std::filesystem::remove_all(dir);
}

// ------------------------------------------------------------------ frequency
TEST_CASE("csv with io::every_steps: rows at the start, every n steps and at the end, none twice "
          "when a run continues") {
  Sim3 sim;
  const auto m = sim.add_material({.name = "glass", .density = 2500, .young = 1e7});
  sim.add_particle({.position = {0, 0, 0}, .radius = 1e-3, .material = m});
  const auto dir = scratch("grain_csv_test_steps");
  auto steps_in = [](const std::filesystem::path& f) {
    std::vector<long> s;
    const auto lines = lines_of(f);
    for (std::size_t k = 1; k < lines.size(); ++k)
      s.push_back(std::stol(split(lines[k])[1]));
    return s;
  };
  const auto a = dir / "a.csv", b = dir / "b.csv", c = dir / "c.csv";
  sim.steps(10, io::every_steps(3, io::csv(a.string())));
  CHECK(steps_in(a) == std::vector<long>{0, 3, 6, 9, 10});
  sim.steps(9, io::every_steps(3, io::csv(b.string())));
  CHECK(steps_in(b) == std::vector<long>{10, 13, 16, 19}); // relative to the start, end on a row
  // the same writers over two runs: the junction is written once
  auto by_steps = io::every_steps(3, io::csv(c.string()));
  auto by_time = io::every(3 * sim.time_step(), io::csv((dir / "d.csv").string()));
  sim.steps(9, by_steps, by_time);
  sim.steps(5, by_steps, by_time);
  CHECK(steps_in(c) == std::vector<long>{19, 22, 25, 28, 31, 33});
  CHECK(steps_in(dir / "d.csv") == std::vector<long>{19, 22, 25, 28, 31, 33});
  CHECK_THROWS_AS(io::every_steps(0, io::csv(a.string())), InputError);
  CHECK_THROWS_AS(io::every(0.0, io::csv(a.string())), InputError);
  CHECK_THROWS_AS(io::every(-1.0, io::csv(a.string())), InputError);
  std::filesystem::remove_all(dir);
}
