// Wall proximity, contact geometry and wall motion.
#include "../approx.hpp"
#include "../errors.hpp"
#include <cmath>
#include <doctest/doctest.h>
#include <grain/grain.hpp>
#include <numbers>

using namespace grain;

namespace {
template <int D, class G>
Wall<D> make(const G& g, WallOptions<D> o = {}) {
  Wall<D> w;
  w.geometry = g;
  w.options = o;
  w.pivot = o.has_pivot ? o.pivot : Wall<D>::default_pivot(w.geometry);
  w.take_snapshot();
  return w;
}
} // namespace

TEST_CASE("segment: interior and end points") {
  auto w = make<2>(walls::Segment{Vec2(0, 0), Vec2(2, 0)});
  auto p = w.proximity(Vec2(1.0, 0.3));
  CHECK(p.distance == grain::test::approx(0.3));
  CHECK(p.normal.isApprox(Vec2(0, -1)));
  CHECK(std::isinf(p.curvature_radius));
  p = w.proximity(Vec2(1.0, -0.2)); // other side
  CHECK(p.distance == grain::test::approx(0.2));
  CHECK(p.normal.isApprox(Vec2(0, 1)));
  p = w.proximity(Vec2(2.3, 0.4)); // beyond the end: radial normal
  CHECK(p.distance == grain::test::approx(0.5));
  CHECK(p.normal.isApprox(Vec2(-0.6, -0.8)));
}

TEST_CASE("circle: inside (concave) and outside (convex)") {
  auto w = make<2>(walls::Circle{Vec2(1, 1), 2.0});
  auto p = w.proximity(Vec2(1.5, 1.0));
  CHECK(p.distance == grain::test::approx(1.5));
  CHECK(p.normal.isApprox(Vec2(1, 0)));
  CHECK(p.curvature_radius == grain::test::approx(-2.0));
  p = w.proximity(Vec2(1.0, 4.0));
  CHECK(p.distance == grain::test::approx(1.0));
  CHECK(p.normal.isApprox(Vec2(0, -1)));
  CHECK(p.curvature_radius == grain::test::approx(2.0));

  // effective radius: R Rw/(Rw - R) inside, R Rw/(Rw + R) outside
  ContactGeometry<2> g;
  const double r = 0.1;
  Vec2 x(1.0 + 1.95, 1.0);
  wall_geometry<2>(g, w, w.proximity(x), x, r, 1.0, Vec2::Zero(), 0.0);
  CHECK(g.overlap == grain::test::approx(0.05));
  CHECK(g.r_eff == grain::test::approx(r * 2.0 / (2.0 - r)));
  x = Vec2(1.0 + 2.05, 1.0);
  wall_geometry<2>(g, w, w.proximity(x), x, r, 1.0, Vec2::Zero(), 0.0);
  CHECK(g.overlap == grain::test::approx(0.05));
  CHECK(g.r_eff == grain::test::approx(r * 2.0 / (2.0 + r)));
  // lens radius of circles r and Rw at centre distance Rw + r - overlap
  const double d = 2.05, x0 = (r * r - 4.0 + d * d) / (2 * d);
  CHECK(lens_contact_radius(g) == grain::test::approx(std::sqrt(r * r - x0 * x0)));
}

TEST_CASE("plane and triangle") {
  auto pl = make<3>(walls::Plane{Vec3(0, 0, 1), Vec3(0, 0, 1)});
  auto p = pl.proximity(Vec3(5, -3, 1.25));
  CHECK(p.distance == grain::test::approx(0.25));
  CHECK(p.normal.isApprox(Vec3(0, 0, -1)));

  auto tr = make<3>(walls::Triangle{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)});
  p = tr.proximity(Vec3(0.2, 0.2, 0.5)); // face
  CHECK(p.distance == grain::test::approx(0.5));
  CHECK(p.normal.isApprox(Vec3(0, 0, -1)));
  p = tr.proximity(Vec3(0.5, -0.3, -0.4)); // edge ab, below
  CHECK(p.distance == grain::test::approx(0.5));
  CHECK(p.normal.isApprox(Vec3(0, 0.6, 0.8)));
  p = tr.proximity(Vec3(-0.3, -0.4, 0)); // corner a
  CHECK(p.distance == grain::test::approx(0.5));
  p = tr.proximity(Vec3(0.8, 0.8, 0)); // hypotenuse
  CHECK(p.distance == grain::test::approx(0.6 / std::sqrt(2.0)));
}

