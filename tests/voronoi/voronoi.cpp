// Cell radii from Voronoi and power diagrams and 3D porosities (grain/thermal/voronoi.hpp, qhull):
// exact lattice values, boundaries, walls, order independence.
#include "../lattices.hpp"
#include <doctest/doctest.h>
#include <grain/thermal/voronoi.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <random>
#include <utility>
#include <vector>

using namespace grain;
using namespace grain::cells;

using grain::test::pairs_within;
using grain::test::square_lattice;

namespace {

constexpr double pi = std::numbers::pi;

/// Calls f(i, j, r) for every pair of the list.
template <class F>
void each_pair(const NeighborList& nl, const std::vector<double>& r, F&& f) {
  for (std::size_t i = 0; i + 1 < nl.offsets.size(); ++i)
    for (std::uint32_t k = nl.offsets[i]; k < nl.offsets[i + 1]; ++k)
      f(i, nl.partners[k], r[k]);
}

/// Adds one wall entry (wall 0) to every particle of a list without walls.
NeighborList with_wall_for_all(NeighborList nl) {
  const std::size_t n = nl.rows();
  nl.wall_offsets.assign(1, 0);
  nl.walls.clear();
  for (std::size_t i = 0; i < n; ++i) {
    nl.walls.push_back(0);
    nl.wall_offsets.push_back(static_cast<std::uint32_t>(nl.walls.size()));
  }
  return nl;
}

std::vector<Vec3> cubic_lattice(int n, double s) {
  std::vector<Vec3> x;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        x.emplace_back(i * s, j * s, k * s);
  return x;
}

/// Face-centred cubic block of m^3 cubic cells of side a, with the closing faces (all sites
/// with coordinates in [0, m a]).
std::vector<Vec3> fcc_block(int m, double a) {
  std::vector<Vec3> x;
  for (int k = 0; k <= 2 * m; ++k)
    for (int j = 0; j <= 2 * m; ++j)
      for (int i = 0; i <= 2 * m; ++i)
        if ((i + j + k) % 2 == 0) x.emplace_back(0.5 * a * i, 0.5 * a * j, 0.5 * a * k);
  return x;
}

/// True if x lies at least `d` inside the bounding box of `all`.
template <int D>
bool interior(const Vec<D>& x, const std::vector<Vec<D>>& all, double d) {
  Vec<D> lo = all[0], hi = all[0];
  for (const auto& p : all) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  return ((x - lo).array() >= d).all() && ((hi - x).array() >= d).all();
}

/// Non-overlapping random disks/balls in a cube of side L by rejection.
template <int D>
void random_packing(std::size_t n, double L, double rmin, double rmax, unsigned seed,
                    std::vector<Vec<D>>& x, std::vector<double>& r) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  x.clear();
  r.clear();
  while (x.size() < n) {
    Vec<D> p;
    for (int d = 0; d < D; ++d)
      p[d] = L * u(gen);
    const double rp = rmin + (rmax - rmin) * u(gen);
    bool ok = true;
    for (std::size_t k = 0; k < x.size() && ok; ++k)
      ok = (x[k] - p).norm() > r[k] + rp;
    if (ok) {
      x.push_back(p);
      r.push_back(rp);
    }
  }
}

} // namespace

