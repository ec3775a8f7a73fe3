#pragma once
/// \file csv.hpp
/// Time histories as CSV files: one row per call (use with `io::every(interval, ...)` or
/// `io::every_steps(n, ...)`), a header row first. Each row is formatted whole and written with
/// one write, then flushed (io/atomic_file.hpp, LineFile), so that a run killed at any moment
/// leaves a valid file of whole rows up to the last row written. Values are written with 17
/// significant digits in the "C" locale; a missing value (a particle that is not active, the mean
/// over an empty group) is written `nan` (never an empty cell, so that every cell parses as a
/// number, e.g. with Python's float()). A row that cannot be written (a full disk) throws
/// io::WriteError naming the writer, the file and the reason, and is cut from the file: the file
/// keeps the whole rows before it. A writer's `resume` member continues the file of a run
/// restarted from a checkpoint (see CsvWriter::resume).
///
/// \code
/// sim.run(1.0, io::every(1e-2, io::history("out/global.csv", io::lifecycle_columns()),
///                        io::particle_history("out/probe.csv", {7, 12}, io::position,
///                                             io::velocity, io::temperature),
///                        io::group_history("out/hot.csv", "hot", io::velocity, io::temperature),
///                        io::csv("out/custom.csv",
///                                io::column("x_7 [m]", [](const auto& s) {
///                                  return s.particles().position[s.index_of(7)].x(); }))));
/// \endcode
///
/// `io::history(path, columns...)` writes the global quantities of a simulation (SI units), then
/// the given columns:
///
/// | column | meaning |
/// |---|---|
/// | `time [s]`, `step` | simulated time and step count |
/// | `particles` | number of (active) particles |
/// | `contacts_pp`, `contacts_pw` | touching particle-particle and particle-wall contacts |
/// | `kinetic_energy [J]` | translational + rotational |
/// | `potential_energy [J]` | gravitational, relative to the origin |
/// | `elastic_energy [J]` | stored in the contacts |
/// | `mean_temperature [K]`, `heat_content [J]`, `heat_inflow [W]` | thermal simulations only: mean particle temperature, sum m c T, and the sum of the particles' heat rates (what walls, convection and dissipation bring in; exchanges between particles cancel) |
///
/// `io::csv(path, columns...)` writes `time [s]`, `step` and the given columns. A column is
/// `io::column(name, f)`, f(sim) a number, or one of these ready-made column sets (each costs
/// nothing unless it is used):
///
/// | column set | columns |
/// |---|---|
/// | `io::particle_columns(ids, quantities...)` | per particle and quantity (table below): `x_7 [m]`, `vx_7 [m/s]`, ...; `nan` while the particle is not active (not yet created, or removed) |
/// | `io::group_columns(group, quantities...)` | `count_<group>` (active particles of the group), then the mean of each quantity over them: `mean_vx_<group> [m/s]`, ... (`nan` for an empty group) |
/// | `io::contact_force_columns(which = Contacts::all)` | `normal_force_total [N]`, `normal_force_mean [N]`: sum and mean of the normal force magnitude \|F_n\| over the touching contacts (`Contacts::particles`: particle-particle only, names ending in `_pp`; `Contacts::walls`: particle-wall only, `_pw`); the mean is `nan` without contacts |
/// | `io::heat_flow_columns()` | thermal simulations: `heat_flow_pp [W]`, the heat exchanged between particles, sum over conducting particle pairs of \|H (T_j - T_i)\|; `heat_flow_pw [W]`, the net heat flowing from the walls into the particles, sum of H (T_wall - T_i) (positive when the walls heat); pairs across a gap count for models that conduct across gaps; 0 when temperatures do not advance (mechanical analysis) |
/// | `io::lifecycle_columns()` | `active`, `inactive` (waiting for their creation time), `removed` (so far): the counts of io::statistics |
/// | `io::dissipated_energy_column()` | `dissipated_energy [J]` if the simulation has `dissipated_energy()`, else no column |
///
/// Per-particle quantities (for `particle_columns` and `group_columns`); a vector gives one
/// column per component (x, y in 2D; x, y, z in 3D), an angular quantity one column in 2D (the z
/// component) and three in 3D:
///
/// | quantity | column (particle 7) | unit |
/// |---|---|---|
/// | `io::position` | `x_7`, `y_7`, `z_7` | m |
/// | `io::displacement` | `ux_7`, ... : position minus the position when the writer started (or when the particle first appeared to it, if it was not active then); with periodic boundaries, of the unwrapped position | m |
/// | `io::velocity` | `vx_7`, ... | m/s |
/// | `io::speed` | `speed_7` = \|v\| | m/s |
/// | `io::acceleration` | `ax_7`, ... = F/m, the total force of the last step over the mass (0 for a fixed particle, inv_mass = 0; for a particle under prescribed motion its forces over its mass, not the prescribed acceleration) | m/s^2 |
/// | `io::omega` | 2D `omega_7`; 3D `omegax_7`, ... | rad/s |
/// | `io::force` | `fx_7`, ... : the total force of the last step | N |
/// | `io::torque` | 2D `torque_7`; 3D `torquex_7`, ... | N m |
/// | `io::temperature` | `temperature_7` (thermal simulations only) | K |
/// | `io::heat_rate` | `heat_rate_7`: net heat flow into the particle in the last step (thermal simulations only) | W |
/// | `io::radius`, `io::mass` | `radius_7`, `mass_7` | m, kg |
/// | `io::quantity(name, unit, f)` | `<name>_7 [<unit>]`; f(sim, index) returns a number or a fixed-size Eigen vector (one column per component, name + x, y, z) | yours |
///
/// Asking for `io::temperature` or `io::heat_rate` (or `heat_flow_columns`) in a mechanical
/// simulation stops the compilation with a message (static_assert).
///
/// A column set of your own is any type with `names(sim, std::vector<std::string>&)` and
/// `values(sim, std::vector<double>&)` that append as many names as values (and optionally
/// `start(sim)`, called once before the header is written).

