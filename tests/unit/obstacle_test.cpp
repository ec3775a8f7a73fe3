// Obstacles: triangle meshes that move rigidly about a reference point. The mesh features (every
// contact of a sphere with the mesh reported once, by one triangle), the motion of the pose,
// input errors, checkpoints and heat conduction from a hot obstacle.
//
// The contact checks use the defining property of a contact with a surface: a local minimum of
// the distance from the sphere centre to the mesh. For random points around each mesh, and
// points near its vertices and edges:
// - the nearest point of the mesh is always reported (no gap between the regions of the faces,
//   edges and vertices): the smallest reported distance is the mesh's, to 1e-12;
// - every report is the nearest point of the triangle that reports it, to 1e-12, and a local
//   minimum: no triangle through the contact point has a nearer point (no tilted edge contact of
//   a neighbour);
// - no two reports are the same contact (no double force on a shared edge or vertex);
// - flat meshes, and convex ones seen from outside, give exactly one report; a box seen from
//   inside gives one per side.

#include "../approx.hpp"
#include "../errors.hpp"
#include "../support/materials.hpp"
#include "../support/meshes.hpp"
#include <doctest/doctest.h>
#include <grain/grain.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <numbers>
#include <random>
#include <sstream>
#include <string>
#include <vector>

using namespace grain;

namespace {

using Contact = Interaction<normal::Hertz<>, tangent::None>;
using Sim = Simulation<Sphere, search::AllPairs, Contact>;

using grain::test::box;
using grain::test::material; // restitution 0.7 in all cases here
using grain::test::moved;
using grain::test::square2;
using grain::test::square8;

/// A height field over [0, 1]^2: n x n cells with random heights in [-0.1, 0.1] (convex,
/// concave and saddle vertices and folds), alternating diagonals.
walls::TriangleMesh terrain(int n, unsigned seed) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> h(-0.1, 0.1);
  walls::TriangleMesh m;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i)
      m.vertices.push_back(Vec3(double(i) / n, double(j) / n, h(gen)));
  auto v = [&](int i, int j) { return static_cast<std::uint32_t>(i + (n + 1) * j); };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      if ((i + j) % 2 == 0) {
        m.triangles.push_back({v(i, j), v(i + 1, j), v(i + 1, j + 1)});
        m.triangles.push_back({v(i, j), v(i + 1, j + 1), v(i, j + 1)});
      } else {
        m.triangles.push_back({v(i, j), v(i + 1, j), v(i, j + 1)});
        m.triangles.push_back({v(i + 1, j), v(i + 1, j + 1), v(i, j + 1)});
      }
    }
  return m;
}
Eigen::Matrix3d some_rotation() {
  return Eigen::AngleAxisd(0.7, Vec3(1, -2, 0.5).normalized()).toRotationMatrix();
}

/// A simulation with only the obstacle, to query its walls.
struct Probe {
  Sim sim;
  Obstacle ob;
  explicit Probe(const walls::TriangleMesh& m, const Vec3& reference = Vec3(0.3, 0.2, 0.1)) {
    const auto k = sim.add_material(material(0.7));
    ob = add_obstacle(sim, m, {.name = "probe", .material = k, .reference_point = reference});
  }
};

/// Reports of the obstacle's triangles for the point x: (wall, proximity) with finite distance.
std::vector<std::pair<std::uint32_t, WallProximity<3>>> reports(const Probe& p, const Vec3& x) {
  std::vector<std::pair<std::uint32_t, WallProximity<3>>> out;
  for (std::uint32_t k = 0; k < p.ob.count; ++k) {
    const auto w = p.ob.wall(k);
    const auto prox = p.sim.walls()[w].proximity(x);
    if (std::isfinite(prox.distance)) out.push_back({w, prox});
  }
  return out;
}

/// Outcome of the contact checks over many points.
struct Tally {
  long points = 0;
  long gaps = 0;       ///< points whose nearest mesh point was not reported
  long strangers = 0;  ///< reports that are not their triangle's nearest point or no minimum
  long duplicates = 0; ///< pairs of reports of the same contact
  long miscounted = 0; ///< points with another number of reports than expected
  double max_error =
      0;             ///< largest deviation (distance / scale, normal scaled to 1e-12 at its bound)
  std::string first; ///< the first failing point, described
};

