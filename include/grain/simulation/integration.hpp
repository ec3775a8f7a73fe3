#pragma once
/// \file integration.hpp
/// The integration of a Simulation: the integrator's two stages per particle, prescribed motion
/// and restraints around them, wall motion, and the fused velocity-Verlet pass that ends one step
/// and starts the next in one sweep over the particles (the second half kick may be deferred to
/// it: `fuse_kick`, `settle_kick`).
///
/// A component of `Simulation` (simulation.hpp): static functions over the simulation's state,
/// which declares it a friend.

#include <grain/core/config.hpp>
#include <grain/core/vector.hpp>
#include <grain/integrate/integrators.hpp>
#include <grain/simulation/components.hpp>
#include <grain/simulation/parallel.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

namespace grain::detail {

template <class Sim>
struct Motion {
  using Contact = typename Sim::contact_type;
  using V = typename Sim::V;
  using A = typename Sim::A;
  using History = typename Sim::History;
  static constexpr int D = Sim::D;
  static constexpr bool thermal = Sim::thermal;
  static constexpr long parallel_threshold = Sim::parallel_threshold;
  using IntegratorT = typename Sim::IntegratorT;
  static constexpr bool predicts_velocity = Sim::predicts_velocity;
  static constexpr bool no_stages = Sim::no_stages;
  static constexpr bool stages_move = Sim::stages_move;
  using Heat = HeatStep<Sim>;

