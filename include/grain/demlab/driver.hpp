#pragma once
/// \file driver.hpp
/// `grain::demlab::main<Sim>(argc, argv)`: runs the data of a DEMLab project (rlrangel/DEMLab, a
/// 2D MATLAB DEM program) on grain. The Python front end `grain-demlab PROJECT.json` writes a
/// program that names the models (`Sim`, a `Simulation<Disk, search::CellList, Interaction<...>,
/// Integrator [, Convection]>`) and a run file with the project's data; the program is run as
/// `program RUNFILE OUTPUT_FOLDER`. The run-file format is the contract of the Python side
/// (python/grain/demlab.py): text records `name`, `analysis`, `shape`, `time_step`, `final_time`,
/// `output_count`, `progress`, `gravity`, `damping`, `fluid`, `bbox`, `sink`, `material`,
/// `particle`, `wall`, `initial`, `condition`, `param`, `record`, `vtk`. The driver writes
/// OUTPUT_FOLDER/results.csv (`time,step,<record>...`, a row at t = 0 and at k final_time /
/// output_count, k = 1..output_count, at the first step at or after each instant; `nan` for a
/// removed particle; 17 significant digits), the VTK series OUTPUT_FOLDER/vtk/<name>_* with
/// `vtk 1`, progress lines, and a line `grain-demlab: note: ...` wherever it runs something other
/// than what the project asks for. Errors: grain::InputError naming the key, the value and the
/// valid values (main prints it on stderr and returns 1).
///
/// Model parameters (`param <key> <value>`) go into `Sim::Params::contact`:
///
// clang-format off
/// | DEMLab | grain |
/// |---|---|
/// | viscoelastic_linear | normal::LinearSpringDashpot[PerContact]: stiff_coeff -> stiffness, stiff_formula -> equivalence, damping_coeff -> damping (else from the restitution), remove_artificial_cohesion -> no_cohesion (default 1) |
/// | viscoelastic_nonlinear | normal::Hertz<D>: TTI -> TsujiDamping (TsujiMap::norouzi, DEMLab's fit), critical_ratio -> CriticalRatioDamping (ratio), KK -> KuwabaraKonoDamping, LH -> LeeHerrmannDamping (damping_coeff -> coefficient) |
/// | elastoplastic_linear | normal::WaltonBraun[PerContact]: stiff_coeff -> stiffness, load_stiff_formula -> equivalence, unload_stiff_formula -> unloading, unload_param -> unloading_slope |
/// | simple_slider, simple_spring, simple_dashpot, spring_slider, dashpot_slider, sds_linear | tangent::Slider, Spring, Dashpot, SpringSlider, DashpotSlider, SpringDashpotSlider: stiff_coeff -> stiffness, damping_coeff -> damping, restitution_coeff -> restitution (kappa = 7/2, DEMLab's 2 m*/7) |
/// | sds_nonlinear DD, LTH, ZZY, TTI | tangent::DiRenzoDiMaio, LangstonTuzunHeyes (damping_coeff -> damping), ZhengZhuYu (damping_coeff -> viscosity), Tsuji (damping_coeff -> damping, else the normal damping) |
/// | rolling constant, viscous | rolling::Constant, Viscous: resistance_coeff -> Params::coefficient (also Material::rolling_friction) |
/// | bob, thermal_pipe, collisional | conduction::BatchelorOBrien, ThermalPipe (isothermal_walls: DEMLab's k_avg = k_p at walls), Collisional |
/// | vononoi_a, vononoi_b, surrounding_layer | conduction::VoronoiA (cutoff_distance -> max_gap_ratio), VoronoiB (core_radius -> core_ratio), SurroundingLayer (layer_thick -> layer_ratio, min_distance -> min_gap); tolerance_absolute/relative -> abs/rel_tolerance; cell_size_method and update_frequency -> the cell-size option (porosity_global: cells::GlobalPorosity, porosity_local: cells::LocalPorosity with LocalRule::interior_angle, voronoi_diagram: cells::VoronoiDiagram) |
// clang-format on
///
/// Readings chosen where the run file or DEMLab leave a choice (closest to DEMLab):
/// - The model names of the run file (`param normal.model` ...) must be those the program was
///   built with; otherwise the run stops (build the program of this project again).
/// - A material field 0 means "not given": young -> young_real, else (thermal analysis only,
///   where it is unused) 1e9 Pa; restitution -> normal.restitution_coeff, else 1 (only where no
///   model needs it); friction and rolling_friction -> tangent.friction_coeff and
///   rolling.resistance_coeff, else 0. A Poisson ratio of 0 is read as 0.
/// - A wall without material (-1) is rigid and insulated: a material with E = G = 1e300 Pa,
///   the particles' Poisson ratio (their mean if they differ, with a note: DEMLab uses each
///   particle's own), no conductivity, and the project's restitution and friction.
/// - Thermal state (DEMLab's defaults): particles start at 0 K unless an initial temperature is
///   given; a wall with a material has 0 K unless an initial or fixed temperature is given (a
///   note says so) and keeps its last temperature when its fixed conditions end.
/// - Several active fixed velocities (or angular velocities) on one element are summed, as in
///   DEMLab; while one of them is active the element is held. grain holds the element over the
///   hull [earliest start, latest end] of their intervals (a note names a gap inside it, where
///   the sum is 0 instead of free motion).
/// - Particles outside the bounding box or inside a sink active at t = 0 are removed before the
///   run (DEMLab's pre-processing); infinite rectangle limits become +-1e300 m. Initial overlaps
///   are accepted whatever their depth (Params::max_start_overlap = inf), as in DEMLab.
/// - Convection acts on every particle (grain has one convection model for all): a
///   `convection.particles` list that leaves some particle out is refused.
/// - A finite `indirect.alpha_radius` is refused (grain's porosity hulls are convex hulls, alpha
///   = inf). Voronoi cutoff_distance defaults to DEMLab's 1 (grain's own default is 0.5).
/// - The driver refuses what grain's models cannot express: viscoelastic_nonlinear with
///   damping_coeff and TTI or no damping_formula (grain's Tsuji damping takes the dimensionless
///   alpha, not eta), sds_linear with neither damping_coeff nor restitution_coeff (DEMLab refuses
///   it too), a dashpot with damping_coeff 0.
/// - sds_nonlinear DD has no viscous part in DEMLab: a damping_coeff given with it is ignored
///   (with a note).
/// - time_step 0: grain's automatic step. A time step above grain's stable limit: a note with both
///   values, and the run at grain's automatic step (a mechanical limit) or at half the
///   conduction limit 2 / lambda_max (the stiffest conduction mode then decays without
///   oscillating).
/// - A row of results.csv holds the state at its instant and the rates evaluated from that state
///   (forces, torques, accelerations, particle heat rates: grain computes them in the step that
///   starts there), as DEMLab stores them; the last row's rates come from one more step after
///   the final time, which is not written.
/// - Global records: over the active particles (`nan` without any), averages of |v|, |w|, |a|,
///   |alpha| and T, extremes of |v|, |a|, T and of the signed w and alpha (DEMLab's);
///   heat_rate_total, conduction_direct_total and conduction_indirect_total are sums of |Q| over
///   the conducting pairs and particle-wall contacts (DEMLab's activity measures).

#include <grain/grain.hpp>
#include <grain/io/atomic_file.hpp>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <limits>
#include <locale>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <tuple>
#include <type_traits>
#include <unordered_map>
#include <utility>
#include <vector>

namespace grain::demlab {
namespace detail {

inline constexpr double inf = std::numeric_limits<double>::infinity();
inline constexpr double nan = std::numeric_limits<double>::quiet_NaN();

/// Throws InputError "<where>: <key> = <value> is invalid; valid: <valid>".
[[noreturn]] inline void fail(const std::string& where, const std::string& key,
                              const std::string& value, const std::string& valid) {
  throw InputError(where + ": " + key + " = " + value + " is invalid; valid: " + valid);
}

/// A number as text (10 significant digits, "inf" for infinity).
inline std::string text(double v) { return grain::detail::to_text(v); }

/// Prints a line "grain-demlab: note: <message>" on stdout.
inline void note(const std::string& message) {
  std::printf("grain-demlab: note: %s\n", message.c_str());
  std::fflush(stdout);
}

/// DEMLab particle ids and wall ids of a record.
struct Ids {
  std::vector<std::int64_t> particles, walls;
};

/// The tokens of one run-file line, read from left to right.
struct Tokens {
  std::vector<std::string> words;
  std::size_t next = 0;
  std::string where; ///< "grain-demlab: FILE:LINE", for messages

  bool done() const { return next >= words.size(); }
  const std::string& word(const std::string& what) {
    if (done()) fail(where, what, "(missing)", "a value (the line ends too early)");
    return words[next++];
  }
  double number(const std::string& what) {
    const std::string& w = word(what);
    char* end = nullptr;
    const double v = std::strtod(w.c_str(), &end);
    if (end == w.c_str() || *end != '\0' || std::isnan(v)) fail(where, what, w, "a number");
    return v;
  }
  long integer(const std::string& what) {
    const std::string& w = word(what);
    char* end = nullptr;
    const long v = std::strtol(w.c_str(), &end, 10);
    if (end == w.c_str() || *end != '\0') fail(where, what, w, "a whole number");
    return v;
  }
  /// `n id1 ... idn`.
  std::vector<std::int64_t> id_list(const std::string& what) {
    const long n = integer(what + " count");
    if (n < 0) fail(where, what + " count", std::to_string(n), "[0, inf)");
    std::vector<std::int64_t> ids;
    for (long k = 0; k < n; ++k)
      ids.push_back(integer(what));
    return ids;
  }
  /// `[P <ids>] [W <ids>]` to the end of the line.
  Ids targets(bool walls_allowed) {
    Ids t;
    while (!done()) {
      const std::string& tag = word("target");
      if (tag == "P")
        t.particles = id_list("particle id");
      else if (tag == "W" && walls_allowed)
        t.walls = id_list("wall id");
      else
        fail(where, "target", tag, walls_allowed ? "P <ids> or W <ids>" : "P <ids>");
    }
    return t;
  }
  void end() {
    if (!done()) fail(where, "field", words[next], "the end of the line (too many fields)");
  }
};

/// A bounding box or a sink: `rectangle|circle|polygon t0 t1 numbers...`.
struct RegionSpec {
  std::string shape;
  double t0 = 0.0, t1 = inf;
  std::vector<double> values;
  std::string where;
};

struct MaterialSpec {
  std::string name;
  double density = 0, young = 0, young_real = 0, shear = 0, poisson = 0, conductivity = 0,
         heat_capacity = 0, restitution = 0, friction = 0, rolling_friction = 0;
};

struct ParticleLine {
  std::int64_t id = 0;
  double x = 0, y = 0, orientation = 0, radius = 0;
  long material = 0;
  std::string where;
};

struct WallLine {
  bool circle = false;
  std::int64_t id = 0;
  std::vector<double> coords; ///< x1 y1 x2 y2 (line) or cx cy r (circle)
  long material = -1;
  std::string where;
};

struct InitialLine {
  std::string kind; ///< velocity, omega, temperature
  std::vector<double> values;
  Ids targets;
  std::string where;
};

/// `condition <kind> <function> <t0> <t1> <parameters> P <ids> W <ids>`.
struct ConditionLine {
  std::string kind, function;
  double t0 = 0.0, t1 = inf;
  int components = 1;
  std::vector<double> values;       ///< constant, linear, oscillatory parameters
  std::vector<double> table_t;      ///< table abscissae [s]
  std::vector<double> table_values; ///< table rows, `components` values each
  Ids targets;
  std::string where;
};

struct ParamLine {
  std::string value;
  std::vector<std::int64_t> ids; ///< convection.particles
  std::string where;
};

struct RecordLine {
  bool global = true;
  std::string quantity;
  std::int64_t id = 0;
  std::string where;
};

/// The contents of a run file.
struct RunFile {
  std::string path, name, analysis;
  bool sphere = true;
  double length = 1.0;
  double time_step = 0.0, final_time = -1.0;
  long output_count = 100;
  double progress = 1.0;
  Vec2 gravity = Vec2::Zero();
  double damping_translation = 0.0, damping_rotation = 0.0;
  bool has_fluid = false;
  std::array<double, 8> fluid{}; ///< rho mu k c vx vy T porosity
  std::optional<RegionSpec> bbox;
  std::vector<RegionSpec> sinks;
  std::vector<MaterialSpec> materials;
  std::vector<ParticleLine> particles;
  std::vector<WallLine> walls;
  std::vector<InitialLine> initials;
  std::vector<ConditionLine> conditions;
  std::map<std::string, ParamLine> params;
  std::vector<RecordLine> records;
  bool vtk = false;
  /// `print <single 0|1> <n> <result>...`: DEMLab's .pos files (results: position, velocity,
  /// acceleration, temperature)
  bool print = false, print_single = false;
  std::vector<std::string> print_results;

