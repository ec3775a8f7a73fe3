// The 1st slot of grain::Interaction takes a normal-force model; a tangential model is rejected.
#include <grain/grain.hpp>

#ifdef GRAIN_SHOULD_FAIL
using Normal = grain::tangent::SpringDashpotSlider;
#else
using Normal = grain::normal::Hertz<>;
#endif

using Contact = grain::Interaction<Normal, grain::tangent::SpringDashpotSlider>;

std::size_t compile_fail_normal_slot() {
  grain::Simulation<grain::Sphere, grain::search::CellList, Contact> sim;
  return sim.size();
}
