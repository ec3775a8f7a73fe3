#pragma once
/// \file rebuild.hpp
/// The neighbour rebuild of a Simulation: when the search says a new list is due (displacements
/// against the skin, or its own schedule), the particles are re-sorted if the search orders
/// them, the search builds the list, pairs a field excludes are dropped, and the contact
/// histories carry over by particle identity; per-entry caches (variable properties, fluid
/// cells) follow the new list.
///
/// A component of `Simulation` (simulation.hpp): static functions over the simulation's state,
/// which declares it a friend.

#include <grain/contact/history.hpp>
#include <grain/core/error.hpp>
#include <grain/core/stages.hpp>
#include <grain/core/vector.hpp>
#include <grain/search/search.hpp>
#include <grain/simulation/components.hpp>
#include <grain/simulation/parallel.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <numeric>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

namespace grain::detail {

template <class Sim>
struct NeighbourRebuild {
  using Contact = typename Sim::contact_type;
  using V = typename Sim::V;
  using A = typename Sim::A;
  using History = typename Sim::History;
  static constexpr int D = Sim::D;
  static constexpr bool thermal = Sim::thermal;
  static constexpr long parallel_threshold = Sim::parallel_threshold;
  using SearchT = typename Sim::search_type;
  using Histories = typename Sim::Histories;
  static constexpr bool excluding_fields = Sim::excluding_fields;
  using Pass = ContactPass<Sim>;
  using Heat = HeatStep<Sim>;

  static void update_neighbors(Sim& s) {
    ++s.steps_since_rebuild_;
    bool far = true;
    if (s.skin_ > 0.0) {
      double d2 = s.prefilled_ ? s.fused_d2_ : -1.0;
      if (d2 < 0.0) {
        d2 = 0.0;
        const auto& x = s.particles_.position;
        const long n = static_cast<long>(x.size());
#pragma omp parallel for reduction(max : d2) schedule(static) if (n >= parallel_threshold)
        for (long i = 0; i < n; ++i)
          d2 = std::max(d2, detail::nan_as_inf((x[i] - s.snapshot_[i]).squaredNorm()));
      }
      const double dp = std::sqrt(d2);
      double dw = 0.0;
      for (const auto& w : s.walls_)
        dw = std::max(dw, w.displacement_since_snapshot(s.reach_));
      // the sliding images of a Lees-Edwards box move the pairs across y like a wall
      const double de = s.periodic_.sheared() ? s.periodic_.travel() : 0.0;
      far = 2.0 * dp + de >= s.skin_ || dp + dw >= s.skin_;
    }
    if (SearchT::due(s.params_.search, s.steps_since_rebuild_, far)) rebuild(s);
  }

  /// Throws naming the first pair of listed particles at the same centre: their contact has no
  /// normal (InputError before the first step, NumericalError later).
  static void require_distinct_centres(const Sim& s) {
    const auto& p = s.particles_;
    for (std::size_t i = 0; i + 1 < s.list_.offsets.size(); ++i)
      for (const auto e : s.list_.pair_entries(i)) {
        const auto j = s.list_.partners[e];
        if (s.separation(i, j) != V::Zero()) [[likely]]
          continue;
        const std::string what = "Simulation: particles " + std::to_string(p.id[i]) + " and " +
                                 std::to_string(p.id[j]) + " have the same centre (" +
                                 detail::vector_text(p.position[i]) +
                                 ") m at t = " + detail::to_text(s.time_) +
                                 " s; their contact has no normal. Valid: distinct centres";
        if (s.initialized_) throw NumericalError(what);
        throw InputError(what);
      }
  }

