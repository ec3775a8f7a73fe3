// Rigid bodies: integration against closed forms, mesh mass properties, mesh surfaces and face
// colours, equivalent mass and critical time step, input validation.
#include "../approx.hpp"
#include "../errors.hpp"
#include <algorithm>
#include <array>
#include <cmath>
#include <doctest/doctest.h>
#include <grain/bodies/eqm.hpp>
#include <grain/bodies/mesh.hpp>
#include <grain/bodies/rigid_body.hpp>
#include <grain/particles/storage.hpp>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

using grain::Vec3;
using grain::test::approx;
using Mat3 = Eigen::Matrix3d;
namespace gb = grain::bodies;

namespace {

using grain::test::error_of;
using grain::test::has;

/// max |a_ij - b_ij| / max|b|: a relative matrix distance.
double rel_diff(const Mat3& a, const Mat3& b) {
  return (a - b).cwiseAbs().maxCoeff() / b.cwiseAbs().maxCoeff();
}
double rel_diff(const Vec3& a, const Vec3& b) { return (a - b).norm() / b.norm(); }

const Mat3 some_rotation =
    Eigen::AngleAxisd(0.7, Vec3(1.0, 2.0, 3.0).normalized()).toRotationMatrix();

void no_loads(gb::RigidBodies&) {}

// Unit cube [0,1]^3 shifted by `o`, in VTK hexahedron order.
std::vector<Vec3> cube_nodes(const Vec3& o = Vec3::Zero()) {
  return {o + Vec3(0, 0, 0), o + Vec3(1, 0, 0), o + Vec3(1, 1, 0), o + Vec3(0, 1, 0),
          o + Vec3(0, 0, 1), o + Vec3(1, 0, 1), o + Vec3(1, 1, 1), o + Vec3(0, 1, 1)};
}

// A tetrahedron element on the given nodes, reordered to positive volume.
gb::Element oriented_tet(const std::vector<Vec3>& x, std::size_t a, std::size_t b, std::size_t c,
                         std::size_t d, double rho) {
  if (gb::detail::tet_volume(x[a], x[b], x[c], x[d]) < 0.0) std::swap(b, c);
  return {{a, b, c, d}, rho};
}

} // namespace

// ---------------------------------------------------------------------------------------------
// Integration
// ---------------------------------------------------------------------------------------------

TEST_CASE("bodies: torque-free asymmetric body conserves energy and angular momentum") {
  // Principal moments 1, 2, 3 kg m^2, rotated so that the world inertia is full; omega has
  // components on all three principal axes. h = 1e-3 s, 1e5 steps (t = 100 s, about 16
  // revolutions). The splitting keeps L = Q pi exactly in every sub-step, so L drifts only by
  // round-off (measured 5.7e-12 relative); the kinetic energy error is O(h^2) and bounded
  // (measured max 2.5e-9 relative; 1.0e-8 at h = 2e-3, 2.5e-7 at h = 1e-2).
  gb::RigidBody d;
  d.mass = 2.0;
  d.inertia = some_rotation * Vec3(1.0, 2.0, 3.0).asDiagonal() * some_rotation.transpose();
  d.omega = some_rotation * Vec3(0.3, 1.0, 0.5);
  gb::RigidBodies b;
  const auto i = b.add(d);
  CHECK(rel_diff(gb::world_inertia(b, i), d.inertia) < 1e-14);
  const double e0 = gb::kinetic_energy(b, i);
  const Vec3 l0 = gb::angular_momentum(b, i);
  CHECK(rel_diff(l0, d.inertia * d.omega) < 1e-14);
  double max_de = 0.0, max_dl = 0.0;
  for (int s = 0; s < 100000; ++s) {
    gb::step(b, 1e-3, no_loads);
    max_de = std::max(max_de, std::abs(gb::kinetic_energy(b, i) - e0) / e0);
    max_dl = std::max(max_dl, rel_diff(gb::angular_momentum(b, i), l0));
  }
  MESSAGE("max relative energy error " << max_de << ", angular momentum " << max_dl);
  CHECK(max_de < 1e-8); // 4x the measured O(h^2) error
  CHECK(max_dl < 1e-9); // round-off over 1e5 steps
  CHECK(b.position[i].norm() == 0.0);
}

TEST_CASE("bodies: symmetric top precession converges at second order") {
  // Torque-free symmetric top, J = diag(2, 2, 1) kg m^2 about the reference axes. Closed form:
  // L is constant, the symmetry axis e turns about L at |L|/J_t, and
  // omega = L/J_t + (1/J_s - 1/J_t)(L.e) e. The error of omega at t = 10 s must fall by 4 when
  // h is halved (measured ratios 4.00); the error at h = 0.01 s is 2.9e-5 relative.
  const double jt = 2.0, js = 1.0, t_end = 10.0;
  auto run = [&](double h) {
    gb::RigidBody d;
    d.inertia = Vec3(jt, jt, js).asDiagonal();
    d.omega = Vec3(0.4, 0.1, 2.0);
    gb::RigidBodies b;
    b.add(d);
    const Vec3 l = d.inertia * d.omega;
    const auto n = static_cast<int>(std::lround(t_end / h));
    for (int s = 0; s < n; ++s)
      gb::step(b, h, no_loads);
    const Vec3 e = Eigen::AngleAxisd(l.norm() / jt * t_end, l.normalized()) * Vec3::UnitZ();
    const Vec3 exact = l / jt + (1.0 / js - 1.0 / jt) * l.dot(e) * e;
    return rel_diff(b.omega[0], exact);
  };
  const double e1 = run(0.01), e2 = run(0.005), e3 = run(0.0025);
  MESSAGE("symmetric top errors " << e1 << " " << e2 << " " << e3);
  CHECK(e1 < 1e-4);
  CHECK(e1 / e2 == approx(4.0).epsilon(0.02)); // second order; 2% for the O(h^4) remainder
  CHECK(e2 / e3 == approx(4.0).epsilon(0.02));
}

