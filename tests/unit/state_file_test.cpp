// Particle state files (io/state_file.hpp): a packing written and read back (CSV, and the VTK
// particle files) gives the same particles bit for bit, a simulation loaded from it runs as the
// one it was written from, and bad files are refused with messages naming the file, the line and
// the value.

#include "../errors.hpp"

#include <doctest/doctest.h>
#include <grain/grain.hpp>
#include <grain/io/state_file.hpp>
#include <grain/models/conduction/batchelor_obrien.hpp>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <string>
#include <vector>

using namespace grain;
using grain::test::error_of;
using grain::test::has;

namespace {

using Thermal =
    Interaction<normal::Hertz<>, tangent::Mindlin, rolling::None, conduction::BatchelorOBrien>;
using Sim3 = Simulation<Sphere, search::CellList, Thermal>;
using Sim2 = Simulation<Disk, search::CellList, Thermal>;
using Mech3 = Simulation<Sphere, search::CellList, presets::LinearCoulomb>;

std::string temp_path(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / "grain_state_test";
  std::filesystem::create_directories(dir);
  return (dir / name).string();
}

void write_text(const std::string& path, const std::string& text) {
  std::ofstream o(path, std::ios::binary | std::ios::trunc);
  o << text;
}

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

/// The set-up without particles: two materials, a floor (at 350 K), a fixed time step.
template <class S>
S empty_sim() {
  constexpr int D = S::dimension;
  typename S::Params prm;
  prm.time_step = 2e-6;
  prm.gravity = Vec<D>::Zero();
  prm.gravity[D - 1] = -9.81;
  S sim(prm);
  Material m;
  m.density = 2500;
  m.young = 1e7;
  m.friction = 0.4;
  m.conductivity = 1;
  m.heat_capacity = 800;
  sim.add_material(m);
  m.density = 7800;
  m.conductivity = 40;
  m.heat_capacity = 450;
  sim.add_material(m);
  WallOptions<D> wall{.material = 0};
  if constexpr (S::thermal) wall.temperature = 350.0;
  if constexpr (D == 3)
    sim.add_wall(walls::Plane{{0, 0, 0}, {0, 0, 1}}, wall);
  else
    sim.add_wall(walls::Segment{Vec2(-1, 0), Vec2(1, 0)}, wall);
  return sim;
}

/// A lattice of particles 3 mm apart with radii in [0.6, 1.2] mm (no two touch), random
/// velocities, angular velocities, temperatures and materials, every 37th particle fixed (if
/// `fixed`), and three groups (one with a comma and a quote in its name).
template <class S>
S packed_sim(bool fixed = true) {
  constexpr int D = S::dimension;
  S sim = empty_sim<S>();
  std::mt19937_64 rng(D * 1000 + 7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const int nx = D == 3 ? 8 : 20, ny = D == 3 ? 8 : 15, nz = D == 3 ? 5 : 1;
  std::vector<std::int64_t> hot, bottom, odd;
  int k = 0;
  for (int i = 0; i < nx; ++i)
    for (int j = 0; j < ny; ++j)
      for (int l = 0; l < nz; ++l, ++k) {
        ParticleSpec<D> p;
        p.position[0] = 0.003 * i + 1e-4 * u(rng);
        p.position[1] = 0.003 * j + (D == 2 ? 0.0015 : 1e-4 * u(rng));
        if constexpr (D == 3) p.position[2] = 0.0015 + 0.003 * l;
        p.radius = 0.0009 + 0.0003 * u(rng);
        p.material = static_cast<std::uint32_t>(k % 2);
        for (int d = 0; d < D; ++d)
          p.velocity[d] = 0.2 * u(rng);
        if constexpr (D == 2)
          p.omega = 50 * u(rng);
        else
          p.omega = Vec3(50 * u(rng), 50 * u(rng), 50 * u(rng));
        if constexpr (S::thermal) p.temperature = 340 + 60 * u(rng);
        p.fixed = fixed && k % 37 == 5;
        const auto id = sim.add_particle(p);
        if (S::thermal && p.temperature > 370) hot.push_back(id);
        if ((D == 3 ? l : j) == 0) bottom.push_back(id);
        if (k % 11 == 3) odd.push_back(id);
      }
  sim.add_group("hot", hot);
  sim.add_group("bottom", bottom);
  sim.add_group("odd \"name\", with a comma", odd);
  return sim;
}

/// Every particle quantity a state file holds is the same bit for bit, in the same order.
template <class S, class T>
void require_same_particles(const S& a, const T& b, bool fixed = true) {
  const auto& p = a.particles();
  const auto& q = b.particles();
  REQUIRE(p.size() == q.size());
  for (std::size_t i = 0; i < p.size(); ++i) {
    CHECK(p.id[i] == q.id[i]);
    CHECK(p.radius[i] == q.radius[i]);
    CHECK(p.material[i] == q.material[i]);
    CHECK(p.mass[i] == q.mass[i]);
    CHECK(p.position[i] == q.position[i]);
    CHECK(p.velocity[i] == q.velocity[i]);
    CHECK(p.omega[i] == q.omega[i]);
    if (fixed) CHECK(p.inv_mass[i] == q.inv_mass[i]);
    if constexpr (S::thermal && T::thermal) CHECK(p.temperature[i] == q.temperature[i]);
  }
}

/// The same positions, velocities and temperatures bit for bit.
template <class S>
void require_same_motion(const S& a, const S& b) {
  const auto& p = a.particles();
  const auto& q = b.particles();
  REQUIRE(p.size() == q.size());
  std::size_t differ = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const std::size_t j = b.index_of(p.id[i]);
    if (p.position[i] != q.position[j] || p.velocity[i] != q.velocity[j] ||
        p.omega[i] != q.omega[j])
      ++differ;
    if constexpr (S::thermal)
      if (p.temperature[i] != q.temperature[j]) ++differ;
  }
  CHECK(differ == 0);
}

template <class S>
std::size_t touching(const S& sim) {
  std::size_t n = 0;
  sim.for_each_contact([&](auto, auto, bool, const auto&, const auto&, double) { ++n; });
  return n;
}

template <class S>
void csv_round_trip() {
  S a = packed_sim<S>();
  REQUIRE(a.size() >= 300);
  const std::string path = temp_path("round_trip_" + std::to_string(S::dimension) + "d.csv");
  io::write_state_csv(a, path);
  S b = empty_sim<S>();
  const auto state = io::read_state_csv(b, path);
  CHECK(state.particles.size() == a.size());
  CHECK(state.time == 0.0);
  CHECK(state.step == 0);
  REQUIRE(state.groups.size() == 3);
  CHECK(io::load_state(b, state) == a.size());
  require_same_particles(a, b);
  for (const char* g : {"hot", "bottom", "odd \"name\", with a comma"})
    CHECK(b.group(g).ids == a.group(g).ids);
  CHECK(!a.group("hot").ids.empty());

  // both run the same steps, with collisions and contacts with the floor
  std::size_t contacts = 0;
  for (int k = 0; k < 50; ++k) {
    a.steps(100);
    b.steps(100);
    contacts += touching(a);
  }
  CHECK(contacts > 100);
  require_same_motion(a, b);

  // a state written after steps: the time and step count come back, and the particles
  const std::string later = temp_path("later_" + std::to_string(S::dimension) + "d.csv");
  io::write_state_csv(a, later);
  S c = empty_sim<S>();
  const auto again = io::read_state_csv(c, later);
  CHECK(again.time == a.time());
  CHECK(again.step == 5000);
  io::load_state(c, again);
  require_same_particles(a, c);
}

/// A state written in the middle of a run, while no particles touch: the loaded simulation runs
/// on as the original, but not necessarily bit for bit. Its particles are in the order of the
/// original's last neighbour-list rebuild and its own rebuilds fall on other steps, so a particle
/// with three or more contact forces may add them in another order (rounding); the contact
/// histories start empty in both here.
template <class S>
void csv_mid_run() {
  S a = packed_sim<S>();
  a.steps(300);
  REQUIRE(touching(a) == 0);
  const std::string path = temp_path("mid_run_" + std::to_string(S::dimension) + "d.csv");
  io::write_state_csv(a, path);
  S b = empty_sim<S>();
  io::load_state(b, io::read_state_csv(b, path));
  std::size_t contacts = 0;
  for (int k = 0; k < 50; ++k) {
    a.steps(100);
    b.steps(100);
    contacts += touching(a);
  }
  CHECK(contacts > 100);
  double largest = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const std::size_t j = b.index_of(a.particles().id[i]);
    largest = std::max(largest, (a.particles().position[i] - b.particles().position[j]).norm());
  }
  CHECK(largest < 1e-12); // m, against radii of 1 mm
}