  static void rebuild(Sim& s) {
    auto& p = s.particles_;
    const std::size_t n = p.size();
    Pass::find_fixed(s);
    s.require_finite_state(); // a non-finite position has no cell
    s.collect_wall_loads();   // the loads of the last evaluation outlive the list entries
    if (s.periodic_.on) wrap(s);
    NeighborList old = std::move(s.list_);
    Histories old_hist = std::move(s.hist_);
    // the new list will be about as long as the old one (one allocation instead of doublings)
    s.list_.partners.reserve(old.partners.size() + old.partners.size() / 16);
    // only the entries with a history are looked up: the others go before the new list is made
    // (the peak memory of a rebuild holds both lists)
    old_hist.shrink_to_contacts(old);
    std::vector<std::uint32_t> perm;
    const double reach = s.skin_ + std::max(s.cutoff_, s.gap_reach_);
    if constexpr (search::Reorders<SearchT, D>) {
      if constexpr (requires {
                      SearchT::order(s.params_.search, p, reach, s.r_max_, &s.periodic_);
                    })
        perm = SearchT::order(s.params_.search, p, reach, s.r_max_,
                              s.periodic_.on ? &s.periodic_ : nullptr);
      else
        perm = SearchT::order(s.params_.search, p, reach, s.r_max_);
      if (!perm.empty()) {
        p.permute(perm);
        s.permute_fields(perm);
        s.vprops_.permute(perm);
        if (s.prefilled_) {
          s.permute_values(s.vf_, perm);
          if constexpr (Contact::has_torque) s.permute_values(s.wf_, perm);
        }
      }
    }
    if constexpr (search::PeriodicSearch<SearchT, D>) {
      if (s.periodic_.on)
        SearchT::build(s.params_.search, p, s.walls_, reach, s.r_max_, s.periodic_, s.list_);
      else
        SearchT::build(s.params_.search, p, s.walls_, reach, s.r_max_, s.list_);
    } else {
      SearchT::build(s.params_.search, p, s.walls_, reach, s.r_max_, s.list_);
    }
    if constexpr (!search::builtin<SearchT>) search::require_valid_list(s.list_, n, SearchT::name);
    if constexpr (excluding_fields) drop_excluded_pairs(s);
    if constexpr (!Contact::needs_cell_radius) // the fluid cells are made from the whole list
      if (s.params_.neighbour_distance_per_particle) drop_distant_pairs(s);
    measure_span(s);
    require_distinct_centres(s);
    // carry the histories of the old list over, by particle identity (origin_ maps the indices
    // after a removal or activation to those of the old list)
    const bool mapped = !s.origin_.empty();
    if (old.rows() == n || (mapped && old.rows() > 0)) {
      auto old_of = [&](std::size_t k) -> std::uint32_t {
        const std::size_t k0 = perm.empty() ? k : perm[k];
        return mapped ? s.origin_[k0] : static_cast<std::uint32_t>(k0);
      };
      // a history is kept in the order of its pair's law: the row first (reversed when the two
      // swap roles), or with sums by id the lower id first (never reversed)
      s.hist_.carry_over(
          old, old_hist, s.list_, old_of,
          [](History& h) {
            if constexpr (!Sim::sums_by_id) Contact::template reverse<D>(h);
            (void)h;
          },
          parallel_threshold);
    } else {
      s.hist_.reset(s.list_);
    }
    s.id_sums_.invalidate();
    ++s.list_generation_;
    s.snapshot_ = p.position;
    s.periodic_.built_slide = s.periodic_.slide;
    s.wall_loads_.reset(s.list_.walls.size());
    // reach of a plane rotation: farthest particle from any wall pivot
    s.reach_ = 0.0;
    for (const auto& w : s.walls_) {
      for (const auto& x : p.position)
        s.reach_ = std::max(s.reach_, (x - w.pivot).norm());
    }
    s.reach_ += 2.0 * s.r_max_ + s.skin_;
    for (auto& w : s.walls_)
      w.take_snapshot();
    s.steps_since_rebuild_ = 0;
    ++s.counters_.rebuilds;
    if (!perm.empty() || !s.origin_.empty()) s.groups_dirty_ = true;
    s.origin_.clear();
    if (s.vprops_.per_particle) refresh_pair_cache(s);
    if (s.heat_on_) Heat::update_cells(s);
  }

