#pragma once
/// \file integrators.hpp
/// Time integration schemes, chosen as the last template argument of `Simulation`.
///
/// Each scheme advances a velocity-like quantity u (v or omega) with its rate a (F/m or T/I) and
/// calls `drift(u, dt)` to advance the matching position-like quantity (x += u dt, or the
/// orientation rotated by u dt). With a = a(x_n):
///
/// | scheme | update | order |
/// |---|---|---|
/// | `ForwardEuler` | x += v dt; v += a dt | 1, gains energy in collisions |
/// | `SymplecticEuler` (modified Euler) | v += a dt; x += v dt | 1 (symplectic, no drift) |
/// | `Taylor2` | x += v dt + a dt^2/2; v += a dt | 1 in v |
/// | `VelocityVerlet` | v += a dt/2; x += v dt; a = a(x); v += a dt/2 | 2 (symplectic) |
///
/// `drift_before_forces` tells the simulation whether positions advance before the forces of the
/// step are computed (Verlet) or after (the Euler family, as in the seed program).

#include <concepts>

namespace grain::integrate {

struct ForwardEuler {
  static constexpr const char* name = "forward Euler";
  static constexpr bool drift_before_forces = false;
  template <class U, class Drift>
  static void before(U&, const U&, double, Drift&&) {}
  template <class U, class Drift>
  static void after(U& u, const U& a, double dt, Drift&& drift) {
    drift(u, dt);
    u += a * dt;
  }
};

struct SymplecticEuler {
  static constexpr const char* name = "symplectic (modified) Euler";
  static constexpr bool drift_before_forces = false;
  template <class U, class Drift>
  static void before(U&, const U&, double, Drift&&) {}
  template <class U, class Drift>
  static void after(U& u, const U& a, double dt, Drift&& drift) {
    u += a * dt;
    drift(u, dt);
  }
};

struct Taylor2 {
  static constexpr const char* name = "Taylor 2nd order";
  static constexpr bool drift_before_forces = false;
  template <class U, class Drift>
  static void before(U&, const U&, double, Drift&&) {}
  template <class U, class Drift>
  static void after(U& u, const U& a, double dt, Drift&& drift) {
    const U mid = u + 0.5 * dt * a;
    drift(mid, dt);
    u += a * dt;
  }
};

struct VelocityVerlet {
  static constexpr const char* name = "velocity Verlet";
  static constexpr bool drift_before_forces = true;
  template <class U, class Drift>
  static void before(U& u, const U& a, double dt, Drift&& drift) {
    u += 0.5 * dt * a;
    drift(u, dt);
  }
  template <class U, class Drift>
  static void after(U& u, const U& a, double dt, Drift&&) {
    u += 0.5 * dt * a;
  }
};

/// An integration scheme.
template <class T>
concept Integrator = requires {
  { T::drift_before_forces } -> std::convertible_to<bool>;
};

} // namespace grain::integrate