template <class S>
void vtk_round_trip(io::VtkFormat format) {
  S a = packed_sim<S>(false);
  a.steps(10); // orientations and forces that are not zero
  const std::string path =
      temp_path(std::string("round_trip_") + std::to_string(S::dimension) + "d_" +
                (format == io::VtkFormat::binary ? "binary" : "ascii") + ".vtk");
  io::write_particles_vtk(a, path, io::fields::all, format);
  S b = empty_sim<S>();
  const auto state = io::read_state_vtk(b, path);
  CHECK(state.time == a.time());
  CHECK(state.step == -1);
  CHECK(state.groups.empty());
  io::load_state(b, state);
  // ASCII files hold 17 significant digits, binary ones the doubles: both exact
  require_same_particles(a, b);
}

} // namespace

TEST_CASE("a CSV state of spheres reads back bit for bit and runs as the original") {
  csv_round_trip<Sim3>();
}

TEST_CASE("a CSV state of disks reads back bit for bit and runs as the original") {
  csv_round_trip<Sim2>();
}

TEST_CASE("a CSV state written in the middle of a run, between contacts, runs on") {
  csv_mid_run<Sim3>();
  csv_mid_run<Sim2>();
}

TEST_CASE("the CSV state file: comment, header, columns") {
  Sim3 a = packed_sim<Sim3>();
  const std::string path = temp_path("columns.csv");
  io::write_state_csv(a, path);
  const std::string text = read_text(path);
  CHECK(text.rfind("# grain state, dim=3, time=0, step=0, particles=320\n"
                   "id,radius [m],material,x [m],y [m],z [m],vx [m/s],vy [m/s],vz [m/s],"
                   "omegax [rad/s],omegay [rad/s],omegaz [rad/s],temperature [K],fixed,groups\n",
                   0) == 0);
  CHECK(has(text, "\"hot;odd \"\"name\"\", with a comma\"\n"));
  CHECK(!std::filesystem::exists(path + ".tmp"));

  Sim2 d = packed_sim<Sim2>();
  io::write_state_csv(d, path);
  CHECK(read_text(path).rfind("# grain state, dim=2, time=0, step=0, particles=300\n"
                              "id,radius [m],material,x [m],y [m],vx [m/s],vy [m/s],"
                              "omega [rad/s],temperature [K],fixed,groups\n",
                              0) == 0);

  // without groups and in a mechanical simulation: no groups and no temperature column
  Mech3 m = empty_sim<Mech3>();
  m.add_particle({.position = {0, 0, 0.01}, .radius = 0.001, .velocity = {0.5, 0, 0}});
  io::write_state_csv(m, path);
  CHECK(read_text(path) == "# grain state, dim=3, time=0, step=0, particles=1\n"
                           "id,radius [m],material,x [m],y [m],z [m],vx [m/s],vy [m/s],vz [m/s],"
                           "omegax [rad/s],omegay [rad/s],omegaz [rad/s],fixed\n"
                           "0,0.001,0,0,0,0.01,0.5,0,0,0,0,0,0\n");

  // one group's particles only
  io::write_state_csv(a, path, "hot");
  const auto hot = io::read_state_csv<Sim3>(path);
  CHECK(hot.particles.size() == a.group("hot").ids.size());
  for (const auto& p : hot.particles)
    CHECK(p.temperature > 370);

  // a group name the format cannot hold
  Sim3 s = empty_sim<Sim3>();
  const auto id = s.add_particle({.position = {0, 0, 0.01}, .radius = 0.001});
  s.add_group("a;b", {id});
  CHECK(has(error_of([&] { io::write_state_csv(s, temp_path("semicolon.csv")); }),
            {"grain::io::write_state_csv", "group name = 'a;b' is invalid"}));
}