  bool mechanical() const { return analysis != "thermal"; }
  bool heated() const { return analysis != "mechanical"; }
  const ParamLine* param(const std::string& key) const {
    const auto it = params.find(key);
    return it == params.end() ? nullptr : &it->second;
  }
  bool has(const std::string& key) const { return param(key) != nullptr; }
  /// The text of a param, or `fallback`.
  std::string word(const std::string& key, const std::string& fallback) const {
    const ParamLine* p = param(key);
    return p ? p->value : fallback;
  }
  /// The number of a param (InputError if it is not one), or `fallback`.
  double number(const std::string& key, double fallback) const {
    const ParamLine* p = param(key);
    if (!p) return fallback;
    char* end = nullptr;
    const double v = std::strtod(p->value.c_str(), &end);
    if (end == p->value.c_str() || *end != '\0' || std::isnan(v))
      fail(p->where, "param " + key, p->value, "a number");
    return v;
  }
  std::string where(const std::string& key) const {
    const ParamLine* p = param(key);
    return p ? p->where : "grain-demlab: " + path;
  }
};

/// The number of components of a condition kind (0 for an unknown kind).
inline int condition_components(const std::string& kind) {
  if (kind == "force" || kind == "fix_velocity") return 2;
  if (kind == "torque" || kind == "heat_flux" || kind == "heat_rate" || kind == "fix_omega" ||
      kind == "fix_temperature")
    return 1;
  return 0;
}

/// Reads a region after its keyword: shape, interval and numbers.
inline RegionSpec read_region(Tokens& t) {
  RegionSpec r;
  r.where = t.where;
  r.shape = t.word("shape");
  r.t0 = t.number("t0");
  r.t1 = t.number("t1");
  if (r.shape == "rectangle") {
    for (const char* k : {"xmin", "ymin", "xmax", "ymax"})
      r.values.push_back(t.number(k));
  } else if (r.shape == "circle") {
    for (const char* k : {"cx", "cy", "r"})
      r.values.push_back(t.number(k));
  } else if (r.shape == "polygon") {
    const long n = t.integer("point count");
    if (n < 3) fail(t.where, "point count", std::to_string(n), "[3, inf)");
    for (long k = 0; k < 2 * n; ++k)
      r.values.push_back(t.number("coordinate"));
  } else {
    fail(t.where, "shape", r.shape, "rectangle, circle, polygon");
  }
  t.end();
  return r;
}

/// Reads and checks the format of a run file (the meaning is checked while the simulation is
/// set up).
inline RunFile read_run_file(const std::string& path) {
  std::ifstream in(path);
  if (!in)
    throw InputError("grain-demlab: run file = '" + path +
                     "' is invalid: it cannot be opened; valid: a readable run file");
  RunFile rf;
  rf.path = path;
  std::string line;
  long number = 0;
  bool first = true;
  while (std::getline(in, line)) {
    ++number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    Tokens t;
    t.where = "grain-demlab: " + path + ":" + std::to_string(number);
    std::istringstream words(line);
    for (std::string w; words >> w;)
      t.words.push_back(w);
    if (t.words.empty() || t.words[0][0] == '#') continue;
    const std::string key = t.word("record");
    if (first) {
      if (key != "grain-demlab-run" || t.word("version") != "1")
        fail(t.where, "first line", line, "'grain-demlab-run 1'");
      t.end();
      first = false;
      continue;
    }
    if (key == "name") {
      rf.name = t.word("name");
    } else if (key == "analysis") {
      rf.analysis = t.word("analysis");
      if (rf.analysis != "mechanical" && rf.analysis != "thermal" &&
          rf.analysis != "thermo_mechanical")
        fail(t.where, "analysis", rf.analysis, "mechanical, thermal, thermo_mechanical");
    } else if (key == "shape") {
      const std::string s = t.word("shape");
      if (s == "sphere") {
        rf.sphere = true;
      } else if (s == "cylinder") {
        rf.sphere = false;
        rf.length = t.number("length");
      } else {
        fail(t.where, "shape", s, "sphere, cylinder <length>");
      }
    } else if (key == "time_step") {
      rf.time_step = t.number("time_step");
      if (!(rf.time_step >= 0.0 && std::isfinite(rf.time_step)))
        fail(t.where, "time_step", text(rf.time_step), "[0, inf) s (0: automatic)");
    } else if (key == "final_time") {
      rf.final_time = t.number("final_time");
      if (!(rf.final_time > 0.0 && std::isfinite(rf.final_time)))
        fail(t.where, "final_time", text(rf.final_time), "(0, inf) s");
    } else if (key == "output_count") {
      rf.output_count = t.integer("output_count");
      if (rf.output_count < 1)
        fail(t.where, "output_count", std::to_string(rf.output_count), "[1, inf)");
    } else if (key == "progress") {
      rf.progress = t.number("progress");
      if (!(rf.progress > 0.0)) fail(t.where, "progress", text(rf.progress), "(0, 100] %");
    } else if (key == "gravity") {
      rf.gravity.x() = t.number("gx"); // (one statement each: the order of reading matters)
      rf.gravity.y() = t.number("gy");
    } else if (key == "damping") {
      rf.damping_translation = t.number("c_translation");
      rf.damping_rotation = t.number("c_rotation");
    } else if (key == "fluid") {
      rf.has_fluid = true;
      std::size_t k = 0;
      for (const char* what : {"density", "viscosity", "conductivity", "heat_capacity",
                               "velocity_x", "velocity_y", "temperature", "porosity"})
        rf.fluid[k++] = t.number(std::string("fluid ") + what);
    } else if (key == "bbox") {
      if (rf.bbox) fail(t.where, "bbox", "a second bounding box", "one bbox line");
      rf.bbox = read_region(t);
      continue;
    } else if (key == "sink") {
      rf.sinks.push_back(read_region(t));
      continue;
    } else if (key == "material") {
      const long index = t.integer("material index");
      if (index != static_cast<long>(rf.materials.size()))
        fail(t.where, "material index", std::to_string(index),
             std::to_string(rf.materials.size()) + " (materials are numbered 0, 1, ... in order)");
      MaterialSpec m;
      m.name = t.word("material name");
      m.density = t.number("density");
      m.young = t.number("young");
      m.young_real = t.number("young_real");
      m.shear = t.number("shear");
      m.poisson = t.number("poisson");
      m.conductivity = t.number("conductivity");
      m.heat_capacity = t.number("heat_capacity");
      m.restitution = t.number("restitution");
      m.friction = t.number("friction");
      m.rolling_friction = t.number("rolling_friction");
      rf.materials.push_back(m);
    } else if (key == "particle") {
      ParticleLine p;
      p.where = t.where;
      p.id = t.integer("particle id");
      p.x = t.number("x");
      p.y = t.number("y");
      p.orientation = t.number("orientation");
      p.radius = t.number("radius");
      p.material = t.integer("material index");
      // the file's line in the message (add_particle would name the particle only)
      for (const auto& [what, v] :
           {std::pair<const char*, double>{"x", p.x}, {"y", p.y}, {"orientation", p.orientation}})
        if (!std::isfinite(v)) fail(t.where, std::string("particle ") + what, text(v), "finite");
      if (!(p.radius > 0.0 && std::isfinite(p.radius)))
        fail(t.where, "particle radius", text(p.radius), "(0, inf) m");
      rf.particles.push_back(p);
    } else if (key == "wall") {
      WallLine w;
      w.where = t.where;
      const std::string kind = t.word("wall kind");
      if (kind != "line" && kind != "circle") fail(t.where, "wall kind", kind, "line, circle");
      w.circle = kind == "circle";
      w.id = t.integer("wall id");
      for (int k = 0; k < (w.circle ? 3 : 4); ++k) {
        w.coords.push_back(t.number("wall coordinate"));
        if (!std::isfinite(w.coords.back()))
          fail(t.where, "wall coordinate", text(w.coords.back()), "finite");
      }
      if (w.circle && !(w.coords[2] > 0.0))
        fail(t.where, "circle wall radius", text(w.coords[2]), "(0, inf) m");
      w.material = t.integer("material index");
      rf.walls.push_back(w);
    } else if (key == "initial") {
      InitialLine c;
      c.where = t.where;
      c.kind = t.word("initial kind");
      const int n = c.kind == "velocity"                             ? 2
                    : (c.kind == "omega" || c.kind == "temperature") ? 1
                                                                     : 0;
      if (n == 0) fail(t.where, "initial kind", c.kind, "velocity, omega, temperature");
      for (int k = 0; k < n; ++k)
        c.values.push_back(t.number("initial value"));
      c.targets = t.targets(c.kind == "temperature");
      rf.initials.push_back(std::move(c));
      continue;
    } else if (key == "condition") {
      ConditionLine c;
      c.where = t.where;
      c.kind = t.word("condition kind");
      c.components = condition_components(c.kind);
      if (c.components == 0)
        fail(t.where, "condition kind", c.kind,
             "force, torque, heat_flux, heat_rate, fix_velocity, fix_omega, fix_temperature");
      c.function = t.word("function");
      c.t0 = t.number("t0");
      c.t1 = t.number("t1");
      if (!(c.t1 >= c.t0)) fail(t.where, "t1", text(c.t1), "[t0, inf] = [" + text(c.t0) + ", inf]");
      const int n = c.components;
      if (c.function == "constant") {
        for (int k = 0; k < n; ++k)
          c.values.push_back(t.number("value"));
      } else if (c.function == "linear") {
        for (int k = 0; k < 2 * n; ++k)
          c.values.push_back(t.number(k < n ? "initial value" : "slope"));
      } else if (c.function == "oscillatory") {
        for (int k = 0; k < 2 * n; ++k)
          c.values.push_back(t.number(k < n ? "base value" : "amplitude"));
        c.values.push_back(t.number("period"));
        c.values.push_back(t.number("shift"));
      } else if (c.function == "table") {
        const long rows = t.integer("table rows");
        if (rows < 2) fail(t.where, "table rows", std::to_string(rows), "[2, inf)");
        for (long r = 0; r < rows; ++r) {
          c.table_t.push_back(t.number("table time"));
          for (int k = 0; k < n; ++k)
            c.table_values.push_back(t.number("table value"));
        }
      } else {
        fail(t.where, "function", c.function, "constant, linear, oscillatory, table");
      }
      const bool walls =
          c.kind == "fix_velocity" || c.kind == "fix_omega" || c.kind == "fix_temperature";
      c.targets = t.targets(true);
      if (!walls && !c.targets.walls.empty())
        fail(t.where, "W (walls of condition " + c.kind + ")",
             std::to_string(c.targets.walls.size()) + " walls",
             "none (prescribed conditions act on particles only)");
      rf.conditions.push_back(std::move(c));
      continue;
    } else if (key == "param") {
      const std::string k = t.word("param key");
      ParamLine p;
      p.where = t.where;
      if (k == "convection.particles") {
        p.ids = t.id_list("particle id");
        p.value = std::to_string(p.ids.size()) + " particles";
      } else {
        p.value = t.word("param value");
      }
      rf.params[k] = std::move(p);
    } else if (key == "record") {
      RecordLine r;
      r.where = t.where;
      const std::string scope = t.word("record scope");
      if (scope != "global" && scope != "particle")
        fail(t.where, "record scope", scope, "global, particle");
      r.global = scope == "global";
      r.quantity = t.word("record quantity");
      if (!r.global) r.id = t.integer("particle id");
      rf.records.push_back(r);
    } else if (key == "vtk") {
      const long v = t.integer("vtk");
      if (v != 0 && v != 1) fail(t.where, "vtk", std::to_string(v), "0, 1");
      rf.vtk = v == 1;
    } else if (key == "print") {
      const long single = t.integer("print single_file");
      if (single != 0 && single != 1)
        fail(t.where, "print single_file", std::to_string(single), "0, 1");
      rf.print = true;
      rf.print_single = single == 1;
      const long n = t.integer("print count");
      for (long k = 0; k < n; ++k) {
        const std::string r = t.word("print result");
        if (r != "position" && r != "velocity" && r != "acceleration" && r != "temperature")
          fail(t.where, "print result", r, "position, velocity, acceleration, temperature");
        rf.print_results.push_back(r);
      }
    } else {
      fail(t.where, "record", key,
           "name, analysis, shape, time_step, final_time, output_count, progress, gravity, "
           "damping, fluid, bbox, sink, material, particle, wall, initial, condition, param, "
           "record, vtk, print");
    }
    t.end();
  }
  const std::string where = "grain-demlab: " + path;
  if (first) fail(where, "first line", "(empty file)", "'grain-demlab-run 1'");
  if (rf.name.empty()) fail(where, "name", "(missing)", "a 'name <name>' line");
  if (rf.analysis.empty()) fail(where, "analysis", "(missing)", "an 'analysis ...' line");
  if (rf.final_time < 0) fail(where, "final_time", "(missing)", "a 'final_time <T>' line");
  return rf;
}

// ------------------------------------------------------------------ model types

template <class T>
struct is_linear : std::false_type {};
template <class V>
struct is_linear<normal::BasicLinearSpringDashpot<V>> : std::true_type {};
template <class T>
struct is_walton_braun : std::false_type {};
template <class V>
struct is_walton_braun<normal::BasicWaltonBraun<V>> : std::true_type {};
/// The impact-velocity policy of the linear normal models.
template <class T>
struct impact_policy {
  using type = normal::PerContactVelocity;
};
template <class V>
struct impact_policy<normal::BasicLinearSpringDashpot<V>> {
  using type = V;
};
template <class V>
struct impact_policy<normal::BasicWaltonBraun<V>> {
  using type = V;
};
template <class T>
struct is_hertz : std::false_type {};
template <class D>
struct is_hertz<normal::Hertz<D>> : std::true_type {};
template <class T>
struct is_combined : std::false_type {};
template <class A, class B>
struct is_combined<conduction::Combined<A, B>> : std::true_type {};

/// The DEMLab name of a normal model ("" for none with an equivalent).
template <class N>
constexpr const char* normal_key() {
  if constexpr (is_linear<N>::value)
    return "viscoelastic_linear";
  else if constexpr (is_hertz<N>::value)
    return "viscoelastic_nonlinear";
  else if constexpr (is_walton_braun<N>::value)
    return "elastoplastic_linear";
  else
    return "";
}
/// DEMLab's damping_formula of Hertz<D>.
template <class D>
constexpr const char* damping_key() {
  if constexpr (std::is_same_v<D, normal::TsujiDamping>)
    return "TTI";
  else if constexpr (std::is_same_v<D, normal::CriticalRatioDamping>)
    return "critical_ratio";
  else if constexpr (std::is_same_v<D, normal::KuwabaraKonoDamping>)
    return "KK";
  else if constexpr (std::is_same_v<D, normal::LeeHerrmannDamping>)
    return "LH";
  else
    return "";
}
template <class N>
struct hertz_damping {
  using type = void;
};
template <class D>
struct hertz_damping<normal::Hertz<D>> {
  using type = D;
};

/// DEMLab's tangent model and formula of a tangent model ({"", ""} for tangent::None,
/// {nullptr, nullptr} for a model without an equivalent).
template <class T>
constexpr std::pair<const char*, const char*> tangent_key() {
  using namespace grain::tangent;
  if constexpr (std::is_same_v<T, None>)
    return {"", ""};
  else if constexpr (std::is_same_v<T, Slider>)
    return {"simple_slider", ""};
  else if constexpr (std::is_same_v<T, Spring>)
    return {"simple_spring", ""};
  else if constexpr (std::is_same_v<T, Dashpot>)
    return {"simple_dashpot", ""};
  else if constexpr (std::is_same_v<T, SpringSlider>)
    return {"spring_slider", ""};
  else if constexpr (std::is_same_v<T, DashpotSlider>)
    return {"dashpot_slider", ""};
  else if constexpr (std::is_same_v<T, SpringDashpotSlider>)
    return {"sds_linear", ""};
  else if constexpr (std::is_same_v<T, DiRenzoDiMaio>)
    return {"sds_nonlinear", "DD"};
  else if constexpr (std::is_same_v<T, LangstonTuzunHeyes>)
    return {"sds_nonlinear", "LTH"};
  else if constexpr (std::is_same_v<T, ZhengZhuYu>)
    return {"sds_nonlinear", "ZZY"};
  else if constexpr (std::is_same_v<T, Tsuji>)
    return {"sds_nonlinear", "TTI"};
  else
    return {nullptr, nullptr};
}

template <class R>
constexpr const char* rolling_key() {
  if constexpr (std::is_same_v<R, rolling::None>)
    return "";
  else if constexpr (std::is_same_v<R, rolling::Constant>)
    return "constant";
  else if constexpr (std::is_same_v<R, rolling::Viscous>)
    return "viscous";
  else
    return nullptr;
}

/// DEMLab's name of a direct ("bob" ...) or indirect ("vononoi_a" ...) conduction model.
template <class M>
constexpr const char* conduction_key() {
  if constexpr (std::is_same_v<M, conduction::BatchelorOBrien>)
    return "bob";
  else if constexpr (std::is_same_v<M, conduction::ThermalPipe>)
    return "thermal_pipe";
  else if constexpr (std::is_same_v<M, conduction::Collisional>)
    return "collisional";
  else if constexpr (std::is_same_v<M, conduction::VoronoiA>)
    return "vononoi_a";
  else if constexpr (std::is_same_v<M, conduction::VoronoiB>)
    return "vononoi_b";
  else if constexpr (std::is_same_v<M, conduction::SurroundingLayer>)
    return "surrounding_layer";
  else if constexpr (std::is_same_v<M, conduction::None>)
    return "";
  else
    return nullptr;
}
template <class M>
constexpr bool indirect_model =
    std::is_same_v<M, conduction::VoronoiA> || std::is_same_v<M, conduction::VoronoiB> ||
    std::is_same_v<M, conduction::SurroundingLayer>;

/// {direct, indirect} DEMLab names of the conduction slot.
template <class M>
std::pair<std::string, std::string> conduction_keys() {
  if constexpr (is_combined<M>::value) {
    return [&]<class A, class B>(conduction::Combined<A, B>*) {
      return std::pair<std::string, std::string>{conduction_key<A>(), conduction_key<B>()};
    }(static_cast<M*>(nullptr));
  } else if constexpr (indirect_model<M>) {
    return {"", conduction_key<M>()};
  } else {
    return {conduction_key<M>(), ""};
  }
}

template <class A>
constexpr const char* area_key() {
  if constexpr (std::is_same_v<A, area::ZhouYuZulli>)
    return "ZYZ";
  else if constexpr (std::is_same_v<A, area::LuMorrisLiBenyahia>)
    return "LMLB";
  else if constexpr (std::is_same_v<A, area::MorrisPannalaMaHrenya>)
    return "MPMH";
  else if constexpr (std::is_same_v<A, area::None> || std::is_same_v<A, area::Geometric>)
    return "";
  else
    return nullptr;
}

template <class C>
constexpr const char* convection_key() {
  if constexpr (std::is_same_v<C, convection::RanzMarshall>)
    return "sphere_hanz_marshall";
  else if constexpr (std::is_same_v<C, convection::Whitaker>)
    return "sphere_whitaker";
  else
    return "";
}

/// Throws unless the run file names the model `expected` ("" = none) under `key`.
inline void expect_model(const RunFile& rf, const std::string& key, const std::string& expected,
                         const std::string& cpp) {
  const std::string got = rf.word(key, "");
  if (got == expected) return;
  fail(rf.where(key), "param " + key, got.empty() ? "(none)" : got,
       (expected.empty() ? std::string("none") : "'" + expected + "'") +
           ", the model of this program (" + cpp +
           "); build the program of this project again with grain-demlab");
}

/// A Yes/No param (`0|1`).
inline bool flag(const RunFile& rf, const std::string& key, bool fallback) {
  const std::string v = rf.word(key, fallback ? "1" : "0");
  if (v == "1" || v == "true") return true;
  if (v == "0" || v == "false") return false;
  fail(rf.where(key), "param " + key, v, "0, 1");
}

/// normal::Equivalence of a stiffness formula.
inline normal::Equivalence equivalence(const RunFile& rf, const std::string& key) {
  const std::string v = rf.word(key, "energy");
  if (v == "energy") return normal::Equivalence::energy;
  if (v == "overlap") return normal::Equivalence::overlap;
  if (v == "time") return normal::Equivalence::time;
  fail(rf.where(key), "param " + key, v, "energy, overlap, time");
}

/// Throws unless `key` (a coefficient) is given and > 0 / >= 0.
inline double required(const RunFile& rf, const std::string& key, const std::string& why,
                       bool positive) {
  if (!rf.has(key)) fail(rf.where(key), "param " + key, "(not given)", "a number (" + why + ")");
  const double v = rf.number(key, 0.0);
  if (!(positive ? v > 0.0 : v >= 0.0) || !std::isfinite(v))
    fail(rf.where(key), "param " + key, text(v), positive ? "(0, inf)" : "[0, inf)");
  return v;
}

/// The restitution coefficient of the project (material field or normal.restitution_coeff); 0 =
/// not given.
inline double project_restitution(const RunFile& rf) {
  for (const auto& m : rf.materials)
    if (m.restitution > 0.0) return m.restitution;
  return rf.number("normal.restitution_coeff", 0.0);
}

/// The normal model's parameters.
template <class N>
void map_normal(typename N::Params& p, const RunFile& rf) {
  static_assert(normal_key<N>()[0] != '\0',
                "grain::demlab::main: the normal model has no DEMLab equivalent; use "
                "normal::LinearSpringDashpot[PerContact], normal::Hertz<D> or "
                "normal::WaltonBraun[PerContact]");
  const std::string cpp = grain::detail::to_text(N::name);
  if (!rf.mechanical()) return; // a thermal analysis evaluates no force
  expect_model(rf, "normal.model", normal_key<N>(), cpp);
  const bool restitution = project_restitution(rf) > 0.0;
  const std::string w = rf.where("normal.model");
  if constexpr (is_linear<N>::value) {
    p.stiffness = rf.has("normal.stiff_coeff") ? required(rf, "normal.stiff_coeff", "", true) : 0.0;
    p.equivalence = equivalence(rf, "normal.stiff_formula");
    if (rf.has("normal.damping_coeff"))
      p.damping = required(rf, "normal.damping_coeff", "", false);
    else if (!restitution)
      fail(w, "param normal.restitution_coeff", "(not given)",
           "a restitution in (0, 1] (viscoelastic_linear without damping_coeff damps from it)");
    if (p.stiffness == 0.0 && p.equivalence != normal::Equivalence::energy && !restitution)
      fail(w, "param normal.restitution_coeff", "(not given)",
           "a restitution in (0, 1] (stiff_formula overlap and time use it)");
    p.no_cohesion = flag(rf, "normal.remove_artificial_cohesion", true);
  } else if constexpr (is_hertz<N>::value) {
    using D = typename hertz_damping<N>::type;
    expect_model(rf, "normal.damping_formula", damping_key<D>(), cpp);
    p.no_cohesion = flag(rf, "normal.remove_artificial_cohesion", true);
    if constexpr (std::is_same_v<D, normal::TsujiDamping>) {
      if (rf.has("normal.damping_coeff"))
        fail(rf.where("normal.damping_coeff"), "param normal.damping_coeff",
             rf.word("normal.damping_coeff", ""),
             "not given with damping_formula TTI (grain's Tsuji damping takes the dimensionless "
             "alpha of the restitution coefficient, not a coefficient eta [N s/m^1.25])");
      if (!restitution)
        fail(w, "param normal.restitution_coeff", "(not given)",
             "a restitution in (0, 1] (damping_formula TTI damps from it)");
      p.damping.map = normal::TsujiMap::norouzi;
    } else if constexpr (std::is_same_v<D, normal::CriticalRatioDamping>) {
      p.damping.ratio = required(rf, "normal.ratio", "damping_formula critical_ratio", false);
    } else {
      p.damping.coefficient = required(rf, "normal.damping_coeff",
                                       std::string("damping_formula ") + damping_key<D>(), false);
    }
  } else {
    p.stiffness = rf.has("normal.stiff_coeff") ? required(rf, "normal.stiff_coeff", "", true) : 0.0;
    p.equivalence = equivalence(rf, "normal.load_stiff_formula");
    const std::string u = rf.word("normal.unload_stiff_formula", "constant");
    if (u == "constant")
      p.unloading = normal::Unloading::constant;
    else if (u == "variable")
      p.unloading = normal::Unloading::variable;
    else
      fail(rf.where("normal.unload_stiff_formula"), "param normal.unload_stiff_formula", u,
           "constant, variable");
    if (p.unloading == normal::Unloading::variable)
      p.unloading_slope =
          required(rf, "normal.unload_param", "unload_stiff_formula variable", true);
    if (!restitution)
      fail(w, "param normal.restitution_coeff", "(not given)",
           "a restitution in (0, 1] (elastoplastic_linear needs it)");
  }
}

/// The tangent model's parameters.
template <class T>
void map_tangent(typename T::Params& p, const RunFile& rf) {
  constexpr auto key = tangent_key<T>();
  static_assert(key.first != nullptr,
                "grain::demlab::main: the tangent model has no DEMLab equivalent; use "
                "tangent::None, Slider, Spring, Dashpot, SpringSlider, DashpotSlider, "
                "SpringDashpotSlider, DiRenzoDiMaio, LangstonTuzunHeyes, ZhengZhuYu or Tsuji");
  if (!rf.mechanical()) return;
  const std::string cpp = grain::detail::to_text(T::name);
  expect_model(rf, "tangent.model", key.first, cpp);
  if (key.second[0] != '\0') expect_model(rf, "tangent.formula", key.second, cpp);
  const bool stiff = rf.has("tangent.stiff_coeff");
  const bool damp = rf.has("tangent.damping_coeff");
  using namespace grain::tangent;
  if constexpr (std::is_same_v<T, Spring> || std::is_same_v<T, SpringSlider>) {
    if (stiff) p.stiffness = required(rf, "tangent.stiff_coeff", "", true);
  } else if constexpr (std::is_same_v<T, Dashpot> || std::is_same_v<T, DashpotSlider>) {
    p.damping = required(rf, "tangent.damping_coeff", std::string(key.first) + " needs it", true);
  } else if constexpr (std::is_same_v<T, SpringDashpotSlider>) {
    if (stiff) p.stiffness = required(rf, "tangent.stiff_coeff", "", true);
    p.kappa = 3.5; // DEMLab: the mass of the tangential motion is 2 m*/7 for any shape
    if (damp) {
      p.damping = required(rf, "tangent.damping_coeff", "", false);
    } else if (rf.has("tangent.restitution_coeff")) {
      p.restitution = rf.number("tangent.restitution_coeff", 0.0);
      if (!(p.restitution >= 0.0 && p.restitution <= 1.0))
        fail(rf.where("tangent.restitution_coeff"), "param tangent.restitution_coeff",
             text(p.restitution), "[0, 1]");
    } else {
      fail(rf.where("tangent.model"), "param tangent.restitution_coeff", "(not given)",
           "a tangential restitution in [0, 1], or tangent.damping_coeff (sds_linear needs one)");
    }
  } else if constexpr (std::is_same_v<T, DiRenzoDiMaio>) {
    if (damp)
      note("tangent.damping_coeff is ignored by sds_nonlinear DD (no viscous part in "
           "DEMLab)");
  } else if constexpr (std::is_same_v<T, LangstonTuzunHeyes>) {
    p.damping = required(rf, "tangent.damping_coeff", "formula LTH needs it", false);
  } else if constexpr (std::is_same_v<T, ZhengZhuYu>) {
    p.viscosity = required(rf, "tangent.damping_coeff", "formula ZZY needs it", false);
  } else if constexpr (std::is_same_v<T, Tsuji>) {
    if (damp) p.damping = required(rf, "tangent.damping_coeff", "", false);
  } else {
    (void)p;
    (void)stiff;
    (void)damp;
  }
}

/// The parameters of a conduction model (recursing into Combined).
template <class M>
void map_conduction(typename M::Params& p, const RunFile& rf) {
  if constexpr (is_combined<M>::value) {
    [&]<class A, class B>(conduction::Combined<A, B>*) {
      map_conduction<A>(p.direct, rf);
      map_conduction<B>(p.indirect, rf);
    }(static_cast<M*>(nullptr));
  } else if constexpr (std::is_same_v<M, conduction::ThermalPipe>) {
    p.isothermal_walls = true; // DEMLab: k_avg = k_p at every wall with a material
  } else if constexpr (std::is_same_v<M, conduction::SurroundingLayer>) {
    p.layer_ratio = rf.number("indirect.layer_thick", 0.4);
    p.min_gap = rf.number("indirect.min_distance", 2.75e-8);
    p.abs_tolerance = rf.number("indirect.tolerance_absolute", p.abs_tolerance);
    p.rel_tolerance = rf.number("indirect.tolerance_relative", p.rel_tolerance);
  } else if constexpr (std::is_same_v<M, conduction::VoronoiA>) {
    p.max_gap_ratio = rf.number("indirect.cutoff_distance", 1.0);
    p.abs_tolerance = rf.number("indirect.tolerance_absolute", p.abs_tolerance);
    p.rel_tolerance = rf.number("indirect.tolerance_relative", p.rel_tolerance);
  } else if constexpr (std::is_same_v<M, conduction::VoronoiB>) {
    p.core_ratio = rf.number("indirect.core_radius", 0.5);
    p.max_gap_ratio = rf.number("indirect.cutoff_distance", 1.0);
  } else {
    (void)p;
    (void)rf;
  }
}

/// Sim::Params::contact from the params of the run file.
template <class Sim>
void map_contact(typename Sim::contact_type::Params& c, const RunFile& rf) {
  using C = typename Sim::contact_type;
  map_normal<typename C::normal_model>(c.normal, rf);
  map_tangent<typename C::tangent_model>(c.tangent, rf);
  using R = typename C::rolling_model;
  static_assert(rolling_key<R>() != nullptr,
                "grain::demlab::main: the rolling model has no DEMLab equivalent; use "
                "rolling::None, rolling::Constant or rolling::Viscous");
  if (rf.mechanical()) {
    expect_model(rf, "rolling.model", rolling_key<R>(), grain::detail::to_text(R::name));
    if constexpr (!std::is_same_v<R, rolling::None>)
      c.rolling.coefficient = required(rf, "rolling.resistance_coeff", "rolling needs it", false);
  }
  using M = typename C::conduction_model;
  using A = typename C::area_model;
  static_assert(area_key<A>() != nullptr,
                "grain::demlab::main: the area correction has no DEMLab equivalent; use "
                "area::None, Geometric, ZhouYuZulli, LuMorrisLiBenyahia or MorrisPannalaMaHrenya");
  if (rf.heated()) {
    const auto [direct, indirect] = conduction_keys<M>();
    const std::string cpp = grain::detail::to_text(M::name);
    expect_model(rf, "direct.model", direct, cpp);
    expect_model(rf, "indirect.model", indirect, cpp);
    map_conduction<M>(c.conduction, rf);
    expect_model(rf, "area.model", area_key<A>(), grain::detail::to_text(A::name));
  }
}

// ------------------------------------------------------------------ time functions

/// Component k of a condition as a TimeFunction with DEMLab's semantics (activity [t0, t1],
/// activation time max(0, t0), table in absolute time with its end values held).
inline TimeFunction component(const ConditionLine& c, int k) {
  const int n = c.components;
  const double ta = std::max(0.0, c.t0);
  const auto v = [&](int i) { return c.values[static_cast<std::size_t>(i)]; };
  TimeFunction f;
  if (c.function == "constant") {
    f = TimeFunction::constant(v(k));
  } else if (c.function == "linear") {
    f = TimeFunction::linear(v(k), v(n + k), ta);
  } else if (c.function == "oscillatory") {
    f = TimeFunction::oscillatory(v(k), v(n + k), v(2 * n), v(2 * n + 1), ta);
  } else {
    std::vector<double> y;
    for (std::size_t r = 0; r < c.table_t.size(); ++r)
      y.push_back(c.table_values[r * static_cast<std::size_t>(n) + static_cast<std::size_t>(k)]);
    f = TimeFunction::table(Table(c.table_t, y, c.where + " " + c.kind));
  }
  return f.active(c.t0, c.t1);
}

/// The sum of several functions (each 0 while inactive), active over [t_begin, t_end].
inline TimeFunction sum_of(std::vector<TimeFunction> fs, double t_begin, double t_end) {
  return TimeFunction::callable([fs = std::move(fs)](double t) {
           double s = 0.0;
           for (const auto& f : fs)
             s += f(t);
           return s;
         })
      .active(t_begin, t_end);
}

/// DEMLab's wall temperature: the initial value (0 K if none) until a fixed temperature acts;
/// the last active fixed condition sets it; when none is active it keeps the value of the last
/// instant one was.
inline TimeFunction wall_temperature(double initial, std::vector<TimeFunction> fixed) {
  if (fixed.empty()) return TimeFunction::constant(initial);
  return TimeFunction::callable([initial, fixed = std::move(fixed)](double t) {
    double last = -inf;
    for (const auto& f : fixed)
      if (f.t_begin() <= t) last = std::max(last, std::min(t, f.t_end()));
    if (last == -inf) return initial;
    double v = initial;
    for (const auto& f : fixed)
      if (f.active(last)) v = f.value(last);
    return v;
  });
}

// ------------------------------------------------------------------ regions

inline Region<2> region(const RegionSpec& r) {
  const auto& v = r.values;
  const auto finite = [](double x) { return std::clamp(x, -1e300, 1e300); };
  if (r.shape == "rectangle")
    return regions::Box<2>{Vec2(finite(v[0]), finite(v[1])), Vec2(finite(v[2]), finite(v[3]))};
  if (r.shape == "circle") return regions::Ball<2>{Vec2(v[0], v[1]), v[2]};
  regions::Polygon p;
  for (std::size_t k = 0; k + 1 < v.size(); k += 2)
    p.vertices.emplace_back(v[k], v[k + 1]);
  return p;
}

inline bool contains(const Region<2>& r, const Vec2& x) {
  return std::visit([&](const auto& g) { return g.contains(x); }, r);
}

// ------------------------------------------------------------------ results

/// Sums of |Q| [W] over the conducting pairs and particle-wall contacts: {all, direct, indirect}.
template <class Sim>
std::array<double, 3> heat_totals(const Sim& s) {
  if constexpr (!Sim::thermal) {
    (void)s;
    return {nan, nan, nan};
  } else {
    using C = typename Sim::contact_type;
    using M = typename C::conduction_model;
    const auto& p = s.particles();
    const auto delta_t = [&](std::size_t i, std::size_t j, bool wall) {
      return (wall ? s.walls()[j].temperature : p.temperature[j]) - p.temperature[i];
    };
    double total = 0.0, direct = 0.0, indirect = 0.0;
    if constexpr (is_combined<M>::value) {
      // the direct part of each touching contact, evaluated with the direct model alone
      std::map<std::tuple<std::size_t, std::size_t, bool>, double> direct_rate;
      const double length = s.shape().sphere_mass ? 0.0 : s.shape().thickness;
      [&]<class Dir, class Ind>(conduction::Combined<Dir, Ind>*) {
        s.for_each_contact([&](const auto& v) {
          if (v.heat_rate == 0.0) return; // insulated, or no temperature difference
          const auto& g = v.geometry;
          const std::size_t mi = p.material[v.i];
          const std::size_t mj = v.wall ? s.walls()[v.j].options.material : p.material[v.j];
          const auto& cp = s.contact_params(mi, mj);
          const PairProperties pair = s.contact_pair(v.i, v.j, v.wall);
          const double a = C::area_model::radius(g, pair, v.result.normal, cp.area);
          const HeatContext hc{
              .contact_radius = a,
              .distance = uses_consistent_distance<Dir> ? C::consistent_distance(g, a) : 0.0,
              .gap = 0.0,
              .cell_radius = inf,
              .length = length,
              .time_step = s.time_step(),
              .touching = true};
          auto h = v.data.conduction.direct;
          const double q =
              Dir::conductance(g, pair, hc, cp.conduction.direct, h) * delta_t(v.i, v.j, v.wall);
          direct_rate[{v.i, v.j, v.wall}] = q;
          direct += std::abs(q);
        });
      }(static_cast<M*>(nullptr));
      s.for_each_conductance([&](std::size_t i, std::size_t j, bool wall, double H) {
        const double q = H * delta_t(i, j, wall);
        total += std::abs(q);
        const auto it = direct_rate.find({i, j, wall});
        indirect += std::abs(q - (it == direct_rate.end() ? 0.0 : it->second));
      });
    } else {
      s.for_each_conductance([&](std::size_t i, std::size_t j, bool wall, double H) {
        total += std::abs(H * delta_t(i, j, wall));
      });
      (indirect_model<M> ? indirect : direct) = total;
    }
    return {total, direct, indirect};
  }
}

/// The value of a per-particle quantity of particle i (current index).
template <class Sim>
double particle_value(const Sim& s, std::size_t i, int q) {
  const auto& p = s.particles();
  const Vec2 v = p.velocity[i];
  const Vec2 f = p.force[i];
  const Vec2 a = f * p.inv_mass[i];
  switch (q) {
  case 0:
    return p.radius[i];
  case 1:
    return p.mass[i];
  case 2:
    return p.position[i].x();
  case 3:
    return p.position[i].y();
  case 4:
    return p.orientation[i];
  case 5:
    return f.norm();
  case 6:
    return f.x();
  case 7:
    return f.y();
  case 8:
    return p.torque[i];
  case 9:
    return v.norm();
  case 10:
    return v.x();
  case 11:
    return v.y();
  case 12:
    return p.omega[i];
  case 13:
    return a.norm();
  case 14:
    return a.x();
  case 15:
    return a.y();
  case 16:
    return p.torque[i] * p.inv_inertia[i];
  case 17:
    if constexpr (Sim::thermal) return p.temperature[i];
    return nan;
  case 18:
    if constexpr (Sim::thermal) return p.heat_rate[i];
    return nan;
  }
  return nan;
}

inline const std::vector<std::string>& particle_quantities() {
  static const std::vector<std::string> q{"radius",           "mass",
                                          "coordinate_x",     "coordinate_y",
                                          "orientation",      "force_modulus",
                                          "force_x",          "force_y",
                                          "torque",           "velocity_modulus",
                                          "velocity_x",       "velocity_y",
                                          "velocity_rot",     "acceleration_modulus",
                                          "acceleration_x",   "acceleration_y",
                                          "acceleration_rot", "temperature",
                                          "heat_rate"};
  return q;
}
inline const std::vector<std::string>& global_quantities() {
  static const std::vector<std::string> q{
      "velocity_mod_avg",     "velocity_rot_avg",        "acceleration_mod_avg",
      "acceleration_rot_avg", "velocity_mod_min",        "velocity_mod_max",
      "velocity_rot_min",     "velocity_rot_max",        "acceleration_mod_min",
      "acceleration_mod_max", "acceleration_rot_min",    "acceleration_rot_max",
      "temperature_avg",      "temperature_min",         "temperature_max",
      "heat_rate_total",      "conduction_direct_total", "conduction_indirect_total"};
  return q;
}
inline std::string joined(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& x : v)
    s += (s.empty() ? "" : ", ") + x;
  return s;
}

/// One column of results.csv.
struct Column {
  bool global = true;
  int quantity = 0;
  std::int64_t id = 0;
};

/// results.csv: `time,step,<column>...`, each row written with one write. A row holds the state
/// at its instant t_k (positions, velocities, temperatures; `capture`, called at the output
/// instants) and the rates evaluated at t_k (forces, torques, accelerations, heat rates of the
/// particles), which grain computes during the step that starts at t_k (`fill`, called after
/// every step): the rates of a row are those of its own state, as DEMLab stores them.
template <class Sim>
struct Results {
  std::vector<Column> columns;
  std::shared_ptr<grain::io::detail::LineFile> file;
  struct Pending {
    bool due = false;
    long step = 0;
    double time = 0.0;
    std::vector<double> values;
    std::string pos_head, pos_position, pos_velocity, pos_temperature; ///< a .pos file's parts
  };
  std::shared_ptr<Pending> pending = std::make_shared<Pending>();
  /// DEMLab's .pos files (Print): `<folder>/<name>_<step>.pos`, or all outputs in
  /// `<folder>/<name>.pos` with `single`; the blocks in the order of `print_results`
  struct PosFiles {
    bool on = false, single = false;
    std::string prefix; ///< <folder>/<name>
    std::vector<std::string> results;
    std::vector<std::pair<std::int64_t, std::uint32_t>> walls; ///< DEMLab id, grain index
    std::shared_ptr<grain::io::detail::LineFile> file;         ///< the single file
  };
  PosFiles pos;