TEST_CASE("bodies: rotation about the intermediate axis is unstable") {
  // J = (1, 2, 3) kg m^2. Spin 1 rad/s about one principal axis with a 1e-3 rad/s perturbation
  // on the others, h = 1e-3 s for 60 s. About the axes of the smallest and largest moment the
  // spin component stays above 0.999 of its start; about the intermediate axis it reverses
  // (the tennis-racket effect; the component reaches about -1).
  auto min_component = [](int axis) {
    gb::RigidBody d;
    d.inertia = some_rotation * Vec3(1.0, 2.0, 3.0).asDiagonal() * some_rotation.transpose();
    Vec3 w = Vec3::Constant(1e-3);
    w(axis) = 1.0;
    d.omega = some_rotation * w;
    gb::RigidBodies b;
    b.add(d);
    double lo = 1.0;
    for (int s = 0; s < 60000; ++s) {
      gb::step(b, 1e-3, no_loads);
      lo = std::min(
          lo, (some_rotation.transpose() * gb::rotation(b, 0).transpose() * b.omega[0])(axis));
    }
    return lo;
  };
  CHECK(min_component(0) > 0.999);
  CHECK(min_component(2) > 0.999);
  CHECK(min_component(1) < -0.9);
}

TEST_CASE("bodies: constant torque about a principal axis gives omega = T t / J") {
  // J = (1, 2, 3) rotated; a torque T = 0.6 N m along the world direction of principal axis 3,
  // starting from rest, 1000 steps of 1e-3 s. pi stays along axis 3, every sub-rotation leaves
  // it unchanged, so omega = T t / J holds to round-off (tolerance 1e-12 relative).
  gb::RigidBody d;
  d.inertia = some_rotation * Vec3(1.0, 2.0, 3.0).asDiagonal() * some_rotation.transpose();
  gb::RigidBodies b;
  b.add(d);
  const Vec3 axis = some_rotation.col(2);
  const double torque = 0.6, h = 1e-3;
  auto loads = [&](gb::RigidBodies& s) { s.torque[0] += torque * axis; };
  loads(b);
  for (int s = 0; s < 1000; ++s)
    gb::step(b, h, loads);
  const double t = 1000 * h;
  CHECK(rel_diff(b.omega[0], torque * t / 3.0 * axis) < 1e-12);
  // the body has turned by T t^2 / (2 J) about the axis
  const Eigen::AngleAxisd turned(gb::rotation(b, 0)); // Lambda(0) = 1
  CHECK(turned.angle() == approx(torque * t * t / 6.0).epsilon(1e-12));
  CHECK(std::abs(turned.axis().dot(axis)) == approx(1.0).epsilon(1e-12));
}

TEST_CASE("bodies: constant force gives x = x0 + v0 t + F t^2 / (2 m)") {
  // Velocity Verlet is exact for a constant force; 1000 steps of 1e-3 s, tolerance 1e-13
  // relative (round-off accumulated over the steps).
  gb::RigidBody d;
  d.mass = 3.0;
  d.inertia = Vec3(1.0, 2.0, 3.0).asDiagonal();
  d.position = Vec3(1.0, -2.0, 0.5);
  d.velocity = Vec3(0.3, 0.2, -0.1);
  gb::RigidBodies b;
  b.add(d);
  const Vec3 f(1.5, -3.0, 6.0);
  auto loads = [&](gb::RigidBodies& s) { s.force[0] += f; };
  loads(b);
  for (int s = 0; s < 1000; ++s)
    gb::step(b, 1e-3, loads);
  const double t = 1.0;
  CHECK(rel_diff(b.position[0], d.position + d.velocity * t + f * t * t / (2.0 * d.mass)) < 1e-13);
  CHECK(rel_diff(b.velocity[0], d.velocity + f * t / d.mass) < 1e-13);
  CHECK(b.omega[0].norm() == 0.0);
}

TEST_CASE("bodies: frames, points and applied forces") {
  gb::RigidBody d;
  d.inertia = gb::inertia_tensor(2.0, 3.0, 4.0, 0.1, -0.2, 0.3);
  d.rotation = some_rotation;
  d.position = Vec3(1.0, 2.0, 3.0);
  d.velocity = Vec3(0.1, 0.0, 0.0);
  d.omega = Vec3(0.0, 0.0, 2.0);
  gb::RigidBodies b;
  const auto i = b.add(d);
  // Lambda is returned as given and J_world = Lambda J_ref Lambda^T
  CHECK(rel_diff(gb::rotation(b, i), some_rotation) < 1e-14);
  CHECK(rel_diff(gb::world_inertia(b, i), some_rotation * d.inertia * some_rotation.transpose()) <
        1e-14);
  CHECK(rel_diff(Mat3(gb::inverse_world_inertia(b, i) * gb::world_inertia(b, i)),
                 Mat3::Identity()) < 1e-14);
  const Vec3 x(1.5, 2.0, 3.0);
  const Vec3 local = gb::to_local(b, i, x);
  CHECK(rel_diff(local, some_rotation.transpose() * Vec3(0.5, 0.0, 0.0)) < 1e-14);
  CHECK(rel_diff(gb::to_world(b, i, local), x) < 1e-15);
  CHECK(rel_diff(gb::point_velocity(b, i, x), Vec3(0.1, 1.0, 0.0)) < 1e-15);
  gb::apply_force(b, i, Vec3(0.0, 2.0, 0.0), x);
  CHECK(rel_diff(b.force[i], Vec3(0.0, 2.0, 0.0)) == 0.0);
  CHECK(rel_diff(b.torque[i], Vec3(0.0, 0.0, 1.0)) < 1e-15);
  gb::clear_forces(b);
  CHECK(b.force[i].norm() + b.torque[i].norm() == 0.0);
  // A material point keeps its local coordinates while the body moves.
  gb::step(b, 0.01, no_loads);
  CHECK(rel_diff(gb::to_local(b, i, gb::to_world(b, i, local)), local) < 1e-14);
}

TEST_CASE("bodies: sphere conversion") {
  const double r = 0.01, rho = 2500.0;
  const double m = 4.0 / 3.0 * std::numbers::pi * r * r * r * rho;
  const auto s = gb::sphere_body(r, rho, Vec3(1, 2, 3), Vec3(0.5, 0, 0), Vec3(0, 0, 10));
  CHECK(s.mass == approx(m).epsilon(1e-15));
  CHECK(rel_diff(s.inertia, Mat3::Identity() * (0.4 * m * r * r)) < 1e-15);
  CHECK(s.radius == r); // the display radius
  gb::RigidBodies b;
  const auto i = b.add(s);
  CHECK(b.radius[i] == r);
  CHECK(gb::kinetic_energy(b, i) ==
        approx(0.5 * m * 0.25 + 0.5 * 0.4 * m * r * r * 100.0).epsilon(1e-14));

  grain::ParticleArrays<3> p;
  p.id = {7};
  p.position = {Vec3(1, 2, 3)};
  p.velocity = {Vec3(0, 1, 0)};
  p.omega = {Vec3(3, 0, 0)};
  p.orientation = {Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Vec3::UnitZ()))};
  p.mass = {m};
  p.inertia = {0.4 * m * r * r};
  p.radius = {r};
  const auto ps = gb::sphere_body(p, 0);
  CHECK(ps.mass == m);
  CHECK(ps.radius == r);
  CHECK(rel_diff(ps.rotation, Eigen::AngleAxisd(0.3, Vec3::UnitZ()).toRotationMatrix()) < 1e-15);
  CHECK(rel_diff(ps.omega, Vec3(3, 0, 0)) == 0.0);
  const auto j = b.add(ps);
  CHECK(j == 1);
  CHECK(b.radius[j] == r);
  CHECK(b.radius[b.add(gb::RigidBody{})] == 0.0); // an analytical body has no shape
  CHECK(has(error_of([&] { (void)gb::sphere_body(p, 1); }), "particle index = 1"));
}

