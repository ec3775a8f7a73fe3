// io::compare takes a scenario in one of two generic forms; anything else is rejected with the
// library's message.
#include <grain/grain.hpp>

using Contact = grain::Interaction<grain::normal::Hertz<>, grain::tangent::None,
                                   grain::rolling::None, grain::conduction::BatchelorOBrien>;
template <class C>
using Sim = grain::Simulation<grain::Disk, grain::search::AllPairs, C>;

grain::io::Comparison compile_fail_compare_scenario() {
  auto mean = grain::io::column("T [K]", [](const auto& s) { return s.mean_temperature(); });
#ifdef GRAIN_SHOULD_FAIL
  auto scenario = [](int) {};
#else
  auto scenario = [](auto& sim) {
    const auto m = sim.add_material({.name = "steel",
                                     .density = 7800.0,
                                     .young = 2e11,
                                     .conductivity = 40.0,
                                     .heat_capacity = 500.0});
    sim.add_particle({.position = grain::Vec2(0.0, 0.0), .radius = 1e-3, .material = m});
  };
#endif
  return grain::io::compare<Sim>(grain::variants<Contact>{}, scenario, {.steps = 1}, mean);
}
