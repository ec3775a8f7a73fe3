// A radiation model needs a thermal contact (one with a conduction model).
#include <grain/grain.hpp>
#include <grain/models/conduction/batchelor_obrien.hpp>
#include <grain/models/radiation/zhou_yu_zulli.hpp>

#ifdef GRAIN_SHOULD_FAIL
using Contact = grain::Interaction<grain::normal::Hertz<>>;
#else
using Contact = grain::Interaction<grain::normal::Hertz<>, grain::tangent::None,
                                   grain::rolling::None, grain::conduction::BatchelorOBrien>;
#endif

std::size_t compile_fail_radiation_needs_heat() {
  grain::Simulation<grain::Sphere, grain::search::CellList, Contact, grain::radiation::ZhouYuZulli>
      sim;
  return sim.size();
}
