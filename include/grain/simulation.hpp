#pragma once
/// \file simulation.hpp
/// `Simulation<Shape, Search, Contact, Integrator>`: particles, walls, materials and the solution
/// loop, assembled at compile time with no run-time dispatch.
///
/// One step, in this order:
/// 1. (Verlet only) half kick and drift of particles; walls move;
/// 2. neighbour search: the candidate list is rebuilt if the search says so (never late);
/// 3. per-contact pipeline for particle pairs and particle-wall pairs (forces, torques);
/// 4. global conditions: gravity, translational and rotational damping;
/// 5. integration (Euler family: particles advance, then walls move; Verlet: second half kick);
/// 6. time advances.
///
/// Force accumulation is race-free and deterministic: rows of the half list are cut into chunks
/// whose length depends only on N and on the largest index distance of a pair, never on the
/// number of threads; even chunks run in parallel, then odd ones, so each particle receives its
/// contributions in a fixed order and the results are bit-identical for any thread count.

#include <grain/core/error.hpp>
#include <grain/core/vector.hpp>
#include <grain/integrate/integrators.hpp>
#include <grain/interaction.hpp>
#include <grain/particles/material.hpp>
#include <grain/particles/shape.hpp>
#include <grain/particles/storage.hpp>
#include <grain/search/search.hpp>
#include <grain/walls/walls.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <string>
#include <vector>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace grain {

/// What a particle is made of and where it starts (SI units).
template <int D>
struct ParticleSpec {
  Vec<D> position = Vec<D>::Zero();      ///< centre [m]
  double radius = 0.0;                   ///< [m], > 0
  std::uint32_t material = 0;            ///< index returned by add_material
  Vec<D> velocity = Vec<D>::Zero();      ///< [m/s]
  Angular<D> omega = zero<Angular<D>>(); ///< angular velocity [rad/s]
  bool fixed = false; ///< if true the particle keeps its velocities (forces do not move it)
  std::int64_t id = -1; ///< -1 = next free id
};

/// Global settings of a simulation.
template <int D, class Contact, class SearchT>
struct SimulationParams {
  double time_step = 0.0; ///< [s]; 0 = automatic (auto_time_step_factor x critical step)
  double auto_time_step_factor = 0.1;
  /// Impact velocity [m/s] used to estimate the stiffness of velocity-dependent contact laws in
  /// the critical time step (the largest of this and twice the fastest initial particle speed).
  double reference_velocity = 1.0;
  Vec<D> gravity = Vec<D>::Zero();         ///< [m/s^2]
  double damping_translational = 0.0;      ///< global damping force -c v, c in [N s/m]
  double damping_rotational = 0.0;         ///< global damping torque -c w, c in [N m s]
  typename Contact::Params contact{};      ///< coefficients of the contact models
  typename SearchT::Params search{};       ///< neighbour-search settings
};

/// Summary counters of a run (for the console summary and benchmarks).
struct RunCounters {
  long steps = 0;
  long rebuilds = 0;
  double wall_seconds = 0.0;
  double particle_steps = 0.0;
};

template <class Shape, class SearchT, class Contact, class IntegratorT = integrate::VelocityVerlet>
class Simulation {
  static_assert(ParticleShape<Shape>,
                "grain::Simulation: the 1st argument must be a particle shape, grain::Disk (2D) "
                "or grain::Sphere (3D)");
  static_assert(search::Search<SearchT>,
                "grain::Simulation: the 2nd argument must be a neighbour search, "
                "search::AllPairs, search::VerletList or search::CellList");
  static_assert(integrate::Integrator<IntegratorT>,
                "grain::Simulation: the 4th argument must be an integrator from grain::integrate, "
                "e.g. integrate::VelocityVerlet");

public:
  static constexpr int dimension = Shape::dimension;
  static constexpr int D = dimension;
  using shape_type = Shape;
  using search_type = SearchT;
  using contact_type = Contact;
  using integrator_type = IntegratorT;
  using Params = SimulationParams<D, Contact, SearchT>;
  using History = typename Contact::template History<D>;
  using V = Vec<D>;
  using A = Angular<D>;
  /// Loops over fewer particles than this run on one thread (a parallel region costs more).
  static constexpr long parallel_threshold = 1000;

