#pragma once
/// \file lu_morris_li_benyahia.hpp
/// Contact-area correction for a softened normal contact law (L. Lu, A. Morris, T. Li,
/// S. Benyahia, Int. J. Heat Mass Transfer 111 (2017) 723), derived for the linear
/// spring-dashpot: the real overlap delta_0 is the one at which the real Hertz contact carries the
/// elastic force of the simulated spring, K_hz,0 delta_0^(3/2) = F_el, and the contact radius is
/// the Hertz radius of that overlap:
///
///   delta_0 = (F_el / K_hz,0)^(2/3),  K_hz,0 = 4/3 E*_0 sqrt(R*)               [m]
///   a'      = sqrt(R* delta_0) = (3 F_el R* / (4 E*_0))^(1/3)                   [m]
///
/// F_el [N] is the elastic part of the normal force of the current step, F_n - eta d(delta)/dt
/// (`NormalResult::force - damping * normal_velocity`; negative values taken as 0): K delta for a
/// linear spring, K_hz delta^(3/2) for Hertz (there delta_0 = (E*/E*_0)^(2/3) delta). R* [m] is the
/// effective radius, E*_0 [Pa] the effective modulus of the real moduli
/// (`PairProperties::young_real_eff`; the simulated `young_eff` if it is not positive). No
/// parameters, no history.
///
/// Relation to the seed program: it writes a' = (K_n a / K_hz,0)^(2/3), the overlap formula above
/// with the contact radius a in place of the overlap delta, and takes the result as the radius.
/// With a Hertz K_n [N/m^(3/2)] (its fallback) that is not even a length. With a linear K_n [N/m]
/// and its lens radius a = sqrt(2 R* delta) it is (3 K_n / (2 E*_0 R*))^(1/3) times the radius
/// given here, e.g. 0.093 for K_n = 1e4 N/m, E*_0 = 37.3 GPa, R* = 0.5 mm. Here the overlap is
/// used, K_n delta = F_el, and a' is the real Hertz radius at the elastic force, the physical
/// target of the correction. It equals `MorrisPannalaMaHrenya` except that the dashpot force is
/// left out: with a damped contact the radius follows the deformation, not the total force (it
/// does not jump at the first touch). With a force clamped at zero (`no_cohesion`) the elastic
/// part read back from the result exceeds the true one in the last steps of a contact.
///
/// Validity: quasi-static elastic contacts of spheres; 2D disks use the same expression.

#include <grain/models/area/morris_pannala_ma_hrenya.hpp>
#include <grain/models/concepts.hpp>

namespace grain::area {

struct LuMorrisLiBenyahia {
  static constexpr Slot slot = Slot::area;
  static constexpr const char* name = "Lu-Morris-Li-Benyahia";
  struct Params {};
  template <int D>
  struct History {};
  static void validate(const Params&) {}

  template <int D>
  GRAIN_INLINE static double radius(const ContactGeometry<D>& g, const PairProperties& pair,
                                    const NormalResult& n, const Params&) {
    const double elastic = n.force - n.damping * g.normal_velocity;
    return MorrisPannalaMaHrenya::hertz_radius(pair, g.r_eff, elastic);
  }
};

} // namespace grain::area