TEST_CASE("voronoi: square lattice, r = s/2 for the 4 nearest neighbours and 0 for diagonals") {
  const double s = 2e-3;
  const int n = 8;
  const auto x = square_lattice(n, s);
  const auto nl = pairs_within<2>(x, 1.5 * s);
  SUBCASE("touching disks: every nearest pair, boundary ones too, has r = s/2") {
    const std::vector<double> R(x.size(), s / 2);
    const auto r = voronoi_radii(x, R, nl);
    int near = 0, diagonal = 0;
    each_pair(nl, r.pair, [&](std::size_t i, std::size_t j, double rij) {
      if ((x[i] - x[j]).norm() < 1.1 * s) {
        CHECK(rij == doctest::Approx(s / 2).epsilon(1e-9));
        ++near;
      } else {
        CHECK(rij == 0.0);
        ++diagonal;
      }
    });
    CHECK(near == 2 * n * (n - 1));
    CHECK(diagonal == 2 * (n - 1) * (n - 1));
  }
  SUBCASE("smaller disks: boundary edges end at the clip box, margin beyond the centres") {
    const std::vector<double> R(x.size(), 0.3 * s);
    for (double margin : {-1.0, 0.8 * s}) {
      const double m = margin < 0 ? 0.3 * s : margin;
      const auto r = voronoi_radii(x, R, nl, {}, {.margin = margin});
      each_pair(nl, r.pair, [&](std::size_t i, std::size_t j, double rij) {
        if ((x[i] - x[j]).norm() > 1.1 * s) return;
        const Vec2 mid = 0.5 * (x[i] + x[j]);
        // a pair along the boundary shares an edge from the lattice inside to the box
        const bool along_boundary = (x[i] - x[j]).x() != 0.0
                                        ? (mid.y() == 0.0 || mid.y() == (n - 1) * s)
                                        : (mid.x() == 0.0 || mid.x() == (n - 1) * s);
        CAPTURE(margin);
        CHECK(rij == doctest::Approx(along_boundary ? (s / 2 + m) / 2 : s / 2).epsilon(1e-9));
      });
    }
  }
}

TEST_CASE("voronoi: hexagonal lattice, r = s/(2 sqrt 3)") {
  const double s = 1e-3;
  std::vector<Vec2> x;
  for (int j = 0; j < 10; ++j)
    for (int i = 0; i < 10; ++i)
      x.emplace_back((i + 0.5 * (j % 2)) * s, j * s * std::sqrt(3.0) / 2);
  const std::vector<double> R(x.size(), s / 2);
  const auto nl = pairs_within<2>(x, 1.8 * s);
  const auto r = voronoi_radii(x, R, nl);
  int checked = 0;
  each_pair(nl, r.pair, [&](std::size_t i, std::size_t j, double rij) {
    CHECK(std::isfinite(rij));
    if (!interior<2>(x[i], x, 1.5 * s) || !interior<2>(x[j], x, 1.5 * s)) return;
    if ((x[i] - x[j]).norm() < 1.1 * s) {
      CHECK(rij == doctest::Approx(s / (2 * std::sqrt(3.0))).epsilon(1e-9));
      ++checked;
    } else {
      CHECK(rij == 0.0); // second neighbours at sqrt(3) s
    }
  });
  CHECK(checked > 50);
}

TEST_CASE("voronoi: simple cubic lattice, face area s^2, r = s/sqrt(pi)") {
  const double s = 1e-3;
  const auto x = cubic_lattice(5, s);
  const std::vector<double> R(x.size(), s / 2); // touching: boundary faces are s^2 too
  const auto nl = pairs_within<3>(x, 1.8 * s);
  const auto r = voronoi_radii(x, R, nl);
  int near = 0, far = 0;
  each_pair(nl, r.pair, [&](std::size_t i, std::size_t j, double rij) {
    if ((x[i] - x[j]).norm() < 1.1 * s) {
      CHECK(rij == doctest::Approx(s / std::sqrt(pi)).epsilon(1e-9));
      ++near;
    } else {
      CHECK(rij == 0.0); // face and body diagonals
      ++far;
    }
  });
  CHECK(near == 3 * 25 * 4);
  CHECK(far > 0);
}

