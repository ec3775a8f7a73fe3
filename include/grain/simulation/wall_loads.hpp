#pragma once
/// \file wall_loads.hpp
/// `WallLoads<D>`: what the particles exert on the walls. The contact pass records, per
/// particle-wall entry of the neighbour list, the force on the particle, the contact point and
/// the couple of rolling resistance; the sums per wall (force, torque about the wall's pivot) and
/// the list of touching contacts are made from them lazily, serially in list order (the same
/// bits for any thread count) or in ascending particle id (`id_order`, with sums by id: the same
/// bits for any order of the list), when asked for or before a rebuild replaces the entries.

#include <grain/core/vector.hpp>
#include <grain/search/neighbor_list.hpp>
#include <grain/walls/walls.hpp>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <tuple>
#include <vector>

namespace grain {

template <int D>
class WallLoads {
public:
  using V = Vec<D>;
  using A = Angular<D>;
  /// What a particle-wall list entry exchanged at the last force evaluation: the force on the
  /// particle [N], the contact point [m] and the couple on the particle beyond that of the force
  /// at the point (rolling resistance) [N m]; zero when not touching.
  struct Entry {
    V force = V::Zero();
    V point = V::Zero();
    A couple = zero<A>();
  };
  /// A touching particle-wall contact of the last force evaluation.
  struct Contact {
    std::int64_t id;
    std::uint32_t wall;
    V point, force; ///< contact point [m], force on the wall [N]
  };

  /// One entry per particle-wall entry of the list, written by the contact pass.
  std::vector<Entry> entries;

  /// Zero entries for a list with n wall entries.
  void reset(std::size_t n) { entries.assign(n, Entry{}); }
  /// The entries hold a new force evaluation (when there are walls).
  void written(bool any_wall) { pending_ = any_wall; }
  /// Forgets the sums (after a checkpoint load: zero until the next step).
  void clear(std::size_t n) {
    reset(n);
    pending_ = false;
    force_.clear();
    torque_.clear();
    contacts_.clear();
  }

  /// Sums the entries per wall, if a force evaluation has not been summed yet: in list order,
  /// or in ascending particle id (then wall index) if `id_order`.
  void collect(const NeighborList& list, const std::vector<std::int64_t>& id,
               const std::vector<Wall<D>>& walls, bool id_order = false) const {
    if (!pending_) return;
    pending_ = false;
    force_.assign(walls.size(), V::Zero());
    torque_.assign(walls.size(), zero<A>());
    contacts_.clear();
    touching_.clear();
    for (std::size_t i = 0; i + 1 < list.wall_offsets.size(); ++i)
      for (const auto e : list.wall_entries(i)) {
        const auto& l = entries[e];
        if (l.force == V::Zero() && l.couple == zero<A>()) continue;
        touching_.push_back({id[i], list.walls[e], e});
      }
    if (id_order) std::sort(touching_.begin(), touching_.end());
    for (const auto& [pid, w, e] : touching_) {
      const auto& l = entries[e];
      force_[w] -= l.force;
      torque_[w] -= cross(V(l.point - walls[w].pivot), l.force) + l.couple;
      contacts_.push_back({pid, w, l.point, V(-l.force)});
    }
  }
  /// The force on wall w [N] (zero before the first evaluation); after collect().
  V force(std::size_t w) const { return w < force_.size() ? force_[w] : V(V::Zero()); }
  /// The torque on wall w about its pivot [N m]; after collect().
  A torque(std::size_t w) const { return w < torque_.size() ? torque_[w] : zero<A>(); }
  /// The touching contacts; after collect().
  const std::vector<Contact>& contacts() const { return contacts_; }

private:
  mutable bool pending_ = false;
  mutable std::vector<V> force_;
  mutable std::vector<A> torque_;
  mutable std::vector<Contact> contacts_;
  /// The touching entries of a collect: (particle id, wall, entry).
  mutable std::vector<std::tuple<std::int64_t, std::uint32_t, std::uint32_t>> touching_;
};

} // namespace grain
