#pragma once
/// \file interaction.hpp
/// `Interaction<Normal, Tangent, Rolling, Conduction, AreaCorrection>`: the compile-time
/// composition of contact models, and the per-contact pipeline.
///
/// Pipeline of one contact (the only place where the order lives):
/// 1. normal force  -> NormalResult {force, stiffness, damping};
/// 2. tangential force, given the normal result (Coulomb limit, default stiffness and damping);
/// 3. torques: the tangential force about each centre (arm x F), then the rolling model;
/// 4. (thermal simulations, `conductance`) the area correction turns the geometry and the normal
///    result into the contact radius a, the centre distance is made consistent with a, and the
///    conduction model returns the conductance H [W/K]; the heat rate into i is H (T_j - T_i).
///    Pairs that do not touch reach only `gap_conductance` (models that conduct across gaps).
/// With `conduction::None` (the default) the simulation is purely mechanical. An adhesive normal
/// model (`cohesive`) is also evaluated for listed pairs within its reach across a gap: there
/// only the normal force acts; in contact, steps 2 and 3 see the load force + adhesion.
///
/// The per-contact history is composed of the non-empty histories of the models in use only; for
/// models without history it costs zero bytes, and it is trivially copyable (a checkpoint or a
/// re-sort of the contact list is a plain copy).

#include <algorithm>
#include <cmath>
#include <grain/core/config.hpp>
#include <grain/models/area/none.hpp>
#include <grain/models/concepts.hpp>
#include <grain/models/conduction/none.hpp>
#include <grain/models/rolling/none.hpp>
#include <grain/models/tangent/none.hpp>
#include <type_traits>

namespace grain {

namespace detail {

/// Placeholder used after a failed concept check so that only the readable message is printed.
template <Slot S>
struct InvalidModel {
  static constexpr Slot slot = S;
  struct Params {};
  template <int D>
  struct History {};
  static void validate(const Params&) {}
  template <int D>
  static NormalResult force(const ContactGeometry<D>&, const PairProperties&, const Params&,
                            History<D>&) {
    return {};
  }
  static double stiffness_estimate(const PairProperties&, const Params&, double, double, double) {
    return 0;
  }
  template <int D>
  static TangentResult<D> force(const ContactGeometry<D>&, const PairProperties&,
                                const NormalResult&, const Params&, History<D>&, double) {
    return {};
  }
  static constexpr bool thermal = false;
  template <int D>
  static double radius(const ContactGeometry<D>&, const PairProperties&, const NormalResult&,
                       const Params&) {
    return 0;
  }
  template <int D, class A>
  static void torque(const ContactGeometry<D>&, const PairProperties&, const NormalResult&,
                     const Params&, History<D>&, double, A&, A&) {}
};

/// A history slot tagged by its position so that two identical empty histories can share an
/// address (and so take no space).
template <class H, int I>
struct Tagged : H {};

/// False if the bytes of a history slot read from a file are not a history of its model (a
/// model whose history holds a truth value or an enumeration says which are, with a static
/// `valid_bytes`; any bytes are a history of the others).
template <class H, int I>
bool valid_bytes(const Tagged<H, I>& h) {
  if constexpr (requires { H::valid_bytes(h); })
    return H::valid_bytes(h);
  else
    return true;
}

/// `p` with the per-pair constants of model M worked out (M::resolve, if M has one).
template <class M>
void resolve_model(typename M::Params& p, const PairProperties& pair) {
  if constexpr (requires { M::resolve(p, pair); }) p = M::resolve(p, pair);
}

} // namespace detail

template <class Normal, class Tangent = tangent::None, class Rolling = rolling::None,
          class Conduction = conduction::None, class AreaCorrection = area::None>
struct Interaction {
  static_assert(NormalModel<Normal>,
                "grain::Interaction: the 1st argument must be a normal-force model, i.e. a type "
                "from namespace grain::normal such as normal::Hertz<> or "
                "normal::LinearSpringDashpot (see docs/concepts.md)");
  static_assert(TangentModel<Tangent>,
                "grain::Interaction: the 2nd argument must be a tangential-force model, i.e. a "
                "type from namespace grain::tangent such as tangent::SpringDashpotSlider or "
                "tangent::None (see docs/concepts.md)");
  static_assert(RollingModel<Rolling>,
                "grain::Interaction: the 3rd argument must be a contact-torque model, i.e. a type "
                "from namespace grain::rolling such as rolling::None (see docs/concepts.md)");
  static_assert(ConductionModel<Conduction>,
                "grain::Interaction: the 4th argument must be a conduction model, i.e. a type "
                "from namespace grain::conduction such as conduction::None (see docs/concepts.md)");
  static_assert(AreaCorrectionModel<AreaCorrection>,
                "grain::Interaction: the 5th argument must be a contact-area correction, i.e. a "
                "type from namespace grain::area such as area::None (see docs/concepts.md)");

