#pragma once
// Relative comparison for tests: a == approx(x).epsilon(e) holds when a == x or
// |a - x| < e (s + max(|a|, |x|)), with the scale s = 0 unless set by .scale(s). Unlike
// doctest::Approx (whose scale is 1, which makes epsilon an absolute bound for quantities much
// smaller than one: 1e-5 m compared with epsilon 1e-3 would pass anything within 1e-3 m), the
// bound is relative. A comparison with exactly zero needs a scale or an absolute bound.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace grain::test {

class Approx {
public:
  explicit Approx(double x) : value_(x) {}
  Approx epsilon(double e) const {
    Approx a = *this;
    a.epsilon_ = e;
    return a;
  }
  Approx scale(double s) const {
    Approx a = *this;
    a.scale_ = s;
    return a;
  }
  double value() const { return value_; }
  double eps() const { return epsilon_; }

  friend bool operator==(double a, const Approx& x) {
    return a == x.value_ || std::abs(a - x.value_) <
                                x.epsilon_ * (x.scale_ + std::max(std::abs(a), std::abs(x.value_)));
  }
  friend bool operator==(const Approx& x, double a) { return a == x; }
  friend bool operator!=(double a, const Approx& x) { return !(a == x); }
  friend bool operator!=(const Approx& x, double a) { return !(a == x); }

private:
  double value_;
  double epsilon_ = std::numeric_limits<float>::epsilon() * 100; // as doctest::Approx
  double scale_ = 0.0;
};

inline Approx approx(double x) { return Approx(x); }

} // namespace grain::test

namespace doctest {
template <>
struct StringMaker<grain::test::Approx> {
  static String convert(const grain::test::Approx& a) {
    std::ostringstream o;
    o.precision(17);
    o << "Approx( " << a.value() << " , rel " << a.eps() << " )";
    return String(o.str().c_str());
  }
};
} // namespace doctest
