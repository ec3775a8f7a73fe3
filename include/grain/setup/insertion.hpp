#pragma once
/// \file insertion.hpp
/// Insertion of particles during a run (LIGGGHTS' fix pour and fix insert/rate/region, Yade's
/// factories): particles enter through a region or a face at a number rate [1/s] or a mass rate
/// [kg/s], with an initial velocity, never overlapping the particles already there. SI units.
///
/// `Simulation::add_insertion(Insertion<D>)` describes one insertion (checked when added);
/// the simulation places its particles in the lifecycle stage of each step (simulation.hpp, step
/// 7), at the time t the step ended, after the removals and with the particles whose creation
/// time has come; with `Insertion::interval` > 0 only at the first step of each interval (and
/// at t_end), in batches:
/// - due: the number rate gives N(t) = floor(rate (t' - t_begin) + 1e-9) particles, t' = min(t,
///   t_end); the mass rate gives the longest prefix of the particle sequence whose mass sum is at
///   most rate (t' - t_begin) (times 1 + 1e-12), so that the mass inserted lags rate (t' - t_begin)
///   by less than one particle's mass. `total_count` and `total_mass` cap both.
/// - radii: particle k of an insertion has the radius drawn from its size distribution by the
///   generator seeded with (seed, k): the sequence of radii is fixed whatever the blockages.
/// - positions: the particles due and not placed are tried in order at uniform random positions
///   in the region (wholly inside it: centre at least r from its boundary) or on the face (centre
///   on it, at least r from its edge), at most `max_attempts` per particle and step. A candidate
///   is kept if it overlaps no particle present (|x - x_j| >= r + r_j) and none placed before it
///   in the step, tested through a cell grid over the region (built in one pass over the
///   positions, the tests O(1) each). The first particle that finds no place ends the insertion's
///   step: it and the rest are carried over to the next steps, never lost, until t_end.
/// - a step that ends with particles carried over counts as blocked (`InsertionStatus`); a
///   blockage that lasts `warn_after` consecutive steps is reported once (detail::warn, the
///   simulation's warning handler), as is an insertion that ends at t_end with a shortfall.
/// - the inserted particles get fresh ids, the insertion's velocity (plus a uniform deviate in
///   [-velocity_spread, velocity_spread] per component), no spin, the temperature given (or the
///   simulation's initial temperature) and become members of the insertion's group.
/// The state of each insertion (counts, mass, the generator's counters, the ids it gave) is part
/// of a checkpoint: a restarted run inserts exactly what the uninterrupted one does.

#include <grain/conditions/conditions.hpp>
#include <grain/conditions/regions.hpp>
#include <grain/core/error.hpp>
#include <grain/core/vector.hpp>
#include <grain/setup/generate.hpp>
#include <grain/simulation/params.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

