#pragma once
/// \file contact_pass.hpp
/// The contact pass of a Simulation: the loads (forces, torques, heat rates) of every contact of
/// the neighbour list at one time, then the global loads (gravity, damping, convection,
/// prescribed loads, restraints). Pair entries are evaluated row by row in deterministic chunks
/// (see `compute_forces`), so the sums are bit-identical for any number of threads; the data of
/// rows ahead are requested early when a list span does not fit in the caches.
///
/// A component of `Simulation` (simulation.hpp): static functions over the simulation's state,
/// which declares it a friend; nothing here is virtual or stored.

#include <grain/contact/geometry.hpp>
#include <grain/contact/history.hpp>
#include <grain/core/config.hpp>
#include <grain/core/error.hpp>
#include <grain/core/vector.hpp>
#include <grain/search/neighbor_list.hpp>
#include <grain/simulation/components.hpp>
#include <grain/simulation/parallel.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <tuple>
#include <type_traits>
#include <vector>

namespace grain::detail {

template <class Sim>
struct ContactPass {
  using Contact = typename Sim::contact_type;
  using V = typename Sim::V;
  using A = typename Sim::A;
  using History = typename Sim::History;
  static constexpr int D = Sim::D;
  static constexpr bool thermal = Sim::thermal;
  static constexpr long parallel_threshold = Sim::parallel_threshold;
  static constexpr bool predicts_velocity = Sim::predicts_velocity;
  static constexpr long prefetch_rows = Sim::prefetch_rows;
  static constexpr double prefetch_span_bytes = Sim::prefetch_span_bytes;
  static constexpr double row_bytes = Sim::row_bytes;
  using Heat = HeatStep<Sim>;
  /// Pair loads kept per entry and summed per particle in ascending partner id (sums<by_id>).
  static constexpr bool by_id = Sim::sums_by_id;

  /// Forces, torques (and heat rates) at time t; `in_step` = called by step() (prescribed motion
  /// of the step is known): the loads start from zero (or from the fused pass's gravity and
  /// damping), the contacts add theirs, then the global and prescribed loads are added.
  static void compute_forces(Sim& s, double t, bool in_step) {
    const bool prefilled = s.prefilled_;
    s.prefilled_ = false;
    start_loads(s, in_step, prefilled);
    contact_loads(s);
    s.wall_loads_.written(!s.walls_.empty());
    add_global_loads(s, t, prefilled);
  }

  /// The velocities the forces see (velocity Verlet: the prediction v(n+1/2) + a(n) dt/2) and
  /// zero loads, unless the fused pass has `prefilled` them; energy tracking starts.
  static void start_loads(Sim& s, bool in_step, bool prefilled) {
    auto& p = s.particles_;
    const long n = static_cast<long>(p.size());
    if constexpr (predicts_velocity) {
      s.vf_.resize(p.size());
      if constexpr (Contact::has_torque) s.wf_.resize(p.size());
    }
    const double half_dt = 0.5 * s.dt_;
    if (!prefilled) { // (an `if` clause would still enter the OpenMP runtime every step)
#pragma omp parallel for schedule(static) if (n >= parallel_threshold)
      for (long i = 0; i < n; ++i) {
        if constexpr (predicts_velocity) {
          s.vf_[i] = p.velocity[i] + (half_dt * p.inv_mass[i]) * p.force[i];
          if constexpr (Contact::has_torque)
            s.wf_[i] = p.omega[i] + (half_dt * p.inv_inertia[i]) * p.torque[i];
        }
        p.force[i] = V::Zero();
        p.torque[i] = zero<A>();
        if constexpr (thermal) p.heat_rate[i] = 0.0;
      }
    }
    if constexpr (predicts_velocity) {
      if (in_step && s.cond_.any_control())
        s.cond_.predict(p, s.vf_, Contact::has_torque ? &s.wf_ : nullptr, s.time_, s.dt_);
    }
    s.tracking_ = s.params_.track_dissipation && in_step;
    if (s.tracking_) s.work_rows_.assign(p.size(), 0.0);
  }

