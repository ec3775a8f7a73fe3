// Spheres dropped onto a plane: they must fall, then come to rest on it without passing through.
#include <grain/grain.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>

int main() {
  using namespace grain;
  using Contact = Interaction<normal::Hertz<>, tangent::SpringDashpotSlider>;
  using Sim = Simulation<Sphere, search::CellList, Contact>;

  Sim::Params params;
  params.gravity = Vec3(0.0, 0.0, -9.81);
  Sim sim(params);

  Material glass;
  glass.name = "glass";
  glass.density = 2500.0;
  glass.young = 1e6;
  glass.poisson = 0.25;
  glass.restitution = 0.3;
  glass.friction = 0.5;
  const auto m = sim.add_material(glass);

  const double r = 1e-3;
  sim.add_wall(walls::Plane{Vec3::Zero(), Vec3::UnitZ()}, {.name = "floor", .material = m});
  const double z0 = 1.5 * r;
  for (int k = 0; k < 3; ++k) {
    ParticleSpec<3> s;
    s.position = Vec3(3.0 * r * k, 0.0, z0);
    s.radius = r;
    s.material = m;
    sim.add_particle(s);
  }

  // a handful of steps: free fall, every sphere moves down
  sim.steps(5);
  for (std::size_t i = 0; i < sim.size(); ++i) {
    const Vec3& x = sim.particles().position[i];
    const Vec3& v = sim.particles().velocity[i];
    if (!(x.z() < z0 && v.z() < 0.0)) {
      std::printf("sphere %zu did not fall: z = %g m, vz = %g m/s\n", i, x.z(), v.z());
      return 1;
    }
  }

  // then the floor stops them: at rest, touching it, slightly overlapping, never through it
  sim.run(0.03);
  const auto [pair_contacts, wall_contacts] = sim.contact_counts();
  double max_speed = 0.0;
  for (std::size_t i = 0; i < sim.size(); ++i) {
    const double z = sim.particles().position[i].z();
    const double speed = sim.particles().velocity[i].norm();
    max_speed = std::max(max_speed, speed);
    if (!(std::isfinite(z) && z < r && z > 0.9 * r && speed < 1e-2)) {
      std::printf("sphere %zu not at rest on the floor: z = %g m, |v| = %g m/s\n", i, z, speed);
      return 1;
    }
  }
  if (wall_contacts != sim.size() || pair_contacts != 0) {
    std::printf("expected %zu sphere-floor and no sphere-sphere contacts, got %zu and %zu\n",
                sim.size(), wall_contacts, pair_contacts);
    return 1;
  }
  std::printf("grain %d.%d.%d: %zu spheres at rest on the floor after %ld steps (dt = %g s, "
              "max |v| = %g m/s)\n",
              GRAIN_VERSION_MAJOR, GRAIN_VERSION_MINOR, GRAIN_VERSION_PATCH, sim.size(),
              sim.step_count(), sim.time_step(), max_speed);
  return 0;
}