TEST_CASE("a hand-written CSV state: any column order, units optional, defaults") {
  const std::string path = temp_path("hand.csv");
  write_text(path, "# a packing\r\n"
                   "\r\n"
                   "note, z,y , x [m], radius,vz, vy,vx,\"groups\",temperature,id,extra\r\n"
                   "first, 3, 2, 1, 0.5, 0, 0, 1e-3, \"left; top\", 300, 7, x\r\n"
                   "# a comment between particles\r\n"
                   "second, 0, 0, +2.5, 0.25, , , , , , , \r\n"
                   "third, 0, 0, 5, 0.25, , , , top, , 3, \r\n");
  const auto st = io::read_state_csv<Sim3>(path);
  REQUIRE(st.particles.size() == 3);
  const auto& p = st.particles[0];
  CHECK(p.position == Vec3(1, 2, 3));
  CHECK(p.radius == 0.5);
  CHECK(p.velocity == Vec3(1e-3, 0, 0));
  CHECK(p.omega == Vec3::Zero());
  CHECK(p.temperature == 300);
  CHECK(p.id == 7);
  CHECK(p.material == 0);
  CHECK(!p.fixed);
  const auto& q = st.particles[1];
  CHECK(q.position == Vec3(2.5, 0, 0));
  CHECK(q.velocity == Vec3::Zero());
  CHECK(std::isnan(q.temperature));
  CHECK(q.id == -1);
  CHECK(std::isnan(st.time));
  CHECK(st.step == -1);
  REQUIRE(st.groups.size() == 2);
  CHECK(st.groups[0].name == "left");
  CHECK(st.groups[0].members == std::vector<std::size_t>{0});
  CHECK(st.groups[1].name == "top");
  CHECK(st.groups[1].members == std::vector<std::size_t>{0, 2});

  Sim3 sim = empty_sim<Sim3>();
  io::load_state(sim, st);
  CHECK(sim.size() == 3);
  CHECK(sim.group("top").ids == std::vector<std::int64_t>{3, 7});
  CHECK(sim.particles().temperature[sim.index_of(8)] == sim.params().initial_temperature);

  // groups not re-created on request
  Sim3 plain = empty_sim<Sim3>();
  io::load_state(plain, st, {.groups = false});
  CHECK(plain.groups().size() == 1); // "all"

  // temperatures left out on request
  const auto cold = io::read_state_csv<Sim3>(path, {.temperatures = false});
  CHECK(std::isnan(cold.particles[0].temperature));
}

