#pragma once
/// \file periodic.hpp
/// Periodic boundaries: the box [lo, hi) along the periodic axes, the nearest image of a
/// partner, and the Lees-Edwards shift of the images along y.
///
/// A particle that leaves the box along a periodic axis re-enters on the other side: its
/// position is wrapped into the box at each neighbour-list build (between builds it may lie
/// outside by up to half the skin) and its image count along that axis changes by one, so that
/// the unwrapped position x + sum_d image_d L_d e_d (+ the Lees-Edwards shift along x) is
/// continuous: the particle's path as if the box had no boundary. A pair interacts through the nearest image of the partner: the separation
/// x_j - x_i with each periodic component brought into [-L/2, L/2]. That image is unique while
/// L >= 2 (2 R_max + reach) along each periodic axis, which `Simulation` checks when it starts.
///
/// Lees-Edwards (sliding images, Lees and Edwards 1972, J. Phys. C 5, 1921): with a shear rate
/// gamma [1/s], the image of the box above (+L_y) moves along x at gamma L_y and is shifted by
/// offset(t) = gamma L_y t (mod L_x). A particle that leaves through the top re-enters through
/// the bottom with x - offset and v_x - gamma L_y (and the reverse through the bottom), and a
/// pair across the y boundary sees the partner's image with those shifts. The flow is along x,
/// its gradient along y; x and y must both be periodic.

#include <array>
#include <cmath>
#include <cstdint>
#include <grain/core/config.hpp>
#include <grain/core/vector.hpp>
#include <limits>

namespace grain {

template <int D>
struct PeriodicBox {
  using V = Vec<D>;
  std::array<bool, D> axis{}; ///< periodic along axis d
  V lo = V::Zero();           ///< lower bounds of the box along the periodic axes [m]
  V length = V::Zero();       ///< box lengths L_d along the periodic axes [m] (0 elsewhere)
  V half = V::Zero();         ///< L_d / 2 [m]
  /// L_d and 1/L_d along the periodic axes, 0 elsewhere: the nearest image without a branch
  /// (minimum_image).
  V wrap_length = V::Zero();
  V wrap_inverse = V::Zero();
  double shear_rate = 0.0;  ///< Lees-Edwards shear rate dv_x/dy [1/s]; 0 = plain periodic
  double slide = 0.0;       ///< how far the image above has moved along x, int gamma L_y dt [m]
  double offset = 0.0;      ///< x shift of the image above: slide mod L_x, in [0, L_x) [m]
  double time = 0.0;        ///< time of `slide` [s]
  double built_slide = 0.0; ///< `slide` at the last list build [m]
  bool on = false;          ///< some axis is periodic

  /// True under Lees-Edwards (a shear rate and periodic boundaries).
  bool sheared() const { return on && shear_rate != 0.0; }
  double hi(int d) const { return lo[d] + length[d]; }
  /// Velocity of the image above relative to the box, gamma L_y [m/s].
  double image_speed() const { return D >= 2 ? shear_rate * length[1] : 0.0; }

  /// Moves the sliding images on to time t [s] at the current shear rate (a change of the rate
  /// acts from the time of the change: the images do not jump).
  void move_to(double t) {
    if (sheared()) {
      slide += image_speed() * (t - time);
      offset = std::fmod(slide, length[0]);
      if (offset < 0.0) offset += length[0];
    }
    time = t;
  }
  /// How far the images across y have moved relative to the box since the last build [m].
  double travel() const { return std::abs(slide - built_slide); }

  /// Number of boxes along y the nearest image of a partner at separation d (x_j - x_i) lies
  /// from the partner (-1, 0 or 1): the image is at x_j - cy L_y e_y (- cy offset e_x).
  GRAIN_INLINE double images_y(const V& d) const {
    return static_cast<double>(d[1] > half[1]) - static_cast<double>(d[1] < -half[1]);
  }