  /// The loads of every entry of the neighbour list, in deterministic chunks of rows
  /// (detail::run_paired_chunks: the same bits for any number of threads). With sums by id, the
  /// rows keep their pair loads per entry (any schedule), and each particle then sums its own.
  static void contact_loads(Sim& s) {
    const long n = static_cast<long>(s.particles_.size());
    const auto& list = s.list_;
    if constexpr (by_id) {
      s.id_sums_.prepare(list, s.particles_.id, parallel_threshold);
      const long span = static_cast<long>(list.max_span);
      const long ahead =
          static_cast<double>(span) * row_bytes > prefetch_span_bytes ? prefetch_rows : n;
      const long chunk = std::max((n + 63) / 64, 1L);
      const long nchunks = (n + chunk - 1) / chunk;
#pragma omp parallel for schedule(static) if (n >= parallel_threshold)
      for (long c = 0; c < nchunks; ++c)
        contact_rows(s, c * chunk, std::min(n, (c + 1) * chunk), ahead, span);
      sum_by_id(s);
      return;
    }
    // deterministic chunks: the chunk length depends on N and the list span only. At least a
    // span (the rows of chunk c then write to chunks c and c + 1 only); two spans while that
    // leaves 16 chunks or more (the rows of a chunk's last span have partners beyond it, which
    // come from memory; fewer such rows measured 2 to 4 % faster at N = 1e5); at most 64 chunks.
    // periodic boundaries: the pairs across the slowest axis of the order (rows [0, ring_rows_)
    // to rows [ring_from_, N)) are left out of the span and of the chunks: they are evaluated
    // after them (ring_contacts)
    const long span = static_cast<long>(s.periodic_.on ? s.near_span_ : list.max_span);
    long chunk = std::max({span, std::min(2 * span, (n + 15) / 16), (n + 63) / 64, 1L});
    // periodic boundaries: the pairs across a periodic middle axis lie about two slabs apart,
    // which leaves few chunks; an even number of them (from 6 up) shares out evenly between
    // two threads (measured 6 % faster at N = 1e4 on two threads)
    if (const long even = (n / chunk) & ~1L; s.periodic_.on && even >= 6)
      chunk = std::max(chunk, (n + even - 1) / even);
    // the rows' own data and the partners beyond the chunk are requested some rows in advance
    // if a span of particle data is too large for the caches (a layer of cells in 3D); with
    // partners close by (a 2D row of cells) all of it is in the caches already
    const long ahead =
        static_cast<double>(span) * row_bytes > prefetch_span_bytes ? prefetch_rows : n;
    auto work = [&](long b, long e) { // entries and rows of rows [b, e)
      return static_cast<double>(list.offsets[e] - list.offsets[b]) +
             static_cast<double>(list.wall_offsets[e] - list.wall_offsets[b]) +
             static_cast<double>(e - b);
    };
    detail::run_paired_chunks(
        n, chunk, work, [&](long b, long e) { contact_rows(s, b, e, ahead, span); },
        n >= parallel_threshold);
    if (s.ring_rows_ > 0) ring_contacts(s);
  }

  /// Sums by id: adds to each particle's loads (its start value and its walls) the loads of its
  /// pairs, in ascending partner id.
  static void sum_by_id(Sim& s) {
    auto& p = s.particles_;
    const long n = static_cast<long>(p.size());
    const bool heat = thermal && s.heat_on_;
#pragma omp parallel for schedule(static) if (n >= parallel_threshold)
    for (long kk = 0; kk < n; ++kk) {
      const auto k = static_cast<std::size_t>(kk);
      V f = p.force[k];
      A t = p.torque[k];
      double q = 0.0;
      if constexpr (thermal) q = p.heat_rate[k];
      s.id_sums_.add(k, f, t, q, heat);
      p.force[k] = f;
      p.torque[k] = t;
      if constexpr (thermal) p.heat_rate[k] = q;
    }
  }

  /// Adds gravity and global damping (unless the fused pass has `prefilled` them), convection,
  /// radiation,
  /// the prescribed loads and heat of groups, and removes the restrained components.
  static void add_global_loads(Sim& s, double t, bool prefilled) {
    auto& p = s.particles_;
    const long n = static_cast<long>(p.size());
    const auto loads = s.global_loads(t);
    const V g = std::get<0>(loads);
    const double ct = std::get<1>(loads), cr = std::get<2>(loads);
    const bool spins = s.spins_(); // rotational damping acts wherever angular velocities move
    if (s.tracking_) damping_work(s, t, ct, cr, spins);
    if (prefilled) {
      // gravity and global damping are already in the force arrays (fused pass)
    } else if (!s.mass_damping_) {
#pragma omp parallel for schedule(static) if (n >= parallel_threshold)
      for (long i = 0; i < n; ++i) {
        p.force[i] += p.mass[i] * g - ct * s.force_velocity()[i];
        if (spins) p.torque[i] -= cr * s.force_omega()[i];
      }
    } else {
      const V dv = s.mass_damping_->first(t);
      const A dw = s.mass_damping_->second(t);
#pragma omp parallel for schedule(static) if (n >= parallel_threshold)
      for (long i = 0; i < n; ++i) {
        const V& v = s.force_velocity()[i];
        p.force[i] += p.mass[i] * (g - dv.cwiseProduct(v)) - ct * v;
        if (spins) {
          const A& w = s.force_omega()[i];
          if constexpr (D == 2)
            p.torque[i] -= cr * w + p.inertia[i] * dw * w;
          else
            p.torque[i] -= cr * w + p.inertia[i] * dw.cwiseProduct(w);
        }
      }
    }
    if (s.heat_on_) {
      Heat::add_convection(s);
      RadiationStep<Sim>::add(s);
    }
    if (s.cond_.any_prescribed()) {
      s.cond_.add_loads(p, t);
      if constexpr (thermal)
        if (s.heat_on_) s.cond_.add_heat(p, t, [&](double r) { return s.surface_area(r); });
    }
    if (s.cond_.any_control()) s.cond_.restrain_loads(p);
  }

