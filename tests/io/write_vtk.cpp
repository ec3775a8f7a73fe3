// Writes legacy VTK files of a small 2D disk simulation and a small 3D sphere simulation with
// io::every(interval, io::vtk(prefix, ...), ...), together with expected.json: the state of each
// simulation at every output, taken straight from its arrays. read_vtk.py reads the VTK files back
// and compares them with expected.json.
//
// Each run feeds several writers from the same every(), one series each (see kVariants): ASCII
// and binary, every field and a chosen few, every particle, a group and an empty group.
// expected.json records, per series, the options it was written with; per run, every field of
// every particle, the walls, the contacts and the groups' members at every output.
//
// The sphere run has an obstacle (two triangles that move and turn about a reference point): its
// triangles are walls like the others, so the files show them moving.
//
// It also checks the errors: a thermal field asked of a mechanical simulation, an unknown field
// name and an unknown group are InputErrors that name what is wrong and what is valid, raised
// before any file is written.
//
// Usage: grain_write_vtk <output directory>

#include <grain/grain.hpp>

#include <cstdio>
#include <cstring>
#include <exception>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <variant>
#include <vector>

namespace {

constexpr long kSteps = 10;         // steps per run
constexpr long kStepsPerOutput = 3; // output interval in steps
// every() fires at the start, at each multiple of the interval and at the end.
constexpr long kExpectedFiles = 1 + kSteps / kStepsPerOutput + (kSteps % kStepsPerOutput != 0);
constexpr int kCircleSegments = 64; // default of write_walls_vtk
constexpr double kPlaneSize = 0.25; // passed to io::vtk

std::string num(double x) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", x);
  return buf;
}
template <int D>
std::string vec(const grain::Vec<D>& v) {
  std::string s = "[";
  for (int d = 0; d < D; ++d)
    s += num(v[d]) + (d + 1 < D ? ", " : "]");
  return s;
}
std::string angular(double w) { return "[0, 0, " + num(w) + "]"; }
std::string angular(const grain::Vec3& w) { return vec<3>(w); }
std::string orientation(double angle) { return num(angle); }
std::string orientation(const Eigen::Quaterniond& q) {
  return "[" + num(q.w()) + ", " + num(q.x()) + ", " + num(q.y()) + ", " + num(q.z()) + "]";
}
std::string quoted(const std::string& s) { return "\"" + s + "\""; }

/// One series written from a run: its name's suffix and the options of its io::vtk writer.
struct Variant {
  const char* suffix;                      // series name = run name + suffix
  const char* format;                      // "ascii" or "binary"
  std::vector<std::string> fields;         // for io::fields::named ({"all"} = the default)
  std::vector<std::string> thermal_fields; // added to `fields` in a thermal run
  const char* group;                       // "" = every particle
  bool contacts;
  std::optional<grain::io::Fields> bits{}; // if given: the writer's fields, = named(fields)
};
namespace fields = grain::io::fields;
/// Groups of the runs: "pair" (two particles, so that some contacts touch it and some do not)
/// and "nobody" (empty).
const std::vector<Variant> kVariants = {
    {"", "ascii", {"all"}, {}, "", true}, // the positional io::vtk(prefix, plane_size, contacts)
    {"_binary", "binary", {"all"}, {}, "", true},
    {"_fields",
     "ascii",
     {"velocity", "orientation", "material", "torque"},
     {},
     "",
     false,
     fields::torque | fields::material | fields::velocity | fields::orientation},
    {"_fields_binary",
     "binary",
     {"mass", "id", "omega"},
     {"heat_rate", "heat_capacity"},
     "",
     false},
    {"_group", "binary", {"all"}, {}, "pair", true},
    {"_group_fields", "ascii", {"radius", "force"}, {"temperature"}, "pair", true},
    {"_empty", "ascii", {"all"}, {}, "nobody", true},
    {"_empty_binary", "binary", {"id", "velocity"}, {}, "nobody", true},
};
const char* const kGroups[] = {"pair", "nobody"};

/// The field names of a variant in a run.
std::vector<std::string> field_names(const Variant& v, bool thermal) {
  std::vector<std::string> out = v.fields;
  if (thermal) out.insert(out.end(), v.thermal_fields.begin(), v.thermal_fields.end());
  return out;
}