  using normal_model =
      std::conditional_t<NormalModel<Normal>, Normal, detail::InvalidModel<Slot::normal>>;
  using tangent_model =
      std::conditional_t<TangentModel<Tangent>, Tangent, detail::InvalidModel<Slot::tangent>>;
  using rolling_model =
      std::conditional_t<RollingModel<Rolling>, Rolling, detail::InvalidModel<Slot::rolling>>;
  using conduction_model = std::conditional_t<ConductionModel<Conduction>, Conduction,
                                              detail::InvalidModel<Slot::conduction>>;
  using area_model = std::conditional_t<AreaCorrectionModel<AreaCorrection>, AreaCorrection,
                                        detail::InvalidModel<Slot::area>>;

  /// True if a model produces torques (then particles carry and integrate rotation).
  static constexpr bool has_torque = !std::is_same_v<tangent_model, tangent::None> ||
                                     !std::is_same_v<rolling_model, rolling::None>;

  /// True if the normal model is adhesive (see `cohesive_model`): it may act across gaps up to
  /// `reach`, and the tangential and rolling models see the load force + adhesion.
  static constexpr bool cohesive = cohesive_model<normal_model>;

  /// True if the conduction model transfers heat (particles then carry temperatures).
  static constexpr bool thermal = conduction_model::thermal;
  /// True if heat also flows across gaps (the search then reaches `cutoff` beyond contact).
  static constexpr bool indirect = thermal && conducts_across_gaps<conduction_model>;
  /// True if the conduction model needs the fluid-cell radius of each pair.
  static constexpr bool needs_cell_radius = thermal && uses_cell_radius<conduction_model>;

  /// Coefficients of every model in use.
  struct Params {
    typename normal_model::Params normal{};
    typename tangent_model::Params tangent{};
    typename rolling_model::Params rolling{};
    typename conduction_model::Params conduction{};
    typename area_model::Params area{};
  };

  /// Per-contact history: the models' histories, empty ones taking no space.
  template <int D>
  struct History {
    [[no_unique_address]] detail::Tagged<typename normal_model::template History<D>, 0> normal;
    [[no_unique_address]] detail::Tagged<typename tangent_model::template History<D>, 1> tangent;
    [[no_unique_address]] detail::Tagged<typename rolling_model::template History<D>, 2> rolling;
    [[no_unique_address]] detail::Tagged<typename conduction_model::template History<D>, 3>
        conduction;
    [[no_unique_address]] detail::Tagged<typename area_model::template History<D>, 4> area;

    /// False if these bytes (read from a checkpoint) are not a history of the models.
    static bool valid_bytes(const History& h) {
      return detail::valid_bytes(h.normal) && detail::valid_bytes(h.tangent) &&
             detail::valid_bytes(h.rolling) && detail::valid_bytes(h.conduction) &&
             detail::valid_bytes(h.area);
    }
  };

  /// True if no model keeps per-contact state (no history array is allocated).
  template <int D>
  static constexpr bool stateless = std::is_empty_v<History<D>>;

  /// What one contact produces.
  template <int D>
  struct Result {
    Vec<D> force = Vec<D>::Zero();            ///< total contact force on i (on j: minus this) [N]
    Angular<D> torque_i = zero<Angular<D>>(); ///< contact torque on i [N m]
    Angular<D> torque_j = zero<Angular<D>>(); ///< contact torque on j [N m]
    NormalResult normal;
    TangentResult<D> tangent;
  };

  /// The coefficients `p` of one pair type with what the models derive from the pair's
  /// properties alone (a restitution map, a stiffness ratio) worked out once: a model may have
  /// `static Params resolve(Params, const PairProperties&)`. Contacts evaluated with the result
  /// give the same bits as with `p`, with fewer operations; the simulation resolves each pair
  /// type before a run (not when contact properties vary per particle).
  static Params resolve(Params p, const PairProperties& pair) {
    detail::resolve_model<normal_model>(p.normal, pair);
    detail::resolve_model<tangent_model>(p.tangent, pair);
    detail::resolve_model<rolling_model>(p.rolling, pair);
    detail::resolve_model<conduction_model>(p.conduction, pair);
    detail::resolve_model<area_model>(p.area, pair);
    return p;
  }

  static void validate(const Params& p) {
    normal_model::validate(p.normal);
    tangent_model::validate(p.tangent);
    rolling_model::validate(p.rolling);
    conduction_model::validate(p.conduction);
    area_model::validate(p.area);
  }