TEST_CASE("a mechanical simulation reads the state of a thermal one without its temperatures") {
  Sim3 a = packed_sim<Sim3>();
  const std::string path = temp_path("to_mechanical.csv");
  io::write_state_csv(a, path);
  Mech3 m = empty_sim<Mech3>();
  const auto st = io::read_state_csv(m, path);
  for (const auto& p : st.particles)
    CHECK(std::isnan(p.temperature));
  io::load_state(m, st);
  require_same_particles(a, m);
  // the thermal type's reading carries temperatures, which a mechanical simulation refuses
  const auto hot = io::read_state_csv<Sim3>(path);
  Mech3 n = empty_sim<Mech3>();
  CHECK(has(error_of([&] { io::load_state(n, hot); }),
            {"grain::io::load_state: particle 0", "the simulation is mechanical"}));
  CHECK(n.size() == 0);
}

TEST_CASE("VTK particle files read back as states, ASCII and binary, 2D and 3D") {
  vtk_round_trip<Sim3>(io::VtkFormat::ascii);
  vtk_round_trip<Sim3>(io::VtkFormat::binary);
  vtk_round_trip<Sim2>(io::VtkFormat::ascii);
  vtk_round_trip<Sim2>(io::VtkFormat::binary);

  // the frames of io::vtk, and a file with fewer fields
  Sim3 a = packed_sim<Sim3>(false);
  const std::string prefix = temp_path("series/bed");
  std::filesystem::remove_all(temp_path("series"));
  a.run(2e-5, io::every(1e-5, io::vtk(prefix, {.format = io::VtkFormat::binary})));
  const auto frames = io::detail::read_series(prefix, "particles");
  REQUIRE(frames.size() >= 3);
  const auto st = io::read_state_vtk<Sim3>(temp_path("series/" + frames.back().first));
  CHECK(st.time == a.time());
  Sim3 b = empty_sim<Sim3>();
  io::load_state(b, st);
  require_same_particles(a, b);

  const std::string few = temp_path("few_fields.vtk");
  io::write_particles_vtk(a, few, io::fields::radius | io::fields::velocity);
  const auto f = io::read_state_vtk<Sim3>(few);
  REQUIRE(f.particles.size() == a.size());
  CHECK(f.particles[4].id == -1);
  CHECK(f.particles[4].velocity == a.particles().velocity[4]);
  CHECK(f.particles[4].omega == Vec3::Zero());
  CHECK(std::isnan(f.particles[4].temperature));
  CHECK(f.particles[4].material == 0);

  // a mechanical simulation ignores the temperatures
  Mech3 m = empty_sim<Mech3>();
  io::load_state(m, io::read_state_vtk(m, prefix + "_particles_000001.vtk"));
  CHECK(m.size() == a.size());
}

