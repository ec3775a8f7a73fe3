// grain's Python extension module `grain._grain`: the compiled models behind the Python front
// ends (grain/parmec.py runs Parmec input decks on them). Each model is one instantiation of
// grain's templates; Python only sets them up and calls their run loops, never inside a step.
//
// Parmec's body model: the rigid bodies, meshes, springs and joints of grain::bodies::BodySystem,
// a history recorder for Parmec's HISTORY command and its DEM run loop.
#include <grain/bodies.hpp>
#include <grain/grain.hpp>
#include <grain/io/console.hpp>
#include <grain/walls/obstacle.hpp>

#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <array>
#include <cstddef>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

namespace py = pybind11;
namespace gb = grain::bodies;
using grain::Vec3;

namespace {

Vec3 vec(const std::array<double, 3>& a) { return {a[0], a[1], a[2]}; }
std::array<double, 3> arr(const Vec3& v) { return {v.x(), v.y(), v.z()}; }

/// Samples of chosen entities of the model (Parmec's HISTORY): one column per request, each
/// started when requested (displacements count from then on), sampled by the run loop.
struct Recorder {
  std::vector<std::function<double()>> columns;
  std::vector<std::vector<double>> values; ///< per column, the samples not yet taken
  std::vector<double> times;               ///< times of the samples not yet taken [s]
  double last = -1.0;
  bool sampled = false;