/// Checks the reports for x (see the file comment) of a sphere of the given radius (reports at
/// a distance >= radius do not count); `expected` < 0: any number of reports, otherwise the
/// number if the mesh is nearer than the radius (0 if not). Normals are compared within
/// 1e-12 + 1e-14 scale / distance: near the surface a normal (q - x)/|q - x| has the round-off of
/// the coordinates divided by the distance.
void check_point(const Probe& p, const Vec3& x, double scale, long expected, Tally& t,
                 double radius = std::numeric_limits<double>::infinity()) {
  ++t.points;
  auto r = reports(p, x);
  std::erase_if(r, [&](const auto& e) { return !(e.second.distance < radius); });
  double nearest = std::numeric_limits<double>::infinity();
  for (std::uint32_t k = 0; k < p.ob.count; ++k)
    nearest = std::min(nearest, p.sim.walls()[p.ob.wall(k)].nearest(x).distance);
  double reported = std::numeric_limits<double>::infinity();
  for (const auto& [w, prox] : r) {
    const auto own = p.sim.walls()[w].nearest(x);
    const double dd = std::abs(prox.distance - own.distance) / scale;
    const double dn = (prox.normal - own.normal).norm();
    const double tol_n = 1e-12 + 1e-14 * scale / own.distance;
    t.max_error = std::max({t.max_error, dd, dn * 1e-12 / tol_n});
    if (dd > 1e-12 || dn > tol_n) ++t.strangers;
    reported = std::min(reported, prox.distance);
    // a contact is a local minimum of the distance: no triangle through its point is nearer
    const Vec3 q = x + prox.distance * prox.normal;
    for (std::uint32_t k = 0; k < p.ob.count; ++k) {
      const auto& wk = p.sim.walls()[p.ob.wall(k)];
      if (wk.nearest(q).distance < 1e-13 * scale + 1e-9 * prox.distance &&
          wk.nearest(x).distance < prox.distance - 1e-13 * scale - 1e-9 * prox.distance)
        ++t.strangers;
    }
  }
  if (nearest < radius && !(std::abs(reported - nearest) <= 1e-12 * scale)) ++t.gaps;
  for (std::size_t a = 0; a < r.size(); ++a)
    for (std::size_t b = a + 1; b < r.size(); ++b) {
      const Vec3 pa = x + r[a].second.distance * r[a].second.normal;
      const Vec3 pb = x + r[b].second.distance * r[b].second.normal;
      if ((pa - pb).norm() < 1e-9 * scale &&
          (r[a].second.normal - r[b].second.normal).norm() < 1e-6)
        ++t.duplicates;
    }
  if (expected >= 0 && static_cast<long>(r.size()) != (nearest < radius ? expected : 0))
    ++t.miscounted;
  if (t.first.empty() && t.gaps + t.strangers + t.duplicates + t.miscounted > 0) {
    std::ostringstream o;
    o.precision(17);
    o << "x = (" << x.transpose() << "), nearest " << nearest << ", reports:";
    for (const auto& [w, prox] : r)
      o << " [wall " << w << ": " << prox.distance << ", (" << prox.normal.transpose() << ")]";
    t.first = o.str();
  }
}

void require_clean(const Tally& t) {
  INFO("points ", t.points, ", largest deviation ", t.max_error, "; first failure: ", t.first);
  CHECK(t.points > 0);
  CHECK(t.gaps == 0);
  CHECK(t.strangers == 0);
  CHECK(t.duplicates == 0);
  CHECK(t.miscounted == 0);
}

/// Random points in the box [lo, hi].
std::vector<Vec3> random_points(const Vec3& lo, const Vec3& hi, int n, unsigned seed) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Vec3> out;
  for (int k = 0; k < n; ++k)
    out.push_back(lo + Vec3(u(gen), u(gen), u(gen)).cwiseProduct(hi - lo));
  return out;
}

/// Points near every vertex and edge midpoint of a mesh: offsets of 0.05, 1e-3 and 1e-6 in random
/// directions (where the regions of faces, edges and vertices meet).
std::vector<Vec3> near_features(const walls::TriangleMesh& m, unsigned seed) {
  std::mt19937 gen(seed);
  std::normal_distribution<double> u(0.0, 1.0);
  std::vector<Vec3> centres = m.vertices;
  for (const auto& t : m.triangles)
    for (int k = 0; k < 3; ++k)
      centres.push_back(0.5 * (m.vertices[t[k]] + m.vertices[t[(k + 1) % 3]]));
  std::vector<Vec3> out;
  for (const auto& c : centres)
    for (double size : {0.05, 1e-3, 1e-6})
      for (int k = 0; k < 8; ++k)
        out.push_back(c + size * Vec3(u(gen), u(gen), u(gen)).normalized());
  return out;
}