namespace grain {

namespace insertion {

/// A segment (2D) through which particles enter: centres on it, at least r from its ends.
struct SegmentFace {
  Vec2 a = Vec2::Zero(); ///< one end [m]
  Vec2 b = Vec2::Zero(); ///< the other end [m]
};
/// A rectangle (3D): corner + s edge1 + u edge2, s and u in [0, 1]; edge1 and edge2 are
/// perpendicular. Centres on it, at least r from its edges.
struct RectangleFace {
  Vec3 corner = Vec3::Zero(); ///< [m]
  Vec3 edge1 = Vec3::Zero();  ///< [m]
  Vec3 edge2 = Vec3::Zero();  ///< [m], perpendicular to edge1
};
/// A planar disk (3D): centres on it, within radius - r of its centre.
struct DiskFace {
  Vec3 center = Vec3::Zero();  ///< [m]
  Vec3 normal = Vec3::UnitZ(); ///< any length > 0
  double radius = 0.0;         ///< [m], > 0
};

} // namespace insertion

/// Where an insertion places particles: a volume (2D: box, ball, polygon; 3D: box, ball,
/// cylinder) or a face (2D: segment; 3D: rectangle, disk).
template <int D>
using InsertionRegion = std::conditional_t<
    D == 2,
    std::variant<regions::Box<2>, regions::Ball<2>, regions::Polygon, insertion::SegmentFace>,
    std::variant<regions::Box<3>, regions::Ball<3>, generate::Cylinder, insertion::RectangleFace,
                 insertion::DiskFace>>;

/// One insertion of particles during a run (see the file comment). Give one rate.
template <int D>
struct Insertion {
  std::string name{};                                 ///< for messages (optional)
  InsertionRegion<D> region{};                        ///< where the particles appear
  generate::Distribution size = generate::Constant{}; ///< of the radius [m]
  std::uint32_t material = 0;                         ///< index returned by add_material
  double number_rate = 0.0;                           ///< particles per second [1/s], or 0
  double mass_rate = 0.0;                             ///< [kg/s], or 0
  std::size_t total_count = 0;                        ///< particles in all; 0 = no limit
  double total_mass = 0.0;                            ///< [kg] in all; 0 = no limit
  Vec<D> velocity = Vec<D>::Zero();                   ///< initial velocity [m/s]
  double velocity_spread = 0.0; ///< [m/s]: each component + uniform in [-spread, spread]
  double t_begin = 0.0;         ///< [s], at or after the time it is added
  double t_end = std::numeric_limits<double>::infinity(); ///< [s], > t_begin
  std::string group{};            ///< the inserted particles join it (made if new); "" = none
  std::uint64_t seed = 1;         ///< of the radii, positions and velocity deviates
  std::size_t max_attempts = 100; ///< trial positions per particle and step
  /// A blockage is reported (a warning) when particles have been carried over after this many
  /// consecutive tries (steps, or batches with `interval`).
  std::uint64_t warn_after = 1000;
  /// [s]: insert in batches, at the first step at or after each t_begin + j interval (j = 1, 2,
  /// ...) and at t_end, instead of at every step (each step that inserts rebuilds the neighbour
  /// list); 0 = every step.
  double interval = 0.0;
  /// Initial temperature [K] (thermal simulations only); NaN = SimulationParams::
  /// initial_temperature.
  double temperature = std::numeric_limits<double>::quiet_NaN();
};

/// What an insertion has done so far.
struct InsertionStatus {
  std::uint64_t inserted = 0;      ///< particles placed
  double mass = 0.0;               ///< their mass [kg]
  std::uint64_t due = 0;           ///< particles due by the last step
  std::uint64_t shortfall = 0;     ///< due - inserted: carried over (or, once finished, lost)
  std::uint64_t attempts = 0;      ///< trial positions
  std::uint64_t blocked_steps = 0; ///< tries (steps or batches) that ended with a carry-over
  std::uint64_t warnings = 0;      ///< warnings given (blockages, a shortfall at the end)
  bool finished = false;           ///< total reached (all placed) or t_end passed
};

namespace detail {

/// The insertions of a simulation: their descriptions, checked, and their state.
template <int D>
class Insertions {
public:
  using V = Vec<D>;
  static constexpr std::size_t no_group = static_cast<std::size_t>(-1);

  struct Entry {
    Insertion<D> spec;
    generate::detail::Sampler sampler;
    std::string obj{};    ///< the name in messages
    double r_lo = 0.0;    ///< smallest radius of the distribution [m]
    double r_hi = 0.0;    ///< largest [m]
    double density = 0.0; ///< of the material [kg/m^3]
    std::size_t group = no_group;
    InsertionStatus status{};
    double due_mass = 0.0;         ///< mass of the particles due [kg]
    std::uint64_t batches = 0;     ///< tries with particles due (seeds of the position streams)
    std::uint64_t ticks = 0;       ///< intervals passed at the last batch (Insertion::interval)
    std::uint64_t blocked_run = 0; ///< consecutive tries that ended with particles carried over
    std::vector<std::pair<std::int64_t, std::int64_t>> ids{}; ///< runs [first, last] of its ids
    /// Its place among the insertions: mixed into its seed, so that two insertions with the same
    /// seed draw different streams.
    std::uint64_t index = 0;
  };
  std::vector<Entry> entries;