  /// An entity of a body, spring, torsion spring or joint of the system.
  std::size_t add(const gb::BodySystem& sys, const std::string& source, std::size_t item,
                  const std::string& entity) {
    auto c = std::make_shared<gb::HistoryColumns>(
        source == "body"             ? gb::body_history({item}, {entity})
        : source == "spring"         ? gb::spring_history({item}, {entity})
        : source == "torsion_spring" ? gb::torsion_history({item}, {entity})
                                     : gb::joint_history({item}, {entity}));
    c->start(sys);
    const gb::BodySystem* s = &sys;
    return push([c, s, v = std::vector<double>()]() mutable {
      v.clear();
      c->values(*s, v);
      return v.at(0);
    });
  }
  /// A column of the material point of body `item` that is at world point `point` now:
  /// PX .. |P| its position, DX .. |D| its displacement from now, VX .. |V| its velocity;
  /// other entities are the body's.
  std::size_t add_point(const gb::BodySystem& sys, std::size_t item,
                        const std::array<double, 3>& point, const std::string& entity) {
    const auto [kind, comp] = split(entity);
    if (kind != 'P' && kind != 'D' && kind != 'V') return add(sys, "body", item, entity);
    const Vec3 start = vec(point);
    const Vec3 local = gb::to_local(sys.bodies(), item, start);
    const gb::BodySystem* s = &sys;
    return push([=]() {
      const Vec3 x = gb::to_world(s->bodies(), item, local);
      const Vec3 q = kind == 'P'   ? x
                     : kind == 'D' ? Vec3(x - start)
                                   : gb::point_velocity(s->bodies(), item, x);
      return comp == 3 ? q.norm() : q[comp];
    });
  }
  /// An entity of a sphere of a particle simulation (by id): PX .. |T| as for a body.
  template <class Sim>
  std::size_t add_particle(const Sim& sim, std::int64_t id, const std::string& entity) {
    const auto [kind, comp] = split(entity);
    const Vec3 start = sim.particles().position[sim.index_of(id)];
    const Sim* s = &sim;
    return push([=]() {
      const auto& p = s->particles();
      const std::size_t i = s->index_of(id);
      const Vec3 q = kind == 'P'   ? Vec3(p.position[i])
                     : kind == 'D' ? Vec3(p.position[i] - start)
                     : kind == 'V' ? Vec3(p.velocity[i])
                     : kind == 'O' ? Vec3(p.omega[i])
                     : kind == 'F' ? Vec3(p.force[i])
                                   : Vec3(p.torque[i]);
      return comp == 3 ? q.norm() : q[comp];
    });
  }
  /// An entity averaged over the spheres whose centres are inside a region now (a live
  /// region: Parmec's HISTORY source (x, y, z, r) or (xmin, ymin, zmin, xmax, ymax, zmax)):
  /// PX .. |T| as for one sphere (DX ..: from each sphere's position when the column started,
  /// or when it was first sampled); NaN while the region holds no sphere.
  template <class Sim>
  std::size_t add_region(const Sim& sim, const std::vector<double>& region,
                         const std::string& entity) {
    const auto [kind, comp] = split(entity);
    const Sim* s = &sim;
    auto start = std::make_shared<std::map<std::int64_t, Vec3>>();
    for (std::size_t i = 0; i < sim.particles().size(); ++i)
      (*start)[sim.particles().id[i]] = sim.particles().position[i];
    return push([=]() {
      const auto& p = s->particles();
      double sum = 0.0;
      std::size_t n = 0;
      for (std::size_t i = 0; i < p.size(); ++i) {
        const Vec3 x = p.position[i];
        const bool in = region.size() == 4
                            ? (x - Vec3(region[0], region[1], region[2])).norm() <= region[3]
                            : x.x() >= region[0] && x.y() >= region[1] && x.z() >= region[2] &&
                                  x.x() <= region[3] && x.y() <= region[4] && x.z() <= region[5];
        if (!in) continue;
        const Vec3 x0 = start->emplace(p.id[i], x).first->second;
        const Vec3 q = kind == 'P'   ? x
                       : kind == 'D' ? Vec3(x - x0)
                       : kind == 'V' ? Vec3(p.velocity[i])
                       : kind == 'O' ? Vec3(p.omega[i])
                       : kind == 'F' ? Vec3(p.force[i])
                                     : Vec3(p.torque[i]);
        sum += comp == 3 ? q.norm() : q[comp];
        ++n;
      }
      return n ? sum / static_cast<double>(n) : std::numeric_limits<double>::quiet_NaN();
    });
  }
  /// PX -> ('P', 0), |P| -> ('P', 3).
  static std::pair<char, int> split(const std::string& e) {
    if (e.size() == 3 && e[0] == '|') return {e[1], 3};
    return {e.empty() ? '?' : e[0], e.size() == 2 ? e[1] - 'X' : 0};
  }
  std::size_t push(std::function<double()> f) {
    columns.push_back(std::move(f));
    values.emplace_back();
    return columns.size() - 1;
  }
  void sample(double t) {
    if (sampled && t == last) return; // the end of one run is the start of the next
    sampled = true;
    last = t;
    times.push_back(t);
    for (std::size_t k = 0; k < columns.size(); ++k)
      values[k].push_back(columns[k]());
  }
  /// The samples since the last call: (times, values per column).
  std::pair<std::vector<double>, std::vector<std::vector<double>>> take() {
    std::pair<std::vector<double>, std::vector<std::vector<double>>> out{std::move(times),
                                                                         std::move(values)};
    times.clear();
    values.assign(columns.size(), {});
    return out;
  }
};

/// The law of one torsion angle as Python gives it: tables as abscissae and values (empty:
/// none) and a critical damping ratio.
struct TorsionAxis {
  std::vector<double> spring_x, spring_y, dashpot_x, dashpot_y;
  double ratio = 0.0;
};

/// A translational spring as Python gives it (see grain/parmec.py SPRING): tables as abscissae
/// and values (empty: none).
struct SpringSpec {
  std::string geometry = "point_to_point"; ///< or constant_direction, planar, point_to_plane
  std::vector<double> spring_x, spring_y, dashpot_x, dashpot_y, unload_x, unload_y;
  double ratio = 0.0;
  std::array<double, 3> direction{0.0, 0.0, 0.0};
  double fyc = 0.0, fyt = 0.0;
  bool inactive = false;
  py::object offset = py::none(); ///< a TimeFunction or None
  double friction = 0.0, kskn = 0.0;
};

gb::SpringParams spring_params(const SpringSpec& x, const std::string& name) {
  gb::SpringParams p;
  p.spring = grain::Table(x.spring_x, x.spring_y, name + " spring table");
  if (!x.dashpot_x.empty())
    p.dashpot = grain::Table(x.dashpot_x, x.dashpot_y, name + " dashpot table");
  if (!x.unload_x.empty()) p.unload = grain::Table(x.unload_x, x.unload_y, name + " unload table");
  p.damping_ratio = x.ratio;
  p.geometry = x.geometry == "constant_direction" ? gb::SpringGeometry::constant_direction
               : x.geometry == "planar"           ? gb::SpringGeometry::planar
               : x.geometry == "point_to_plane"   ? gb::SpringGeometry::point_to_plane
                                                  : gb::SpringGeometry::point_to_point;
  p.direction = vec(x.direction);
  p.fyc = x.fyc;
  p.fyt = x.fyt;
  p.inactive = x.inactive;
  if (!x.offset.is_none()) p.offset = py::cast<grain::TimeFunction>(x.offset);
  p.friction = x.friction;
  p.kskn = x.kskn;
  p.name = name;
  return p;
}

/// Parmec's rotation [e1x, e1y, e1z, e2x, ...]: the columns of Lambda (reference -> world).
Eigen::Matrix3d rotation_matrix(const std::array<double, 9>& rot) {
  Eigen::Matrix3d r;
  for (int c = 0; c < 3; ++c)
    for (int k = 0; k < 3; ++k)
      r(k, c) = rot[static_cast<std::size_t>(3 * c + k)];
  return r;
}

grain::TimeFunction time_function(const py::object& f) { return py::cast<grain::TimeFunction>(f); }
grain::VectorTimeFunction<3> vector_function(const py::object& x, const py::object& y,
                                             const py::object& z) {
  return {time_function(x), time_function(y), time_function(z)};
}

/// A Python callable kept by grain: released with the GIL held (a run releases the GIL).
std::shared_ptr<py::object> hold(py::object f) {
  return {new py::object(std::move(f)), [](py::object* p) {
            py::gil_scoped_acquire gil;
            delete p;
          }};
}

/// A Python function of time as a grain function, called with the GIL.
grain::TimeFunction scalar_callable(py::object f) {
  if (!PyCallable_Check(f.ptr())) throw py::type_error("TimeFunction.callable: not a callable");
  auto h = hold(std::move(f));
  return grain::TimeFunction::callable([h](double t) {
    py::gil_scoped_acquire gil;
    return py::cast<double>((*h)(t));
  });
}

/// A vector function of time from Python: None (the zero vector), a sequence of 3
/// TimeFunctions, or a callable returning 3 numbers.
grain::VectorTimeFunction<3> vector_arg(const py::object& x) {
  if (x.is_none()) return {};
  if (PyCallable_Check(x.ptr())) {
    auto h = hold(x);
    return grain::VectorTimeFunction<3>::callable([h](double t) {
      py::gil_scoped_acquire gil;
      return vec(py::cast<std::array<double, 3>>((*h)(t)));
    });
  }
  const auto f = py::cast<std::array<grain::TimeFunction, 3>>(x);
  return grain::VectorTimeFunction<3>(f);
}

// ------------------------------------------------------------------------ Parmec's model
/// GRANULAR's law: a linear spring-dashpot with a critical damping ratio, and a linear
/// spring-dashpot-slider whose stiffness and damping are kskn times the normal ones.
using ParmecContact = grain::presets::LinearCoulomb;
using ParmecSim = grain::Simulation<grain::Sphere, grain::search::CellList, ParmecContact,
                                    grain::stages<gb::Coupling>>;

/// Parmec's model: spheres and triangle obstacles in a particle simulation with GRANULAR's
/// contact law, coupled to a body system (meshes, analytical bodies, springs, torsion springs,
/// joints). Without spheres and obstacles the body system runs alone.
class ParmecModel {
public:
  ParmecModel() : sim_(params()) {}
  ParmecModel(const ParmecModel&) = delete;
  ParmecModel& operator=(const ParmecModel&) = delete;