// ---------------------------------------------------------------------------------------------
// Mesh mass properties (all closed forms; tolerance 1e-14 relative = a few ulps of the sums)
// ---------------------------------------------------------------------------------------------

TEST_CASE("bodies: unit cube hexahedron") {
  const double rho = 2700.0;
  const gb::Mesh mesh{cube_nodes(), {{{0, 1, 2, 3, 4, 5, 6, 7}, rho}}};
  const auto p = gb::mass_properties(mesh);
  CHECK(p.volume == approx(1.0).epsilon(1e-14));
  CHECK(p.mass == approx(rho).epsilon(1e-14));
  CHECK(rel_diff(p.centre, Vec3::Constant(0.5)) < 1e-14);
  CHECK(rel_diff(p.inertia, Mat3::Identity() * (rho / 6.0)) < 1e-14);
  // about a corner: 2/3 m a^2 on the diagonal, -1/4 m a^2 off it
  Mat3 corner = Mat3::Constant(-rho / 4.0);
  corner.diagonal().setConstant(2.0 * rho / 3.0);
  CHECK(rel_diff(gb::parallel_axis(p.inertia, p.mass, -p.centre), corner) < 1e-14);
  // the rigid body of the mesh
  const auto body = gb::mesh_body(mesh);
  gb::RigidBodies b;
  const auto i = b.add(body);
  CHECK(rel_diff(b.inertia[i], Vec3::Constant(rho / 6.0)) < 1e-14);
  CHECK(rel_diff(gb::to_local(b, i, Vec3(1, 1, 1)), Vec3::Constant(0.5)) < 1e-15);
}

TEST_CASE("bodies: tetrahedron, pyramid and wedge against textbook formulas") {
  const double rho = 1000.0, a = 0.3, bb = 0.5, c = 0.7;
  SUBCASE("right tetrahedron") {
    // vertices 0, a e_x, b e_y, c e_z: V = abc/6, centre (a,b,c)/4,
    // J_xx = 3/80 m (b^2 + c^2), J_xy = m a b / 80 (tensor entry = minus the product integral).
    const gb::Mesh mesh{{Vec3::Zero(), Vec3(a, 0, 0), Vec3(0, bb, 0), Vec3(0, 0, c)},
                        {{{0, 1, 2, 3}, rho}}};
    const auto p = gb::mass_properties(mesh);
    const double m = rho * a * bb * c / 6.0;
    CHECK(p.mass == approx(m).epsilon(1e-14));
    CHECK(rel_diff(p.centre, Vec3(a, bb, c) / 4.0) < 1e-14);
    Mat3 j;
    j << 3.0 / 80.0 * m * (bb * bb + c * c), m * a * bb / 80.0, m * a * c / 80.0, m * a * bb / 80.0,
        3.0 / 80.0 * m * (a * a + c * c), m * bb * c / 80.0, m * a * c / 80.0, m * bb * c / 80.0,
        3.0 / 80.0 * m * (a * a + bb * bb);
    CHECK(rel_diff(p.inertia, j) < 1e-14);
  }
  SUBCASE("square pyramid") {
    // base side a in z = 0 centred at the origin, apex at height H: V = a^2 H / 3, centre
    // H/4 above the base, J_zz = m a^2 / 10, J_xx = J_yy = m (a^2/20 + 3 H^2/80).
    const double h = c;
    const gb::Mesh mesh{{Vec3(-a / 2, -a / 2, 0), Vec3(a / 2, -a / 2, 0), Vec3(a / 2, a / 2, 0),
                         Vec3(-a / 2, a / 2, 0), Vec3(0, 0, h)},
                        {{{0, 1, 2, 3, 4}, rho}}};
    const auto p = gb::mass_properties(mesh);
    const double m = rho * a * a * h / 3.0;
    CHECK(p.mass == approx(m).epsilon(1e-14));
    CHECK(rel_diff(p.centre, Vec3(0, 0, h / 4.0)) < 1e-14);
    const double jx = m * (a * a / 20.0 + 3.0 * h * h / 80.0);
    CHECK(rel_diff(p.inertia, Vec3(jx, jx, m * a * a / 10.0).asDiagonal().toDenseMatrix()) < 1e-14);
  }
  SUBCASE("right triangular wedge") {
    // right triangle with legs a (x) and b (y), extruded by L along z: V = a b L / 2, centre
    // (a/3, b/3, L/2), J_xx = m (b^2/18 + L^2/12), J_yy = m (a^2/18 + L^2/12),
    // J_zz = m (a^2 + b^2)/18, J_xy = m a b / 36. VTK order: the normal of (0,1,2) points away
    // from (3,4,5).
    const double l = c;
    const gb::Mesh mesh{{Vec3(0, 0, 0), Vec3(0, bb, 0), Vec3(a, 0, 0), Vec3(0, 0, l),
                         Vec3(0, bb, l), Vec3(a, 0, l)},
                        {{{0, 1, 2, 3, 4, 5}, rho}}};
    const auto p = gb::mass_properties(mesh);
    const double m = rho * a * bb * l / 2.0;
    CHECK(p.mass == approx(m).epsilon(1e-14));
    CHECK(rel_diff(p.centre, Vec3(a / 3.0, bb / 3.0, l / 2.0)) < 1e-14);
    Mat3 j;
    j << m * (bb * bb / 18.0 + l * l / 12.0), m * a * bb / 36.0, 0.0, m * a * bb / 36.0,
        m * (a * a / 18.0 + l * l / 12.0), 0.0, 0.0, 0.0, m * (a * a + bb * bb) / 18.0;
    CHECK(rel_diff(p.inertia, j) < 1e-14);
  }
}

