#pragma once
/// \file regions.hpp
/// Regions of space for the bounding box and the sinks of a simulation (lengths in m).
///
/// | region | 2D | 3D | contains x when |
/// |---|---|---|---|
/// | `regions::Box<D>{lo, hi}` | rectangle | box | lo <= x <= hi componentwise |
/// | `regions::Ball<D>{centre, radius}` | circle | sphere | |x - centre| <= radius |
/// | `regions::Polygon{vertices}` | polygon | - | x inside the simple polygon (even-odd rule) or on
/// its edge |
///
/// A particle leaves the bounding box when its centre is no longer contained; it enters a sink
/// when its centre is contained.

#include <grain/core/error.hpp>
#include <grain/core/vector.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <variant>
#include <vector>

namespace grain::regions {

/// Axis-aligned rectangle (2D) or box (3D).
template <int D>
struct Box {
  Vec<D> lo = Vec<D>::Zero(); ///< lower corner [m]
  Vec<D> hi = Vec<D>::Zero(); ///< upper corner [m]

  bool contains(const Vec<D>& x) const {
    return (x.array() >= lo.array()).all() && (x.array() <= hi.array()).all();
  }
  void validate(const std::string& obj) const {
    for (int d = 0; d < D; ++d) {
      detail::require_finite(obj + " (Box)", "lo component", lo[d]);
      detail::require_finite(obj + " (Box)", "hi component", hi[d]);
      detail::require(hi[d] > lo[d], obj + " (Box)", "hi component", hi[d],
                      "(lo, inf) = (" + detail::to_text(lo[d]) + ", inf) m");
    }
  }
};

/// Circle (2D) or sphere (3D).
template <int D>
struct Ball {
  Vec<D> center = Vec<D>::Zero(); ///< [m]
  double radius = 0.0;            ///< [m], > 0

  bool contains(const Vec<D>& x) const { return (x - center).squaredNorm() <= radius * radius; }
  void validate(const std::string& obj) const {
    for (int d = 0; d < D; ++d)
      detail::require_finite(obj + " (Ball)", "center component", center[d]);
    detail::require_positive(obj + " (Ball)", "radius", radius);
  }
};

/// Simple polygon (2D), vertices in order (either orientation), not repeated at the end.
struct Polygon {
  std::vector<Vec2> vertices; ///< [m], at least 3

  bool contains(const Vec2& x) const {
    const std::size_t n = vertices.size();
    bool in = false;
    for (std::size_t k = 0, l = n - 1; k < n; l = k++) {
      const Vec2& a = vertices[k];
      const Vec2& b = vertices[l];
      // on the edge counts as inside
      const Vec2 ab = b - a;
      const double len2 = ab.squaredNorm();
      const double s = len2 > 0 ? std::clamp((x - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
      if ((a + s * ab - x).squaredNorm() <= 1e-24 * (1.0 + len2)) return true;
      if ((a.y() > x.y()) != (b.y() > x.y()) &&
          x.x() < (b.x() - a.x()) * (x.y() - a.y()) / (b.y() - a.y()) + a.x())
        in = !in;
    }
    return in;
  }
  void validate(const std::string& obj) const {
    if (vertices.size() < 3)
      throw InputError(obj + " (Polygon): vertices = " + std::to_string(vertices.size()) +
                       " is invalid; valid range: [3, inf) vertices");
    for (const auto& v : vertices)
      detail::require(all_finite(v), obj + " (Polygon)", "vertex", "(non-finite)",
                      "finite coordinates");
    // twice the signed area (shoelace formula), taken about the first vertex so that its
    // round-off is ~eps times the squared extent, not times the squared distance to the origin;
    // collinear vertices give a round-off residue, not an exact zero, hence the relative bound
    const Vec2 o = vertices.front();
    Vec2 lo = o, hi = o;
    double area2 = 0.0;
    for (std::size_t k = 0, l = vertices.size() - 1; k < vertices.size(); l = k++) {
      const Vec2 a = vertices[l] - o, b = vertices[k] - o;
      area2 += a.x() * b.y() - b.x() * a.y();
      lo = lo.cwiseMin(vertices[k]);
      hi = hi.cwiseMax(vertices[k]);
    }
    const double min_area = 0.5e-10 * (hi - lo).squaredNorm();
    std::string range = "(";
    range += detail::to_text(min_area);
    range += ", inf) m^2 = (1e-10 x squared extent / 2, inf) (vertices not all on one line)";
    detail::require(0.5 * std::abs(area2) > min_area, obj + " (Polygon)", "area",
                    0.5 * std::abs(area2), range);
  }
};

} // namespace grain::regions

namespace grain {

/// A region of a D-dimensional simulation.
template <int D>
using Region =
    std::conditional_t<D == 2, std::variant<regions::Box<2>, regions::Ball<2>, regions::Polygon>,
                       std::variant<regions::Box<3>, regions::Ball<3>>>;

/// A region with an activity interval [t_begin, t_end] [s].
template <int D>
struct TimedRegion {
  Region<D> region;
  double t_begin = -std::numeric_limits<double>::infinity();
  double t_end = std::numeric_limits<double>::infinity();

  bool active(double t) const { return t >= t_begin && t <= t_end; }
  bool contains(const Vec<D>& x) const {
    return std::visit([&](const auto& r) { return r.contains(x); }, region);
  }
  void validate(const std::string& obj) const {
    std::visit([&](const auto& r) { r.validate(obj); }, region);
    detail::require(!std::isnan(t_begin) && t_begin < std::numeric_limits<double>::infinity(), obj,
                    "t_begin", t_begin, "[-inf, inf) s");
    detail::require(!std::isnan(t_end) && t_end >= t_begin, obj, "t_end", t_end,
                    "[t_begin, inf] = [" + detail::to_text(t_begin) + ", inf] s");
  }
};

} // namespace grain
