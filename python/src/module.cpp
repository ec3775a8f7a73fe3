// grain's Python extension module `grain._grain`: the compiled models behind the Python front
// ends (grain/parmec.py runs Parmec input decks on them). Each model is one instantiation of
// grain's templates; Python only sets them up and calls their run loops, never inside a step.
//
// Parmec's body model: the rigid bodies, meshes, springs and joints of grain::bodies::BodySystem,
// a history recorder for Parmec's HISTORY command and its DEM run loop.
#include <grain/bodies.hpp>
#include <grain/io/console.hpp>

#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <array>
#include <cstddef>
#include <optional>
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

/// Samples of chosen entities of a BodySystem (Parmec's HISTORY): one column per request, each
/// started when requested (displacements count from then on), sampled by the run loop.
struct Recorder {
  std::vector<gb::HistoryColumns> columns;
  std::vector<std::vector<double>> values; ///< per column, the samples not yet taken
  std::vector<double> times;               ///< times of the samples not yet taken [s]
  double last = -1.0;
  bool sampled = false;

  std::size_t add(const gb::BodySystem& sys, const std::string& source, std::size_t item,
                  const std::string& entity) {
    gb::HistoryColumns c = source == "body"             ? gb::body_history({item}, {entity})
                           : source == "spring"         ? gb::spring_history({item}, {entity})
                           : source == "torsion_spring" ? gb::torsion_history({item}, {entity})
                                                        : gb::joint_history({item}, {entity});
    c.start(sys);
    columns.push_back(std::move(c));
    values.emplace_back();
    return columns.size() - 1;
  }
  void sample(const gb::BodySystem& sys) {
    if (sampled && sys.time() == last) return; // the end of one run is the start of the next
    sampled = true;
    last = sys.time();
    times.push_back(sys.time());
    std::vector<double> v;
    for (std::size_t k = 0; k < columns.size(); ++k) {
      v.clear();
      columns[k].values(sys, v);
      values[k].push_back(v.at(0));
    }
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

grain::TimeFunction time_function(const py::object& f) { return py::cast<grain::TimeFunction>(f); }
grain::VectorTimeFunction<3> vector_function(const py::object& x, const py::object& y,
                                             const py::object& z) {
  return {time_function(x), time_function(y), time_function(z)};
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
      .def("__call__", [](const grain::TimeFunction& f, double t) { return f(t); });

  py::class_<gb::BodySystem>(m, "BodySystem",
                             "Rigid bodies, meshes, springs and joints (grain::bodies)")
      .def(py::init<>())
      .def(
          "add_analytical",
          [](gb::BodySystem& s, std::array<double, 6> j, double mass, std::array<double, 9> rot,
             std::array<double, 3> position, std::string name) {
            gb::RigidBody b;
            b.mass = mass;
            b.inertia = gb::inertia_tensor(j[0], j[1], j[2], j[3], j[4], j[5]);
            Eigen::Matrix3d r;
            for (int c = 0; c < 3; ++c) // [e1x, e1y, e1z, e2x, ...]: the columns of Lambda
              for (int k = 0; k < 3; ++k)
                r(k, c) = rot[static_cast<std::size_t>(3 * c + k)];
            b.rotation = r;
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
             std::array<bool, 3> cone, std::string name) {
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
            return s.add_torsion_spring(std::move(p), b1, b2, vec(zdir), vec(xdir));
          },
          py::arg("body1"), py::arg("body2"), py::arg("zdir"), py::arg("xdir"), py::arg("axes"),
          py::arg("cone"), py::arg("name"),
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
          "run",
          [](gb::BodySystem& s, double duration, double step, double files, double history,
             Recorder& rec, const std::string& prefix) {
            auto record = [&rec](const gb::BodySystem& sys) { rec.sample(sys); };
            py::gil_scoped_release free; // the run loop is C++ alone
            if (prefix.empty())
              s.run(duration, step, grain::io::every(history, record));
            else
              s.run(duration, step, grain::io::every(history, record),
                    grain::io::every(files, gb::body_vtk(prefix)));
          },
          py::arg("duration"), py::arg("step"), py::arg("files"), py::arg("history"),
          py::arg("recorder"), py::arg("prefix"),
          "Runs for `duration` [s] with steps of `step` [s], sampling the recorder every "
          "`history` [s] and writing VTK files with `prefix` every `files` [s] (none if empty)");

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
      .def("take", &Recorder::take);
}
