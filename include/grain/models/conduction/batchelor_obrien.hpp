#pragma once
/// \file batchelor_obrien.hpp
/// Direct conduction through the contact area of two touching solids (Batchelor & O'Brien,
/// Proc. R. Soc. Lond. A 355 (1977) 313), valid when the solid conducts much better than the
/// surrounding fluid (k_s >> k_f):
///
///   H = 4 k* a,   k* = k1 k2 / (k1 + k2)                                   [W/K]
///
/// (H = 2 k a for equal conductivities), a [m] the contact radius after the area correction. The
/// same formula serves spheres and 2D disks, particle-particle and particle-wall contacts (the wall
/// conducts with its material's conductivity). No history; no conduction across gaps.

#include <grain/models/concepts.hpp>

namespace grain::conduction {

struct BatchelorOBrien {
  static constexpr Slot slot = Slot::conduction;
  static constexpr const char* name = "Batchelor-O'Brien";
  static constexpr bool thermal = true;
  static constexpr bool uses_distance = false; ///< needs the contact radius only
  struct Params {};
  template <int D>
  struct History {};
  static void validate(const Params&) {}

  template <int D>
  GRAIN_INLINE static double conductance(const ContactGeometry<D>&, const PairProperties& pair,
                                         const HeatContext& c, const Params&, History<D>&) {
    return c.touching ? 4.0 * pair.conductivity_eff * c.contact_radius : 0.0;
  }
};

} // namespace grain::conduction