  /// Energy tracking: adds the power of the global damping (negative: it removes energy) to the
  /// rows' power and the work of the step to the total.
  static void damping_work(Sim& s, double t, double ct, double cr, bool spins) {
    const auto& p = s.particles_;
    const long n = static_cast<long>(p.size());
    const V dv = s.mass_damping_ ? V(s.mass_damping_->first(t)) : V(V::Zero());
    const A dw = s.mass_damping_ ? A(s.mass_damping_->second(t)) : zero<A>();
    for (long i = 0; i < n; ++i) {
      const V& v = s.force_velocity()[i];
      double w = -ct * v.squaredNorm() - p.mass[i] * v.dot(dv.cwiseProduct(v));
      if (spins) {
        const A& o = s.force_omega()[i];
        if constexpr (D == 2)
          w -= cr * o * o + p.inertia[i] * dw * o * o;
        else
          w -= cr * o.squaredNorm() + p.inertia[i] * o.dot(dw.cwiseProduct(o));
      }
      s.work_rows_[static_cast<std::size_t>(i)] += w;
    }
    double sum = 0.0;
    for (double w : s.work_rows_)
      sum += w;
    s.work_in_ += sum * s.dt_;
  }

  /// What the contact law of a list entry reads: the effective properties of the pair (per entry
  /// with variable properties) and its resolved contact parameters. Every evaluation of a
  /// contact (this pass, the conductances across gaps, for_each_contact, for_each_conductance)
  /// takes them from `pair_law` or `wall_law`, and calls `evaluate` and `conductance`.
  struct Law {
    const PairProperties& pair;
    const typename Contact::Params& params;
  };
  /// The law of pair entry e, between particles i and j.
  GRAIN_INLINE static Law pair_law(const Sim& s, std::size_t e, std::size_t i, std::size_t j) {
    const auto& p = s.particles_;
    // one material: one pair type (the materials of the particles need not be read)
    const std::size_t k = s.table_.size() == 1 ? 0 : s.table_.index(p.material[i], p.material[j]);
    return {s.vprops_.per_particle ? s.pair_cache_[e] : s.table_.properties(k),
            s.table_.resolved(k)};
  }
  /// The law of wall entry e, between particle i and wall w.
  GRAIN_INLINE static Law wall_law(const Sim& s, std::size_t e, std::size_t i, std::size_t w) {
    const std::size_t k = s.table_.size() == 1 ? 0
                                               : s.table_.index(s.particles_.material[i],
                                                                s.walls_[w].options.material);
    return {s.vprops_.per_particle ? s.wall_pair_cache_[e] : s.table_.properties(k),
            s.table_.resolved(k)};
  }
  /// The contact law at geometry g; advances the history h.
  GRAIN_INLINE static auto evaluate(const Sim& s, const ContactGeometry<D>& g, const Law& law,
                                    History& h) {
    return Contact::evaluate(g, law.pair, law.params, h, s.dt_);
  }
  /// The conductance [W/K] of a touching contact with result r of `evaluate`.
  template <class R>
  GRAIN_INLINE static double conductance(const Sim& s, const ContactGeometry<D>& g, const Law& law,
                                         const R& r, History& h, double cell_radius) {
    return Contact::conductance(g, law.pair, r.normal, law.params, h, s.dt_, Heat::length(s),
                                cell_radius);
  }

  /// The particles of the pair of row i and partner j in the order its law and history take them:
  /// (i, j), or with sums by id the particle of lower id first.
  GRAIN_INLINE static std::pair<std::size_t, std::size_t> oriented(const Sim& s, std::size_t i,
                                                                   std::size_t j) {
    if constexpr (by_id)
      if (s.particles_.id[j] < s.particles_.id[i]) return {j, i};
    (void)s;
    return {i, j};
  }