/// Points above and below the unit square on its special places: the diagonal(s), the shared
/// vertices and edges, the boundary (sides, corners, side midpoints) and just next to them.
std::vector<Vec3> special_points() {
  std::vector<Vec3> out;
  const double near = 1e-9;
  for (double h : {0.05, -0.05, 0.3})
    for (double x : {0.0, 0.25, 0.5, 0.5 + near, 0.5 - near, 0.75, 1.0, -0.2, 1.2})
      for (double y : {0.0, 0.25, 0.5, 0.5 + near, 0.75, 1.0, -0.2, 1.2})
        out.push_back(Vec3(x, y, h));
  for (double h : {0.05, -0.05})
    for (double t : {0.1, 0.3, 0.5, 0.9}) {
      out.push_back(Vec3(t, t, h));         // on the diagonal
      out.push_back(Vec3(t + near, t, h));  // next to it
      out.push_back(Vec3(t, t + 1e-15, h)); // at round-off distance
      out.push_back(Vec3(t, 1.0 - t, h));   // the other diagonal of square8
    }
  return out;
}

} // namespace

TEST_CASE("obstacle mesh features: edges, vertices and their owners") {
  SUBCASE("a square in two triangles") {
    const auto f = walls::MeshFeatures::build(square2(), Vec3::Zero(), "Obstacle 'square'");
    REQUIRE(f->edge_count() == 5);
    int boundary = 0, flat = 0;
    for (std::uint32_t e = 0; e < 5; ++e) {
      const auto kind = f->edge_kind(e);
      boundary += kind == walls::MeshFeatures::EdgeKind::boundary;
      flat += kind == walls::MeshFeatures::EdgeKind::flat;
      const auto v = f->edge_vertices(e);
      if (v[0] == 0 && v[1] == 2) {
        CHECK(kind == walls::MeshFeatures::EdgeKind::flat);
        CHECK(f->edge_faces(e) == std::vector<std::uint32_t>{0, 1});
        CHECK(f->edge_owner(e) == 0);
      }
    }
    CHECK(boundary == 4);
    CHECK(flat == 1);
    // the corners are convex from both sides: margin = distance from 0 to the hull of the edge
    // directions, 1/sqrt(2) for two perpendicular edges
    for (std::uint32_t v = 0; v < 4; ++v)
      CHECK(f->vertex_margin(v) == test::approx(std::sqrt(0.5)));
    CHECK(f->vertex_owner(3) == 1);
    CHECK(f->vertex_owner(2) == 0);
  }
  SUBCASE("a square in eight triangles: the centre is flat, the side midpoints are straight") {
    const auto f = walls::MeshFeatures::build(square8(), Vec3::Zero(), "Obstacle 'square'");
    CHECK(f->edge_count() == 16);
    CHECK(std::abs(f->vertex_margin(4)) < 1e-15);
    for (std::uint32_t v : {1u, 3u, 5u, 7u})
      CHECK(std::abs(f->vertex_margin(v)) < 1e-15);
    for (std::uint32_t v : {0u, 2u, 6u, 8u})
      CHECK(f->vertex_margin(v) > 0.5);
  }
  SUBCASE("a box: convex folds and corners, flat diagonals") {
    const auto f = walls::MeshFeatures::build(box(Vec3(0, 0, 0), Vec3(1, 2, 3)), Vec3::Zero(),
                                              "Obstacle 'box'");
    REQUIRE(f->edge_count() == 18);
    int folds = 0, flat = 0;
    for (std::uint32_t e = 0; e < 18; ++e) {
      folds += f->edge_kind(e) == walls::MeshFeatures::EdgeKind::fold;
      flat += f->edge_kind(e) == walls::MeshFeatures::EdgeKind::flat;
      const auto faces = f->edge_faces(e);
      CHECK(f->edge_owner(e) == *std::min_element(faces.begin(), faces.end()));
    }
    CHECK(folds == 12);
    CHECK(flat == 6);
    for (std::uint32_t v = 0; v < 8; ++v)
      CHECK(f->vertex_margin(v) > 0.5);
  }
  SUBCASE("a saddle vertex has no cone") {
    // four triangles around the origin, their outer corners alternately up and down
    walls::TriangleMesh m{
        {Vec3(0, 0, 0), Vec3(1, 0, 0.5), Vec3(0, 1, -0.5), Vec3(-1, 0, 0.5), Vec3(0, -1, -0.5)},
        {{0, 1, 2}, {0, 2, 3}, {0, 3, 4}, {0, 4, 1}}};
    const auto f = walls::MeshFeatures::build(m, Vec3::Zero(), "Obstacle 'saddle'");
    CHECK(f->vertex_margin(0) < -0.1);
  }
}