  gb::BodySystem& system() { return sim_.stage<gb::Coupling>().system(); }
  ParmecSim& sim() { return sim_; }
  /// True once spheres or obstacles exist: the particle simulation drives the run.
  bool particles() const { return sim_.particles().size() > 0 || !sim_.walls().empty(); }

  std::uint32_t add_material(double density, double young, double poisson, std::string name) {
    grain::Material m;
    m.name = std::move(name);
    m.density = density;
    m.young = young;
    m.poisson = poisson;
    m.restitution = 1.0; // GRANULAR gives the damping as a ratio
    m.friction = 0.0;    // and the friction per pair of colours
    return sim_.add_material(m);
  }
  std::int64_t add_sphere(const std::array<double, 3>& c, double radius, std::uint32_t material) {
    grain::ParticleSpec<3> p;
    p.position = vec(c);
    p.radius = radius;
    p.material = material;
    return sim_.add_particle(p);
  }
  void set_sphere_velocity(std::int64_t id, const std::array<double, 3>& v,
                           const std::array<double, 3>& w) {
    const std::string g = "SPHERE " + std::to_string(id);
    if (groups_.insert(id).second) sim_.add_group(g, {id});
    sim_.set_velocity(g, vec(v), vec(w));
  }
  std::size_t attach(std::int64_t id) { return sim_.stage<gb::Coupling>().attach(sim_, id); }
  /// Turns a sphere into a body without contact (Parmec's ANALYTICAL with `particle`), with the
  /// values given (the sphere's otherwise); returns the body index.
  std::size_t convert(std::int64_t id, std::optional<double> mass,
                      std::optional<std::array<double, 6>> inertia,
                      std::optional<std::array<double, 9>> rotation,
                      std::optional<std::array<double, 3>> position, std::string name) {
    gb::AnalyticalOptions o;
    o.mass = mass;
    if (inertia) {
      const auto& j = *inertia;
      o.inertia = gb::inertia_tensor(j[0], j[1], j[2], j[3], j[4], j[5]);
    }
    if (rotation) o.rotation = rotation_matrix(*rotation);
    if (position) o.position = vec(*position);
    o.name = std::move(name);
    return sim_.stage<gb::Coupling>().convert(sim_, id, o);
  }
  std::size_t add_obstacle(const std::vector<std::array<double, 9>>& triangles,
                           const std::vector<std::uint32_t>& materials,
                           const std::array<double, 3>& point, const py::object& linear,
                           const py::object& angular, const std::string& name) {
    std::vector<grain::walls::Triangle> t;
    for (const auto& x : triangles)
      t.push_back({Vec3(x[0], x[1], x[2]), Vec3(x[3], x[4], x[5]), Vec3(x[6], x[7], x[8])});
    grain::ObstacleOptions o;
    o.name = name;
    o.materials = materials;
    o.reference_point = vec(point);
    if (!linear.is_none()) o.velocity = vector_arg(linear);
    if (!angular.is_none()) o.omega = vector_arg(angular);
    return grain::add_obstacle(sim_, t, o).first_wall;
  }
  /// GRANULAR's law for the pair of materials a, b: spring [N/m], damper (critical damping
  /// ratio), static and dynamic friction, kskn = k_t / k_n.
  void set_pair(std::uint32_t a, std::uint32_t b, double spring, double damper, double mu_s,
                double mu_d, double kskn) {
    ParmecContact::Params p;
    // spring 0 (the seed's default for a pair without a law): no force; grain's 0 would mean
    // the Hertz-equivalent stiffness, so the smallest normal number stands for it
    p.normal.stiffness = spring > 0.0 ? spring : std::numeric_limits<double>::min();
    p.normal.damping_ratio = damper;
    p.tangent.stiffness_ratio = kskn;
    p.tangent.damping_factor = kskn;
    sim_.set_pair_parameters(a, b, p);
    grain::PairOverride o;
    o.friction = mu_d;
    o.friction_static = mu_s;
    sim_.set_pair(a, b, o);
    pairs_[{std::min(a, b), std::max(a, b)}] = {spring, damper};
  }
  /// The critical step of the contacts [s]: the stiffest spring of the pairs in use on the
  /// lightest sphere (m/2 between two spheres, m against an obstacle), with the largest damping
  /// ratio (critical_step of eqm.hpp); infinity without spheres.
  double critical_contacts() const {
    const auto& p = sim_.particles();
    if (p.size() == 0) return std::numeric_limits<double>::infinity();
    double m = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < p.size(); ++i)
      m = std::min(m, p.mass[i]);
    double k = 0.0, xi = 0.0;
    for (const auto& [ab, law] : pairs_) {
      k = std::max(k, law.first);
      xi = std::max(xi, law.second);
    }
    if (k == 0.0) return std::numeric_limits<double>::infinity();
    const double me = p.size() > 1 ? 0.5 * m : m;
    return gb::critical_step(std::sqrt(k / me), xi);
  }

