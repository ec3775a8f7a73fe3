#pragma once
/// \file generate.hpp
/// Initial packings: a region filled with non-overlapping particles whose radii follow a size
/// distribution (lengths in m, volumes in m^3, areas in m^2).
///
/// `generate::fill(region, distribution, options)` returns the particles as
/// `ParticleSpec<D>` (centre, radius, the caller's material; ids -1); `generate::add_to(sim,
/// result)` adds them to a simulation. A particle is wholly inside the region: its centre lies
/// inside and at least its radius r from the boundary. Two particles i, j do not overlap:
/// |x_i - x_j| >= r_i + r_j.
///
/// Regions: `regions::Box<D>`, `regions::Ball<D>`, `regions::Polygon` (2D), and here
/// `generate::Cylinder` (3D: axis from a to b, radius) and `generate::ClosedMesh` (3D: the inside
/// of a closed, consistently oriented triangle mesh; inside by the parity of the crossings of a
/// ray in +z, distance to the triangles through a bucket grid).
///
/// Size distributions of the radius r [m]: `Constant`, `Uniform` on [min, max], `Normal`
/// (mean, std) and `LogNormal` (ln r normal with mean ln(median) and standard deviation sigma),
/// both truncated to [min, max] by rejection, and `Discrete` (radii with number or mass
/// fractions; a mass fraction w_k becomes the number fraction n_k = (w_k / r_k^D) / sum_l (w_l /
/// r_l^D), D = 3 for spheres, 2 for disks of one thickness). Samples come from xoshiro256**
/// seeded by splitmix64, uniform u = (bits >> 11) 2^-53 in [0, 1), normal deviates by
/// Marsaglia's polar method (z = v sqrt(-2 ln s / s), s = v1^2 + v2^2 < 1): the same numbers on
/// every platform whose std::log and std::exp agree (sqrt is exact in IEEE arithmetic).
///
/// Targets: a number of particles or a solid fraction phi = sum V_i / V_region (V_i = 4/3 pi r^3
/// in 3D, pi r^2 in 2D; V_region the region's volume or area). For a fraction the radii are drawn
/// until their volume sum is nearest phi V_region (within half a particle's volume).
///
/// Modes (`Mode`):
/// - `random`: random sequential addition. Each particle (by default largest first) is tried at
///   uniform random centres in the region's bounding box shrunk by r until one fits the region
///   and overlaps no particle placed before (a cell grid of cell size >= 2 r_max makes the test
///   O(1)). After `Options::max_failures` consecutive failed trials of one particle the fill
///   stops: InputError "placed N of M particles, solid fraction x of y, after K attempts", or
///   with `Options::partial` the particles placed. It jams near phi = 0.38 (3D) and 0.55 (2D)
///   for equal sizes.
/// - `lattice`: sites of a simple cubic (square in 2D) or hexagonal close-packed (triangular in
///   2D) lattice of spacing a = 2 r_max + gap (r_max the distribution's upper bound), the first
///   site at lo + a/2 of the bounding box, kept where a ball of radius a/2 fits the region; in a
///   box of sides L_d the cubic lattice has prod_d floor(L_d / a) sites.
/// - `grow`: random addition of the radii shrunk by s0 = (phi_0 / phi)^(1/D) (phi_0 =
///   `Growth::start_fraction`), then radius growth: all radii times a common factor s rising to 1
///   in steps, each followed by Gauss-Seidel sweeps that push every overlapping pair apart along
///   its centre line (by `Growth::over_relaxation` x the overlap, half each) and move particles
///   back inside the region, until no overlap exceeds `Growth::tolerance` x the smaller radius. A step that does not relax in
///   `Growth::max_sweeps` sweeps is undone and halved; below `Growth::min_step` the packing is
///   jammed. The growth aims at s = 1 / (1 - tolerance); the overlaps left are then removed
///   exactly by shrinking every radius by the common factor 1 - e, e = max(o_ij / (r_i + r_j),
///   boundary excess / r_i), and s is capped at 1: the result has no overlap at all (the pair
///   test |x_i - x_j| >= r_i + r_j passes exactly). If s stays below 1 the fill stops as above.
///   `generate::grow` does the same to any packing.

#include <grain/conditions/regions.hpp>
#include <grain/core/error.hpp>
#include <grain/core/vector.hpp>
#include <grain/simulation/params.hpp>
#include <grain/walls/mesh_features.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <numbers>
#include <string>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

namespace grain::generate {

// ============================================================================ random numbers

/// xoshiro256** seeded by splitmix64: a 64-bit generator that gives the same sequence everywhere.
class Random {
public:
  explicit Random(std::uint64_t seed) {
    for (auto& w : s_) {
      seed += 0x9e3779b97f4a7c15ULL;
      std::uint64_t z = seed;
      z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
      z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
      w = z ^ (z >> 31);
    }
  }
  std::uint64_t next() {
    const std::uint64_t out = rotl(s_[1] * 5, 7) * 9;
    const std::uint64_t t = s_[1] << 17;
    s_[2] ^= s_[0];
    s_[3] ^= s_[1];
    s_[1] ^= s_[2];
    s_[0] ^= s_[3];
    s_[2] ^= t;
    s_[3] = rotl(s_[3], 45);
    return out;
  }
  /// Uniform in [0, 1), 53 random bits.
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }
  /// Uniform in [lo, hi).
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
  /// Standard normal deviate (Marsaglia's polar method; the second deviate is kept for the next
  /// call).
  double normal() {
    if (has_spare_) {
      has_spare_ = false;
      return spare_;
    }
    double v1, v2, s;
    do {
      v1 = 2.0 * uniform() - 1.0;
      v2 = 2.0 * uniform() - 1.0;
      s = v1 * v1 + v2 * v2;
    } while (s >= 1.0 || s == 0.0);
    const double f = std::sqrt(-2.0 * std::log(s) / s);
    spare_ = v2 * f;
    has_spare_ = true;
    return v1 * f;
  }

private:
  static std::uint64_t rotl(std::uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }
  std::array<std::uint64_t, 4> s_{};
  double spare_ = 0.0;
  bool has_spare_ = false;
};

// ============================================================================ distributions

/// Every particle of one radius [m].
struct Constant {
  double radius = 0.0; ///< [m], > 0
};
/// Radius uniform on [min, max] [m].
struct Uniform {
  double min = 0.0; ///< [m], > 0
  double max = 0.0; ///< [m], >= min
};
/// Normal radius (mean, std) [m] truncated to [min, max] (0 < min < max).
struct Normal {
  double mean = 0.0; ///< of the untruncated distribution [m]
  double std = 0.0;  ///< of the untruncated distribution [m], > 0
  double min = 0.0;  ///< [m], > 0
  double max = 0.0;  ///< [m], > min
};
/// Log-normal radius: ln r normal with mean ln(median) and standard deviation sigma (of the
/// untruncated distribution), truncated to [min, max] (0 < min < max). The untruncated mean is
/// median exp(sigma^2 / 2); `from_mean` takes that mean instead of the median.
struct LogNormal {
  double median = 0.0; ///< exp(mean of ln r) [m], > 0
  double sigma = 0.0;  ///< standard deviation of ln r [-], > 0
  double min = 0.0;    ///< [m], > 0
  double max = 0.0;    ///< [m], > min
  /// The log-normal whose untruncated mean radius is `mean` [m].
  static LogNormal from_mean(double mean, double sigma, double min, double max) {
    return {mean * std::exp(-0.5 * sigma * sigma), sigma, min, max};
  }
};
/// A list of radii with their number fractions or mass fractions (each >= 0, summing to 1
/// within 1e-9).
struct Discrete {
  enum class Basis { number, mass };
  std::vector<double> radii;     ///< [m], > 0
  std::vector<double> fractions; ///< one per radius
  Basis basis = Basis::number;
};

/// A size distribution of the radius.
using Distribution = std::variant<Constant, Uniform, Normal, LogNormal, Discrete>;

// ============================================================================ regions

/// A solid circular cylinder (3D): the points within `radius` of the segment from a to b.
struct Cylinder {
  Vec3 a = Vec3::Zero(); ///< centre of one end [m]
  Vec3 b = Vec3::Zero(); ///< centre of the other end [m]
  double radius = 0.0;   ///< [m], > 0

