#pragma once
/// \file morris_pannala_ma_hrenya.hpp
/// Contact-area correction for a softened Young's modulus from the normal force (A. B. Morris,
/// S. Pannala, Z. Ma, C. M. Hrenya, AIChE J. 62 (2016) 4526): the contact radius is the Hertz
/// radius that the real material would have under the current normal force,
///
///   a' = (3 F_n R* / (4 E*_0))^(1/3)                                        [m]
///
/// F_n [N] is the normal force of the current step (`NormalResult::force`, its damping part
/// included, negative values taken as 0), R* [m] the effective radius and E*_0 [Pa] the effective
/// modulus of the real moduli (`PairProperties::young_real_eff`; taken equal to the simulated
/// `young_eff` if it is not positive). The result does not depend on the simulated stiffness, so
/// any normal model (Hertz, linear spring-dashpot, hysteretic) can be used. No parameters, no
/// history.
///
/// The paper also multiplies by a contact-time factor (t_c,0/t_c)^(2/3) for collisions; it is not
/// applied here, so the correction is the static one (exact for enduring contacts, e.g. packed
/// beds). The seed program writes (F_n R*/E*_0)^(1/3), without the Hertz factor 3/4, which is
/// (4/3)^(1/3) = 1.1006 times the radius given here.
///
/// Validity: elastic, frictionless Hertz contact of spheres under the real modulus; 2D disks use
/// the same expression.

#include <algorithm>
#include <cmath>
#include <grain/models/concepts.hpp>

namespace grain::area {

struct MorrisPannalaMaHrenya {
  static constexpr Slot slot = Slot::area;
  static constexpr const char* name = "Morris-Pannala-Ma-Hrenya";
  struct Params {};
  template <int D>
  struct History {};
  static void validate(const Params&) {}

  /// Real-material Hertz radius (3 F R*/(4 E*_0))^(1/3) [m] for a force F [N] (F < 0 gives 0).
  static double hertz_radius(const PairProperties& pair, double r_eff, double force) {
    const double e0 = pair.young_real_eff > 0.0 ? pair.young_real_eff : pair.young_eff;
    return std::cbrt(0.75 * std::max(force, 0.0) * r_eff / e0);
  }

  template <int D>
  GRAIN_INLINE static double radius(const ContactGeometry<D>& g, const PairProperties& pair,
                                    const NormalResult& n, const Params&) {
    return hertz_radius(pair, g.r_eff, n.force);
  }
};

} // namespace grain::area