TEST_CASE("bodies: a hexahedron equals its splits into 5 and 6 tetrahedra") {
  // A parallelepiped (planar faces) from an affine map of the unit cube; the 24-tetrahedron
  // decomposition, the 5- and the 6-tetrahedron splits all fill it exactly.
  Mat3 a;
  a << 1.0, 0.2, -0.1, 0.1, 0.8, 0.3, -0.2, 0.1, 1.2;
  std::vector<Vec3> x = cube_nodes();
  for (auto& p : x)
    p = a * p + Vec3(0.3, -0.4, 2.0);
  const double rho = 7800.0;
  const auto hex = gb::mass_properties({x, {{{0, 1, 2, 3, 4, 5, 6, 7}, rho}}});
  CHECK(hex.volume == approx(a.determinant()).epsilon(1e-14));
  gb::Mesh five{x, {}};
  for (auto t : std::vector<std::array<std::size_t, 4>>{
           {0, 1, 3, 4}, {1, 2, 3, 6}, {1, 4, 5, 6}, {3, 4, 6, 7}, {1, 3, 4, 6}})
    five.elements.push_back(oriented_tet(x, t[0], t[1], t[2], t[3], rho));
  gb::Mesh six{x, {}};
  for (auto t : std::vector<std::array<std::size_t, 4>>{
           {0, 1, 2, 6}, {0, 2, 3, 6}, {0, 3, 7, 6}, {0, 7, 4, 6}, {0, 4, 5, 6}, {0, 5, 1, 6}})
    six.elements.push_back(oriented_tet(x, t[0], t[1], t[2], t[3], rho));
  for (const auto* m : {&five, &six}) {
    const auto p = gb::mass_properties(*m);
    CHECK(p.mass == approx(hex.mass).epsilon(1e-14));
    CHECK(rel_diff(p.centre, hex.centre) < 1e-14);
    CHECK(rel_diff(p.inertia, hex.inertia) < 1e-13);
  }
}

TEST_CASE("bodies: warped hexahedron keeps the trilinear element's volume") {
  // Nodes of the unit cube moved by up to 0.15: faces are not planar. The 24-tetrahedron
  // decomposition encloses exactly the volume of the trilinear (isoparametric) element, computed
  // here by 3x3x3 Gauss quadrature (exact for its polynomial Jacobian); tolerance 1e-14.
  std::vector<Vec3> x = cube_nodes();
  const std::array<Vec3, 8> shift{Vec3(0.10, -0.05, 0.02),  Vec3(-0.03, 0.08, -0.12),
                                  Vec3(0.15, 0.02, 0.07),   Vec3(-0.09, -0.11, 0.04),
                                  Vec3(0.05, 0.13, -0.06),  Vec3(-0.14, 0.01, 0.09),
                                  Vec3(0.02, -0.07, -0.15), Vec3(0.08, 0.06, 0.11)};
  for (std::size_t k = 0; k < 8; ++k)
    x[k] += shift[k];
  const auto hex = gb::mass_properties({x, {{{0, 1, 2, 3, 4, 5, 6, 7}, 1.0}}});
  const double g[3] = {0.5 - 0.5 * std::sqrt(0.6), 0.5, 0.5 + 0.5 * std::sqrt(0.6)};
  const double w[3] = {5.0 / 18.0, 8.0 / 18.0, 5.0 / 18.0};
  const std::vector<Vec3> ref = cube_nodes();
  double v = 0.0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k) {
        const Vec3 u(g[i], g[j], g[k]);
        Mat3 jac = Mat3::Zero();
        for (std::size_t n = 0; n < 8; ++n) {
          Vec3 shape, dshape;
          for (int d = 0; d < 3; ++d) {
            shape(d) = ref[n](d) > 0.5 ? u(d) : 1.0 - u(d);
            dshape(d) = ref[n](d) > 0.5 ? 1.0 : -1.0;
          }
          jac.col(0) += dshape(0) * shape(1) * shape(2) * x[n];
          jac.col(1) += shape(0) * dshape(1) * shape(2) * x[n];
          jac.col(2) += shape(0) * shape(1) * dshape(2) * x[n];
        }
        v += jac.determinant() * w[i] * w[j] * w[k];
      }
  CHECK(hex.volume == approx(v).epsilon(1e-14));
}

TEST_CASE("bodies: mixed mesh under translation and rotation") {
  // A hexahedron (density 1000), a pyramid on its top (2000) and a wedge against its side
  // (3000). Moving the mesh rigidly by x -> R x + t keeps the mass, moves the centre to R c + t
  // and turns the inertia into R J R^T (tolerance 1e-13: the sums mix magnitudes).
  std::vector<Vec3> x = cube_nodes();
  x.push_back(Vec3(0.5, 0.5, 1.6)); // 8: pyramid apex
  x.push_back(Vec3(1.6, 0.0, 0.0)); // 9, 10: wedge edge
  x.push_back(Vec3(1.6, 1.0, 0.0));
  gb::Mesh mesh{x,
                {{{0, 1, 2, 3, 4, 5, 6, 7}, 1000.0},
                 {{4, 5, 6, 7, 8}, 2000.0},
                 // wedge: triangle (1, 9, 5) and (2, 10, 6) along +y; normal of (1, 9, 5) is -y
                 {{1, 9, 5, 2, 10, 6}, 3000.0}}};
  const auto p = gb::mass_properties(mesh);
  // closed-form parts: cube, pyramid (V = 0.6/3, centre 1 + 0.6/4), wedge (V = 0.6/2,
  // centre (1 + 0.6/3, 0.5, 1/3))
  const double m_cube = 1000.0, m_pyr = 2000.0 * 0.2, m_wedge = 3000.0 * 0.3;
  CHECK(p.mass == approx(m_cube + m_pyr + m_wedge).epsilon(1e-14));
  const Vec3 c = (m_cube * Vec3(0.5, 0.5, 0.5) + m_pyr * Vec3(0.5, 0.5, 1.15) +
                  m_wedge * Vec3(1.2, 0.5, 1.0 / 3.0)) /
                 (m_cube + m_pyr + m_wedge);
  CHECK(rel_diff(p.centre, c) < 1e-14);

  gb::Mesh moved = mesh;
  const Vec3 t(-3.0, 10.0, 0.25);
  for (auto& n : moved.nodes)
    n = some_rotation * n + t;
  const auto q = gb::mass_properties(moved);
  CHECK(q.mass == approx(p.mass).epsilon(1e-14));
  CHECK(rel_diff(q.centre, some_rotation * p.centre + t) < 1e-14);
  CHECK(rel_diff(q.inertia, some_rotation * p.inertia * some_rotation.transpose()) < 1e-13);
  // per-element sum with the parallel-axis theorem equals the mesh result
  Mat3 sum = Mat3::Zero();
  for (const auto& e : mesh.elements) {
    const auto pe = gb::element_mass_properties(mesh.nodes, e);
    sum += gb::parallel_axis(pe.inertia, pe.mass, pe.centre - p.centre);
  }
  CHECK(rel_diff(sum, p.inertia) < 1e-13);
  // Parmec's MESH flat element list gives the same mesh
  const std::vector<std::size_t> flat{8, 0, 1, 2, 3, 4, 5, 6, 7, 0,  5, 4, 5,
                                      6, 7, 8, 1, 6, 1, 9, 5, 2, 10, 6, 2};
  const std::vector<double> densities{1000.0, 2000.0, 3000.0};
  const gb::Mesh listed{x, gb::elements_from_list(flat, densities)};
  CHECK(rel_diff(gb::mass_properties(listed).inertia, p.inertia) < 1e-15);
}