#include <grain/core/error.hpp>
#include <grain/core/vector.hpp>
#include <grain/io/atomic_file.hpp>
#include <grain/io/write_error.hpp>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <locale>
#include <memory>
#include <ostream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <tuple>
#include <type_traits>
#include <unordered_map>
#include <utility>
#include <vector>

namespace grain::io {

/// A CSV column: its header and a function of the simulation that returns its value.
template <class F>
struct Column {
  std::string name;
  F value;
};
template <class F>
Column<F> column(std::string name, F f) {
  return {std::move(name), std::move(f)};
}

namespace detail {

inline constexpr double missing = std::numeric_limits<double>::quiet_NaN();
inline constexpr std::size_t npos = static_cast<std::size_t>(-1);

/// An output column or column set (anything but a path or a stream).
template <class C>
concept column_like = std::is_class_v<C> && !std::convertible_to<C, std::string>;

// The column-set protocol: io::Column is a set of one column.
template <class C, class Sim>
void start_columns(C& c, const Sim& sim) {
  if constexpr (requires { c.start(sim); }) c.start(sim);
}
template <class C, class Sim>
void column_names(const C& c, const Sim& sim, std::vector<std::string>& out) {
  if constexpr (requires { c.names(sim, out); }) {
    c.names(sim, out);
  } else {
    static_assert(
        requires { c.name; }, "grain::io: a column must be io::column(name, f) or a "
                              "column set with names(sim, names) and values(sim, "
                              "values)");
    out.push_back(c.name);
  }
}
template <class C, class Sim>
void column_values(C& c, const Sim& sim, std::vector<double>& out) {
  if constexpr (requires { c.values(sim, out); })
    c.values(sim, out);
  else
    out.push_back(static_cast<double>(c.value(sim)));
}
template <class Tuple, class Sim>
void start_all(Tuple& columns, const Sim& sim) {
  std::apply([&](auto&... c) { (start_columns(c, sim), ...); }, columns);
}
template <class Tuple, class Sim>
void names_of_all(const Tuple& columns, const Sim& sim, std::vector<std::string>& out) {
  std::apply([&](const auto&... c) { (column_names(c, sim, out), ...); }, columns);
}
template <class Tuple, class Sim>
void values_of_all(Tuple& columns, const Sim& sim, std::vector<double>& out) {
  std::apply([&](auto&... c) { (column_values(c, sim, out), ...); }, columns);
}

/// A number as written in a CSV cell ("nan" for any NaN, whatever its sign).
inline void write_number(std::ostream& o, double v) {
  if (std::isnan(v))
    o << "nan";
  else
    o << v;
}

/// A CSV cell: quoted if it holds a comma, a quote or a line break.
inline std::string quoted(const std::string& s) {
  if (s.find_first_of(",\"\n\r") == std::string::npos) return s;
  std::string q = "\"";
  for (char ch : s)
    q += ch == '"' ? std::string("\"\"") : std::string(1, ch);
  return q + "\"";
}

inline std::string with_unit(std::string name, const std::string& unit) {
  if (!unit.empty()) name += " [" + unit + "]";
  return name;
}

// ------------------------------------------------------------ per-particle quantities
/// Number of columns of a value type: 1 for a number, the size of a fixed-size vector.
template <class T>
constexpr int components_of() {
  if constexpr (std::is_arithmetic_v<T>) {
    return 1;
  } else {
    static_assert(
        requires { T::RowsAtCompileTime; } && T::ColsAtCompileTime == 1 && T::RowsAtCompileTime > 0,
        "grain::io::quantity: f(sim, index) must return a number or a fixed-size "
        "Eigen column vector (e.g. grain::Vec<D>)");
    return T::RowsAtCompileTime;
  }
}

/// Appends a number or the components of a vector.
template <class T>
void append_value(const T& v, std::vector<double>& out) {
  if constexpr (std::is_arithmetic_v<T>) {
    out.push_back(static_cast<double>(v));
  } else {
    const Eigen::Matrix<double, T::RowsAtCompileTime, 1> e = v;
    for (int k = 0; k < T::RowsAtCompileTime; ++k)
      out.push_back(e[k]);
  }
}

/// Column bases of a quantity with n components: "v" -> vx, vy, vz; n = 1 -> "v".
inline void component_bases(const std::string& symbol, int n, std::vector<std::string>& out) {
  static constexpr const char* axes[] = {"x", "y", "z"};
  if (n == 1) {
    out.push_back(symbol);
    return;
  }
  for (int k = 0; k < n; ++k)
    out.push_back(symbol + (k < 3 ? axes[k] : std::to_string(k)));
}

template <class Sim>
std::array<double, 3> position_of(const Sim& sim, std::size_t i) {
  std::array<double, 3> a{0.0, 0.0, 0.0};
  for (int d = 0; d < Sim::dimension; ++d)
    a[static_cast<std::size_t>(d)] = sim.unwrapped_position(i)[d]; // periodic: unwrapped
  return a;
}

} // namespace detail

/// The built-in per-particle quantities (see the table in the file comment).
namespace quantities {
struct Position {
  static constexpr const char* symbol = "";
  static constexpr const char* unit = "m";
  static constexpr bool thermal = false;
  template <class Sim>
  static auto get(const Sim& s, std::size_t i) {
    return s.particles().position[i];
  }
};
/// Position minus a reference position kept by the column set.
struct Displacement {
  static constexpr const char* symbol = "u";
  static constexpr const char* unit = "m";
  static constexpr bool thermal = false;
  template <class Sim>
  static auto get(const Sim& s, std::size_t i) {
    return s.particles().position[i];
  }
};
struct Velocity {
  static constexpr const char* symbol = "v";
  static constexpr const char* unit = "m/s";
  static constexpr bool thermal = false;
  template <class Sim>
  static auto get(const Sim& s, std::size_t i) {
    return s.particles().velocity[i];
  }
};
struct Speed {
  static constexpr const char* symbol = "speed";
  static constexpr const char* unit = "m/s";
  static constexpr bool thermal = false;
  template <class Sim>
  static double get(const Sim& s, std::size_t i) {
    return s.particles().velocity[i].norm();
  }
};
struct Acceleration {
  static constexpr const char* symbol = "a";
  static constexpr const char* unit = "m/s^2";
  static constexpr bool thermal = false;
  template <class Sim>
  static auto get(const Sim& s, std::size_t i) {
    return Vec<Sim::dimension>(s.particles().force[i] * s.particles().inv_mass[i]);
  }
};
struct Omega {
  static constexpr const char* symbol = "omega";
  static constexpr const char* unit = "rad/s";
  static constexpr bool thermal = false;
  template <class Sim>
  static auto get(const Sim& s, std::size_t i) {
    return s.particles().omega[i];
  }
};
struct Force {
  static constexpr const char* symbol = "f";
  static constexpr const char* unit = "N";
  static constexpr bool thermal = false;
  template <class Sim>
  static auto get(const Sim& s, std::size_t i) {
    return s.particles().force[i];
  }
};
struct Torque {
  static constexpr const char* symbol = "torque";
  static constexpr const char* unit = "N m";
  static constexpr bool thermal = false;
  template <class Sim>
  static auto get(const Sim& s, std::size_t i) {
    return s.particles().torque[i];
  }
};
struct Temperature {
  static constexpr const char* symbol = "temperature";
  static constexpr const char* unit = "K";
  static constexpr bool thermal = true;
  template <class Sim>
  static double get(const Sim& s, std::size_t i) {
    return s.particles().temperature[i];
  }
};
struct HeatRate {
  static constexpr const char* symbol = "heat_rate";
  static constexpr const char* unit = "W";
  static constexpr bool thermal = true;
  template <class Sim>
  static double get(const Sim& s, std::size_t i) {
    return s.particles().heat_rate[i];
  }
};
struct Radius {
  static constexpr const char* symbol = "radius";
  static constexpr const char* unit = "m";
  static constexpr bool thermal = false;
  template <class Sim>
  static double get(const Sim& s, std::size_t i) {
    return s.particles().radius[i];
  }
};
struct Mass {
  static constexpr const char* symbol = "mass";
  static constexpr const char* unit = "kg";
  static constexpr bool thermal = false;
  template <class Sim>
  static double get(const Sim& s, std::size_t i) {
    return s.particles().mass[i];
  }
};
/// A quantity of your own: f(sim, index) returns a number or a fixed-size Eigen vector.
template <class F>
struct User {
  std::string name;
  std::string unit;
  F f;
};
} // namespace quantities

inline constexpr quantities::Position position{};
inline constexpr quantities::Displacement displacement{};
inline constexpr quantities::Velocity velocity{};
inline constexpr quantities::Speed speed{};
inline constexpr quantities::Acceleration acceleration{};
inline constexpr quantities::Omega omega{};
inline constexpr quantities::Force force{};
inline constexpr quantities::Torque torque{};
inline constexpr quantities::Temperature temperature{};
inline constexpr quantities::HeatRate heat_rate{};
inline constexpr quantities::Radius radius{};
inline constexpr quantities::Mass mass{};

/// quantity(name, unit, f): a per-particle quantity of your own, f(sim, index) a number or a
/// fixed-size Eigen vector; `unit` may be empty.
template <class F>
quantities::User<F> quantity(std::string name, std::string unit, F f) {
  if (name.empty())
    throw InputError("grain::io::quantity: name = \"\" is invalid; valid: a non-empty name (it "
                     "heads the columns, e.g. \"speed\" gives speed_7)");
  return {std::move(name), std::move(unit), std::move(f)};
}

namespace detail {

template <class Q>
struct is_user_quantity : std::false_type {};
template <class F>
struct is_user_quantity<quantities::User<F>> : std::true_type {};

template <class Q>
concept particle_quantity = is_user_quantity<Q>::value || requires {
  Q::symbol;
  Q::unit;
  Q::thermal;
};

template <class Q>
constexpr bool is_displacement = std::is_same_v<Q, quantities::Displacement>;

/// True for a quantity this simulation has (false: check_quantity stops the compilation).
template <class Q, class Sim>
constexpr bool quantity_ok() {
  if constexpr (is_user_quantity<Q>::value)
    return true;
  else if constexpr (!particle_quantity<Q>)
    return false;
  else
    return !Q::thermal || Sim::thermal;
}

template <class Q, class Sim>
constexpr void check_quantity() {
  static_assert(particle_quantity<Q>,
                "grain::io: a per-particle quantity must be io::position, io::displacement, "
                "io::velocity, io::speed, io::acceleration, io::omega, io::force, io::torque, "
                "io::temperature, io::heat_rate, io::radius, io::mass or io::quantity(name, "
                "unit, f)");
  if constexpr (particle_quantity<Q> && !is_user_quantity<Q>::value)
    static_assert(!Q::thermal || Sim::thermal,
                  "grain::io: io::temperature and io::heat_rate need a thermal simulation: give "
                  "the Interaction a conduction model (e.g. conduction::BatchelorOBrien), or "
                  "leave these quantities out of particle_columns / group_columns");
}

/// The value of quantity q for particle i (displacement: relative to `ref`).
template <class Q, class Sim>
auto quantity_value(const Q& q, const Sim& sim, std::size_t i, const std::array<double, 3>& ref) {
  if constexpr (!quantity_ok<Q, Sim>()) {
    return 0.0; // after the static_assert of check_quantity: no further errors
  } else if constexpr (is_user_quantity<Q>::value) {
    return q.f(sim, i);
  } else if constexpr (is_displacement<Q>) {
    Vec<Sim::dimension> u = sim.unwrapped_position(i); // periodic: the true displacement
    for (int d = 0; d < Sim::dimension; ++d)
      u[d] -= ref[static_cast<std::size_t>(d)];
    return u;
  } else {
    return Q::get(sim, i);
  }
}

template <class Q, class Sim>
constexpr int quantity_components() {
  check_quantity<Q, Sim>();
  using T = std::decay_t<decltype(quantity_value(std::declval<const Q&>(),
                                                 std::declval<const Sim&>(), std::size_t{},
                                                 std::declval<const std::array<double, 3>&>()))>;
  return components_of<T>();
}

template <class Q>
std::string quantity_symbol(const Q& q) {
  if constexpr (is_user_quantity<Q>::value)
    return q.name;
  else if constexpr (particle_quantity<Q>)
    return Q::symbol;
  else
    return "?";
}
template <class Q>
std::string quantity_unit(const Q& q) {
  if constexpr (is_user_quantity<Q>::value)
    return q.unit;
  else if constexpr (particle_quantity<Q>)
    return Q::unit;
  else
    return "";
}

/// Appends the column bases of quantity q ("vx", "vy", ...).
template <class Q, class Sim>
void quantity_bases(const Q& q, std::vector<std::string>& out) {
  component_bases(quantity_symbol(q), quantity_components<Q, Sim>(), out);
}

template <class... Qs>
constexpr bool any_displacement = (is_displacement<Qs> || ...);

} // namespace detail

/// The columns of `particle_columns`: chosen quantities of chosen particles (by id).
template <class... Qs>
struct ParticleColumns {
  std::vector<std::int64_t> ids;
  std::tuple<Qs...> quantities;
  // state: the last known index of each id, and the reference positions of `displacement`
  std::vector<std::size_t> index_{};
  std::vector<std::size_t> current_{};
  std::vector<std::pair<std::int64_t, std::size_t>> sorted_{};
  std::vector<std::array<double, 3>> reference_{};
  std::vector<char> has_reference_{};

