// Fuzz target of grain::io::load_checkpoint: any file either loads (into a fresh simulation of
// the type that wrote it) or is rejected with grain::InputError, and a rejected load leaves the
// simulation as it was.
//
// Two simulation types are tried with every input: 3D spheres with Hertz-Mindlin and
// Batchelor-O'Brien conduction (thermal; a wall, a group with a prescribed force, a fixed
// temperature, a particle created late), and 3D spheres with the linear spring-dashpot preset.
//
// With GRAIN_FUZZ_STEPS=<k> set, a simulation that loaded also runs k steps (InputError and
// NumericalError allowed): this finds states the loader accepts that a run cannot use.
//
// Seed corpus: run the target with GRAIN_FUZZ_WRITE_SEEDS=<folder> set; it writes a checkpoint
// of each simulation type (after a few steps, and before the late particle is created) into the
// folder and exits (scripts/fuzz.sh --seeds does this for fuzz/corpus/checkpoint_fuzz).

#include "fuzz_support.hpp"

#include <grain/grain.hpp>
#include <grain/models/conduction/batchelor_obrien.hpp>

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

namespace {

using namespace grain;

using Thermal =
    Interaction<normal::Hertz<>, tangent::Mindlin, rolling::None, conduction::BatchelorOBrien>;
using ThermalSim = Simulation<Sphere, search::CellList, Thermal>;
using LinearSim = Simulation<Sphere, search::CellList, presets::LinearCoulomb>;

template <class S>
S make() {
  typename S::Params prm;
  prm.time_step = 2e-6;
  prm.gravity = Vec3(0, 0, -9.81);
  prm.max_start_overlap = 0.25; // the pile starts up to 0.17 R into itself
  S sim(prm);
  Material m;
  m.density = 2500;
  m.young = 1e7;
  m.friction = 0.4;
  m.conductivity = 1;
  m.heat_capacity = 800;
  const auto k = sim.add_material(m);
  WallOptions<3> wall;
  wall.material = k;
  if constexpr (S::thermal) wall.temperature = 350.0;
  sim.add_wall(walls::Plane{{0, 0, 0}, {0, 0, 1}}, wall);
  std::vector<std::int64_t> ids;
  for (int i = 0; i < 2; ++i)
    for (int l = 0; l < 2; ++l) {
      ParticleSpec<3> p{.position = {0.0195 * i, 0.001 * l, 0.0099 + 0.0195 * l},
                        .radius = 0.01,
                        .material = k,
                        .velocity = {0.05 * l, -0.02 * i, 0}};
      if constexpr (S::thermal) p.temperature = 300.0 + 5 * l;
      ids.push_back(sim.add_particle(p));
    }
  ParticleSpec<3> late{.position = {0.03, 0.03, 0.2},
                       .radius = 0.008,
                       .material = k,
                       .creation_time = 1.0,
                       .destruction_time = 2.0};
  if constexpr (S::thermal) late.temperature = 400.0;
  sim.add_particle(late);
  sim.add_group("top", {ids.back()});
  sim.prescribe_force("top", VectorTimeFunction<3>(TimeFunction::constant(0.1), 0.0, 0.0));
  if constexpr (S::thermal) {
    sim.add_group("held", {ids.front()});
    sim.fix_temperature("held", 380.0);
  }
  sim.initialize();
  return sim;
}

/// Loads the file into a copy of `fresh`; InputError is the only way to refuse it, and a refused
/// load leaves the simulation as it was.
template <class S>
void load(const S& fresh, const std::string& path) {
  S sim = fresh;
  try {
    io::load_checkpoint(sim, path);
  } catch (const InputError&) {
    if (sim.size() != fresh.size() || sim.step_count() != fresh.step_count() ||
        sim.particles().position != fresh.particles().position)
      grain_fuzz::fail("a refused load changed the simulation");
    return;
  }
  if (sim.particles().position.size() != sim.size() ||
      sim.particles().material.size() != sim.size())
    grain_fuzz::fail("loaded particle arrays of different lengths");
  static const long steps = [] {
    const char* k = std::getenv("GRAIN_FUZZ_STEPS");
    return k ? std::atol(k) : 0L;
  }();
  if (steps > 0) {
    try {
      sim.steps(steps);
    } catch (const InputError&) {
    } catch (const NumericalError&) {
    }
  }
}

template <class S>
void write_seeds(const S& fresh, const std::filesystem::path& dir, const std::string& name) {
  S sim = fresh;
  sim.steps(5);
  io::save_checkpoint(sim, (dir / (name + "_5_steps.ckpt")).string());
  sim.steps(200);
  io::save_checkpoint(sim, (dir / (name + "_205_steps.ckpt")).string());
}

const ThermalSim& thermal_sim() {
  static const ThermalSim s = make<ThermalSim>();
  return s;
}
const LinearSim& linear_sim() {
  static const LinearSim s = make<LinearSim>();
  return s;
}

} // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  if (const char* dir = std::getenv("GRAIN_FUZZ_WRITE_SEEDS")) {
    std::filesystem::create_directories(dir);
    write_seeds(thermal_sim(), dir, "thermal");
    write_seeds(linear_sim(), dir, "linear");
    std::exit(0);
  }
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = grain_fuzz::write_input("run.ckpt", data, size);
  load(thermal_sim(), path);
  load(linear_sim(), path);
  return 0;
}