// ---------------------------------------------------------------------------------------------
// Mesh surfaces and face colours
// ---------------------------------------------------------------------------------------------

namespace {

/// Area vector of a face (1/2 the cross product of the diagonals for a quadrilateral): its right-
/// hand normal times its area.
Vec3 area_vector(const gb::MeshSurface& s, std::size_t f) {
  const auto& v = s.faces[f];
  const auto x = [&](std::size_t k) { return s.nodes[v[k]]; };
  return v.size() == 3 ? Vec3(0.5 * (x(1) - x(0)).cross(x(2) - x(0)))
                       : Vec3(0.5 * (x(2) - x(0)).cross(x(3) - x(1)));
}
Vec3 face_centroid(const gb::MeshSurface& s, std::size_t f) {
  Vec3 c = Vec3::Zero();
  for (const auto v : s.faces[f])
    c += s.nodes[v];
  return c / static_cast<double>(s.faces[f].size());
}
/// The enclosed volume by the divergence theorem: sum over faces of centroid . A / 3 (exact for
/// planar faces).
double enclosed_volume(const gb::MeshSurface& s) {
  double v = 0.0;
  for (std::size_t f = 0; f < s.faces.size(); ++f)
    v += face_centroid(s, f).dot(area_vector(s, f)) / 3.0;
  return v;
}
/// For a convex body: every face's outward normal points away from the centre of mass (the
/// origin of the local coordinates), i.e. the centre is on the inner side of every face plane.
bool outward(const gb::MeshSurface& s) {
  for (std::size_t f = 0; f < s.faces.size(); ++f)
    if (!(face_centroid(s, f).dot(area_vector(s, f)) > 0.0)) return false;
  return true;
}
/// Number of faces with k nodes.
std::size_t faces_of_size(const gb::MeshSurface& s, std::size_t k) {
  return static_cast<std::size_t>(
      std::count_if(s.faces.begin(), s.faces.end(), [&](const auto& f) { return f.size() == k; }));
}

/// Two unit cubes side by side along x (nodes 0-7 the first, 1, 8, 9, 2, 5, 10, 11, 6 the
/// second), sharing the face x = 1.
gb::Mesh two_cubes() {
  std::vector<Vec3> x = cube_nodes();
  for (const Vec3& p : {Vec3(2, 0, 0), Vec3(2, 1, 0), Vec3(2, 0, 1), Vec3(2, 1, 1)})
    x.push_back(p);
  return {x, {{{0, 1, 2, 3, 4, 5, 6, 7}, 1000.0}, {{1, 8, 9, 2, 5, 10, 11, 6}, 1000.0}}};
}

} // namespace

TEST_CASE("bodies: surface of one and of two hexahedra") {
  SUBCASE("one hexahedron: six outward quadrilaterals") {
    const gb::Mesh mesh{cube_nodes(Vec3(2, -1, 3)), {{{0, 1, 2, 3, 4, 5, 6, 7}, 1000.0}}};
    const auto s = gb::mesh_surface(mesh);
    CHECK(s.faces.size() == 6);
    CHECK(faces_of_size(s, 4) == 6);
    CHECK(s.nodes.size() == 8);
    CHECK(s.colors == std::vector<int>(6, 1));
    CHECK(s.elements == std::vector<std::size_t>(6, 0));
    CHECK(outward(s));
    CHECK(enclosed_volume(s) == approx(1.0).epsilon(1e-12));
    // local coordinates: relative to the centre (2.5, -0.5, 3.5); every face a unit square
    // along an axis
    for (std::size_t k = 0; k < s.nodes.size(); ++k)
      CHECK((s.nodes[k].cwiseAbs() - Vec3::Constant(0.5)).norm() < 1e-15);
    for (std::size_t f = 0; f < 6; ++f) {
      const Vec3 a = area_vector(s, f);
      CHECK(a.norm() == approx(1.0).epsilon(1e-15));
      CHECK(a.cwiseAbs().maxCoeff() == approx(1.0).epsilon(1e-15));
    }
  }
  SUBCASE("two hexahedra: the shared face is inside") {
    const gb::Mesh mesh = two_cubes();
    const auto s = gb::mesh_surface(mesh);
    CHECK(s.faces.size() == 10);
    CHECK(faces_of_size(s, 4) == 10);
    CHECK(s.nodes.size() == 12);
    CHECK(std::count(s.elements.begin(), s.elements.end(), 0) == 5);
    CHECK(std::count(s.elements.begin(), s.elements.end(), 1) == 5);
    CHECK(outward(s));
    CHECK(enclosed_volume(s) == approx(2.0).epsilon(1e-12));
    // the centre is (1, 0.5, 0.5): no face lies in the plane x = 1 (local x = 0)
    for (std::size_t f = 0; f < s.faces.size(); ++f) {
      bool all_in_middle = true;
      for (const auto v : s.faces[f])
        all_in_middle = all_in_middle && std::abs(s.nodes[v].x()) < 1e-15;
      CHECK_FALSE(all_in_middle);
    }
  }
}

