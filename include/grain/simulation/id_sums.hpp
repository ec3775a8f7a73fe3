#pragma once
/// \file id_sums.hpp
/// The pair loads of a `Simulation` with `grain::sums<grain::by_id>` (core/sums.hpp): written by
/// the contact pass into a share per particle of each pair, then summed per particle in ascending
/// partner id. The incidences (each particle's pairs, sorted by the partner's id) are made once
/// per neighbour list.

#include <grain/core/config.hpp>
#include <grain/core/vector.hpp>
#include <grain/search/neighbor_list.hpp>

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <type_traits>
#include <utility>
#include <vector>

namespace grain::detail {

/// Storage of a simulation that sums by list order: nothing.
struct NoIdSums {
  void invalidate() {}
};

/// The loads of the pairs of a half neighbour list, and their sums per particle in ascending
/// partner id. Each particle has a share per pair it is in (an incidence), its shares in
/// ascending partner id: the contact pass writes a pair's loads into the shares of both its
/// particles, and each particle then adds its own shares in order (a stream, with no test).
///
/// The shares of a pair that does not act are exact zeros (cleared when the pair stops acting),
/// and each sum starts from a value that is not -0 (x + 0.0): adding +0 or -0 to it is then the
/// identity, and so is any number of such terms. A pair listed within the skin only thus leaves
/// every bit as if it were not listed.
/// `Torque`: the contact law makes torques; `Thermal`: heat rates.
template <int D, bool Torque, bool Thermal>
struct IdSums {
  using V = Vec<D>;
  using A = Angular<D>;
  struct NoTorque {};
  struct NoHeat {};
  using TorqueT = std::conditional_t<Torque, A, NoTorque>;
  using HeatT = std::conditional_t<Thermal, double, NoHeat>;
  /// Zero, or nothing for an absent quantity.
  template <class T>
  static T blank() {
    if constexpr (std::is_empty_v<T>)
      return T{};
    else
      return zero<T>();
  }
  /// What a pair adds to one of its particles (zeros by default).
  struct Share {
    V force = V::Zero();                                     ///< [N]
    [[no_unique_address]] TorqueT torque = blank<TorqueT>(); ///< [N m]
    [[no_unique_address]] HeatT heat = blank<HeatT>();       ///< [W]
  };
  /// What the shares of list entry e hold.
  enum Acts : std::uint8_t {
    nothing = 0,   ///< zeros: the pair is apart
    contact = 1,   ///< the contact law acted: force, torques (and heat)
    heat_only = 2, ///< conduction across a gap: heat only (the force and torque are zeros)
  };

  std::vector<std::uint8_t> acts;   ///< per list entry, an Acts
  std::vector<std::uint32_t> first; ///< particle k's shares are [first[k], first[k + 1])
  std::vector<Share> shares;        ///< per incidence, in that order
  /// Per list entry e: the incidence of its row [2 e] and of its partner [2 e + 1].
  std::vector<std::uint32_t> where;
  bool stale = true; ///< the incidences must be made anew (a new neighbour list)

  void invalidate() { stale = true; }

  /// Notes what entry e holds now (`now`, an Acts); clears its shares if it held something else.
  GRAIN_INLINE void acts_now(std::uint32_t e, std::uint8_t now) {
    const std::uint8_t was = acts[e];
    acts[e] = now;
    if (was != now && was != nothing) [[unlikely]]
      clear(e);
  }
  /// Clears both shares of entry e.
  [[gnu::noinline]] void clear(std::uint32_t e) {
    shares[where[2 * std::size_t{e}]] = Share{};
    shares[where[2 * std::size_t{e} + 1]] = Share{};
  }
  /// The shares of entry e for its particles i and j (`i_is_row`: i is the entry's row).
  GRAIN_INLINE std::pair<Share&, Share&> shares_of(std::uint32_t e, bool i_is_row) {
    Share& row = shares[where[2 * std::size_t{e}]];
    Share& partner = shares[where[2 * std::size_t{e} + 1]];
    if (i_is_row) return {row, partner};
    return {partner, row};
  }

  /// Makes the incidences of `list` if they are stale (ids: the particles' ids), each particle's
  /// sorted by the partner's id.
  void prepare(const NeighborList& list, const std::vector<std::int64_t>& id, long threshold) {
    const std::size_t entries = list.partners.size();
    if (!stale && first.size() == list.rows() + 1 && where.size() == 2 * entries) return;
    stale = false;
    acts.assign(entries, nothing);
    const std::size_t n = list.rows();
    first.assign(n + 1, 0);
    for (std::size_t i = 0; i < n; ++i) {
      first[i + 1] += list.offsets[i + 1] - list.offsets[i];
      for (const auto e : list.pair_entries(i))
        ++first[list.partners[e] + 1];
    }
    for (std::size_t i = 0; i < n; ++i)
      first[i + 1] += first[i];
    // (partner id, 2 e + side), sorted per particle by the partner's id
    std::vector<std::pair<std::int64_t, std::uint32_t>> items(2 * entries);
    std::vector<std::uint32_t> next(first.begin(), first.end() - 1);
    for (std::size_t i = 0; i < n; ++i)
      for (const auto e : list.pair_entries(i)) {
        const auto j = list.partners[e];
        items[next[i]++] = {id[j], 2 * e};
        items[next[j]++] = {id[i], 2 * e + 1};
      }
    shares.assign(2 * entries, Share{});
    where.resize(2 * entries);
    const long nl = static_cast<long>(n);
#pragma omp parallel for schedule(static) if (nl >= threshold)
    for (long k = 0; k < nl; ++k) {
      const auto b = items.begin() + first[static_cast<std::size_t>(k)];
      const auto e = items.begin() + first[static_cast<std::size_t>(k) + 1];
      std::sort(b, e, [](const auto& x, const auto& y) { return x.first < y.first; });
      for (auto it = b; it != e; ++it) {
        const auto c = static_cast<std::uint32_t>(it - items.begin());
        where[it->second] = c;
      }
    }
  }

  /// Particle k's pair loads, added to its force f, torque t and heat rate q (with `heat`) in
  /// ascending partner id; each sum first made +0 if it is -0.
  template <class T>
  GRAIN_INLINE void add(std::size_t k, V& f, T& t, double& q, bool heat) const {
    const Share* share = shares.data() + first[k];
    const std::uint32_t count = first[k + 1] - first[k];
    V fk = f + V::Zero();
    for (std::uint32_t c = 0; c < count; ++c)
      fk += share[c].force;
    f = fk;
    if constexpr (Torque) {
      T tk = t + zero<T>();
      for (std::uint32_t c = 0; c < count; ++c)
        tk += share[c].torque;
      t = tk;
    }
    if constexpr (Thermal) {
      if (heat) {
        double qk = q + 0.0;
        for (std::uint32_t c = 0; c < count; ++c)
          qk += share[c].heat;
        q = qk;
      }
    }
    (void)t, (void)q, (void)heat;
  }
};

} // namespace grain::detail
