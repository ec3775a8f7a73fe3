// A program may name its own things like grain's model namespaces (normal, tangent, rolling, area,
// conduction) and other namespaces (search, walls, io): grain's headers compile after such
// declarations, and the patterns of README.md ("Names: using grain in your program") use grain
// without ambiguity. (`using namespace grain;` at namespace scope would make the unqualified
// names below ambiguous; that is a compile error and is not tested here.)
#include <doctest/doctest.h>

#include <cmath>

// the program's own names at global scope, declared before grain's headers
static const double rolling = 0.02; // a rolling-friction coefficient
static double normal(double x) { return -x; }
static double area(double r) { return 3.0 * r * r; }
struct tangent {
  double x = 0.0, y = 0.0;
};
static const int conduction = 1;
static const int search = 2;
static const int walls = 3;
static const int io = 4;

#include <grain/grain.hpp>

namespace g = grain; // pattern 1: a short namespace alias

// pattern 2: using-declarations of the names the program uses
using grain::Material;
using grain::Vec3;

namespace {

using Contact = g::Interaction<g::normal::Hertz<>, g::tangent::Mindlin, g::rolling::Constant>;
using Sim = g::Simulation<g::Sphere, g::search::AllPairs, Contact>;

double settle() {
  Sim sim({.gravity = Vec3(0.0, 0.0, -9.81)});
  Material m;
  m.density = 2500.0;
  m.young = 1e7;
  m.poisson = 0.25;
  m.restitution = 0.5;
  m.friction = 0.5;
  m.rolling_friction = rolling; // the program's own `rolling`
  const auto mat = sim.add_material(m);
  sim.add_particle({.position = Vec3(0.0, 0.0, 1.05e-3), .radius = 1e-3, .material = mat});
  sim.add_wall(g::walls::Plane{Vec3::Zero(), Vec3::UnitZ()}, {.material = mat});
  sim.run(0.05);
  return sim.particles().position[0].z();
}

} // namespace

// pattern 3: a program's code in its own namespace, where its names come first
namespace app {
const double rolling = 0.5;
using namespace grain;
inline double rolling_friction() { return rolling; } // app::rolling, not grain::rolling
} // namespace app

TEST_CASE("user names: a program's own normal, tangent, rolling, area and conduction live "
          "alongside grain") {
  CHECK(normal(2.0) == -2.0);
  CHECK(area(1.0) == 3.0);
  const tangent t{1.0, 2.0};
  CHECK(t.y == 2.0);
  CHECK(conduction + search + walls + io == 10);
  CHECK(app::rolling_friction() == 0.5);
  // a glass sphere (R = 1 mm) dropped 0.05 mm onto a plane of its own material comes to rest
  // with the Hertz static overlap (m g / K_hz)^(2/3), K_hz = 4/3 E* sqrt(R), E* = E/(2(1 - nu^2))
  const double m = 2500.0 * 4.0 / 3.0 * 3.141592653589793 * 1e-9;
  const double k_hz = 4.0 / 3.0 * 1e7 / (2.0 * (1.0 - 0.25 * 0.25)) * std::sqrt(1e-3);
  const double overlap = std::pow(m * 9.81 / k_hz, 2.0 / 3.0);
  const double z = settle();
  MESSAGE("overlap " << 1e-3 - z << " m, Hertz static overlap " << overlap << " m");
  CHECK(std::abs((1e-3 - z) / overlap - 1.0) <= 1e-2);
}