  /// Geometry of pair (i, j) if it touches, with the velocities `v`, `w` (by default the
  /// particles' own).
  GRAIN_INLINE static bool touching_pair(const Sim& s, std::size_t i, std::size_t j,
                                         ContactGeometry<D>& g, const std::vector<V>& v,
                                         const std::vector<A>& w) {
    const auto& p = s.particles_;
    const double rs = p.radius[i] + p.radius[j];
    if (s.separation(i, j).squaredNorm() >= rs * rs) return false;
    pair_geometry_of(s, i, j, g, v, w);
    return true;
  }
  static bool touching_pair(const Sim& s, std::size_t i, std::size_t j, ContactGeometry<D>& g) {
    return touching_pair(s, i, j, g, s.particles_.velocity, s.particles_.omega);
  }
  /// Geometry of pair (i, j), which touches, with the velocities `v`, `w`.
  /// `entry` (if >= 0): the list entry of the pair, whose partner's image was found at the list
  /// build (image_code_): its shift is taken off instead of finding the nearest image again (the
  /// same bits).
  GRAIN_INLINE static void pair_geometry_of(const Sim& s, std::size_t i, std::size_t j,
                                            ContactGeometry<D>& g, const std::vector<V>& v,
                                            const std::vector<A>& w, long entry = -1) {
    const auto& p = s.particles_;
    V d = p.position[j] - p.position[i];
    const V* vj = &v[j];
    V vj_image;
    if (s.periodic_.on) [[unlikely]] { // the nearest image of j
      if (!s.periodic_.sheared() && entry >= 0) [[likely]] {
        // the shift is that of the row's partner: taken off x_partner - x_row, added to the other
        const V& shift = s.image_shift_[s.image_code_[static_cast<std::size_t>(entry)]];
        if (i < j) // (the row is the lower index of a half list)
          d -= shift;
        else
          d += shift;
      } else if (!s.periodic_.sheared()) {
        d = PeriodicBox<D>::minimum_image(d, s.periodic_.wrap_length, s.periodic_.wrap_inverse);
      } else if (nearest_image(s, d, v[j], vj_image)) // out of line: a sliding image
        vj = &vj_image;
    }
    const double dist = std::sqrt(d.squaredNorm());
    pair_geometry<D>(g, p.position[i], V(d * (1.0 / dist)), dist, p.radius[i], p.radius[j],
                     p.mass[i], p.mass[j], v[i], *vj, w[i], w[j]);
    if (s.has_fixed_) [[unlikely]] // out of line: the contact pass stays as without the check
      g.m_eff = effective_mass(s, i, j, g.m_eff);
  }
  /// Turns the separation d = x_j - x_i into that of the nearest image of j; true if that image
  /// slides (Lees-Edwards), its velocity then in `vj_image` (vj plus the sliding speed).
  [[gnu::noinline]] static bool nearest_image(const Sim& s, V& d, const V& vj, V& vj_image) {
    double image_vx = 0.0;
    d = s.periodic_.nearest(d, image_vx);
    if (image_vx == 0.0) return false;
    vj_image = vj;
    vj_image[0] += image_vx;
    return true;
  }
  /// The velocity of particle j's image that pair (i, j) sees [m/s]: v[j], plus the sliding
  /// speed of a Lees-Edwards image.
  GRAIN_INLINE static const V& partner_velocity(const Sim& s, std::size_t i, std::size_t j,
                                                const std::vector<V>& v, V& image) {
    if (!s.periodic_.sheared()) [[likely]]
      return v[j];
    V d = s.particles_.position[j] - s.particles_.position[i];
    return nearest_image(s, d, v[j], image) ? image : v[j];
  }
  /// Geometry of the contact of particle i with wall k if they touch, with the velocities `v`,
  /// `w` (by default the particles' own).
  GRAIN_INLINE static bool touching_wall(const Sim& s, std::size_t i, std::size_t k,
                                         ContactGeometry<D>& g, const std::vector<V>& v,
                                         const std::vector<A>& w) {
    const auto& p = s.particles_;
    const auto prox = s.walls_[k].proximity(p.position[i]);
    if (prox.distance >= p.radius[i]) return false;
    wall_geometry<D>(g, s.walls_[k], prox, p.position[i], p.radius[i], p.mass[i], v[i], w[i]);
    return true;
  }
  static bool touching_wall(const Sim& s, std::size_t i, std::size_t k, ContactGeometry<D>& g) {
    return touching_wall(s, i, k, g, s.particles_.velocity, s.particles_.omega);
  }
  /// Geometry of pair (i, j) if the contact law acts on it: touching, or within the reach of an
  /// adhesive normal model across a gap (`Contact::cohesive`; the overlap is then negative).
  static bool acting_pair(const Sim& s, std::size_t i, std::size_t j, ContactGeometry<D>& g) {
    if constexpr (Contact::cohesive) {
      const auto& p = s.particles_;
      const double rs = p.radius[i] + p.radius[j] + s.gap_reach_;
      if (s.separation(i, j).squaredNorm() >= rs * rs) return false;
      pair_geometry_of(s, i, j, g, p.velocity, p.omega);
      return true;
    } else {
      return touching_pair(s, i, j, g);
    }
  }
  /// Geometry of the contact of particle i with wall k if the contact law acts on it (as
  /// acting_pair), with the velocities `v`, `w`.
  GRAIN_INLINE static bool acting_wall(const Sim& s, std::size_t i, std::size_t k,
                                       ContactGeometry<D>& g, const std::vector<V>& v,
                                       const std::vector<A>& w) {
    if constexpr (Contact::cohesive) {
      const auto& p = s.particles_;
      const auto prox = s.walls_[k].proximity(p.position[i]);
      if (prox.distance >= p.radius[i] + s.gap_reach_) return false;
      wall_geometry<D>(g, s.walls_[k], prox, p.position[i], p.radius[i], p.mass[i], v[i], w[i]);
      return true;
    } else {
      return touching_wall(s, i, k, g, v, w);
    }
  }
  static bool acting_wall(const Sim& s, std::size_t i, std::size_t k, ContactGeometry<D>& g) {
    return acting_wall(s, i, k, g, s.particles_.velocity, s.particles_.omega);
  }
  /// Effective mass of the contact of particles i and j [kg]: m_i m_j / (m_i + m_j) (m_eff), or
  /// the free partner's mass if the other is fixed (an infinite mass, as against a wall; the
  /// restitution-based damping of the contact laws then gives the restitution asked for).
  [[gnu::noinline]] static double effective_mass(const Sim& s, std::size_t i, std::size_t j,
                                                 double m_eff) {
    const bool fi = s.fixed_particle(i), fj = s.fixed_particle(j);
    if (fi == fj) return m_eff;
    return fi ? s.particles_.mass[j] : s.particles_.mass[i];
  }
  /// Notes whether some particle is fixed (the geometry then checks each touching pair).
  static void find_fixed(Sim& s) {
    s.has_fixed_ = false;
    for (std::size_t i = 0; i < s.particles_.size() && !s.has_fixed_; ++i)
      s.has_fixed_ = s.fixed_particle(i);
  }

