#pragma once
// Measurement of one simulated impact, shared by the impact tests (Hertz, linear spring-dashpot,
// Chung & Ooi). The overlap is computed from the particle positions after every step. The contact
// runs from the zero crossing of the overlap before the first step with overlap > 0 to the one
// after the last such step (linear interpolation between the two samples that bracket each
// crossing). Peaks of the overlap and of the normal force are refined by the parabola through the
// three samples around the largest one. Everything here is a template over the simulation type
// (instantiated by the tests that use it) or a small inline function.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace grain::test {

/// t_c v / delta_max = 2 int_0^1 dx / sqrt(1 - x^(5/2)) = (4/5) B(2/5, 1/2) = 2.94328.
inline double hertz_time_factor() {
  return 0.8 * std::tgamma(0.4) * std::tgamma(0.5) / std::tgamma(0.9);
}

/// Closed-form undamped Hertz impact: m* d2(delta)/dt2 + K_hz delta^(3/2) = 0 with
/// K_hz = 4/3 E* sqrt(R*), delta(0) = 0, d(delta)/dt(0) = v.
struct HertzReference {
  double m_eff = 0.0; ///< m* [kg]
  double r_eff = 0.0; ///< R* [m]
  double e_eff = 0.0; ///< E* [Pa]
  double v = 0.0;     ///< impact normal velocity [m/s]

  double k_hertz() const { return 4.0 / 3.0 * e_eff * std::sqrt(r_eff); }
  double delta_max() const {
    return std::pow(15.0 * m_eff * v * v / (16.0 * e_eff * std::sqrt(r_eff)), 0.4);
  }
  double force_max() const { return k_hertz() * std::pow(delta_max(), 1.5); }
  double contact_time() const { return hertz_time_factor() * delta_max() / v; }
};

/// Peak of equally spaced samples, refined by the parabola through the largest one and its two
/// neighbours (the largest sample itself at either end or where the samples are not concave);
/// 0 for no samples.
inline double refined_peak(const std::vector<double>& y) {
  if (y.empty()) return 0.0;
  const auto it = std::max_element(y.begin(), y.end());
  const auto k = static_cast<std::size_t>(it - y.begin());
  if (k == 0 || k + 1 >= y.size()) return *it;
  const double y0 = y[k - 1], y1 = y[k], y2 = y[k + 1];
  const double curvature = y0 - 2.0 * y1 + y2;
  if (curvature >= 0.0) return y1;
  return y1 - (y0 - y2) * (y0 - y2) / (8.0 * curvature);
}

/// Whether a contact trace also records the normal force of the contacts after every step.
enum class Forces { skip, record };

/// The samples of one contact, taken after every step with overlap > 0.
struct ContactTrace {
  std::vector<double> time;    ///< [s]
  std::vector<double> overlap; ///< [m]
  std::vector<double> force;   ///< sum of the normal forces of all contacts [N] (Forces::record)
  double t_on = -1.0;          ///< interpolated start of the contact [s]
  double t_off = -1.0;         ///< interpolated end of the contact [s]
};

/// Steps `sim` until the contact is over (at most `max_steps` steps). `overlap(sim)` is the signed
/// overlap from the positions (negative while apart); it must be negative at the start.
template <Forces F = Forces::record, class Sim, class Overlap>
ContactTrace trace_contact(Sim& sim, Overlap overlap, long max_steps) {
  ContactTrace out;
  double t_prev = sim.time();
  double d_prev = overlap(sim);
  REQUIRE(d_prev < 0.0);
  long k = 0;
  for (; k < max_steps; ++k) {
    sim.step();
    const double t = sim.time(), d = overlap(sim);
    if (d > 0.0) {
      if constexpr (F == Forces::record) {
        double f = 0.0;
        sim.for_each_contact(
            [&](auto, auto, bool, const auto&, const auto& r) { f += r.normal.force; });
        out.force.push_back(f);
      }
      out.time.push_back(t);
      out.overlap.push_back(d);
      if (!(d_prev > 0.0)) out.t_on = t_prev + (t - t_prev) * (-d_prev) / (d - d_prev);
    } else if (d_prev > 0.0) {
      out.t_off = t_prev + (t - t_prev) * d_prev / (d_prev - d);
      break;
    }
    t_prev = t;
    d_prev = d;
  }
  REQUIRE(k < max_steps); // the contact ended
  REQUIRE(out.t_on >= 0.0);
  return out;
}