  template <class Sim>
  void start(const Sim& sim) {
    (detail::check_quantity<Qs, Sim>(), ...);
    const auto& removed = sim.removed_ids();
    for (const auto id : ids) {
      // a waiting particle (creation time ahead) cannot be told apart from an unknown id
      const bool known = sim.is_active(id) || sim.inactive_count() > 0 ||
                         std::find(removed.begin(), removed.end(), id) != removed.end();
      if (!known)
        throw InputError("grain::io::particle_columns: id = " + std::to_string(id) +
                         " is invalid; valid: ids of added particles (active, waiting for their "
                         "creation time or removed)");
    }
    index_.assign(ids.size(), detail::npos);
    current_.assign(ids.size(), detail::npos);
    reference_.assign(ids.size(), {0.0, 0.0, 0.0});
    has_reference_.assign(ids.size(), 0);
    sorted_.clear();
    for (std::size_t k = 0; k < ids.size(); ++k)
      sorted_.push_back({ids[k], k});
    std::sort(sorted_.begin(), sorted_.end());
    locate(sim);
    if constexpr (detail::any_displacement<Qs...>)
      for (std::size_t k = 0; k < ids.size(); ++k)
        if (current_[k] != detail::npos) {
          reference_[k] = detail::position_of(sim, current_[k]);
          has_reference_[k] = 1;
        }
  }

