// Initial packings (generate::fill): particles wholly inside every region type and free of
// overlaps (brute force over all pairs), targets reached, the size distributions against their
// closed forms, reproducibility, lattice counts, the failure report, the radius growth and the
// input checks.
//
// Statistical checks use N draws and 3 standard errors: at a fixed seed they are deterministic,
// and a correct sampler passes each with probability 0.997.

#include "../errors.hpp"
#include "../support/meshes.hpp"
#include <doctest/doctest.h>
#include <grain/grain.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <string>
#include <vector>

using namespace grain;
using grain::test::error_of;
using grain::test::has;

namespace {

/// The largest overlap (r_i + r_j - |x_i - x_j|) / min(r_i, r_j) over all pairs (<= 0: none).
template <int D>
double worst_overlap(const generate::Result<D>& res) {
  double worst = -std::numeric_limits<double>::infinity();
  const auto& p = res.particles;
  for (std::size_t i = 0; i < p.size(); ++i)
    for (std::size_t j = i + 1; j < p.size(); ++j) {
      const double o = p[i].radius + p[j].radius - (p[i].position - p[j].position).norm();
      worst = std::max(worst, o / std::min(p[i].radius, p[j].radius));
    }
  return worst;
}

/// True if no two particles overlap: |x_i - x_j| >= r_i + r_j exactly (squared, as the fill).
template <int D>
bool no_overlap(const generate::Result<D>& res) {
  const auto& p = res.particles;
  for (std::size_t i = 0; i < p.size(); ++i)
    for (std::size_t j = i + 1; j < p.size(); ++j) {
      const double s = p[i].radius + p[j].radius;
      if ((p[i].position - p[j].position).squaredNorm() < s * s) return false;
    }
  return true;
}

double seg_distance(const Vec2& x, const Vec2& a, const Vec2& b) {
  const Vec2 ab = b - a;
  const double s = std::clamp((x - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
  return (a + s * ab - x).norm();
}

/// Wholly inside, tested independently of the library's own test.
bool inside(const regions::Box<3>& b, const Vec3& x, double r) {
  return (x.array() - r >= b.lo.array()).all() && (x.array() + r <= b.hi.array()).all();
}
bool inside(const regions::Box<2>& b, const Vec2& x, double r) {
  return (x.array() - r >= b.lo.array()).all() && (x.array() + r <= b.hi.array()).all();
}
template <int D>
bool inside(const regions::Ball<D>& b, const Vec<D>& x, double r) {
  return (x - b.center).norm() + r <= b.radius * (1 + 1e-14);
}
bool inside(const generate::Cylinder& c, const Vec3& x, double r) {
  const Vec3 u = (c.b - c.a).normalized();
  const double t = (x - c.a).dot(u);
  return t >= r * (1 - 1e-12) && t <= (c.b - c.a).norm() - r * (1 - 1e-12) &&
         ((x - c.a) - t * u).norm() + r <= c.radius * (1 + 1e-14);
}
bool inside(const regions::Polygon& p, const Vec2& x, double r) {
  if (!p.contains(x)) return false;
  for (std::size_t k = 0, l = p.vertices.size() - 1; k < p.vertices.size(); l = k++)
    if (seg_distance(x, p.vertices[l], p.vertices[k]) < r * (1 - 1e-12)) return false;
  return true;
}

template <class R, int D>
bool all_inside(const R& region, const generate::Result<D>& res) {
  for (const auto& p : res.particles)
    if (!inside(region, p.position, p.radius)) return false;
  return true;
}

template <int D>
double volume_of(double r) {
  return D == 3 ? 4.0 / 3.0 * std::numbers::pi * r * r * r : std::numbers::pi * r * r;
}

/// Checks a random fill of `region`: no overlap, all inside, the target reached.
template <class R>
void check_fill(const R& region, double region_volume, const generate::Options& o,
                const generate::Distribution& dist, double r_max) {
  constexpr int D = generate::detail::region_dimension<R>::value;
  const auto res = generate::fill(region, dist, o);
  CHECK(res.complete);
  CHECK(res.particles.size() > 1000);
  CHECK(no_overlap(res));
  CHECK(all_inside(region, res));
  double v = 0.0;
  for (const auto& p : res.particles) {
    v += volume_of<D>(p.radius);
    CHECK(p.id == -1);
    CHECK(p.material == o.material);
  }
  CHECK(res.solid_fraction == doctest::Approx(v / region_volume).epsilon(1e-12));
  if (o.count > 0) CHECK(res.particles.size() == o.count);
  // the fraction within one particle's volume of the target
  if (o.solid_fraction > 0)
    CHECK(std::abs(res.solid_fraction - o.solid_fraction) <= volume_of<D>(r_max) / region_volume);
}

double normal_pdf(double z) { return std::exp(-0.5 * z * z) / std::sqrt(2 * std::numbers::pi); }
double normal_cdf(double z) { return 0.5 * std::erfc(-z / std::sqrt(2.0)); }

/// Mean, standard deviation and their standard errors of a sample.
struct Moments {
  double mean, sd, se_mean, se_sd;
};
Moments moments(const std::vector<double>& v) {
  const double n = static_cast<double>(v.size());
  double m = 0;
  for (double x : v)
    m += x;
  m /= n;
  double m2 = 0, m4 = 0;
  for (double x : v) {
    m2 += (x - m) * (x - m);
    m4 += std::pow(x - m, 4);
  }
  m2 /= n;
  m4 /= n;
  const double sd = std::sqrt(m2);
  return {m, sd, sd / std::sqrt(n), std::sqrt((m4 - m2 * m2) / n) / (2 * sd)};
}

std::vector<double> draws(const generate::Distribution& d, int dim, std::size_t n,
                          std::uint64_t seed = 11) {
  const generate::detail::Sampler s(d, dim);
  generate::Random rng(seed);
  std::vector<double> v(n);
  for (auto& x : v)
    x = s.sample(rng);
  return v;
}

} // namespace

TEST_CASE("generate: random fills are inside every region and free of overlaps (3D)") {
  const generate::Uniform dist{0.02, 0.03};
  generate::Options o{.material = 3, .solid_fraction = 0.3, .seed = 5};
  SUBCASE("box") {
    const regions::Box<3> box{Vec3(0.1, -0.2, 0.0), Vec3(0.9, 0.6, 0.7)};
    check_fill(box, 0.8 * 0.8 * 0.7, o, dist, 0.03);
  }
  SUBCASE("sphere") {
    const regions::Ball<3> ball{Vec3(1, 2, 3), 0.5};
    check_fill(ball, 4.0 / 3.0 * std::numbers::pi * 0.125, o, dist, 0.03);
  }
  SUBCASE("cylinder along a slanted axis, by count") {
    const auto cyl = generate::Cylinder::along(Vec3(0, 0, 0), Vec3(1, 1, 2), 0.3, -0.4, 0.9);
    CHECK((cyl.b - cyl.a).norm() == doctest::Approx(1.3));
    o.solid_fraction = 0;
    o.count = 1500;
    check_fill(cyl, std::numbers::pi * 0.09 * 1.3, o, dist, 0.03);
  }
  SUBCASE("closed mesh: a cube of 12 triangles") {
    const generate::ClosedMesh cube(test::box(Vec3(0, 0, 0), Vec3(0.7, 0.7, 0.7)), "cube");
    CHECK(cube.volume() == doctest::Approx(0.343).epsilon(1e-12));
    check_fill(regions::Box<3>{Vec3(0, 0, 0), Vec3(0.7, 0.7, 0.7)}, 0.343, o, dist, 0.03);
    const auto res = generate::fill(cube, dist, o);
    CHECK(no_overlap(res));
    CHECK(all_inside(regions::Box<3>{Vec3(0, 0, 0), Vec3(0.7, 0.7, 0.7)}, res));
    CHECK(std::abs(res.solid_fraction - 0.3) <= volume_of<3>(0.03) / 0.343);
  }
}

TEST_CASE("generate: random fills are inside every region and free of overlaps (2D)") {
  const generate::Uniform dist{0.004, 0.006};
  generate::Options o{.solid_fraction = 0.45, .seed = 9};
  SUBCASE("rectangle") {
    const regions::Box<2> box{Vec2(0, 0), Vec2(0.6, 0.4)};
    check_fill(box, 0.24, o, dist, 0.006);
  }
  SUBCASE("circle, by count") {
    const regions::Ball<2> ball{Vec2(-1, 1), 0.25};
    o.solid_fraction = 0;
    o.count = 1100;
    check_fill(ball, std::numbers::pi * 0.0625, o, dist, 0.006);
  }
  SUBCASE("L-shaped polygon (not convex)") {
    const regions::Polygon poly{{Vec2(0, 0), Vec2(0.52, 0), Vec2(0.52, 0.26), Vec2(0.26, 0.26),
                                 Vec2(0.26, 0.52), Vec2(0, 0.52)}};
    check_fill(poly, 0.52 * 0.52 - 0.26 * 0.26, o, dist, 0.006);
  }
}

TEST_CASE("generate: a cube mesh fills like the equal box, and its inside test is exact on edges") {
  const Vec3 lo(-0.3, 0.1, 0.2), hi(0.4, 0.6, 0.9);
  const generate::ClosedMesh cube(test::box(lo, hi));
  const regions::Box<3> box{lo, hi};
  const generate::Options o{.solid_fraction = 0.25, .seed = 21};
  const generate::LogNormal dist{0.02, 0.2, 0.01, 0.04};
  const auto a = generate::fill(cube, dist, o);
  const auto b = generate::fill(box, dist, o);
  // the same trial positions are accepted: the same packing, to the last bit
  REQUIRE(a.particles.size() == b.particles.size());
  for (std::size_t k = 0; k < a.particles.size(); ++k)
    CHECK(a.particles[k].position == b.particles[k].position);
  CHECK(a.solid_fraction == doctest::Approx(b.solid_fraction).epsilon(1e-12)); // volumes
  CHECK(a.attempts == b.attempts);
  // rays in +z through the diagonal edges of the top and bottom faces and through vertices
  const Vec3 c = 0.5 * (lo + hi);
  const double t = 0.37;
  CHECK(cube.contains(Vec3(lo.x() + t * (hi.x() - lo.x()), lo.y() + t * (hi.y() - lo.y()), c.z())));
  CHECK(cube.contains(c));
  CHECK_FALSE(cube.contains(Vec3(hi.x() + 1e-9, c.y(), c.z())));
  CHECK_FALSE(cube.contains(Vec3(c.x(), c.y(), hi.z() + 1e-9)));
  // an octahedron turned so that a vertical ray meets its vertices and edges
  walls::TriangleMesh oct;
  oct.vertices = {Vec3(1, 0, 0),  Vec3(-1, 0, 0), Vec3(0, 1, 0),
                  Vec3(0, -1, 0), Vec3(0, 0, 1),  Vec3(0, 0, -1)};
  oct.triangles = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4},
                   {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  const generate::ClosedMesh o8(oct, "octahedron");
  CHECK(o8.volume() == doctest::Approx(4.0 / 3.0).epsilon(1e-12));
  int wrong = 0;
  for (int i = -20; i <= 20; ++i)
    for (int j = -20; j <= 20; ++j)
      for (int k = -20; k <= 20; ++k) {
        const Vec3 x(0.05 * i, 0.05 * j, 0.05 * k + 0.001); // rays through x = 0 or y = 0 edges
        const double l1 = std::abs(x.x()) + std::abs(x.y()) + std::abs(x.z());
        if (std::abs(l1 - 1.0) < 1e-9) continue; // on the surface
        wrong += o8.contains(x) != (l1 < 1.0);
      }
  CHECK(wrong == 0);
}

TEST_CASE("generate: the inside test of a terraced mesh is exact at every step height") {
  // A staircase of unit voxels of side 1/16 m (exact binary heights): column i (of 12) holds
  // i + 1 voxels, 5 columns deep in y. Its flat treads lie at every height 1/16 .. 12/16 m, so
  // some fall on the boundaries of the mesh's bucket grid, where a crossing height rounded below
  // its tread lands in a cell that does not hold the triangle. The surface is made of the voxel
  // faces that have no voxel beside them (two triangles each, outward), on shared vertices.
  // 40 000 random points against the staircase's closed-form inside test; points within 1e-9 m
  // of a face are skipped. Expected: no wrong answer.
  const int nx = 12, ny = 5;
  const double s = 1.0 / 16.0;
  auto height = [](int i) { return i + 1; };
  auto filled = [&](int i, int j, int k) {
    return i >= 0 && i < nx && j >= 0 && j < ny && k >= 0 && k < height(i);
  };
  walls::TriangleMesh m;
  std::vector<std::int64_t> index_of((nx + 1) * (ny + 1) * (nx + 2), -1);
  auto vertex = [&](int i, int j, int k) {
    auto& v = index_of[(k * (ny + 1) + j) * (nx + 1) + i];
    if (v < 0) {
      v = static_cast<std::int64_t>(m.vertices.size());
      m.vertices.push_back(Vec3(i * s, j * s, k * s));
    }
    return static_cast<std::uint32_t>(v);
  };
  // a unit square face from corner (i, j, k), spanning axes u and w, outward along +d or -d
  auto quad = [&](std::array<int, 3> c, int u, int w, bool flip) {
    std::array<std::array<int, 3>, 4> q{c, c, c, c};
    q[1][u] += 1;
    q[2][u] += 1;
    q[2][w] += 1;
    q[3][w] += 1;
    std::array<std::uint32_t, 4> v{};
    for (int k = 0; k < 4; ++k)
      v[k] = vertex(q[k][0], q[k][1], q[k][2]);
    if (flip) std::swap(v[1], v[3]);
    m.triangles.push_back({v[0], v[1], v[2]});
    m.triangles.push_back({v[0], v[2], v[3]});
  };
  for (int i = 0; i < nx; ++i)
    for (int j = 0; j < ny; ++j)
      for (int k = 0; k < height(i); ++k)
        for (int d = 0; d < 3; ++d) {
          const int u = (d + 1) % 3, w = (d + 2) % 3; // (u, w, d) right-handed
          for (int side = 0; side < 2; ++side) {
            std::array<int, 3> n{i, j, k};
            n[d] += side == 0 ? -1 : 1;
            if (filled(n[0], n[1], n[2])) continue;
            std::array<int, 3> c{i, j, k};
            c[d] += side;
            quad(c, u, w, side == 0); // u x w = +d: counter-clockwise seen from outside on +d
          }
        }
  const generate::ClosedMesh stairs(m, "stairs");
  double volume = 0.0;
  for (int i = 0; i < nx; ++i)
    volume += height(i) * ny * s * s * s;
  CHECK(stairs.volume() == doctest::Approx(volume).epsilon(1e-12));
  std::uint64_t state = 12345;
  auto uniform = [&] {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return static_cast<double>(state >> 11) * 0x1.0p-53;
  };
  int wrong = 0, tested = 0;
  for (int n = 0; n < 40000; ++n) {
    const Vec3 x(-0.05 + (nx * s + 0.1) * uniform(), -0.05 + (ny * s + 0.1) * uniform(),
                 -0.05 + ((nx + 1) * s + 0.1) * uniform());
    const int i = static_cast<int>(std::floor(x.x() / s));
    const double top = i >= 0 && i < nx ? height(i) * s : 0.0;
    // distance to the nearest face plane that could bound the point
    const double near = std::min({std::abs(x.x() - std::round(x.x() / s) * s), std::abs(x.y()),
                                  std::abs(x.y() - ny * s), std::abs(x.z()),
                                  std::abs(x.z() - std::round(x.z() / s) * s)});
    if (near < 1e-9) continue;
    ++tested;
    const bool inside =
        x.x() > 0 && x.x() < nx * s && x.y() > 0 && x.y() < ny * s && x.z() > 0 && x.z() < top;
    wrong += stairs.contains(x) != inside;
  }
  MESSAGE(tested << " points tested");
  CHECK(tested > 39000);
  CHECK(wrong == 0);
  // points just below and above every tread, at the centre of the tread
  for (int i = 0; i < nx; ++i) {
    const double xc = (i + 0.5) * s, yc = 2.5 * s, z = height(i) * s;
    CHECK(stairs.contains(Vec3(xc, yc, z - 1e-12)));
    CHECK_FALSE(stairs.contains(Vec3(xc, yc, z + 1e-12)));
  }
}

TEST_CASE("generate: size distributions match their closed forms") {
  const std::size_t n = 200000;
  SUBCASE("uniform") {
    const auto m = moments(draws(generate::Uniform{1e-3, 3e-3}, 3, n));
    CHECK(std::abs(m.mean - 2e-3) < 3 * m.se_mean);
    CHECK(std::abs(m.sd - 2e-3 / std::sqrt(12.0)) < 3 * m.se_sd);
  }
  SUBCASE("truncated normal (asymmetric bounds)") {
    const double mu = 1e-3, s = 0.3e-3, a = 0.6e-3, b = 1.9e-3;
    const double al = (a - mu) / s, be = (b - mu) / s, Z = normal_cdf(be) - normal_cdf(al);
    const double dphi = (normal_pdf(al) - normal_pdf(be)) / Z;
    const double mean = mu + s * dphi;
    const double sd =
        s * std::sqrt(1 + (al * normal_pdf(al) - be * normal_pdf(be)) / Z - dphi * dphi);
    const auto v = draws(generate::Normal{mu, s, a, b}, 3, n);
    CHECK(*std::min_element(v.begin(), v.end()) >= a);
    CHECK(*std::max_element(v.begin(), v.end()) <= b);
    const auto m = moments(v);
    CHECK(std::abs(m.mean - mean) < 3 * m.se_mean);
    CHECK(std::abs(m.sd - sd) < 3 * m.se_sd);
  }
  SUBCASE("log-normal median (bounds symmetric in ln r keep the median)") {
    const double med = 0.5e-3, sig = 0.4;
    auto v = draws(generate::LogNormal{med, sig, 0.25 * med, 4.0 * med}, 3, n);
    std::nth_element(v.begin(), v.begin() + n / 2, v.end());
    const double z = std::log(4.0) / sig, Z = normal_cdf(z) - normal_cdf(-z);
    const double density = normal_pdf(0.0) / (sig * med * Z); // of r at the median
    const double se = 1.0 / (2.0 * density * std::sqrt(double(n)));
    CHECK(std::abs(v[n / 2] - med) < 3 * se);
    // from_mean: median = mean exp(-sigma^2 / 2)
    CHECK(generate::LogNormal::from_mean(1.0, 0.4, 0.1, 10).median ==
          doctest::Approx(std::exp(-0.08)));
  }
  SUBCASE("discrete: number and mass fractions (3D and 2D)") {
    const std::vector<double> r{1e-3, 2e-3, 3e-3};
    const std::vector<double> f{0.2, 0.5, 0.3};
    for (auto basis : {generate::Discrete::Basis::number, generate::Discrete::Basis::mass})
      for (int dim : {3, 2}) {
        CAPTURE(dim);
        const auto v = draws(generate::Discrete{r, f, basis}, dim, n);
        std::vector<double> p(3);
        double sum = 0;
        for (int k = 0; k < 3; ++k)
          sum += p[k] =
              basis == generate::Discrete::Basis::number ? f[k] : f[k] / std::pow(r[k], dim);
        for (int k = 0; k < 3; ++k) {
          const double expect = p[k] / sum;
          const double got = double(std::count(v.begin(), v.end(), r[k])) / double(n);
          CHECK(std::abs(got - expect) < 3 * std::sqrt(expect * (1 - expect) / double(n)));
        }
      }
  }
}

TEST_CASE("generate: the same seed gives the same packing, another seed another") {
  const regions::Ball<3> ball{Vec3::Zero(), 0.2};
  const generate::Normal dist{0.01, 0.003, 0.005, 0.02};
  generate::Options o{.solid_fraction = 0.3, .seed = 1234};
  const auto a = generate::fill(ball, dist, o);
  const auto b = generate::fill(ball, dist, o);
  REQUIRE(a.particles.size() == b.particles.size());
  bool same = true;
  for (std::size_t k = 0; k < a.particles.size(); ++k)
    same = same && a.particles[k].position == b.particles[k].position &&
           a.particles[k].radius == b.particles[k].radius;
  CHECK(same);
  o.seed = 1235;
  const auto c = generate::fill(ball, dist, o);
  CHECK(c.particles.front().position != a.particles.front().position);
  CHECK(c.particles.front().radius != a.particles.front().radius);
}

TEST_CASE("generate: lattices in a box have the closed-form number of sites") {
  const double r = 0.05, gap = 0.01, a = 2 * r + gap; // spacing 0.11
  generate::Options o{.mode = generate::Mode::lattice, .gap = gap};
  const double Lx = 1.0, Ly = 0.83, Lz = 0.61;
  const regions::Box<3> box3{Vec3(0.2, 0.1, 0.3), Vec3(0.2 + Lx, 0.1 + Ly, 0.3 + Lz)};
  const regions::Box<2> box2{Vec2(0.2, 0.1), Vec2(0.2 + Lx, 0.1 + Ly)};
  auto fl = [](double v) { return static_cast<std::size_t>(std::floor(v)); };
  // square / simple cubic: prod floor(L / a)
  const auto sq = generate::fill(box2, generate::Constant{r}, o);
  CHECK(sq.particles.size() == fl(Lx / a) * fl(Ly / a));
  const auto sc = generate::fill(box3, generate::Constant{r}, o);
  CHECK(sc.particles.size() == fl(Lx / a) * fl(Ly / a) * fl(Lz / a));
  CHECK(no_overlap(sc));
  CHECK(all_inside(box3, sc));
  // triangular: rows h = a sqrt(3)/2 apart, odd rows shifted by a/2
  o.lattice = generate::Lattice::hexagonal;
  const double h = a * std::sqrt(3.0) / 2, c = a * std::sqrt(2.0 / 3.0);
  const std::size_t rows = fl((Ly - a) / h) + 1;
  const std::size_t layer_a = (rows + 1) / 2 * fl(Lx / a) + rows / 2 * fl(Lx / a - 0.5);
  const auto tri = generate::fill(box2, generate::Constant{r}, o);
  CHECK(tri.particles.size() == layer_a);
  CHECK(no_overlap(tri));
  // hexagonal close packing ABAB: B layers shifted by (a/2, h/3)
  const std::size_t rows_b = fl((Ly - a - h / 3) / h) + 1;
  const std::size_t layer_b = (rows_b + 1) / 2 * fl(Lx / a - 0.5) + rows_b / 2 * fl(Lx / a - 1);
  const std::size_t layers = fl((Lz - a) / c) + 1;
  const auto hcp = generate::fill(box3, generate::Constant{r}, o);
  CHECK(hcp.particles.size() == (layers + 1) / 2 * layer_a + layers / 2 * layer_b);
  CHECK(no_overlap(hcp));
  CHECK(all_inside(box3, hcp));
  // the closest pairs of the hcp lattice are a apart (12 neighbours inside)
  CHECK(worst_overlap(hcp) == doctest::Approx(-gap / r).epsilon(1e-9));
  // a count takes the first sites; a fraction stops at it
  o.count = 10;
  CHECK(generate::fill(box3, generate::Uniform{0.03, 0.05}, o).particles.size() == 10);
  o.count = 0;
  o.solid_fraction = 0.2;
  const auto part = generate::fill(box3, generate::Constant{r}, o);
  CHECK(std::abs(part.solid_fraction - 0.2) <= volume_of<3>(r) / (Lx * Ly * Lz));
  o.solid_fraction = 0.6; // more than the lattice holds
  CHECK(has(error_of([&] { generate::fill(box3, generate::Constant{r}, o); }),
            {"placed", "lattice sites"}));
}

TEST_CASE("generate: an unreachable fraction reports how far it got") {
  const regions::Box<3> box{Vec3::Zero(), Vec3(0.5, 0.5, 0.5)};
  generate::Options o{.solid_fraction = 0.7, .max_failures = 2000};
  const std::string msg = error_of([&] { generate::fill(box, generate::Constant{0.025}, o); });
  CHECK(has(msg, {"generate::fill (Box): placed ", " particles, solid fraction ", " of 0.7, after ",
                  " attempts", "max_failures = 2000"}));
  o.partial = true;
  const auto res = generate::fill(box, generate::Constant{0.025}, o);
  CHECK_FALSE(res.complete);
  CHECK(res.solid_fraction > 0.25);
  CHECK(res.solid_fraction < 0.4);
  CHECK(res.particles.size() < res.target_count);
  CHECK(no_overlap(res));
  MESSAGE("random sequential addition stopped at solid fraction " << res.solid_fraction);
}

TEST_CASE("generate: radius growth reaches a dense packing without overlaps") {
  const regions::Box<3> box{Vec3::Zero(), Vec3(1, 1, 1)};
  const generate::Options o{.solid_fraction = 0.62, .mode = generate::Mode::grow, .partial = true};
  const auto res = generate::fill(box, generate::Constant{0.04}, o);
  MESSAGE("growth: " << res.particles.size() << " spheres, solid fraction " << res.solid_fraction
                     << ", radius factor " << res.radius_scale << ", " << res.sweeps << " sweeps");
  CHECK(res.solid_fraction >= 0.55);
  CHECK(worst_overlap(res) <= 1e-6); // relative to the radius
  CHECK(no_overlap(res));
  CHECK(all_inside(box, res));
  // a reachable target is met exactly, with the drawn radii (factor 1)
  const auto ok = generate::fill(box, generate::Uniform{0.03, 0.05},
                                 {.solid_fraction = 0.45, .mode = generate::Mode::grow});
  CHECK(ok.complete);
  CHECK(ok.radius_scale == 1.0);
  CHECK(std::abs(ok.solid_fraction - 0.45) <= volume_of<3>(0.05));
  CHECK(no_overlap(ok));
  CHECK(all_inside(box, ok));
  // and in a circle in 2D; generate::grow on a given packing
  const regions::Ball<2> circle{Vec2::Zero(), 0.3};
  const auto start = generate::fill(circle, generate::Constant{0.01}, {.solid_fraction = 0.4});
  const auto grown = generate::grow(circle, start, 0.7);
  CHECK(grown.complete);
  CHECK(grown.solid_fraction == doctest::Approx(0.7).epsilon(1e-9));
  CHECK(no_overlap(grown));
  CHECK(all_inside(circle, grown));
  // without partial, a jammed growth throws with the fraction reached
  CHECK(has(error_of([&] {
              generate::fill(box, generate::Constant{0.04},
                             {.solid_fraction = 0.7, .mode = generate::Mode::grow});
            }),
            {"grown to solid fraction", "jammed"}));
}

TEST_CASE("generate: add_to adds the particles to a simulation") {
  using Contact = Interaction<normal::Hertz<>, tangent::None>;
  Simulation<Sphere, search::CellList, Contact> sim;
  const auto glass = sim.add_material(
      {.name = "glass", .density = 2500, .young = 1e7, .poisson = 0.25, .restitution = 0.5});
  const auto res = generate::fill(regions::Box<3>{Vec3::Zero(), Vec3(0.02, 0.02, 0.02)},
                                  generate::Constant{1e-3}, {.material = glass, .count = 50});
  const auto ids = generate::add_to(sim, res);
  CHECK(ids.size() == 50);
  CHECK(sim.particles().size() == 50);
}

TEST_CASE("generate: bad parameters are refused naming them") {
  const regions::Box<3> box{Vec3::Zero(), Vec3(1, 1, 1)};
  const generate::Options o{.solid_fraction = 0.2};
  auto msg = [&](const generate::Distribution& d, const generate::Options& op) {
    return error_of([&] { generate::fill(box, d, op); });
  };
  CHECK(has(msg(generate::Constant{-1e-3}, o),
            {"generate::Constant", "radius = -0.001", "(0, inf)"}));
  CHECK(has(msg(generate::Constant{NAN}, o), {"generate::Constant", "radius = nan"}));
  CHECK(has(msg(generate::Uniform{2e-3, 1e-3}, o),
            {"generate::Uniform", "max = 0.001", "[min, inf)"}));
  CHECK(has(msg(generate::Normal{1e-3, 1e-4, 0, 0}, o), {"generate::Normal", "min = 0"}));
  CHECK(has(msg(generate::Normal{1e-3, 1e-4, 2e-3, 1e-3}, o), {"generate::Normal", "max = 0.001"}));
  CHECK(has(msg(generate::Normal{1e-3, 0, 5e-4, 2e-3}, o), {"generate::Normal", "std = 0"}));
  CHECK(has(msg(generate::Normal{1e-3, 1e-5, 5e-3, 6e-3}, o), {"probability of [min, max]"}));
  CHECK(has(msg(generate::LogNormal{1e-3, -0.2, 5e-4, 2e-3}, o),
            {"generate::LogNormal", "sigma = -0.2"}));
  CHECK(has(msg(generate::Discrete{{1e-3, 2e-3}, {0.5, 0.4}}, o),
            {"generate::Discrete", "sum of the fractions = 0.9", "[1 - 1e-9, 1 + 1e-9]"}));
  CHECK(has(msg(generate::Discrete{{1e-3, 2e-3}, {0.5}}, o), {"number of fractions = 1"}));
  CHECK(has(msg(generate::Discrete{{1e-3, 0}, {0.5, 0.5}}, o), {"radius 1 = 0"}));
  CHECK(has(msg(generate::Discrete{{1e-3, 2e-3}, {1.5, -0.5}}, o), {"fraction 0 = 1.5"}));
  const generate::Constant c{0.01};
  CHECK(has(msg(c, {.solid_fraction = 1.2}),
            {"generate::fill (Box)", "solid_fraction = 1.2", "(0, 1)"}));
  CHECK(has(msg(c, {.solid_fraction = -0.1}), {"solid_fraction = -0.1"}));
  CHECK(has(msg(c, {.count = 5, .solid_fraction = 0.1}), {"both given"}));
  CHECK(has(msg(c, {}), {"count = 0 and solid_fraction = 0"}));
  CHECK(has(msg(c, {.count = 5, .mode = generate::Mode::lattice, .gap = -1}), {"gap = -1"}));
  CHECK(has(msg(c, {.count = 5, .max_failures = 0}), {"max_failures = 0"}));
  CHECK(
      has(msg(c, {.count = 5, .growth = {.tolerance = 0}}), {"generate::Growth", "tolerance = 0"}));
  CHECK(has(error_of([&] {
              generate::fill(regions::Box<3>{Vec3::Zero(), Vec3(1, -1, 1)}, c, o);
            }),
            {"(Box)", "hi component = -1"}));
  CHECK(has(error_of([&] {
              generate::fill(generate::Cylinder{Vec3::Zero(), Vec3(0, 0, 1), 0}, c, o);
            }),
            {"(Cylinder)", "radius = 0"}));
  CHECK(has(error_of([&] {
              generate::fill(generate::Cylinder{Vec3::Zero(), Vec3::Zero(), 1}, c, o);
            }),
            {"(Cylinder)", "length |b - a| = 0"}));
  CHECK(has(error_of([&] {
              generate::fill(regions::Polygon{{Vec2(0, 0), Vec2(1, 0)}}, c, o);
            }),
            {"(Polygon)", "vertices = 2"}));
  auto open = test::box(Vec3::Zero(), Vec3(1, 1, 1));
  open.triangles.pop_back();
  CHECK(has(error_of([&] { generate::ClosedMesh m(open, "lid"); }),
            {"generate::ClosedMesh 'lid'", "edge (", "used by 1 triangle(s)", "closed"}));
  auto flipped = test::box(Vec3::Zero(), Vec3(1, 1, 1));
  std::swap(flipped.triangles[0][1], flipped.triangles[0][2]);
  CHECK(has(error_of([&] { generate::ClosedMesh m(flipped); }), {"in the same direction"}));
  // a particle that cannot fit at all
  CHECK(has(msg(generate::Constant{0.6}, {.count = 1}), {"placed 0 of 1"}));
}
