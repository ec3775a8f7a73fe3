#pragma once
/// \file params.hpp
/// What a `Simulation` is given: a particle's specification (`ParticleSpec`), the analysis, the
/// global settings (`SimulationParams`), the run counters, and the traits that sort a
/// simulation's options (integrator, convection model, cell-size method, stages, fields).

#include <grain/core/stages.hpp>
#include <grain/core/sums.hpp>
#include <grain/core/vector.hpp>
#include <grain/integrate/integrators.hpp>
#include <grain/models/concepts.hpp>
#include <grain/models/convection/none.hpp>
#include <grain/models/radiation/none.hpp>
#include <grain/particles/material.hpp>
#include <grain/thermal/cells.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <type_traits>

namespace grain {

/// What a particle is made of and where it starts (SI units).
template <int D>
struct ParticleSpec {
  Vec<D> position = Vec<D>::Zero();      ///< centre [m]
  double radius = 0.0;                   ///< [m], > 0
  std::uint32_t material = 0;            ///< index returned by add_material
  Vec<D> velocity = Vec<D>::Zero();      ///< [m/s]
  Angular<D> omega = zero<Angular<D>>(); ///< angular velocity [rad/s]
  /// Initial temperature [K] (thermal simulations only); NaN = SimulationParams::initial_temperature.
  double temperature = std::numeric_limits<double>::quiet_NaN();
  bool fixed = false; ///< if true the particle keeps its velocities (forces do not move it)
  /// Time [s] from which the particle exists; before it, it is inactive (stored, but invisible to
  /// contacts, output and statistics). -inf (default) = from the start.
  double creation_time = -std::numeric_limits<double>::infinity();
  /// Time [s] at which the particle is removed, with its contacts; +inf (default) = never.
  double destruction_time = std::numeric_limits<double>::infinity();
  std::int64_t id = -1; ///< -1 = next free id
};

/// What a simulation advances.
enum class Analysis {
  automatic,         ///< thermo-mechanical if the contact has a conduction model, else mechanical
  mechanical,        ///< motion only; temperatures (if any) stay constant
  thermal,           ///< temperatures only; particles never move, conductances computed once
  thermo_mechanical, ///< motion and temperatures every step
};

namespace detail {
template <class T>
concept integrator_option = integrate::Integrator<T>;
template <class T>
concept convection_option = ConvectionModel<T>;

/// The first of Ts satisfying the predicate P, or Default.
template <template <class> class P, class Default, class... Ts>
struct pick {
  using type = Default;
};
template <template <class> class P, class Default, class T, class... Ts>
struct pick<P, Default, T, Ts...> {
  using type = std::conditional_t<P<T>::value, T, typename pick<P, Default, Ts...>::type>;
};
template <class T>
struct is_integrator : std::bool_constant<integrator_option<T>> {};
template <class T>
struct is_convection : std::bool_constant<convection_option<T>> {};
template <class T>
struct is_radiation : std::bool_constant<RadiationModel<T>> {};
template <class T>
struct is_cell_method : std::bool_constant<cells::CellSizeMethod<T>> {};
template <class T>
struct is_option
    : std::bool_constant<integrator_option<T> || convection_option<T> || RadiationModel<T> ||
                         cells::CellSizeMethod<T> || is_stages<T>::value || is_fields<T>::value ||
                         is_sums<T>::value> {};
} // namespace detail

/// Global settings of a simulation.
template <int D, class Contact, class SearchT, class Convection = convection::None,
          class CellSize = cells::GlobalPorosity, class Radiation = radiation::None>
struct SimulationParams {
  double time_step = 0.0; ///< [s]; 0 = automatic (auto_time_step_factor x critical step)
  double auto_time_step_factor = 0.1;
  /// Impact velocity [m/s] used to estimate the stiffness of velocity-dependent contact laws in
  /// the critical time step (the largest of this and twice the fastest initial particle speed).
  double reference_velocity = 1.0;
  Vec<D> gravity = Vec<D>::Zero();    ///< [m/s^2]
  double damping_translational = 0.0; ///< global damping force -c v, c in [N s/m]
  double damping_rotational = 0.0;    ///< global damping torque -c w, c in [N m s]
  typename Contact::Params contact{}; ///< coefficients of the contact models
  typename SearchT::Params search{};  ///< neighbour-search settings
  /// The largest overlap allowed at the start of a run, as a fraction of the smaller radius
  /// (of the particle's radius against a wall), for the particles and walls added since the
  /// last start: a deeper one is an InputError naming both (it would fire them apart; a centre
  /// behind a plane overlaps it by more than the radius). Infinity allows any overlap.
  double max_start_overlap = 0.05;
  /// The largest distance a particle may travel in one step, as a fraction of its radius (and
  /// the largest angle it may turn, in radians): beyond it the run stops with NumericalError
  /// (no contact can be resolved at that speed; a stable step gives far less). Infinity turns
  /// the check off.
  double max_step_travel = 1.0;