  // ---------------------------------------------------------------- integration
  /// The integrator's first stage for particle i: velocity and position, angular velocity and
  /// (if `orient`) orientation.
  GRAIN_INLINE static void before_one(Sim& s, std::size_t i, double dt, bool spins, bool orient) {
    auto& p = s.particles_;
    const V a = p.force[i] * p.inv_mass[i];
    IntegratorT::before(p.velocity[i], a, dt,
                        [&](const V& u, double h) { p.position[i] += u * h; });
    if (Contact::has_torque || spins) { // folded at compile time for torque-making contacts
      const A al = p.torque[i] * p.inv_inertia[i];
      IntegratorT::before(p.omega[i], al, dt, [&](const A& u, double h) {
        if (orient) rotate(p.orientation[i], u, h);
      });
    } else if (orient) {
      rotate(p.orientation[i], p.omega[i], dt);
    }
  }
  static void integrate_before(Sim& s, double dt) {
    auto& p = s.particles_;
    const long n = static_cast<long>(p.size());
    const bool control = s.cond_.any_control();
    if constexpr (IntegratorT::drift_before_forces) {
      if (!control && !s.mass_damping_ && !stages_move) {
        fused_before(s, dt);
        return;
      }
    }
    settle_kick(s);
    if (control) s.cond_.save(p, s.time_, dt);
    const bool spins = s.spins_();
    const bool orient = s.params_.track_orientation;
#pragma omp parallel for schedule(static) if (n >= parallel_threshold)
    for (long i = 0; i < n; ++i) {
      before_one(s, static_cast<std::size_t>(i), dt, spins, orient);
    }
    if (control) s.cond_.drift(p, s.time_, dt, true, rotator());
  }
  static void integrate_after(Sim& s, double dt) {
    auto& p = s.particles_;
    const long n = static_cast<long>(p.size());
    const bool control = s.cond_.any_control();
    if constexpr (!IntegratorT::drift_before_forces)
      if (control) s.cond_.save(p, s.time_, dt);
    const bool spins = s.spins_();
    const bool orient = s.params_.track_orientation;
#pragma omp parallel for schedule(static) if (n >= parallel_threshold)
    for (long i = 0; i < n; ++i) {
      const V a = p.force[i] * p.inv_mass[i];
      IntegratorT::after(p.velocity[i], a, dt,
                         [&](const V& u, double h) { p.position[i] += u * h; });
      if (Contact::has_torque || spins) { // folded at compile time for torque-making contacts
        const A al = p.torque[i] * p.inv_inertia[i];
        IntegratorT::after(p.omega[i], al, dt, [&](const A& u, double h) {
          if (orient) rotate(p.orientation[i], u, h);
        });
      } else if (!IntegratorT::drift_before_forces && orient) {
        rotate(p.orientation[i], p.omega[i], dt);
      }
    }
    if (control) {
      if constexpr (IntegratorT::drift_before_forces)
        s.cond_.finish(p, s.time_, dt);
      else
        s.cond_.drift(p, s.time_, dt, false, rotator());
    }
  }
  /// The second half kick of velocity Verlet for particle i (what integrate_after does for it
  /// when no particle is controlled).
  GRAIN_INLINE static void after_one(Sim& s, std::size_t i, double dt, bool spins) {
    auto& p = s.particles_;
    const V a = p.force[i] * p.inv_mass[i];
    IntegratorT::after(p.velocity[i], a, dt, [](const V&, double) {});
    if (Contact::has_torque || spins) {
      const A al = p.torque[i] * p.inv_inertia[i];
      IntegratorT::after(p.omega[i], al, dt, [](const A&, double) {});
    }
  }
  /// True if the second half kick of this step may be left to the next step's fused pass: the
  /// fused pass runs (velocity Verlet, no controlled particle, no mass damping), and nothing
  /// between the two reads or changes velocities or forces (no stage, no variable property, no
  /// particle created or removed).
  static bool fuse_kick(const Sim& s) {
    if constexpr (IntegratorT::drift_before_forces && no_stages)
      return !s.cond_.any_control() && !s.mass_damping_ && s.vprops_.empty() && !s.lifecycle_due();
    else
      return false;
  }
  /// Applies a temperature update and a half kick left pending (a run interrupted by an
  /// exception, a re-initialisation, a step that cannot use the fused pass).
  static void settle_kick(Sim& s) {
    if (s.kick_pending_) {
      s.kick_pending_ = false;
      const bool spins = s.spins_();
      for (std::size_t i = 0; i < s.particles_.size(); ++i)
        after_one(s, i, s.dt_, spins);
    }
    if (s.heat_pending_) {
      s.heat_pending_ = false;
      Heat::integrate_temperature(s, s.dt_);
    }
  }
  /// Velocity Verlet without controlled particles or mass damping: one pass over the particles
  /// ends step n (when its second half kick was left pending) and starts step n+1. Per particle:
  /// the half kick and the drift, the displacement
  /// since the last neighbour-list build, the velocities the forces will see (v(n+1/2) +
  /// a(n) dt/2), and the force arrays started with gravity and global damping (heat rates with
  /// zero). `compute_forces` and `update_neighbors` then skip their own passes over the particles.
  static void fused_before(Sim& s, double dt) {
    auto& p = s.particles_;
    const long n = static_cast<long>(p.size());
    const bool spins = s.spins_();
    const bool orient = s.params_.track_orientation;
    if constexpr (predicts_velocity) {
      s.vf_.resize(p.size());
      if constexpr (Contact::has_torque) s.wf_.resize(p.size());
    }
    const auto loads = s.global_loads(s.time_ + dt);
    const V g = std::get<0>(loads);
    const double ct = std::get<1>(loads), cr = std::get<2>(loads);
    const bool check = s.skin_ > 0.0 && s.snapshot_.size() == p.size();
    const bool kick = s.kick_pending_;
    s.kick_pending_ = false;
    const Fused f{dt, g, ct, cr, ct != 0.0 || cr != 0.0, spins, orient, s.heat_pending_};
    s.heat_pending_ = false;
    // the two flags that change between steps select a loop compiled for them
    const double d2 =
        kick ? (check ? fused_pass<true, true>(s, n, f) : fused_pass<true, false>(s, n, f))
             : (check ? fused_pass<false, true>(s, n, f) : fused_pass<false, false>(s, n, f));
    // an infinite value: a position or temperature that is not finite (or a displacement too
    // large to square, which the rebuild it forces handles)
    if (d2 == std::numeric_limits<double>::infinity()) s.require_finite_state();
    s.fused_d2_ = check ? d2 : -1.0;
    s.prefilled_ = true;
  }