  bool empty() const { return entries.empty(); }
  /// True if some insertion may still place particles.
  bool active() const {
    for (const auto& e : entries)
      if (!e.status.finished) return true;
    return false;
  }
  /// The largest radius any insertion can give [m] (0 without insertions).
  double largest_radius() const {
    double r = 0.0;
    for (const auto& e : entries)
      r = std::max(r, e.r_hi);
    return r;
  }
  /// The largest speed of an inserted particle [m/s].
  double largest_speed() const {
    double v = 0.0;
    for (const auto& e : entries)
      v = std::max(v, e.spec.velocity.norm() + std::sqrt(double(D)) * e.spec.velocity_spread);
    return v;
  }
  /// Calls f(r, material) with the smallest and the largest radius of each insertion that is not
  /// finished (for the time step and the search).
  template <class F>
  void for_each_bound(F&& f) const {
    for (const auto& e : entries)
      if (!e.status.finished) {
        f(e.r_lo, e.spec.material);
        f(e.r_hi, e.spec.material);
      }
  }

  // ---------------------------------------------------------------- checks
  /// Checks `spec` (InputError naming `obj`, the value and the valid range) and adds it. `now`:
  /// the current time [s]; `density`: of its material; `thermal`: the simulation has
  /// temperatures.
  void add(const Insertion<D>& spec, const std::string& obj, double now, double density,
           bool thermal) {
    Entry e{spec, make_sampler(spec.size, obj), obj};
    e.density = density;
    std::visit([&](const auto& d) { bounds_of(d, e.r_lo, e.r_hi); }, spec.size);
    std::visit([&](const auto& r) { check(r, obj, e.r_hi, spec.velocity); }, spec.region);
    const bool by_number = spec.number_rate != 0.0, by_mass = spec.mass_rate != 0.0;
    if (by_number == by_mass)
      throw InputError(obj + ": number_rate = " + to_text(spec.number_rate) +
                       " 1/s and mass_rate = " + to_text(spec.mass_rate) +
                       " kg/s is invalid; valid: one rate in (0, inf), the other 0");
    if (by_number) require_positive(obj, "number_rate", spec.number_rate);
    if (by_mass) require_positive(obj, "mass_rate", spec.mass_rate);
    require_non_negative(obj, "total_mass", spec.total_mass);
    for (int d = 0; d < D; ++d)
      require_finite(obj, "velocity component", spec.velocity[d]);
    require_non_negative(obj, "velocity_spread", spec.velocity_spread);
    require(std::isfinite(spec.t_begin) && spec.t_begin >= now, obj, "t_begin", spec.t_begin,
            cat("[current time, inf) = [", to_text(now), ", inf) s"));
    require(spec.t_end > spec.t_begin, obj, "t_end", spec.t_end,
            cat("(t_begin, inf] = (", to_text(spec.t_begin), ", inf] s"));
    require(spec.max_attempts > 0, obj, "max_attempts", spec.max_attempts, "[1, inf)");
    require(spec.warn_after > 0, obj, "warn_after", spec.warn_after, "[1, inf) steps");
    require_non_negative(obj, "interval", spec.interval);
    if (thermal) {
      if (!std::isnan(spec.temperature))
        require(std::isfinite(spec.temperature) && spec.temperature >= 0.0, obj, "temperature",
                spec.temperature, "[0, inf) K, or NaN for the initial temperature");
    } else if (!std::isnan(spec.temperature)) {
      throw InputError(obj + ": temperature = " + to_text(spec.temperature) +
                       " K is given but the contact has no conduction model; valid: leave it "
                       "unset, or give the Interaction a conduction model");
    }
    e.index = entries.size();
    entries.push_back(std::move(e));
  }

