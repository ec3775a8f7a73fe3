#pragma once
/// \file concepts.hpp
/// What a contact model is: the slots of `Interaction`, the values that flow between models, and
/// the concepts that check a model type at the boundary (see docs/concepts.md).
///
/// Every model is a stateless struct with
/// - `static constexpr Slot slot` naming the slot it fills,
/// - `struct Params` (user coefficients with defaults) and `static void validate(const Params&)`,
/// - `template <int D> struct History` (per-contact state; an empty struct costs zero bytes),
/// - one static function of its slot (`force`, `tangential`, `torque`, ...).
/// A model may define `template <int D> static void reverse(History<D>&)` to mirror its history
/// when the two partners of a pair swap roles.

#include <grain/contact/geometry.hpp>
#include <grain/particles/material.hpp>
#include <concepts>
#include <utility>

namespace grain {

/// The slots of `Interaction<Normal, Tangent, Rolling, Conduction, AreaCorrection>`.
enum class Slot { normal, tangent, rolling, conduction, area };

/// Result of a normal-force model (all scalars along the normal).
struct NormalResult {
  double force = 0.0;     ///< repulsive force magnitude [N] (negative = attractive)
  double stiffness = 0.0; ///< tangent stiffness dF_elastic/d delta [N/m]
  double damping = 0.0;   ///< damping coefficient dF/d(delta rate) [N s/m]
  double elastic_energy = 0.0; ///< energy stored in the elastic part [J]
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
  { M::validate(std::declval<const typename M::Params&>()) };
} && std::is_trivially_copyable_v<typename M::template History<2>> &&
     std::is_trivially_copyable_v<typename M::template History<3>>;
} // namespace detail

/// A normal-force model: `NormalResult force(const ContactGeometry<D>&, const PairProperties&,
/// const Params&, History<D>&)`.
template <class M>
concept NormalModel =
    detail::fills_slot<M, Slot::normal> &&
    requires(const ContactGeometry<3>& g, const PairProperties& p, const typename M::Params& prm,
             typename M::template History<3>& h) {
      { M::force(g, p, prm, h) } -> std::same_as<NormalResult>;
      { M::stiffness_estimate(p, prm, 1.0, 1.0, 1.0) } -> std::convertible_to<double>;
    };

/// A tangential-force model: `TangentResult<D> force(geometry, pair, NormalResult, Params,
/// History<D>&, dt)`.
template <class M>
concept TangentModel =
    detail::fills_slot<M, Slot::tangent> &&
    requires(const ContactGeometry<3>& g, const PairProperties& p, const NormalResult& n,
             const typename M::Params& prm, typename M::template History<3>& h) {
      { M::force(g, p, n, prm, h, 1.0) } -> std::same_as<TangentResult<3>>;
    };

/// A contact-torque (rolling resistance) model: adds torques to particle i and j.
template <class M>
concept RollingModel =
    detail::fills_slot<M, Slot::rolling> &&
    requires(const ContactGeometry<3>& g, const PairProperties& p, const NormalResult& n,
             const typename M::Params& prm, typename M::template History<3>& h, Vec3& ti,
             Vec3& tj) {
      { M::torque(g, p, n, prm, h, 1.0, ti, tj) };
    };

/// A heat-conduction model (the thermal layer fills this slot; `conduction::None` is the
/// mechanical default).
template <class M>
concept ConductionModel = detail::fills_slot<M, Slot::conduction>;

/// A contact-area correction model (`area::None` is the default).
template <class M>
concept AreaCorrectionModel = detail::fills_slot<M, Slot::area>;

/// Mirrors a history when the partners of a pair swap roles (no-op unless the model defines it).
template <class M, int D>
inline void reverse_history(typename M::template History<D>& h) {
  if constexpr (requires { M::reverse(h); }) M::reverse(h);
}

} // namespace grain