TEST_CASE("obstacle of one triangle: the same contacts as a lone triangle") {
  const walls::Triangle lone{Vec3(0.1, 0.2, 0.3), Vec3(1.3, 0.1, 0.5), Vec3(0.4, 0.9, -0.2)};
  Probe p(walls::triangle_mesh(std::vector<walls::Triangle>{lone}));
  Wall<3> w;
  w.geometry = lone;
  double worst = 0.0;
  long reported = 0;
  for (const auto& x : random_points(Vec3(-0.5, -0.5, -0.7), Vec3(1.8, 1.5, 1.2), 4000, 7)) {
    const auto a = p.sim.walls()[p.ob.wall(0)].proximity(x);
    const auto b = w.proximity(x);
    reported += std::isfinite(a.distance);
    worst = std::max(
        {worst, std::abs(a.distance - b.distance) / b.distance, (a.normal - b.normal).norm()});
  }
  INFO("largest relative deviation ", worst);
  CHECK(reported == 4000);
  CHECK(worst < 1e-12);
}

TEST_CASE("obstacle contacts: flat squares report exactly one contact, that of the plane") {
  const Eigen::Matrix3d R = some_rotation();
  const Vec3 shift(0.4, -1.1, 2.0);
  for (const bool eight : {false, true})
    for (const bool turned : {false, true}) {
      CAPTURE(eight);
      CAPTURE(turned);
      const auto base = eight ? square8() : square2();
      const Eigen::Matrix3d Q = turned ? R : Eigen::Matrix3d::Identity();
      const Vec3 s = turned ? shift : Vec3::Zero();
      Probe p(moved(base, Q, s), turned ? Vec3(0.5, 0.5, 2.0) : Vec3(0.2, 0.7, 0.0));
      Tally t;
      std::vector<Vec3> pts = special_points();
      for (const auto& x : random_points(Vec3(-0.4, -0.4, -0.3), Vec3(1.4, 1.4, 0.3), 3000, 11))
        pts.push_back(x);
      for (const auto& x : near_features(base, 3))
        pts.push_back(x);
      for (const auto& x : pts)
        check_point(p, Q * x + s, 1.0, 1, t);
      require_clean(t);

      // over the square the one contact is the plane's: distance |h|, normal -+n
      const Vec3 n = Q * Vec3::UnitZ();
      double worst = 0.0;
      for (const auto& x : pts) {
        if (x.x() < 0 || x.x() > 1 || x.y() < 0 || x.y() > 1) continue;
        const auto r = reports(p, Q * x + s);
        REQUIRE(r.size() == 1);
        const Vec3 plane_normal = x.z() > 0 ? Vec3(-n) : n;
        worst = std::max({worst, std::abs(r[0].second.distance - std::abs(x.z())),
                          (r[0].second.normal - plane_normal).norm()});
      }
      CHECK(worst < 1e-14);
    }
}

TEST_CASE("obstacle contacts: a box seen from outside and from inside") {
  const Eigen::Matrix3d R = some_rotation();
  const Vec3 lo(0, 0, 0), hi(1, 0.6, 0.4);
  for (const bool turned : {false, true}) {
    CAPTURE(turned);
    const Eigen::Matrix3d Q = turned ? R : Eigen::Matrix3d::Identity();
    const Vec3 s = turned ? Vec3(-0.3, 0.2, 1.0) : Vec3::Zero();
    Probe p(moved(box(lo, hi), Q, s));
    Tally outside, inside;
    std::vector<Vec3> out_pts, in_pts;
    for (const auto& x : random_points(Vec3(-0.3, -0.3, -0.3), Vec3(1.3, 0.9, 0.7), 4000, 5)) {
      const bool in = (x.array() > lo.array()).all() && (x.array() < hi.array()).all();
      (in ? in_pts : out_pts).push_back(x);
    }
    for (const auto& x : near_features(box(lo, hi), 4)) {
      const bool in = (x.array() > lo.array()).all() && (x.array() < hi.array()).all();
      (in ? in_pts : out_pts).push_back(x);
    }
    // exactly over edges and corners, along their bisectors and on the end planes
    for (double a : {0.0, 0.5, 1.0})
      for (double d : {0.05, 0.2}) {
        out_pts.push_back(Vec3(a, -d, -d));
        out_pts.push_back(Vec3(-d, a * 0.6, -d));
        out_pts.push_back(Vec3(a, 0.3, -d));
        out_pts.push_back(Vec3(-d, -d, a * 0.4));
        out_pts.push_back(Vec3(1 + d, 0.6 + d, 0.4 + d));
        out_pts.push_back(Vec3(0.0, -d, 0.2));
      }
    // a sphere smaller than the box (radius 0.25 < 0.4) touches it once from outside
    for (const auto& x : out_pts)
      check_point(p, Q * x + s, 1.0, 1, outside, 0.25);
    for (const auto& x : in_pts)
      check_point(p, Q * x + s, 1.0, 6, inside);
    require_clean(outside);
    require_clean(inside);
  }
}