/// What one simulated impact produced.
struct Impact {
  double delta_max = 0.0;    ///< [m]
  double force_max = 0.0;    ///< [N] (0 unless the forces were recorded)
  double contact_time = 0.0; ///< [s]
  double restitution = 0.0;  ///< rebound / impact normal relative velocity
  long contact_steps = 0;    ///< number of samples with overlap > 0
};

/// Steps `sim` through one impact and three steps of free flight after it. `overlap(sim)` is the
/// signed overlap from the positions (negative while apart), `approach(sim)` the normal relative
/// velocity (positive approaching).
template <Forces F = Forces::record, class Sim, class Overlap, class Approach>
Impact measure_impact(Sim& sim, Overlap overlap, Approach approach, long max_steps) {
  Impact out;
  const double v_in = approach(sim);
  const ContactTrace c = trace_contact<F>(sim, overlap, max_steps);
  // free flight afterwards: the velocities are final
  for (int extra = 0; extra < 3; ++extra) {
    sim.step();
    REQUIRE(overlap(sim) < 0.0);
  }
  out.delta_max = refined_peak(c.overlap);
  out.force_max = refined_peak(c.force);
  out.contact_time = c.t_off - c.t_on;
  out.restitution = -approach(sim) / v_in;
  out.contact_steps = static_cast<long>(c.overlap.size());
  return out;
}

/// measure_impact with the overlap and approach of `m` (a PairMeasure or a WallMeasure).
template <Forces F = Forces::record, class Sim, class Measure>
Impact measure_impact(Sim& sim, const Measure& m, long max_steps) {
  return measure_impact<F>(
      sim, [&](const Sim& s) { return m.overlap(s); }, [&](const Sim& s) { return m.approach(s); },
      max_steps);
}

/// Overlap and approach of two particles that meet head-on along the unit vector `n`.
template <class V>
struct PairMeasure {
  std::int64_t a = 0; ///< id of the first particle
  std::int64_t b = 0; ///< id of the second particle, ahead of the first along n
  double reach = 0.0; ///< sum of the radii [m]
  V n;                ///< unit vector from a to b

  /// Sum of the radii minus the centre distance [m] (negative while apart).
  template <class Sim>
  double overlap(const Sim& s) const {
    const auto& q = s.particles();
    return reach - (q.position[s.index_of(b)] - q.position[s.index_of(a)]).norm();
  }
  /// (v_a - v_b) . n [m/s] (positive approaching).
  template <class Sim>
  double approach(const Sim& s) const {
    const auto& q = s.particles();
    return (q.velocity[s.index_of(a)] - q.velocity[s.index_of(b)]).dot(n);
  }
};

/// Adds the particles `a` and `b` for a head-on impact along the unit vector `n`: b is placed
/// ahead of a along n at the centre distance r_a + r_b + gap, a moves with v_a n and b with v_b n.
template <class Sim, class Spec, class V>
PairMeasure<V> add_head_on(Sim& sim, Spec a, Spec b, const V& n, double v_a, double v_b,
                           double gap) {
  a.velocity = v_a * n;
  b.position = a.position + (a.radius + b.radius + gap) * n;
  b.velocity = v_b * n;
  return {sim.add_particle(a), sim.add_particle(b), a.radius + b.radius, n};
}

/// Overlap and approach of a particle and a flat wall.
template <class V>
struct WallMeasure {
  std::int64_t id = 0; ///< the particle
  double radius = 0.0; ///< its radius [m]
  V point;             ///< a point of the wall's surface
  V normal;            ///< unit normal of the wall, towards the particle

  /// Radius minus the distance of the centre from the wall [m] (negative while apart).
  template <class Sim>
  double overlap(const Sim& s) const {
    return radius - (s.particles().position[s.index_of(id)] - point).dot(normal);
  }
  /// Velocity towards the wall [m/s] (positive approaching).
  template <class Sim>
  double approach(const Sim& s) const {
    return -s.particles().velocity[s.index_of(id)].dot(normal);
  }
};

} // namespace grain::test
