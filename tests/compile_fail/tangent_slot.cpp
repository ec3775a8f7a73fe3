// The 2nd slot of grain::Interaction takes a tangential-force model; a normal model is rejected.
#include <grain/grain.hpp>

#ifdef GRAIN_SHOULD_FAIL
using Tangent = grain::normal::LinearSpringDashpot;
#else
using Tangent = grain::tangent::SpringDashpotSlider;
#endif

using Contact = grain::Interaction<grain::normal::Hertz<>, Tangent>;

std::size_t compile_fail_tangent_slot() {
  grain::Simulation<grain::Sphere, grain::search::CellList, Contact> sim;
  return sim.size();
}