TEST_CASE("pair geometry: overlap, arms and relative velocity with rotation") {
  ContactGeometry<3> g;
  const Vec3 xi(0, 0, 0), xj(0.19, 0, 0);
  const Vec3 n(1, 0, 0);
  pair_geometry<3>(g, xi, n, 0.19, 0.1, 0.1, 2.0, 2.0, Vec3(1, 0, 0), Vec3(-1, 0, 0),
                   Vec3(0, 0, 10), Vec3(0, 0, 0));
  CHECK(g.overlap == grain::test::approx(0.01));
  CHECK(g.point.isApprox(Vec3(0.095, 0, 0)));
  CHECK(g.normal_velocity == grain::test::approx(2.0));
  // w x arm = (0,0,10) x (0.095,0,0) = (0, 0.95, 0)
  CHECK(g.tangential_velocity.isApprox(Vec3(0, 0.95, 0)));
  CHECK(g.r_eff == grain::test::approx(0.05));
  CHECK(g.m_eff == grain::test::approx(1.0));
  CHECK(lens_contact_radius(g) == grain::test::approx(std::sqrt(0.01 - 0.095 * 0.095)));
}

TEST_CASE("wall motion: translation, rotation about the pivot, surface velocity") {
  auto w = make<2>(walls::Segment{Vec2(-1, 0), Vec2(1, 0)},
                   {.velocity = Vec2(0.5, 0), .omega = std::numbers::pi / 2});
  CHECK(w.velocity_at(Vec2(1, 0)).isApprox(Vec2(0.5, std::numbers::pi / 2)));
  w.move(1.0); // quarter turn about the midpoint, then shift by 0.5 in x
  const auto& s = std::get<walls::Segment>(w.geometry);
  CHECK((s.a - Vec2(0.5, -1)).norm() < 1e-12);
  CHECK((s.b - Vec2(0.5, 1)).norm() < 1e-12);
  CHECK(w.displacement_since_snapshot(10.0) == grain::test::approx(std::hypot(1.5, 1.0)));

  // a rotating circle keeps its geometry but drags particles with its surface speed
  auto drum = make<2>(walls::Circle{Vec2::Zero(), 1.0}, {.omega = 2.0});
  drum.move(0.3);
  CHECK(std::get<walls::Circle>(drum.geometry).center.norm() < 1e-15);
  CHECK(drum.velocity_at(Vec2(0, -1)).isApprox(Vec2(2.0, 0)));
  CHECK(drum.displacement_since_snapshot(10.0) < 1e-15);

  auto plane = make<3>(walls::Plane{Vec3::Zero(), Vec3::UnitZ()}, {.velocity = Vec3(0, 0, 0.1)});
  plane.move(2.0);
  CHECK(plane.proximity(Vec3(0, 0, 1)).distance == grain::test::approx(0.8));
}