/// The io::vtk writer of a variant (the first one through the positional overload).
grain::io::VtkWriter writer(const std::filesystem::path& prefix, const Variant& v, bool thermal,
                            bool& ok) {
  namespace io = grain::io;
  if (v.suffix[0] == '\0') return io::vtk(prefix.string(), kPlaneSize, v.contacts);
  const io::Fields named = io::fields::named(field_names(v, thermal));
  if (v.bits && *v.bits != named) {
    std::fprintf(stderr, "write_vtk: %s: fields::named gives bits %#x, the operators %#x\n",
                 v.suffix, named.bits, v.bits->bits);
    ok = false;
  }
  return io::vtk(prefix.string(),
                 {.plane_size = kPlaneSize,
                  .contacts = v.contacts,
                  .fields = v.bits ? *v.bits : named,
                  .group = v.group,
                  .format = std::strcmp(v.format, "binary") == 0 ? io::VtkFormat::binary
                                                                 : io::VtkFormat::ascii});
}

/// JSON text of one wall geometry.
std::string wall_json(const grain::walls::Segment& g) {
  return R"({"type": "segment", "a": )" + vec<2>(g.a) + R"(, "b": )" + vec<2>(g.b) + "}";
}
std::string wall_json(const grain::walls::Circle& g) {
  return R"({"type": "circle", "center": )" + vec<2>(g.center) + R"(, "radius": )" + num(g.radius) +
         "}";
}
std::string wall_json(const grain::walls::Plane& g) {
  return R"({"type": "plane", "point": )" + vec<3>(g.point) + R"(, "normal": )" + vec<3>(g.normal) +
         "}";
}
std::string wall_json(const grain::walls::Triangle& g) {
  return R"({"type": "triangle", "a": )" + vec<3>(g.a) + R"(, "b": )" + vec<3>(g.b) + R"(, "c": )" +
         vec<3>(g.c) + "}";
}

/// Output action run right after io::vtk in the same every(): records the state the VTK writer
/// has just seen, read from the simulation's own arrays.
struct Recorder {
  std::vector<std::string>* frames;
  template <class Sim>
  void operator()(const Sim& sim) const {
    const auto& p = sim.particles();
    std::ostringstream o;
    o << "{\"time\": " << num(sim.time()) << ",\n       \"particles\": [";
    for (std::size_t i = 0; i < p.size(); ++i) {
      o << (i ? ",\n         " : "\n         ") << "{\"id\": " << p.id[i]
        << ", \"position\": " << vec<Sim::dimension>(p.position[i])
        << ", \"radius\": " << num(p.radius[i])
        << ", \"velocity\": " << vec<Sim::dimension>(p.velocity[i])
        << ", \"omega\": " << angular(p.omega[i])
        << ", \"force\": " << vec<Sim::dimension>(p.force[i])
        << ", \"torque\": " << angular(p.torque[i]) << ", \"mass\": " << num(p.mass[i])
        << ", \"orientation\": " << orientation(p.orientation[i])
        << ", \"material\": " << p.material[i];
      if constexpr (Sim::thermal)
        o << ", \"temperature\": " << num(p.temperature[i])
          << ", \"heat_rate\": " << num(p.heat_rate[i])
          << ", \"heat_capacity\": " << num(p.heat_capacity[i]);
      o << "}";
    }
    o << "],\n       \"walls\": [";
    for (std::size_t w = 0; w < sim.walls().size(); ++w) {
      o << (w ? ",\n         " : "\n         ")
        << std::visit([](const auto& g) { return wall_json(g); }, sim.walls()[w].geometry);
      o.seekp(-1, std::ios_base::cur); // reopen the wall's object
      o << ", \"present\": " << (sim.walls()[w].present ? 1 : 0) << "}";
      if constexpr (Sim::thermal) {
        const auto& wall = sim.walls()[w];
        o.seekp(-1, std::ios_base::cur); // reopen the wall's object
        o << ", \"conducts\": " << (wall.conducts() ? 1 : 0)
          << ", \"temperature\": " << num(wall.conducts() ? wall.temperature : 0.0) << "}";
      }
    }
    o << "],\n       \"contacts\": [";
    bool first = true;
    sim.for_each_contact([&](std::size_t i, std::size_t j, bool wall, const auto& g, const auto& r,
                             double q) {
      using C = typename Sim::contact_type;
      const auto& pair = sim.pair_properties(p.material[i], wall ? sim.walls()[j].options.material
                                                                 : p.material[j]);
      o << (first ? "\n         " : ",\n         ") << "{\"id_i\": " << p.id[i]
        << ", \"id_j\": " << (wall ? -1 : p.id[j]) << ", \"wall\": " << (wall ? long(j) : -1L)
        << ", \"normal_force\": " << num(r.normal.force)
        << ", \"normal_viscous\": " << num(r.normal.viscous)
        << ", \"tangential_force\": " << vec<Sim::dimension>(r.tangent.force)
        << ", \"normal\": " << vec<Sim::dimension>(g.normal) << ", \"overlap\": " << num(g.overlap)
        << ", \"contact_radius\": "
        << num(C::area_model::radius(g, pair, r.normal, sim.params().contact.area))
        << ", \"heat_rate\": " << num(q) << "}";
      first = false;
    });
    o << "],\n       \"groups\": {";
    for (const char* g : kGroups) {
      o << (g == kGroups[0] ? "" : ", ") << quoted(g) << ": [";
      const auto& members = sim.group_indices(g);
      for (std::size_t k = 0; k < members.size(); ++k)
        o << (k ? ", " : "") << p.id[members[k]];
      o << "]";
    }
    o << "}}";
    frames->push_back(o.str());
  }
};