  /// An extra family of output files (Parmec's OUTPUT): `<prefix><number>_<kind>_NNNNNN.vtk`,
  /// of the bodies `bodies` (empty: all) and the spheres `spheres` (empty: all), with the body
  /// files `files` (BodyVtkFiles) and, if `particles`, the spheres (with the contact network if
  /// `contacts`).
  void add_output(int number, std::vector<std::size_t> bodies, std::vector<std::int64_t> spheres,
                  unsigned files, bool particles, bool contacts) {
    Output o;
    o.number = number;
    o.bodies = std::move(bodies);
    o.files = files;
    o.particles = particles;
    o.contacts = contacts;
    if (!spheres.empty()) {
      o.group = "OUTPUT " + std::to_string(number);
      sim_.add_group(o.group, std::move(spheres));
    }
    outputs_.push_back(std::move(o));
  }

  /// Runs for `duration` [s] with steps of `step` [s]: the particle simulation (which steps the
  /// coupled system) if there are spheres or obstacles, else the body system alone; samples the
  /// recorder at the `history` interval and writes VTK files with `prefix` at the `files`
  /// interval (none if the prefix is empty). The writers continue their numbering across runs.
  void run(double duration, double step, const grain::TimeFunction& files,
           const grain::TimeFunction& history, Recorder& rec, const std::string& prefix) {
    if (prefix != prefix_) {
      prefix_ = prefix;
      body_writer_.reset();
      particle_writer_.reset();
      for (auto& o : outputs_) {
        o.body_writer.reset();
        o.particle_writer.reset();
      }
    }
    if (!prefix.empty() && !body_writer_) body_writer_ = gb::body_vtk(prefix);
    if (!prefix.empty() && !particle_writer_) particle_writer_ = grain::io::vtk(prefix);
    for (auto& o : outputs_) {
      if (prefix.empty() || o.body_writer) continue;
      const std::string p = prefix + std::to_string(o.number);
      o.body_writer = gb::body_vtk(p);
      o.body_writer->subset = o.bodies;
      o.body_writer->files = o.files;
      grain::io::VtkOptions v;
      v.contacts = o.contacts;
      v.group = o.group;
      o.particle_writer = grain::io::vtk(p, v);
    }
    const auto fixed = [](const grain::TimeFunction& f) {
      return f.kind() == grain::TimeFunction::Kind::constant && !f.has_interval();
    };
    if (fixed(files) && fixed(history))
      run_with(duration, step, files.value(0.0), history.value(0.0), rec);
    else if (fixed(files))
      run_with(duration, step, files.value(0.0), history, rec);
    else if (fixed(history))
      run_with(duration, step, files, history.value(0.0), rec);
    else
      run_with(duration, step, files, history, rec);
  }

private:
  static ParmecSim::Params params() {
    ParmecSim::Params p;
    p.time_step = 1.0; // set by each run
    return p;
  }

  template <class Files, class History>
  void run_with(double duration, double step, const Files& files, const History& history,
                Recorder& rec) {
    gb::BodySystem& sys = system();
    if (!particles()) {
      auto record = [&rec](const gb::BodySystem& s) { rec.sample(s.time()); };
      if (!body_writer_)
        sys.run(duration, step, grain::io::every(history, record));
      else
        sys.run(duration, step, grain::io::every(history, record),
                grain::io::every(files, [this](const gb::BodySystem& s) {
                  (*body_writer_)(s);
                  for (auto& o : outputs_)
                    if (o.files) (*o.body_writer)(s);
                }));
      return;
    }
    sim_.set_time_step(step);
    auto record = [&rec](const ParmecSim& s) { rec.sample(s.time()); };
    if (!body_writer_) {
      sim_.run(duration, grain::io::every(history, record));
      return;
    }
    auto write = [this, &sys](const ParmecSim& s) {
      (*particle_writer_)(s);
      if (sys.bodies().size() > 0) (*body_writer_)(sys);
      for (auto& o : outputs_) {
        if (o.particles) (*o.particle_writer)(s);
        if (o.files && sys.bodies().size() > 0) (*o.body_writer)(sys);
      }
    };
    sim_.run(duration, grain::io::every(history, record), grain::io::every(files, write));
  }

  struct Output {
    int number = 1;
    std::vector<std::size_t> bodies{};
    std::string group{};
    unsigned files = gb::all_body_files;
    bool particles = true, contacts = false;
    std::optional<gb::BodyVtkWriter> body_writer{};
    std::optional<grain::io::VtkWriter> particle_writer{};
  };

  ParmecSim sim_;
  std::vector<Output> outputs_{};
  std::set<std::int64_t> groups_{};
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::pair<double, double>> pairs_{};
  std::string prefix_{};
  std::optional<gb::BodyVtkWriter> body_writer_{};
  std::optional<grain::io::VtkWriter> particle_writer_{};
};