TEST_CASE("obstacle contacts: a rough terrain has no gaps, no tilted neighbours, no doubles") {
  for (unsigned seed : {1u, 2u, 3u}) {
    CAPTURE(seed);
    Probe p(terrain(6, seed));
    Tally t;
    for (const auto& x : random_points(Vec3(-0.2, -0.2, -0.35), Vec3(1.2, 1.2, 0.35), 4000, seed))
      check_point(p, x, 1.0, -1, t);
    for (const auto& x : near_features(terrain(6, seed), seed))
      check_point(p, x, 1.0, -1, t);
    require_clean(t);
  }
}

TEST_CASE("obstacle contacts: a fold is one edge contact on its convex side, two faces on its "
          "concave side") {
  // a roof: two faces meeting at the ridge x = 0 (z = 0), sloping down to z = -0.5 at x = +-1
  walls::TriangleMesh roof{{Vec3(0, 0, 0), Vec3(0, 1, 0), Vec3(1, 0, -0.5), Vec3(1, 1, -0.5),
                            Vec3(-1, 0, -0.5), Vec3(-1, 1, -0.5)},
                           {{0, 2, 3}, {0, 3, 1}, {0, 1, 5}, {0, 5, 4}}};
  Probe p(roof);
  // above the ridge, inside the wedge of the two face normals: one contact, the ridge's
  auto r = reports(p, Vec3(0.02, 0.5, 0.3));
  REQUIRE(r.size() == 1);
  CHECK(r[0].second.distance == test::approx(std::hypot(0.02, 0.3)));
  CHECK(r[0].second.normal.isApprox(Vec3(-0.02, 0, -0.3).normalized(), 1e-14));
  // above one face: that face only (the ridge of the other face is no contact)
  const Vec3 n = Vec3(0.5, 0, 1).normalized();
  r = reports(p, Vec3(0.3, 0.5, 0.2));
  REQUIRE(r.size() == 1);
  CHECK(r[0].second.normal.isApprox(-n, 1e-14));
  // below the ridge (the concave side): both faces
  r = reports(p, Vec3(0.0, 0.5, -0.1));
  REQUIRE(r.size() == 2);
  CHECK(r[0].second.distance == test::approx(0.1 / std::sqrt(1.25)));
  CHECK(r[1].second.distance == test::approx(0.1 / std::sqrt(1.25)));
}