  /// The cylinder around the axis through `point` along `direction` (any length), between the
  /// heights h0 < h1 [m] measured along the unit axis from `point`.
  static Cylinder along(const Vec3& point, const Vec3& direction, double radius, double h0,
                        double h1) {
    const double n = direction.norm();
    const Vec3 u = n > 0 ? Vec3(direction / n) : Vec3::Zero();
    return {point + h0 * u, point + h1 * u, radius};
  }
  void validate(const std::string& obj) const {
    for (int d = 0; d < 3; ++d) {
      detail::require_finite(obj + " (Cylinder)", "a component", a[d]);
      detail::require_finite(obj + " (Cylinder)", "b component", b[d]);
    }
    detail::require_positive(obj + " (Cylinder)", "radius", radius);
    detail::require((b - a).norm() > 0.0, obj + " (Cylinder)", "length |b - a|", (b - a).norm(),
                    "(0, inf) m");
  }
};

/// The inside of a closed triangle mesh (3D). The mesh must be closed and consistently
/// oriented: every edge belongs to exactly two triangles that run through it in opposite
/// directions (either orientation of the whole). Built once; the triangles are kept in a bucket
/// grid so that a test touches only the triangles near the point. Inside: odd parity of the
/// crossings of the ray from the point in +z, counted in the xy projection with a symbolic
/// perturbation of the point (an orientation that is exactly zero counts as positive when the
/// edge, taken from its lexicographically smaller end, points in +x, or in +y at equal x), so a
/// ray through an edge or a vertex is counted as for a ray beside it. Queries are const and keep
/// no state (several threads may share one object).
class ClosedMesh {
public:
  explicit ClosedMesh(const walls::TriangleMesh& mesh, std::string name = "ClosedMesh")
      : name_(std::move(name)) {
    build(mesh);
  }

  const std::string& name() const { return name_; }
  /// The bounding box [m].
  const Vec3& lo() const { return lo_; }
  const Vec3& hi() const { return hi_; }
  /// The enclosed volume [m^3]: |sum over triangles of a . (b x c) / 6|.
  double volume() const { return volume_; }

  /// True if x is inside (odd number of crossings of the ray x + t e_z, t > 0).
  bool contains(const Vec3& x) const {
    for (int d = 0; d < 3; ++d)
      if (!(x[d] >= lo_[d] && x[d] <= hi_[d])) return false;
    const auto c = coords(x);
    int crossings = 0;
    for (long k = c[2]; k < n_[2]; ++k) {
      const long cell = index({c[0], c[1], k});
      for (auto t = start_[cell]; t < start_[cell + 1]; ++t) {
        const std::uint32_t f = items_[t];
        double z;
        if (!crossing(f, x, z) || !(z > x.z())) continue;
        // count the crossing in the one cell of the column that holds it
        if (std::clamp(static_cast<long>(std::floor((z - lo_.z()) * inv_[2])), 0L, n_[2] - 1) != k)
          continue;
        ++crossings;
      }
    }
    return crossings % 2 == 1;
  }

  /// True if some triangle lies closer than `r` to x.
  bool near_surface(const Vec3& x, double r) const {
    bool found = false;
    for_triangles_near(x, r, [&](std::uint32_t f) {
      if ((closest_point(f, x) - x).squaredNorm() < r * r) found = true;
      return found;
    });
    return found;
  }

  /// The nearest point of the surface to x [m] (search radius `r` first, then all triangles).
  Vec3 nearest_point(const Vec3& x, double r) const {
    double best = std::numeric_limits<double>::infinity();
    Vec3 p = x;
    auto take = [&](std::uint32_t f) {
      const Vec3 q = closest_point(f, x);
      const double d2 = (q - x).squaredNorm();
      if (d2 < best) best = d2, p = q;
      return false;
    };
    for_triangles_near(x, r, take);
    if (!(best <= r * r))
      for (std::uint32_t f = 0; f < tris_.size(); ++f)
        take(f);
    return p;
  }

private:
  struct Tri {
    std::array<Vec3, 3> p;
  };