TEST_CASE("bad CSV state files are refused naming the file, the line and the value") {
  const std::string path = temp_path("bad.csv");
  const std::string head = "# grain state, dim=3, time=0, step=0\n"
                           "id,radius [m],material,x [m],y [m],z [m],vx [m/s],vy [m/s],vz [m/s]\n";
  const std::string good = "0,0.001,0,0,0,0.01,0,0,0\n";
  const auto error = [&](const std::string& text, const Sim3* sim = nullptr) {
    write_text(path, text);
    return error_of([&] {
      if (sim)
        (void)io::read_state_csv(*sim, path);
      else
        (void)io::read_state_csv<Sim3>(path);
    });
  };
  const std::string at = "grain::io::read_state_csv: '" + path + "' line ";

  std::string e = error("# grain state, dim=3\nid,x,y,z,vx\n");
  CHECK(has(e, {at.c_str(), "line 2: header = 'id,x,y,z,vx' is invalid", "'radius [m]'",
                "'vy [m/s]'", "'vz [m/s]'"}));
  e = error(head + good + "1,0.001,0,abc,0,0.01,0,0,0\n");
  CHECK(has(e, (at + "4: x [m] = 'abc' is invalid; valid range: a finite number [m]").c_str()));
  e = error(head + good + "1,0.001,0,0,0,0.01,nan,0,0\n");
  CHECK(has(e, (at + "4: vx [m/s] = 'nan' is invalid").c_str()));
  e = error(head + "1,-0.001,0,0,0,0.01,0,0,0\n");
  CHECK(has(e, (at + "3: radius [m] = '-0.001' is invalid; valid range: (0, inf) m").c_str()));
  e = error(head + "1,0,0,0,0,0.01,0,0,0\n");
  CHECK(has(e, (at + "3: radius [m] = '0' is invalid").c_str()));
  e = error(head + good + "\n1,0.001,0,1,0,0.01,0,0,0\n0,0.001,0,2,0,0.01,0,0,0\n");
  CHECK(has(e, (at + "6: id = '0' is invalid; valid: an id no other particle has (line 3 has "
                     "it)")
                   .c_str()));
  e = error("# grain state, dim=2, time=0, step=0\nid,radius,x,y\n0,0.001,0,0\n");
  CHECK(
      has(e, (at + "1: dim = '2' is invalid; valid: 3, the dimension of the simulation").c_str()));
  e = error("id,radius,x,y,omega\n0,0.001,0,0,0\n");
  CHECK(has(e, (at + "1: column = 'omega' is invalid").c_str()));
  e = error(head + good + "1,0.001,0,0,0,0.01,0\n");
  CHECK(has(e, (at + "4: cells = 7 is invalid; valid: 9, one per column of the header on line 2 "
                     "(a line cut short?)")
                   .c_str()));
  e = error(head + good + "1,0.001,0,0,0,0.01,0,0,0,5\n");
  CHECK(has(e, (at + "4: cells = 10 is invalid").c_str()));
  e = error("");
  CHECK(has(e, (at + "1: header = '' (the file is empty) is invalid").c_str()));
  e = error("# grain state, dim=3\n\n");
  CHECK(has(e, (at + "2: header = none (only comments) is invalid").c_str()));
  e = error("# grain state, dim=3, particles=3\n" + head.substr(head.find('\n') + 1) + good);
  CHECK(has(
      e, (at + "3: particle lines = 1 is invalid; valid: 3, the number given on line 1").c_str()));
  e = error(head + "0,0.001,5,0,0,0.01,0,0,0\n");
  CHECK(e.empty()); // no simulation: any material index
  const Sim3 sim = empty_sim<Sim3>();
  e = error(head + "0,0.001,5,0,0,0.01,0,0,0\n", &sim);
  CHECK(has(e, (at + "3: material = '5' is invalid; valid range: [0, 1] (the indices of the "
                     "simulation's 2 materials)")
                   .c_str()));
  e = error("id,radius,x,y,z,temperature\n0,0.001,0,0,0,-3\n");
  CHECK(has(e, (at + "2: temperature = '-3' is invalid; valid range: [0, inf) K").c_str()));
  e = error("id,radius [mm],x,y,z\n0,1,0,0,0\n");
  CHECK(has(
      e, (at + "1: unit of column 'radius [mm]' = 'mm' is invalid; valid: m (SI units)").c_str()));
  e = error("id,radius,x,y,z,fixed\n0,0.001,0,0,0,2\n");
  CHECK(has(e, (at + "2: fixed = '2' is invalid; valid: 0 (free) or 1 (fixed)").c_str()));
  e = error("id,radius,x,y,z,groups\n0,0.001,0,0,0,\"a\n");
  CHECK(has(e, (at + "2: line = '0,0.001,0,0,0,\"a' is invalid").c_str()));
  e = error("id,radius,x,y,z,groups\n0,0.001,0,0,0,all\n");
  CHECK(has(e, (at + "2: groups = 'all' is invalid").c_str()));
  e = error("id,radius,x,y,z\n9223372036854775807,0.001,0,0,0\n");
  CHECK(has(e, (at + "2: id = '9223372036854775807' is invalid").c_str()));
  e = error("id,radius,x,y,z,x\n");
  CHECK(has(e, (at + "1: column = 'x' is invalid; valid: a column named once").c_str()));

  const std::string missing = temp_path("no such file.csv");
  std::filesystem::remove(missing);
  CHECK(has(error_of([&] { (void)io::read_state_csv<Sim3>(missing); }),
            ("grain::io::read_state_csv: file = '" + missing + "' is invalid: it does not exist")
                .c_str()));
  CHECK(has(error_of([&] { (void)io::read_state_csv<Sim3>(temp_path("")); }),
            "is invalid: it is not a regular file"));
}

