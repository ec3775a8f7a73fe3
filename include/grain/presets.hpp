#pragma once
/// \file presets.hpp
/// Named combinations of contact models that users reach for. Each is an ordinary
/// `Interaction<...>`; coefficients are set through `Params` as for any other combination.

#include <grain/interaction.hpp>
#include <grain/models/normal/hertz.hpp>
#include <grain/models/normal/linear_spring_dashpot.hpp>
#include <grain/models/normal/walton_braun.hpp>
#include <grain/models/rolling/constant.hpp>
#include <grain/models/rolling/epsd.hpp>
#include <grain/models/tangent/mindlin.hpp>
#include <grain/models/tangent/spring_dashpot_slider.hpp>

namespace grain::presets {

/// Linear spring-dashpot with Coulomb friction (the classic Cundall-Strack contact; LAMMPS and
/// LIGGGHTS "hooke/history").
using LinearCoulomb = Interaction<normal::LinearSpringDashpot, tangent::SpringDashpotSlider>;

/// Hertz-Mindlin with Tsuji damping from the restitution coefficient and Coulomb friction
/// (LIGGGHTS "hertz tangential history").
using HertzMindlin = Interaction<normal::Hertz<>, tangent::Mindlin>;

/// Hertz-Mindlin with Tsuji damping and constant (directional) rolling resistance (Zhou et al.
/// 1999), the usual choice for non-spherical effects of real grains.
using HertzMindlinRolling = Interaction<normal::Hertz<>, tangent::Mindlin, rolling::Constant>;

/// Hertz-Mindlin with Tsuji damping and the elastic-plastic spring-dashpot rolling resistance of
/// Ai et al. (2011), which can hold a particle at rest on a slope.
using HertzMindlinEPSD = Interaction<normal::Hertz<>, tangent::Mindlin, rolling::EPSD>;

/// Walton-Braun elasto-plastic normal force with Coulomb friction.
using WaltonBraunCoulomb = Interaction<normal::WaltonBraun, tangent::SpringDashpotSlider>;

} // namespace grain::presets
