// Writes legacy VTK files of a small 2D disk simulation and a small 3D sphere simulation with
// io::every(interval, io::vtk(prefix)), together with expected.json: the state of each simulation
// at every output, taken straight from its arrays. read_vtk.py reads the VTK files back and
// compares them with expected.json.
//
// Usage: grain_write_vtk <output directory>

#include <grain/grain.hpp>

#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
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
  for (int d = 0; d < D; ++d) s += num(v[d]) + (d + 1 < D ? ", " : "]");
  return s;
}
std::string angular(double w) { return "[0, 0, " + num(w) + "]"; }
std::string angular(const grain::Vec3& w) { return vec<3>(w); }

/// JSON text of one wall geometry.
std::string wall_json(const grain::walls::Segment& g) {
  return R"({"type": "segment", "a": )" + vec<2>(g.a) + R"(, "b": )" + vec<2>(g.b) + "}";
}
std::string wall_json(const grain::walls::Circle& g) {
  return R"({"type": "circle", "center": )" + vec<2>(g.center) + R"(, "radius": )" +
         num(g.radius) + "}";
}
std::string wall_json(const grain::walls::Plane& g) {
  return R"({"type": "plane", "point": )" + vec<3>(g.point) + R"(, "normal": )" +
         vec<3>(g.normal) + "}";
}
std::string wall_json(const grain::walls::Triangle& g) {
  return R"({"type": "triangle", "a": )" + vec<3>(g.a) + R"(, "b": )" + vec<3>(g.b) +
         R"(, "c": )" + vec<3>(g.c) + "}";
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
        << ", \"force\": " << vec<Sim::dimension>(p.force[i]);
      if constexpr (Sim::thermal)
        o << ", \"temperature\": " << num(p.temperature[i])
          << ", \"heat_rate\": " << num(p.heat_rate[i]);
      o << "}";
    }
    o << "],\n       \"walls\": [";
    for (std::size_t w = 0; w < sim.walls().size(); ++w) {
      o << (w ? ",\n         " : "\n         ")
        << std::visit([](const auto& g) { return wall_json(g); }, sim.walls()[w].geometry);
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
      const auto& pair = sim.pair_properties(
          p.material[i], wall ? sim.walls()[j].options.material : p.material[j]);
      o << (first ? "\n         " : ",\n         ") << "{\"id_i\": " << p.id[i]
        << ", \"id_j\": " << (wall ? -1 : p.id[j]) << ", \"wall\": " << (wall ? long(j) : -1L)
        << ", \"normal_force\": " << num(r.normal.force)
        << ", \"tangential_force\": " << vec<Sim::dimension>(r.tangent.force)
        << ", \"overlap\": " << num(g.overlap) << ", \"contact_radius\": "
        << num(C::area_model::radius(g, pair, r.normal, sim.params().contact.area))
        << ", \"heat_rate\": " << num(q) << "}";
      first = false;
    });
    o << "]}";
    frames->push_back(o.str());
  }
};

/// Checks that the run exercises every field: some particle has a non-zero value of each.
template <class Sim>
bool exercised(const Sim& sim, const char* name) {
  const auto& p = sim.particles();
  bool force = false, velocity = false, omega = false;
  for (std::size_t i = 0; i < p.size(); ++i) {
    force = force || p.force[i].norm() > 0;
    velocity = velocity || p.velocity[i].norm() > 0;
    omega = omega || grain::norm(p.omega[i]) > 0;
  }
  const auto [pp, pw] = sim.contact_counts();
  if (force && velocity && omega && pp > 0 && pw > 0) return true;
  std::fprintf(stderr,
               "write_vtk: the %s set-up is degenerate (force %d, velocity %d, omega %d, "
               "%zu particle and %zu wall contacts)\n",
               name, force, velocity, omega, pp, pw);
  return false;
}

