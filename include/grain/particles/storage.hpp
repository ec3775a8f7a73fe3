#pragma once
/// \file storage.hpp
/// Particle data as a structure of arrays: one contiguous array per field.
///
/// Indices into the arrays change when the neighbour search re-sorts particles in space; ids never
/// change. `index_of(id)` maps an id to the current index.

#include <grain/core/vector.hpp>
#include <cstdint>
#include <numeric>
#include <vector>

namespace grain {

/// Per-particle fields of a D-dimensional simulation (SI units).
template <int D>
struct ParticleArrays {
  using V = Vec<D>;
  using A = Angular<D>;
  std::vector<std::int64_t> id;         ///< stable identifier
  std::vector<V> position;              ///< [m]
  std::vector<V> velocity;              ///< [m/s]
  std::vector<A> omega;                 ///< angular velocity [rad/s]
  std::vector<Orientation<D>> orientation;
  std::vector<V> force;                 ///< total force of the current step [N]
  std::vector<A> torque;                ///< total torque of the current step [N m]
  std::vector<double> radius;           ///< [m]
  std::vector<double> mass;             ///< [kg]
  std::vector<double> inv_mass;         ///< [1/kg]; 0 for a particle that does not move
  std::vector<double> inertia;          ///< moment of inertia [kg m^2]
  std::vector<double> inv_inertia;      ///< [1/(kg m^2)]
  std::vector<std::uint32_t> material;  ///< index into the material table

  std::size_t size() const { return id.size(); }

  /// Reorders every field so that new index k holds old index perm[k] (a shorter perm also
  /// removes the particles it does not name).
  void permute(const std::vector<std::uint32_t>& perm) {
    apply(id, perm);
    apply(position, perm);
    apply(velocity, perm);
    apply(omega, perm);
    apply(orientation, perm);
    apply(force, perm);
    apply(torque, perm);
    apply(radius, perm);
    apply(mass, perm);
    apply(inv_mass, perm);
    apply(inertia, perm);
    apply(inv_inertia, perm);
    apply(material, perm);
  }

protected:
  template <class T>
  static void apply(std::vector<T>& v, const std::vector<std::uint32_t>& perm) {
    std::vector<T> out(perm.size());
    for (std::size_t k = 0; k < perm.size(); ++k) out[k] = v[perm[k]];
    v.swap(out);
  }
};

/// Per-particle fields of a simulation with heat transfer: the mechanical fields plus the
/// thermal state. A purely mechanical simulation uses `ParticleArrays` and has none of these.
template <int D>
struct ThermalParticleArrays : ParticleArrays<D> {
  std::vector<double> temperature;       ///< [K]
  std::vector<double> heat_rate;         ///< net heat flow into the particle this step [W]
  std::vector<double> heat_capacity;     ///< thermal inertia C = m c [J/K]
  std::vector<double> inv_heat_capacity; ///< 1/C [K/J]; 0 for a particle at fixed temperature

  /// Reorders every field so that new index k holds old index perm[k].
  void permute(const std::vector<std::uint32_t>& perm) {
    ParticleArrays<D>::permute(perm);
    this->apply(temperature, perm);
    this->apply(heat_rate, perm);
    this->apply(heat_capacity, perm);
    this->apply(inv_heat_capacity, perm);
  }
};

/// True for particle storage with a thermal state.
template <class P>
concept HasTemperature = requires(const P& p) {
  p.temperature;
  p.heat_rate;
};

} // namespace grain