TEST_CASE("voronoi: FCC lattice, rhombic dodecahedron faces of area s^2/(2 sqrt 2)") {
  // Cubic cell a, nearest distance s = a/sqrt 2. The rhombic faces have diagonals a/sqrt 2 and
  // a/2: area a^2/(4 sqrt 2) = s^2/(2 sqrt 2) (12 faces at s/2 from the centre enclose a^3/4).
  const double a = 2e-3, s = a / std::sqrt(2.0);
  const auto x = fcc_block(3, a);
  const std::vector<double> R(x.size(), s / 2);
  const auto nl = pairs_within<3>(x, 1.1 * a);
  const auto r = voronoi_radii(x, R, nl);
  const double expected = std::sqrt(s * s / (2 * std::sqrt(2.0)) / pi);
  int near = 0, second = 0;
  each_pair(nl, r.pair, [&](std::size_t i, std::size_t j, double rij) {
    if (!interior<3>(x[i], x, 0.9 * a) || !interior<3>(x[j], x, 0.9 * a)) return;
    if ((x[i] - x[j]).norm() < 1.1 * s) {
      CHECK(rij == doctest::Approx(expected).epsilon(1e-9));
      ++near;
    } else {
      CHECK(rij == 0.0); // second neighbours at a share only a vertex
      ++second;
    }
  });
  CHECK(near > 12);
  CHECK(second > 0);
}

TEST_CASE("voronoi: power diagram puts the face through the contact point") {
  // Disks A (R = 1) at (0, 0) and B (R = 1) at (2, 0) touch; C (R = 0.2) touches both above.
  // The A-B edge lies on x = 1 and ends at the box bottom (y = -1, margin R_max = 1) and at the
  // vertex shared with C, below the axis in the Voronoi diagram and above it in the power diagram.
  const double rc = 0.2, yc = std::sqrt((1 + rc) * (1 + rc) - 1);
  const std::vector<Vec2> x{{0, 0}, {2, 0}, {1, yc}};
  const std::vector<double> R{1, 1, rc};
  const auto nl = pairs_within<2>(x, 3.0);
  // vertex (1, y) equidistant from A and C: 1 + y^2 - w_A = (y - yc)^2 - w_C
  const double y_voronoi = (yc * yc - 1) / (2 * yc);
  const double y_power = (yc * yc - rc * rc) / (2 * yc);
  const auto rv = voronoi_radii(x, R, nl, {}, {.diagram = Diagram::voronoi});
  const auto rp = voronoi_radii(x, R, nl);
  CHECK(rv.pair[0] == doctest::Approx((y_voronoi + 1) / 2).epsilon(1e-9));
  CHECK(rp.pair[0] == doctest::Approx((y_power + 1) / 2).epsilon(1e-9));
  // the A-C power edge lies on the common tangent at the contact point (at distance 1 from A)
  // and runs from the A-B-C vertex to the box's left or top side
  const Vec2 contact = x[2] / (1 + rc);
  const Vec2 vertex(1, y_power);
  const Vec2 dir = (x[2] - x[0]).normalized();
  CHECK((vertex - contact).dot(dir) == doctest::Approx(0.0).scale(1.0));
  const Vec2 along(-dir.y(), dir.x()); // from the vertex towards the upper left
  double t = std::numeric_limits<double>::infinity();
  if (along.x() < 0) t = std::min(t, (-1.0 - vertex.x()) / along.x());     // box x >= -1
  if (along.y() > 0) t = std::min(t, (yc + 1.0 - vertex.y()) / along.y()); // box y <= yc + 1
  CHECK(rp.pair[1] == doctest::Approx(t / 2).epsilon(1e-9));
}