/// Runs a simulation with VTK output and returns the JSON text of its series.
template <class Sim>
std::string run_series(Sim& sim, const std::filesystem::path& dir, const std::string& name,
                       bool& ok) {
  sim.initialize();
  const double interval = static_cast<double>(kStepsPerOutput) * sim.time_step();
  std::vector<std::string> frames;
  sim.steps(kSteps, grain::io::every(interval,
                                     grain::io::vtk((dir / name).string(), kPlaneSize, true),
                                     Recorder{&frames}));
  if (static_cast<long>(frames.size()) != kExpectedFiles) {
    std::fprintf(stderr, "write_vtk: %s: every() fired %zu times, expected %ld\n", name.c_str(),
                 frames.size(), kExpectedFiles);
    ok = false;
  }
  ok = exercised(sim, name.c_str()) && ok;
  std::string s = "{\"dimension\": " + std::to_string(Sim::dimension) +
                  ", \"particle_count\": " + std::to_string(sim.size()) +
                  ", \"wall_count\": " + std::to_string(sim.walls().size()) +
                  ", \"wall_cells\": " + std::to_string(sim.walls().size()) +
                  ", \"files\": " + std::to_string(kExpectedFiles) +
                  ", \"final_time\": " + num(sim.time()) + ",\n     \"frames\": [";
  for (std::size_t k = 0; k < frames.size(); ++k) s += (k ? ",\n      " : "\n      ") + frames[k];
  return s + "]}";
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

std::string disks(const std::filesystem::path& dir, bool& ok) {
  grain::SimulationParams<2, Contact, grain::search::AllPairs> params;
  params.gravity = grain::Vec2(0.0, -9.81);
  grain::Simulation<grain::Disk, grain::search::AllPairs, Contact> sim(params,
                                                                       grain::Disk{0.01, false});
  const auto m = sim.add_material(material());
  // ids out of order, so that the reader has to match particles by id
  sim.add_particle({.position = {-0.02, -0.04}, .radius = 0.011, .material = m,
                    .velocity = {0.031, -0.012}, .omega = 1.5, .id = 7});
  sim.add_particle({.position = {0.0021, -0.039}, .radius = 0.012, .material = m,
                    .velocity = {-0.024, 0.017}, .omega = -2.25, .id = 3});
  sim.add_particle({.position = {0.0245, -0.0405}, .radius = 0.0105, .material = m,
                    .velocity = {0.0, 0.043}, .omega = 0.75, .id = 12});
  sim.add_particle({.position = {0.0013, 0.0895}, .radius = 0.0113, .material = m,
                    .velocity = {0.052, 0.011}, .omega = -3.5, .id = 5});
  sim.add_particle({.position = {-0.05, 0.02}, .radius = 0.0097, .material = m,
                    .velocity = {-0.013, -0.029}, .omega = 0.0, .id = 40});
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
  return run_series(sim, dir, "disks", ok);
}

std::string spheres(const std::filesystem::path& dir, bool& ok) {
  grain::Simulation<grain::Sphere, grain::search::CellList, ThermalContact>::Params params;
  params.gravity = grain::Vec3(0.0, 0.0, -9.81);
  params.initial_temperature = 310.0;
  grain::Simulation<grain::Sphere, grain::search::CellList, ThermalContact> sim(params);
  grain::Material mat = material();
  mat.conductivity = 1.0;
  mat.heat_capacity = 800.0;
  const auto m = sim.add_material(mat);
  // ids in reverse spatial order: the cell list re-sorts the arrays
  sim.add_particle({.position = {0.09, 0.01, 0.0095}, .radius = 0.0105, .material = m,
                    .velocity = {0.012, -0.021, 0.005}, .omega = {0.5, -1.25, 2.0},
                    .temperature = 350.0, .id = 20});
  sim.add_particle({.position = {0.0695, 0.0105, 0.0097}, .radius = 0.0102, .material = m,
                    .velocity = {-0.031, 0.004, 0.0}, .omega = {-1.5, 0.0, 0.25}, .id = 4});
  sim.add_particle({.position = {0.02, -0.03, 0.0118}, .radius = 0.012, .material = m,
                    .velocity = {0.0, 0.0, -0.041}, .omega = {0.0, 3.0, 0.0}, .id = 9});
  sim.add_particle({.position = {0.1002, -0.0011, 0.0398}, .radius = 0.0107, .material = m,
                    .velocity = {0.007, 0.009, -0.011}, .omega = {1.0, 1.0, -1.0}, .id = 15});
  sim.add_particle({.position = {-0.01, -0.06, 0.05}, .radius = 0.0093, .material = m,
                    .velocity = {0.021, 0.033, -0.017}, .omega = {0.0, 0.0, 0.0}, .id = 1});
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
  sim.add_wall(grain::walls::Triangle{{0.05, -0.05, 0.03}, {0.15, -0.045, 0.031},
                                      {0.1, 0.05, 0.0295}},
               tilted);
  return run_series(sim, dir, "spheres", ok);
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
    const std::string d = disks(dir, ok);
    const std::string s = spheres(dir, ok);
    std::ofstream o(dir / "expected.json");
    o << "{\"circle_segments\": " << kCircleSegments << ", \"plane_size\": " << num(kPlaneSize)
      << ",\n \"series\": {\n  \"disks\": " << d << ",\n  \"spheres\": " << s << "}}\n";
    o.close();
    if (!o) {
      std::fprintf(stderr, "write_vtk: cannot write %s\n", (dir / "expected.json").string().c_str());
      return 1;
    }
    return ok ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "write_vtk: %s\n", e.what());
    return 1;
  }
}