TEST_CASE(
    "plane turning about a distant pivot: the displacement bound covers every point within reach") {
  // the plane's point sits 100 m from the pivot; the rotation moves it by -omega x 100 m along z
  // and the translation brings it back, so the point stays where it was while the plane tilts:
  // at 0.5 m above the pivot the distance changes by 100 m x 1e-4 rad = 0.01 m
  const double om = 1e-3;
  auto plane =
      make<3>(walls::Plane{Vec3(100, 0, 0), Vec3::UnitZ()}, {.velocity = Vec3(0, 0, 100 * om),
                                                             .omega = Vec3(0, om, 0),
                                                             .has_pivot = true,
                                                             .pivot = Vec3::Zero()});
  const double reach = 1.0;
  std::vector<Vec3> xs;
  for (int i = 0; i < 50; ++i) { // points within reach of the pivot, inside and on the sphere
    const double a = 0.7 * i, b = 1.3 * i;
    const double r = reach * (i % 5 + 1) / 5.0;
    xs.emplace_back(r * std::sin(a) * std::cos(b), r * std::sin(a) * std::sin(b), r * std::cos(a));
  }
  std::vector<double> d0;
  for (const auto& x : xs)
    d0.push_back(plane.proximity(x).distance);
  for (int k = 0; k < 10; ++k)
    plane.move(1e-2);
  CHECK((std::get<walls::Plane>(plane.geometry).point - Vec3(100, 0, 0)).norm() < 1e-6);
  const double bound = plane.displacement_since_snapshot(reach);
  double largest = 0.0;
  for (std::size_t i = 0; i < xs.size(); ++i)
    largest = std::max(largest, std::abs(plane.proximity(xs[i]).distance - d0[i]));
  CHECK(largest == grain::test::approx(0.01).epsilon(0.02)); // the tilt over 100 m dominates
  CHECK(bound >= largest);
  CHECK(bound < 1.05 * largest); // and the bound stays tight: 0.01 x (1 + reach / 100 m)
}

TEST_CASE("wall input: a non-finite pivot, a temperature below 0 K") {
  using grain::test::error_of;
  using grain::test::has;
  auto w = make<3>(walls::Plane{Vec3::Zero(), Vec3::UnitZ()},
                   {.name = "lid", .has_pivot = true, .pivot = Vec3(std::nan(""), 0, 0)});
  const auto e = error_of([&] { w.validate(); });
  CHECK(has(e, "Wall 'lid'"));
  CHECK(has(e, "pivot"));

  // a table with a value below 0 K is rejected before the run
  auto hot =
      make<2>(walls::Segment{Vec2(0, 0), Vec2(1, 0)},
              {.name = "heater", .temperature = TimeFunction::table({{0.0, 300.0}, {1.0, -50.0}})});
  const auto t = error_of([&] { hot.validate(); });
  CHECK(has(t, "Wall 'heater'"));
  CHECK(has(t, "-50"));
  CHECK(has(t, "[0, inf) K"));

  // a ramp that passes 0 K is accepted at t = 0 and stopped where it goes below
  auto ramp = make<2>(walls::Segment{Vec2(0, 0), Vec2(1, 0)},
                      {.name = "cooler", .temperature = TimeFunction::linear(300.0, -100.0)});
  CHECK(error_of([&] { ramp.validate(); }).empty());
  ramp.update_temperature(2.0);
  CHECK(ramp.temperature == grain::test::approx(100.0));
  const auto r = error_of([&] { ramp.update_temperature(4.0); });
  CHECK(has(r, "Wall 'cooler'"));
  CHECK(has(r, "t = 4"));
  CHECK(has(r, "-100"));
  CHECK(ramp.temperature == grain::test::approx(100.0)); // the last valid value is kept
}

TEST_CASE("a particle turning with a rotating wall has no relative rotation") {
  // a disk carried rigidly by a drum (same angular velocity, contact point moving with the
  // surface) has zero relative velocity and zero relative rotation at the contact
  auto drum = make<2>(walls::Circle{Vec2::Zero(), 1.0}, {.omega = 0.7});
  const double r = 0.1;
  const Vec2 x(0.0, -0.905);
  ContactGeometry<2> g;
  const Vec2 v = cross(0.7, x); // rigid rotation of the centre about the drum axis
  wall_geometry<2>(g, drum, drum.proximity(x), x, r, 1.0, v, 0.7);
  CHECK(g.omega_rel == grain::test::approx(0.0));
  CHECK(g.velocity.norm() < 1e-14);
}