  explicit Simulation(Params params = {}, Shape shape = {}) : params_(std::move(params)), shape_(shape) {
    shape_.validate();
    Contact::validate(params_.contact);
    SearchT::validate(params_.search);
    for (int d = 0; d < D; ++d)
      detail::require_finite("Simulation", "gravity component", params_.gravity[d]);
    detail::require_non_negative("Simulation", "damping_translational", params_.damping_translational);
    detail::require_non_negative("Simulation", "damping_rotational", params_.damping_rotational);
    detail::require_non_negative("Simulation", "time_step", params_.time_step);
    detail::require_in("Simulation", "auto_time_step_factor", params_.auto_time_step_factor, 1e-6,
                       1.0, "(0, 1]");
    detail::require_positive("Simulation", "reference_velocity", params_.reference_velocity);
  }

  // ---------------------------------------------------------------- set-up
  /// Adds a material; returns its index.
  std::uint32_t add_material(const Material& m) {
    m.validate();
    const auto n0 = materials_.size();
    std::vector<PairOverride> grown((n0 + 1) * (n0 + 1));
    for (std::size_t a = 0; a < n0; ++a)
      for (std::size_t b = 0; b < n0; ++b) grown[a * (n0 + 1) + b] = overrides_[a * n0 + b];
    overrides_.swap(grown);
    materials_.push_back(m);
    update_pairs();
    initialized_ = false;
    return static_cast<std::uint32_t>(materials_.size() - 1);
  }
  /// Overrides mixed restitution / friction for one pair of materials.
  void set_pair(std::uint32_t a, std::uint32_t b, const PairOverride& o) {
    check_material(a, "set_pair");
    check_material(b, "set_pair");
    const auto n = materials_.size();
    overrides_[a * n + b] = overrides_[b * n + a] = o;
    update_pairs();
    initialized_ = false;
  }

  /// Adds a particle; returns its id. Throws InputError on bad input.
  std::int64_t add_particle(const ParticleSpec<D>& s) {
    const std::int64_t id = s.id >= 0 ? s.id : next_id_;
    const std::string obj = std::string(Shape::name) + " particle " + std::to_string(id);
    detail::require(all_finite(s.position), obj, "position", to_text(s.position), "finite coordinates");
    detail::require_positive(obj, "radius", s.radius);
    detail::require(all_finite(s.velocity), obj, "velocity", to_text(s.velocity), "finite components");
    detail::require(all_finite(s.omega), obj, "omega", "(non-finite)", "finite components");
    check_material(s.material, obj);
    next_id_ = std::max(next_id_, id + 1);
    const Material& m = materials_[s.material];
    const double mass = m.density * shape_.volume(s.radius);
    const double inertia = shape_.inertia_factor() * mass * s.radius * s.radius;
    auto& p = particles_;
    p.id.push_back(id);
    p.position.push_back(s.position);
    p.velocity.push_back(s.velocity);
    p.omega.push_back(s.omega);
    p.orientation.push_back(identity_orientation<D>());
    p.force.push_back(V::Zero());
    p.torque.push_back(zero<A>());
    p.radius.push_back(s.radius);
    p.mass.push_back(mass);
    p.inv_mass.push_back(s.fixed ? 0.0 : 1.0 / mass);
    p.inertia.push_back(inertia);
    p.inv_inertia.push_back(s.fixed ? 0.0 : 1.0 / inertia);
    p.material.push_back(s.material);
    initialized_ = false;
    return id;
  }

  /// Adds a wall; returns its index. Throws InputError on bad geometry.
  template <class G>
  std::uint32_t add_wall(const G& geometry, WallOptions<D> options = {}) {
    static_assert(std::is_constructible_v<WallGeometry<D>, G>,
                  "grain::Simulation::add_wall: this wall type does not exist in this dimension "
                  "(2D: walls::Segment, walls::Circle; 3D: walls::Plane, walls::Triangle)");
    Wall<D> w;
    w.geometry = geometry;
    w.options = options;
    w.validate();
    check_material(options.material, "Wall '" + options.name + "'");
    w.pivot = options.has_pivot ? options.pivot : Wall<D>::default_pivot(w.geometry);
    w.take_snapshot();
    walls_.push_back(w);
    initialized_ = false;
    return static_cast<std::uint32_t>(walls_.size() - 1);
  }