  static std::string fixed15(double v) {
    char b[64];
    std::snprintf(b, sizeof b, "%.15f", v);
    return b;
  }
  /// The state blocks of a .pos file (what the rates of the step do not change).
  void pos_state(const Sim& s) const {
    const auto& p = s.particles();
    auto& q = *pending;
    const auto [pp, pw] = s.contact_counts();
    char b[256];
    std::snprintf(b, sizeof b,
                  "%%STEP %ld\n%%TIME %.6f\n\n%%PARTICLES    %zu\n%%WALLS        %zu\n"
                  "%%INTERACTIONS %zu\n\n",
                  s.step_count(), s.time(), p.size(), pos.walls.size(), pp + pw);
    q.pos_head = (pos.single ? std::string(75, '-') + "\n" : std::string()) + b;
    std::vector<std::size_t> order(p.size());
    for (std::size_t i = 0; i < p.size(); ++i)
      order[i] = i;
    std::sort(order.begin(), order.end(),
              [&](std::size_t a, std::size_t c) { return p.id[a] < p.id[c]; });
    q.pos_position = "%PARTICLE_COORDINATE_ORIENTATION\n";
    q.pos_velocity = "%PARTICLE_VELOCITY\n";
    q.pos_temperature = "%PARTICLE_TEMPERATURE\n";
    for (const auto i : order) {
      const std::string id = std::to_string(p.id[i]);
      q.pos_position += id + " " + fixed15(p.position[i].x()) + " " + fixed15(p.position[i].y()) +
                        " " + fixed15(p.orientation[i]) + "\n";
      q.pos_velocity += id + " " + fixed15(p.velocity[i].x()) + " " + fixed15(p.velocity[i].y()) +
                        " " + fixed15(p.omega[i]) + "\n";
      if constexpr (Sim::thermal) q.pos_temperature += id + " " + fixed15(p.temperature[i]) + "\n";
    }
    q.pos_position += "\n";
    q.pos_velocity += "\n";
    q.pos_temperature += "\n";
    if (!pos.walls.empty()) {
      q.pos_position += "%WALL_COORDINATE\n";
      q.pos_temperature += "%WALL_TEMPERATURE\n";
      for (const auto& [id, k] : pos.walls) {
        const auto& w = s.walls()[k];
        std::string line = std::to_string(id);
        if (const auto* seg = std::get_if<walls::Segment>(&w.geometry))
          line += " " + fixed15(seg->a.x()) + " " + fixed15(seg->a.y()) + " " +
                  fixed15(seg->b.x()) + " " + fixed15(seg->b.y());
        else if (const auto* c = std::get_if<walls::Circle>(&w.geometry))
          line += " " + fixed15(c->center.x()) + " " + fixed15(c->center.y()) + " " +
                  fixed15(c->radius);
        q.pos_position += line + "\n";
        q.pos_temperature += std::to_string(id) + " " + fixed15(w.temperature) + "\n";
      }
      q.pos_position += "\n";
      q.pos_temperature += "\n";
    }
  }
  /// Writes the .pos file of the pending output, its accelerations from the rates in `s`.
  void pos_write(const Sim& s) const {
    const auto& p = s.particles();
    std::vector<std::size_t> order(p.size());
    for (std::size_t i = 0; i < p.size(); ++i)
      order[i] = i;
    std::sort(order.begin(), order.end(),
              [&](std::size_t a, std::size_t c) { return p.id[a] < p.id[c]; });
    std::string text = pending->pos_head;
    for (const auto& r : pos.results) {
      if (r == "position") {
        text += pending->pos_position;
      } else if (r == "velocity") {
        text += pending->pos_velocity;
      } else if (r == "temperature") {
        text += pending->pos_temperature;
      } else {
        text += "%PARTICLE_ACCELERATION\n";
        for (const auto i : order) {
          const Vec2 a = Vec2(p.force[i]) * p.inv_mass[i];
          text += std::to_string(p.id[i]) + " " + fixed15(a.x()) + " " + fixed15(a.y()) + " " +
                  fixed15(p.torque[i] * p.inv_inertia[i]) + "\n";
        }
        text += "\n";
      }
    }
    const std::string path = pos.single ? pos.prefix + ".pos"
                                        : pos.prefix + "_" + std::to_string(pending->step) + ".pos";
    if (pos.single) {
      pos.file->write(text);
    } else {
      grain::io::detail::AtomicFile f("grain-demlab print", path);
      f.stream() << text;
      f.commit();
    }
  }

