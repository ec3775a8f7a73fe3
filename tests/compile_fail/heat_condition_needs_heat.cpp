// A heat condition (heat rate, heat flux, fixed temperature) needs a thermal simulation.
#include <grain/grain.hpp>
#include <grain/models/conduction/batchelor_obrien.hpp>

#ifdef GRAIN_SHOULD_FAIL
using Contact = grain::Interaction<grain::normal::Hertz<>>;
#else
using Contact = grain::Interaction<grain::normal::Hertz<>, grain::tangent::None,
                                   grain::rolling::None, grain::conduction::BatchelorOBrien>;
#endif

std::size_t compile_fail_heat_condition_needs_heat() {
  grain::Simulation<grain::Sphere, grain::search::CellList, Contact> sim;
  sim.prescribe_heat_rate("all", 1.0);
  return sim.size();
}