TEST_CASE("bad VTK particle files are refused naming the file and what was expected") {
  Sim3 a = packed_sim<Sim3>(false);
  const std::string ascii = temp_path("bad_source_ascii.vtk");
  const std::string binary = temp_path("bad_source_binary.vtk");
  io::write_particles_vtk(a, ascii);
  io::write_particles_vtk(a, binary, io::fields::all, io::VtkFormat::binary);
  const std::string path = temp_path("bad.vtk");
  const auto error = [&](const std::string& text) {
    write_text(path, text);
    return error_of([&] { (void)io::read_state_vtk<Sim3>(path); });
  };
  const std::string at = "grain::io::read_state_vtk: '" + path + "' ";
  const std::string full = read_text(binary);
  const std::string text = read_text(ascii);

  // a wall file
  const std::string walls = temp_path("walls.vtk");
  io::write_walls_vtk(a, walls);
  CHECK(has(error_of([&] { (void)io::read_state_vtk<Sim3>(walls); }),
            {walls.c_str(), "line 2", "expected a particle file", "this is a wall file"}));
  // not VTK at all
  CHECK(has(error("id,radius,x\n"), {(at + "line 1").c_str(), "# vtk DataFile Version"}));
  CHECK(has(error(""), {(at + "line 1").c_str(), "# vtk DataFile Version"}));
  // cut short, binary and ASCII
  for (const std::size_t keep : {full.size() / 3, full.size() / 2, full.size() - 9})
    CHECK(has(error(full.substr(0, keep)), {at.c_str(), "expected"}));
  CHECK(has(error(text.substr(0, text.size() / 2)), {at.c_str(), "expected"}));
  // a count the file cannot hold: refused before anything is allocated
  std::string huge = text;
  huge.replace(huge.find("POINTS 320"), 10, "POINTS 999999999999");
  CHECK(has(error(huge), {(at + "line 5").c_str(), "cannot hold 999999999999"}));
  huge = full;
  huge.replace(huge.find("POINTS 320"), 10, "POINTS 18446744073709551615");
  CHECK(has(error(huge), {(at + "byte").c_str(), "cannot hold 18446744073709551615"}));
  // no radius
  const std::string no_radius = temp_path("no_radius.vtk");
  io::write_particles_vtk(a, no_radius, io::fields::id | io::fields::velocity);
  CHECK(has(error_of([&] { (void)io::read_state_vtk<Sim3>(no_radius); }),
            {no_radius.c_str(), "expected a point array 'radius'"}));
  // a number that is not one
  const std::string radii = "SCALARS radius double 1\nLOOKUP_TABLE default\n";
  std::string word = text;
  word.replace(word.find(radii) + radii.size(), 1, "x");
  CHECK(has(error(word), {at.c_str(), "expected a number, not '"}));
  // a negative radius
  std::string negative = text;
  negative.insert(negative.find(radii) + radii.size(), "-");
  CHECK(has(error(negative), {(at + "array 'radius' at line").c_str(), "point 0: radius = -0.",
                              "valid range: (0, inf) m"}));
  // a duplicate id
  std::string twice = text;
  const std::string id_array = "SCALARS id long 1\nLOOKUP_TABLE default\n";
  const std::size_t ids = twice.find(id_array) + id_array.size();
  twice.replace(ids, 3, "1\n1");
  CHECK(has(error(twice), {"point 1: id = 1 is invalid; valid: an id no other point has (point 0 "
                           "has it)"}));
  // a 3D file read by a 2D simulation: its orientations, or its centres
  CHECK(has(error_of([&] { (void)io::read_state_vtk<Sim2>(ascii); }),
            {ascii.c_str(), "array 'orientation' = 4 components is invalid",
             "this file is of a 3D simulation"}));
  const std::string centres = temp_path("centres.vtk");
  io::write_particles_vtk(a, centres, io::fields::radius);
  CHECK(has(error_of([&] { (void)io::read_state_vtk<Sim2>(centres); }),
            {centres.c_str(), "POINTS at line 5, point 0: z = ",
             "valid: 0 (a 2D simulation reads the files of disks"}));
  // a material the simulation does not have
  Sim3 no_materials({.time_step = 1e-6});
  CHECK(has(error_of([&] { (void)io::read_state_vtk(no_materials, ascii); }),
            {"point 0: material = 0 is invalid; valid: none (the simulation has no materials"}));
  // missing
  CHECK(has(error_of([&] { (void)io::read_state_vtk<Sim3>(temp_path("none.vtk")); }),
            "it does not exist"));
}