// ------------------------------------------------------------- grain's API for any preset
/// Binds a 3D simulation of spheres with grain's usual API as the Python class `name`:
/// materials, particles, plane and triangle walls, gravity, groups with fixed velocities,
/// the automatic or a given time step, runs with VTK output and CSV histories, and the
/// particles' state as lists. Adding a model is one line: bind_simulation<Simulation<...>>(m,
/// "Name").
template <class Sim>
void bind_simulation(py::module_& m, const char* name, const char* doc) {
  py::class_<Sim>(m, name, doc)
      .def(py::init([](double time_step, std::array<double, 3> gravity) {
             typename Sim::Params p;
             p.time_step = time_step;
             p.gravity = vec(gravity);
             return std::make_unique<Sim>(p);
           }),
           py::arg("time_step") = 0.0, py::arg("gravity") = std::array<double, 3>{0, 0, 0},
           "time_step [s] (0: automatic, 0.1 of the critical step), gravity [m/s^2]")
      .def(
          "add_material",
          [](Sim& s, const std::string& name, double density, double young, double poisson,
             double restitution, double friction, double rolling_friction) {
            grain::Material x;
            x.name = name;
            x.density = density;
            x.young = young;
            x.poisson = poisson;
            x.restitution = restitution;
            x.friction = friction;
            x.rolling_friction = rolling_friction;
            return s.add_material(x);
          },
          py::arg("name"), py::arg("density"), py::arg("young"), py::arg("poisson") = 0.25,
          py::arg("restitution") = 0.5, py::arg("friction") = 0.5,
          py::arg("rolling_friction") = 0.0, "A material [kg/m^3, Pa, -]; returns its index")
      .def(
          "add_particle",
          [](Sim& s, std::array<double, 3> position, double radius, std::uint32_t material,
             std::array<double, 3> velocity, std::array<double, 3> omega) {
            grain::ParticleSpec<3> p;
            p.position = vec(position);
            p.radius = radius;
            p.material = material;
            p.velocity = vec(velocity);
            p.omega = vec(omega);
            return s.add_particle(p);
          },
          py::arg("position"), py::arg("radius"), py::arg("material") = 0,
          py::arg("velocity") = std::array<double, 3>{0, 0, 0},
          py::arg("omega") = std::array<double, 3>{0, 0, 0}, "A sphere [m, m/s, rad/s]; its id")
      .def(
          "add_plane",
          [](Sim& s, std::array<double, 3> point, std::array<double, 3> normal,
             std::uint32_t material, std::string name) {
            return s.add_wall(grain::walls::Plane{vec(point), vec(normal)},
                              {.name = std::move(name), .material = material});
          },
          py::arg("point"), py::arg("normal"), py::arg("material") = 0, py::arg("name") = "plane",
          "A plane wall, the normal towards the particles")
      .def(
          "add_triangle",
          [](Sim& s, std::array<double, 3> a, std::array<double, 3> b, std::array<double, 3> c,
             std::uint32_t material, std::string name) {
            return s.add_wall(grain::walls::Triangle{vec(a), vec(b), vec(c)},
                              {.name = std::move(name), .material = material});
          },
          py::arg("a"), py::arg("b"), py::arg("c"), py::arg("material") = 0,
          py::arg("name") = "triangle")
      .def(
          "set_gravity",
          [](Sim& s, const py::object& x, const py::object& y, const py::object& z) {
            s.set_gravity(vector_function(x, y, z));
          },
          py::arg("x"), py::arg("y"), py::arg("z"), "Gravity [m/s^2]: TimeFunctions per axis")
      .def("add_group",
           [](Sim& s, std::string n, std::vector<std::int64_t> ids) {
             return s.add_group(std::move(n), std::move(ids));
           })
      .def(
          "fix_velocity",
          [](Sim& s, const std::string& group, const py::object& v) {
            s.fix_velocity(group, vector_arg(v));
          },
          py::arg("group"), py::arg("velocity"),
          "A fixed velocity [m/s]: 3 TimeFunctions or a callable of time returning 3 numbers")
      .def("critical_time_step", &Sim::critical_time_step)
      .def("time_step", &Sim::time_step)
      .def("set_time_step", &Sim::set_time_step, py::arg("time_step"))
      .def("time", &Sim::time)
      .def("size", [](const Sim& s) { return s.particles().size(); })
      .def("positions",
           [](const Sim& s) {
             std::vector<std::array<double, 3>> x;
             for (const auto& p : s.particles().position)
               x.push_back(arr(p));
             return x;
           })
      .def("velocities",
           [](const Sim& s) {
             std::vector<std::array<double, 3>> x;
             for (const auto& v : s.particles().velocity)
               x.push_back(arr(v));
             return x;
           })
      .def("ids", [](const Sim& s) { return s.particles().id; })
      .def("kinetic_energy", [](const Sim& s) { return s.kinetic_energy(); })
      .def(
          "run",
          [](Sim& s, double duration, const std::string& vtk, double interval,
             const std::string& history) {
            py::gil_scoped_release free;
            if (vtk.empty() && history.empty()) {
              s.run(duration);
            } else if (history.empty()) {
              s.run(duration, grain::io::every(interval, grain::io::vtk(vtk)));
            } else if (vtk.empty()) {
              s.run(duration, grain::io::every(interval, grain::io::history(history)));
            } else {
              s.run(duration, grain::io::every(interval, grain::io::vtk(vtk)),
                    grain::io::every(interval, grain::io::history(history)));
            }
          },
          py::arg("duration"), py::arg("vtk") = "", py::arg("interval") = 0.01,
          py::arg("history") = "",
          "Runs for `duration` [s]; every `interval` [s] writes VTK files with prefix `vtk` and a "
          "row of the CSV history `history` (time, particles, energies), when given");
}

} // namespace