/// Checks that the run exercises every field: some particle has a non-zero value of each.
template <class Sim>
bool exercised(const Sim& sim, const char* name) {
  const auto& p = sim.particles();
  bool force = false, velocity = false, omega = false, torque = false;
  for (std::size_t i = 0; i < p.size(); ++i) {
    force = force || p.force[i].norm() > 0;
    velocity = velocity || p.velocity[i].norm() > 0;
    omega = omega || grain::norm(p.omega[i]) > 0;
    torque = torque || grain::norm(p.torque[i]) > 0;
  }
  const auto [pp, pw] = sim.contact_counts();
  if (force && velocity && omega && torque && pp > 0 && pw > 0) return true;
  std::fprintf(stderr,
               "write_vtk: the %s set-up is degenerate (force %d, velocity %d, omega %d, "
               "torque %d, %zu particle and %zu wall contacts)\n",
               name, force, velocity, omega, torque, pp, pw);
  return false;
}

/// The writers of every variant of a run, as one output action.
struct Writers {
  std::vector<grain::io::VtkWriter> all;
  template <class Sim>
  void start(const Sim& sim) {
    for (auto& w : all)
      w.start(sim);
  }
  template <class Sim>
  void operator()(const Sim& sim) {
    for (auto& w : all)
      w(sim);
  }
};

/// Expects f() to throw grain::InputError whose message holds every one of `words`.
template <class F>
bool expect_input_error(const char* what, F f, std::initializer_list<const char*> words) {
  try {
    f();
  } catch (const grain::InputError& e) {
    for (const char* w : words) {
      if (std::strstr(e.what(), w) == nullptr) {
        std::fprintf(stderr, "write_vtk: %s: the message '%s' does not mention '%s'\n", what,
                     e.what(), w);
        return false;
      }
    }
    return true;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "write_vtk: %s: threw '%s', expected an InputError\n", what, e.what());
    return false;
  }
  std::fprintf(stderr, "write_vtk: %s: no error, expected an InputError\n", what);
  return false;
}