  void set_gravity(const V& g) {
    for (int d = 0; d < D; ++d) detail::require_finite("Simulation", "gravity component", g[d]);
    params_.gravity = g;
  }

  // ---------------------------------------------------------------- time step
  /// Rayleigh time pi R sqrt(rho/G)/(0.1631 nu + 0.8766) of the smallest particle [s].
  double rayleigh_time() const {
    double t = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < particles_.size(); ++i) {
      const Material& m = materials_[particles_.material[i]];
      const double g = m.shear_modulus();
      t = std::min(t, std::numbers::pi * particles_.radius[i] * std::sqrt(m.density / g) /
                          (0.1631 * m.poisson + 0.8766));
    }
    return t;
  }

  /// Contact-stiffness limit 2 sqrt(m*/k) of the stiffest, lightest contact that can occur [s]
  /// (the stability limit of the undamped oscillator for the symplectic schemes).
  double contact_time_step() const {
    if (particles_.size() == 0) return std::numeric_limits<double>::infinity();
    const double v = reference_speed();
    double t = std::numeric_limits<double>::infinity();
    // smallest particle of each material
    const auto nm = materials_.size();
    std::vector<double> rmin(nm, std::numeric_limits<double>::infinity()), mmin(nm, 0.0);
    for (std::size_t i = 0; i < particles_.size(); ++i) {
      const auto k = particles_.material[i];
      if (particles_.radius[i] < rmin[k]) {
        rmin[k] = particles_.radius[i];
        mmin[k] = particles_.mass[i];
      }
    }
    std::vector<bool> wall_material(nm, false);
    for (const auto& w : walls_) wall_material[w.options.material] = true;
    for (std::size_t a = 0; a < nm; ++a) {
      if (!std::isfinite(rmin[a])) continue;
      for (std::size_t b = 0; b < nm; ++b) {
        const bool pair = std::isfinite(rmin[b]);
        if (pair) {
          const double re = rmin[a] * rmin[b] / (rmin[a] + rmin[b]);
          const double me = mmin[a] * mmin[b] / (mmin[a] + mmin[b]);
          const double k = Contact::stiffness_estimate(pair_properties(a, b), params_.contact, re, me, v);
          if (k > 0) t = std::min(t, 2.0 * std::sqrt(me / k));
        }
        if (wall_material[b]) {
          const double k = Contact::stiffness_estimate(pair_properties(a, b), params_.contact,
                                                       rmin[a], mmin[a], v);
          if (k > 0) t = std::min(t, 2.0 * std::sqrt(mmin[a] / k));
        }
      }
    }
    return t;
  }

  /// The critical time step: min(Rayleigh time, contact limit) [s].
  double critical_time_step() const { return std::min(rayleigh_time(), contact_time_step()); }

  /// The time step in use [s] (after initialisation).
  double time_step() const { return dt_; }

  // ---------------------------------------------------------------- running
  /// Validates the set-up, fixes the time step, builds the neighbour list and computes the
  /// initial forces. Called by run() and step() when needed; raises InputError on bad input.
  void initialize() {
    if (materials_.empty() && (particles_.size() > 0 || !walls_.empty()))
      throw InputError("Simulation: no material was added; add_material() first");
    const double critical = critical_time_step();
    if (params_.time_step > 0.0) {
      if (params_.time_step > critical)
        throw InputError("Simulation: time_step = " + detail::to_text(params_.time_step) +
                         " s is above the stable limit; valid range: (0, " +
                         detail::to_text(critical) + "] s (Rayleigh time " +
                         detail::to_text(rayleigh_time()) + " s, contact limit 2 sqrt(m*/k) = " +
                         detail::to_text(contact_time_step()) + " s)");
      dt_ = params_.time_step;
    } else {
      if (!std::isfinite(critical))
        throw InputError("Simulation: time_step = 0 (automatic) needs particles to estimate it; "
                         "valid range: (0, inf) s");
      dt_ = params_.auto_time_step_factor * critical;
    }
    r_max_ = 0.0;
    for (double r : particles_.radius) r_max_ = std::max(r_max_, r);
    skin_ = SearchT::skin(params_.search, r_max_);
    rebuild();
    if constexpr (IntegratorT::drift_before_forces) {
      // forces at the initial positions; histories are not advanced by this evaluation
      auto saved = history_;
      auto saved_w = wall_history_;
      compute_forces();
      history_ = saved;
      wall_history_ = saved_w;
    }
    initialized_ = true;
  }

  /// Advances one time step.
  void step() {
    if (!initialized_) initialize();
    const auto t0 = std::chrono::steady_clock::now();
    const double dt = dt_;
    if constexpr (IntegratorT::drift_before_forces) {
      integrate_before(dt);
      move_walls(dt);
    }
    update_neighbors();
    compute_forces();
    integrate_after(dt);
    if constexpr (!IntegratorT::drift_before_forces) move_walls(dt);
    ++step_;
    time_ = static_cast<double>(step_) * dt_ + time_offset_;
    counters_.steps += 1;
    counters_.particle_steps += static_cast<double>(particles_.size());
    counters_.wall_seconds +=
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  }

  /// Runs n steps, calling each observer after every step (see io::every).
  template <class... Observers>
  void steps(long n, Observers&&... obs) {
    if (!initialized_) initialize();
    (start_observer(obs), ...);
    for (long k = 0; k < n; ++k) {
      step();
      (obs(*this), ...);
    }
    (finish_observer(obs), ...);
  }

  /// Runs for `duration` seconds of simulated time (rounded up to whole steps).
  template <class... Observers>
  void run(double duration, Observers&&... obs) {
    detail::require_non_negative("Simulation::run", "duration", duration);
    if (!initialized_) initialize();
    const long n = static_cast<long>(std::ceil(duration / dt_ - 1e-9));
    end_time_ = time_ + static_cast<double>(n) * dt_;
    steps(n, std::forward<Observers>(obs)...);
  }

  // ---------------------------------------------------------------- read access
  const ParticleArrays<D>& particles() const { return particles_; }
  ParticleArrays<D>& particles() { return particles_; }
  const std::vector<Wall<D>>& walls() const { return walls_; }
  std::vector<Wall<D>>& walls() { return walls_; }
  const std::vector<Material>& materials() const { return materials_; }
  const Params& params() const { return params_; }
  const Shape& shape() const { return shape_; }
  const NeighborList& neighbor_list() const { return list_; }
  const std::vector<History>& histories() const { return history_; }
  double time() const { return time_; }
  long step_count() const { return step_; }
  /// End time of the current run() (for progress reports), or the current time.
  double end_time() const { return std::max(end_time_, time_); }
  double skin() const { return skin_; }
  const RunCounters& counters() const { return counters_; }
  std::size_t size() const { return particles_.size(); }

  /// Current index of the particle with this id (particles are re-sorted by the cell list).
  std::size_t index_of(std::int64_t id) const {
    for (std::size_t i = 0; i < particles_.size(); ++i)
      if (particles_.id[i] == id) return i;
    throw InputError("Simulation::index_of: id = " + std::to_string(id) +
                     " is invalid; valid range: ids of existing particles");
  }

  /// Effective properties of two materials.
  const PairProperties& pair_properties(std::size_t a, std::size_t b) const {
    return pairs_[a * materials_.size() + b];
  }

  /// Visits every touching contact: f(i, j_or_wall, is_wall, geometry, result). The contact
  /// models are evaluated on copies of the histories, so the state is not changed.
  template <class F>
  void for_each_contact(F&& f) const {
    ContactGeometry<D> g;
    const auto& p = particles_;
    for (std::size_t i = 0; i < p.size(); ++i) {
      for (auto e = list_.offsets[i]; e < list_.offsets[i + 1]; ++e) {
        const auto j = list_.partners[e];
        if (!touching_pair(i, j, g)) continue;
        History h = history_at(history_, e);
        auto r = Contact::evaluate(g, pair_properties(p.material[i], p.material[j]), params_.contact, h, dt_);
        f(i, static_cast<std::size_t>(j), false, g, r);
      }
      for (auto e = list_.wall_offsets[i]; e < list_.wall_offsets[i + 1]; ++e) {
        const auto w = list_.walls[e];
        if (!touching_wall(i, w, g)) continue;
        History h = history_at(wall_history_, e);
        auto r = Contact::evaluate(g, pair_properties(p.material[i], walls_[w].options.material),
                                   params_.contact, h, dt_);
        f(i, static_cast<std::size_t>(w), true, g, r);
      }
    }
  }

  /// Number of touching particle-particle and particle-wall contacts.
  std::pair<std::size_t, std::size_t> contact_counts() const {
    std::size_t pp = 0, pw = 0;
    ContactGeometry<D> g;
    for (std::size_t i = 0; i < particles_.size(); ++i) {
      for (auto e = list_.offsets[i]; e < list_.offsets[i + 1]; ++e)
        pp += touching_pair(i, list_.partners[e], g);
      for (auto e = list_.wall_offsets[i]; e < list_.wall_offsets[i + 1]; ++e)
        pw += touching_wall(i, list_.walls[e], g);
    }
    return {pp, pw};
  }

  /// Translational + rotational kinetic energy [J].
  double kinetic_energy() const {
    double e = 0.0;
    for (std::size_t i = 0; i < particles_.size(); ++i)
      e += 0.5 * particles_.mass[i] * particles_.velocity[i].squaredNorm() +
           0.5 * particles_.inertia[i] * squared_norm(particles_.omega[i]);
    return e;
  }
  /// Elastic energy stored in all contacts [J].
  double elastic_energy() const {
    double e = 0.0;
    for_each_contact([&](auto, auto, bool, const auto&, const auto& r) {
      e += r.normal.elastic_energy + r.tangent.elastic_energy;
    });
    return e;
  }
  /// Gravitational potential energy relative to the origin [J].
  double potential_energy() const {
    double e = 0.0;
    for (std::size_t i = 0; i < particles_.size(); ++i)
      e -= particles_.mass[i] * params_.gravity.dot(particles_.position[i]);
    return e;
  }