PYBIND11_MODULE(_grain, m) {
  m.doc() = "grain's compiled models (header-only C++20 DEM library)";
  // grain's exceptions: bad input is a ValueError, a numerical failure an ArithmeticError
  static py::exception<grain::InputError> input_error(m, "InputError", PyExc_ValueError);
  static py::exception<grain::NumericalError> numerical_error(m, "NumericalError",
                                                              PyExc_ArithmeticError);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const grain::InputError& e) {
      input_error(e.what());
    } catch (const grain::NumericalError& e) {
      numerical_error(e.what());
    }
  });

  py::class_<grain::TimeFunction>(m, "TimeFunction",
                                  "A scalar function of time: a constant or a table")
      .def_static("constant", &grain::TimeFunction::constant, py::arg("value"))
      .def_static(
          "table",
          [](std::vector<double> t, std::vector<double> v, std::string name) {
            return grain::TimeFunction::table(
                grain::Table(std::move(t), std::move(v), std::move(name)));
          },
          py::arg("times"), py::arg("values"), py::arg("name") = "time series")
      .def_static("callable", &scalar_callable, py::arg("function"),
                  "A Python function of time [s]; called with the GIL once or twice per step")
      .def("is_constant",
           [](const grain::TimeFunction& f) {
             return f.kind() == grain::TimeFunction::Kind::constant && !f.has_interval();
           })
      .def("__call__", [](const grain::TimeFunction& f, double t) { return f(t); });

  py::class_<gb::BodySystem>(m, "BodySystem",
                             "Rigid bodies, meshes, springs and joints (grain::bodies)")
      .def(
          "add_analytical",
          [](gb::BodySystem& s, std::array<double, 6> j, double mass, std::array<double, 9> rot,
             std::array<double, 3> position, std::string name) {
            gb::RigidBody b;
            b.mass = mass;
            b.inertia = gb::inertia_tensor(j[0], j[1], j[2], j[3], j[4], j[5]);
            b.rotation = rotation_matrix(rot);
            b.position = vec(position);
            b.name = std::move(name);
            return s.add_body(b);
          },
          py::arg("inertia"), py::arg("mass"), py::arg("rotation"), py::arg("position"),
          py::arg("name"))
      .def(
          "add_mesh",
          [](gb::BodySystem& s, const std::vector<double>& nodes,
             const std::vector<std::size_t>& elements, const std::vector<double>& densities,
             const std::vector<long>& colors, std::string name) {
            if (nodes.size() % 3 != 0)
              throw grain::InputError(name +
                                      ": nodes list length = " + std::to_string(nodes.size()) +
                                      " is invalid; valid: a multiple of 3");
            gb::Mesh mesh;
            for (std::size_t k = 0; k + 2 < nodes.size(); k += 3)
              mesh.nodes.emplace_back(nodes[k], nodes[k + 1], nodes[k + 2]);
            mesh.elements = gb::elements_from_list(elements, densities);
            return s.add_mesh_body(mesh, gb::face_colors_from_list(colors, name), Vec3::Zero(),
                                   Vec3::Zero(), name);
          },
          py::arg("nodes"), py::arg("elements"), py::arg("densities"), py::arg("colors"),
          py::arg("name"))
      .def(
          "set_velocity",
          [](gb::BodySystem& s, std::size_t i, std::array<double, 3> v, std::array<double, 3> w) {
            s.bodies().velocity.at(i) = vec(v);
            s.bodies().omega.at(i) = vec(w);
          },
          py::arg("body"), py::arg("linear"), py::arg("angular"))
      .def(
          "add_ball_joint",
          [](gb::BodySystem& s, long b1, std::array<double, 3> p, long b2) {
            return s.add_ball_joint(b1, vec(p), b2);
          },
          py::arg("body1"), py::arg("point"), py::arg("body2") = gb::world)
      .def(
          "add_spring",
          [](gb::BodySystem& s, const SpringSpec& spec, long b1, std::array<double, 3> p1, long b2,
             std::array<double, 3> p2, std::array<double, 3> normal, std::string name) {
            return s.add_spring(spring_params(spec, name), b1, vec(p1), b2, vec(p2), vec(normal));
          },
          py::arg("spec"), py::arg("body1"), py::arg("point1"), py::arg("body2"), py::arg("point2"),
          py::arg("normal"), py::arg("name"))
      .def(
          "add_unspring",
          [](gb::BodySystem& s, std::vector<std::size_t> tsprings,
             std::vector<std::size_t> msprings, std::optional<double> min,
             std::optional<double> max, const std::string& entity, const std::string& op, bool abs,
             int nsteps, int nfreq,
             const std::vector<std::tuple<std::size_t, std::vector<double>, std::vector<double>>>&
                 unload,
             std::vector<std::size_t> activate, std::string name) {
            gb::UnspringRule r;
            r.tsprings = std::move(tsprings);
            r.msprings = std::move(msprings);
            r.min = min;
            r.max = max;
            r.entity = entity == "STROKE" ? gb::SpringEntity::stroke
                       : entity == "F"    ? gb::SpringEntity::total_force
                       : entity == "FF"   ? gb::SpringEntity::friction_force
                                          : gb::SpringEntity::elastic_force;
            r.op = op == "MIN"   ? gb::SpringOperator::min
                   : op == "MAX" ? gb::SpringOperator::max
                                 : gb::SpringOperator::sum;
            r.abs = abs;
            r.nsteps = nsteps;
            r.nfreq = nfreq;
            for (const auto& [spring, x, y] : unload)
              r.unload.emplace_back(spring, grain::Table(x, y, name + " unload curve"));
            r.activate = std::move(activate);
            r.name = std::move(name);
            return s.add_unspring(std::move(r));
          },
          py::arg("tsprings"), py::arg("msprings"), py::arg("min"), py::arg("max"),
          py::arg("entity"), py::arg("op"), py::arg("abs"), py::arg("nsteps"), py::arg("nfreq"),
          py::arg("unload"), py::arg("activate"), py::arg("name"))
      .def(
          "add_torsion_spring",
          [](gb::BodySystem& s, long b1, long b2, std::array<double, 3> zdir,
             std::array<double, 3> xdir, const std::array<TorsionAxis, 3>& axes,
             std::array<bool, 3> cone, std::string name,
             std::optional<std::array<double, 3>> refpnt) {
            gb::TorsionSpringParams p;
            std::array<gb::TorsionLaw*, 3> laws{&p.roll, &p.pitch, &p.yaw};
            for (std::size_t a = 0; a < 3; ++a) {
              const TorsionAxis& x = axes[a];
              if (!x.spring_x.empty())
                laws[a]->spring = grain::Table(x.spring_x, x.spring_y, name + " spring table");
              if (!x.dashpot_x.empty())
                laws[a]->dashpot = grain::Table(x.dashpot_x, x.dashpot_y, name + " dashpot table");
              laws[a]->damping_ratio = x.ratio;
            }
            p.cone = cone;
            p.name = std::move(name);
            std::optional<Vec3> ref;
            if (refpnt) ref = vec(*refpnt);
            return s.add_torsion_spring(std::move(p), b1, b2, vec(zdir), vec(xdir), ref);
          },
          py::arg("body1"), py::arg("body2"), py::arg("zdir"), py::arg("xdir"), py::arg("axes"),
          py::arg("cone"), py::arg("name"), py::arg("refpnt") = py::none(),
          "A torsion spring; `axes` = the (roll, pitch, yaw) laws (TorsionAxis), grain's signs: "
          "positive table slopes restore")
      .def(
          "set_gravity",
          [](gb::BodySystem& s, const py::object& x, const py::object& y, const py::object& z) {
            s.set_gravity(vector_function(x, y, z));
          },
          py::arg("x"), py::arg("y"), py::arg("z"))
      .def(
          "critical",
          [](gb::BodySystem& s) {
            s.initialize();
            return s.critical_bound();
          },
          "The critical time step at the stiffest state of every spring [s] (infinity if "
          "nothing limits it)")
      .def(
          "critical_lists",
          [](gb::BodySystem& s, std::size_t n_springs, std::size_t n_bodies) {
            s.initialize();
            const gb::CriticalSteps c = s.critical_bound(n_springs, n_bodies);
            using Row = std::tuple<double, std::size_t, double, double>;
            std::pair<std::vector<Row>, std::vector<Row>> out;
            for (const auto& x : c.springs)
              out.first.emplace_back(x.step, x.index, x.omega, x.damping_ratio);
            for (const auto& x : c.bodies)
              out.second.emplace_back(x.step, x.index, x.omega, x.damping_ratio);
            return out;
          },
          "The n lowest per-spring and per-body bounds: lists of (step, index, omega, xi)")
      .def(
          "equivalent_mass",
          [](const gb::BodySystem& s, std::size_t i, std::array<double, 3> p1, long j,
             std::array<double, 3> p2, std::optional<std::array<double, 3>> d) {
            const auto& b = s.bodies();
            if (j < 0)
              return d ? gb::equivalent_mass(b, i, vec(p1), vec(*d))
                       : gb::equivalent_mass(b, i, vec(p1));
            const auto k = static_cast<std::size_t>(j);
            return d ? gb::equivalent_mass(b, i, vec(p1), k, vec(p2), vec(*d))
                     : gb::equivalent_mass(b, i, vec(p1), k, vec(p2));
          },
          py::arg("body1"), py::arg("point1"), py::arg("body2"), py::arg("point2"),
          py::arg("direction"),
          "The equivalent point mass [kg] at point1 of body1 (relative to point2 of body2 if "
          "body2 >= 0; along `direction` if given, else the smallest over all directions)")
      .def("size", [](const gb::BodySystem& s) { return s.bodies().size(); })
      .def("time", &gb::BodySystem::time)
      .def("position",
           [](const gb::BodySystem& s, std::size_t i) { return arr(s.bodies().position.at(i)); })
      .def(
          "restrain",
          [](gb::BodySystem& s, std::size_t b, const std::vector<std::array<double, 3>>& linear,
             const std::vector<std::array<double, 3>>& angular) {
            std::vector<Vec3> l, a;
            for (const auto& d : linear)
              l.push_back(vec(d));
            for (const auto& d : angular)
              a.push_back(vec(d));
            s.restrain(b, l, a);
          },
          py::arg("body"), py::arg("linear"), py::arg("angular"))
      .def(
          "prescribe",
          [](gb::BodySystem& s, std::size_t b, const py::object& linear, const py::object& angular,
             const std::string& kind) {
            std::optional<grain::VectorTimeFunction<3>> l, a;
            if (!linear.is_none()) l = vector_arg(linear);
            if (!angular.is_none()) a = vector_arg(angular);
            s.prescribe_motion(b, std::move(l), std::move(a), kind);
          },
          py::arg("body"), py::arg("linear"), py::arg("angular"), py::arg("kind"),
          "Prescribed motion: each history None, 3 TimeFunctions or a callable of time "
          "returning 3 numbers")
      .def(
          "set_damping",
          [](gb::BodySystem& s, const py::object& linear, const py::object& angular) {
            s.set_damping(vector_arg(linear), vector_arg(angular));
          },
          py::arg("linear"), py::arg("angular"))
      .def("set_adaptive", &gb::BodySystem::set_adaptive, py::arg("factor"));

  py::class_<ParmecModel>(m, "ParmecModel",
                          "Parmec's model: spheres and obstacles with GRANULAR's contact law in a "
                          "particle simulation, coupled to a BodySystem")
      .def(py::init<>())
      .def("system", &ParmecModel::system, py::return_value_policy::reference_internal,
           "The body system (meshes, analytical bodies, springs, joints)")
      .def("particles", &ParmecModel::particles)
      .def("time",
           [](ParmecModel& m) { return m.particles() ? m.sim().time() : m.system().time(); })
      .def("add_material", &ParmecModel::add_material, py::arg("density"), py::arg("young"),
           py::arg("poisson"), py::arg("name"))
      .def("add_sphere", &ParmecModel::add_sphere, py::arg("center"), py::arg("radius"),
           py::arg("material"))
      .def("set_sphere_velocity", &ParmecModel::set_sphere_velocity, py::arg("id"),
           py::arg("linear"), py::arg("angular"))
      .def("convert", &ParmecModel::convert, py::arg("id"), py::arg("mass"), py::arg("inertia"),
           py::arg("rotation"), py::arg("position"), py::arg("name"))
      .def("attach", &ParmecModel::attach, py::arg("id"),
           "Makes a sphere a body of the system (for springs, joints, restraints); its index")
      .def("sphere_position",
           [](ParmecModel& m, std::int64_t id) {
             return arr(m.sim().particles().position[m.sim().index_of(id)]);
           })
      .def("add_obstacle", &ParmecModel::add_obstacle, py::arg("triangles"), py::arg("materials"),
           py::arg("point"), py::arg("linear"), py::arg("angular"), py::arg("name"))
      .def("set_pair", &ParmecModel::set_pair, py::arg("a"), py::arg("b"), py::arg("spring"),
           py::arg("damper"), py::arg("mu_s"), py::arg("mu_d"), py::arg("kskn"))
      .def(
          "set_gravity",
          [](ParmecModel& m, const py::object& x, const py::object& y, const py::object& z) {
            auto g = vector_function(x, y, z);
            m.system().set_gravity(g);
            m.sim().set_gravity(g);
          },
          py::arg("x"), py::arg("y"), py::arg("z"))
      .def("critical_contacts", &ParmecModel::critical_contacts)
      .def("add_output", &ParmecModel::add_output, py::arg("number"), py::arg("bodies"),
           py::arg("spheres"), py::arg("files"), py::arg("particles"), py::arg("contacts"))
      .def(
          "run",
          [](ParmecModel& m, double duration, double step, const grain::TimeFunction& files,
             const grain::TimeFunction& history, Recorder& rec, const std::string& prefix) {
            py::gil_scoped_release free; // the run loop is C++ alone (callables take the GIL)
            m.run(duration, step, files, history, rec, prefix);
          },
          py::arg("duration"), py::arg("step"), py::arg("files"), py::arg("history"),
          py::arg("recorder"), py::arg("prefix"),
          "Runs for `duration` [s] with steps of `step` [s], sampling the recorder at the "
          "`history` interval and writing VTK files with `prefix` at the `files` interval (none "
          "if the prefix is empty); intervals are TimeFunctions of time [s]");

  // grain's usual API for a preset: Hertz-Mindlin spheres (presets::HertzMindlin)
  bind_simulation<
      grain::Simulation<grain::Sphere, grain::search::CellList, grain::presets::HertzMindlin>>(
      m, "HertzMindlin",
      "Spheres with Hertz-Mindlin contacts (Tsuji damping from the restitution, Coulomb "
      "friction): grain's Simulation with its usual API");

  py::class_<SpringSpec>(m, "SpringSpec", "The law and geometry of a translational spring")
      .def(py::init<>())
      .def_readwrite("geometry", &SpringSpec::geometry)
      .def_readwrite("spring_x", &SpringSpec::spring_x)
      .def_readwrite("spring_y", &SpringSpec::spring_y)
      .def_readwrite("dashpot_x", &SpringSpec::dashpot_x)
      .def_readwrite("dashpot_y", &SpringSpec::dashpot_y)
      .def_readwrite("unload_x", &SpringSpec::unload_x)
      .def_readwrite("unload_y", &SpringSpec::unload_y)
      .def_readwrite("ratio", &SpringSpec::ratio)
      .def_readwrite("direction", &SpringSpec::direction)
      .def_readwrite("fyc", &SpringSpec::fyc)
      .def_readwrite("fyt", &SpringSpec::fyt)
      .def_readwrite("inactive", &SpringSpec::inactive)
      .def_readwrite("offset", &SpringSpec::offset)
      .def_readwrite("friction", &SpringSpec::friction)
      .def_readwrite("kskn", &SpringSpec::kskn);

  py::class_<TorsionAxis>(m, "TorsionAxis", "The law of one torsion angle")
      .def(py::init<>())
      .def_readwrite("spring_x", &TorsionAxis::spring_x)
      .def_readwrite("spring_y", &TorsionAxis::spring_y)
      .def_readwrite("dashpot_x", &TorsionAxis::dashpot_x)
      .def_readwrite("dashpot_y", &TorsionAxis::dashpot_y)
      .def_readwrite("ratio", &TorsionAxis::ratio);

  py::class_<Recorder>(m, "Recorder", "Time histories of entities of a BodySystem")
      .def(py::init<>())
      .def("add", &Recorder::add, py::arg("system"), py::arg("source"), py::arg("item"),
           py::arg("entity"))
      .def("size", [](const Recorder& r) { return r.columns.size(); })
      .def("add_point", &Recorder::add_point, py::arg("system"), py::arg("body"), py::arg("point"),
           py::arg("entity"))
      .def(
          "add_particle",
          [](Recorder& r, ParmecModel& m, std::int64_t id, const std::string& entity) {
            return r.add_particle(m.sim(), id, entity);
          },
          py::arg("model"), py::arg("id"), py::arg("entity"))
      .def(
          "add_region",
          [](Recorder& r, ParmecModel& m, const std::vector<double>& region,
             const std::string& entity) { return r.add_region(m.sim(), region, entity); },
          py::arg("model"), py::arg("region"), py::arg("entity"),
          "An entity averaged over the spheres inside a sphere (x, y, z, r) or box (xmin, ymin, "
          "zmin, xmax, ymax, zmax)")
      .def(
          "value", [](const Recorder& r, std::size_t column) { return r.columns.at(column)(); },
          py::arg("column"), "The value of a column now")
      .def("take", &Recorder::take);
}