/// The input errors of io::vtk, after the run; each must be raised before a file is written
/// (read_vtk.py reports any file of a series it does not know, such as these "bad_" ones).
template <class Sim>
bool check_errors(Sim& sim, const std::filesystem::path& dir) {
  namespace io = grain::io;
  const double interval = sim.time_step();
  bool ok = true;
  if constexpr (!Sim::thermal) {
    ok = expect_input_error(
             "a thermal field of a mechanical simulation (io::vtk)",
             [&] {
               sim.steps(1, io::every(interval, io::vtk((dir / "bad_fields").string(),
                                                        {.fields = io::fields::velocity |
                                                                   io::fields::temperature})));
             },
             {"grain::io::vtk: field = 'temperature'", "mechanical simulation",
              "valid values: id, radius, velocity, omega, force, torque, mass, orientation, "
              "material, all"}) &&
         ok;
    ok = expect_input_error(
             "a thermal field of a mechanical simulation (write_particles_vtk)",
             [&] {
               io::write_particles_vtk(sim, (dir / "bad_direct_particles_000000.vtk").string(),
                                       io::fields::id | io::fields::heat_capacity);
             },
             {"write_particles_vtk", "field = 'heat_capacity'", "valid values: id, radius"}) &&
         ok;
  }
  ok = expect_input_error("an unknown field name",
                          [] {
                            (void)io::fields::named({"velocity", "temprature"});
                          },
                          {"field = 'temprature'", "temperature, heat_rate, heat_capacity, all"}) &&
       ok;
  ok = expect_input_error("an unknown group",
                          [&] {
                            sim.steps(1, io::every(interval, io::vtk((dir / "bad_group").string(),
                                                                     {.group = "nosuch"})));
                          },
                          {"'nosuch'", "'pair'", "'nobody'"}) &&
       ok;
  // outside every() the writer first runs after a step: start() must check before the run
  const long steps = sim.step_count();
  ok = expect_input_error(
           "an unknown group (io::vtk as an observer of steps)",
           [&] {
             sim.steps(1, io::vtk((dir / "bad_group_observer").string(), {.group = "nosuch"}));
           },
           {"'nosuch'", "'pair'"}) &&
       ok;
  if (sim.step_count() != steps) {
    std::fprintf(stderr, "write_vtk: the unknown group was found only after the run started\n");
    ok = false;
  }
  return ok;
}

/// Runs a simulation with one io::vtk writer per variant; appends the JSON text of the run to
/// `runs` and of its series to `series`.
template <class Sim>
void run_series(Sim& sim, const std::filesystem::path& dir, const std::string& name,
                std::string& runs, std::string& series, bool& ok) {
  sim.initialize();
  const double interval = static_cast<double>(kStepsPerOutput) * sim.time_step();
  std::vector<std::string> frames;
  Writers writers;
  for (const auto& v : kVariants) {
    writers.all.push_back(writer(dir / (name + v.suffix), v, Sim::thermal, ok));
    std::string fields;
    for (const auto& f : field_names(v, Sim::thermal))
      fields += (fields.empty() ? "" : ", ") + quoted(f);
    series += (series.empty() ? "\n  " : ",\n  ") + quoted(name + v.suffix) +
              ": {\"run\": " + quoted(name) + ", \"format\": " + quoted(v.format) +
              ", \"fields\": [" + fields +
              "], \"group\": " + (v.group[0] ? quoted(v.group) : std::string("null")) +
              ", \"contacts\": " + (v.contacts ? "true" : "false") + "}";
  }
  sim.steps(kSteps, grain::io::every(interval, std::move(writers), Recorder{&frames}));
  if (static_cast<long>(frames.size()) != kExpectedFiles) {
    std::fprintf(stderr, "write_vtk: %s: every() fired %zu times, expected %ld\n", name.c_str(),
                 frames.size(), kExpectedFiles);
    ok = false;
  }
  ok = exercised(sim, name.c_str()) && ok;
  const double final_time = sim.time();
  ok = check_errors(sim, dir) && ok;
  runs += (runs.empty() ? "\n  " : ",\n  ") + quoted(name) +
          ": {\"dimension\": " + std::to_string(Sim::dimension) +
          ", \"thermal\": " + (Sim::thermal ? "true" : "false") +
          ", \"particle_count\": " + std::to_string(sim.size()) +
          ", \"wall_count\": " + std::to_string(sim.walls().size()) +
          ", \"wall_cells\": " + std::to_string(sim.walls().size()) +
          ", \"files\": " + std::to_string(kExpectedFiles) +
          ", \"final_time\": " + num(final_time) + ",\n     \"frames\": [";
  for (std::size_t k = 0; k < frames.size(); ++k)
    runs += (k ? ",\n      " : "\n      ") + frames[k];
  runs += "]}";
}