TEST_CASE("bodies: surfaces of a tetrahedron, a pyramid, a wedge and a mixed mesh") {
  const double rho = 1000.0, a = 0.3, bb = 0.5, c = 0.7;
  struct Case {
    std::string name;
    gb::Mesh mesh;
    std::size_t triangles, quads;
  };
  const std::vector<Case> cases{
      {"tetrahedron",
       {{Vec3(0.1, 0, 0), Vec3(a, 0.05, 0), Vec3(0, bb, 0.1), Vec3(0, 0, c)},
        {{{0, 1, 2, 3}, rho}}},
       4,
       0},
      {"pyramid",
       {{Vec3(-a / 2, -a / 2, 0), Vec3(a / 2, -a / 2, 0), Vec3(a / 2, a / 2, 0),
         Vec3(-a / 2, a / 2, 0), Vec3(0.05, -0.02, c)},
        {{{0, 1, 2, 3, 4}, rho}}},
       4,
       1},
      {"wedge",
       {{Vec3(0, 0, 0), Vec3(0, bb, 0), Vec3(a, 0, 0), Vec3(0, 0, c), Vec3(0, bb, c),
         Vec3(a, 0, c)},
        {{{0, 1, 2, 3, 4, 5}, rho}}},
       2,
       3},
  };
  double worst = 0.0; // largest relative error of the enclosed volume
  for (const auto& k : cases) {
    CAPTURE(k.name);
    for (const bool turned : {false, true}) {
      CAPTURE(turned);
      gb::Mesh mesh = k.mesh;
      if (turned)
        for (auto& n : mesh.nodes)
          n = some_rotation * n + Vec3(-3.0, 10.0, 0.25);
      const auto s = gb::mesh_surface(mesh);
      CHECK(faces_of_size(s, 3) == k.triangles);
      CHECK(faces_of_size(s, 4) == k.quads);
      CHECK(s.nodes.size() == mesh.nodes.size());
      CHECK(outward(s));
      const double v = gb::mass_properties(mesh).volume;
      CHECK(enclosed_volume(s) == approx(v).epsilon(1e-12));
      worst = std::max(worst, std::abs(enclosed_volume(s) / v - 1.0));
    }
  }
  // the hexahedron, pyramid and wedge of the mixed-mesh test: 4 + 4 + 4 boundary faces (the
  // cube's top and +x faces are shared), volume 1 + 0.2 + 0.3
  std::vector<Vec3> x = cube_nodes();
  x.push_back(Vec3(0.5, 0.5, 1.6));
  x.push_back(Vec3(1.6, 0.0, 0.0));
  x.push_back(Vec3(1.6, 1.0, 0.0));
  for (auto& n : x)
    n = some_rotation * n + Vec3(1.0, 2.0, 3.0);
  const gb::Mesh mixed{
      x, {{{0, 1, 2, 3, 4, 5, 6, 7}, 1.0}, {{4, 5, 6, 7, 8}, 2.0}, {{1, 9, 5, 2, 10, 6}, 3.0}}};
  const auto s = gb::mesh_surface(mixed);
  CHECK(s.faces.size() == 12);
  for (std::size_t e = 0; e < 3; ++e)
    CHECK(std::count(s.elements.begin(), s.elements.end(), e) == 4);
  CHECK(faces_of_size(s, 3) == 6);
  CHECK(enclosed_volume(s) == approx(1.5).epsilon(1e-12));
  worst = std::max(worst, std::abs(enclosed_volume(s) / 1.5 - 1.0));
  MESSAGE("surfaces: largest relative error of the enclosed volume ", worst);
  // local coordinates relative to the centre of mass
  const Vec3 centre = gb::mass_properties(mixed).centre;
  for (std::size_t f = 0; f < s.faces.size(); ++f)
    for (const auto v : s.faces[f]) {
      bool found = false;
      for (const Vec3& n : x)
        found = found || (s.nodes[v] + centre - n).norm() < 1e-14;
      CHECK(found);
    }
}

TEST_CASE("bodies: face colours of a mesh surface") {
  const gb::Mesh mesh = two_cubes();
  // global 3; the outer face x = 2 (nodes 8, 9, 11, 10 in its cycle) given reversed from
  // another node, the face x = 0 (0, 3, 7, 4) in no cyclic order
  const gb::FaceColors colors{3, {{{10, 11, 9, 8}, 7}, {{7, 0, 4, 3}, 5}}};
  const auto s = gb::mesh_surface(mesh, colors);
  REQUIRE(s.faces.size() == 10);
  CHECK(std::count(s.colors.begin(), s.colors.end(), 3) == 8);
  CHECK(std::count(s.colors.begin(), s.colors.end(), 7) == 1);
  CHECK(std::count(s.colors.begin(), s.colors.end(), 5) == 1);
  for (std::size_t f = 0; f < s.faces.size(); ++f) {
    // the local x of the face's nodes: -1 for x = 0, +1 for x = 2
    double lo = 1e9, hi = -1e9;
    for (const auto v : s.faces[f]) {
      lo = std::min(lo, s.nodes[v].x());
      hi = std::max(hi, s.nodes[v].x());
    }
    const int want = (hi < -0.999) ? 5 : (lo > 0.999) ? 7 : 3;
    CHECK(s.colors[f] == want);
    if (want == 7) CHECK(s.elements[f] == 1);
    if (want == 5) CHECK(s.elements[f] == 0);
  }
  // Parmec's flat list gives the same colours; a global colour alone
  const std::vector<long> flat{3, 4, 10, 11, 9, 8, 7, 4, 7, 0, 4, 3, 5};
  const auto parsed = gb::face_colors_from_list(flat);
  CHECK(parsed.global == 3);
  CHECK(parsed.faces == colors.faces);
  CHECK(gb::mesh_surface(mesh, parsed).colors == s.colors);
  const std::vector<long> only{4};
  const auto global = gb::face_colors_from_list(only);
  CHECK(global.global == 4);
  CHECK(global.faces.empty());
  CHECK(gb::mesh_surface(mesh, global).colors == std::vector<int>(10, 4));
  // a triangle of a tetrahedron, listed from its second node
  const gb::Mesh tet{{Vec3::Zero(), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)},
                     {{{0, 1, 2, 3}, 1.0}}};
  const auto t = gb::mesh_surface(tet, {2, {{{2, 3, 1}, 9}}});
  CHECK(std::count(t.colors.begin(), t.colors.end(), 9) == 1);
  CHECK(std::count(t.colors.begin(), t.colors.end(), 2) == 3);
}

