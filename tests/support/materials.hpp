#pragma once
// Materials used by several tests.
#include <grain/particles/material.hpp>

namespace grain::test {

/// The soft material of the impact and obstacle tests: density 2500 kg/m^3, E = 1e7 Pa (with a
/// linear spring of given stiffness it enters only the Rayleigh time of the stability check),
/// Poisson ratio 0.25, the given restitution and friction; name and the other properties are
/// Material's defaults.
inline Material material(double restitution, double friction = 0.0) {
  Material m;
  m.density = 2500.0;
  m.young = 1.0e7;
  m.poisson = 0.25;
  m.restitution = restitution;
  m.friction = friction;
  return m;
}

/// Glass of the thermal tests: density 2500 kg/m^3, E = `young` (70 GPa unless given), real
/// Young's modulus `young_real` (0: the same as E), Poisson ratio 0.25, conductivity 1 W/(m K),
/// heat capacity 800 J/(kg K); restitution and friction are Material's defaults.
inline Material glass(double young = 7e10, double young_real = 0.0) {
  Material m;
  m.name = "glass";
  m.density = 2500.0;
  m.young = young;
  m.young_real = young_real;
  m.poisson = 0.25;
  m.conductivity = 1.0;
  m.heat_capacity = 800.0;
  return m;
}

} // namespace grain::test