  /// Requests the data that row i reads of its partners at or beyond `end` (the next chunk's
  /// particles, not yet rows in this sweep), so that their cache misses overlap with the work of
  /// the rows before it. Read intent only: a partner may belong to another thread's chunk.
  GRAIN_INLINE static void prefetch_row(const Sim& s, std::size_t i, std::size_t end) {
    for (const auto e : s.list_.pair_entries(i)) {
      const auto j = s.list_.partners[e];
      if (j >= end) prefetch_particle<0>(s, j);
    }
  }

  /// Requests the data of row i itself: its particle's state and loads, the start of its list
  /// entries and histories. These are sequential streams, but a row reads a dozen of them at
  /// once, more than the hardware prefetchers follow: at N = 1e6 (from memory) they stalled the
  /// rows (docs/performance.md).
  GRAIN_INLINE static void prefetch_own(const Sim& s, std::size_t i) {
    prefetch_particle<1>(s, i);
    const auto e = s.list_.offsets[i]; // may be the end of the list (no entries left)
    GRAIN_PREFETCH(s.list_.partners.data() + e, 0);
    if constexpr (!Contact::template stateless<D>) {
      GRAIN_PREFETCH(s.hist_.pair.data() + e, 1);
      GRAIN_PREFETCH(s.hist_.pair.data() + std::min<std::size_t>(e + 2, s.hist_.pair.size()), 1);
    }
    // the rows' offsets into the list (read here, further ahead) and into the wall entries
    GRAIN_PREFETCH(s.list_.offsets.data() + (i >= 2 * prefetch_rows ? i - 2 * prefetch_rows : 0),
                   0);
    GRAIN_PREFETCH(s.list_.wall_offsets.data() + i, 0);
  }

  /// The requests made at row ii of the rows [begin, end) of a chunk, run downwards: the own data
  /// of the row 2 x `ahead` rows further down, and the partners beyond the chunk of the row
  /// `ahead` rows further down if it is at or above `cold` (none below the chunk's first row).
  GRAIN_INLINE static void request_ahead(const Sim& s, long ii, long ahead, long begin, long cold,
                                         long end) {
    if (ii - ahead >= begin) {
      if (ii - ahead >= cold)
        prefetch_row(s, static_cast<std::size_t>(ii - ahead), static_cast<std::size_t>(end));
      if (ii - 2 * ahead >= begin) prefetch_own(s, static_cast<std::size_t>(ii - 2 * ahead));
    }
  }

  /// Requests what a contact reads of particle k, with write intent (Write = 1, a row's own
  /// particle) for the loads it adds. A request changes no data: near a chunk's end the row
  /// ahead may be another thread's, which costs at most a cache line moved between cores.
  template <int Write>
  GRAIN_INLINE static void prefetch_particle(const Sim& s, std::size_t k) {
    const auto& p = s.particles_;
    GRAIN_PREFETCH(&p.position[k], 0);
    GRAIN_PREFETCH(&p.material[k], 0);
    GRAIN_PREFETCH(&p.radius[k], 0);
    GRAIN_PREFETCH(&s.force_velocity()[k], 0);
    GRAIN_PREFETCH(&p.force[k], Write);
    if constexpr (Contact::has_torque) {
      GRAIN_PREFETCH(&s.force_omega()[k], 0);
      GRAIN_PREFETCH(&p.torque[k], Write);
    }
    GRAIN_PREFETCH(&p.mass[k], 0);
    if constexpr (thermal) {
      if (s.heat_on_) {
        GRAIN_PREFETCH(&p.temperature[k], 0);
        GRAIN_PREFETCH(&p.heat_rate[k], Write);
      }
    }
  }

