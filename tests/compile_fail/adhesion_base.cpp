// normal::Dmt and normal::Capillary add adhesion to an elastic normal model; a base that is not
// a normal-force model is rejected with a message that names the remedy.
#include <grain/grain.hpp>

#ifdef GRAIN_SHOULD_FAIL
using Normal = grain::normal::Capillary<grain::tangent::Mindlin>;
#else
using Normal = grain::normal::Capillary<grain::normal::Hertz<>>;
#endif

using Contact = grain::Interaction<Normal, grain::tangent::Mindlin>;

std::size_t compile_fail_adhesion_base() {
  grain::Simulation<grain::Sphere, grain::search::CellList, Contact> sim;
  return sim.size();
}
