#pragma once
/// \file statistics.hpp
/// Statistics of the active particles of a simulation (or of a group, optionally only its free
/// particles): count, total, mean, minimum and maximum of per-particle fields, and counts of
/// particles and contacts.
///
/// | field | per particle | unit |
/// |---|---|---|
/// | `speed` | \|v\| | m/s |
/// | `velocity[d]` | component d of v | m/s |
/// | `acceleration` | \|F\| / m (0 for a fixed particle) | m/s^2 |
/// | `force` | \|F\|, the total force of the last step | N |
/// | `angular_speed` | \|omega\| | rad/s |
/// | `torque` | \|T\| | N m |
/// | `kinetic_energy` | m v^2/2 + I omega^2/2 | J |
/// | `radius`, `mass` | R, m | m, kg |
/// | `height` | last coordinate of the centre (y in 2D, z in 3D) | m |
/// | `temperature`, `heat_rate` | T, Q (thermal simulations; empty otherwise) | K, W |
///
/// A particle is free when it is moved by forces: not `fixed` and not under prescribed motion.
/// ```cpp
/// const auto s = grain::io::statistics(sim);            // every active particle
/// const auto h = grain::io::statistics(sim, "hot", true); // free particles of group "hot"
/// std::printf("%zu particles, mean speed %g m/s\n", s.particles, s.speed.mean);
/// ```

#include <grain/core/vector.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <string>

namespace grain::io {

/// Count, total, mean, minimum and maximum of one field (mean, min, max are NaN when empty).
struct FieldStatistics {
  std::size_t count = 0;
  double total = 0.0;
  double mean = std::numeric_limits<double>::quiet_NaN();
  double min = std::numeric_limits<double>::quiet_NaN();
  double max = std::numeric_limits<double>::quiet_NaN();

  void add(double x) {
    if (count == 0) {
      min = max = x;
    } else {
      min = std::min(min, x);
      max = std::max(max, x);
    }
    ++count;
    total += x;
  }
  void finish() {
    if (count > 0) mean = total / static_cast<double>(count);
  }
};

/// Statistics of a selection of particles at one time.
template <int D>
struct Statistics {
  double time = 0.0; ///< [s]
  long step = 0;
  std::size_t particles = 0;      ///< particles in the selection
  std::size_t free_particles = 0; ///< of which free (moved by forces)
  std::size_t active = 0;         ///< active particles of the whole simulation
  std::size_t inactive = 0;       ///< particles waiting for their creation time
  std::size_t removed = 0;        ///< particles removed so far
  std::size_t contacts = 0;       ///< touching particle-particle contacts (whole simulation)
  std::size_t wall_contacts = 0;  ///< touching particle-wall contacts (whole simulation)
  FieldStatistics speed, acceleration, force, angular_speed, torque, kinetic_energy, radius, mass,
      height, temperature, heat_rate;
  FieldStatistics velocity[D];
};

/// Statistics of the active particles of `group` ("all" by default), only the free ones if
/// `free_only`.
template <class Sim>
Statistics<Sim::dimension> statistics(const Sim& sim, const std::string& group = "all",
                                      bool free_only = false) {
  constexpr int D = Sim::dimension;
  Statistics<D> s;
  s.time = sim.time();
  s.step = sim.step_count();
  s.active = sim.size();
  s.inactive = sim.inactive_count();
  s.removed = sim.removed_ids().size();
  const auto [pp, pw] = sim.contact_counts();
  s.contacts = pp;
  s.wall_contacts = pw;
  const auto& p = sim.particles();
  for (const auto i : sim.group_indices(group)) {
    const bool free = sim.is_free(i);
    if (free_only && !free) continue;
    ++s.particles;
    if (free) ++s.free_particles;
    const auto& v = p.velocity[i];
    s.speed.add(v.norm());
    for (int d = 0; d < D; ++d)
      s.velocity[d].add(v[d]);
    const double f = p.force[i].norm();
    s.force.add(f);
    s.acceleration.add(f * p.inv_mass[i]);
    const double w = std::sqrt(squared_norm(p.omega[i]));
    s.angular_speed.add(w);
    s.torque.add(std::sqrt(squared_norm(p.torque[i])));
    s.kinetic_energy.add(0.5 * p.mass[i] * v.squaredNorm() + 0.5 * p.inertia[i] * w * w);
    s.radius.add(p.radius[i]);
    s.mass.add(p.mass[i]);
    s.height.add(p.position[i][D - 1]);
    if constexpr (Sim::thermal) {
      s.temperature.add(p.temperature[i]);
      s.heat_rate.add(p.heat_rate[i]);
    }
  }
  for (auto* f : {&s.speed, &s.acceleration, &s.force, &s.angular_speed, &s.torque,
                  &s.kinetic_energy, &s.radius, &s.mass, &s.height, &s.temperature, &s.heat_rate})
    f->finish();
  for (auto& f : s.velocity)
    f.finish();
  return s;
}

} // namespace grain::io