  /// The contact of list entry e between particles `row` and `partner` (partner > row), which
  /// touch: geometry, contact law, loads added to both (and heat); with sums by id, kept in the
  /// entry's load.
  GRAIN_INLINE static void pair_contact(Sim& s, std::uint32_t e, std::size_t row,
                                        std::uint32_t partner) {
    auto& p = s.particles_;
    const auto& vf = s.force_velocity();
    const auto& wf = s.force_omega();
    const auto [i, j] = oriented(s, row, partner);
    ContactGeometry<D> gc; // local to the contact: kept in registers
    pair_geometry_of(s, i, j, gc, vf, wf, static_cast<long>(e));
    if constexpr (predicts_velocity && Contact::has_torque) {
      V image;
      set_slip_velocity<D>(gc, p.velocity[i], partner_velocity(s, i, j, p.velocity, image),
                           p.omega[i], p.omega[j]);
    }
    const Law law = pair_law(s, e, i, j);
    History& h = s.hist(s.hist_.pair, e);
    auto r = evaluate(s, gc, law, h);
    if constexpr (by_id) {
      auto [si, sj] = s.id_sums_.shares_of(e, i == row);
      si.force = r.force;
      sj.force = -r.force; // (adding it is subtracting r.force: the same bits)
      if constexpr (Contact::has_torque) {
        si.torque = r.torque_i;
        sj.torque = r.torque_j;
      }
    } else {
      p.force[i] += r.force;
      p.force[j] -= r.force;
      if constexpr (Contact::has_torque) {
        p.torque[i] += r.torque_i;
        p.torque[j] += r.torque_j;
      }
    }
    if (s.tracking_) {
      V image;
      double work = r.force.dot(vf[i] - partner_velocity(s, i, j, vf, image));
      if constexpr (Contact::has_torque) work += dot(r.torque_i, wf[i]) + dot(r.torque_j, wf[j]);
      s.work_rows_[row] += work;
    }
    if constexpr (thermal) {
      if (s.heat_on_) {
        double H;
        if constexpr (Contact::cohesive && Contact::indirect) {
          // an adhesive pair bonded across a gap conducts as any pair across a gap
          ContactGeometry<D> gg;
          H = gc.overlap > 0.0 ? conductance(s, gc, law, r, h, Heat::cell_radius_pair(s, e))
                               : Heat::gap_pair_conductance(s, i, j, e, gg);
        } else {
          H = conductance(s, gc, law, r, h, Heat::cell_radius_pair(s, e));
        }
        const double q = H * (p.temperature[j] - p.temperature[i]);
        const double w = Heat::dissipation_heat(s, gc, r);
        if constexpr (by_id) {
          auto [si, sj] = s.id_sums_.shares_of(e, i == row);
          si.heat = q + w;
          sj.heat = w - q;
        } else {
          p.heat_rate[i] += q + w;
          p.heat_rate[j] += w - q;
        }
      }
    }
  }

  /// The wall entries of row i.
  GRAIN_INLINE static void wall_contacts(Sim& s, std::size_t i) {
    if (s.list_.wall_offsets[i] == s.list_.wall_offsets[i + 1]) return; // most rows: no wall
    auto& p = s.particles_;
    const auto& vf = s.force_velocity();
    const auto& wf = s.force_omega();
    [[maybe_unused]] const bool heat = s.heat_on_;
    ContactGeometry<D> g;
    for (const auto e : s.list_.wall_entries(i)) {
      const auto w = s.list_.walls[e];
      if (!acting_wall(s, i, w, g, vf, wf)) {
        if constexpr (!Contact::template stateless<D>) s.hist_.wall[e] = History{};
        s.wall_loads_.entries[e] = {};
        if constexpr (Contact::indirect) {
          if (heat && s.wall_conducts(w))
            p.heat_rate[i] += Heat::gap_wall_conductance(s, i, w, e, g) *
                              (s.walls_[w].temperature - p.temperature[i]);
        }
        continue;
      }
      if constexpr (predicts_velocity && Contact::has_torque)
        set_slip_velocity<D>(g, s.walls_[w], p.velocity[i], p.omega[i]);
      const Law law = wall_law(s, e, i, w);
      History& h = s.hist(s.hist_.wall, e);
      auto r = evaluate(s, g, law, h);
      p.force[i] += r.force;
      if constexpr (Contact::has_torque) {
        p.torque[i] += r.torque_i;
        s.wall_loads_.entries[e] = {r.force, g.point, A(r.torque_i - cross(g.arm_i, r.force))};
      } else {
        s.wall_loads_.entries[e] = {r.force, g.point, zero<A>()};
      }
      if (s.tracking_) {
        double work = r.force.dot(vf[i] - s.walls_[w].velocity_at(g.point));
        if constexpr (Contact::has_torque) work += dot(r.torque_i, wf[i]);
        s.work_rows_[i] += work;
      }
      if constexpr (thermal) {
        if (heat) {
          if (s.wall_conducts(w)) {
            double H;
            if constexpr (Contact::cohesive && Contact::indirect) {
              ContactGeometry<D> gg; // bonded across a gap: as any gap
              H = g.overlap > 0.0 ? conductance(s, g, law, r, h, Heat::cell_radius_wall(s, e))
                                  : Heat::gap_wall_conductance(s, i, w, e, gg);
            } else {
              H = conductance(s, g, law, r, h, Heat::cell_radius_wall(s, e));
            }
            p.heat_rate[i] += H * (s.walls_[w].temperature - p.temperature[i]);
          }
          p.heat_rate[i] += Heat::dissipation_heat(s, g, r);
        }
      }
    }
  }

  /// The contacts of rows [begin, end), from the last row down. Each row's loads are added to
  /// both partners in the order of the list (the same order for any number of threads).
  /// Going down, the partners of a row (j > i) in the chunk were rows a moment ago and are in
  /// the caches: what comes from memory is the rows' own data, as sequential streams, and the
  /// partners beyond the chunk of the rows of its last span (`ahead`: see request_ahead). Going
  /// up instead, every row met a partner a layer of cells ahead for the first time in the step,
  /// through the list (measured 1 to 5 % slower at N = 1e5 and 1e6, docs/performance.md).
  static void contact_rows(Sim& s, long begin, long end, long ahead, long span) {
    const long cold = std::max(begin, end - span); // rows with partners beyond the chunk
    if constexpr (Contact::indirect) {
      rows_with_gaps<false>(s, begin, end, ahead, cold);
    } else {
      // requests ahead only where a chunk is longer than the distance they look ahead; a blank
      // history of zero bytes (the usual one) is told from a live one without reading the blank
      bool zero = true;
      if constexpr (!Contact::template stateless<D>) zero = detail::any_bits(s.blank_history_) == 0;
      if (end - begin > ahead)
        zero ? rows_collected<true, true, false>(s, begin, end, ahead, cold)
             : rows_collected<true, false, false>(s, begin, end, ahead, cold);
      else
        zero ? rows_collected<false, true, false>(s, begin, end, ahead, cold)
             : rows_collected<false, false, false>(s, begin, end, ahead, cold);
    }
  }