  template <class Sim>
  void names(const Sim& sim, std::vector<std::string>& out) const {
    (void)sim;
    std::vector<std::string> bases;
    for (const auto id : ids) {
      std::apply(
          [&](const auto&... q) {
            auto one = [&](const auto& qq) {
              using Q = std::decay_t<decltype(qq)>;
              bases.clear();
              detail::quantity_bases<Q, Sim>(qq, bases);
              for (const auto& b : bases)
                out.push_back(
                    detail::with_unit(b + "_" + std::to_string(id), detail::quantity_unit(qq)));
            };
            (one(q), ...);
          },
          quantities);
    }
  }

  template <class Sim>
  void values(const Sim& sim, std::vector<double>& out) {
    if (index_.size() != ids.size()) start(sim);
    locate(sim);
    for (std::size_t k = 0; k < ids.size(); ++k) {
      const std::size_t i = current_[k];
      if (i != detail::npos) {
        if constexpr (detail::any_displacement<Qs...>) {
          if (!has_reference_[k]) { // first seen now: its displacement starts here
            reference_[k] = detail::position_of(sim, i);
            has_reference_[k] = 1;
          }
        }
      }
      std::apply(
          [&](const auto&... q) {
            auto one = [&](const auto& qq) {
              using Q = std::decay_t<decltype(qq)>;
              if (i == detail::npos) {
                out.insert(out.end(),
                           static_cast<std::size_t>(detail::quantity_components<Q, Sim>()),
                           detail::missing);
              } else {
                detail::append_value(detail::quantity_value(qq, sim, i, reference_[k]), out);
              }
            };
            (one(q), ...);
          },
          quantities);
    }
  }

private:
  /// Current index of each id (npos if not active): the cached index if it still holds the id,
  /// otherwise one pass over the particles.
  template <class Sim>
  void locate(const Sim& sim) {
    const auto& pid = sim.particles().id;
    const std::size_t n = pid.size();
    bool miss = false;
    for (std::size_t k = 0; k < ids.size(); ++k) {
      const std::size_t i = index_[k];
      current_[k] = i < n && pid[i] == ids[k] ? i : detail::npos;
      miss = miss || current_[k] == detail::npos;
    }
    if (!miss) return;
    for (std::size_t i = 0; i < n; ++i) {
      const auto it = std::lower_bound(sorted_.begin(), sorted_.end(),
                                       std::pair<std::int64_t, std::size_t>{pid[i], 0});
      if (it != sorted_.end() && it->first == pid[i]) current_[it->second] = i;
    }
    index_ = current_;
  }
};

/// particle_columns(ids, quantities...): the quantities (io::position, io::velocity, ...,
/// io::quantity(name, unit, f)) of the particles with these ids, one column per component:
/// x_7 [m], y_7 [m], vx_7 [m/s], ... (`nan` while a particle is not active).
template <class... Qs>
ParticleColumns<Qs...> particle_columns(std::vector<std::int64_t> ids, Qs... quantities) {
  static_assert(sizeof...(Qs) > 0, "grain::io::particle_columns: give at least one quantity, "
                                   "e.g. particle_columns({7}, io::position, io::velocity)");
  if (ids.empty())
    throw InputError("grain::io::particle_columns: ids = {} is invalid; valid: at least one "
                     "particle id");
  std::vector<std::int64_t> sorted = ids;
  std::sort(sorted.begin(), sorted.end());
  const auto twice = std::adjacent_find(sorted.begin(), sorted.end());
  if (twice != sorted.end())
    throw InputError("grain::io::particle_columns: id = " + std::to_string(*twice) +
                     " is given twice; valid: distinct ids");
  return {std::move(ids), {std::move(quantities)...}};
}

/// The columns of `group_columns`: the count of a group's active particles and the means of
/// chosen quantities over them.
template <class... Qs>
struct GroupColumns {
  std::string group;
  std::tuple<Qs...> quantities;
  // state: reference positions of `displacement` (by id), sums of one row
  std::unordered_map<std::int64_t, std::array<double, 3>> reference_{};
  std::vector<double> sums_{}, one_{};
  bool started_ = false;