  /// What the fused pass needs per step.
  struct Fused {
    double dt;
    V g;           ///< gravity at the end of the step [m/s^2]
    double ct, cr; ///< global damping [N s/m], [N m s]
    bool damped;   ///< ct or cr is not 0 (else the loads start with the weight alone)
    bool spins, orient;
    bool heat; ///< the last step's temperature update was left to this pass (with its kick)
  };
  /// The fused pass over all n particles, with the last step's second half kick if Kick, and the
  /// displacement since the last neighbour-list build measured if Check (a snapshot exists);
  /// returns the largest squared displacement (0 without Check).
  template <bool Kick, bool Check>
  static double fused_pass(Sim& s, long n, const Fused& f) {
    double d2 = 0.0;
    // Each thread runs its share forwards: it ends on the particles its first contact chunks
    // (its last ones: the contact pass runs down) read next, which are then still in the caches
    // (the share is about the one the contact pass works on; at N = 1e6 the particle data do not
    // fit in the caches).
#pragma omp parallel reduction(max : d2) if (n >= parallel_threshold)
    {
      Sim& sim = s; // held by each thread (not read through the team's shared reference)
      const auto [lo, hi] = detail::static_share(n);
      for (long i = lo; i < hi; ++i)
        d2 = std::max(
            d2, detail::nan_as_inf(fused_one<Kick, Check>(sim, static_cast<std::size_t>(i), f)));
    }
    return d2;
  }
  /// The fused pass for particle i (see fused_before); returns its squared displacement since the
  /// last neighbour-list build (0 without Check), or +inf if its temperature is not finite. The
  /// same arithmetic as after_one + before_one and the loads' start, on local copies (each array
  /// read and written once).
  template <bool Kick, bool Check>
  GRAIN_INLINE static double fused_one(Sim& s, std::size_t i, const Fused& f) {
    auto& p = s.particles_;
    const double half_dt = 0.5 * f.dt;
    const double im = p.inv_mass[i];
    const V F = p.force[i];
    V v = p.velocity[i];
    {
      const V a = F * im;
      if constexpr (Kick) IntegratorT::after(v, a, f.dt, [](const V&, double) {});
      V x = p.position[i];
      IntegratorT::before(v, a, f.dt, [&](const V& u, double h) { x += u * h; });
      p.position[i] = x;
      p.velocity[i] = v;
    }
    if (Contact::has_torque || f.spins) { // folded at compile time for torque-making contacts
      const double iI = p.inv_inertia[i];
      const A T = p.torque[i];
      A w = p.omega[i];
      const A al = T * iI;
      if constexpr (Kick) IntegratorT::after(w, al, f.dt, [](const A&, double) {});
      IntegratorT::before(w, al, f.dt, [&](const A& u, double h) {
        if (f.orient) rotate(p.orientation[i], u, h);
      });
      p.omega[i] = w;
      if constexpr (Contact::has_torque) {
        if constexpr (predicts_velocity) {
          const A wp = w + (half_dt * iI) * T;
          s.wf_[i] = wp;
          p.torque[i] = f.damped ? A(-f.cr * wp) : zero<A>();
        } else {
          p.torque[i] = f.damped ? A(-f.cr * w) : zero<A>();
        }
      } else {
        // no contact torque; a prescribed torque still spins the particle, and damping acts on it
        p.torque[i] = A(-f.cr * w);
      }
    } else {
      if (f.orient) rotate(p.orientation[i], p.omega[i], f.dt);
      p.torque[i] = zero<A>();
    }
    if constexpr (predicts_velocity) {
      const V vp = v + (half_dt * im) * F;
      s.vf_[i] = vp;
      p.force[i] = f.damped ? V(p.mass[i] * f.g - f.ct * vp) : V(p.mass[i] * f.g);
    } else {
      p.force[i] = f.damped ? V(p.mass[i] * f.g - f.ct * v) : V(p.mass[i] * f.g);
    }
    if constexpr (thermal) {
      if constexpr (Kick)
        if (f.heat) Heat::temperature_step(s, i, f.dt);
      p.heat_rate[i] = 0.0;
      if (!std::isfinite(p.temperature[i])) return std::numeric_limits<double>::infinity();
    }
    if constexpr (Check)
      return (p.position[i] - s.snapshot_[i]).squaredNorm();
    else
      return 0.0;
  }

  static auto rotator() {
    return [](Orientation<D>& q, const A& w, double h) { rotate(q, w, h); };
  }
  /// Walls move over [t, t + dt] with their velocities at mid-step and end with those at t + dt.
  static void move_walls(Sim& s, double dt) {
    for (auto& w : s.walls_) {
      w.update_motion(s.time_ + 0.5 * dt);
      w.move(dt);
      w.update_motion(s.time_ + dt);
    }
  }
};

} // namespace grain::detail
