#pragma once
/// \file quadrature.hpp
/// Globally adaptive Gauss-Kronrod (7-15) quadrature of a smooth function of one variable, for
/// the models that have no closed form (e.g. the indirect conduction models).
///
///   I = int_a^b f(x) dx
///
/// Each subinterval is integrated with the 15-point Kronrod rule; the difference to the embedded
/// 7-point Gauss rule, |K15 - G7|, is its error estimate (pessimistic for smooth f: the Kronrod
/// value is usually far more accurate). The subinterval with the largest estimate is bisected
/// until the summed estimate E satisfies
///
///   E <= max(abs_tol, rel_tol |I|)
///
/// or a guard stops the refinement: a subinterval is not bisected below `max_depth` levels (nor
/// once its midpoint cannot be represented), and at most `max_intervals` subintervals are kept.
/// The result then holds the best value found and `converged = false`.
///
/// Break points (`integrate_split`): an integrand with a kink or a change of formula at known
/// interior points is integrated piecewise, each piece starting as its own subinterval, so that no
/// Kronrod rule straddles the kink. Break points outside (a, b) are ignored; their order does
/// not matter.
///
/// The rule is exact for polynomials of degree <= 22 (Kronrod) and 13 (Gauss) on each
/// subinterval. Nodes and weights: Piessens et al., QUADPACK (Springer, 1983), routine QK15.
/// No dynamic allocation (the subintervals live in a fixed array on the stack).

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <initializer_list>
#include <limits>

namespace grain::detail {

/// Tolerances and guards of `integrate`.
struct QuadratureOptions {
  double abs_tol = 1e-10;  ///< absolute tolerance (units of the integral); >= 0
  double rel_tol = 1e-6;   ///< relative tolerance; >= 0 (abs_tol or rel_tol must be > 0)
  int max_depth = 40;      ///< bisection levels below each piece of [a, b]
  int max_intervals = 200; ///< subintervals kept at most (capped at `kMaxIntervals`)
};

/// Result of `integrate`.
struct QuadratureResult {
  double value = 0.0;    ///< estimate of the integral
  double error = 0.0;    ///< summed |K15 - G7| over the final subintervals
  int evaluations = 0;   ///< calls of the integrand
  bool converged = true; ///< false if a guard stopped the refinement (or f was not finite)
};

namespace quadrature_impl {

inline constexpr int kMaxIntervals = 256;

// Kronrod abscissae on [-1, 1] (x[1], x[3], x[5], x[7] are the 7-point Gauss nodes).
inline constexpr std::array<double, 8> xgk = {
    0.991455371120812639206854697526329, 0.949107912342758524526189684047851,
    0.864864423359769072789712788640926, 0.741531185599394439863864773280788,
    0.586087235467691130294144845693013, 0.405845151377397166906606412076961,
    0.207784955007898467600689403773245, 0.000000000000000000000000000000000};
// Kronrod weights.
inline constexpr std::array<double, 8> wgk = {
    0.022935322010529224963732008058970, 0.063092092629978553290700663189204,
    0.104790010322250183839876322541518, 0.140653259715525918745189590510238,
    0.169004726639267902826583426598550, 0.190350578064785409913256402421014,
    0.204432940075298892414161999234649, 0.209482141084727828012999174891714};
// Gauss weights of the nodes x[1], x[3], x[5], x[7].
inline constexpr std::array<double, 4> wg = {
    0.129484966168869693270611432679082, 0.279705391489276667901467771423780,
    0.381830050505118944950369775488975, 0.417959183673469387755102040816327};

struct Piece {
  double a, b, value, error;
  int depth;
};

/// K15 and |K15 - G7| of f on [a, b].
template <class F>
Piece kronrod15(F& f, double a, double b, int depth) {
  const double c = 0.5 * (a + b), h = 0.5 * (b - a);
  const double fc = f(c);
  double k = wgk[7] * fc, g = wg[3] * fc;
  for (int i = 0; i < 7; ++i) {
    const double dx = h * xgk[i];
    const double s = f(c - dx) + f(c + dx);
    k += wgk[i] * s;
    if (i % 2 == 1) g += wg[i / 2] * s;
  }
  return {a, b, k * h, std::abs((k - g) * h), depth};
}

} // namespace quadrature_impl

/// Integral of f over [a, b] (b < a gives minus the integral over [b, a]), split first at the
/// `n_breaks` points `breaks` that lie strictly inside. See the file comment.
template <class F>
QuadratureResult integrate_split(F&& f, double a, double b, const double* breaks,
                                 std::size_t n_breaks, const QuadratureOptions& opt = {}) {
  using namespace quadrature_impl;
  QuadratureResult r;
  if (a == b) return r;
  if (b < a) {
    r = integrate_split(f, b, a, breaks, n_breaks, opt);
    r.value = -r.value;
    return r;
  }
  const int cap = std::clamp(opt.max_intervals, 1, kMaxIntervals);
  std::array<Piece, kMaxIntervals> pieces;
  int n = 0;

  // initial pieces: [a, b] cut at the sorted interior break points
  std::array<double, kMaxIntervals + 1> cuts;
  int m = 0;
  cuts[m++] = a;
  for (std::size_t i = 0; i < n_breaks && m < cap; ++i)
    if (breaks[i] > a && breaks[i] < b) cuts[m++] = breaks[i];
  std::sort(cuts.begin() + 1, cuts.begin() + m);
  m = static_cast<int>(std::unique(cuts.begin(), cuts.begin() + m) - cuts.begin());
  cuts[m++] = b;
  for (int i = 0; i + 1 < m; ++i) {
    pieces[n++] = kronrod15(f, cuts[i], cuts[i + 1], 0);
    r.evaluations += 15;
  }

  for (;;) {
    double value = 0.0, error = 0.0;
    for (int i = 0; i < n; ++i) {
      value += pieces[i].value;
      error += pieces[i].error;
    }
    r.value = value;
    r.error = error;
    if (!std::isfinite(value) || !std::isfinite(error)) {
      r.converged = false;
      return r;
    }
    if (error <= std::max(opt.abs_tol, opt.rel_tol * std::abs(value))) {
      r.converged = true;
      return r;
    }
    // bisect the splittable piece with the largest error estimate
    int worst = -1;
    for (int i = 0; i < n; ++i) {
      const Piece& p = pieces[i];
      const double mid = 0.5 * (p.a + p.b);
      if (p.depth >= opt.max_depth || !(mid > p.a && mid < p.b) || p.error == 0.0) continue;
      if (worst < 0 || p.error > pieces[worst].error) worst = i;
    }
    if (worst < 0 || n >= cap) {
      r.converged = false;
      return r;
    }
    const Piece p = pieces[worst];
    const double mid = 0.5 * (p.a + p.b);
    pieces[worst] = kronrod15(f, p.a, mid, p.depth + 1);
    pieces[n++] = kronrod15(f, mid, p.b, p.depth + 1);
    r.evaluations += 30;
  }
}

/// Integral of f over [a, b] split at the interior points of the list `breaks`.
template <class F>
QuadratureResult integrate_split(F&& f, double a, double b, std::initializer_list<double> breaks,
                                 const QuadratureOptions& opt = {}) {
  return integrate_split(f, a, b, breaks.begin(), breaks.size(), opt);
}

/// Integral of f over [a, b].
template <class F>
QuadratureResult integrate(F&& f, double a, double b, const QuadratureOptions& opt = {}) {
  return integrate_split(f, a, b, nullptr, 0, opt);
}

} // namespace grain::detail