  template <class Sim>
  void start(const Sim& sim) {
    (detail::check_quantity<Qs, Sim>(), ...);
    (void)sim.group(group); // an unknown group is an InputError that lists the known ones
    started_ = true;
    if constexpr (detail::any_displacement<Qs...>)
      for (const auto i : sim.group_indices(group))
        reference_.emplace(sim.particles().id[i], detail::position_of(sim, i));
  }

  template <class Sim>
  void names(const Sim& sim, std::vector<std::string>& out) const {
    (void)sim;
    out.push_back("count_" + group);
    std::vector<std::string> bases;
    std::apply(
        [&](const auto&... q) {
          auto one = [&](const auto& qq) {
            using Q = std::decay_t<decltype(qq)>;
            bases.clear();
            detail::quantity_bases<Q, Sim>(qq, bases);
            for (const auto& b : bases)
              out.push_back(
                  detail::with_unit("mean_" + b + "_" + group, detail::quantity_unit(qq)));
          };
          (one(q), ...);
        },
        quantities);
  }

  template <class Sim>
  void values(const Sim& sim, std::vector<double>& out) {
    if (!started_) start(sim);
    const auto& members = sim.group_indices(group);
    constexpr std::size_t width =
        (std::size_t{0} + ... + static_cast<std::size_t>(detail::quantity_components<Qs, Sim>()));
    sums_.assign(width, 0.0);
    static constexpr std::array<double, 3> origin{0.0, 0.0, 0.0};
    for (const auto i : members) {
      const std::array<double, 3>* ref = &origin;
      if constexpr (detail::any_displacement<Qs...>)
        ref = &reference_.try_emplace(sim.particles().id[i], detail::position_of(sim, i))
                   .first->second;
      one_.clear();
      std::apply(
          [&](const auto&... q) {
            (detail::append_value(detail::quantity_value(q, sim, i, *ref), one_), ...);
          },
          quantities);
      for (std::size_t c = 0; c < width; ++c)
        sums_[c] += one_[c];
    }
    const auto n = members.size();
    out.push_back(static_cast<double>(n));
    for (std::size_t c = 0; c < width; ++c)
      out.push_back(n > 0 ? sums_[c] / static_cast<double>(n) : detail::missing);
  }
};

/// group_columns(group, quantities...): count_<group>, the number of the group's active
/// particles, then the mean of each quantity over them: mean_vx_<group> [m/s], ...
template <class... Qs>
GroupColumns<Qs...> group_columns(std::string group, Qs... quantities) {
  static_assert(sizeof...(Qs) > 0, "grain::io::group_columns: give at least one quantity, e.g. "
                                   "group_columns(\"hot\", io::velocity, io::temperature)");
  if (group.empty())
    throw InputError("grain::io::group_columns: group = \"\" is invalid; valid: the name of a "
                     "group (\"all\" or one given to Simulation::add_group)");
  return {std::move(group), {std::move(quantities)...}};
}

/// Which touching contacts `contact_force_columns` sums over.
enum class Contacts { all, particles, walls };

/// The columns of `contact_force_columns`: sum and mean of |F_n| over touching contacts.
struct ContactForceColumns {
  Contacts which = Contacts::all;