TEST_CASE("bodies: face colour input errors name the object, the value and the range") {
  const gb::Mesh mesh = two_cubes();
  auto surface_error = [&](const gb::FaceColors& c) {
    return error_of([&] { (void)gb::mesh_surface(mesh, c, "block"); });
  };
  std::string e = surface_error({1, {{{1, 2, 6, 5}, 2}}});
  CHECK(has(e, "block face colour 0: nodes = (1, 2, 6, 5) is invalid; valid range: the nodes of "
               "a boundary face (this face is shared by two elements"));
  e = surface_error({1, {{{0, 1, 2, 3}, 2}, {{0, 1, 2}, 2}}});
  CHECK(has(e, "block face colour 1: nodes = (0, 1, 2) is invalid; valid range: the nodes of a "
               "boundary face (no element has a face with these nodes)"));
  e = surface_error({1, {{{0, 1, 2, 3}, -1}}});
  CHECK(has(e, "block face colour 0: colour = -1 is invalid; valid range: [0, inf)"));
  CHECK(gb::mesh_surface(mesh, {0, {{{0, 1, 2, 3}, 0}}}, "block").colors.at(0) == 0);
  e = surface_error({1, {{{0, 1, 2, 99}, 2}}});
  CHECK(has(e, "block face colour 0: node = 99 is invalid; valid range: [0, 12) (the mesh's "
               "nodes)"));
  e = surface_error({1, {{{0, 1, 2, 3, 4}, 2}}});
  CHECK(has(e, "block face colour 0: number of nodes = 5 is invalid; valid range: 3 or 4"));
  e = surface_error({-2, {}});
  CHECK(has(e, "block: global colour = -2 is invalid; valid range: [0, inf)"));
  // a bad element is reported as by mass_properties
  gb::Mesh inverted = mesh;
  inverted.elements[1].nodes = {5, 10, 11, 6, 1, 8, 9, 2}; // numbered from the top face
  CHECK(has(error_of([&] { (void)gb::mesh_surface(inverted, {}, "block"); }),
            "block element 1 (hexahedron): volume = -1"));

  auto list_error = [](std::vector<long> list) {
    return error_of([&] { (void)gb::face_colors_from_list(list, "block"); });
  };
  CHECK(has(list_error({}), "block colour list: length = 0 is invalid; valid range: at least 1"));
  CHECK(has(list_error({-1}),
            "block colour list: global colour = -1 is invalid; valid range: [0, 2147483647]"));
  CHECK(gb::face_colors_from_list(std::vector<long>{0}, "block").global == 0);
  CHECK(has(list_error({1, 5, 0, 1, 2, 3, 4, 2}),
            "block colour list entry 0: number of nodes = 5 is invalid; valid range: 3 or 4"));
  CHECK(has(list_error({1, 3, 0, 1, 2, 2, 4, 0, 1, 2}),
            "block colour list entry 1: list length = 10 is invalid; valid range: at least 12 "
            "entries"));
  CHECK(has(list_error({1, 3, 0, -1, 2, 2}), "block colour list entry 0: node = -1 is invalid"));
  CHECK(has(list_error({1, 3, 0, 1, 2, -4}), "block colour list entry 0: colour = -4 is invalid"));
}

// ---------------------------------------------------------------------------------------------
// Equivalent mass and critical step
// ---------------------------------------------------------------------------------------------

TEST_CASE("bodies: equivalent point mass") {
  const double r = 0.1, rho = 1000.0;
  gb::RigidBodies b;
  const auto s = b.add(gb::sphere_body(r, rho, Vec3(1, 1, 1)));
  const double m = b.mass[s], j = 0.4 * m * r * r;
  // at the centre: m in every direction (tolerance: a few ulps)
  CHECK(gb::equivalent_mass(b, s, Vec3(1, 1, 1), Vec3(0, 0, 1)) == approx(m).epsilon(1e-15));
  CHECK(gb::equivalent_mass(b, s, Vec3(1, 1, 1)) == approx(m).epsilon(1e-15));
  // on the surface, perpendicular to the arm: 1/(1/m + r^2/J) = 2/7 m
  const Vec3 p = Vec3(1, 1, 1) + Vec3(r, 0, 0);
  const double perp = 1.0 / (1.0 / m + r * r / j);
  CHECK(perp == approx(2.0 / 7.0 * m).epsilon(1e-15));
  CHECK(gb::equivalent_mass(b, s, p, Vec3(0, 2, 0)) == approx(perp).epsilon(1e-14));
  CHECK(gb::equivalent_mass(b, s, p, Vec3(1, 0, 0)) == approx(m).epsilon(1e-14));
  CHECK(gb::equivalent_mass(b, s, p) == approx(perp).epsilon(1e-14));
  // relative: two equal bodies combine in series
  const auto s2 = b.add(gb::sphere_body(r, rho, Vec3(3, 1, 1)));
  CHECK(gb::equivalent_mass(b, s, Vec3(1, 1, 1), s2, Vec3(3, 1, 1), Vec3(1, 0, 0)) ==
        approx(m / 2.0).epsilon(1e-14));
  CHECK(gb::equivalent_mass(b, s, p, s2, Vec3(3, 1, 1) - Vec3(r, 0, 0), Vec3(0, 0, 1)) ==
        approx(perp / 2.0).epsilon(1e-14));
  CHECK(gb::equivalent_mass(b, s, p, s2, Vec3(3, 1, 1) - Vec3(r, 0, 0)) ==
        approx(perp / 2.0).epsilon(1e-14));

  // Asymmetric rotated body: a force F along d at p, applied over one kick of h, changes the
  // point's velocity along d by (h/2) |F| / m_eq (tolerance 1e-13).
  gb::RigidBody d;
  d.mass = 5.0;
  d.inertia = some_rotation * Vec3(1.0, 2.0, 2.5).asDiagonal() * some_rotation.transpose();
  const auto k = b.add(d);
  const Vec3 q(0.3, -0.2, 0.5), dir = Vec3(1.0, 1.0, -0.5).normalized();
  const double meq = gb::equivalent_mass(b, k, q, dir);
  const double before = gb::point_velocity(b, k, q).dot(dir);
  gb::clear_forces(b);
  gb::apply_force(b, k, 4.0 * dir, q);
  gb::kick(b, 0.01);
  const double after = gb::point_velocity(b, k, q).dot(dir);
  CHECK(after - before == approx(0.005 * 4.0 / meq).epsilon(1e-13));
  CHECK(meq < d.mass);
  CHECK(gb::equivalent_mass(b, k, q) <= meq);
}

