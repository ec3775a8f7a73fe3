#pragma once
/// \file conditions.hpp
/// Groups of particles and walls, and the conditions applied to them: initial, prescribed
/// (summed) and fixed (replacing) conditions, prescribed motion and restraints.
///
/// | condition | on | unit | effect each step |
/// |---|---|---|---|
/// | prescribed force | particles | N | F += f(t) (every active condition adds) |
/// | prescribed torque | particles | N m | T += f(t) |
/// | prescribed heat flux | particles | W/m^2 | Q += q(t) S (S the particle surface) |
/// | prescribed heat rate | particles | W | Q += f(t) |
/// | fixed / prescribed velocity | particles, walls | m/s | v = f(t) while active |
/// | fixed / prescribed angular velocity | particles, walls | rad/s | omega = f(t) while active |
/// | prescribed acceleration | particles | m/s^2 | dv/dt = f(t) while active |
/// | prescribed angular acceleration | particles | rad/s^2 | d omega/dt = f(t) while active |
/// | fixed temperature | particles, walls | K | T = f(t) while active |
/// | restraint | particles | - | no motion along the given directions (linear, angular) |
///
/// A prescribed force, torque, heat flux or heat rate is a function of time by default; given a
/// `Variable` (`temperature`, `speed`) it is a function of that quantity of each particle instead
/// (the first seed's independent variable of a prescribed condition): its value is taken at the
/// particle's own temperature [K] or speed |v| [m/s] at the start of the step's force evaluation,
/// while its activity interval stays in time (a vector function is then active while any of its
/// components is). A heat flux q(T) = h (T_inf - T), for example, is a convective loss.
///
/// Prescribed motion (the kinds "vv", "va", "av", "aa" of a linear and an angular history, each
/// a velocity or an acceleration) overrides the dynamics of the part (linear or angular) it
/// prescribes while its function is active (each component while its own function is active),
/// whatever the integrator: over a step [t, t + dt] a
/// prescribed velocity moves the particle by dt v(t + dt/2) and leaves it with v(t + dt); a
/// prescribed acceleration a gives v += dt a(t + dt/2) and x += dt (v_old + v_new)/2 (exact for a
/// constant or linear velocity history). When several motion conditions cover a particle, the
/// one added last wins (separately for the linear and the angular part). Restraints project the
/// force and the velocity (torque and angular velocity) onto the free directions, so the
/// particle never moves along a restrained direction; prescribed motion overrides restraints.
///
/// Groups hold particle ids, which never change, and wall indices; the reserved group "all"
/// holds every particle (including particles added or activated later) and every wall.