  /// With periodic boundaries, what the force loop needs of the list: the span of its chunks,
  /// the largest j - i of the pairs with j - i <= N/2 (`near_span_`), and the rows holding the
  /// others (`ring_rows_`: rows [0, ring_rows_) pair with rows [ring_from_, N) across the slowest
  /// axis of the order); and for each entry the periodic image of its partner (`image_code_`, the shift
  /// `image_shift_[code]` taken off x_j - x_i; fixed until the next build, as positions are only
  /// wrapped at builds; not used under Lees-Edwards, whose images move).
  static void measure_span(Sim& s) {
    s.near_span_ = s.list_.max_span;
    s.ring_rows_ = 0;
    s.ring_from_ = 0;
    s.ring_split_.clear();
    if (!s.periodic_.on) {
      s.image_code_.clear();
      return;
    }
    const auto& box = s.periodic_;
    for (int c = 0; c < 27; ++c) {
      V shift = V::Zero();
      int code = c;
      for (int k = 0; k < D; ++k, code /= 3)
        shift[k] = static_cast<double>(code % 3 - 1) * box.wrap_length[k];
      s.image_shift_[static_cast<std::size_t>(c)] = shift;
    }
    const std::size_t n = s.list_.rows();
    const auto& x = s.particles_.position;
    s.image_code_.resize(s.list_.partners.size());
    std::uint32_t near = 0, ring = 0, ring_from = static_cast<std::uint32_t>(n);
    for (std::size_t i = 0; i < n; ++i)
      for (const auto e : s.list_.pair_entries(i)) {
        const auto j = s.list_.partners[e];
        const auto d = static_cast<std::uint32_t>(j - i);
        if (2 * static_cast<std::size_t>(d) <= n)
          near = std::max(near, d);
        else {
          if (ring <= i) { // the first far entry of row i (its partners ascend)
            s.ring_split_.resize(i + 1, 0);
            for (std::size_t k = ring; k < i; ++k) // rows between without far entries
              s.ring_split_[k] = s.list_.offsets[k + 1];
            s.ring_split_[i] = e;
          }
          ring = static_cast<std::uint32_t>(i + 1);
          ring_from = std::min(ring_from, static_cast<std::uint32_t>(j));
        }
        const V r = x[j] - x[i];
        const V m = PeriodicBox<D>::minimum_image(r, box.wrap_length, box.wrap_inverse);
        int code = 0;
        for (int k = D - 1; k >= 0; --k) // the boxes taken off: (r - m) / L, -1, 0 or 1
          code = 3 * code + 1 +
                 (box.axis[k] ? static_cast<int>(std::lround((r[k] - m[k]) * box.wrap_inverse[k]))
                              : 0);
        s.image_code_[e] = static_cast<std::uint8_t>(code);
      }
    s.near_span_ = near;
    s.ring_rows_ = ring;
    s.ring_from_ = ring_from;
  }

  /// Brings every particle back into the periodic box (PeriodicBox::wrap), counting the boxes
  /// crossed; under Lees-Edwards the velocities the forces see change with the velocities.
  static void wrap(Sim& s) {
    auto& p = s.particles_;
    const bool sheared_prediction = s.periodic_.sheared() && s.prefilled_;
    for (std::size_t i = 0; i < p.size(); ++i) {
      const double vx = p.velocity[i][0];
      if (!s.periodic_.wrap(p.position[i], p.velocity[i], s.image_[i], s.shear_shift_[i])) {
        const std::string what =
            "Simulation: particle " + std::to_string(p.id[i]) + " at position (" +
            detail::vector_text(p.position[i]) +
            ") m is more than 1e9 periodic boxes away at t = " + detail::to_text(s.time_) +
            " s; valid: a position within 1e9 box lengths of the box";
        if (s.initialized_) throw NumericalError(what);
        throw InputError(what);
      }
      if constexpr (Sim::predicts_velocity)
        if (sheared_prediction) s.vf_[i][0] += p.velocity[i][0] - vx;
    }
  }

  /// The build of an initialisation: carries out the removals requested since the last build
  /// (remove_particle before a run), maps the rows of the old list to the current particles
  /// (those added since were appended) so that the histories of the old pairs carry over, and
  /// rebuilds.
  static void initial_build(Sim& s) {
    s.origin_.clear();
    // particles added since the last build were appended: the old rows keep their indices, so
    // the contact histories of the old pairs carry over; particles removed since then are
    // taken out here
    std::vector<std::uint32_t> kept(s.particles_.size());
    std::iota(kept.begin(), kept.end(), 0u);
    const bool renumbered = !s.life_.removal_requests.empty();
    if (renumbered) {
      s.collect_wall_loads(); // before the particles are renumbered
      std::sort(s.life_.removal_requests.begin(), s.life_.removal_requests.end());
      std::erase_if(kept, [&](std::uint32_t i) {
        return std::binary_search(s.life_.removal_requests.begin(), s.life_.removal_requests.end(),
                                  s.particles_.id[i]);
      });
      s.life_.removal_requests.clear();
      keep_particles(s, kept);
    }
    if (s.list_.rows() > 0 && (s.list_.rows() < s.particles_.size() || renumbered)) {
      s.origin_.assign(s.particles_.size(), Sim::none);
      for (std::size_t i = 0; i < kept.size(); ++i)
        if (kept[i] < s.list_.rows()) s.origin_[i] = kept[i];
    }
    rebuild(s);
  }