  /// True for the columns whose value grain evaluates within a step (forces, torques,
  /// accelerations, particle heat rates).
  static bool rate(const Column& c) {
    if (c.global)
      return c.quantity == 2 || c.quantity == 3 || (c.quantity >= 8 && c.quantity <= 11);
    return (c.quantity >= 5 && c.quantity <= 8) || (c.quantity >= 13 && c.quantity <= 16) ||
           c.quantity == 18;
  }
  /// At an output instant: the state columns (the row is written after the next step).
  void capture(const Sim& s) const {
    if (pending->due) write(values(s)); // two instants in one step: the rates as they are
    pending->due = true;
    pending->step = s.step_count();
    pending->time = s.time();
    pending->values = values(s);
    if (pos.on) pos_state(s);
  }
  /// After every step: completes and writes the row captured before it.
  void fill(const Sim& s) const {
    if (!pending->due || s.step_count() == pending->step) return;
    const auto now = values(s);
    auto row = pending->values;
    for (std::size_t k = 0; k < columns.size(); ++k)
      if (rate(columns[k])) row[k] = now[k];
    if (pos.on) pos_write(s);
    write(row);
  }
  bool due() const { return pending->due; }

  void write(const std::vector<double>& vals) const {
    pending->due = false;
    std::ostringstream row;
    row.imbue(std::locale::classic());
    row.precision(17);
    row << pending->time << ',' << pending->step;
    for (const double v : vals) {
      row << ',';
      if (std::isnan(v))
        row << "nan";
      else
        row << v;
    }
    row << '\n';
    file->write(row.str());
  }

