#pragma once
/// \file concepts.hpp
/// What a contact model is: the slots of `Interaction`, the values that flow between models, and
/// the concepts that check a model type at the boundary (see docs/concepts.md).
///
/// Every model is a stateless struct with
/// - `static constexpr Slot slot` naming the slot it fills,
/// - `struct Params` (user coefficients with defaults) and `static void validate(const Params&)`,
/// - `template <int D> struct History` (per-contact state; an empty struct costs zero bytes),
/// - one static function of its slot (`force` for normal and tangential models, `torque`, ...).
/// A model may define `template <int D> static void reverse(History<D>&)` to mirror its history
/// when the two partners of a pair swap roles.

#include <concepts>
#include <grain/contact/geometry.hpp>
#include <grain/core/config.hpp>
#include <grain/particles/material.hpp>
#include <limits>
#include <utility>

namespace grain {

/// The slots of `Interaction<Normal, Tangent, Rolling, Conduction, AreaCorrection>`.
enum class Slot { normal, tangent, rolling, conduction, area, convection, radiation };

/// Result of a normal-force model (all scalars along the normal).
struct NormalResult {
  double force = 0.0; ///< repulsive force magnitude [N] (negative = attractive)
  /// stiffness [N/m] the tangential and rolling models scale with: dF_elastic/d delta of an
  /// elastic law, the loading stiffness of a hysteretic one (continuous while in contact)
  double stiffness = 0.0;
  double damping = 0.0;        ///< damping coefficient dF/d(delta rate) [N s/m]
  double elastic_energy = 0.0; ///< energy stored in the elastic part [J]
  /// True if the bodies overlap but the contact carries nothing: a hysteretic law below its
  /// residual overlap, the particles off their plastic dent. No heat flows through it.
  bool detached = false;
  /// Adhesive models: the attraction [N] that presses the surfaces together (the pull-off
  /// offset). The tangential and rolling models limit their forces with the load force +
  /// adhesion instead of the force (see `cohesive_model`); 0 for the others.
  double adhesion = 0.0;
  /// The viscous (dashpot) part of `force` [N], as the law applied it (after any clamping of the
  /// total to zero); `force - viscous` is the elastic part (with adhesion, the elastic and
  /// adhesive part). 0 for laws without damping.
  double viscous = 0.0;
};

/// Result of a tangential-force model.
template <int D>
struct TangentResult {
  Vec<D> force = Vec<D>::Zero(); ///< tangential force on particle i [N]
  double elastic_energy = 0.0;   ///< energy stored in the tangential spring [J]
  bool sliding = false;
};

namespace detail {
template <class M, Slot S>
concept fills_slot = requires {
  { M::slot } -> std::convertible_to<Slot>;
  requires M::slot == S;
  typename M::Params;
  typename M::template History<2>;
  typename M::template History<3>;
  {M::validate(std::declval<const typename M::Params&>())};
}
&&std::is_trivially_copyable_v<typename M::template History<2>>&&
    std::is_trivially_copyable_v<typename M::template History<3>>;
} // namespace detail

/// True if the normal model `M` is adhesive (`static constexpr bool cohesive = true`): it sets
/// `NormalResult::adhesion`, it may act across a gap, and it gives `static double reach(const
/// Params&, const PairProperties&, double r_eff)`, the largest gap [m] across which it acts on a
/// pair of effective radius up to r_eff (0: in contact only). The search then reaches that far
/// beyond contact, and the model's `force` is called for listed pairs closer than that, with a
/// negative overlap (minus the gap) for those that do not touch: it keeps in its history whether
/// the pair is bonded and returns a zero force for a pair that is not. Across a gap only the
/// normal force acts (the tangential and rolling models are not called and their histories are
/// cleared); the model marks such results `detached` (no heat flows through them).
template <class M>
inline constexpr bool cohesive_model = [] {
  if constexpr (requires { M::cohesive; })
    return static_cast<bool>(M::cohesive);
  else
    return false;
}();

/// A normal-force model: `NormalResult force(const ContactGeometry<D>&, const PairProperties&,
/// const Params&, History<D>&)`.
template <class M>
concept NormalModel = detail::fills_slot<M, Slot::normal> &&
    requires(const ContactGeometry<3>& g, const PairProperties& p, const typename M::Params& prm,
             typename M::template History<3>& h) {
  { M::force(g, p, prm, h) } -> std::same_as<NormalResult>;
  { M::stiffness_estimate(p, prm, 1.0, 1.0, 1.0) } -> std::convertible_to<double>;
} &&(!cohesive_model<M> || requires(const typename M::Params& prm, const PairProperties& p) {
  { M::reach(prm, p, 1.0) } -> std::convertible_to<double>;
});

/// A tangential-force model: `TangentResult<D> force(geometry, pair, NormalResult, Params,
/// History<D>&, dt)`.
template <class M>
concept TangentModel = detail::fills_slot<M, Slot::tangent> &&
    requires(const ContactGeometry<3>& g, const PairProperties& p, const NormalResult& n,
             const typename M::Params& prm, typename M::template History<3>& h) {
  { M::force(g, p, n, prm, h, 1.0) } -> std::same_as<TangentResult<3>>;
};

/// A contact-torque (rolling resistance) model: adds torques to particle i and j.
template <class M>
concept RollingModel = detail::fills_slot<M, Slot::rolling> &&
    requires(const ContactGeometry<3>& g, const PairProperties& p, const NormalResult& n,
             const typename M::Params& prm, typename M::template History<3>& h, Vec3& ti,
             Vec3& tj) {
  {M::torque(g, p, n, prm, h, 1.0, ti, tj)};
};

/// What a conduction model sees of a pair besides its `ContactGeometry` (SI units). For a pair
/// that does not touch (indirect conduction across a gap) the geometry holds the normal, the
/// centre distance, the radii, r_eff and m_eff, and a negative overlap (minus the gap).
struct HeatContext {
  /// Contact radius a after the area correction [m]; 0 for a pair that does not touch.
  double contact_radius = 0.0;
  /// Centre distance consistent with `contact_radius` [m]: for touching particles
  /// sqrt(R_i^2 - a^2) + sqrt(R_j^2 - a^2), for a flat wall the centre-to-surface distance
  /// sqrt(R_i^2 - a^2); for a gap the actual distance (centre-to-surface for a wall).
  double distance = 0.0;
  /// Surface separation [m]: 0 while touching, > 0 across a gap.
  double gap = 0.0;
  /// Radius of the fluid cell shared by the pair [m] (the Voronoi models' r_ij), set by the
  /// simulation when the conduction model asks for it (`uses_cell_radius`), else infinite.
  double cell_radius = std::numeric_limits<double>::infinity();
  /// Cylinder length L [m] of 2D disks; 0 for spheres (and for disks with sphere mass).
  double length = 0.0;
  double time_step = 0.0; ///< [s]
  bool touching = false;
};

/// A heat-conduction model: `static constexpr bool thermal` (false only for `conduction::None`)
/// and, if thermal, `double conductance(const ContactGeometry<D>&, const PairProperties&,
/// const HeatContext&, const Params&, History<D>&)` returning the conductance H [W/K] of the
/// pair, so that the heat rate into particle i is H (T_j - T_i). A model that also conducts across
/// gaps sets `static constexpr bool indirect = true` and gives `static double cutoff(const
/// Params&, double r_max)`, the largest gap [m] across which it conducts.
template <class M>
concept ConductionModel = detail::fills_slot<M, Slot::conduction> && requires {
  { M::thermal } -> std::convertible_to<bool>;
} &&(!M::thermal ||
     requires(const ContactGeometry<3>& g, const ContactGeometry<2>& g2, const PairProperties& p,
              const HeatContext& c, const typename M::Params& prm,
              typename M::template History<3>& h, typename M::template History<2>& h2) {
       { M::conductance(g, p, c, prm, h) } -> std::convertible_to<double>;
       { M::conductance(g2, p, c, prm, h2) } -> std::convertible_to<double>;
     });

/// A contact-area correction: `double radius(const ContactGeometry<D>&, const PairProperties&,
/// const NormalResult&, const Params&)` returns the contact radius [m] that conduction models use.
template <class M>
concept AreaCorrectionModel = detail::fills_slot<M, Slot::area> &&
    requires(const ContactGeometry<3>& g, const PairProperties& p, const NormalResult& n,
             const typename M::Params& prm) {
  { M::radius(g, p, n, prm) } -> std::convertible_to<double>;
};

/// A convection model (particle to surrounding fluid), an optional argument of `Simulation`:
/// `static constexpr bool active` and, if active, `double nusselt(double Re, double Pr, const
/// Params&)`, the Nusselt number of a particle at Reynolds number Re = rho_f 2R |v_f - v|/mu_f and
/// Prandtl number Pr = mu_f c_f / k_f. The simulation applies h = Nu k_f/(2R) over the particle
/// surface S: Q = h S (T_f - T).
template <class M>
concept ConvectionModel = requires {
  { M::slot } -> std::convertible_to<Slot>;
  requires M::slot == Slot::convection;
  typename M::Params;
  { M::active } -> std::convertible_to<bool>;
  {M::validate(std::declval<const typename M::Params&>())};
}
&&(!M::active || requires(const typename M::Params& p) {
  { M::nusselt(1.0, 1.0, p) } -> std::convertible_to<double>;
});

/// A thermal radiation model (particle to its surroundings), an optional argument of
/// `Simulation`: `static constexpr bool active` and, if active,
/// `double domain_radius(double R, const Params&)`, the radius [m] of the domain around a particle
/// of radius R whose particles it sees; `double local_temperature(double porosity, double T_f,
/// double T_mean, const Params&)`, the temperature [K] the particle sees from the porosity of the
/// domain, the fluid temperature and the mean temperature of the other particles in it; and
/// `double heat_rate(double emissivity, double area, double T_local, double T, const Params&)`,
/// the heat rate [W] into a particle of surface `area` [m^2] at temperature T.
template <class M>
concept RadiationModel = requires {
  { M::slot } -> std::convertible_to<Slot>;
  requires M::slot == Slot::radiation;
  typename M::Params;
  { M::active } -> std::convertible_to<bool>;
  {M::validate(std::declval<const typename M::Params&>())};
}
&&(!M::active || requires(const typename M::Params& p) {
  { M::domain_radius(1.0, p) } -> std::convertible_to<double>;
  { M::local_temperature(0.5, 300.0, 300.0, p) } -> std::convertible_to<double>;
  { M::heat_rate(1.0, 1.0, 300.0, 300.0, p) } -> std::convertible_to<double>;
});

/// True if the conduction model `M` conducts across gaps (evaluated for pairs within its cutoff).
template <class M>
inline constexpr bool conducts_across_gaps = [] {
  if constexpr (requires { M::indirect; })
    return static_cast<bool>(M::indirect);
  else
    return false;
}();

/// True unless the conduction model `M` declares `uses_distance = false`: it then does not read
/// `HeatContext::distance`, and the consistent centre distance is not computed.
template <class M>
inline constexpr bool uses_consistent_distance = [] {
  if constexpr (requires { M::uses_distance; })
    return static_cast<bool>(M::uses_distance);
  else
    return true;
}();

/// True if the conduction model `M` needs the fluid-cell radius of each pair.
template <class M>
inline constexpr bool uses_cell_radius = [] {
  if constexpr (requires { M::uses_cell_radius; })
    return static_cast<bool>(M::uses_cell_radius);
  else
    return false;
}();

/// Mirrors a history when the partners of a pair swap roles (no-op unless the model defines it).
template <class M, int D>
inline void reverse_history(typename M::template History<D>& h) {
  if constexpr (requires { M::reverse(h); }) M::reverse(h);
}

} // namespace grain