  /// Periodic boundaries: the pairs across the slowest axis of the order (the far entries of
  /// rows [0, ring_rows_), whose partners lie in rows [ring_from_, N)), after the chunks, on one
  /// thread (about a layer of cells of pairs): every particle receives them after the pairs of
  /// the chunks, for any number of threads.
  static void ring_contacts(Sim& s) {
    const long rows = static_cast<long>(s.ring_rows_), n = static_cast<long>(s.particles_.size());
    if constexpr (Contact::indirect) {
      rows_with_gaps<true>(s, 0, rows, n, 0);
    } else {
      bool zero = true;
      if constexpr (!Contact::template stateless<D>) zero = detail::any_bits(s.blank_history_) == 0;
      zero ? rows_collected<false, true, true>(s, 0, rows, n, 0)
           : rows_collected<false, false, true>(s, 0, rows, n, 0);
    }
  }

  /// The entries a pass over row i evaluates: all of them, or with periodic boundaries for a
  /// row paired across the slowest axis of the order (i < ring_rows_), those before its far
  /// entries (`Ring` false: the chunks) or its far entries (`Ring` true: ring_contacts).
  template <bool Ring>
  GRAIN_INLINE static std::pair<std::uint32_t, std::uint32_t> row_entries(const Sim& s,
                                                                          std::uint32_t i) {
    std::uint32_t r0 = s.list_.offsets[i], r1 = s.list_.offsets[i + 1];
    if constexpr (Ring) {
      r0 = s.ring_split_[i];
    } else if constexpr (!by_id) { // (sums by id: the chunks evaluate every entry)
      if (i < s.ring_rows_) [[unlikely]]
        r1 = s.ring_split_[i];
    }
    return {r0, r1};
  }

  /// The contact laws of n touching pairs (list entries and their rows) collected by
  /// rows_collected: the one copy of the inlined law pipeline, called once per batch.
  GRAIN_NOINLINE static void pair_contacts(Sim& s, const std::uint32_t* entry,
                                           const std::uint32_t* row, std::uint32_t n) {
    for (std::uint32_t k = 0; k < n; ++k)
      pair_contact(s, entry[k], row[k], s.list_.partners[entry[k]]);
  }
  /// The wall entries of rows [first, last), from the last down.
  GRAIN_NOINLINE static void wall_rows(Sim& s, long first, long last) {
    for (long r = last - 1; r >= first; --r)
      wall_contacts(s, static_cast<std::size_t>(r));
  }

  /// contact_rows with a conduction model that conducts across gaps: row by row, each listed
  /// pair either touches (the contact law) or conducts across its gap (`Ring`: the far entries
  /// of ring_contacts, without the walls).
  template <bool Ring>
  GRAIN_INLINE static void rows_with_gaps(Sim& s, long begin, long end, long ahead, long cold) {
    auto& p = s.particles_;
    ContactGeometry<D> g;
    [[maybe_unused]] const bool heat = s.heat_on_;
    for (long ii = end - 1; ii >= begin; --ii) {
      request_ahead(s, ii, ahead, begin, cold, end);
      const auto i = static_cast<std::size_t>(ii);
      const auto [r0, r1] = row_entries<Ring>(s, static_cast<std::uint32_t>(i));
      for (auto e = r0; e < r1; ++e) {
        const auto j = s.list_.partners[e];
        double rs = p.radius[i] + p.radius[j];
        if constexpr (Contact::cohesive) rs += s.gap_reach_; // the law acts across the gap
        if (s.separation(i, j).squaredNorm() < rs * rs) {
          if constexpr (by_id) s.id_sums_.acts_now(e, s.id_sums_.contact);
          pair_contact(s, e, i, j); // the geometry is made there, once
          continue;
        }
        if constexpr (!Contact::template stateless<D>) s.hist_.pair[e] = History{};
        if (heat) {
          const auto [a, b] = oriented(s, i, j);
          const double H = Heat::gap_pair_conductance(s, a, b, e, g);
          const double q = H * (p.temperature[b] - p.temperature[a]);
          if constexpr (by_id) {
            // a pair out of reach (H = 0) keeps zero shares
            s.id_sums_.acts_now(e, H != 0.0 ? s.id_sums_.heat_only : s.id_sums_.nothing);
            if (H != 0.0) {
              auto [sa, sb] = s.id_sums_.shares_of(e, a == i);
              sa.heat = q;
              sb.heat = -q;
            }
          } else {
            p.heat_rate[a] += q;
            p.heat_rate[b] -= q;
          }
        } else if constexpr (by_id) {
          s.id_sums_.acts_now(e, s.id_sums_.nothing);
        }
      }
      if constexpr (!Ring) wall_contacts(s, i);
    }
  }