  /// The per-contact pipeline (see the file comment for the order).
  template <int D>
  GRAIN_INLINE static Result<D> evaluate(const ContactGeometry<D>& g, const PairProperties& pair,
                                         const Params& p, History<D>& h, double dt) {
    Result<D> r;
    r.normal = normal_model::force(g, pair, p.normal, h.normal);
    if constexpr (cohesive) {
      if (!(g.overlap > 0.0)) { // across a gap: the normal force only, the other histories
        h.tangent = {};         // start afresh at the next touch, as after a separation
        h.rolling = {};
        h.conduction = {};
        h.area = {};
        r.force = -r.normal.force * g.normal;
        return r;
      }
      NormalResult load = r.normal; // the Coulomb limits see the load + adhesion
      load.force += r.normal.adhesion;
      r.tangent = tangent_model::force(g, pair, load, p.tangent, h.tangent, dt);
      r.force = r.tangent.force - r.normal.force * g.normal;
      if constexpr (has_torque) {
        r.torque_i = cross(g.arm_i, r.tangent.force);
        r.torque_j = cross(g.arm_j, Vec<D>(-r.tangent.force));
        rolling_model::torque(g, pair, load, p.rolling, h.rolling, dt, r.torque_i, r.torque_j);
      }
      return r;
    }
    r.tangent = tangent_model::force(g, pair, r.normal, p.tangent, h.tangent, dt);
    r.force = r.tangent.force - r.normal.force * g.normal;
    if constexpr (has_torque) {
      r.torque_i = cross(g.arm_i, r.tangent.force);
      r.torque_j = cross(g.arm_j, Vec<D>(-r.tangent.force));
      rolling_model::torque(g, pair, r.normal, p.rolling, h.rolling, dt, r.torque_i, r.torque_j);
    }
    return r;
  }

  /// Conductance H [W/K] of a touching pair whose normal force is `n` (step 4 of the pipeline).
  /// `length` is the cylinder length of 2D disks (0 for spheres), `cell_radius` the fluid-cell
  /// radius (infinite when unused). A contact the normal model reports `detached` (Walton-Braun
  /// below its residual overlap, off its plastic dent) conducts nothing, whatever the overlap.
  template <int D>
  GRAIN_INLINE static double conductance(const ContactGeometry<D>& g, const PairProperties& pair,
                                         const NormalResult& n, const Params& p, History<D>& h,
                                         double dt, double length, double cell_radius) {
    if constexpr (thermal) {
      if (n.detached) return 0.0;
      const double a = area_model::radius(g, pair, n, p.area);
      const HeatContext c{
          .contact_radius = a,
          .distance = uses_consistent_distance<conduction_model> ? consistent_distance(g, a) : 0.0,
          .gap = 0.0,
          .cell_radius = cell_radius,
          .length = length,
          .time_step = dt,
          .touching = true};
      return conduction_model::conductance(g, pair, c, p.conduction, h.conduction);
    } else {
      return 0.0;
    }
  }

  /// Conductance H [W/K] of a pair separated by a gap (models that conduct across gaps only).
  template <int D>
  static double gap_conductance(const ContactGeometry<D>& g, const PairProperties& pair,
                                const Params& p, History<D>& h, double dt, double length,
                                double cell_radius) {
    if constexpr (indirect) {
      const HeatContext c{.contact_radius = 0.0,
                          .distance = g.distance,
                          .gap = -g.overlap,
                          .cell_radius = cell_radius,
                          .length = length,
                          .time_step = dt,
                          .touching = false};
      return conduction_model::conductance(g, pair, c, p.conduction, h.conduction);
    } else {
      return 0.0;
    }
  }

  /// Largest gap [m] across which the normal model acts on a pair of effective radius up to
  /// `r_max` (0 unless it is cohesive).
  static double reach(const Params& p, const PairProperties& pair, double r_max) {
    if constexpr (cohesive)
      return normal_model::reach(p.normal, pair, r_max);
    else
      return 0.0;
  }

  /// Largest gap [m] across which heat flows (0 unless the conduction model is indirect).
  static double cutoff(const Params& p, double r_max) {
    if constexpr (indirect)
      return conduction_model::cutoff(p.conduction, r_max);
    else
      return 0.0;
  }

  /// Centre distance (pair) or centre-to-surface distance (flat wall) at which the undeformed
  /// bodies intersect in a lens of radius a [m].
  template <int D>
  static double consistent_distance(const ContactGeometry<D>& g, double a) {
    const double a2 = a * a;
    const double di = std::sqrt(std::max(g.radius_i * g.radius_i - a2, 0.0));
    if (g.wall) {
      if (std::isinf(g.radius_j)) return di;
      const double rw = std::abs(g.radius_j);
      const double dj = std::sqrt(std::max(rw * rw - a2, 0.0));
      return g.radius_j > 0 ? di + dj - rw : rw - dj + di; // centre-to-surface distance
    }
    return di + std::sqrt(std::max(g.radius_j * g.radius_j - a2, 0.0));
  }

  /// Mirrors the history of a pair whose partners swap roles.
  template <int D>
  static void reverse(History<D>& h) {
    reverse_history<normal_model, D>(h.normal);
    reverse_history<tangent_model, D>(h.tangent);
    reverse_history<rolling_model, D>(h.rolling);
    reverse_history<conduction_model, D>(h.conduction);
    reverse_history<area_model, D>(h.area);
  }

  /// Largest normal stiffness expected for a contact [N/m] (for the stable time step).
  static double stiffness_estimate(const PairProperties& pair, const Params& p, double r_eff,
                                   double m_eff, double v) {
    return normal_model::stiffness_estimate(pair, p.normal, r_eff, m_eff, v);
  }
};

} // namespace grain
