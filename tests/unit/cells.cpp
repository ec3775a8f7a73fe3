// Cell-size methods without qhull (grain/thermal/cells.hpp): the porosity relation, disk and ball
// overlaps with polygons and polyhedra, 2D global and local porosity, radii from porosities.
#include "../lattices.hpp"
#include <doctest/doctest.h>
#include <grain/thermal/cells.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

using namespace grain;
using namespace grain::cells;

using grain::test::pairs_within;
using grain::test::square_lattice;

namespace {

constexpr double pi = std::numbers::pi;

/// n rows of n disks, hexagonal (triangular) lattice of spacing s.
std::vector<Vec2> hexagonal_lattice(int n, double s) {
  std::vector<Vec2> x;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
      x.emplace_back((i + 0.5 * (j % 2)) * s, j * s * std::sqrt(3.0) / 2);
  return x;
}

/// The unit cube [0,1]^3 as 12 triangles, counter-clockwise seen from outside.
const std::vector<Vec3> cube_vertices = [] {
  std::vector<Vec3> v;
  for (int k = 0; k < 8; ++k)
    v.emplace_back(k & 1, (k >> 1) & 1, (k >> 2) & 1);
  return v;
}();
const std::vector<TriangleIndices> cube_triangles{{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6},
                                                  {0, 1, 4}, {1, 5, 4}, {2, 6, 3}, {3, 6, 7},
                                                  {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};

/// Area of the disk (c, R) inside the unit square by the midpoint rule over x (reference).
double disk_in_unit_square_numeric(const Vec2& c, double R, int steps) {
  const double x0 = std::max(0.0, c.x() - R), x1 = std::min(1.0, c.x() + R);
  const double dx = (x1 - x0) / steps;
  double a = 0.0;
  for (int k = 0; k < steps; ++k) {
    const double x = x0 + (k + 0.5) * dx;
    const double h = std::sqrt(std::max(R * R - (x - c.x()) * (x - c.x()), 0.0));
    a += std::max(0.0, std::min(1.0, c.y() + h) - std::max(0.0, c.y() - h)) * dx;
  }
  return a;
}

} // namespace

TEST_CASE("cells: porosity relation r = 0.56 R (1 - phi)^(-1/3)") {
  CHECK(cell_radius_from_porosity(1.0, 0.4) == doctest::Approx(0.6640).epsilon(1e-4));
  CHECK(cell_radius_from_porosity(2e-3, 0.4) == doctest::Approx(0.56 * 2e-3 / std::cbrt(0.6)));
  CHECK(cell_radius_from_porosity(1e-3, 0.0) == doctest::Approx(0.56e-3));
  CHECK(std::isinf(cell_radius_from_porosity(1e-3, 1.0)));
  CHECK_THROWS_AS(cell_radius_from_porosity(1e-3, -0.1), InputError);
  CHECK_THROWS_AS(cell_radius_from_porosity(1e-3, 1.5), InputError);
  CHECK_THROWS_AS(cell_radius_from_porosity(-1.0, 0.4), InputError);
}

TEST_CASE("cells: convex hull of 2D points, counter-clockwise, without edge points") {
  const std::vector<Vec2> p{{0, 0}, {2, 0}, {1, 0}, {2, 2}, {1, 1}, {0, 2}, {0, 1}, {2, 2}};
  const auto h = convex_hull(p);
  REQUIRE(h.size() == 4);
  CHECK(h == std::vector<std::uint32_t>{0, 1, 3, 5});
  std::vector<Vec2> poly;
  for (auto k : h)
    poly.push_back(p[k]);
  CHECK(polygon_area(poly) == doctest::Approx(4.0));
  std::reverse(poly.begin(), poly.end());
  CHECK(polygon_area(poly) == doctest::Approx(-4.0));
  CHECK(convex_hull(std::vector<Vec2>{{0, 0}, {1, 1}, {2, 2}}).size() == 2); // collinear
  CHECK(convex_hull(std::vector<Vec2>{{1, 1}, {1, 1}}).size() == 1);
  CHECK(convex_hull(std::vector<Vec2>{}).empty());
}

TEST_CASE("cells: disk inside a polygon, exact") {
  const std::vector<Vec2> sq{{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  const double R = 0.3, disk = pi * R * R;
  CHECK(disk_polygon_overlap(Vec2(0.5, 0.5), R, sq) == doctest::Approx(disk).epsilon(1e-14));
  CHECK(disk_polygon_overlap(Vec2(0.5, 0.0), R, sq) == doctest::Approx(disk / 2).epsilon(1e-14));
  CHECK(disk_polygon_overlap(Vec2(0.0, 0.0), R, sq) == doctest::Approx(disk / 4).epsilon(1e-14));
  CHECK(disk_polygon_overlap(Vec2(2.0, 0.5), R, sq) == doctest::Approx(0.0));
  // circular segment cut off by one edge, centre at depth h
  const double h = 0.1;
  const double segment = R * R * std::acos(h / R) - h * std::sqrt(R * R - h * h);
  CHECK(disk_polygon_overlap(Vec2(0.5, h), R, sq) ==
        doctest::Approx(disk - segment).epsilon(1e-13));
  // either orientation
  const std::vector<Vec2> cw(sq.rbegin(), sq.rend());
  CHECK(disk_polygon_overlap(Vec2(0.5, h), R, cw) ==
        doctest::Approx(disk - segment).epsilon(1e-13));
  // a disk cut by two edges and larger than the square, against the midpoint rule (error < 1e-6)
  for (const auto& [c, r] : {std::pair{Vec2(0.1, 0.95), 0.5}, std::pair{Vec2(0.3, 0.6), 2.0},
                             std::pair{Vec2(-0.2, 0.4), 0.45}}) {
    CAPTURE(r);
    CHECK(disk_polygon_overlap(c, r, sq) ==
          doctest::Approx(disk_in_unit_square_numeric(c, r, 200000)).epsilon(1e-6));
  }
}

TEST_CASE("cells: ball inside a triangulated polyhedron, exact") {
  const auto& v = cube_vertices;
  const auto& t = cube_triangles;
  CHECK(polyhedron_volume(v, t) == doctest::Approx(1.0).epsilon(1e-15));
  const double R = 0.3, ball = 4.0 / 3.0 * pi * R * R * R;
  CHECK(ball_polyhedron_overlap(Vec3(0.5, 0.5, 0.5), R, v, t) ==
        doctest::Approx(ball).epsilon(1e-13));
  CHECK(ball_polyhedron_overlap(Vec3(0.5, 0.5, 0), R, v, t) ==
        doctest::Approx(ball / 2).epsilon(1e-13));
  CHECK(ball_polyhedron_overlap(Vec3(0.5, 0, 0), R, v, t) ==
        doctest::Approx(ball / 4).epsilon(1e-13));
  CHECK(ball_polyhedron_overlap(Vec3(0, 0, 0), R, v, t) ==
        doctest::Approx(ball / 8).epsilon(1e-13));
  CHECK(ball_polyhedron_overlap(Vec3(0.5, 0.5, 0.5), 5.0, v, t) ==
        doctest::Approx(1.0).epsilon(1e-13));
  CHECK(ball_polyhedron_overlap(Vec3(3, 0.5, 0.5), 0.5, v, t) == doctest::Approx(0.0).scale(1.0));
  // spherical cap: inside at depth h, and a cap poking in from outside
  const double h = 0.1, d = R - h;
  const double cap = pi * d * d * (3 * R - d) / 3;
  CHECK(ball_polyhedron_overlap(Vec3(0.5, 0.5, h), R, v, t) ==
        doctest::Approx(ball - cap).epsilon(1e-13));
  const double cap_out = pi * (R - 0.2) * (R - 0.2) * (3 * R - (R - 0.2)) / 3;
  CHECK(ball_polyhedron_overlap(Vec3(1.2, 0.5, 0.5), R, v, t) ==
        doctest::Approx(cap_out).epsilon(1e-12));
  // reversed orientation gives the same
  std::vector<TriangleIndices> rev;
  for (auto tr : t)
    rev.push_back({tr[0], tr[2], tr[1]});
  CHECK(ball_polyhedron_overlap(Vec3(0.5, 0.5, h), R, v, rev) ==
        doctest::Approx(ball - cap).epsilon(1e-13));
  // a ball cut by three faces, against slices: int of (disk of the section inside the square) dz
  const Vec3 c(0.1, 0.85, 0.95);
  const double r = 0.4;
  const int steps = 4000;
  const double z0 = std::max(0.0, c.z() - r), z1 = std::min(1.0, c.z() + r);
  double ref = 0.0;
  for (int k = 0; k < steps; ++k) { // midpoint rule over z
    const double z = z0 + (z1 - z0) * (k + 0.5) / steps;
    const double rs = std::sqrt(std::max(r * r - (z - c.z()) * (z - c.z()), 0.0));
    const std::vector<Vec2> sq{{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    ref += disk_polygon_overlap(Vec2(c.x(), c.y()), rs, sq) * (z1 - z0) / steps;
  }
  CHECK(ball_polyhedron_overlap(c, r, v, t) == doctest::Approx(ref).epsilon(1e-6));
}

TEST_CASE("cells: global porosity of square lattices of touching disks is 1 - pi/4") {
  // The hull of an n x n block holds exactly (n-1)^2 cells and (n-1)^2 disks (whole inside,
  // halves on edges, quarters at corners): no boundary effect, for any n.
  const double s = 2e-3;
  for (int n : {2, 3, 10, 40}) {
    const auto x = square_lattice(n, s);
    const std::vector<double> R(x.size(), s / 2);
    CAPTURE(n);
    CHECK(global_porosity(x, R) == doctest::Approx(1 - pi / 4).epsilon(1e-12));
    const std::vector<double> Rs(x.size(), 0.3 * s);
    CHECK(global_porosity(x, Rs) == doctest::Approx(1 - pi * 0.09).epsilon(1e-12));
  }
  CHECK(global_porosity(std::vector<Vec2>{{0, 0}, {1, 0}}, std::vector<double>{0.5, 0.5}) == 1.0);
  CHECK(global_porosity(std::vector<Vec2>{{0, 0}, {1, 0}, {2, 0}}, std::vector<double>(3, 0.5)) ==
        1.0);
}

TEST_CASE("cells: global porosity of hexagonal blocks is 1 - pi/(2 sqrt 3)") {
  // The zig-zag sides of an n-row block add isosceles triangles of the same area and solid as
  // the lattice triangles: again exact for any n.
  const double s = 1e-3;
  for (int n : {3, 4, 10, 31}) {
    const auto x = hexagonal_lattice(n, s);
    const std::vector<double> R(x.size(), s / 2);
    CAPTURE(n);
    CHECK(global_porosity(x, R) == doctest::Approx(1 - pi / (2 * std::sqrt(3.0))).epsilon(1e-12));
  }
}

TEST_CASE("cells: global porosity of round lattice patches tends to the lattice value") {
  // Disks of a lattice within a circle of radius rho: the hull edges of the round patch cut
  // disks near them, which adds void along the boundary, O(s/rho) = O(N^(-1/2)); measured
  // 0.05 s/rho (square) and 0.1 s/rho (hexagonal) for rho = 10...80 s. Tolerance 0.15 s/rho.
  const double s = 1e-3;
  for (bool hex : {false, true}) {
    const double phi_inf = hex ? 1 - pi / (2 * std::sqrt(3.0)) : 1 - pi / 4;
    for (double rho : {10.0, 20.0, 40.0}) {
      std::vector<Vec2> x;
      const int m = static_cast<int>(rho) + 2;
      for (int j = -2 * m; j <= 2 * m; ++j)
        for (int i = -2 * m; i <= 2 * m; ++i) {
          const Vec2 p = hex ? Vec2(i + 0.5 * (j & 1), j * std::sqrt(3.0) / 2) : Vec2(i, j);
          if (p.norm() <= rho) x.push_back(s * p);
        }
      const std::vector<double> R(x.size(), s / 2);
      const double phi = global_porosity(x, R);
      CAPTURE(hex);
      CAPTURE(rho);
      CHECK(phi >= phi_inf - 1e-12);
      CHECK(phi - phi_inf < 0.15 / rho);
    }
  }
}

TEST_CASE("cells: local porosity of interior particles of lattices") {
  const double s = 1.5e-3, R = s / 2;
  SUBCASE("square lattice") {
    const auto x = square_lattice(7, s);
    const std::vector<double> r(x.size(), R);
    const std::size_t mid = 3 * 7 + 3;
    // 4 neighbours: hull is a diamond of area 2 s^2
    const auto nl4 = pairs_within<2>(x, 1.2 * s);
    CHECK(local_porosity(x, r, nl4)[mid] == doctest::Approx(1 - pi / 4).epsilon(1e-12));
    CHECK(local_porosity(x, r, nl4, LocalRule::interior_angle)[mid] ==
          doctest::Approx(1 - 3 * pi / 16).epsilon(1e-12));
    // 8 neighbours: hull is a square of area 4 s^2
    const auto nl8 = pairs_within<2>(x, 1.5 * s);
    CHECK(local_porosity(x, r, nl8)[mid] == doctest::Approx(1 - pi / 4).epsilon(1e-12));
    CHECK(local_porosity(x, r, nl8, LocalRule::interior_angle)[mid] ==
          doctest::Approx(1 - 7 * pi / 32).epsilon(1e-12));
    // a corner particle with 2 neighbours: a right triangle, every centre a hull vertex
    CHECK(local_porosity(x, r, nl4)[0] == doctest::Approx(1 - pi / 4).epsilon(1e-12));
    CHECK(local_porosity(x, r, nl4, LocalRule::interior_angle)[0] ==
          doctest::Approx(1 - pi / 4).epsilon(1e-12));
  }
  SUBCASE("hexagonal lattice") {
    const auto x = hexagonal_lattice(7, s);
    const std::vector<double> r(x.size(), R);
    const auto nl = pairs_within<2>(x, 1.2 * s);
    const std::size_t mid = 3 * 7 + 3;
    CHECK(local_porosity(x, r, nl)[mid] ==
          doctest::Approx(1 - pi / (2 * std::sqrt(3.0))).epsilon(1e-12));
    CHECK(local_porosity(x, r, nl, LocalRule::interior_angle)[mid] ==
          doctest::Approx(1 - 5 * pi / (12 * std::sqrt(3.0))).epsilon(1e-12));
  }
  SUBCASE("degenerate neighbourhoods give 1") {
    const std::vector<Vec2> x{{0, 0}, {1e-3, 0}, {2e-3, 0}, {5e-3, 5e-3}};
    const std::vector<double> r(x.size(), 0.5e-3);
    const auto nl = pairs_within<2>(x, 2.5e-3);
    const auto phi = local_porosity(x, r, nl);
    CHECK(phi[0] == 1.0); // collinear
    CHECK(phi[3] == 1.0); // alone
  }
}

TEST_CASE("cells: 2D porosities do not depend on the order of the particles") {
  std::mt19937 gen(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Vec2> x;
  std::vector<double> r;
  while (x.size() < 300) { // non-overlapping disks by rejection
    const Vec2 p(u(gen) * 0.05, u(gen) * 0.05);
    const double rp = 0.6e-3 + 0.6e-3 * u(gen);
    bool ok = true;
    for (std::size_t k = 0; k < x.size() && ok; ++k)
      ok = (x[k] - p).norm() > r[k] + rp;
    if (ok) {
      x.push_back(p);
      r.push_back(rp);
    }
  }
  std::vector<std::size_t> perm(x.size());
  for (std::size_t k = 0; k < perm.size(); ++k)
    perm[k] = k;
  std::shuffle(perm.begin(), perm.end(), gen);
  std::vector<Vec2> xp;
  std::vector<double> rp;
  for (auto k : perm) {
    xp.push_back(x[k]);
    rp.push_back(r[k]);
  }
  CHECK(global_porosity(xp, rp) == doctest::Approx(global_porosity(x, r)).epsilon(1e-12));
  const auto phi = local_porosity(x, r, pairs_within<2>(x, 4e-3));
  const auto phip = local_porosity(xp, rp, pairs_within<2>(xp, 4e-3));
  for (std::size_t k = 0; k < perm.size(); ++k) {
    CHECK(phip[k] == doctest::Approx(phi[perm[k]]).epsilon(1e-12));
    CHECK(phi[k] >= 0.0);
    CHECK(phi[k] <= 1.0);
  }
}

TEST_CASE("cells: radii from porosities") {
  // pairs (0,1), (0,2), (1,2); walls: particle 0 -> wall 0, particle 2 -> wall 1
  NeighborList nl;
  nl.offsets = {0, 2, 3, 3};
  nl.partners = {1, 2, 2};
  nl.wall_offsets = {0, 1, 1, 2};
  nl.walls = {0, 1};
  const std::vector<double> R{1e-3, 2e-3, 3e-3};
  const std::vector<double> phi{0.3, 0.5, 1.0};
  const auto local = porosity_radii(R, phi, nl);
  REQUIRE(local.pair.size() == 3);
  REQUIRE(local.wall.size() == 2);
  CHECK(local.pair[0] == doctest::Approx(0.56 * 1.5e-3 / std::cbrt(1 - 0.4)));
  CHECK(local.pair[1] == doctest::Approx(0.56 * 2e-3 / std::cbrt(1 - 0.65)));
  CHECK(local.pair[2] == doctest::Approx(0.56 * 2.5e-3 / std::cbrt(1 - 0.75)));
  CHECK(local.wall[0] == doctest::Approx(0.56 * 1e-3 / std::cbrt(0.7)));
  CHECK(std::isinf(local.wall[1])); // phi = 1: no solid around, no indirect conduction
  const auto global = porosity_radii(R, 0.4, nl);
  CHECK(global.pair[2] == doctest::Approx(0.6640 * 2.5e-3).epsilon(1e-4));
  CHECK(global.wall[0] == doctest::Approx(0.6640 * 1e-3).epsilon(1e-4));
  CHECK_THROWS_AS(porosity_radii(R, std::vector<double>{0.3}, nl), InputError);
}

TEST_CASE("cells: bad input is rejected") {
  const std::vector<Vec2> x{{0, 0}, {1, 0}, {0, 1}};
  CHECK_THROWS_AS(global_porosity(x, std::vector<double>{1.0}), InputError);
  CHECK_THROWS_AS(global_porosity(x, std::vector<double>{1.0, -1.0, 1.0}), InputError);
  NeighborList nl;
  nl.clear(2);
  nl.offsets = {0, 0, 0};
  CHECK_THROWS_AS(local_porosity(x, std::vector<double>(3, 0.1), nl), InputError);
}
