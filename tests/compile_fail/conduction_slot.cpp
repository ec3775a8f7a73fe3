// The 4th slot of grain::Interaction takes a conduction model; an area correction is rejected.
#include <grain/grain.hpp>
#include <grain/models/conduction/batchelor_obrien.hpp>

#ifdef GRAIN_SHOULD_FAIL
using Conduction = grain::area::None;
#else
using Conduction = grain::conduction::BatchelorOBrien;
#endif

using Contact = grain::Interaction<grain::normal::Hertz<>, grain::tangent::None,
                                   grain::rolling::None, Conduction>;

std::size_t compile_fail_conduction_slot() {
  grain::Simulation<grain::Sphere, grain::search::CellList, Contact> sim;
  return sim.size();
}
