// Fuzz target of grain::io::read_state_vtk: any file either reads as a particle file of
// write_particles_vtk, giving only particles that add_particle accepts, or is refused with
// grain::InputError. A state that reads is checked value by value and then loaded
// (io::load_state) into a fresh simulation, which must take all of it.
//
// Every input is read for two simulation types: 3D spheres with Hertz-Mindlin and
// Batchelor-O'Brien conduction (thermal), and 2D disks with the linear spring-dashpot preset
// (mechanical); both with two materials. The seeds are files of write_particles_vtk (a few
// particles, ASCII and binary, 2D and 3D, every field or a few) and broken ones.

#include "fuzz_support.hpp"

#include <grain/grain.hpp>
#include <grain/io/state_file.hpp>
#include <grain/models/conduction/batchelor_obrien.hpp>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <set>
#include <string>

namespace {

using namespace grain;

using Thermal =
    Interaction<normal::Hertz<>, tangent::Mindlin, rolling::None, conduction::BatchelorOBrien>;
using Sim3 = Simulation<Sphere, search::CellList, Thermal>;
using Sim2 = Simulation<Disk, search::CellList, presets::LinearCoulomb>;

template <class S>
S make() {
  S sim({.time_step = 1e-6});
  Material m;
  m.density = 2500;
  m.young = 1e7;
  m.conductivity = 1;
  m.heat_capacity = 800;
  sim.add_material(m);
  sim.add_material(m);
  return sim;
}

const Sim3& sim3() {
  static const Sim3 s = make<Sim3>();
  return s;
}
const Sim2& sim2() {
  static const Sim2 s = make<Sim2>();
  return s;
}

template <class S>
void read(const S& fresh, const std::string& path) {
  io::ParticleState<S::dimension> st;
  try {
    st = io::read_state_vtk(fresh, path);
  } catch (const InputError&) {
    return;
  }
  if (!st.groups.empty()) grain_fuzz::fail("groups from a VTK file");
  std::set<std::int64_t> ids;
  for (const auto& p : st.particles) {
    if (!(std::isfinite(p.radius) && p.radius > 0)) grain_fuzz::fail("radius not in (0, inf)");
    if (!all_finite(p.position) || !all_finite(p.velocity) || !all_finite(p.omega))
      grain_fuzz::fail("position, velocity or omega not finite");
    if (p.material >= fresh.materials().size()) grain_fuzz::fail("material out of range");
    if constexpr (S::thermal) {
      if (!std::isnan(p.temperature) && !(std::isfinite(p.temperature) && p.temperature >= 0))
        grain_fuzz::fail("temperature not in [0, inf)");
    } else if (!std::isnan(p.temperature)) {
      grain_fuzz::fail("temperature in a mechanical state");
    }
    if (p.id < -1 || p.id == std::numeric_limits<std::int64_t>::max())
      grain_fuzz::fail("id out of range");
    if (p.id >= 0 && !ids.insert(p.id).second) grain_fuzz::fail("an id twice");
    if (p.fixed) grain_fuzz::fail("a fixed particle from a VTK file");
  }
  S sim = fresh;
  try {
    io::load_state(sim, st);
  } catch (const InputError& e) {
    std::fprintf(stderr, "%s\n", e.what());
    grain_fuzz::fail("a state that was read could not be loaded");
  }
  if (sim.size() != st.particles.size()) grain_fuzz::fail("not every particle was loaded");
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = grain_fuzz::write_input("state.vtk", data, size);
  read(sim3(), path);
  read(sim2(), path);
  return 0;
}