TEST_CASE("obstacle: corners follow the rotation by the integral of the angular velocity") {
  const auto m = box(Vec3(0, 0, 0), Vec3(0.2, 0.1, 0.05));
  const Vec3 ref(0.3, -0.1, 0.2); // not the centroid
  const double dt = 1e-3;
  const int steps = 2000;
  auto corners_error = [&](const Sim& sim, const Obstacle& ob, const Vec3& centre,
                           const Eigen::Matrix3d& Q) {
    double worst = 0.0;
    for (std::uint32_t k = 0; k < ob.count; ++k) {
      const auto& t = std::get<walls::Triangle>(sim.walls()[ob.wall(k)].geometry);
      const auto& v = m.triangles[k];
      const Vec3 want[3] = {centre + Q * (m.vertices[v[0]] - ref),
                            centre + Q * (m.vertices[v[1]] - ref),
                            centre + Q * (m.vertices[v[2]] - ref)};
      worst =
          std::max({worst, (t.a - want[0]).norm(), (t.b - want[1]).norm(), (t.c - want[2]).norm()});
    }
    return worst;
  };
  auto make = [&](VectorTimeFunction<3> v, VectorTimeFunction<3> w, Obstacle& ob) {
    Sim::Params prm;
    prm.time_step = dt;
    Sim sim(prm);
    const auto k = sim.add_material(material(0.7));
    ob = add_obstacle(sim, m,
                      {.name = "spinner",
                       .material = k,
                       .reference_point = ref,
                       .velocity = std::move(v),
                       .omega = std::move(w)});
    return sim;
  };
  SUBCASE("constant velocities: exact to round-off") {
    const Vec3 v(0.1, -0.2, 0.05), w(2.0, -1.0, 3.0);
    Obstacle ob;
    Sim sim = make(v, w, ob);
    sim.steps(steps);
    const double t = sim.time();
    CHECK(t == test::approx(steps * dt).epsilon(1e-12));
    const Eigen::Matrix3d Q = Eigen::AngleAxisd(w.norm() * t, w.normalized()).toRotationMatrix();
    const double err = corners_error(sim, ob, ref + v * t, Q);
    INFO("corner error ", err, " m after ", steps, " steps");
    CHECK(err < 1e-13);
    CHECK((ob.reference_point(sim) - (ref + v * t)).norm() < 1e-13);
    CHECK(ob.orientation(sim).angularDistance(Eigen::Quaterniond(Q)) < 1e-13);
    // the walls' surface velocity is that of a rigid body: v + w x (p - reference)
    const auto& wall = sim.walls()[ob.wall(3)];
    const Vec3 x = ob.vertex(sim, 5);
    CHECK((wall.velocity_at(x) - (v + w.cross(x - ob.reference_point(sim)))).norm() < 1e-13);
  }
  SUBCASE("angular velocity growing linearly: exact (the midpoint rule integrates it exactly)") {
    const Vec3 axis = Vec3(1, 1, -2).normalized();
    Obstacle ob;
    Sim sim = make(Vec3(Vec3::Zero()),
                   VectorTimeFunction<3>::along(axis, TimeFunction::linear(0.5, 3.0)), ob);
    sim.steps(steps);
    const double t = sim.time();
    const double angle = 0.5 * t + 1.5 * t * t;
    const Eigen::Matrix3d Q = Eigen::AngleAxisd(angle, axis).toRotationMatrix();
    const double err = corners_error(sim, ob, ref, Q);
    INFO("corner error ", err, " m");
    CHECK(err < 1e-13);
  }
  SUBCASE("oscillating angular velocity: the midpoint rule's error") {
    // w(t) = A sin(c t), c = 2 pi / P, about a fixed axis: angle(t) = A/c (1 - cos(c t)). The
    // rotation angle of the steps is the midpoint rule of that integral, which errs by
    // dt^2/24 (w'(0) - w'(t)) + O(dt^4) = dt^2/24 A c (1 - cos(c t)) + O(dt^4), and by at most
    // t dt^2 max|w''| / 24 = t dt^2 A c^2 / 24 (t = 2 s is 2.86 periods: no cancellation)
    const Vec3 axis = Vec3(0, 1, 0);
    const double A = 4.0, P = 0.7;
    Obstacle ob;
    Sim sim = make(Vec3(0, 0, 0.3),
                   VectorTimeFunction<3>::along(axis, TimeFunction::oscillatory(0.0, A, P)), ob);
    sim.steps(steps);
    const double t = sim.time();
    const double c = 2 * std::numbers::pi / P;
    const double angle = A / c * (1 - std::cos(c * t));
    const double predicted = dt * dt / 24 * A * c * (1 - std::cos(c * t));
    const double bound = t * dt * dt * A * c * c / 24;
    const Eigen::Quaterniond q = ob.orientation(sim);
    const double error = 2 * std::atan2(q.vec().dot(axis), q.w()) - angle;
    INFO("angle error ", error, " rad, predicted ", predicted, " rad, bound ", bound, " rad");
    CHECK(std::abs(error - predicted) < 1e-3 * predicted);
    CHECK(std::abs(error) < bound);
    // the corners follow the orientation: the farthest is 0.43 m from the reference point
    const Eigen::Matrix3d Q = Eigen::AngleAxisd(angle, axis).toRotationMatrix();
    CHECK(corners_error(sim, ob, ref + Vec3(0, 0, 0.3) * t, Q) < 0.43 * std::abs(error) * 1.001);
  }
}