  /// The separation x_j' - x_i of the nearest image j' of the partner, from d = x_j - x_i.
  /// Positions lie within half a skin of the box, so one box length at most is taken off each
  /// component (a whole number of them along x under Lees-Edwards).
  GRAIN_INLINE V nearest(V d) const {
    if (sheared()) [[unlikely]]
      return nearest_sheared(d);
    return minimum_image(d, wrap_length, wrap_inverse);
  }
  /// d - n l, n_k the whole number nearest to d_k u_k (l = wrap_length, u = wrap_inverse: the
  /// nearest image without Lees-Edwards; n_k = 0 along the other axes). The rounding adds and
  /// takes off 1.5 2^52 (exact to the nearest whole number below 2^51 in magnitude): no branch
  /// and no conversion, so that the loops over list entries stay short.
  GRAIN_INLINE static V minimum_image(const V& d, const V& l, const V& u) {
    V n;
#if defined(__FAST_MATH__) // the sum below may be folded away: round as the library does
    for (int k = 0; k < D; ++k)
      n[k] = std::nearbyint(d[k] * u[k]);
#else
    constexpr double shift = 0x1.8p52;
    for (int k = 0; k < D; ++k)
      n[k] = (d[k] * u[k] + shift) - shift;
#endif
    return d - n.cwiseProduct(l);
  }
  /// Makes axis d periodic over [lo, lo + length).
  void set_axis(int d, double low, double len) {
    axis[d] = true;
    lo[d] = low;
    length[d] = len;
    half[d] = 0.5 * len;
    wrap_length[d] = len;
    wrap_inverse[d] = 1.0 / len;
    on = true;
  }
  /// As nearest, and the velocity of the image j' relative to j along x (Lees-Edwards).
  GRAIN_INLINE V nearest(V d, double& image_vx) const {
    image_vx = sheared() ? -images_y(d) * image_speed() : 0.0;
    return nearest(d);
  }
  /// The separation of the nearest image from x_i to x_j (x_j - x_i without periodic axes).
  GRAIN_INLINE V separation(const V& xi, const V& xj) const {
    V d = xj - xi;
    return on ? nearest(d) : d;
  }

  /// Wraps position x (and velocity v) into the box along the periodic axes, counting the
  /// boxes crossed in `image`. Under Lees-Edwards, `shear_shift` [m] collects what the offset's
  /// reduction modulo L_x took off: the unwrapped x is then x + image_x L_x + image_y slide
  /// + shear_shift (the box of image_y has slid image_y slide). Returns false, changing
  /// nothing, for a position more than 1e9 boxes away (its image count would overflow).
  bool wrap(V& x, V& v, std::array<std::int32_t, D>& image, double& shear_shift) const {
    for (int k = 0; k < D; ++k)
      if (axis[k] && !(std::abs((x[k] - lo[k]) / length[k]) < 1e9)) return false;
    // the boxes to take off along axis k: none for a coordinate within rounding below lo, whose
    // wrapped value would round to hi (it stays where it is: the grid takes it as in the box)
    auto boxes = [&](int k) {
      const double c = std::floor((x[k] - lo[k]) / length[k]);
      return c != 0.0 && x[k] - c * length[k] >= hi(k) ? c + 1.0 : c;
    };
    if (sheared()) {
      const double c = boxes(1);
      if (c != 0.0) {
        x[1] -= c * length[1];
        x[0] -= c * offset;
        v[0] -= c * image_speed();
        image[1] += static_cast<std::int32_t>(c);
        shear_shift += c * (offset - slide);
      }
    }
    for (int k = 0; k < D; ++k) {
      if (!axis[k] || (k == 1 && sheared())) continue;
      const double c = boxes(k);
      if (c == 0.0) continue;
      x[k] -= c * length[k];
      image[k] += static_cast<std::int32_t>(c);
    }
    return true;
  }

private:
  V nearest_sheared(V d) const {
    const double cy = images_y(d);
    d[1] -= cy * length[1];
    d[0] -= cy * offset;
    d[0] -= length[0] * std::floor(d[0] / length[0] + 0.5);
    for (int k = 2; k < D; ++k)
      if (axis[k])
        d[k] -= length[k] *
                (static_cast<double>(d[k] > half[k]) - static_cast<double>(d[k] < -half[k]));
    return d;
  }
};

} // namespace grain
