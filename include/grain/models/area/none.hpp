#pragma once
/// \file none.hpp
/// No contact-area correction. Conduction models see the Hertz contact radius of the simulated
/// overlap,
///
///   a = sqrt(R* delta)                                                       [m]
///
/// (Johnson, Contact Mechanics, 1985, eq. 4.22; R* the effective radius, delta the overlap). It is
/// the radius of the true contact circle of two elastic spheres, and 1/sqrt(2) times the half
/// chord of the lens of the undeformed bodies (`area::Geometric`). 2D disks use the same
/// expression.

#include <algorithm>
#include <cmath>
#include <grain/models/concepts.hpp>

namespace grain::area {

struct None {
  static constexpr Slot slot = Slot::area;
  static constexpr const char* name = "none";
  struct Params {};
  template <int D>
  struct History {};
  static void validate(const Params&) {}
  template <int D>
  GRAIN_INLINE static double radius(const ContactGeometry<D>& g, const PairProperties&,
                                    const NormalResult&, const Params&) {
    return std::sqrt(g.r_eff * std::max(g.overlap, 0.0));
  }
};

/// The half chord of the lens of the two undeformed bodies (`lens_contact_radius`),
/// a = sqrt(R1^2 - ((R1^2 - R2^2 + d^2)/(2 d))^2), about sqrt(2 R* delta) for small overlaps: the
/// contact radius of the seed program. No correction of the modulus.
struct Geometric {
  static constexpr Slot slot = Slot::area;
  static constexpr const char* name = "geometric";
  struct Params {};
  template <int D>
  struct History {};
  static void validate(const Params&) {}
  template <int D>
  GRAIN_INLINE static double radius(const ContactGeometry<D>& g, const PairProperties&,
                                    const NormalResult&, const Params&) {
    return lens_contact_radius(g);
  }
};

} // namespace grain::area