TEST_CASE("obstacle input errors name the obstacle, the value and the valid range") {
  Sim sim;
  const auto k = sim.add_material(material(0.7));
  const ObstacleOptions o{.name = "hopper", .material = k};
  using test::error_of;
  using test::has;
  auto message = [&](walls::TriangleMesh m, ObstacleOptions opt) {
    return error_of([&] { add_obstacle(sim, m, opt); });
  };
  std::string e = message({}, o);
  CHECK(has(e, "Obstacle 'hopper'"));
  CHECK(has(e, "number of triangles = 0 is invalid; valid range: [1, inf)"));

  auto m = square2();
  m.triangles[1][2] = 7;
  e = message(m, o);
  CHECK(has(e, "Obstacle 'hopper': triangle 1 vertex index 2 = 7 is invalid; valid range: [0, 4)"));

  m = square2();
  m.vertices[1] = Vec3(1, 1, 0); // corners (0, 0, 0), (1, 1, 0), (2, 2, 0) of triangle 0
  m.vertices[2] = Vec3(2, 2, 0);
  e = message(m, o);
  CHECK(has(e, "Obstacle 'hopper': triangle 0 area = 0 is invalid"));
  CHECK(has(e, "are collinear"));

  m = square2();
  m.triangles[0] = {0, 1, 1};
  e = message(m, o);
  CHECK(has(e, "Obstacle 'hopper': triangle 0 vertex indices = 0, 1, 1 is invalid; valid range: "
               "three different vertices"));

  m = square2();
  m.vertices[3].y() = std::numeric_limits<double>::quiet_NaN();
  e = message(m, o);
  CHECK(has(e, "Obstacle 'hopper': vertex 3 = (0, nan, 0) is invalid; valid range: finite"));

  // the same corner in a list of triangles: a vertex of its own, rejected with its coordinates
  // (not sorted with the others: NaN has no order)
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::vector<walls::Triangle> listed{{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, nan, 0)},
                                            {Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0)}};
  e = error_of([&] { add_obstacle(sim, listed, o); });
  CHECK(has(e, "Obstacle 'hopper': vertex 2 = (0, nan, 0) is invalid; valid range: finite"));

  ObstacleOptions bad = o;
  bad.material = 3;
  e = message(square2(), bad);
  CHECK(has(e, "Obstacle 'hopper': material = 3 is invalid; valid range: [0, 1)"));

  bad = o;
  bad.reference_point.x() = std::numeric_limits<double>::infinity();
  e = message(square2(), bad);
  CHECK(has(e, "Obstacle 'hopper': reference point = (inf, 0, 0) is invalid"));

  // per-triangle materials: one per triangle, each known
  bad = o;
  bad.materials = {k, k, k};
  e = message(square2(), bad);
  CHECK(has(e, "Obstacle 'hopper': number of materials = 3 is invalid; valid range: 0 (every "
               "triangle uses material) or 2 (one per triangle)"));
  bad.materials = {k};
  CHECK(has(message(square2(), bad), "number of materials = 1 is invalid"));
  bad.materials = {k, 5};
  e = message(square2(), bad);
  CHECK(has(e, "Obstacle 'hopper': triangle 1 material = 5 is invalid; valid range: [0, 1) "
               "(indices returned by add_material)"));

  bad = o;
  bad.flat_angle = 2.0;
  e = message(square2(), bad);
  CHECK(has(e, "Obstacle 'hopper': flat_angle = 2 is invalid; valid range: [0, pi/2) rad"));

  // nothing was added by the failed calls
  CHECK(sim.walls().empty());

  // per-triangle materials: triangle k (wall first_wall + k) gets materials[k]
  const auto k2 = sim.add_material(material(0.7));
  const auto ob =
      add_obstacle(sim, square2(), {.name = "two", .material = k, .materials = {k2, k}});
  CHECK(sim.walls()[ob.wall(0)].options.material == k2);
  CHECK(sim.walls()[ob.wall(1)].options.material == k);
}

TEST_CASE("obstacle from a list of triangles: equal corners become shared vertices") {
  const std::vector<walls::Triangle> tris = {{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0)},
                                             {Vec3(0, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0)}};
  const auto m = walls::triangle_mesh(tris);
  CHECK(m.vertices.size() == 4);
  REQUIRE(m.triangles.size() == 2);
  CHECK(m.triangles[1][0] == 0);
  CHECK(m.triangles[1][1] == 2);
  Sim sim;
  const auto k = sim.add_material(material(0.7));
  const auto ob = add_obstacle(sim, tris, {.name = "sheet", .material = k});
  CHECK(ob.count == 2);
  CHECK(ob.walls() == std::vector<std::uint32_t>{0, 1});
  CHECK(sim.walls()[1].options.name == "sheet[1]");
  // the shared diagonal: one contact
  int n = 0;
  for (auto w : ob.walls())
    n += std::isfinite(sim.walls()[w].proximity(Vec3(0.4, 0.4, 0.1)).distance);
  CHECK(n == 1);
}