TEST_CASE("voronoi: random packings, boundary particles get finite positive radii") {
  for (int dim : {2, 3}) {
    CAPTURE(dim);
    auto run = [&](auto tag) {
      constexpr int D = decltype(tag)::value;
      std::vector<Vec<D>> x;
      std::vector<double> R;
      random_packing<D>(D == 2 ? 400 : 600, D == 2 ? 0.04 : 0.02, 0.5e-3, 1e-3, 3, x, R);
      const auto nl = pairs_within<D>(x, 6e-3);
      const auto r = voronoi_radii(x, R, nl);
      std::vector<double> largest(x.size(), 0.0);
      double bound = 0.0; // half the diagonal of the clip box
      {
        Vec<D> lo = x[0], hi = x[0];
        for (const auto& p : x) {
          lo = lo.cwiseMin(p);
          hi = hi.cwiseMax(p);
        }
        bound = 0.5 * ((hi - lo).array() + 2e-3).matrix().norm();
      }
      each_pair(nl, r.pair, [&](std::size_t i, std::size_t j, double rij) {
        CHECK(std::isfinite(rij));
        CHECK(rij >= 0.0);
        CHECK(rij <= bound);
        largest[i] = std::max(largest[i], rij);
        largest[j] = std::max(largest[j], rij);
      });
      for (double v : largest)
        CHECK(v > 0.0); // every particle conducts to some neighbour
    };
    if (dim == 2)
      run(std::integral_constant<int, 2>{});
    else
      run(std::integral_constant<int, 3>{});
  }
}

TEST_CASE("voronoi: radii do not depend on the order of the particles") {
  auto check = [](auto tag) {
    constexpr int D = decltype(tag)::value;
    std::vector<Vec<D>> x;
    std::vector<double> R;
    random_packing<D>(300, D == 2 ? 0.05 : 0.02, 0.4e-3, 1.2e-3, 11, x, R);
    std::vector<std::size_t> perm(x.size());
    for (std::size_t k = 0; k < perm.size(); ++k)
      perm[k] = k;
    std::shuffle(perm.begin(), perm.end(), std::mt19937(5));
    std::vector<Vec<D>> xp;
    std::vector<double> Rp;
    for (auto k : perm) {
      xp.push_back(x[k]);
      Rp.push_back(R[k]);
    }
    for (Diagram diagram : {Diagram::power, Diagram::voronoi}) {
      const auto nl = pairs_within<D>(x, 6e-3);
      const auto nlp = pairs_within<D>(xp, 6e-3);
      const auto r = voronoi_radii(x, R, nl, {}, {.diagram = diagram});
      const auto rp = voronoi_radii(xp, Rp, nlp, {}, {.diagram = diagram});
      std::map<std::pair<std::size_t, std::size_t>, double> by_pair;
      each_pair(nl, r.pair, [&](std::size_t i, std::size_t j, double rij) {
        by_pair[{std::min(i, j), std::max(i, j)}] = rij;
      });
      REQUIRE(by_pair.size() == nlp.partners.size());
      int positive = 0;
      each_pair(nlp, rp.pair, [&](std::size_t i, std::size_t j, double rij) {
        const std::size_t a = perm[i], b = perm[j];
        const double ref = by_pair.at({std::min(a, b), std::max(a, b)});
        CHECK(rij == doctest::Approx(ref).epsilon(1e-9).scale(1e-3));
        positive += rij > 0;
      });
      CHECK(positive > 300);
    }
  };
  check(std::integral_constant<int, 2>{});
  check(std::integral_constant<int, 3>{});
}