#include <grain/conditions/variable_property.hpp>
#include <grain/core/error.hpp>
#include <grain/core/time_function.hpp>
#include <grain/core/vector.hpp>

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace grain {

/// A named set of particles (by id) and walls (by index).
struct Group {
  std::string name;
  bool everything = false;          ///< every particle (present and future) and every wall
  std::vector<std::int64_t> ids;    ///< particle ids, sorted, unique
  std::vector<std::uint32_t> walls; ///< wall indices, sorted, unique
};

/// How a prescribed motion history is read.
enum class MotionKind : std::uint8_t { velocity, acceleration };

/// The third seed's kind strings: "vv", "va", "av", "aa" = (linear, angular) each a velocity (v)
/// or an acceleration (a).
inline std::pair<MotionKind, MotionKind>
motion_kinds(std::string_view kind, const std::string& obj = "prescribed motion") {
  auto one = [&](char c) { return c == 'v' ? MotionKind::velocity : MotionKind::acceleration; };
  const bool ok =
      kind.size() == 2 && (kind[0] == 'v' || kind[0] == 'a') && (kind[1] == 'v' || kind[1] == 'a');
  if (!ok)
    throw InputError(obj + ": kind = '" + std::string(kind) +
                     "' is invalid; valid values: 'vv', 'va', 'av', 'aa' (linear, angular: "
                     "v = velocity, a = acceleration)");
  return {one(kind[0]), one(kind[1])};
}

namespace detail {

/// Orthonormal basis of the given directions (Gram-Schmidt); each must be finite, non-zero and
/// independent of the previous ones.
template <int N>
inline std::vector<Vec<N>> orthonormal(const std::vector<Vec<N>>& dirs, const std::string& obj,
                                       const char* what) {
  std::vector<Vec<N>> out;
  if (dirs.size() > static_cast<std::size_t>(N))
    throw InputError(obj + ": " + what + " directions = " + std::to_string(dirs.size()) +
                     " is invalid; valid range: [0, " + std::to_string(N) + "] directions");
  for (const auto& d : dirs) {
    const double n = d.norm();
    if (!all_finite(d) || !(n > 0))
      throw InputError(obj + ": " + what + " direction |d| = " + to_text(n) +
                       " is invalid; valid range: (0, inf), finite components");
    Vec<N> u = d / n;
    for (const auto& b : out)
      u -= u.dot(b) * b;
    const double m = u.norm();
    if (!(m > 1e-9))
      throw InputError(obj + ": " + what +
                       " directions are linearly dependent; valid: independent directions");
    out.push_back(u / m);
  }
  return out;
}

template <class T>
inline T project_out(T v, const std::vector<T>& basis) {
  for (const auto& b : basis)
    v -= v.dot(b) * b;
  return v;
}

/// The conditions of a simulation with their groups; `Simulation` owns one and calls it at the
/// points of its loop. Particle indices of the groups are refreshed whenever indices change.
template <int D>
class ConditionSet {
public:
  using V = Vec<D>;
  using A = Angular<D>;
  using VF = VectorTimeFunction<D>;
  using AF = AngularTimeFunction<D>;

  template <class F>
  struct On {
    std::size_t group;
    F f;
    Variable of = Variable::time; ///< the argument of f
  };
  struct LinearMotion {
    std::size_t group;
    VF f;
    MotionKind kind;
  };
  struct AngularMotion {
    std::size_t group;
    AF f;
    MotionKind kind;
  };
  struct RestraintOn {
    std::size_t group;
    std::vector<V> linear;     // orthonormal
    std::vector<Vec3> angular; // orthonormal (3D)
    bool rotation = false;     // 2D: rotation restrained
  };
  /// A particle under motion control or restraint (refreshed with the indices).
  struct Control {
    std::uint32_t i = 0;
    std::int64_t id = -1;          // particle id (the per-step state follows it across a refresh)
    int linear = -1, angular = -1; // motion condition, -1 = none
    std::vector<V> lin;            // restrained linear directions (orthonormal)
    std::vector<Vec3> ang;         // restrained angular directions (3D)
    bool rotation = false;         // 2D rotation restrained
    // per step
    V x0, v0, am;
    A w0, alpha;
    Orientation<D> q0;
    bool lin_on = false, ang_on = false;      // some component prescribed during the step
    std::array<bool, 3> lin_act{}, ang_act{}; // which components (2D angular: the first)
  };

  std::vector<Group> groups{Group{"all", true, {}, {}}};
  std::vector<std::vector<std::uint32_t>> members{{}};
  std::vector<On<VF>> forces;
  std::vector<On<AF>> torques;
  std::vector<On<TimeFunction>> heat_fluxes, heat_rates, temperatures;
  std::vector<LinearMotion> linear_motion;
  std::vector<AngularMotion> angular_motion;
  std::vector<RestraintOn> restraints;
  std::vector<Control> controls;

  bool any_prescribed() const {
    return !forces.empty() || !torques.empty() || !heat_fluxes.empty() || !heat_rates.empty();
  }
  bool any_control() const { return !controls.empty(); }

  std::size_t find(const std::string& name) const {
    for (std::size_t g = 0; g < groups.size(); ++g)
      if (groups[g].name == name) return g;
    std::string known;
    for (const auto& g : groups)
      known += (known.empty() ? "'" : ", '") + g.name + "'";
    throw InputError("group = '" + name + "' is invalid; valid values: " + known +
                     " (groups made by add_group)");
  }

  std::size_t add(Group g) {
    const std::string obj = "Simulation::add_group '" + g.name + "'";
    if (g.name.empty()) throw InputError(obj + ": name = '' is invalid; valid: a non-empty name");
    for (const auto& h : groups)
      if (h.name == g.name)
        throw InputError(obj + ": name = '" + g.name +
                         "' is invalid; valid: a name not used by another group");
    std::sort(g.ids.begin(), g.ids.end());
    g.ids.erase(std::unique(g.ids.begin(), g.ids.end()), g.ids.end());
    std::sort(g.walls.begin(), g.walls.end());
    g.walls.erase(std::unique(g.walls.begin(), g.walls.end()), g.walls.end());
    groups.push_back(std::move(g));
    members.emplace_back();
    return groups.size() - 1;
  }

  /// Recomputes the current indices of every group from the id array, and the controls.
  void refresh(const std::vector<std::int64_t>& id) {
    const std::size_t n = id.size();
    std::vector<std::pair<std::int64_t, std::uint32_t>> order(n);
    for (std::size_t i = 0; i < n; ++i)
      order[i] = {id[i], static_cast<std::uint32_t>(i)};
    std::sort(order.begin(), order.end());
    for (std::size_t g = 0; g < groups.size(); ++g) {
      auto& m = members[g];
      m.clear();
      if (groups[g].everything) {
        m.resize(n);
        for (std::size_t i = 0; i < n; ++i)
          m[i] = static_cast<std::uint32_t>(i);
        continue;
      }
      // merge the sorted ids with the sorted (id, index) pairs
      std::size_t k = 0;
      for (const auto x : groups[g].ids) {
        while (k < n && order[k].first < x)
          ++k;
        if (k < n && order[k].first == x) m.push_back(order[k].second);
      }
      std::sort(m.begin(), m.end());
    }
    build_controls(id);
  }

  /// The argument of a condition that is a function of a particle's quantity (not time).
  template <class P>
  static double argument(const P& p, std::uint32_t i, Variable of) {
    if (of == Variable::speed) return p.velocity[i].norm();
    if constexpr (requires { p.temperature; })
      return p.temperature[i];
    else
      return std::numeric_limits<double>::quiet_NaN(); // refused where the condition is given
  }

  /// Calls add(i, value) for each member i of condition c's group while c is active at t: value
  /// = c.f(t), or with a particle argument (`of`) the function's value at the particle's own
  /// temperature or speed.
  template <class P, class F, class Add>
  void each_value(const On<F>& c, const P& p, double t, Add&& add) const {
    if (!c.f.active(t)) return;
    if (c.of == Variable::time) {
      const auto v = c.f(t);
      for (const auto i : members[c.group])
        add(i, v);
    } else {
      for (const auto i : members[c.group])
        add(i, c.f.value(argument(p, i, c.of)));
    }
  }

  /// Sums the prescribed forces and torques at time t into the force arrays.
  template <class P>
  void add_loads(P& p, double t) const {
    for (const auto& c : forces)
      each_value(c, p, t, [&](std::uint32_t i, const V& f) { p.force[i] += f; });
    for (const auto& c : torques)
      each_value(c, p, t, [&](std::uint32_t i, const A& f) { p.torque[i] += f; });
  }

  /// Sums the prescribed heat fluxes (times the surface of each particle) and heat rates.
  template <class P, class Surface>
  void add_heat(P& p, double t, Surface&& surface) const {
    for (const auto& c : heat_fluxes)
      each_value(c, p, t,
                 [&](std::uint32_t i, double q) { p.heat_rate[i] += q * surface(p.radius[i]); });
    for (const auto& c : heat_rates)
      each_value(c, p, t, [&](std::uint32_t i, double q) { p.heat_rate[i] += q; });
  }

  /// Sets the temperatures fixed at time t (those whose function is active).
  template <class P>
  void fix_temperatures(P& p, double t) const {
    for (const auto& c : temperatures) {
      if (!c.f.active(t)) continue;
      const double v = c.f.value(t);
      if (!(v >= 0.0))
        throw InputError("Simulation::fix_temperature (group '" + groups[c.group].name +
                         "'): T = " + to_text(v) + " K at t = " + to_text(t) +
                         " s is invalid; valid range: [0, inf) K");
      for (const auto i : members[c.group])
        p.temperature[i] = v;
    }
  }

  /// Removes the restrained components of forces and torques.
  template <class P>
  void restrain_loads(P& p) const {
    for (const auto& c : controls) {
      if (!c.lin.empty()) p.force[c.i] = project_out(V(p.force[c.i]), c.lin);
      if constexpr (D == 2) {
        if (c.rotation) p.torque[c.i] = 0.0;
      } else {
        if (!c.ang.empty()) p.torque[c.i] = project_out(Vec3(p.torque[c.i]), c.ang);
      }
    }
  }
  /// Removes the restrained components of the velocities.
  template <class P>
  void restrain_velocities(P& p) const {
    for (const auto& c : controls)
      restrain_velocity(p, c);
  }

  /// Saves the state of the controlled particles before the integrator moves them, and decides
  /// which motion conditions act during the step [t, t + dt].
  template <class P>
  void save(const P& p, double t, double dt) {
    const double tm = t + 0.5 * dt;
    for (auto& c : controls) {
      const auto i = c.i;
      c.x0 = p.position[i];
      c.v0 = p.velocity[i];
      c.w0 = p.omega[i];
      c.q0 = p.orientation[i];
      // each component is prescribed while its own function is active, free otherwise
      c.lin_act = c.linear >= 0
                      ? active_components(linear_motion[static_cast<std::size_t>(c.linear)].f, tm)
                      : std::array<bool, 3>{};
      c.ang_act = c.angular >= 0
                      ? active_components(angular_motion[static_cast<std::size_t>(c.angular)].f, tm)
                      : std::array<bool, 3>{};
      c.lin_on = c.lin_act[0] || c.lin_act[1] || c.lin_act[2];
      c.ang_on = c.ang_act[0] || c.ang_act[1] || c.ang_act[2];
      if (c.lin_on) {
        const auto& m = linear_motion[static_cast<std::size_t>(c.linear)];
        if (m.kind == MotionKind::acceleration) c.am = m.f.value(tm);
      }
      if (c.ang_on) {
        const auto& m = angular_motion[static_cast<std::size_t>(c.angular)];
        if (m.kind == MotionKind::acceleration) c.alpha = value_of(m.f, tm);
      }
    }
  }

  /// After the integrator has moved the particles over [t, t + dt]: replaces the prescribed parts
  /// by the prescribed motion and removes restrained velocity components. `half` = the velocity
  /// kept is the mid-step one (velocity Verlet's first half), else the end-of-step one.
  template <class P, class Rotate>
  void drift(P& p, double t, double dt, bool half, Rotate&& rotate) const {
    const double tm = t + 0.5 * dt, t1 = t + dt;
    for (const auto& c : controls) {
      const auto i = c.i;
      if (c.lin_on) {
        const auto& m = linear_motion[static_cast<std::size_t>(c.linear)];
        V x, v;
        if (m.kind == MotionKind::velocity) {
          const V vm = m.f.value(tm);
          x = c.x0 + dt * vm;
          v = half ? vm : V(m.f.value(t1));
        } else {
          const V v1 = c.v0 + dt * c.am;
          x = c.x0 + (0.5 * dt) * (c.v0 + v1);
          v = half ? V(c.v0 + (0.5 * dt) * c.am) : v1;
        }
        p.position[i] = blend(x, V(p.position[i]), c.lin_act);
        p.velocity[i] = blend(v, V(p.velocity[i]), c.lin_act);
      }
      if (c.ang_on) {
        const auto& m = angular_motion[static_cast<std::size_t>(c.angular)];
        A wm, w1;
        if (m.kind == MotionKind::velocity) {
          wm = value_of(m.f, tm);
          w1 = value_of(m.f, t1);
        } else {
          wm = c.w0 + (0.5 * dt) * c.alpha;
          w1 = c.w0 + dt * c.alpha;
        }
        // free components turn at the rate the integrator gave them
        const A w = blend(wm, A(p.omega[i]), c.ang_act);
        p.orientation[i] = c.q0;
        rotate(p.orientation[i], w, dt);
        p.omega[i] = blend(half ? wm : w1, A(p.omega[i]), c.ang_act);
      }
      restrain_velocity(p, c);
    }
  }

  /// Velocity Verlet's second half: the end-of-step velocities of the prescribed parts.
  template <class P>
  void finish(P& p, double t, double dt) const {
    const double t1 = t + dt;
    for (const auto& c : controls) {
      const auto i = c.i;
      if (c.lin_on) {
        const auto& m = linear_motion[static_cast<std::size_t>(c.linear)];
        const V v = m.kind == MotionKind::velocity ? V(m.f.value(t1)) : V(c.v0 + dt * c.am);
        p.velocity[i] = blend(v, V(p.velocity[i]), c.lin_act);
      }
      if (c.ang_on) {
        const auto& m = angular_motion[static_cast<std::size_t>(c.angular)];
        const A w = m.kind == MotionKind::velocity ? A(value_of(m.f, t1)) : A(c.w0 + dt * c.alpha);
        p.omega[i] = blend(w, A(p.omega[i]), c.ang_act);
      }
      restrain_velocity(p, c);
    }
  }

  /// The velocities the forces of velocity Verlet see at t + dt for the prescribed parts.
  template <class P>
  void predict(const P& p, std::vector<V>& vf, std::vector<A>* wf, double t, double dt) const {
    (void)p;
    for (const auto& c : controls) {
      if (c.lin_on) {
        const auto& m = linear_motion[static_cast<std::size_t>(c.linear)];
        const V v = m.kind == MotionKind::velocity ? V(m.f.value(t + dt)) : V(c.v0 + dt * c.am);
        vf[c.i] = blend(v, V(vf[c.i]), c.lin_act);
      } else if (!c.lin.empty()) {
        vf[c.i] = project_out(V(vf[c.i]), c.lin);
      }
      if (wf) {
        if (c.ang_on) {
          const auto& m = angular_motion[static_cast<std::size_t>(c.angular)];
          const A w =
              m.kind == MotionKind::velocity ? A(value_of(m.f, t + dt)) : A(c.w0 + dt * c.alpha);
          (*wf)[c.i] = blend(w, A((*wf)[c.i]), c.ang_act);
        } else {
          restrain_angular((*wf)[c.i], c);
        }
      }
    }
  }

private:
  static A value_of(const AF& f, double t) { return f.value(t); }

  /// Which components of a motion history are active at t.
  template <int N>
  static std::array<bool, 3> active_components(const VectorTimeFunction<N>& f, double t) {
    std::array<bool, 3> a{};
    for (int k = 0; k < N; ++k)
      a[static_cast<std::size_t>(k)] = f.component_active(k, t);
    return a;
  }
  static std::array<bool, 3> active_components(const TimeFunction& f, double t) {
    return {f.active(t), false, false};
  }
  /// The prescribed value in the active components, the free one in the others.
  template <int N>
  static Vec<N> blend(const Vec<N>& prescribed, const Vec<N>& free, const std::array<bool, 3>& on) {
    Vec<N> v = free;
    for (int k = 0; k < N; ++k)
      if (on[static_cast<std::size_t>(k)]) v[k] = prescribed[k];
    return v;
  }
  static double blend(double prescribed, double free, const std::array<bool, 3>& on) {
    return on[0] ? prescribed : free;
  }

  static void restrain_angular(A& w, const Control& c) {
    if constexpr (D == 2) {
      if (c.rotation) w = 0.0;
    } else {
      if (!c.ang.empty()) w = project_out(Vec3(w), c.ang);
    }
  }

  template <class P>
  static void restrain_velocity(P& p, const Control& c) {
    if (!c.lin_on && !c.lin.empty()) p.velocity[c.i] = project_out(V(p.velocity[c.i]), c.lin);
    if (!c.ang_on) restrain_angular(p.omega[c.i], c);
  }

  void build_controls(const std::vector<std::int64_t>& id) {
    // The per-step state (x0, v0, ..., lin_on, ang_on, lin_act, ang_act, set by save() and used by
    // drift(), predict() and finish()) belongs to the particle, not to its index: velocity Verlet
    // re-sorts the particles at a neighbour-list rebuild between save() and finish(), and the
    // refresh that follows must not drop it, so it is carried over by id.
    std::vector<Control> old = std::move(controls);
    std::sort(old.begin(), old.end(),
              [](const Control& a, const Control& b) { return a.id < b.id; });
    controls.clear();
    if (linear_motion.empty() && angular_motion.empty() && restraints.empty()) return;
    const std::size_t n = id.size();
    std::vector<int> slot(n, -1);
    auto control_of = [&](std::uint32_t i) -> Control& {
      if (slot[i] < 0) {
        slot[i] = static_cast<int>(controls.size());
        controls.emplace_back();
        controls.back().i = i;
      }
      return controls[static_cast<std::size_t>(slot[i])];
    };
    for (std::size_t k = 0; k < linear_motion.size(); ++k)
      for (const auto i : members[linear_motion[k].group])
        control_of(i).linear = static_cast<int>(k);
    for (std::size_t k = 0; k < angular_motion.size(); ++k)
      for (const auto i : members[angular_motion[k].group])
        control_of(i).angular = static_cast<int>(k);
    for (const auto& r : restraints)
      for (const auto i : members[r.group]) {
        Control& c = control_of(i);
        c.lin = merge(c.lin, r.linear);
        if constexpr (D == 3) c.ang = merge(c.ang, r.angular);
        c.rotation = c.rotation || r.rotation;
      }
    std::sort(controls.begin(), controls.end(),
              [](const Control& a, const Control& b) { return a.i < b.i; });
    for (auto& c : controls) {
      c.id = id[c.i];
      const auto it = std::lower_bound(old.begin(), old.end(), c.id,
                                       [](const Control& a, std::int64_t x) { return a.id < x; });
      if (it == old.end() || it->id != c.id) continue;
      c.x0 = it->x0;
      c.v0 = it->v0;
      c.am = it->am;
      c.w0 = it->w0;
      c.alpha = it->alpha;
      c.q0 = it->q0;
      c.lin_on = it->lin_on;
      c.ang_on = it->ang_on;
      c.lin_act = it->lin_act;
      c.ang_act = it->ang_act;
    }
  }

  /// Orthonormal basis of the union of two orthonormal sets (directions already spanned are
  /// dropped).
  template <class T>
  static std::vector<T> merge(std::vector<T> a, const std::vector<T>& b) {
    for (const auto& d : b) {
      T u = project_out(d, a);
      const double m = u.norm();
      if (m > 1e-9) a.push_back(u / m);
    }
    return a;
  }
};

} // namespace detail
} // namespace grain