  // ---------------------------------------------------------------- the step
  /// Places the particles due at time t. `x`, `r`: the positions and radii of the particles;
  /// only those at the indices `kept` (all if null) are present; `born` holds the particles that
  /// arrive in this step, and receives the inserted ones. `r_max`: the largest radius present;
  /// `volume(r)`: a particle's volume [m^3]; `temperature`: the default temperature (NaN in a
  /// simulation without temperatures); `next_id`: the next free id (advanced); `groups`: the
  /// simulation's groups (the new ids join the insertion's). Returns the number placed.
  template <class Volume>
  std::size_t place(double t, const std::vector<V>& x, const std::vector<double>& r,
                    const std::vector<std::uint32_t>* kept, std::vector<ParticleSpec<D>>& born,
                    double r_max, Volume&& volume, double temperature, std::int64_t& next_id,
                    std::vector<Group>& groups) {
    std::size_t total = 0;
    for (auto& e : entries) {
      if (e.status.finished || t < e.spec.t_begin) continue;
      if (e.spec.interval > 0.0 && t < e.spec.t_end) {
        // batches: only at the first step of each interval (a quotient within 1e-9 below a
        // whole number counts as it)
        const double q = std::floor((t - e.spec.t_begin) / e.spec.interval + 1e-9);
        if (!(q > static_cast<double>(e.ticks))) continue;
        e.ticks = static_cast<std::uint64_t>(q);
      }
      auto& st = e.status;
      const bool exhausted = advance_due(e, std::min(t, e.spec.t_end), volume);
      std::size_t now = 0;
      if (st.inserted < st.due) {
        now = place_one(e, t, x, r, kept, born, r_max, volume, temperature, next_id, groups);
        total += now;
        if (st.inserted < st.due) {
          ++st.blocked_steps;
          if (++e.blocked_run == e.spec.warn_after) {
            ++st.warnings;
            warn(e.obj + ": the region is blocked at t = " + to_text(t) +
                 " s: " + std::to_string(st.due - st.inserted) +
                 " particles due are carried over (" + std::to_string(st.inserted) + " of " +
                 std::to_string(st.due) + " placed so far) after " + std::to_string(e.blocked_run) +
                 " tries in a row that left particles over; insertion resumes when there is "
                 "room");
          }
        } else {
          e.blocked_run = 0;
        }
      }
      st.shortfall = st.due - st.inserted;
      if (t >= e.spec.t_end || (exhausted && st.shortfall == 0)) {
        st.finished = true;
        if (st.shortfall > 0) {
          ++st.warnings;
          warn(e.obj + ": ended at t_end = " + to_text(e.spec.t_end) + " s with " +
               std::to_string(st.shortfall) + " of " + std::to_string(st.due) +
               " particles due not inserted (the region stayed blocked)");
        }
      }
    }
    return total;
  }

  /// The radius [m] of particle k of insertion e.
  static double radius(const Entry& e, std::uint64_t k) {
    generate::Random rng(mix(e, k, 0));
    return e.sampler.sample(rng);
  }

  // ---------------------------------------------------------------- checkpoint
  /// Visits the state of every insertion; reading, the ids each gave join its group again (the
  /// program makes the groups and insertions before loading).
  /// `most` bounds the particles all insertions can have given (those present and removed).
  template <class Archive>
  void serialize(Archive& ar, std::vector<Group>& groups, std::uint64_t most) {
    std::uint64_t n = entries.size();
    ar(n);
    if constexpr (Archive::reading)
      if (n != entries.size())
        throw InputError(cat("checkpoint: insertions = ", std::to_string(n),
                             " is invalid; valid: ", std::to_string(entries.size()),
                             " (the insertions of this simulation, added in the same order "
                             "before loading)"));
    for (auto& e : entries) {
      auto& st = e.status;
      ar(st.inserted, st.mass, st.due, st.shortfall, st.attempts, st.blocked_steps, st.warnings,
         st.finished, e.due_mass, e.batches, e.ticks, e.blocked_run, e.ids);
      if constexpr (Archive::reading) {
        if (st.inserted > st.due || st.inserted > most || !(st.mass >= 0.0) ||
            !(e.due_mass >= 0.0) || !ids_match(e.ids, st.inserted))
          throw InputError("checkpoint: the state of insertion " + e.obj + " is invalid");
        most -= st.inserted;
        if (e.group != no_group && !groups[e.group].everything) {
          auto& ids = groups[e.group].ids;
          for (const auto& [a, b] : e.ids)
            for (std::int64_t id = a; id <= b; ++id)
              ids.push_back(id);
          std::sort(ids.begin(), ids.end());
          ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
        }
      }
    }
  }

private:
  using Random = generate::Random;