grain::Material material() {
  grain::Material m;
  m.name = "glass";
  m.density = 2500.0;
  m.young = 1e7;
  m.poisson = 0.25;
  m.restitution = 0.6;
  m.friction = 0.4;
  return m;
}

using Contact =
    grain::Interaction<grain::normal::LinearSpringDashpot, grain::tangent::SpringDashpotSlider>;
/// The sphere series is thermo-mechanical: particles and walls also carry temperatures.
using ThermalContact =
    grain::Interaction<grain::normal::LinearSpringDashpot, grain::tangent::SpringDashpotSlider,
                       grain::rolling::None, grain::conduction::BatchelorOBrien>;

void disks(const std::filesystem::path& dir, std::string& runs, std::string& series, bool& ok) {
  grain::SimulationParams<2, Contact, grain::search::AllPairs> params;
  params.gravity = grain::Vec2(0.0, -9.81);
  params.max_start_overlap = std::numeric_limits<double>::infinity(); // a random pile
  grain::Simulation<grain::Disk, grain::search::AllPairs, Contact> sim(params,
                                                                       grain::Disk{0.01, false});
  const auto m = sim.add_material(material());
  // ids out of order, so that the reader has to match particles by id
  sim.add_particle({.position = {-0.02, -0.04},
                    .radius = 0.011,
                    .material = m,
                    .velocity = {0.031, -0.012},
                    .omega = 1.5,
                    .id = 7});
  sim.add_particle({.position = {0.0021, -0.039},
                    .radius = 0.012,
                    .material = m,
                    .velocity = {-0.024, 0.017},
                    .omega = -2.25,
                    .id = 3});
  sim.add_particle({.position = {0.0245, -0.0405},
                    .radius = 0.0105,
                    .material = m,
                    .velocity = {0.0, 0.043},
                    .omega = 0.75,
                    .id = 12});
  sim.add_particle({.position = {0.0013, 0.0895},
                    .radius = 0.0113,
                    .material = m,
                    .velocity = {0.052, 0.011},
                    .omega = -3.5,
                    .id = 5});
  sim.add_particle({.position = {-0.05, 0.02},
                    .radius = 0.0097,
                    .material = m,
                    .velocity = {-0.013, -0.029},
                    .omega = 0.0,
                    .id = 40});
  grain::WallOptions<2> moving;
  moving.name = "floor";
  moving.material = m;
  moving.velocity = grain::Vec2(0.004, 0.002);
  sim.add_wall(grain::walls::Segment{{-0.08, -0.05}, {0.09, -0.0499}}, moving);
  grain::WallOptions<2> drum;
  drum.name = "drum";
  drum.material = m;
  drum.velocity = grain::Vec2(-0.003, 0.001);
  drum.omega = 2.0;
  sim.add_wall(grain::walls::Circle{{0.0007, -0.0003}, 0.1}, drum);
  // 7 touches 3 and the floor; 3 and 12 touch each other and the floor without 7 or 40
  sim.add_group("pair", {7, 40});
  sim.add_group("nobody", {});
  run_series(sim, dir, "disks", runs, series, ok);
}