TEST_CASE("obstacle: a checkpoint keeps the pose and the mesh features") {
  auto make = [] {
    Sim::Params prm;
    prm.time_step = 1e-4;
    prm.gravity = Vec3(0, 0, -9.81);
    Sim sim(prm);
    const auto k = sim.add_material(material(0.7));
    add_obstacle(sim, square8(),
                 {.name = "tray",
                  .material = k,
                  .reference_point = Vec3(0.5, 0.5, 0),
                  .velocity = Vec3(0.01, 0, 0.02),
                  .omega = Vec3(0, 0.3, 0.5)});
    for (int i = 0; i < 3; ++i)
      sim.add_particle(
          {.position = Vec3(0.25 + 0.25 * i, 0.5, 0.06), .radius = 0.05, .material = k});
    return sim;
  };
  const auto dir = std::filesystem::temp_directory_path() / "grain_obstacle_test";
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "tray.ckpt").string();
  Sim whole = make();
  whole.steps(400);
  Sim first = make();
  first.steps(150);
  io::save_checkpoint(first, path);
  Sim resumed = make();
  io::load_checkpoint(resumed, path);
  resumed.steps(250);
  REQUIRE(whole.size() == resumed.size());
  bool same = true;
  for (std::size_t i = 0; i < whole.size(); ++i)
    same = same && whole.particles().position[i] == resumed.particles().position[i] &&
           whole.particles().velocity[i] == resumed.particles().velocity[i];
  for (std::size_t w = 0; w < whole.walls().size(); ++w) {
    const auto& a = std::get<walls::Triangle>(whole.walls()[w].geometry);
    const auto& b = std::get<walls::Triangle>(resumed.walls()[w].geometry);
    same = same && a.a == b.a && a.b == b.b && a.c == b.c && a.origin == b.origin &&
           a.orientation.coeffs() == b.orientation.coeffs() && b.mesh != nullptr;
  }
  CHECK(same);
  CHECK(whole.contact_counts().second > 0);
}

TEST_CASE("obstacle: a hot obstacle heats a sphere over its shared vertex once, as a plane") {
  // contact conduction (overlap) and conduction through the fluid across a gap, over the vertex
  // that 8 triangles share: the same heat rate as from a hot plane (8 independent triangles
  // would each conduct)
  using Hot =
      Interaction<normal::Hertz<>, tangent::None, rolling::None,
                  conduction::Combined<conduction::BatchelorOBrien, conduction::SurroundingLayer>>;
  using HotSim = Simulation<Sphere, search::AllPairs, Hot>;
  auto heat_rate = [](int floor, double gap) {
    HotSim::Params p;
    p.analysis = Analysis::thermal;
    p.time_step = 1e-3;
    p.fluid.conductivity = 0.026;
    HotSim sim(p);
    const auto k = sim.add_material({.name = "glass",
                                     .density = 2500,
                                     .young = 7e10,
                                     .conductivity = 1.0,
                                     .heat_capacity = 800});
    if (floor == 0)
      sim.add_wall(walls::Plane{Vec3::Zero(), Vec3::UnitZ()},
                   {.material = k, .temperature = 400.0});
    if (floor == 1)
      add_obstacle(sim, square8(), {.name = "hot", .material = k, .temperature = 400.0});
    if (floor == 2)
      for (const auto& t : square8().triangles)
        sim.add_wall(walls::Triangle{square8().vertices[t[0]], square8().vertices[t[1]],
                                     square8().vertices[t[2]]},
                     {.material = k, .temperature = 400.0});
    sim.add_particle({.position = Vec3(0.5, 0.5, 0.01 + gap),
                      .radius = 0.01,
                      .material = k,
                      .temperature = 300});
    sim.step();
    return sim.particles().heat_rate[0];
  };
  for (const double gap : {-1e-5, 1e-4}) {
    CAPTURE(gap);
    const double plane = heat_rate(0, gap), ob = heat_rate(1, gap), lone = heat_rate(2, gap);
    INFO("heat rate ", ob, " W (plane ", plane, " W, independent triangles ", lone, " W)");
    CHECK(plane > 0.0);
    CHECK(ob == test::approx(plane).epsilon(1e-12));
    CHECK(lone > 2.0 * plane);
  }
}