  /// True if `runs` are ascending, disjoint runs [first, last] of ids >= 0 that hold `count`
  /// ids in all (what a file read may not be trusted with: the runs are expanded into groups).
  static bool ids_match(const std::vector<std::pair<std::int64_t, std::int64_t>>& runs,
                        std::uint64_t count) {
    std::uint64_t total = 0;
    std::int64_t last = -1;
    for (const auto& [a, b] : runs) {
      if (!(a > last && b >= a)) return false;
      const std::uint64_t n = static_cast<std::uint64_t>(b - a) + 1; // b - a < 2^63
      if (n > count - total) return false;
      total += n;
      last = b;
    }
    return total == count;
  }

  static std::uint64_t splitmix(std::uint64_t z) {
    z += 0x9e3779b97f4a7c15ULL;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  }
  /// The seed of stream `stream` (0: radii, 1: positions) number k of insertion e.
  static std::uint64_t mix(const Entry& e, std::uint64_t k, std::uint64_t stream) {
    return splitmix(splitmix(e.spec.seed ^ splitmix(e.index)) ^ splitmix(2 * k + stream + 1));
  }

  static generate::detail::Sampler make_sampler(const generate::Distribution& d,
                                                const std::string& obj) {
    try {
      return generate::detail::Sampler(d, D);
    } catch (const InputError& e) {
      throw InputError(obj + ", size: " + e.what());
    }
  }
  static void bounds_of(const generate::Constant& d, double& lo, double& hi) { lo = hi = d.radius; }
  static void bounds_of(const generate::Uniform& d, double& lo, double& hi) {
    lo = d.min, hi = d.max;
  }
  static void bounds_of(const generate::Normal& d, double& lo, double& hi) {
    lo = d.min, hi = d.max;
  }
  static void bounds_of(const generate::LogNormal& d, double& lo, double& hi) {
    lo = d.min, hi = d.max;
  }
  static void bounds_of(const generate::Discrete& d, double& lo, double& hi) {
    lo = *std::min_element(d.radii.begin(), d.radii.end());
    hi = *std::max_element(d.radii.begin(), d.radii.end());
  }

  static std::string to_text(double v) { return grain::detail::to_text(v); }
  /// The parts appended in order (messages that start with a literal are built so, not by
  /// "literal" + std::string: GCC 12 at -O3 gives a false -Wrestrict warning for that).
  template <class... T>
  static std::string cat(const T&... parts) {
    std::string s;
    ((s += parts), ...);
    return s;
  }

  /// "<what> = v is invalid; valid range: [2 x largest radius, inf) m".
  static void require_room(bool ok, const std::string& obj, const char* what, double v,
                           double need) {
    require(
        ok, obj, what, v,
        cat("[", to_text(need), ", inf) m (room for the largest radius of the size distribution)"));
  }
  /// The unit normal of a face and a check that the velocity leaves it.
  static void require_leaves(const std::string& obj, const V& n, const V& v) {
    const double vn = v.dot(n);
    require(vn != 0.0, obj, "velocity component normal to the face", vn,
            "(-inf, 0) or (0, inf) m/s (particles must leave the face)");
  }