  /// Keeps the particles `kept` names (ascending old indices), with their fields and pair
  /// overrides, renumbered 0 .. kept.size() - 1.
  static void keep_particles(Sim& s, const std::vector<std::uint32_t>& kept) {
    s.particles_.permute(kept);
    s.permute_fields(kept);
    s.vprops_.permute(kept);
    s.groups_dirty_ = true;
  }

  /// Contact constants of every list entry from the particles' current properties.
  static void refresh_pair_cache(Sim& s) {
    const auto& p = s.particles_;
    const std::size_t n = p.size();
    std::vector<Material> eff(n);
    for (std::size_t i = 0; i < n; ++i)
      eff[i] = s.material_of(i);
    s.pair_cache_.resize(s.list_.partners.size());
    s.wall_pair_cache_.resize(s.list_.walls.size());
    const long nl = static_cast<long>(n);
#pragma omp parallel for schedule(static) if (nl >= parallel_threshold)
    for (long i = 0; i < nl; ++i) {
      const auto mi = p.material[i];
      for (const auto e : s.list_.pair_entries(i)) {
        const auto [a, b] = Pass::oriented(s, static_cast<std::size_t>(i), s.list_.partners[e]);
        s.pair_cache_[e] =
            s.table_.mix_of(eff[a], eff[b], s.table_.index(p.material[a], p.material[b]));
      }
      for (const auto e : s.list_.wall_entries(i)) {
        const auto w = s.list_.walls[e];
        const auto mw = s.walls_[w].options.material;
        s.wall_pair_cache_[e] = s.table_.mix_of(eff[i], s.wall_material(w), s.table_.index(mi, mw));
      }
    }
  }

  /// With models acting across gaps and particles of several sizes, removes the pairs farther
  /// apart than the skin plus the larger of the two particles' neighbour distances (the largest
  /// gap across which the models act on a particle of that radius). Between rebuilds no gap
  /// shrinks by more than the skin, so no pair the models could act on is missing. Particle-wall
  /// rows are kept as built.
  static void drop_distant_pairs(Sim& s) {
    const auto& p = s.particles_;
    const std::size_t n = p.size();
    if (n == 0 || std::max(s.cutoff_, s.gap_reach_) == 0.0) return;
    const auto [lo, hi] = std::minmax_element(p.radius.begin(), p.radius.end());
    if (s.neighbour_distance(*lo) == s.neighbour_distance(*hi)) return; // nothing to drop
    std::vector<double> c(n);
    for (std::size_t i = 0; i < n; ++i)
      c[i] = s.skin_ + s.neighbour_distance(p.radius[i]);
    std::uint32_t out = 0, begin = s.list_.offsets[0];
    for (std::size_t i = 0; i + 1 < s.list_.offsets.size(); ++i) {
      const std::uint32_t end = s.list_.offsets[i + 1];
      for (std::uint32_t e = begin; e < end; ++e) {
        const auto j = s.list_.partners[e];
        const double reach = p.radius[i] + p.radius[j] + std::max(c[i], c[j]);
        if (s.periodic_.separation(p.position[i], p.position[j]).squaredNorm() >= reach * reach)
          continue;
        s.list_.partners[out++] = j;
      }
      begin = end;
      s.list_.offsets[i + 1] = out;
    }
    s.list_.partners.resize(out);
  }

  /// Removes the pairs that a field excludes (two members of the same clump: rigid, they never
  /// act on each other) from the list. The largest index span is kept (an upper bound is all the
  /// chunking needs).
  static void drop_excluded_pairs(Sim& s) {
    auto excluded = [&](std::size_t i, std::size_t j) {
      return std::apply(
          [&](const auto&... f) { return (detail::field_excludes(f[i], f[j]) || ... || false); },
          s.fields_);
    };
    std::uint32_t out = 0, begin = s.list_.offsets[0];
    for (std::size_t i = 0; i + 1 < s.list_.offsets.size(); ++i) {
      const std::uint32_t end = s.list_.offsets[i + 1];
      for (std::uint32_t e = begin; e < end; ++e) {
        const auto j = s.list_.partners[e];
        if (excluded(i, j)) continue;
        s.list_.partners[out++] = j;
      }
      begin = end;
      s.list_.offsets[i + 1] = out;
    }
    s.list_.partners.resize(out);
  }
};

} // namespace grain::detail