  std::vector<double> values(const Sim& s) const {
    const auto& p = s.particles();
    std::unordered_map<std::int64_t, std::size_t> index;
    bool globals = false, heat = false;
    for (const auto& c : columns) {
      globals = globals || c.global;
      heat = heat || (c.global && c.quantity >= 15);
    }
    for (const auto& c : columns)
      if (!c.global) {
        for (std::size_t i = 0; i < p.size(); ++i)
          index[p.id[i]] = i;
        break;
      }
    // global statistics: {|v|, |w|, |a|, |alpha|, T, w, alpha} -> sum, min, max (DEMLab's
    // averages of the rotations are of |w| and |alpha|, their extremes signed)
    std::array<double, 7> sum{}, lo, hi;
    lo.fill(inf);
    hi.fill(-inf);
    const std::size_t n = p.size();
    if (globals)
      for (std::size_t i = 0; i < n; ++i) {
        const double alpha = p.torque[i] * p.inv_inertia[i];
        double x[7] = {Vec2(p.velocity[i]).norm(),
                       std::abs(p.omega[i]),
                       Vec2(p.force[i] * p.inv_mass[i]).norm(),
                       std::abs(alpha),
                       nan,
                       p.omega[i],
                       alpha};
        if constexpr (Sim::thermal) x[4] = p.temperature[i];
        for (int k = 0; k < 7; ++k) {
          sum[static_cast<std::size_t>(k)] += x[k];
          lo[static_cast<std::size_t>(k)] = std::min(lo[static_cast<std::size_t>(k)], x[k]);
          hi[static_cast<std::size_t>(k)] = std::max(hi[static_cast<std::size_t>(k)], x[k]);
        }
      }
    const std::array<double, 3> q = heat ? heat_totals(s) : std::array<double, 3>{nan, nan, nan};
    std::vector<double> out;
    out.reserve(columns.size());
    for (const auto& c : columns) {
      double v = nan;
      if (!c.global) {
        const auto it = index.find(c.id);
        if (it != index.end()) v = particle_value(s, it->second, c.quantity);
      } else if (c.quantity >= 15) {
        v = q[static_cast<std::size_t>(c.quantity - 15)];
      } else if (n > 0) {
        // avg: 0 |v|, 1 |w|, 2 |a|, 3 |alpha|; then min/max pairs of |v|, w, |a|, alpha; then
        // T avg, min, max
        static constexpr int stat[15][2] = {{0, 0}, {1, 0}, {2, 0}, {3, 0}, {0, 1},
                                            {0, 2}, {5, 1}, {5, 2}, {2, 1}, {2, 2},
                                            {6, 1}, {6, 2}, {4, 0}, {4, 1}, {4, 2}};
        const auto k = static_cast<std::size_t>(stat[c.quantity][0]);
        const int what = stat[c.quantity][1];
        v = what == 0 ? sum[k] / static_cast<double>(n) : what == 1 ? lo[k] : hi[k];
      }
      out.push_back(v);
    }
    return out;
  }
};

/// A console line every `progress` % of the final time.
struct Progress {
  double final_time = 1.0;
  std::chrono::steady_clock::time_point started = std::chrono::steady_clock::now();