  static void check(const regions::Box<D>& b, const std::string& obj, double r, const V&) {
    b.validate(obj);
    const double side = (b.hi - b.lo).minCoeff();
    require_room(side >= 2 * r, obj + " (Box)", "smallest side", side, 2 * r);
  }
  static void check(const regions::Ball<D>& b, const std::string& obj, double r, const V&) {
    b.validate(obj);
    require_room(b.radius >= r, obj + " (Ball)", "radius", b.radius, r);
  }
  static void check(const regions::Polygon& p, const std::string& obj, double, const V&) {
    p.validate(obj);
  }
  static void check(const generate::Cylinder& c, const std::string& obj, double r, const V&) {
    c.validate(obj);
    require_room(c.radius >= r, obj + " (Cylinder)", "radius", c.radius, r);
    require_room((c.b - c.a).norm() >= 2 * r, obj + " (Cylinder)", "length |b - a|",
                 (c.b - c.a).norm(), 2 * r);
  }
  static void check(const insertion::SegmentFace& f, const std::string& obj, double r, const V& v) {
    const std::string o = obj + " (SegmentFace)";
    require(all_finite(f.a), o, "a", "(non-finite)", "finite coordinates");
    require(all_finite(f.b), o, "b", "(non-finite)", "finite coordinates");
    const double len = (f.b - f.a).norm();
    require_room(len >= 2 * r && len > 0, o, "length |b - a|", len, 2 * r);
    const Vec2 u = (f.b - f.a) / len;
    if constexpr (D == 2) require_leaves(o, Vec2(-u.y(), u.x()), v);
  }
  static void check(const insertion::RectangleFace& f, const std::string& obj, double r,
                    const V& v) {
    const std::string o = obj + " (RectangleFace)";
    require(all_finite(f.corner), o, "corner", "(non-finite)", "finite coordinates");
    require(all_finite(f.edge1) && all_finite(f.edge2), o, "edge", "(non-finite)",
            "finite components");
    const double l1 = f.edge1.norm(), l2 = f.edge2.norm();
    require_room(l1 >= 2 * r && l1 > 0, o, "|edge1|", l1, 2 * r);
    require_room(l2 >= 2 * r && l2 > 0, o, "|edge2|", l2, 2 * r);
    const double c = f.edge1.dot(f.edge2) / (l1 * l2);
    require(std::abs(c) <= 1e-9, o, "cosine of the angle between edge1 and edge2", c,
            "[-1e-9, 1e-9] (perpendicular edges)");
    if constexpr (D == 3) require_leaves(o, Vec3(f.edge1.cross(f.edge2).normalized()), v);
  }
  static void check(const insertion::DiskFace& f, const std::string& obj, double r, const V& v) {
    const std::string o = obj + " (DiskFace)";
    require(all_finite(f.center), o, "center", "(non-finite)", "finite coordinates");
    const double n = f.normal.norm();
    require(all_finite(f.normal) && n > 0, o, "|normal|", n, "(0, inf)");
    require_positive(o, "radius", f.radius);
    require_room(f.radius >= r, o, "radius", f.radius, r);
    if constexpr (D == 3) require_leaves(o, Vec3(f.normal / n), v);
  }

