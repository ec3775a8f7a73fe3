#pragma once
/// \file storage.hpp
/// Particle data as a structure of arrays: one contiguous array per field.
///
/// Indices into the arrays change when the neighbour search re-sorts particles in space; ids never
/// change. `index_of(id)` maps an id to the current index.

#include <cstdint>
#include <grain/core/vector.hpp>
#include <numeric>
#include <vector>

namespace grain {

namespace detail {

/// Reorders v so that new index k holds old index perm[k], in place (no second array: a
/// re-sort of a million particles would otherwise allocate and free one copy per field).
/// `perm` is a permutation of 0 .. v.size() - 1, or an ascending selection (a removal: the
/// particles it does not name go).
template <class T>
void permute_in_place(std::vector<T>& v, const std::vector<std::uint32_t>& perm) {
  if (perm.size() < v.size()) {
    bool ascending = true;
    for (std::size_t k = 1; k < perm.size() && ascending; ++k)
      ascending = perm[k - 1] < perm[k];
    if (ascending) { // perm[k] >= k: a forward copy never overwrites what it still reads
      for (std::size_t k = 0; k < perm.size(); ++k)
        v[k] = v[perm[k]];
      v.resize(perm.size());
      return;
    }
    std::vector<T> out(perm.size());
    for (std::size_t k = 0; k < perm.size(); ++k)
      out[k] = v[perm[k]];
    v.swap(out);
    return;
  }
  // follow each cycle of the permutation once, holding one element aside
  std::vector<bool> done(v.size(), false);
  for (std::size_t s = 0; s < v.size(); ++s) {
    if (done[s]) continue;
    T first = v[s];
    std::size_t k = s;
    for (;;) {
      done[k] = true;
      const std::size_t from = perm[k];
      if (from == s) {
        v[k] = first;
        break;
      }
      v[k] = v[from];
      k = from;
    }
  }
}

} // namespace detail

/// Per-particle fields of a D-dimensional simulation (SI units).
template <int D>
struct ParticleArrays {
  using V = Vec<D>;
  using A = Angular<D>;
  std::vector<std::int64_t> id; ///< stable identifier
  std::vector<V> position;      ///< [m]
  std::vector<V> velocity;      ///< [m/s]
  std::vector<A> omega;         ///< angular velocity [rad/s]
  std::vector<Orientation<D>> orientation;
  std::vector<V> force;                ///< total force of the current step [N]
  std::vector<A> torque;               ///< total torque of the current step [N m]
  std::vector<double> radius;          ///< [m]
  std::vector<double> mass;            ///< [kg]
  std::vector<double> inv_mass;        ///< [1/kg]; 0 for a particle that does not move
  std::vector<double> inertia;         ///< moment of inertia [kg m^2]
  std::vector<double> inv_inertia;     ///< [1/(kg m^2)]
  std::vector<std::uint32_t> material; ///< index into the material table

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
    detail::permute_in_place(v, perm);
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