  /// contact_rows without conduction across gaps: a branch-free distance test over the entries
  /// of several rows, collecting the touching pairs; then the contact law for all of them in one
  /// loop (its length varies less than that of a row), then the walls of those rows. The history
  /// of a pair that no longer touches is cleared (written only if it is not blank already).
  /// `Ring`: the far entries of ring_contacts, without the walls.
  template <bool Ahead, bool ZeroBlank, bool Ring>
  GRAIN_INLINE static void rows_collected(Sim& s, long begin, long end, long ahead, long cold) {
    auto& p = s.particles_;
    const bool periodic = s.periodic_.on;
    const auto& box = s.periodic_;
    // the image of each entry's partner, found at the list build (NeighbourRebuild::measure_span)
    const std::uint8_t* image_code = s.image_code_.data();
    const V* image_shift = s.image_shift_.data();
    const bool sheared = box.sheared();
    constexpr std::uint32_t capacity = 64;
    std::uint32_t hit_entry[capacity], hit_row[capacity];
    std::uint32_t nhit = 0;
    long last = end; // rows [i, last) have their pairs collected, their walls pending
    auto laws = [&] GRAIN_INLINE_LAMBDA { // the collected pairs
      pair_contacts(s, hit_entry, hit_row, nhit);
      nhit = 0;
    };
    auto flush = [&](long first) GRAIN_INLINE_LAMBDA {
      laws();
      if (!Ring && !s.walls_.empty()) wall_rows(s, first, last);
      last = first;
    };
    // the distance tests of entries [b, b_end) of row i; `images` (std::true_type with periodic
    // boundaries): through the nearest image of the partner. Two loops, so that the one without
    // images is the loop of a simulation without periodic boundaries.
    // the arrays the tests read, held here (not reloaded through the vectors at each entry)
    const std::uint32_t* partners = s.list_.partners.data();
    const V* position = p.position.data();
    const double* radius = p.radius.data();
    [[maybe_unused]] History* hist = s.hist_.pair.data();
    [[maybe_unused]] std::uint8_t* acts = nullptr;
    if constexpr (by_id) acts = s.id_sums_.acts.data();
    auto test_entries = [&](auto images, std::uint32_t b, std::uint32_t b_end, std::uint32_t i,
                            const V& xi, double ri) GRAIN_INLINE_LAMBDA {
      for (auto e = b; e < b_end; ++e) {
        const auto j = partners[e];
        double rs = ri + radius[j];
        if constexpr (Contact::cohesive) rs += s.gap_reach_; // the law acts across the gap
        V d = position[j] - xi;
        if constexpr (decltype(images)::value) {
          if (sheared) [[unlikely]]
            d = box.nearest(d); // sliding images: the nearest one now
          else
            d -= image_shift[image_code[e]]; // the same bits as PeriodicBox::minimum_image
        }
        const bool t = d.squaredNorm() < rs * rs;
        if constexpr (by_id) { // contact (1) or nothing (0); shares cleared when a pair parts
          const std::uint8_t was = acts[e], now = static_cast<std::uint8_t>(t);
          acts[e] = now;
          if (was > now) [[unlikely]]
            s.id_sums_.clear(e);
        }
        hit_entry[nhit] = e;
        hit_row[nhit] = i;
        nhit += t;
        if constexpr (!Contact::template stateless<D>) {
          // no branch on the distance test: clearing a stale history is rare
          const std::uint64_t live = ZeroBlank ? detail::any_bits(hist[e])
                                               : detail::byte_difference(hist[e], s.blank_history_);
          const std::uint64_t stale = live & (std::uint64_t{0} - static_cast<std::uint64_t>(!t));
          if (stale != 0) [[unlikely]]
            hist[e] = s.blank_history_;
        }
      }
    };
    auto test = [&](std::uint32_t b, std::uint32_t b_end, std::uint32_t i, const V& xi, double ri)
                    GRAIN_INLINE_LAMBDA {
                      if (periodic) [[unlikely]]
                        test_entries(std::true_type{}, b, b_end, i, xi, ri);
                      else
                        test_entries(std::false_type{}, b, b_end, i, xi, ri);
                    };
    for (long ii = end - 1; ii >= begin; --ii) {
      if constexpr (Ahead) request_ahead(s, ii, ahead, begin, cold, end);
      const auto i = static_cast<std::uint32_t>(ii);
      const auto [r0, r1] = row_entries<Ring>(s, i);
      const V xi = p.position[i];
      const double ri = p.radius[i];
      if (nhit + (r1 - r0) > capacity) {
        flush(ii + 1);
        if (r1 - r0 > capacity) { // a long row (a large particle among small ones): in blocks
          for (auto b = r0; b < r1; b += capacity) {
            test(b, std::min(r1, b + capacity), i, xi, ri);
            laws();
          }
          continue;
        }
      }
      test(r0, r1, i, xi, ri);
    }
    flush(begin);
  }
};

} // namespace grain::detail