TEST_CASE("voronoi: particle-wall radii from the cell's face on the wall") {
  SUBCASE("square lattice on a floor: bottom row r = s/2, rows above 0") {
    const double s = 1e-3;
    const auto x = square_lattice(6, s);
    const std::vector<double> R(x.size(), s / 2);
    const auto nl = with_wall_for_all(pairs_within<2>(x, 1.5 * s));
    const std::vector<WallPlane<2>> floor(nl.walls.size(), {Vec2(0, -s / 2), Vec2(0, 1)});
    const auto r = voronoi_radii(x, R, nl, floor);
    REQUIRE(r.wall.size() == x.size());
    for (std::size_t i = 0; i < x.size(); ++i) {
      CAPTURE(i);
      CHECK(r.wall[i] == doctest::Approx(x[i].y() == 0.0 ? s / 2 : 0.0).scale(s));
    }
    // a floor with a gap of R/2 under the bottom row (normal of any length and sense): the same
    const std::vector<WallPlane<2>> low(nl.walls.size(), {Vec2(0, -0.75 * s), Vec2(0, -3)});
    const auto rl = voronoi_radii(x, R, nl, low);
    for (std::size_t i = 0; i < x.size(); ++i)
      CHECK(rl.wall[i] == doctest::Approx(x[i].y() == 0.0 ? s / 2 : 0.0).scale(s));
    // a wall farther than 2 R_max from every centre gets 0
    const std::vector<WallPlane<2>> far(nl.walls.size(), {Vec2(0, -3 * s), Vec2(0, 1)});
    for (double v : voronoi_radii(x, R, nl, far).wall)
      CHECK(v == 0.0);
  }
  SUBCASE("cubic lattice on a floor: bottom layer r = s/sqrt(pi)") {
    const double s = 1e-3;
    const auto x = cubic_lattice(4, s);
    const std::vector<double> R(x.size(), s / 2);
    const auto nl = with_wall_for_all(pairs_within<3>(x, 1.1 * s));
    const std::vector<WallPlane<3>> floor(nl.walls.size(), {Vec3(0, 0, -s / 2), Vec3(0, 0, 1)});
    const auto r = voronoi_radii(x, R, nl, floor);
    for (std::size_t i = 0; i < x.size(); ++i) {
      CAPTURE(i);
      CHECK(r.wall[i] == doctest::Approx(x[i].z() == 0.0 ? s / std::sqrt(pi) : 0.0).scale(s));
    }
  }
  SUBCASE("a lone particle: its face is the clip box section, 2R wide") {
    const double R = 1e-3;
    NeighborList nl;
    nl.clear(1);
    nl.offsets.push_back(0);
    nl.walls.push_back(0);
    nl.wall_offsets.push_back(1);
    const auto r2 = voronoi_radii(std::vector<Vec2>{{0, 0}}, std::vector<double>{R}, nl,
                                  std::vector<WallPlane<2>>{{Vec2(0, -R), Vec2(0, 1)}});
    CHECK(r2.wall[0] == doctest::Approx(R)); // L = 2R
    const auto r3 = voronoi_radii(std::vector<Vec3>{{0, 0, 0}}, std::vector<double>{R}, nl,
                                  std::vector<WallPlane<3>>{{Vec3(0, 0, -R), Vec3(0, 0, 1)}});
    CHECK(r3.wall[0] == doctest::Approx(2 * R / std::sqrt(pi))); // A = (2R)^2
  }
}

TEST_CASE("voronoi: small and degenerate inputs") {
  const double R = 1e-3;
  // two particles: the face is the clip box section through the bisector
  const std::vector<Vec3> two{{0, 0, 0}, {2 * R, 0, 0}};
  const auto nl2 = pairs_within<3>(two, 5 * R);
  CHECK(voronoi_radii(two, std::vector<double>{R, R}, nl2).pair[0] ==
        doctest::Approx(2 * R / std::sqrt(pi)));
  // collinear disks in 2D
  const std::vector<Vec2> line{{0, 0}, {2 * R, 0}, {4 * R, 0}};
  const auto nl3 = pairs_within<2>(line, 5 * R);
  const auto r = voronoi_radii(line, std::vector<double>(3, R), nl3);
  CHECK(r.pair[0] == doctest::Approx(R)); // (0,1): edge 2R long
  CHECK(r.pair[1] == 0.0);                // (0,2): not neighbours
  // empty input, bad input
  CHECK(voronoi_radii(std::vector<Vec2>{}, std::vector<double>{}, pairs_within<2>({}, 1.0))
            .pair.empty());
  CHECK_THROWS_AS(voronoi_radii(line, std::vector<double>{R}, nl3), InputError);
  CHECK_THROWS_AS(voronoi_radii(line, std::vector<double>(3, 0.0), nl3), InputError); // margin 0
  CHECK(voronoi_radii(line, std::vector<double>(3, 0.0), nl3, {}, {.margin = R}).pair[0] ==
        doctest::Approx(R));
  CHECK_THROWS_AS(voronoi_radii(line, std::vector<double>(3, R), nl3,
                                std::vector<WallPlane<2>>{{Vec2::Zero(), Vec2::UnitY()}}),
                  InputError);
}