void spheres(const std::filesystem::path& dir, std::string& runs, std::string& series, bool& ok) {
  grain::Simulation<grain::Sphere, grain::search::CellList, ThermalContact>::Params params;
  params.gravity = grain::Vec3(0.0, 0.0, -9.81);
  params.max_start_overlap = std::numeric_limits<double>::infinity();
  params.initial_temperature = 310.0;
  grain::Simulation<grain::Sphere, grain::search::CellList, ThermalContact> sim(params);
  grain::Material mat = material();
  mat.conductivity = 1.0;
  mat.heat_capacity = 800.0;
  const auto m = sim.add_material(mat);
  // ids in reverse spatial order: the cell list re-sorts the arrays
  sim.add_particle({.position = {0.09, 0.01, 0.0095},
                    .radius = 0.0105,
                    .material = m,
                    .velocity = {0.012, -0.021, 0.005},
                    .omega = {0.5, -1.25, 2.0},
                    .temperature = 350.0,
                    .id = 20});
  sim.add_particle({.position = {0.0695, 0.0105, 0.0097},
                    .radius = 0.0102,
                    .material = m,
                    .velocity = {-0.031, 0.004, 0.0},
                    .omega = {-1.5, 0.0, 0.25},
                    .id = 4});
  sim.add_particle({.position = {0.02, -0.03, 0.0118},
                    .radius = 0.012,
                    .material = m,
                    .velocity = {0.0, 0.0, -0.041},
                    .omega = {0.0, 3.0, 0.0},
                    .id = 9});
  sim.add_particle({.position = {0.1002, -0.0011, 0.0398},
                    .radius = 0.0107,
                    .material = m,
                    .velocity = {0.007, 0.009, -0.011},
                    .omega = {1.0, 1.0, -1.0},
                    .id = 15});
  sim.add_particle({.position = {-0.01, -0.06, 0.05},
                    .radius = 0.0093,
                    .material = m,
                    .velocity = {0.021, 0.033, -0.017},
                    .omega = {0.0, 0.0, 0.0},
                    .id = 1});
  grain::WallOptions<3> floor;
  floor.name = "floor";
  floor.material = m;
  floor.velocity = grain::Vec3(0.0, 0.0, 0.003);
  floor.temperature = grain::TimeFunction::linear(290.0, 100.0); // K, K/s
  sim.add_wall(grain::walls::Plane{{0.01, -0.02, 0.0}, grain::Vec3(0.01, -0.005, 1.0).normalized()},
               floor);
  grain::WallOptions<3> tilted;
  tilted.name = "shelf";
  tilted.material = m;
  tilted.omega = grain::Vec3(0.4, -0.3, 1.2);
  sim.add_wall(
      grain::walls::Triangle{{0.05, -0.05, 0.03}, {0.15, -0.045, 0.031}, {0.1, 0.05, 0.0295}},
      tilted);
  // an obstacle: a square of two triangles that moves and turns about its reference point; 1
  // rests on it exactly over the shared diagonal (one contact)
  grain::add_obstacle(sim,
                      grain::walls::TriangleMesh{{{-0.03, -0.08, 0.0409},
                                                  {0.01, -0.08, 0.0409},
                                                  {0.01, -0.04, 0.0409},
                                                  {-0.03, -0.04, 0.0409}},
                                                 {{0, 1, 2}, {0, 2, 3}}},
                      {.name = "tray",
                       .material = m,
                       .reference_point = {-0.01, -0.06, 0.0409},
                       .velocity = grain::Vec3(0.002, 0.0, 0.001),
                       .omega = grain::Vec3(0.0, 0.0, 2.0),
                       .temperature = 330.0});
  // a gate switched off: written with present = 0
  grain::WallOptions<3> gate;
  gate.name = "gate";
  gate.material = m;
  gate.active = false;
  sim.add_wall(grain::walls::Plane{{0.0, 0.0, 0.5}, grain::Vec3(0.0, 0.0, -1.0)}, gate);
  // 4 touches 20 and the floor; 20, 9 and 15 have contacts without 4 or 1; 1 touches the tray
  sim.add_group("pair", {4, 1});
  sim.add_group("nobody", {});
  run_series(sim, dir, "spheres", runs, series, ok);
}

} // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s <output directory>\n", argv[0]);
    return 2;
  }
  try {
    const std::filesystem::path dir(argv[1]);
    std::filesystem::create_directories(dir);
    bool ok = true;
    std::string runs, series;
    disks(dir, runs, series, ok);
    spheres(dir, runs, series, ok);
    std::ofstream o(dir / "expected.json");
    o << "{\"circle_segments\": " << kCircleSegments << ", \"plane_size\": " << num(kPlaneSize)
      << ",\n \"series\": {" << series << "},\n \"runs\": {" << runs << "}}\n";
    o.close();
    if (!o) {
      std::fprintf(stderr, "write_vtk: cannot write %s\n",
                   (dir / "expected.json").string().c_str());
      return 1;
    }
    return ok ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "write_vtk: %s\n", e.what());
    return 1;
  }
}