  // ---------------------------------------------------------------- geometry of the regions
  /// Two unit vectors perpendicular to the unit vector n and to each other.
  static std::pair<Vec3, Vec3> plane_basis(const Vec3& n) {
    const Vec3 a = std::abs(n.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
    const Vec3 u = a.cross(n).normalized();
    return {u, n.cross(u)};
  }
  /// A point uniform in the disk of radius rho about the origin, in the basis (u, w).
  static Vec3 in_disk(Random& rng, const Vec3& u, const Vec3& w, double rho) {
    for (;;) {
      const double s = rng.uniform(-1.0, 1.0), q = rng.uniform(-1.0, 1.0);
      if (s * s + q * q <= 1.0) return rho * (s * u + q * w);
    }
  }

  static std::pair<V, V> box_of(const regions::Box<D>& b) { return generate::detail::bounds(b); }
  static std::pair<V, V> box_of(const regions::Ball<D>& b) { return generate::detail::bounds(b); }
  static std::pair<Vec2, Vec2> box_of(const regions::Polygon& p) {
    return generate::detail::bounds(p);
  }
  static std::pair<Vec3, Vec3> box_of(const generate::Cylinder& c) {
    return generate::detail::bounds(c);
  }
  static std::pair<Vec2, Vec2> box_of(const insertion::SegmentFace& f) {
    return {f.a.cwiseMin(f.b), f.a.cwiseMax(f.b)};
  }
  static std::pair<Vec3, Vec3> box_of(const insertion::RectangleFace& f) {
    Vec3 lo = f.corner, hi = f.corner;
    for (const Vec3& p :
         {Vec3(f.corner + f.edge1), Vec3(f.corner + f.edge2), Vec3(f.corner + f.edge1 + f.edge2)})
      lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
    return {lo, hi};
  }
  static std::pair<Vec3, Vec3> box_of(const insertion::DiskFace& f) {
    const Vec3 n = f.normal.normalized();
    Vec3 e;
    for (int d = 0; d < 3; ++d)
      e[d] = f.radius * std::sqrt(std::max(0.0, 1.0 - n[d] * n[d]));
    return {Vec3(f.center - e), Vec3(f.center + e)};
  }

  /// A trial centre for a particle of radius r wholly inside the region (or on the face, at least
  /// r from its edge); false if the trial missed the region (a rejection counts as an attempt).
  static bool candidate(const regions::Box<D>& b, double r, Random& rng, V& c) {
    for (int d = 0; d < D; ++d)
      c[d] = rng.uniform(b.lo[d] + r, b.hi[d] - r);
    return generate::detail::fits(b, c, r);
  }
  static bool candidate(const regions::Ball<D>& b, double r, Random& rng, V& c) {
    for (int d = 0; d < D; ++d)
      c[d] = rng.uniform(b.center[d] - (b.radius - r), b.center[d] + (b.radius - r));
    return generate::detail::fits(b, c, r);
  }
  static bool candidate(const regions::Polygon& p, double r, Random& rng, Vec2& c) {
    const auto [lo, hi] = generate::detail::bounds(p);
    for (int d = 0; d < 2; ++d) {
      if (lo[d] + r > hi[d] - r) return false;
      c[d] = rng.uniform(lo[d] + r, hi[d] - r);
    }
    return generate::detail::fits(p, c, r);
  }
  static bool candidate(const generate::Cylinder& cy, double r, Random& rng, Vec3& c) {
    const Vec3 axis = cy.b - cy.a;
    const double len = axis.norm();
    const Vec3 n = axis / len;
    const auto [u, w] = plane_basis(n);
    c = cy.a + rng.uniform(r, len - r) * n + in_disk(rng, u, w, cy.radius - r);
    return generate::detail::fits(cy, c, r);
  }
  static bool candidate(const insertion::SegmentFace& f, double r, Random& rng, Vec2& c) {
    const double len = (f.b - f.a).norm();
    c = f.a + rng.uniform(r, len - r) * ((f.b - f.a) / len);
    return true;
  }
  static bool candidate(const insertion::RectangleFace& f, double r, Random& rng, Vec3& c) {
    const double l1 = f.edge1.norm(), l2 = f.edge2.norm();
    c = f.corner + rng.uniform(r, l1 - r) / l1 * f.edge1 + rng.uniform(r, l2 - r) / l2 * f.edge2;
    return true;
  }
  static bool candidate(const insertion::DiskFace& f, double r, Random& rng, Vec3& c) {
    const auto [u, w] = plane_basis(f.normal.normalized());
    c = f.center + in_disk(rng, u, w, f.radius - r);
    return true;
  }

  // ---------------------------------------------------------------- due and placement
  /// Advances the particles due to the time tt [s]; returns true if the totals are reached (no
  /// particle will be due after those).
  template <class Volume>
  static bool advance_due(Entry& e, double tt, Volume& volume) {
    const auto& sp = e.spec;
    auto& st = e.status;
    constexpr auto no_limit = std::numeric_limits<std::uint64_t>::max();
    std::uint64_t cap = no_limit;
    if (sp.number_rate > 0.0) {
      const double q = sp.number_rate * (tt - sp.t_begin);
      cap = q <= 0.0 ? 0 : static_cast<std::uint64_t>(std::floor(std::min(q, 0x1p62) + 1e-9));
    }
    bool by_count = false;
    if (sp.total_count > 0 && sp.total_count <= cap) {
      cap = sp.total_count;
      by_count = true;
    }
    double m_due = std::numeric_limits<double>::infinity();
    if (sp.mass_rate > 0.0) m_due = sp.mass_rate * (tt - sp.t_begin);
    bool by_mass = false;
    if (sp.total_mass > 0.0 && sp.total_mass <= m_due) {
      m_due = sp.total_mass;
      by_mass = true;
    }
    if (!std::isfinite(m_due)) { // a count alone: no radius needed
      st.due = std::max(st.due, cap);
      return by_count;
    }
    // at most 2^20 particles more per step (a rate of absurd mass lags rather than hangs)
    for (std::uint64_t more = 0; st.due < cap && more < (std::uint64_t{1} << 20); ++more) {
      const double m = e.density * volume(radius(e, st.due));
      if (e.due_mass + m > m_due * (1.0 + 1e-12)) return by_mass;
      e.due_mass += m;
      ++st.due;
    }
    return by_count && st.due >= cap;
  }

  template <class Volume>
  static std::size_t place_one(Entry& e, double t, const std::vector<V>& x,
                               const std::vector<double>& r, const std::vector<std::uint32_t>* kept,
                               std::vector<ParticleSpec<D>>& born, double r_max, Volume& volume,
                               double temperature, std::int64_t& next_id,
                               std::vector<Group>& groups) {
    auto& st = e.status;
    // the grid of the particles near the region: cells at least r_hi + r_max wide
    const auto [lo0, hi0] = std::visit([](const auto& g) { return box_of(g); }, e.spec.region);
    const double reach = e.r_hi + std::max(r_max, e.r_hi);
    const V lo = V(lo0.array() - reach), hi = V(hi0.array() + reach);
    auto near = [&](const V& p) {
      return (p.array() >= lo.array()).all() && (p.array() <= hi.array()).all();
    };
    std::vector<std::uint32_t> items;
    const std::size_t n = kept ? kept->size() : x.size();
    for (std::size_t k = 0; k < n; ++k) {
      const std::uint32_t i = kept ? (*kept)[k] : static_cast<std::uint32_t>(k);
      if (near(x[i])) items.push_back(i);
    }
    std::vector<std::size_t> born_items;
    for (std::size_t k = 0; k < born.size(); ++k)
      if (near(born[k].position)) born_items.push_back(k);
    const std::size_t wanted = static_cast<std::size_t>(
        std::min<std::uint64_t>(st.due - st.inserted, std::uint64_t(1) << 24));
    generate::detail::SlotGrid<D> grid;
    const std::size_t count = items.size() + born_items.size() + wanted;
    grid.reset(lo, hi, reach * (1.0 + 1e-12), 2 * count + 64, count);
    for (const auto i : items)
      grid.insert(x[i], r[i]);
    for (const auto k : born_items)
      grid.insert(born[k].position, born[k].radius);

    Random rng(mix(e, e.batches++, 1));
    std::size_t placed = 0;
    while (st.inserted < st.due) {
      const double rk = radius(e, st.inserted);
      V c = V::Zero();
      bool found = false;
      for (std::size_t a = 0; a < e.spec.max_attempts && !found; ++a) {
        ++st.attempts;
        found =
            std::visit([&](const auto& g) { return candidate(g, rk, rng, c); }, e.spec.region) &&
            !grid.overlaps(c, rk);
      }
      if (!found) break;
      grid.insert(c, rk);
      ParticleSpec<D> ps;
      ps.position = c;
      ps.radius = rk;
      ps.material = e.spec.material;
      ps.velocity = e.spec.velocity;
      if (e.spec.velocity_spread > 0.0)
        for (int d = 0; d < D; ++d)
          ps.velocity[d] += rng.uniform(-e.spec.velocity_spread, e.spec.velocity_spread);
      ps.temperature = std::isnan(e.spec.temperature) ? temperature : e.spec.temperature;
      ps.creation_time = t;
      ps.id = next_id++;
      born.push_back(ps);
      if (!e.ids.empty() && e.ids.back().second + 1 == ps.id)
        e.ids.back().second = ps.id;
      else
        e.ids.push_back({ps.id, ps.id});
      if (e.group != no_group && !groups[e.group].everything) groups[e.group].ids.push_back(ps.id);
      ++st.inserted;
      st.mass += e.density * volume(rk);
      ++placed;
    }
    return placed;
  }
};

} // namespace detail
} // namespace grain