TEST_CASE("voronoi: 3D hull volume and global porosity") {
  const double s = 1e-3;
  CHECK(hull_volume(cubic_lattice(3, s)) == doctest::Approx(8 * s * s * s).epsilon(1e-12));
  const std::vector<Vec3> octahedron{{s, 0, 0},  {-s, 0, 0}, {0, s, 0},
                                     {0, -s, 0}, {0, 0, s},  {0, 0, -s}};
  CHECK(hull_volume(octahedron) == doctest::Approx(4.0 / 3.0 * s * s * s).epsilon(1e-12));
  CHECK(hull_volume(std::vector<Vec3>{{0, 0, 0}, {s, 0, 0}, {0, s, 0}, {s, s, 0}}) == 0.0);
  // blocks of whole lattice cells: balls on faces, edges, corners count 1/2, 1/4, 1/8 exactly,
  // so there is no boundary effect for any block size
  for (int n : {2, 3, 6}) {
    const auto x = cubic_lattice(n, s);
    CAPTURE(n);
    CHECK(global_porosity(x, std::vector<double>(x.size(), s / 2)) ==
          doctest::Approx(1 - pi / 6).epsilon(1e-12));
  }
  const double a = 1e-3;
  const auto f = fcc_block(2, a);
  CHECK(global_porosity(f, std::vector<double>(f.size(), a / (2 * std::sqrt(2.0)))) ==
        doctest::Approx(1 - pi / (3 * std::sqrt(2.0))).epsilon(1e-12));
  // a flat layer has no volume
  const auto layer = cubic_lattice(3, s);
  std::vector<Vec3> flat;
  for (const auto& p : layer)
    if (p.z() == 0.0) flat.push_back(p);
  CHECK(global_porosity(flat, std::vector<double>(flat.size(), s / 2)) == 1.0);
}

TEST_CASE("voronoi: 3D local porosity of an interior particle of a cubic lattice") {
  const double s = 1e-3;
  const auto x = cubic_lattice(5, s);
  const std::vector<double> R(x.size(), s / 2);
  const std::size_t mid = 2 + 5 * (2 + 5 * 2);
  // 26 neighbours: the hull is a cube of 8 cells holding 8 balls' worth
  CHECK(local_porosity(x, R, pairs_within<3>(x, 1.8 * s))[mid] ==
        doctest::Approx(1 - pi / 6).epsilon(1e-12));
  // 6 neighbours: an octahedron of volume 4/3 s^3; the centre ball whole, each vertex ball the
  // octahedron's vertex solid angle 4 asin(1/3) over 4 pi:
  // phi = 1 - (pi/8) (1 + 6 asin(1/3)/pi) = 1 - pi/8 - (3/4) asin(1/3)
  const auto phi6 = local_porosity(x, R, pairs_within<3>(x, 1.1 * s));
  CHECK(phi6[mid] == doctest::Approx(1 - pi / 8 - 0.75 * std::asin(1.0 / 3.0)).epsilon(1e-12));
  // a corner particle with 3 neighbours spans a tetrahedron; a lone particle gives 1
  CHECK(phi6[0] > 0.0);
  CHECK(phi6[0] < 1.0);
  const std::vector<Vec3> one{{0, 0, 0}};
  CHECK(local_porosity(one, std::vector<double>{s}, pairs_within<3>(one, s))[0] == 1.0);
}