  void build(const walls::TriangleMesh& mesh) {
    const std::string obj = "generate::ClosedMesh '" + name_ + "'";
    if (mesh.triangles.size() < 4)
      throw InputError(obj + ": triangles = " + std::to_string(mesh.triangles.size()) +
                       " is invalid; valid range: [4, inf) (a closed surface)");
    for (const auto& v : mesh.vertices)
      detail::require(all_finite(v), obj, "vertex", "(non-finite)", "finite coordinates");
    // closed and consistently oriented: each undirected edge twice, once in each direction
    struct E {
      std::uint32_t lo, hi;
      int dir;
    };
    std::vector<E> edges;
    edges.reserve(3 * mesh.triangles.size());
    lo_ = Vec3::Constant(std::numeric_limits<double>::infinity());
    hi_ = -lo_;
    double six_volume = 0.0;
    for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
      const auto& t = mesh.triangles[f];
      Tri tri;
      for (int k = 0; k < 3; ++k) {
        detail::require(t[k] < mesh.vertices.size(), obj,
                        ("vertex index of triangle " + std::to_string(f)).c_str(), t[k],
                        "[0, " + std::to_string(mesh.vertices.size()) + ")");
        tri.p[k] = mesh.vertices[t[k]];
        lo_ = lo_.cwiseMin(tri.p[k]);
        hi_ = hi_.cwiseMax(tri.p[k]);
      }
      const double area2 = (tri.p[1] - tri.p[0]).cross(tri.p[2] - tri.p[0]).norm();
      detail::require(area2 > 0.0, obj, ("area of triangle " + std::to_string(f)).c_str(),
                      0.5 * area2, "(0, inf) m^2");
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t a = t[k], b = t[(k + 1) % 3];
        edges.push_back({std::min(a, b), std::max(a, b), a < b ? 1 : -1});
      }
      six_volume += tri.p[0].dot(tri.p[1].cross(tri.p[2]));
      tris_.push_back(tri);
    }
    std::sort(edges.begin(), edges.end(),
              [](const E& x, const E& y) { return x.lo != y.lo ? x.lo < y.lo : x.hi < y.hi; });
    for (std::size_t i = 0; i < edges.size();) {
      std::size_t j = i;
      int sum = 0;
      while (j < edges.size() && edges[j].lo == edges[i].lo && edges[j].hi == edges[i].hi)
        sum += edges[j++].dir;
      if (j - i != 2 || sum != 0)
        throw InputError(obj + ": edge (" + std::to_string(edges[i].lo) + ", " +
                         std::to_string(edges[i].hi) + ") is used by " + std::to_string(j - i) +
                         " triangle(s)" + (j - i == 2 ? " in the same direction" : "") +
                         "; valid: a closed, consistently oriented mesh (every edge in exactly "
                         "two triangles, in opposite directions)");
      i = j;
    }
    volume_ = std::abs(six_volume) / 6.0;
    detail::require(volume_ > 1e-12 * (hi_ - lo_).prod(), obj, "volume", volume_,
                    "(1e-12 x bounding-box volume, inf) m^3");
    // bucket grid: about two triangles per cell, at most 128 cells a side
    const Vec3 ext = hi_ - lo_;
    const double h = std::max({std::cbrt(ext.prod() / (2.0 * static_cast<double>(tris_.size()))),
                               ext.maxCoeff() / 128.0, 1e-300});
    for (int d = 0; d < 3; ++d) {
      n_[d] = std::clamp(static_cast<long>(std::ceil(ext[d] / h)), 1L, 128L);
      inv_[d] = ext[d] > 0 ? static_cast<double>(n_[d]) / ext[d] : 0.0;
    }
    std::vector<std::uint32_t> count(static_cast<std::size_t>(n_[0] * n_[1] * n_[2]) + 1, 0);
    auto each_cell = [&](const Tri& t, auto&& f) {
      Vec3 a = t.p[0].cwiseMin(t.p[1]).cwiseMin(t.p[2]);
      Vec3 b = t.p[0].cwiseMax(t.p[1]).cwiseMax(t.p[2]);
      const auto ca = coords(a), cb = coords(b);
      for (long k = ca[2]; k <= cb[2]; ++k)
        for (long j = ca[1]; j <= cb[1]; ++j)
          for (long i = ca[0]; i <= cb[0]; ++i)
            f(index({i, j, k}));
    };
    for (const auto& t : tris_)
      each_cell(t, [&](long c) { ++count[c + 1]; });
    for (std::size_t c = 1; c < count.size(); ++c)
      count[c] += count[c - 1];
    start_ = count;
    items_.resize(start_.back());
    for (std::uint32_t f = 0; f < tris_.size(); ++f)
      each_cell(tris_[f], [&](long c) { items_[count[c]++] = f; });
  }

  std::array<long, 3> coords(const Vec3& x) const {
    std::array<long, 3> c{};
    for (int d = 0; d < 3; ++d)
      c[d] = std::clamp(static_cast<long>(std::floor((x[d] - lo_[d]) * inv_[d])), 0L, n_[d] - 1);
    return c;
  }
  long index(const std::array<long, 3>& c) const { return c[0] + n_[0] * (c[1] + n_[1] * c[2]); }

  /// Calls f(triangle) for the triangles in the cells that the ball (x, r) touches (some more
  /// than once) until f returns true.
  template <class F>
  void for_triangles_near(const Vec3& x, double r, F&& f) const {
    const auto a = coords(Vec3(x.array() - r)), b = coords(Vec3(x.array() + r));
    for (long k = a[2]; k <= b[2]; ++k)
      for (long j = a[1]; j <= b[1]; ++j)
        for (long i = a[0]; i <= b[0]; ++i) {
          const long c = index({i, j, k});
          for (auto t = start_[c]; t < start_[c + 1]; ++t)
            if (f(items_[t])) return;
        }
  }

  /// Sign of the orientation of x against the projected edge p -> q, perturbed symbolically (see
  /// the class comment); the edge is evaluated from its lexicographically smaller end, so that
  /// two triangles sharing it compute the same number.
  static int side(const Vec3& p, const Vec3& q, const Vec3& x) {
    const bool flip = q.x() < p.x() || (q.x() == p.x() && q.y() < p.y());
    const Vec3& s = flip ? q : p;
    const Vec3& e = flip ? p : q;
    const double dx = e.x() - s.x(), dy = e.y() - s.y();
    const double o = dx * (x.y() - s.y()) - dy * (x.x() - s.x());
    int sign = o > 0 ? 1 : o < 0 ? -1 : (dx > 0 || (dx == 0 && dy > 0)) ? 1 : -1;
    return flip ? -sign : sign;
  }

  /// True if the vertical line through x crosses triangle f (perturbed); z the crossing height.
  bool crossing(std::uint32_t f, const Vec3& x, double& z) const {
    const auto& p = tris_[f].p;
    const int s0 = side(p[1], p[2], x), s1 = side(p[2], p[0], x), s2 = side(p[0], p[1], x);
    if (s0 != s1 || s1 != s2) return false;
    const auto area = [](const Vec3& a, const Vec3& b, const Vec3& c) {
      return (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
    };
    const double A = area(p[0], p[1], p[2]);
    if (A == 0.0) {
      z = std::max({p[0].z(), p[1].z(), p[2].z()});
      return true;
    }
    const double l0 = area(x, p[1], p[2]) / A, l1 = area(p[0], x, p[2]) / A;
    z = l0 * p[0].z() + l1 * p[1].z() + (1.0 - l0 - l1) * p[2].z();
    // within the triangle's heights: rounded outside them (a flat face on a bucket boundary), the
    // crossing would fall in a cell that does not hold the triangle and go uncounted
    z = std::clamp(z, std::min({p[0].z(), p[1].z(), p[2].z()}),
                   std::max({p[0].z(), p[1].z(), p[2].z()}));
    return true;
  }

  /// The point of triangle f nearest to x: the projection onto its plane if that lies inside
  /// (barycentric u, v >= 0, u + v <= 1), else the nearest point of its three edges.
  Vec3 closest_point(std::uint32_t f, const Vec3& x) const {
    const auto& p = tris_[f].p;
    const Vec3 e1 = p[1] - p[0], e2 = p[2] - p[0], w = x - p[0];
    const Vec3 n = e1.cross(e2);
    const double nn = n.squaredNorm();
    const double u = w.cross(e2).dot(n) / nn, v = e1.cross(w).dot(n) / nn;
    if (u >= 0 && v >= 0 && u + v <= 1) return p[0] + u * e1 + v * e2;
    Vec3 best = p[0];
    double best2 = std::numeric_limits<double>::infinity();
    for (int k = 0; k < 3; ++k) {
      const Vec3& a = p[k];
      const Vec3 ab = p[(k + 1) % 3] - a;
      const double s = std::clamp((x - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
      const Vec3 q = a + s * ab;
      const double d2 = (q - x).squaredNorm();
      if (d2 < best2) best2 = d2, best = q;
    }
    return best;
  }

  std::string name_;
  std::vector<Tri> tris_;
  Vec3 lo_ = Vec3::Zero(), hi_ = Vec3::Zero();
  double volume_ = 0.0;
  std::array<long, 3> n_{1, 1, 1};
  std::array<double, 3> inv_{0, 0, 0};
  std::vector<std::uint32_t> start_, items_;
};

// ============================================================================ options, result

/// How the particles are placed (see the file comment).
enum class Mode { random, lattice, grow };
/// Lattice of `Mode::lattice`.
enum class Lattice {
  cubic,    ///< simple cubic (3D), square (2D)
  hexagonal ///< hexagonal close-packed, layers ABAB (3D); triangular (2D)
};

/// Settings of the radius growth (`Mode::grow`, `generate::grow`).
struct Growth {
  /// Solid fraction of the random start (radii shrunk to it) [-]; 0 = 0.3 (3D), 0.45 (2D).
  double start_fraction = 0.0;
  /// Largest overlap r_i + r_j - |x_i - x_j| left by the relaxation of a growth step, relative to
  /// the smaller radius [-] (removed at the end by a common shrink of the radii).
  double tolerance = 1e-2;
  /// Relaxation sweeps allowed per growth step.
  std::size_t max_sweeps = 100;
  /// A pair with overlap o is pushed apart by over_relaxation x o (half each) [-], in (0, 2).
  double over_relaxation = 1.8;
  /// First relative growth of the radii per step [-] (raised by half after each step that
  /// relaxed, up to this value; halved after each that did not).
  double step = 0.01;
  /// The growth stops (jammed) when the step falls below this [-].
  double min_step = 1e-4;
};

/// What to generate. Give one target: `count` or `solid_fraction` (in lattice mode neither:
/// every site).
struct Options {
  std::uint32_t material = 0;  ///< material index of every particle (from add_material)
  std::size_t count = 0;       ///< number of particles, or 0
  double solid_fraction = 0.0; ///< solid fraction in (0, 1), or 0
  Mode mode = Mode::random;
  Lattice lattice = Lattice::cubic;
  double gap = 0.0;          ///< lattice: extra distance between neighbouring particles [m]
  std::uint64_t seed = 1;    ///< of the radii and the positions
  bool largest_first = true; ///< random, grow: place the radii in decreasing order
  /// random, grow: consecutive failed trial positions of one particle after which the fill
  /// stops.
  std::size_t max_failures = 20000;
  /// On a target not reached: return what was placed (Result::complete = false) instead of
  /// throwing InputError.
  bool partial = false;
  Growth growth{}; ///< Mode::grow
};

/// A generated packing.
template <int D>
struct Result {
  std::vector<ParticleSpec<D>> particles; ///< centre, radius, material; id -1
  double solid_fraction = 0.0;            ///< reached: sum V_i / V_region [-]
  double target_fraction = 0.0;           ///< of all M particles that were to be placed [-]
  std::size_t target_count = 0;           ///< M
  std::size_t attempts = 0;               ///< trial positions (random, grow) or lattice sites
  std::size_t sweeps = 0;                 ///< relaxation sweeps (grow)
  double radius_scale = 1.0;              ///< factor of the drawn radii (grow: < 1 if it jammed)
  bool complete = true;                   ///< target reached
};

/// Adds the particles of a result to a simulation; returns their ids (in order).
template <class Sim, int D>
std::vector<std::int64_t> add_to(Sim& sim, const Result<D>& result) {
  std::vector<std::int64_t> ids;
  ids.reserve(result.particles.size());
  for (const auto& p : result.particles)
    ids.push_back(sim.add_particle(p));
  return ids;
}

// ============================================================================ details

namespace detail {

using grain::detail::require;
using grain::detail::require_finite;
using grain::detail::require_positive;
using grain::detail::to_text;

template <class R>
struct region_dimension;
template <int D>
struct region_dimension<regions::Box<D>> : std::integral_constant<int, D> {};
template <int D>
struct region_dimension<regions::Ball<D>> : std::integral_constant<int, D> {};
template <>
struct region_dimension<regions::Polygon> : std::integral_constant<int, 2> {};
template <>
struct region_dimension<Cylinder> : std::integral_constant<int, 3> {};
template <>
struct region_dimension<ClosedMesh> : std::integral_constant<int, 3> {};

/// Volume (3D) or area (2D) of a particle of radius r.
template <int D>
double particle_volume(double r) {
  if constexpr (D == 3)
    return 4.0 / 3.0 * std::numbers::pi * r * r * r;
  else
    return std::numbers::pi * r * r;
}

// ---- regions: name, check, bounding box, measure, fits, push_inside
template <int D>
const char* region_name(const regions::Box<D>&) {
  return "Box";
}
template <int D>
const char* region_name(const regions::Ball<D>&) {
  return "Ball";
}
inline const char* region_name(const regions::Polygon&) { return "Polygon"; }
inline const char* region_name(const Cylinder&) { return "Cylinder"; }
inline const char* region_name(const ClosedMesh&) { return "ClosedMesh"; }

template <int D>
void check_region(const regions::Box<D>& b, const std::string& obj) {
  b.validate(obj);
}
template <int D>
void check_region(const regions::Ball<D>& b, const std::string& obj) {
  b.validate(obj);
}
inline void check_region(const regions::Polygon& p, const std::string& obj) { p.validate(obj); }
inline void check_region(const Cylinder& c, const std::string& obj) { c.validate(obj); }
inline void check_region(const ClosedMesh&, const std::string&) {} // checked when built

template <int D>
std::pair<Vec<D>, Vec<D>> bounds(const regions::Box<D>& b) {
  return {b.lo, b.hi};
}
template <int D>
std::pair<Vec<D>, Vec<D>> bounds(const regions::Ball<D>& b) {
  return {Vec<D>(b.center.array() - b.radius), Vec<D>(b.center.array() + b.radius)};
}
inline std::pair<Vec2, Vec2> bounds(const regions::Polygon& p) {
  Vec2 lo = p.vertices.front(), hi = lo;
  for (const auto& v : p.vertices)
    lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
  return {lo, hi};
}
inline std::pair<Vec3, Vec3> bounds(const Cylinder& c) {
  const Vec3 u = (c.b - c.a).normalized();
  Vec3 e;
  for (int d = 0; d < 3; ++d)
    e[d] = c.radius * std::sqrt(std::max(0.0, 1.0 - u[d] * u[d]));
  return {Vec3(c.a.cwiseMin(c.b) - e), Vec3(c.a.cwiseMax(c.b) + e)};
}
inline std::pair<Vec3, Vec3> bounds(const ClosedMesh& m) { return {m.lo(), m.hi()}; }

template <int D>
double measure(const regions::Box<D>& b) {
  return (b.hi - b.lo).prod();
}
template <int D>
double measure(const regions::Ball<D>& b) {
  return particle_volume<D>(b.radius);
}
inline double measure(const regions::Polygon& p) {
  const Vec2 o = p.vertices.front();
  double a2 = 0.0;
  for (std::size_t k = 0, l = p.vertices.size() - 1; k < p.vertices.size(); l = k++) {
    const Vec2 a = p.vertices[l] - o, b = p.vertices[k] - o;
    a2 += a.x() * b.y() - b.x() * a.y();
  }
  return 0.5 * std::abs(a2);
}
inline double measure(const Cylinder& c) {
  return std::numbers::pi * c.radius * c.radius * (c.b - c.a).norm();
}
inline double measure(const ClosedMesh& m) { return m.volume(); }

template <int D>
bool fits(const regions::Box<D>& b, const Vec<D>& x, double r) {
  return (x.array() - r >= b.lo.array()).all() && (x.array() + r <= b.hi.array()).all();
}
template <int D>
bool fits(const regions::Ball<D>& b, const Vec<D>& x, double r) {
  return r <= b.radius && (x - b.center).squaredNorm() <= (b.radius - r) * (b.radius - r);
}
/// The point of the polygon's boundary nearest to x.
inline Vec2 polygon_nearest(const regions::Polygon& p, const Vec2& x) {
  double best = std::numeric_limits<double>::infinity();
  Vec2 q = x;
  for (std::size_t k = 0, l = p.vertices.size() - 1; k < p.vertices.size(); l = k++) {
    const Vec2& a = p.vertices[l];
    const Vec2 ab = p.vertices[k] - a;
    const double s = std::clamp((x - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
    const Vec2 c = a + s * ab;
    const double d2 = (c - x).squaredNorm();
    if (d2 < best) best = d2, q = c;
  }
  return q;
}
inline bool fits(const regions::Polygon& p, const Vec2& x, double r) {
  return p.contains(x) && (polygon_nearest(p, x) - x).squaredNorm() >= r * r;
}
inline bool fits(const Cylinder& c, const Vec3& x, double r) {
  const Vec3 axis = c.b - c.a;
  const double len = axis.norm();
  const Vec3 u = axis / len;
  const Vec3 w = x - c.a;
  const double t = w.dot(u);
  if (!(t >= r && t <= len - r) || r > c.radius) return false;
  return (w - t * u).squaredNorm() <= (c.radius - r) * (c.radius - r);
}
inline bool fits(const ClosedMesh& m, const Vec3& x, double r) {
  for (int d = 0; d < 3; ++d)
    if (!(x[d] - r >= m.lo()[d] && x[d] + r <= m.hi()[d])) return false;
  return !m.near_surface(x, r) && m.contains(x);
}

template <int D>
Vec<D> push_inside(const regions::Box<D>& b, const Vec<D>& x, double r) {
  Vec<D> y = x;
  for (int d = 0; d < D; ++d)
    y[d] = b.hi[d] - b.lo[d] < 2 * r ? 0.5 * (b.lo[d] + b.hi[d])
                                     : std::clamp(x[d], b.lo[d] + r, b.hi[d] - r);
  return y;
}
template <int D>
Vec<D> push_inside(const regions::Ball<D>& b, const Vec<D>& x, double r) {
  const Vec<D> w = x - b.center;
  const double n = w.norm(), room = std::max(0.0, b.radius - r);
  return n > room ? Vec<D>(b.center + w * (room / n)) : x;
}
/// Moves x to the point at distance r inside the boundary beyond its nearest boundary point q
/// (a region whose shape is given by a nearest-point function and an inside test).
template <int D>
Vec<D> push_from(const Vec<D>& x, const Vec<D>& q, double r, bool inside) {
  const Vec<D> w = x - q;
  const double d = w.norm();
  if (inside && d >= r) return x;
  if (d == 0.0) return x; // on the boundary: the next sweep moves it
  return inside ? Vec<D>(q + w * (r / d)) : Vec<D>(q - w * (r / d));
}
inline Vec2 push_inside(const regions::Polygon& p, const Vec2& x, double r) {
  return push_from<2>(x, polygon_nearest(p, x), r, p.contains(x));
}
inline Vec3 push_inside(const Cylinder& c, const Vec3& x, double r) {
  const Vec3 axis = c.b - c.a;
  const double len = axis.norm();
  const Vec3 u = axis / len;
  const Vec3 w = x - c.a;
  const double t = w.dot(u);
  const double tc = len < 2 * r ? 0.5 * len : std::clamp(t, r, len - r);
  const Vec3 radial = w - t * u;
  const double n = radial.norm(), room = std::max(0.0, c.radius - r);
  return c.a + tc * u + (n > room ? Vec3(radial * (room / n)) : radial);
}
inline Vec3 push_inside(const ClosedMesh& m, const Vec3& x, double r) {
  if (!m.near_surface(x, r) && m.contains(x)) return x;
  return push_from<3>(x, m.nearest_point(x, r), r, m.contains(x));
}

// ---- distributions
/// A checked distribution ready to sample.
class Sampler {
public:
  explicit Sampler(const Distribution& dist, int dimension) : dist_(dist) {
    std::visit([&](const auto& d) { check(d, dimension); }, dist_);
  }
  double sample(Random& rng) const {
    return std::visit([&](const auto& d) { return draw(d, rng); }, dist_);
  }
  /// The largest radius the distribution can give [m].
  double upper() const { return upper_; }

private:
  void check(const Constant& d, int) {
    require_positive("generate::Constant", "radius", d.radius);
    upper_ = d.radius;
  }
  void check(const Uniform& d, int) {
    require_positive("generate::Uniform", "min", d.min);
    require(std::isfinite(d.max) && d.max >= d.min, "generate::Uniform", "max", d.max,
            "[min, inf) = [" + to_text(d.min) + ", inf) m");
    upper_ = d.max;
  }
  static void check_bounds(const std::string& obj, double min, double max) {
    require_positive(obj, "min", min);
    require(std::isfinite(max) && max > min, obj, "max", max,
            "(min, inf) = (" + to_text(min) + ", inf) m");
  }
  /// Requires P(lo <= z <= hi) >= 1e-6 for a standard normal z (else rejection never ends).
  static void check_mass(const std::string& obj, double lo, double hi) {
    const double p = 0.5 * (std::erfc(-hi / std::sqrt(2.0)) - std::erfc(-lo / std::sqrt(2.0)));
    require(p >= 1e-6, obj, "probability of [min, max]", p,
            "[1e-6, 1] (bounds that hold some of the distribution)");
  }
  void check(const Normal& d, int) {
    require_finite("generate::Normal", "mean", d.mean);
    require_positive("generate::Normal", "std", d.std);
    check_bounds("generate::Normal", d.min, d.max);
    check_mass("generate::Normal", (d.min - d.mean) / d.std, (d.max - d.mean) / d.std);
    upper_ = d.max;
  }
  void check(const LogNormal& d, int) {
    require_positive("generate::LogNormal", "median", d.median);
    require_positive("generate::LogNormal", "sigma", d.sigma);
    check_bounds("generate::LogNormal", d.min, d.max);
    check_mass("generate::LogNormal", std::log(d.min / d.median) / d.sigma,
               std::log(d.max / d.median) / d.sigma);
    upper_ = d.max;
  }
  void check(const Discrete& d, int dimension) {
    const std::string obj = "generate::Discrete";
    require(!d.radii.empty(), obj, "number of radii", d.radii.size(), "[1, inf)");
    require(d.fractions.size() == d.radii.size(), obj, "number of fractions", d.fractions.size(),
            std::to_string(d.radii.size()) + " (one per radius)");
    double sum = 0.0;
    for (std::size_t k = 0; k < d.radii.size(); ++k) {
      require_positive(obj, ("radius " + std::to_string(k)).c_str(), d.radii[k]);
      grain::detail::require_in(obj, ("fraction " + std::to_string(k)).c_str(), d.fractions[k], 0.0,
                                1.0, "[0, 1]");
      sum += d.fractions[k];
      upper_ = std::max(upper_, d.radii[k]);
    }
    require(std::abs(sum - 1.0) <= 1e-9, obj, "sum of the fractions", sum, "[1 - 1e-9, 1 + 1e-9]");
    // number weights: mass fractions divided by r^D
    double total = 0.0;
    for (std::size_t k = 0; k < d.radii.size(); ++k) {
      const double w = d.basis == Discrete::Basis::number
                           ? d.fractions[k]
                           : d.fractions[k] / std::pow(d.radii[k], dimension);
      total += w;
      cumulative_.push_back(total);
    }
    for (auto& c : cumulative_)
      c /= total;
    cumulative_.back() = 1.0;
  }

  double draw(const Constant& d, Random&) const { return d.radius; }
  double draw(const Uniform& d, Random& rng) const { return rng.uniform(d.min, d.max); }
  double draw(const Normal& d, Random& rng) const {
    for (;;) {
      const double r = d.mean + d.std * rng.normal();
      if (r >= d.min && r <= d.max) return r;
    }
  }
  double draw(const LogNormal& d, Random& rng) const {
    for (;;) {
      const double r = d.median * std::exp(d.sigma * rng.normal());
      if (r >= d.min && r <= d.max) return r;
    }
  }
  double draw(const Discrete& d, Random& rng) const {
    const double u = rng.uniform();
    const auto k =
        std::upper_bound(cumulative_.begin(), cumulative_.end(), u) - cumulative_.begin();
    return d.radii[std::min<std::size_t>(k, d.radii.size() - 1)];
  }

  Distribution dist_;
  std::vector<double> cumulative_;
  double upper_ = 0.0;
};

// ---- cell grid of the overlap tests
/// A uniform grid over a box with linked lists of items; cells at least `h_min` wide, so that
/// items closer than h_min lie in neighbouring cells.
template <int D>
class CellGrid {
public:
  void reset(const Vec<D>& lo, const Vec<D>& hi, double h_min, std::size_t max_cells,
             std::size_t items) {
    lo_ = lo;
    const Vec<D> ext = hi - lo;
    const double h = std::max(
        h_min,
        std::pow(ext.prod() / static_cast<double>(std::max<std::size_t>(max_cells, 1)), 1.0 / D));
    std::size_t cells = 1;
    for (int d = 0; d < D; ++d) {
      n_[d] = std::max(1L, static_cast<long>(std::floor(ext[d] / h)));
      n_[d] = std::min(n_[d], 1L << 20);
      inv_[d] = static_cast<double>(n_[d]) / ext[d];
      cells *= static_cast<std::size_t>(n_[d]);
    }
    head_.assign(cells, -1);
    next_.assign(items, -1);
  }
  long cell(const Vec<D>& x) const {
    long c = 0;
    for (int d = D - 1; d >= 0; --d)
      c = c * n_[d] + coord(x, d);
    return c;
  }
  void insert(std::int32_t i, const Vec<D>& x) {
    const long c = cell(x);
    next_[i] = head_[c];
    head_[c] = i;
  }
  /// Calls f(j) for the items of the cells around x (3^D cells) until f returns true; returns
  /// whether it did.
  template <class F>
  bool any(const Vec<D>& x, F&& f) const {
    std::array<long, D> c{};
    for (int d = 0; d < D; ++d)
      c[d] = coord(x, d);
    if constexpr (D == 3) {
      for (long k = std::max(0L, c[2] - 1); k <= std::min(n_[2] - 1, c[2] + 1); ++k)
        for (long j = std::max(0L, c[1] - 1); j <= std::min(n_[1] - 1, c[1] + 1); ++j)
          for (long i = std::max(0L, c[0] - 1); i <= std::min(n_[0] - 1, c[0] + 1); ++i)
            for (std::int32_t q = head_[i + n_[0] * (j + n_[1] * k)]; q >= 0; q = next_[q])
              if (f(q)) return true;
    } else {
      for (long j = std::max(0L, c[1] - 1); j <= std::min(n_[1] - 1, c[1] + 1); ++j)
        for (long i = std::max(0L, c[0] - 1); i <= std::min(n_[0] - 1, c[0] + 1); ++i)
          for (std::int32_t q = head_[i + n_[0] * j]; q >= 0; q = next_[q])
            if (f(q)) return true;
    }
    return false;
  }

private:
  long coord(const Vec<D>& x, int d) const {
    return std::clamp(static_cast<long>(std::floor((x[d] - lo_[d]) * inv_[d])), 0L, n_[d] - 1);
  }
  Vec<D> lo_ = Vec<D>::Zero();
  std::array<long, D> n_{};
  std::array<double, D> inv_{};
  std::vector<std::int32_t> head_, next_;
};

/// The grid of random sequential addition: cells at least `h_min` wide, each holding the centres
/// and radii of its particles inline (`per_cell` slots, the rest in a linked overflow list), so
/// that an overlap test reads a few contiguous blocks of memory.
template <int D>
class SlotGrid {
public:
  void reset(const Vec<D>& lo, const Vec<D>& hi, double h_min, std::size_t max_cells,
             std::size_t items) {
    lo_ = lo;
    const Vec<D> ext = hi - lo;
    const double h = std::max(
        h_min,
        std::pow(ext.prod() / static_cast<double>(std::max<std::size_t>(max_cells, 1)), 1.0 / D));
    std::size_t cells = 1;
    for (int d = 0; d < D; ++d) {
      n_[d] = std::clamp(static_cast<long>(std::floor(ext[d] / h)), 1L, 1L << 20);
      inv_[d] = static_cast<double>(n_[d]) / ext[d];
      cells *= static_cast<std::size_t>(n_[d]);
    }
    per_cell_ = std::clamp<std::size_t>(2 * items / cells + 1, 2, 16);
    slots_.assign(cells * per_cell_, Item{});
    count_.assign(cells, 0);
    over_head_.assign(cells, -1);
    over_.clear();
  }
  void insert(const Vec<D>& x, double r) {
    const long c = cell(x);
    if (count_[c] < per_cell_) {
      slots_[c * per_cell_ + count_[c]++] = Item{x, r, -1};
    } else {
      over_.push_back(Item{x, r, over_head_[c]});
      over_head_[c] = static_cast<std::int32_t>(over_.size() - 1);
    }
  }
  /// True if a stored ball overlaps the ball (x, r) (|x - x_j| < r + r_j).
  bool overlaps(const Vec<D>& x, double r) const {
    std::array<long, D> c{}, a{}, b{};
    for (int d = 0; d < D; ++d) {
      c[d] = coord(x, d);
      a[d] = std::max(0L, c[d] - 1);
      b[d] = std::min(n_[d] - 1, c[d] + 1);
    }
    auto test = [&](long k) {
      const Item* it = &slots_[k * per_cell_];
      for (std::size_t q = 0, m = count_[k]; q < m; ++q) {
        const double s = r + it[q].r;
        if ((it[q].x - x).squaredNorm() < s * s) return true;
      }
      for (std::int32_t q = over_head_[k]; q >= 0; q = over_[q].next) {
        const double s = r + over_[q].r;
        if ((over_[q].x - x).squaredNorm() < s * s) return true;
      }
      return false;
    };
    if constexpr (D == 3) {
      if (test(c[0] + n_[0] * (c[1] + n_[1] * c[2]))) return true; // the likeliest first
      for (long k = a[2]; k <= b[2]; ++k)
        for (long j = a[1]; j <= b[1]; ++j)
          for (long i = a[0]; i <= b[0]; ++i)
            if ((i != c[0] || j != c[1] || k != c[2]) && test(i + n_[0] * (j + n_[1] * k)))
              return true;
    } else {
      if (test(c[0] + n_[0] * c[1])) return true;
      for (long j = a[1]; j <= b[1]; ++j)
        for (long i = a[0]; i <= b[0]; ++i)
          if ((i != c[0] || j != c[1]) && test(i + n_[0] * j)) return true;
    }
    return false;
  }

private:
  struct Item {
    Vec<D> x = Vec<D>::Zero();
    double r = 0.0;
    std::int32_t next = -1; ///< overflow list
  };
  long coord(const Vec<D>& x, int d) const {
    return std::clamp(static_cast<long>(std::floor((x[d] - lo_[d]) * inv_[d])), 0L, n_[d] - 1);
  }
  long cell(const Vec<D>& x) const {
    long c = 0;
    for (int d = D - 1; d >= 0; --d)
      c = c * n_[d] + coord(x, d);
    return c;
  }
  Vec<D> lo_ = Vec<D>::Zero();
  std::array<long, D> n_{};
  std::array<double, D> inv_{};
  std::size_t per_cell_ = 2;
  std::vector<Item> slots_, over_;
  std::vector<std::uint8_t> count_;
  std::vector<std::int32_t> over_head_;
};

/// The radii to place: `count` draws, or draws until their volume sum is nearest
/// target_fraction x volume.
template <int D>
std::vector<double> draw_radii(const Sampler& s, Random& rng, std::size_t count, double fraction,
                               double volume) {
  std::vector<double> radii;
  if (count > 0) {
    radii.reserve(count);
    for (std::size_t k = 0; k < count; ++k)
      radii.push_back(s.sample(rng));
    return radii;
  }
  const double target = fraction * volume;
  double sum = 0.0;
  for (;;) {
    const double r = s.sample(rng);
    const double v = particle_volume<D>(r);
    if (!radii.empty() && std::abs(sum + v - target) >= std::abs(sum - target)) break;
    radii.push_back(r);
    sum += v;
    if (radii.size() > (std::size_t(1) << 31))
      throw InputError("generate::fill: solid_fraction = " + to_text(fraction) +
                       " needs more than 2^31 particles of this distribution in this region; "
                       "valid: a target of at most 2^31 particles");
  }
  return radii;
}

template <int D>
double volume_sum(const std::vector<double>& radii, std::size_t n, double scale = 1.0) {
  double v = 0.0;
  for (std::size_t k = 0; k < n; ++k)
    v += particle_volume<D>(scale * radii[k]);
  return v;
}

/// The failure message of a fill.
inline std::string shortfall(const std::string& obj, std::size_t placed, std::size_t wanted,
                             double fraction, double target, std::size_t attempts,
                             const std::string& why) {
  return obj + ": placed " + std::to_string(placed) + " of " + std::to_string(wanted) +
         " particles, solid fraction " + to_text(fraction) + " of " + to_text(target) + ", after " +
         std::to_string(attempts) + " attempts; " + why;
}

/// Random sequential addition of `radii` (in this order) with the scale factor `scale`.
/// Returns the number placed; `x` receives the centres.
template <int D, class R>
std::size_t place_random(const R& region, const std::vector<double>& radii, double scale,
                         Random& rng, std::size_t max_failures, std::vector<Vec<D>>& x,
                         std::size_t& attempts) {
  const auto [lo, hi] = bounds(region);
  const std::size_t n = radii.size();
  double r_max = 0.0;
  for (double r : radii)
    r_max = std::max(r_max, scale * r);
  SlotGrid<D> grid;
  grid.reset(lo, hi, 2.0 * r_max * (1.0 + 1e-12), 2 * n + 64, n);
  x.clear();
  x.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double r = scale * radii[i];
    bool room = true;
    for (int d = 0; d < D; ++d)
      room = room && lo[d] + r <= hi[d] - r;
    std::size_t failures = 0;
    bool done = false;
    while (room && failures < max_failures) {
      ++attempts;
      Vec<D> c;
      for (int d = 0; d < D; ++d)
        c[d] = rng.uniform(lo[d] + r, hi[d] - r);
      if (fits(region, c, r) && !grid.overlaps(c, r)) {
        grid.insert(c, r);
        x.push_back(c);
        done = true;
        break;
      }
      ++failures;
    }
    if (!done) return i;
  }
  return n;
}

/// Lattice sites (first at lo + a/2, spacing a) where a ball of radius a/2 fits the region, in
/// the order z (3D), y, x.
template <int D, class R>
std::vector<Vec<D>> lattice_sites(const R& region, Lattice kind, double a, std::size_t& tested) {
  const auto [lo, hi] = bounds(region);
  std::vector<Vec<D>> sites;
  const bool hex = kind == Lattice::hexagonal;
  const double row = hex ? a * std::sqrt(3.0) / 2.0 : a;   // row spacing in y
  const double layer = hex ? a * std::sqrt(2.0 / 3.0) : a; // layer spacing in z (3D)
  const long layers =
      D == 3 ? static_cast<long>(std::floor((hi[D - 1] - lo[D - 1]) / layer)) + 1 : 1;
  for (long m = 0; m < layers; ++m) {
    const bool b_layer = hex && (m % 2 == 1);
    const double y0 = lo[1] + 0.5 * a + (b_layer ? row / 3.0 : 0.0);
    const long rows = static_cast<long>(std::floor((hi[1] - y0) / row)) + 1;
    for (long j = 0; j < rows; ++j) {
      const double x0 =
          lo[0] + 0.5 * a + ((hex && j % 2 == 1) ? 0.5 * a : 0.0) + (b_layer ? 0.5 * a : 0.0);
      const long cols = static_cast<long>(std::floor((hi[0] - x0) / a)) + 1;
      for (long i = 0; i < cols; ++i) {
        Vec<D> s;
        s[0] = x0 + static_cast<double>(i) * a;
        s[1] = y0 + static_cast<double>(j) * row;
        if constexpr (D == 3) s[2] = lo[2] + 0.5 * a + static_cast<double>(m) * layer;
        ++tested;
        if (fits(region, s, 0.5 * a)) sites.push_back(s);
      }
    }
  }
  return sites;
}

/// Radius growth: radii r0_k s with s rising from s_start towards s_end (see the file comment).
/// Returns the scale reached (<= s_end); `x` holds the relaxed centres, and at that scale no two
/// particles overlap and every one fits the region.
template <int D, class R>
double grow_radii(const R& region, std::vector<Vec<D>>& x, const std::vector<double>& r0,
                  double s_start, double s_end, const Growth& g, std::size_t& sweeps) {
  const auto box = bounds(region);
  const Vec<D> lo = box.first, hi = box.second;
  const std::size_t n = x.size();
  double r0_max = 0.0;
  for (double r : r0)
    r0_max = std::max(r0_max, r);
  CellGrid<D> grid;
  auto build = [&](double sc) {
    grid.reset(lo, hi, 2.2 * r0_max * sc, 2 * n + 64, n);
    for (std::size_t i = 0; i < n; ++i)
      grid.insert(static_cast<std::int32_t>(i), x[i]);
  };
  // calls f(i, j, w = x_j - x_i, d^2, (r_i + r_j)^2) for the pairs closer than r_i + r_j
  auto for_overlaps = [&](double sc, auto&& f) {
    for (std::size_t i = 0; i < n; ++i) {
      const double ri = sc * r0[i];
      grid.any(x[i], [&](std::int32_t jj) {
        const auto j = static_cast<std::size_t>(jj);
        if (j <= i) return false;
        const double rj = sc * r0[j];
        const Vec<D> w = x[j] - x[i];
        const double d2 = w.squaredNorm(), s2 = (ri + rj) * (ri + rj);
        if (d2 < s2) f(i, j, w, d2, ri, rj);
        return false;
      });
    }
  };
  // the pairs closer than r_i + r_j + skin, rebuilt when a particle has moved skin / 2
  std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;
  std::vector<Vec<D>> x_built;
  double built_scale = -1.0, skin = 0.0;
  auto update_pairs = [&](double sc) {
    bool stale = sc != built_scale;
    for (std::size_t i = 0; i < n && !stale; ++i)
      stale = (x[i] - x_built[i]).squaredNorm() > 0.25 * skin * skin;
    if (!stale) return;
    skin = 0.2 * sc * r0_max;
    grid.reset(lo, hi, 2.0 * r0_max * sc + skin, 2 * n + 64, n);
    for (std::size_t i = 0; i < n; ++i)
      grid.insert(static_cast<std::int32_t>(i), x[i]);
    pairs.clear();
    for (std::size_t i = 0; i < n; ++i) {
      const double ri = sc * r0[i];
      grid.any(x[i], [&](std::int32_t jj) {
        const auto j = static_cast<std::size_t>(jj);
        const double c = ri + sc * r0[j] + skin;
        if (j > i && (x[j] - x[i]).squaredNorm() < c * c)
          pairs.emplace_back(static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(j));
        return false;
      });
    }
    x_built = x;
    built_scale = sc;
  };
  // one Gauss-Seidel sweep: every overlapping pair pushed apart by half its overlap each, then
  // every particle moved back inside; returns the largest overlap found relative to the smaller
  // radius, or displacement back inside relative to the radius
  auto sweep = [&](double sc) {
    ++sweeps;
    update_pairs(sc);
    double worst = 0.0;
    for (const auto& [i, j] : pairs) {
      const double ri = sc * r0[i], rj = sc * r0[j];
      const Vec<D> w = x[j] - x[i];
      const double d2 = w.squaredNorm();
      if (d2 >= (ri + rj) * (ri + rj)) continue;
      const double d = std::sqrt(d2);
      const double o = ri + rj - d;
      worst = std::max(worst, o / std::min(ri, rj));
      Vec<D> nrm = Vec<D>::Zero();
      if (d > 0)
        nrm = w / d;
      else
        nrm[0] = 1.0;
      x[i] -= g.over_relaxation * 0.5 * o * nrm;
      x[j] += g.over_relaxation * 0.5 * o * nrm;
    }
    for (std::size_t i = 0; i < n; ++i) {
      const double ri = sc * r0[i];
      const Vec<D> y = push_inside(region, x[i], ri);
      worst = std::max(worst, (y - x[i]).norm() / ri);
      x[i] = y;
    }
    return worst;
  };
  auto relax = [&](double sc) {
    for (std::size_t k = 0; k < g.max_sweeps; ++k)
      if (sweep(sc) <= g.tolerance) return true;
    return false;
  };

  // grow a little beyond s_end: the overlaps left (<= tolerance) are removed by a shrink below
  const double s_goal = s_end / (1.0 - std::min(0.5, g.tolerance));
  double s = s_start, step = g.step;
  std::vector<Vec<D>> saved = x;
  const bool relaxed = relax(s);
  while (s < s_goal) {
    if (!relaxed) break;
    const double next = std::min(s * (1.0 + step), s_goal);
    saved = x;
    if (relax(next)) {
      s = next;
      step = std::min(g.step, step * 1.5);
    } else {
      x = saved;
      step *= 0.5;
      if (step < g.min_step) break;
    }
  }
  if (!relaxed) s = s_start;

  // shrink: overlap o_ij <= e (r_i + r_j) and a boundary excess <= e r_i vanish for radii times
  // (1 - e); repeated (with e doubled) until an exact check passes
  double e = 0.0;
  build(s);
  for_overlaps(s, [&](std::size_t, std::size_t, const Vec<D>&, double d2, double ri, double rj) {
    e = std::max(e, 1.0 - std::sqrt(d2) / (ri + rj));
  });
  for (std::size_t i = 0; i < n; ++i)
    e = std::max(e, (push_inside(region, x[i], s * r0[i]) - x[i]).norm() / (s * r0[i]));
  for (int round = 0; round < 64; ++round) {
    const double sc = std::min(s_end, s * (1.0 - e) * (1.0 - 1e-14));
    bool ok = true;
    for (std::size_t i = 0; i < n && ok; ++i)
      ok = fits(region, x[i], sc * r0[i]);
    if (ok) {
      build(sc);
      for_overlaps(
          sc, [&](std::size_t, std::size_t, const Vec<D>&, double, double, double) { ok = false; });
    }
    if (ok) return sc;
    e = std::max(2.0 * e, 1e-12);
  }
  throw NumericalError("generate::grow: the grown packing could not be made free of overlaps");
}

template <class R>
std::string object_name(const R& region) {
  return std::string("generate::fill (") + region_name(region) + ")";
}

inline void check_growth(const Growth& g) {
  const std::string obj = "generate::Growth";
  grain::detail::require_in(obj, "start_fraction", g.start_fraction, 0.0, 1.0, "[0, 1)");
  require(g.start_fraction < 1.0, obj, "start_fraction", g.start_fraction, "[0, 1)");
  require_positive(obj, "tolerance", g.tolerance);
  require(g.max_sweeps > 0, obj, "max_sweeps", g.max_sweeps, "[1, inf)");
  require_positive(obj, "step", g.step);
  require_positive(obj, "min_step", g.min_step);
  require(std::isfinite(g.over_relaxation) && g.over_relaxation > 0.0 && g.over_relaxation < 2.0,
          obj, "over_relaxation", g.over_relaxation, "(0, 2)");
}

} // namespace detail

// ============================================================================ entry points

/// Fills `region` with non-overlapping particles whose radii follow `distribution` (see the file
/// comment). Throws InputError naming the parameter for bad input, and "placed N of M
/// particles, solid fraction x of y, after K attempts" when the target is not reached (unless
/// `options.partial`).
template <class R>
Result<detail::region_dimension<R>::value> fill(const R& region, const Distribution& distribution,
                                                const Options& options = {}) {
  constexpr int D = detail::region_dimension<R>::value;
  const std::string obj = detail::object_name(region);
  detail::check_region(region, obj);
  const detail::Sampler sampler(distribution, D);
  const bool has_count = options.count > 0, has_fraction = options.solid_fraction != 0.0;
  if (has_fraction)
    detail::require(std::isfinite(options.solid_fraction) && options.solid_fraction > 0.0 &&
                        options.solid_fraction < 1.0,
                    obj, "solid_fraction", options.solid_fraction, "(0, 1)");
  if (has_count && has_fraction)
    throw InputError(obj + ": count = " + std::to_string(options.count) +
                     " and solid_fraction = " + detail::to_text(options.solid_fraction) +
                     " are both given; valid: one target (the other 0)");
  if (!has_count && !has_fraction && options.mode != Mode::lattice)
    throw InputError(obj + ": count = 0 and solid_fraction = 0; valid: one target, count in "
                           "[1, inf) or solid_fraction in (0, 1)");
  detail::require(std::isfinite(options.gap) && options.gap >= 0.0, obj, "gap", options.gap,
                  "[0, inf) m");
  detail::require(options.max_failures > 0, obj, "max_failures", options.max_failures, "[1, inf)");
  detail::check_growth(options.growth);

  const double volume = detail::measure(region);
  Random rng(options.seed);
  Result<D> out;
  std::vector<Vec<D>> x;
  std::vector<double> radii;
  std::string failure;

  if (options.mode == Mode::lattice) {
    const double a = 2.0 * sampler.upper() + options.gap;
    std::vector<Vec<D>> sites = detail::lattice_sites<D>(region, options.lattice, a, out.attempts);
    std::size_t n = sites.size();
    if (has_count) {
      if (n >= options.count) {
        n = options.count;
        for (std::size_t k = 0; k < n; ++k)
          radii.push_back(sampler.sample(rng));
        out.target_count = n;
      } else {
        for (std::size_t k = 0; k < options.count; ++k)
          radii.push_back(sampler.sample(rng));
        out.target_count = options.count;
        failure = "the lattice has " + std::to_string(n) + " sites in the region";
      }
      out.target_fraction = detail::volume_sum<D>(radii, radii.size()) / volume;
    } else if (has_fraction) {
      // radii for the sites in order until their volume sum is nearest the target
      const double target = options.solid_fraction * volume;
      double sum = 0.0;
      bool reached = false;
      while (radii.size() < n) {
        const double r = sampler.sample(rng);
        const double v = detail::particle_volume<D>(r);
        if (!radii.empty() && std::abs(sum + v - target) >= std::abs(sum - target)) {
          reached = true;
          break;
        }
        radii.push_back(r);
        sum += v;
      }
      n = radii.size();
      out.target_fraction = options.solid_fraction;
      out.target_count = n;
      if (!reached && n > 0 && target - sum > 0.5 * detail::particle_volume<D>(sampler.upper())) {
        // as many more as the mean volume so far says
        out.target_count = static_cast<std::size_t>(std::llround(target / (sum / double(n))));
        failure = "every one of the " + std::to_string(n) + " lattice sites in the region is taken";
      }
    } else {
      for (std::size_t k = 0; k < n; ++k)
        radii.push_back(sampler.sample(rng));
      out.target_count = n;
      out.target_fraction = detail::volume_sum<D>(radii, n) / volume;
    }
    n = std::min(n, sites.size());
    if (n == 0 && failure.empty())
      failure = "no site of the lattice of spacing " + detail::to_text(a) +
                " m (2 x largest radius + gap) fits the region";
    sites.resize(n);
    x = std::move(sites);
  } else {
    radii = detail::draw_radii<D>(sampler, rng, options.count, options.solid_fraction, volume);
    if (options.largest_first) std::stable_sort(radii.begin(), radii.end(), std::greater<>());
    out.target_count = radii.size();
    out.target_fraction =
        has_fraction ? options.solid_fraction : detail::volume_sum<D>(radii, radii.size()) / volume;
    double scale = 1.0;
    if (options.mode == Mode::grow) {
      const double start =
          options.growth.start_fraction > 0 ? options.growth.start_fraction : (D == 3 ? 0.3 : 0.45);
      const double full = detail::volume_sum<D>(radii, radii.size()) / volume;
      if (start < full) scale = std::pow(start / full, 1.0 / D);
    }
    const std::size_t placed =
        detail::place_random<D>(region, radii, scale, rng, options.max_failures, x, out.attempts);
    if (placed < radii.size()) {
      failure = "a particle of radius " + detail::to_text(scale * radii[placed]) +
                " m found no place in max_failures = " + std::to_string(options.max_failures) +
                " consecutive attempts (random sequential addition jams near solid fraction "
                "0.38 in 3D, 0.55 in 2D; use Mode::grow or settle the particles for denser "
                "packings)";
      if (options.mode == Mode::grow) out.radius_scale = scale;
    } else if (options.mode == Mode::grow) {
      out.radius_scale =
          detail::grow_radii<D>(region, x, radii, scale, 1.0, options.growth, out.sweeps);
      if (out.radius_scale < 1.0) {
        const double reached =
            detail::volume_sum<D>(radii, radii.size(), out.radius_scale) / volume;
        const std::string msg =
            obj + ": grown to solid fraction " + detail::to_text(reached) + " of " +
            detail::to_text(out.target_fraction) + " (radius factor " +
            detail::to_text(out.radius_scale) + " of 1) after " + std::to_string(out.sweeps) +
            " relaxation sweeps; placed " + std::to_string(x.size()) + " of " +
            std::to_string(radii.size()) +
            " particles at the drawn radii times the factor: the packing jammed (the growth step "
            "fell below Growth::min_step = " +
            detail::to_text(options.growth.min_step) + ")";
        if (!options.partial) throw InputError(msg);
        out.complete = false;
      }
    }
  }

  const double scale = out.radius_scale;
  out.particles.reserve(x.size());
  double solid = 0.0;
  for (std::size_t k = 0; k < x.size(); ++k) {
    ParticleSpec<D> p;
    p.position = x[k];
    p.radius = scale * radii[k];
    p.material = options.material;
    solid += detail::particle_volume<D>(p.radius);
    out.particles.push_back(p);
  }
  out.solid_fraction = solid / volume;
  if (!failure.empty()) {
    out.complete = false;
    if (!options.partial)
      throw InputError(detail::shortfall(obj, x.size(), out.target_count, out.solid_fraction,
                                         out.target_fraction, out.attempts, failure));
  }
  return out;
}

/// Grows the radii of `packing` (particles inside `region`, not overlapping) by a common factor
/// until the solid fraction is `target` or the packing jams (see the file comment); returns the
/// packing with the grown radii, the fraction reached, the factor (`radius_scale`), the sweeps,
/// and `complete` = target reached. Throws InputError for bad input only.
template <class R>
Result<detail::region_dimension<R>::value> grow(const R& region,
                                                Result<detail::region_dimension<R>::value> packing,
                                                double target, const Growth& growth = {}) {
  constexpr int D = detail::region_dimension<R>::value;
  const std::string obj = std::string("generate::grow (") + detail::region_name(region) + ")";
  detail::check_region(region, obj);
  detail::check_growth(growth);
  detail::require(std::isfinite(target) && target > 0.0 && target < 1.0, obj, "target", target,
                  "(0, 1)");
  detail::require(!packing.particles.empty(), obj, "particles", packing.particles.size(),
                  "[1, inf)");
  const double volume = detail::measure(region);
  std::vector<Vec<D>> x;
  std::vector<double> r0;
  for (const auto& p : packing.particles) {
    detail::require_positive(obj, "radius", p.radius);
    x.push_back(p.position);
    r0.push_back(p.radius);
  }
  const double start = detail::volume_sum<D>(r0, r0.size()) / volume;
  const double s_end = std::pow(target / start, 1.0 / D);
  const double s =
      s_end > 1.0 ? detail::grow_radii<D>(region, x, r0, 1.0, s_end, growth, packing.sweeps) : 1.0;
  double solid = 0.0;
  for (std::size_t k = 0; k < x.size(); ++k) {
    packing.particles[k].position = x[k];
    packing.particles[k].radius = s * r0[k];
    solid += detail::particle_volume<D>(s * r0[k]);
  }
  packing.solid_fraction = solid / volume;
  packing.radius_scale *= s;
  packing.target_fraction = target;
  packing.complete = s >= s_end;
  return packing;
}

} // namespace grain::generate