  template <class Sim>
  void operator()(const Sim& s) const {
    const double elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    std::printf("grain-demlab: t = %.6g s (%5.1f %%), step %ld, %.1f s elapsed\n", s.time(),
                100.0 * std::min(1.0, s.time() / final_time), s.step_count(), elapsed);
    std::fflush(stdout);
  }
};

// ------------------------------------------------------------------ set-up and run

/// Runs the run file `path` with the models of Sim, writing into `out`.
template <class Sim>
int run(const std::string& path, const std::string& out) {
  static_assert(Sim::dimension == 2 && std::is_same_v<typename Sim::shape_type, Disk>,
                "grain::demlab::main: DEMLab is 2D: the simulation's shape must be grain::Disk");
  using C = typename Sim::contact_type;
  using Conv = typename Sim::convection_type;
  const RunFile rf = read_run_file(path);
  const std::string file = "grain-demlab: " + path;

  // ---- global parameters
  typename Sim::Params params;
  params.analysis = rf.analysis == "mechanical" ? Analysis::mechanical
                    : rf.analysis == "thermal"  ? Analysis::thermal
                                                : Analysis::thermo_mechanical;
  if (rf.heated() && !Sim::thermal)
    fail(file, "analysis", rf.analysis,
         "mechanical for this program (it has no conduction model); build the program of this "
         "project again with grain-demlab");
  params.time_step = rf.time_step;
  params.gravity = rf.gravity;
  params.damping_translational = rf.damping_translation;
  params.damping_rotational = rf.damping_rotation;
  params.max_start_overlap = inf; // DEMLab accepts any initial overlap
  params.initial_temperature = 0.0;
  params.fluid.temperature = 0.0; // DEMLab's defaults
  if (rf.has_fluid) {
    const auto& f = rf.fluid;
    params.fluid.density = f[0];
    params.fluid.viscosity = f[1];
    params.fluid.conductivity = f[2];
    params.fluid.heat_capacity = f[3];
    params.fluid.velocity = Vec2(f[4], f[5]);
    params.fluid.temperature = f[6];
  }
  map_contact<Sim>(params.contact, rf);

  // convection and fluid cells
  const std::string conv = rf.word("convection.model", "");
  if (rf.heated() && conv != convection_key<Conv>())
    fail(rf.where("convection.model"), "param convection.model", conv.empty() ? "(none)" : conv,
         std::string(convection_key<Conv>()[0] ? convection_key<Conv>() : "none") +
             ", the convection model of this program (" + Conv::name +
             "); build the program of this project again with grain-demlab");
  if constexpr (C::needs_cell_radius) {
    using Cells = typename Sim::CellSizeT;
    const std::string method = rf.word("indirect.cell_size_method", "porosity_global");
    const std::string name = Cells::name;
    const std::string want = method == "porosity_global"   ? "global porosity"
                             : method == "porosity_local"  ? "local porosity"
                             : method == "voronoi_diagram" ? "Voronoi diagram"
                                                           : "";
    if (want.empty())
      fail(rf.where("indirect.cell_size_method"), "param indirect.cell_size_method", method,
           "porosity_global, porosity_local, voronoi_diagram");
    if (want != name)
      fail(rf.where("indirect.cell_size_method"), "param indirect.cell_size_method", method,
           "the cell-size method of this program (cells: " + name +
               "); give the Simulation the option cells::" +
               (method == "porosity_local"    ? "LocalPorosity"
                : method == "voronoi_diagram" ? "VoronoiDiagram (grain/thermal/voronoi.hpp, qhull)"
                                              : "GlobalPorosity"));
    if (rf.has("indirect.alpha_radius") && std::isfinite(rf.number("indirect.alpha_radius", inf)))
      fail(rf.where("indirect.alpha_radius"), "param indirect.alpha_radius",
           rf.word("indirect.alpha_radius", ""),
           "inf (grain's porosity hulls are convex hulls: alpha = inf)");
    if constexpr (requires { params.cells.update_frequency; })
      params.cells.update_frequency =
          static_cast<long>(rf.number("indirect.update_frequency", 0.0));
    if constexpr (requires { params.cells.porosity; })
      if (rf.has_fluid && rf.fluid[7] >= 0.0) params.cells.porosity = rf.fluid[7];
    if constexpr (requires { params.cells.rule; })
      params.cells.rule = cells::LocalRule::interior_angle; // DEMLab's 2D rule
  }

  const Disk shape{.thickness = rf.sphere ? 1.0 : rf.length, .sphere_mass = rf.sphere};
  Sim sim(params, shape);

  // ---- materials
  const double e = project_restitution(rf);
  const double mu = [&] {
    for (const auto& m : rf.materials)
      if (m.friction > 0.0) return m.friction;
    return rf.number("tangent.friction_coeff", 0.0);
  }();
  const double mu_r = [&] {
    for (const auto& m : rf.materials)
      if (m.rolling_friction > 0.0) return m.rolling_friction;
    return rf.number("rolling.resistance_coeff", 0.0);
  }();
  if (rf.materials.empty()) fail(file, "material", "(none)", "at least one 'material' line");
  for (const auto& m : rf.materials) {
    Material g;
    g.name = m.name;
    g.density = m.density;
    g.young = m.young > 0.0 ? m.young : m.young_real;
    if (!(g.young > 0.0)) {
      if (rf.mechanical())
        fail(file, "material " + m.name + " young", "0 (not given)",
             "(0, inf) Pa (a mechanical analysis needs Young's modulus)");
      g.young = 1e9; // unused by a thermal analysis
    }
    g.young_real = m.young_real;
    g.shear = m.shear;
    g.poisson = m.poisson;
    g.conductivity = m.conductivity;
    g.heat_capacity = m.heat_capacity;
    g.restitution = m.restitution > 0.0 ? m.restitution : (e > 0.0 ? e : 1.0);
    g.friction = m.friction > 0.0 ? m.friction : mu;
    g.rolling_friction = m.rolling_friction > 0.0 ? m.rolling_friction : mu_r;
    sim.add_material(g);
  }
  std::optional<std::uint32_t> rigid; // the material of walls without one
  auto rigid_material = [&]() -> std::uint32_t {
    if (rigid) return *rigid;
    std::set<long> used;
    for (const auto& p : rf.particles)
      used.insert(p.material);
    double nu = 0.0;
    std::set<double> nus;
    for (const long k : used)
      if (k >= 0 && k < static_cast<long>(rf.materials.size())) {
        nu += rf.materials[static_cast<std::size_t>(k)].poisson;
        nus.insert(rf.materials[static_cast<std::size_t>(k)].poisson);
      }
    if (!used.empty()) nu /= static_cast<double>(used.size());
    if (nus.size() > 1)
      note("walls without material take the mean Poisson ratio of the particles, " + text(nu) +
           " (DEMLab uses each particle's own)");
    Material g;
    g.name = "rigid wall (no material)";
    g.density = 1.0;
    g.young = 1e300;
    g.poisson = nu;
    g.restitution = e > 0.0 ? e : 1.0;
    g.friction = mu;
    g.rolling_friction = mu_r;
    rigid = sim.add_material(g);
    return *rigid;
  };
  auto material_index = [&](long k, const std::string& where) {
    if (k < 0 || k >= static_cast<long>(rf.materials.size()))
      fail(where, "material index", std::to_string(k),
           "[0, " + std::to_string(rf.materials.size()) + ") (or -1 for a wall)");
    return static_cast<std::uint32_t>(k);
  };

  // ---- initial conditions per element (later lines override earlier ones)
  std::map<std::int64_t, Vec2> v0;
  std::map<std::int64_t, double> w0, temp0;
  std::map<std::int64_t, double> wall_temp0;
  std::set<std::int64_t> particle_ids, wall_ids;
  for (const auto& p : rf.particles)
    if (!particle_ids.insert(p.id).second)
      fail(p.where, "particle id", std::to_string(p.id), "an id not used before");
  for (const auto& w : rf.walls)
    if (!wall_ids.insert(w.id).second)
      fail(w.where, "wall id", std::to_string(w.id), "an id not used before");
  auto check_ids = [&](const Ids& t, const std::string& where) {
    for (const auto id : t.particles)
      if (!particle_ids.count(id))
        fail(where, "particle id", std::to_string(id), "ids of 'particle' lines");
    for (const auto id : t.walls)
      if (!wall_ids.count(id)) fail(where, "wall id", std::to_string(id), "ids of 'wall' lines");
  };
  for (const auto& c : rf.initials) {
    check_ids(c.targets, c.where);
    for (const auto id : c.targets.particles) {
      if (c.kind == "velocity")
        v0[id] = Vec2(c.values[0], c.values[1]);
      else if (c.kind == "omega")
        w0[id] = c.values[0];
      else
        temp0[id] = c.values[0];
    }
    for (const auto id : c.targets.walls)
      wall_temp0[id] = c.values[0];
  }
  for (const auto& c : rf.conditions)
    check_ids(c.targets, c.where);

  // ---- particles (grain's ids are DEMLab's ids)
  for (const auto& p : rf.particles) {
    ParticleSpec<2> s;
    s.id = p.id;
    s.position = Vec2(p.x, p.y);
    s.radius = p.radius;
    s.material = material_index(p.material, p.where);
    if (v0.count(p.id)) s.velocity = v0[p.id];
    if (w0.count(p.id)) s.omega = w0[p.id];
    if constexpr (Sim::thermal) s.temperature = temp0.count(p.id) ? temp0[p.id] : 0.0;
    sim.add_particle(s);
    sim.particles().orientation[sim.index_of(p.id)] = p.orientation;
  }

  // ---- walls (with DEMLab's wall temperatures)
  std::map<std::int64_t, std::uint32_t> wall_index;
  std::vector<std::string> cold;
  for (const auto& w : rf.walls) {
    WallOptions<2> o;
    o.name = "wall " + std::to_string(w.id);
    o.material = w.material < 0 ? rigid_material() : material_index(w.material, w.where);
    if (rf.heated() && w.material >= 0) {
      std::vector<TimeFunction> fixed;
      for (const auto& c : rf.conditions)
        if (c.kind == "fix_temperature" &&
            std::count(c.targets.walls.begin(), c.targets.walls.end(), w.id))
          fixed.push_back(component(c, 0));
      const bool given = wall_temp0.count(w.id) > 0;
      if (!given && fixed.empty()) cold.push_back(std::to_string(w.id));
      o.temperature = wall_temperature(given ? wall_temp0[w.id] : 0.0, std::move(fixed));
    }
    const auto& x = w.coords;
    wall_index[w.id] = w.circle
                           ? sim.add_wall(walls::Circle{Vec2(x[0], x[1]), x[2]}, o)
                           : sim.add_wall(walls::Segment{Vec2(x[0], x[1]), Vec2(x[2], x[3])}, o);
  }
  if (!cold.empty())
    note("wall " + joined(cold) +
         ": a material and no temperature; held at 0 K as in DEMLab (give it an initial or "
         "fixed temperature)");

  // ---- bounding box and sinks; particles outside at t = 0 leave before the run
  std::set<std::int64_t> removed;
  auto active_at_0 = [](const RegionSpec& r) { return r.t0 <= 0.0 && 0.0 <= r.t1; };
  if (rf.bbox) {
    const auto g = region(*rf.bbox);
    sim.set_bounding_box(g, rf.bbox->t0, rf.bbox->t1);
    if (active_at_0(*rf.bbox))
      for (const auto& p : rf.particles)
        if (!contains(g, Vec2(p.x, p.y))) removed.insert(p.id);
  }
  for (const auto& r : rf.sinks) {
    const auto g = region(r);
    sim.add_sink(g, r.t0, r.t1);
    if (active_at_0(r))
      for (const auto& p : rf.particles)
        if (contains(g, Vec2(p.x, p.y))) removed.insert(p.id);
  }
  for (const auto id : removed)
    sim.remove_particle(id);
  if (!removed.empty())
    note(std::to_string(removed.size()) +
         " particles outside the bounding box or inside a sink at t = 0 were removed");

  // ---- conditions
  int groups = 0;
  auto group = [&](const Ids& t, bool with_walls) {
    std::vector<std::int64_t> ids;
    for (const auto id : t.particles)
      if (!removed.count(id)) ids.push_back(id);
    std::vector<std::uint32_t> ws;
    if (with_walls)
      for (const auto id : t.walls)
        ws.push_back(wall_index.at(id));
    const std::string name = "demlab " + std::to_string(++groups);
    sim.add_group(name, ids, ws);
    return name;
  };
  for (const auto& c : rf.conditions) {
    const bool heat = c.kind == "heat_flux" || c.kind == "heat_rate" || c.kind == "fix_temperature";
    if (heat && !Sim::thermal)
      fail(c.where, "condition", c.kind,
           "a mechanical condition (this program has no thermal state)");
    if (c.kind == "force") {
      sim.prescribe_force(group(c.targets, false),
                          VectorTimeFunction<2>(component(c, 0), component(c, 1)));
    } else if (c.kind == "torque") {
      sim.prescribe_torque(group(c.targets, false), component(c, 0));
    } else if (c.kind == "fix_temperature") {
      if (!c.targets.particles.empty()) {
        Ids t = c.targets;
        t.walls.clear();
        if constexpr (Sim::thermal) sim.fix_temperature(group(t, false), component(c, 0));
      }
    } else if (c.kind == "heat_flux" || c.kind == "heat_rate") {
      if constexpr (Sim::thermal) {
        if (c.kind == "heat_flux")
          sim.prescribe_heat_flux(group(c.targets, false), component(c, 0));
        else
          sim.prescribe_heat_rate(group(c.targets, false), component(c, 0));
      }
    }
  }
  // fixed velocities: the elements under the same set of conditions share one summed function
  for (const std::string kind : {"fix_velocity", "fix_omega"}) {
    std::map<std::pair<char, std::int64_t>, std::vector<std::size_t>> of;
    for (std::size_t k = 0; k < rf.conditions.size(); ++k) {
      const auto& c = rf.conditions[k];
      if (c.kind != kind) continue;
      for (const auto id : c.targets.particles)
        of[{'P', id}].push_back(k);
      for (const auto id : c.targets.walls)
        of[{'W', id}].push_back(k);
    }
    std::map<std::vector<std::size_t>, Ids> sets;
    for (const auto& [element, list] : of)
      (element.first == 'P' ? sets[list].particles : sets[list].walls).push_back(element.second);
    for (const auto& [list, targets] : sets) {
      double t_begin = inf, t_end = -inf;
      std::vector<std::pair<double, double>> spans;
      for (const auto k : list) {
        t_begin = std::min(t_begin, rf.conditions[k].t0);
        t_end = std::max(t_end, rf.conditions[k].t1);
        spans.push_back({rf.conditions[k].t0, rf.conditions[k].t1});
      }
      std::sort(spans.begin(), spans.end());
      double reach = spans.front().second;
      for (const auto& [b, e1] : spans) {
        // (a wall without an active condition stands still in DEMLab too: only particles,
        // which DEMLab sets free there, differ)
        if (b > reach && !targets.particles.empty())
          note(kind + " of " + std::to_string(targets.particles.size()) +
               " particles: the conditions leave a gap (" + text(reach) + ", " + text(b) +
               ") s inside their span; grain holds them at 0 there (DEMLab lets them move "
               "freely)");
        reach = std::max(reach, e1);
      }
      const int n = kind == "fix_velocity" ? 2 : 1;
      std::array<TimeFunction, 2> f;
      for (int d = 0; d < n; ++d) {
        if (list.size() == 1) {
          f[static_cast<std::size_t>(d)] = component(rf.conditions[list[0]], d);
        } else {
          std::vector<TimeFunction> parts;
          for (const auto k : list)
            parts.push_back(component(rf.conditions[k], d));
          f[static_cast<std::size_t>(d)] = sum_of(std::move(parts), t_begin, t_end);
        }
      }
      const std::string g = group(targets, true);
      if (n == 2)
        sim.fix_velocity(g, VectorTimeFunction<2>(f[0], f[1]));
      else
        sim.fix_omega(g, f[0]);
    }
  }

  // ---- convection targets (grain's convection acts on every particle)
  if (const ParamLine* cp = rf.param("convection.particles")) {
    std::set<std::int64_t> targets(cp->ids.begin(), cp->ids.end());
    for (const auto& p : rf.particles)
      if (!targets.count(p.id))
        fail(cp->where, "param convection.particles", cp->value,
             "every particle (grain applies one convection model to all particles; particle " +
                 std::to_string(p.id) + " is not listed)");
  }

  // ---- records
  std::vector<Column> columns;
  std::string header = "time,step";
  for (const auto& r : rf.records) {
    const auto& names = r.global ? global_quantities() : particle_quantities();
    const auto it = std::find(names.begin(), names.end(), r.quantity);
    if (it == names.end())
      fail(r.where, std::string("record ") + (r.global ? "global" : "particle"), r.quantity,
           joined(names));
    Column c{r.global, static_cast<int>(it - names.begin()), r.id};
    const bool thermal_q = r.global ? c.quantity >= 12 : c.quantity >= 17;
    if (thermal_q && !Sim::thermal)
      fail(r.where, std::string("record ") + (r.global ? "global" : "particle"), r.quantity,
           "a mechanical quantity (this program has no thermal state)");
    if (!r.global && !particle_ids.count(r.id))
      fail(r.where, "record particle id", std::to_string(r.id), "ids of 'particle' lines");
    columns.push_back(c);
    header += "," + r.quantity + (r.global ? "" : ":" + std::to_string(r.id));
  }
  std::filesystem::create_directories(out);
  Results<Sim> results{columns, std::make_shared<grain::io::detail::LineFile>(
                                    "grain-demlab results", out + "/results.csv")};
  results.file->write(header + "\n");
  if (rf.print && !rf.print_results.empty()) {
    auto& pos = results.pos;
    pos.on = true;
    pos.single = rf.print_single;
    pos.prefix = out + "/" + rf.name;
    for (const auto& r : rf.print_results) {
      const bool thermal_r = r == "temperature";
      const bool mech_r = r == "velocity" || r == "acceleration";
      // DEMLab prints what the analysis has (a warning for the rest)
      if ((thermal_r && !rf.heated()) || (mech_r && !rf.mechanical()))
        note("Print result " + r + " is not available in a " + rf.analysis +
             " analysis: not printed");
      else
        pos.results.push_back(r);
    }
    for (const auto& [id, k] : wall_index)
      pos.walls.push_back({id, k});
    if (pos.single)
      pos.file =
          std::make_shared<grain::io::detail::LineFile>("grain-demlab print", pos.prefix + ".pos");
  }

  // ---- notes on the models
  if constexpr (Sim::thermal)
    if (rf.heated() && std::is_same_v<typename C::area_model, area::None>)
      note("contact radius a = sqrt(R* delta) (grain's Hertz radius, area::None); DEMLab's "
           "uncorrected radius is the lens half-chord, about sqrt(2 R* delta) (area::Geometric)");
  if constexpr (is_linear<typename C::normal_model>::value ||
                is_walton_braun<typename C::normal_model>::value)
    if (rf.mechanical() && !rf.has("normal.stiff_coeff") &&
        !impact_policy<typename C::normal_model>::type::per_contact)
      note(std::string(C::normal_model::object) +
           " without stiff_coeff: the Hertz-equivalent stiffness of every contact is taken at "
           "the reference velocity 1 m/s (DEMLab: at each contact's impact velocity, the "
           "...PerContact model)");

  // ---- time step
  if (rf.time_step > 0.0) {
    bool refused = false;
    try {
      sim.initialize();
    } catch (const InputError& err) {
      if (std::string(err.what()).rfind("Simulation: time_step = ", 0) != 0) throw;
      refused = true;
    }
    if (refused) {
      const double mech = sim.forces_move() ? sim.mechanical_time_step() : inf;
      const double cond = sim.heats() ? sim.conduction_time_step() : inf;
      double dt = 0.0;
      std::string limit;
      if (mech <= cond) {
        // grain's automatic step: a fraction of the limit, as for a project without time_step
        // (a step at the limit itself is only marginally stable)
        sim.set_time_step(0.0);
        sim.initialize();
        dt = sim.time_step();
        limit = text(mech) + " s (" +
                (mech == sim.rayleigh_time() ? std::string("the Rayleigh time")
                                             : std::string("the contact limit 2 sqrt(m*/k)")) +
                "); running at grain's automatic step " + text(dt) + " s";
      } else {
        // half the conduction limit 2 / lambda_max: the stiffest mode of the conduction
        // network decays without oscillating (forward Euler's factor 1 - lambda dt >= 0)
        dt = 0.5 * cond;
        limit = text(cond) + " s (the conduction limit 2 / lambda_max); running at half of it, " +
                text(dt) + " s";
      }
      note("time_step " + text(rf.time_step) + " s is above grain's stable limit " + limit);
      sim.set_time_step(dt);
    }
  }
  sim.initialize();
  if (rf.time_step == 0.0)
    note("time_step 0 (automatic): grain's automatic step " + text(sim.time_step()) +
         " s (DEMLab's auto_time_step uses other estimates)");

  std::printf("grain-demlab: %s: %s analysis, %zu particles, %zu walls, %zu materials, "
              "final time %.6g s, time step %.6g s, %ld outputs\n",
              rf.name.c_str(), rf.analysis.c_str(), sim.size(), sim.walls().size(),
              rf.materials.size(), rf.final_time, sim.time_step(), rf.output_count);
  std::fflush(stdout);

  // ---- run
  const double every = rf.final_time / static_cast<double>(rf.output_count);
  const Progress progress{rf.final_time};
  auto progress_every =
      grain::io::every(rf.final_time * std::min(rf.progress, 100.0) / 100.0, progress);
  auto capture = [&results](const Sim& s) { results.capture(s); };
  auto fill = [&results](const Sim& s) { results.fill(s); };
  // fill before capture: with an output at every step, a row is completed before the next one
  // is captured
  if (rf.vtk) {
    std::filesystem::create_directories(out + "/vtk");
    sim.run(rf.final_time, grain::io::summary(), progress_every, fill,
            grain::io::every(every, capture, grain::io::vtk(out + "/vtk/" + rf.name)));
  } else {
    sim.run(rf.final_time, grain::io::summary(), progress_every, fill,
            grain::io::every(every, capture));
  }
  // the rates of the last row: one more evaluation, from the final state (not written)
  if (results.due()) {
    sim.step();
    results.fill(sim);
  }
  std::printf("grain-demlab: wrote %s/results.csv%s\n", out.c_str(),
              rf.vtk ? (" and the VTK series " + out + "/vtk/" + rf.name + "_*").c_str() : "");
  return 0;
}

} // namespace detail

/// Runs a DEMLab run file with the models of `Sim`: `program RUNFILE OUTPUT_FOLDER`. Returns 0,
/// or prints the error on stderr and returns 1.
template <class Sim>
int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: %s RUNFILE OUTPUT_FOLDER\n", argc > 0 ? argv[0] : "program");
    return 1;
  }
  try {
    return detail::run<Sim>(argv[1], argv[2]);
  } catch (const std::exception& e) {
    std::string message = e.what();
    if (message.rfind("grain-demlab: ", 0) == 0) message.erase(0, 14);
    std::fprintf(stderr, "grain-demlab: error: %s\n", message.c_str());
    return 1;
  }
}

} // namespace grain::demlab