TEST_CASE("bodies: critical time step") {
  const double k = 1e6, m = 2.0, w = std::sqrt(k / m);
  CHECK(gb::natural_frequency(k, m) == approx(w).epsilon(1e-15));
  CHECK(gb::critical_step(w, 0.0) == approx(2.0 / w).epsilon(1e-15));
  CHECK(gb::critical_step(w, 1.0) == approx(2.0 / w * (std::sqrt(2.0) - 1.0)).epsilon(1e-15));
  CHECK(gb::critical_step(w, 0.3) == approx(2.0 / w * (std::sqrt(1.09) - 0.3)).epsilon(1e-15));
  CHECK(gb::spring_critical_step(k, m, 0.3) == gb::critical_step(w, 0.3));
  CHECK(gb::critical_damping(k, m) == approx(2.0 * std::sqrt(k * m)).epsilon(1e-15));
  // large damping without cancellation: h ~ 1/(omega xi)
  CHECK(gb::critical_step(w, 1e8) == approx(1.0 / (w * 1e8)).epsilon(1e-15));

  // The rule is sharp for the integrator: a body on a spring (and dashpot, evaluated with the
  // half-step velocity the loads see) to a fixed point stays bounded at 0.99 h_crit and grows
  // without bound at 1.01 h_crit (2000 steps; measured growth > 1e30 for every xi below).
  auto amplitude = [&](double factor, double xi) {
    gb::RigidBodies b;
    gb::RigidBody d;
    d.mass = m;
    d.position = Vec3(1e-3, 0, 0);
    b.add(d);
    const double c = xi * gb::critical_damping(k, m);
    auto spring = [&](gb::RigidBodies& s) { s.force[0] += -k * s.position[0] - c * s.velocity[0]; };
    spring(b);
    const double h = factor * gb::spring_critical_step(k, m, xi);
    double amp = 0.0;
    for (int s = 0; s < 2000; ++s) {
      gb::step(b, h, spring);
      amp = std::max(amp, b.position[0].norm());
    }
    return amp / 1e-3;
  };
  for (const double xi : {0.0, 0.1, 0.5, 1.0, 2.0}) {
    CAPTURE(xi);
    CHECK(amplitude(0.99, xi) < 10.0);
    CHECK(amplitude(1.01, xi) > 1e3);
  }
}

// ---------------------------------------------------------------------------------------------
// Input validation
// ---------------------------------------------------------------------------------------------

TEST_CASE("bodies: invalid input") {
  gb::RigidBodies b;
  auto add = [&](auto change) {
    gb::RigidBody d;
    d.name = "body A";
    change(d);
    return error_of([&] { b.add(d); });
  };
  CHECK(has(add([](gb::RigidBody& d) { d.mass = -1.0; }), "body A: mass = -1"));
  CHECK(has(add([](gb::RigidBody& d) { d.mass = 0.0; }), "valid range: (0, inf)"));
  CHECK(has(add([](gb::RigidBody& d) { d.mass = std::nan(""); }), "mass = nan"));
  CHECK(has(add([](gb::RigidBody& d) { d.inertia(0, 1) = 0.5; }), "symmetric"));
  CHECK(has(add([](gb::RigidBody& d) { d.inertia(2, 2) = -1.0; }), "positive definite"));
  CHECK(has(add([](gb::RigidBody& d) { d.inertia.setZero(); }), "positive definite"));
  CHECK(has(add([](gb::RigidBody& d) { d.inertia = Vec3(1, 1, 5).asDiagonal(); }), "J1 + J2"));
  CHECK(has(add([](gb::RigidBody& d) { d.inertia(1, 1) = std::nan(""); }), "finite"));
  CHECK(has(add([](gb::RigidBody& d) { d.rotation(0, 0) = 2.0; }), "rotation"));
  CHECK(has(add([](gb::RigidBody& d) { d.rotation = -Mat3::Identity(); }), "det = +1"));
  CHECK(has(add([](gb::RigidBody& d) { d.velocity.x() = std::numeric_limits<double>::infinity(); }),
            "velocity"));
  CHECK(has(add([](gb::RigidBody& d) { d.radius = -0.1; }),
            "body A: radius = -0.1 is invalid; valid range: [0, inf) m"));
  CHECK(has(add([](gb::RigidBody& d) { d.radius = std::nan(""); }), "radius = nan"));
  CHECK(b.size() == 0);
  CHECK(has(error_of([] { (void)gb::sphere_body(-1.0, 1000.0, Vec3::Zero()); }), "radius = -1"));

  const std::vector<Vec3> x{Vec3::Zero(), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
  auto mesh_error = [&](gb::Element e) {
    return error_of([&] { (void)gb::mass_properties({x, {{{0, 1, 2, 3}, 1.0}, e}}); });
  };
  const std::string inverted = mesh_error({{0, 2, 1, 3}, 1.0});
  CHECK(has(inverted, "mesh element 1 (tetrahedron): volume = -0.1666666667"));
  CHECK(has(inverted, "inverted"));
  CHECK(has(mesh_error({{0, 1, 2, 2}, 1.0}), "element 1 (tetrahedron): volume = 0"));
  CHECK(has(mesh_error({{0, 1, 2}, 1.0}), "number of nodes = 3"));
  CHECK(has(mesh_error({{0, 1, 2, 7}, 1.0}), "node index = 7"));
  CHECK(has(mesh_error({{0, 1, 2, 3}, -2.0}), "density = -2"));
  // a hexahedron numbered from the top face is inverted
  const std::string hex = error_of([] {
    (void)gb::mass_properties({cube_nodes(), {{{4, 5, 6, 7, 0, 1, 2, 3}, 1.0}}});
  });
  CHECK(has(hex, "mesh element 0 (hexahedron): volume = -1"));
  CHECK(has(error_of([] { (void)gb::mass_properties({cube_nodes(), {}}); }), "number of elements"));
  gb::RigidBodies one;
  one.add(gb::RigidBody{});
  CHECK(has(error_of([&] { (void)gb::equivalent_mass(one, 0, Vec3::Zero(), Vec3::Zero()); }),
            "direction"));
  CHECK(has(error_of([&] { (void)gb::equivalent_mass(one, 3, Vec3::Zero()); }), "body index = 3"));
  CHECK(has(error_of([&] { (void)gb::equivalent_mass(one, 0, Vec3::Zero(), 0, Vec3::UnitX()); }),
            "body j = 0 is invalid; valid range: a body other than body i = 0"));
  CHECK(has(error_of([] { (void)gb::critical_step(1.0, -0.1); }), "damping ratio = -0.1"));
  CHECK(has(error_of([] { (void)gb::natural_frequency(0.0, 1.0); }), "stiffness = 0"));
}
