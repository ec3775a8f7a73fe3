#pragma once
/// \file variable_property.hpp
/// `VariableProperty`: a particle property that follows a table of an independent variable
/// (the first seed's variable properties), applied to every particle of a group.
///
/// | property | unit | valid values | recomputed with it |
/// |---|---|---|---|
/// | `radius` | m | > 0 | mass (density kept), inertia, volume, weight, m c, list, contacts |
/// | `density` | kg/m^3 | > 0 | mass, inertia, weight, thermal inertia m c |
/// | `heat_capacity` | J/(kg K) | > 0 | thermal inertia m c |
/// | `young` | Pa | > 0 | contact constants (E*, G* with G derived from E and nu) |
/// | `poisson` | - | (-1, 0.5) | contact constants |
/// | `restitution` | - | (0, 1] | contact constants (damping) |
/// | `friction` | - | >= 0 | contact constants (sliding and static friction) |
/// | `rolling_friction` | - | >= 0 | contact constants |
/// | `conductivity` | W/(m K) | >= 0 | contact constants (conductance) |
///
/// | variable | unit |
/// |---|---|
/// | `temperature` | K (thermal simulations) |
/// | `time` | s |
/// | `speed` | m/s, \|v\| of the particle |
///
/// The property is updated every `every` steps while t_begin <= t <= t_end, and at
/// initialisation. One object serves all particles of its group; each particle takes the value
/// at its own variable. Contact constants of the pairs that involve a particle with a variable
/// contact property are computed per contact from the particles' current properties (mixing
/// rules of particles/material.hpp) and cached until the next update or neighbour-list rebuild.
///
/// The automatic time step is chosen before the run from the extreme table values (largest
/// Young's modulus and conductivity, smallest radius, density and heat capacity; the Poisson
/// ratio is taken as the material's); a given time step is checked before the run against the
/// current values. The conduction limit depends on the contacts: it is checked again after each
/// update of a conductivity, heat capacity, density or radius, and a time step above it stops the
/// run with an InputError. A radius change rebuilds the neighbour list at that update.

#include <grain/core/error.hpp>
#include <grain/core/table.hpp>

#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <string>

namespace grain {

/// A property a table may drive.
enum class Property : std::uint8_t {
  radius,
  density,
  heat_capacity,
  young,
  poisson,
  restitution,
  friction,
  rolling_friction,
  conductivity
};

/// The independent variable of a variable property.
enum class Variable : std::uint8_t { temperature, time, speed };

inline const char* property_name(Property p) {
  switch (p) {
  case Property::radius:
    return "radius";
  case Property::density:
    return "density";
  case Property::heat_capacity:
    return "heat_capacity";
  case Property::young:
    return "young";
  case Property::poisson:
    return "poisson";
  case Property::restitution:
    return "restitution";
  case Property::friction:
    return "friction";
  case Property::rolling_friction:
    return "rolling_friction";
  case Property::conductivity:
    return "conductivity";
  }
  return "?";
}

inline const char* variable_name(Variable v) {
  switch (v) {
  case Variable::temperature:
    return "temperature";
  case Variable::time:
    return "time";
  case Variable::speed:
    return "speed";
  }
  return "?";
}

/// True if the property enters the contact constants (mixed per pair).
inline bool is_contact_property(Property p) {
  return p != Property::radius && p != Property::density && p != Property::heat_capacity;
}

/// A property of a group's particles given by a table of an independent variable.
struct VariableProperty {
  std::string group = "all";
  Property property = Property::young;
  Variable variable = Variable::temperature;
  std::shared_ptr<const Table> table; ///< property value (SI unit of the property) vs variable
  long every = 1;                     ///< update frequency [steps], >= 1
  double t_begin = -std::numeric_limits<double>::infinity(); ///< activity interval [s]
  double t_end = std::numeric_limits<double>::infinity();

  VariableProperty() = default;
  VariableProperty(std::string group_name, Property p, Variable v, Table t, long every_steps = 1)
      : group(std::move(group_name)), property(p), variable(v),
        table(std::make_shared<const Table>(std::move(t))), every(every_steps) {}

  bool active(double t) const { return t >= t_begin && t <= t_end; }

  /// Throws InputError naming the property, its table and the offending value.
  void validate() const {
    const std::string obj = std::string("VariableProperty (") + property_name(property) + " vs " +
                            variable_name(variable) + ", group '" + group + "')";
    if (!table) throw InputError(obj + ": table = null is invalid; valid: a Table");
    detail::require_given(*table, obj, "table", "the table of the property against the variable");
    detail::require(every >= 1, obj, "every", every, "[1, inf) steps");
    detail::require(!std::isnan(t_begin) && t_begin < std::numeric_limits<double>::infinity(), obj,
                    "t_begin", t_begin, "[-inf, inf) s");
    detail::require(!std::isnan(t_end) && t_end >= t_begin, obj, "t_end", t_end,
                    "[t_begin, inf] s");
    const auto& y = table->y();
    for (std::size_t k = 0; k < y.size(); ++k) {
      const double v = y[k];
      bool ok = std::isfinite(v);
      const char* range = "";
      switch (property) {
      case Property::radius:
      case Property::density:
      case Property::heat_capacity:
      case Property::young:
        ok = ok && v > 0;
        range = "(0, inf)";
        break;
      case Property::poisson:
        ok = ok && v > -1.0 && v < 0.5;
        range = "(-1, 0.5)";
        break;
      case Property::restitution:
        ok = ok && v > 0.0 && v <= 1.0;
        range = "(0, 1]";
        break;
      case Property::friction:
      case Property::rolling_friction:
      case Property::conductivity:
        ok = ok && v >= 0.0;
        range = "[0, inf)";
        break;
      }
      if (!ok)
        throw InputError(obj + ": " + table->label() + " y[" + std::to_string(k) +
                         "] = " + detail::to_text(v) + " is invalid for " +
                         property_name(property) + "; valid range: " + range);
    }
  }
};

} // namespace grain