  template <class Sim>
  void names(const Sim&, std::vector<std::string>& out) const {
    const std::string s = which == Contacts::all         ? ""
                          : which == Contacts::particles ? "_pp"
                                                         : "_pw";
    out.push_back("normal_force_total" + s + " [N]");
    out.push_back("normal_force_mean" + s + " [N]");
  }
  template <class Sim>
  void values(const Sim& sim, std::vector<double>& out) const {
    double total = 0.0;
    std::size_t count = 0;
    sim.for_each_contact([&](std::size_t, std::size_t, bool wall, const auto&, const auto& r) {
      if ((wall && which == Contacts::particles) || (!wall && which == Contacts::walls)) return;
      total += std::abs(r.normal.force);
      ++count;
    });
    out.push_back(total);
    out.push_back(count > 0 ? total / static_cast<double>(count) : detail::missing);
  }
};
/// contact_force_columns(which = Contacts::all): normal_force_total [N], normal_force_mean [N]
/// over the touching contacts (particle-particle and particle-wall; `_pp` / `_pw` only).
inline ContactForceColumns contact_force_columns(Contacts which = Contacts::all) { return {which}; }

/// The columns of `heat_flow_columns`: heat exchanged between particles, and from the walls.
struct HeatFlowColumns {
  template <class Sim>
  void names(const Sim&, std::vector<std::string>& out) const {
    static_assert(Sim::thermal, "grain::io::heat_flow_columns needs a thermal simulation: give "
                                "the Interaction a conduction model (e.g. "
                                "conduction::BatchelorOBrien), or leave these columns out");
    out.push_back("heat_flow_pp [W]");
    out.push_back("heat_flow_pw [W]");
  }
  template <class Sim>
  void values(const Sim& sim, std::vector<double>& out) const {
    double pp = 0.0, pw = 0.0;
    if constexpr (Sim::thermal) {
      if (sim.heats()) {
        const auto& p = sim.particles();
        sim.for_each_conductance([&](std::size_t i, std::size_t j, bool wall, double H) {
          if (wall)
            pw += H * (sim.walls()[j].temperature - p.temperature[i]);
          else
            pp += std::abs(H * (p.temperature[j] - p.temperature[i]));
        });
      }
    }
    out.push_back(pp);
    out.push_back(pw);
  }
};
/// heat_flow_columns(): heat_flow_pp [W] (sum of |H (T_j - T_i)| over conducting particle
/// pairs) and heat_flow_pw [W] (net heat from the walls into the particles). Thermal only.
inline HeatFlowColumns heat_flow_columns() { return {}; }

/// The columns of `lifecycle_columns`: active, inactive and removed particles.
struct LifecycleColumns {
  template <class Sim>
  void names(const Sim&, std::vector<std::string>& out) const {
    out.insert(out.end(), {"active", "inactive", "removed"});
  }
  template <class Sim>
  void values(const Sim& sim, std::vector<double>& out) const {
    out.push_back(static_cast<double>(sim.size()));
    out.push_back(static_cast<double>(sim.inactive_count()));
    out.push_back(static_cast<double>(sim.removed_ids().size()));
  }
};
/// lifecycle_columns(): active, inactive (waiting for their creation time) and removed (so far)
/// particles.
inline LifecycleColumns lifecycle_columns() { return {}; }

/// The column of `dissipated_energy_column`, present only if the simulation has
/// `dissipated_energy()`.
struct DissipatedEnergyColumn {
  template <class Sim>
  void names(const Sim& sim, std::vector<std::string>& out) const {
    if constexpr (requires { sim.dissipated_energy(); }) out.push_back("dissipated_energy [J]");
  }
  template <class Sim>
  void values(const Sim& sim, std::vector<double>& out) const {
    if constexpr (requires { sim.dissipated_energy(); })
      out.push_back(static_cast<double>(sim.dissipated_energy()));
  }
};
/// dissipated_energy_column(): dissipated_energy [J] if the simulation provides
/// `dissipated_energy()`; no column otherwise.
inline DissipatedEnergyColumn dissipated_energy_column() { return {}; }

namespace detail {

/// The number of bytes at the start of the CSV file `path` that a writer resuming at step `step`
/// keeps: its header, if it is `header`, and the complete rows of the steps before `step` that
/// follow it (0: no such file, or nothing to keep). A file with another header but rows to keep
/// is an InputError.
inline std::uintmax_t resumable_bytes(const std::string& path, const std::string& header,
                                      long step) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return 0;
  std::string head(header.size(), '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<std::size_t>(in.gcount()));
  const bool same = head == header;
  if (!same) { // the first line of the file, to look at its first row
    in.clear();
    in.seekg(0);
    std::getline(in, head);
  }
  // the step of a complete row, the second cell ("time,step,..."); -1 if it is none
  const auto step_of = [](const std::string& row) -> long {
    const auto a = row.find(',');
    if (a == std::string::npos) return -1;
    const auto b = std::min(row.find(',', a + 1), row.size());
    long s = -1;
    const auto [end, err] = std::from_chars(row.data() + a + 1, row.data() + b, s);
    return err == std::errc{} && end == row.data() + b ? s : -1;
  };
  std::uintmax_t keep = same ? header.size() : 0;
  for (std::string row; std::getline(in, row);) {
    if (in.eof()) break; // a last row without its line break is incomplete
    const long s = step_of(row);
    if (s < 0 || s >= step) break;
    if (!same)
      throw InputError("grain::io::csv: resume of '" + path + "': header = '" + head +
                       "' is invalid; valid: '" + header.substr(0, header.size() - 1) +
                       "' (the columns of this writer), or a file without rows before step " +
                       std::to_string(step));
    keep += row.size() + 1;
  }
  return keep;
}

} // namespace detail

/// The writer behind `io::csv` and `io::history`.
template <bool Global, class... Columns>
struct CsvWriter {
  std::string path;
  std::tuple<Columns...> columns;
  /// Continue an existing file (a run restarted from a checkpoint): keep its header and its rows
  /// of the steps before the step at which the writer starts, drop the later ones and append.
  /// Without such rows (or without the file) the file is written anew.
  bool resume = false;
  std::shared_ptr<detail::LineFile> out{}; ///< the file (shared by the copies of the writer)
  std::size_t width = 0;                   ///< number of cells after time and step
  std::vector<double> cells_{};            ///< one row's cells

