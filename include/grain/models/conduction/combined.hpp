#pragma once
/// \file combined.hpp
/// `conduction::Combined<Direct, Indirect>`: a direct model (through the contact area) and an
/// indirect one (through the interstitial fluid, also across gaps) acting in parallel:
///
///   H = H_direct + H_indirect                                               [W/K]
///
/// e.g. `Combined<BatchelorOBrien, SurroundingLayer>`. The histories of both are kept; the cutoff
/// and the need for a fluid-cell radius are those of the indirect model.

#include <grain/models/concepts.hpp>

namespace grain::conduction {

template <class Direct, class Indirect>
struct Combined {
  static_assert(ConductionModel<Direct> && Direct::thermal,
                "grain::conduction::Combined<Direct, Indirect>: the 1st argument must be a thermal "
                "conduction model such as conduction::BatchelorOBrien");
  static_assert(ConductionModel<Indirect> && Indirect::thermal,
                "grain::conduction::Combined<Direct, Indirect>: the 2nd argument must be a thermal "
                "conduction model such as conduction::SurroundingLayer");

  static constexpr Slot slot = Slot::conduction;
  static constexpr const char* name = "combined";
  static constexpr bool thermal = true;
  static constexpr bool indirect = conducts_across_gaps<Direct> || conducts_across_gaps<Indirect>;
  static constexpr bool uses_cell_radius =
      grain::uses_cell_radius<Direct> || grain::uses_cell_radius<Indirect>;
  static constexpr bool uses_distance =
      uses_consistent_distance<Direct> || uses_consistent_distance<Indirect>;

  struct Params {
    typename Direct::Params direct{};
    typename Indirect::Params indirect{};
  };
  template <int D>
  struct History {
    [[no_unique_address]] typename Direct::template History<D> direct;
    [[no_unique_address]] typename Indirect::template History<D> indirect;
  };
  static void validate(const Params& p) {
    Direct::validate(p.direct);
    Indirect::validate(p.indirect);
  }
  static double cutoff(const Params& p, double r_max) {
    double c = 0.0;
    if constexpr (conducts_across_gaps<Direct>) c = Direct::cutoff(p.direct, r_max);
    if constexpr (conducts_across_gaps<Indirect>)
      c = std::max(c, Indirect::cutoff(p.indirect, r_max));
    return c;
  }
  template <int D>
  GRAIN_INLINE static double conductance(const ContactGeometry<D>& g, const PairProperties& pair,
                                         const HeatContext& c, const Params& p, History<D>& h) {
    return Direct::conductance(g, pair, c, p.direct, h.direct) +
           Indirect::conductance(g, pair, c, p.indirect, h.indirect);
  }
  template <int D>
  static void reverse(History<D>& h) {
    reverse_history<Direct, D>(h.direct);
    reverse_history<Indirect, D>(h.indirect);
  }
};

} // namespace grain::conduction