  // thermal settings (used when the contact has a conduction model)
  Analysis analysis = Analysis::automatic;
  double initial_temperature = 293.15; ///< default particle temperature [K]
  /// Surrounding / interstitial fluid (convection, conduction through the fluid).
  Fluid<D> fluid{};
  typename Convection::Params convection{}; ///< coefficients of the convection model
  typename Radiation::Params radiation{};   ///< settings of the radiation model
  /// Fraction in [0, 1] of the power dissipated at contacts (viscous normal damping eta
  /// (d delta/dt)^2 and sliding friction -F_t . v_t) that heats the two partners, half each (a
  /// wall's half leaves the system). 0 (default): dissipation makes no heat. Hysteresis of
  /// plastic normal models, sticking tangential dashpots and rolling resistance are not counted.
  double dissipation_heating = 0.0;
  /// If true, the simulation accumulates the energy dissipated by the contacts and the global
  /// damping (Simulation::dissipated_energy); off by default (it costs a few operations per
  /// contact).
  bool track_dissipation = false;
  /// If true (default), particle orientations (3D: unit quaternions, 2D: angles) are integrated
  /// from the angular velocities. No contact model reads them; they serve output (the VTK field
  /// `orientation`) and checkpoints. False saves a rotation per particle and step (about 15 % of
  /// a settling step of spheres); the orientations then stay where they were.
  bool track_orientation = true;
  /// Models that act across gaps (indirect conduction, adhesion) make the neighbour search reach
  /// their largest gap, which grows with the radius. If true (default), a mixed population lists
  /// a pair only within the skin plus the larger of the two particles' own neighbour distances
  /// (the largest gap across which the models act on a particle of that radius): small particles
  /// do not carry the partners of the largest ones. False lists every pair within the distance
  /// of the largest particle. Results are the same either way.
  bool neighbour_distance_per_particle = true;
  /// Settings of the fluid-cell size method (Voronoi conduction models only).
  typename CellSize::Params cells{};
};

/// Summary counters of a run (for the console summary and benchmarks).
struct RunCounters {
  long steps = 0;
  long rebuilds = 0;
  double wall_seconds = 0.0;
  double particle_steps = 0.0;
};

namespace detail {
/// The dimension of a particle shape (3 for a type that is not one: its own check reports it).
template <class Shape>
inline constexpr int dimension_of = [] {
  if constexpr (requires { Shape::dimension; })
    return int(Shape::dimension);
  else
    return 3;
}();

/// The number of steps of length dt that cover `duration` [s]: rounded up, but a quotient within
/// rounding of a whole number (relative 1e-12, at least 1e-9 steps) counts as that number.
inline long steps_for(double duration, double dt) {
  const double q = duration / dt;
  return static_cast<long>(std::ceil(q - std::max(1e-9, 1e-12 * q)));
}
} // namespace detail

} // namespace grain