TEST_CASE("load_state checks before it adds") {
  Sim3 a = packed_sim<Sim3>();
  const std::string path = temp_path("twice.csv");
  io::write_state_csv(a, path);
  const auto st = io::read_state_csv(a, path);
  Sim3 b = empty_sim<Sim3>();
  io::load_state(b, st);
  const std::size_t n = b.size();
  // the same ids again
  CHECK(has(error_of([&] { io::load_state(b, st); }),
            {"grain::io::load_state: particle 0 (id 0) of the state: id = 0 is invalid"}));
  CHECK(b.size() == n);
  // the same groups again, with new ids
  auto fresh = st;
  for (auto& p : fresh.particles)
    p.id = -1;
  CHECK(has(error_of([&] { io::load_state(b, fresh); }),
            {"grain::io::load_state: group '", "' of the state: name = '",
             "' is invalid; valid: a name no group of the simulation has"}));
  CHECK(b.size() == n);
  // without the groups: added with the next free ids
  CHECK(io::load_state(b, fresh, {.groups = false}) == st.particles.size());
  CHECK(b.size() == 2 * n);
  // a material the simulation does not have
  Sim3 c = empty_sim<Sim3>();
  auto other = st.particles;
  other[3].material = 2;
  CHECK(has(error_of([&] { io::load_state(c, other); }),
            "particle 3 (id 3) of the state: material = 2 is invalid; valid range: [0, 2)"));
  CHECK(c.size() == 0);
}

TEST_CASE("add_particle refuses the largest id (it has no next one)") {
  Sim3 s = empty_sim<Sim3>();
  CHECK(has(error_of([&] {
              s.add_particle({.position = {0, 0, 0.01},
                              .radius = 0.001,
                              .id = std::numeric_limits<std::int64_t>::max()});
            }),
            "id = 9223372036854775807 is invalid; valid range: [0, 9223372036854775806]"));
  CHECK(s.add_particle({.position = {0, 0, 0.01},
                        .radius = 0.001,
                        .id = std::numeric_limits<std::int64_t>::max() - 1}) ==
        std::numeric_limits<std::int64_t>::max() - 1);
  CHECK(has(error_of([&] {
              s.add_particle({.position = {0, 0, 0.05}, .radius = 0.001});
            }),
            "id = 9223372036854775807 is invalid"));
}
