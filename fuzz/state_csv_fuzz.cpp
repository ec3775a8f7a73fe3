// Fuzz target of grain::io::read_state_csv: any file either reads, giving only particles that
// add_particle accepts and groups that add_group accepts, or is refused with grain::InputError.
// A state that reads is checked value by value and then loaded (io::load_state) into a fresh
// simulation, which must take all of it.
//
// Every input is read for two simulation types: 3D spheres with Hertz-Mindlin and
// Batchelor-O'Brien conduction (thermal), and 2D disks with the linear spring-dashpot preset
// (mechanical: the temperature column is ignored); both with two materials.

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

/// The promises of a state that was read (from either reader).
template <class S>
void check_state(const S& fresh, const io::ParticleState<S::dimension>& st) {
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
    if (p.creation_time != -HUGE_VAL || p.destruction_time != HUGE_VAL)
      grain_fuzz::fail("creation or destruction time set");
  }
  std::set<std::string> names;
  for (const auto& g : st.groups) {
    if (g.name.empty() || g.name == "all" || !names.insert(g.name).second)
      grain_fuzz::fail("group name empty, 'all' or twice");
    if (g.members.empty()) grain_fuzz::fail("group without members");
    for (std::size_t k = 0; k < g.members.size(); ++k) {
      if (g.members[k] >= st.particles.size()) grain_fuzz::fail("group member out of range");
      if (k > 0 && !(g.members[k] > g.members[k - 1])) grain_fuzz::fail("members not increasing");
    }
  }
  S sim = fresh;
  try {
    io::load_state(sim, st);
  } catch (const InputError& e) {
    std::fprintf(stderr, "%s\n", e.what());
    grain_fuzz::fail("a state that was read could not be loaded");
  }
  if (sim.size() != st.particles.size()) grain_fuzz::fail("not every particle was loaded");
  if (sim.groups().size() != st.groups.size() + 1) grain_fuzz::fail("not every group was added");
}

template <class S>
void read(const S& fresh, const std::string& path) {
  io::ParticleState<S::dimension> st;
  try {
    st = io::read_state_csv(fresh, path);
  } catch (const InputError&) {
    return;
  }
  check_state(fresh, st);
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = grain_fuzz::write_input("state.csv", data, size);
  read(sim3(), path);
  read(sim2(), path);
  return 0;
}