  template <class Sim>
  void start(const Sim& sim) {
    if (out) return;                 // a later run appends to the same file
    detail::start_all(columns, sim); // may raise InputError: before the file is made
    std::vector<std::string> names{"time [s]", "step"};
    if constexpr (Global) {
      names.insert(names.end(), {"particles", "contacts_pp", "contacts_pw", "kinetic_energy [J]",
                                 "potential_energy [J]", "elastic_energy [J]"});
      if constexpr (Sim::thermal)
        names.insert(names.end(), {"mean_temperature [K]", "heat_content [J]", "heat_inflow [W]"});
    }
    detail::names_of_all(columns, sim, names);
    width = names.size() - 2;
    std::string header;
    for (std::size_t k = 0; k < names.size(); ++k)
      header += (k ? "," : "") + detail::quoted(names[k]);
    header += '\n';
    detail::require_output_folder("grain::io::csv", path);
    const std::uintmax_t keep =
        resume ? detail::resumable_bytes(path, header, sim.step_count()) : 0;
    if (keep > 0) std::filesystem::resize_file(path, keep);
    auto file = std::make_shared<detail::LineFile>("grain::io::csv", path, keep);
    if (keep == 0) file->write(header);
    out = std::move(file);
  }

  template <class Sim>
  void operator()(const Sim& sim) {
    if (!out) start(sim);
    cells_.clear();
    if constexpr (Global) {
      const auto [pp, pw] = sim.contact_counts();
      cells_.insert(cells_.end(), {static_cast<double>(sim.size()), static_cast<double>(pp),
                                   static_cast<double>(pw), sim.kinetic_energy(),
                                   sim.potential_energy(), sim.elastic_energy()});
      if constexpr (Sim::thermal) {
        double inflow = 0.0;
        for (double q : sim.particles().heat_rate)
          inflow += q;
        cells_.insert(cells_.end(), {sim.mean_temperature(), sim.thermal_energy(), inflow});
      }
    }
    detail::values_of_all(columns, sim, cells_);
    if (cells_.size() != width)
      throw std::logic_error("grain::io::csv '" + path + "': the columns gave " +
                             std::to_string(cells_.size()) + " values for " +
                             std::to_string(width) +
                             " names; a column set must give one value per name");
    std::ostringstream row;
    row.imbue(std::locale::classic());
    row.precision(17);
    row << sim.time() << ',' << sim.step_count();
    for (const double v : cells_) {
      row << ',';
      detail::write_number(row, v);
    }
    row << '\n';
    out->write(row.str()); // the whole row with one write, or none of it
  }
};

/// csv(path, columns...): time, step and the given columns, one row per call.
template <class... Columns>
CsvWriter<false, Columns...> csv(std::string path, Columns... columns) {
  return {std::move(path), {std::move(columns)...}};
}

/// history(path, columns...): the global quantities of the simulation (table in the file
/// comment), then the given columns.
template <class... Columns>
CsvWriter<true, Columns...> history(std::string path, Columns... columns) {
  return {std::move(path), {std::move(columns)...}};
}

/// particle_history(path, ids, quantities...): time, step and particle_columns(ids, ...).
template <class... Qs>
CsvWriter<false, ParticleColumns<Qs...>>
particle_history(std::string path, std::vector<std::int64_t> ids, Qs... quantities) {
  return csv(std::move(path), particle_columns(std::move(ids), std::move(quantities)...));
}

/// group_history(path, group, quantities...): time, step and group_columns(group, ...).
template <class... Qs>
CsvWriter<false, GroupColumns<Qs...>> group_history(std::string path, std::string group,
                                                    Qs... quantities) {
  return csv(std::move(path), group_columns(std::move(group), std::move(quantities)...));
}

} // namespace grain::io