private:
  void update_pairs() {
    const auto nm = materials_.size();
    pairs_.resize(nm * nm);
    for (std::size_t a = 0; a < nm; ++a)
      for (std::size_t b = 0; b < nm; ++b)
        pairs_[a * nm + b] =
            PairProperties::mix(materials_[a], materials_[b], overrides_[a * nm + b]);
  }
  static std::string to_text(const V& v) {
    std::string s = "(";
    for (int d = 0; d < D; ++d) s += detail::to_text(v[d]) + (d + 1 < D ? ", " : ")");
    return s;
  }
  void check_material(std::uint32_t m, const std::string& obj) const {
    if (m >= materials_.size())
      throw InputError(obj + ": material = " + std::to_string(m) + " is invalid; valid range: [0, " +
                       std::to_string(materials_.size()) + ") (indices returned by add_material)");
  }
  double reference_speed() const {
    double v = 0.0;
    for (const auto& u : particles_.velocity) v = std::max(v, u.norm());
    for (const auto& w : walls_) v = std::max(v, w.options.velocity.norm());
    return std::max(params_.reference_velocity, 2.0 * v);
  }

  template <class O>
  void start_observer(O& o) {
    if constexpr (requires { o.start(*this); }) o.start(*this);
  }
  template <class O>
  void finish_observer(O& o) {
    if constexpr (requires { o.finish(*this); }) o.finish(*this);
  }

  static History history_at(const std::vector<History>& h, std::size_t e) {
    if constexpr (Contact::template stateless<D>)
      return History{};
    else
      return h[e];
  }

  bool touching_pair(std::size_t i, std::size_t j, ContactGeometry<D>& g) const {
    return touching_pair(i, j, g, particles_.velocity, particles_.omega);
  }
  bool touching_wall(std::size_t i, std::size_t w, ContactGeometry<D>& g) const {
    return touching_wall(i, w, g, particles_.velocity, particles_.omega);
  }
  /// Geometry of pair (i, j) if it touches, with the velocities `v`, `w`.
  bool touching_pair(std::size_t i, std::size_t j, ContactGeometry<D>& g, const std::vector<V>& v,
                     const std::vector<A>& w) const {
    const auto& p = particles_;
    const V d = p.position[j] - p.position[i];
    const double d2 = d.squaredNorm();
    const double rs = p.radius[i] + p.radius[j];
    if (d2 >= rs * rs) return false;
    const double dist = std::sqrt(d2);
    pair_geometry<D>(g, p.position[i], V(d / dist), dist, p.radius[i], p.radius[j],
                     p.mass[i], p.mass[j], v[i], v[j], w[i], w[j]);
    return true;
  }
  bool touching_wall(std::size_t i, std::size_t k, ContactGeometry<D>& g, const std::vector<V>& v,
                     const std::vector<A>& w) const {
    const auto& p = particles_;
    const auto prox = walls_[k].proximity(p.position[i]);
    if (prox.distance >= p.radius[i]) return false;
    wall_geometry<D>(g, walls_[k], prox, p.position[i], p.radius[i], p.mass[i], v[i], w[i]);
    return true;
  }

  // ---------------------------------------------------------------- neighbours
  void update_neighbors() {
    ++steps_since_rebuild_;
    bool far = true;
    if (skin_ > 0.0) {
      double d2 = 0.0;
      const auto& x = particles_.position;
      const long n = static_cast<long>(x.size());
#pragma omp parallel for reduction(max : d2) schedule(static) if (n >= parallel_threshold)
      for (long i = 0; i < n; ++i) d2 = std::max(d2, (x[i] - snapshot_[i]).squaredNorm());
      const double dp = std::sqrt(d2);
      double dw = 0.0;
      for (const auto& w : walls_) dw = std::max(dw, w.displacement_since_snapshot(reach_));
      far = 2.0 * dp >= skin_ || dp + dw >= skin_;
    }
    if (SearchT::due(params_.search, steps_since_rebuild_, far)) rebuild();
  }

  void rebuild() {
    auto& p = particles_;
    const std::size_t n = p.size();
    NeighborList old = std::move(list_);
    std::vector<History> old_hist = std::move(history_), old_whist = std::move(wall_history_);
    std::vector<std::uint32_t> perm;
    const double reach = skin_;
    if constexpr (SearchT::sorts) {
      if (params_.search.sort && n > 1) {
        perm = search::detail::cell_order(p, 2.0 * r_max_ + reach);
        p.permute(perm);
      }
      search::detail::build_cells(p, walls_, reach, r_max_, list_);
    } else {
      search::detail::build_all_pairs(p, walls_, reach, list_);
    }
    // carry the histories of the old list over, by particle identity
    if constexpr (!Contact::template stateless<D>) {
      history_.assign(list_.partners.size(), History{});
      wall_history_.assign(list_.walls.size(), History{});
      if (old.rows() == n) {
        auto old_of = [&](std::size_t k) -> std::uint32_t {
          return perm.empty() ? static_cast<std::uint32_t>(k) : perm[k];
        };
        const long nl = static_cast<long>(n);
#pragma omp parallel for schedule(static) if (nl >= parallel_threshold)
        for (long i = 0; i < nl; ++i) {
          const std::uint32_t a = old_of(static_cast<std::size_t>(i));
          for (auto e = list_.offsets[i]; e < list_.offsets[i + 1]; ++e) {
            const std::uint32_t b = old_of(list_.partners[e]);
            const std::uint32_t lo = std::min(a, b), hi = std::max(a, b);
            const auto first = old.partners.begin() + old.offsets[lo];
            const auto last = old.partners.begin() + old.offsets[lo + 1];
            const auto it = std::lower_bound(first, last, hi);
            if (it != last && *it == hi) {
              history_[e] = old_hist[static_cast<std::size_t>(it - old.partners.begin())];
              if (a > b) Contact::template reverse<D>(history_[e]);
            }
          }
          for (auto e = list_.wall_offsets[i]; e < list_.wall_offsets[i + 1]; ++e) {
            for (auto o = old.wall_offsets[a]; o < old.wall_offsets[a + 1]; ++o)
              if (old.walls[o] == list_.walls[e]) {
                wall_history_[e] = old_whist[o];
                break;
              }
          }
        }
      }
    }
    snapshot_ = p.position;
    // reach of a plane rotation: farthest particle from any wall pivot
    reach_ = 0.0;
    for (const auto& w : walls_) {
      for (const auto& x : p.position) reach_ = std::max(reach_, (x - w.pivot).norm());
    }
    reach_ += 2.0 * r_max_ + skin_;
    for (auto& w : walls_) w.take_snapshot();
    steps_since_rebuild_ = 0;
    ++counters_.rebuilds;
  }

  // ---------------------------------------------------------------- forces
  /// Velocities the forces see. With velocity Verlet the state holds v(n+1/2) while forces are
  /// computed; forces use the prediction v(n+1/2) + a(n) dt/2, so that velocity-dependent forces
  /// (dashpots, global damping) are second-order accurate, and tangential springs still
  /// integrate the half-step velocity that moved the particles (ContactGeometry::slip_velocity).
  static constexpr bool predicts_velocity = IntegratorT::drift_before_forces;

  void compute_forces() {
    auto& p = particles_;
    const long n = static_cast<long>(p.size());
    if constexpr (predicts_velocity) {
      vf_.resize(p.size());
      if constexpr (Contact::has_torque) wf_.resize(p.size());
    }
    const double half_dt = 0.5 * dt_;
#pragma omp parallel for schedule(static) if (n >= parallel_threshold)
    for (long i = 0; i < n; ++i) {
      if constexpr (predicts_velocity) {
        vf_[i] = p.velocity[i] + (half_dt * p.inv_mass[i]) * p.force[i];
        if constexpr (Contact::has_torque)
          wf_[i] = p.omega[i] + (half_dt * p.inv_inertia[i]) * p.torque[i];
      }
      p.force[i] = V::Zero();
      p.torque[i] = zero<A>();
    }
    // deterministic chunks: the chunk length depends on N and the list span only
    const long span = static_cast<long>(list_.max_span);
    const long chunk = std::max({span, (n + 63) / 64, 1L});
    const long nchunks = (n + chunk - 1) / chunk;
    for (int phase = 0; phase < 2; ++phase) {
#pragma omp parallel for schedule(dynamic, 1) if (n >= parallel_threshold)
      for (long c = phase; c < nchunks; c += 2) {
        const long end = std::min(n, (c + 1) * chunk);
        for (long i = c * chunk; i < end; ++i) contact_row(static_cast<std::size_t>(i));
      }
    }
    const V g = params_.gravity;
    const double ct = params_.damping_translational, cr = params_.damping_rotational;
#pragma omp parallel for schedule(static) if (n >= parallel_threshold)
    for (long i = 0; i < n; ++i) {
      p.force[i] += p.mass[i] * g - ct * force_velocity()[i];
      if constexpr (Contact::has_torque) p.torque[i] -= cr * force_omega()[i];
    }
  }

  const std::vector<V>& force_velocity() const {
    if constexpr (predicts_velocity) return vf_;
    else return particles_.velocity;
  }
  const std::vector<A>& force_omega() const {
    if constexpr (predicts_velocity && Contact::has_torque) return wf_;
    else return particles_.omega;
  }

  void contact_row(std::size_t i) {
    auto& p = particles_;
    ContactGeometry<D> g;
    const double dt = dt_;
    const auto& vf = force_velocity();
    const auto& wf = force_omega();
    for (auto e = list_.offsets[i]; e < list_.offsets[i + 1]; ++e) {
      const auto j = list_.partners[e];
      if (!touching_pair(i, j, g, vf, wf)) {
        if constexpr (!Contact::template stateless<D>) history_[e] = History{};
        continue;
      }
      if constexpr (predicts_velocity && Contact::has_torque)
        set_slip_velocity<D>(g, p.velocity[i], p.velocity[j], p.omega[i], p.omega[j]);
      const auto& pair = pairs_[p.material[i] * materials_.size() + p.material[j]];
      auto r = Contact::evaluate(g, pair, params_.contact, hist(history_, e), dt);
      p.force[i] += r.force;
      p.force[j] -= r.force;
      if constexpr (Contact::has_torque) {
        p.torque[i] += r.torque_i;
        p.torque[j] += r.torque_j;
      }
    }
    for (auto e = list_.wall_offsets[i]; e < list_.wall_offsets[i + 1]; ++e) {
      const auto w = list_.walls[e];
      if (!touching_wall(i, w, g, vf, wf)) {
        if constexpr (!Contact::template stateless<D>) wall_history_[e] = History{};
        continue;
      }
      if constexpr (predicts_velocity && Contact::has_torque)
        set_slip_velocity<D>(g, walls_[w], p.velocity[i], p.omega[i]);
      const auto& pair = pairs_[p.material[i] * materials_.size() + walls_[w].options.material];
      auto r = Contact::evaluate(g, pair, params_.contact, hist(wall_history_, e), dt);
      p.force[i] += r.force;
      if constexpr (Contact::has_torque) p.torque[i] += r.torque_i;
    }
  }

  History& hist(std::vector<History>& h, std::size_t e) {
    if constexpr (Contact::template stateless<D>) {
      static thread_local History empty;
      return empty;
    } else {
      return h[e];
    }
  }

  // ---------------------------------------------------------------- integration
  void integrate_before(double dt) {
    auto& p = particles_;
    const long n = static_cast<long>(p.size());
#pragma omp parallel for schedule(static) if (n >= parallel_threshold)
    for (long i = 0; i < n; ++i) {
      const V a = p.force[i] * p.inv_mass[i];
      IntegratorT::before(p.velocity[i], a, dt, [&](const V& u, double h) { p.position[i] += u * h; });
      if constexpr (Contact::has_torque) {
        const A al = p.torque[i] * p.inv_inertia[i];
        IntegratorT::before(p.omega[i], al, dt, [&](const A& u, double h) { rotate(p.orientation[i], u, h); });
      } else {
        rotate(p.orientation[i], p.omega[i], dt);
      }
    }
  }
  void integrate_after(double dt) {
    auto& p = particles_;
    const long n = static_cast<long>(p.size());
#pragma omp parallel for schedule(static) if (n >= parallel_threshold)
    for (long i = 0; i < n; ++i) {
      const V a = p.force[i] * p.inv_mass[i];
      IntegratorT::after(p.velocity[i], a, dt, [&](const V& u, double h) { p.position[i] += u * h; });
      if constexpr (Contact::has_torque) {
        const A al = p.torque[i] * p.inv_inertia[i];
        IntegratorT::after(p.omega[i], al, dt, [&](const A& u, double h) { rotate(p.orientation[i], u, h); });
      } else if constexpr (!IntegratorT::drift_before_forces) {
        rotate(p.orientation[i], p.omega[i], dt);
      }
    }
  }
  void move_walls(double dt) {
    for (auto& w : walls_) w.move(dt);
  }

  Params params_;
  Shape shape_;
  std::vector<Material> materials_;
  std::vector<PairOverride> overrides_;
  std::vector<PairProperties> pairs_;
  ParticleArrays<D> particles_;
  std::vector<Wall<D>> walls_;
  NeighborList list_;
  std::vector<History> history_, wall_history_;
  std::vector<V> snapshot_;
  std::vector<V> vf_; ///< velocities seen by the forces (velocity Verlet)
  std::vector<A> wf_; ///< angular velocities seen by the forces (velocity Verlet)
  double dt_ = 0.0, time_ = 0.0, time_offset_ = 0.0, end_time_ = 0.0;
  double r_max_ = 0.0, skin_ = 0.0, reach_ = 0.0;
  long step_ = 0, steps_since_rebuild_ = 0;
  std::int64_t next_id_ = 0;
  bool initialized_ = false;
  RunCounters counters_;
};

} // namespace grain
