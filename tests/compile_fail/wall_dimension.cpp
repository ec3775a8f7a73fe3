// add_wall accepts only the wall types of the simulation's dimension: no plane in 2D.
#include <grain/grain.hpp>

using Contact = grain::Interaction<grain::normal::Hertz<>, grain::tangent::SpringDashpotSlider>;

std::uint32_t compile_fail_wall_dimension() {
  grain::Simulation<grain::Disk, grain::search::CellList, Contact> sim;
  sim.add_material({.name = "steel", .density = 7800.0, .young = 2e11});
#ifdef GRAIN_SHOULD_FAIL
  return sim.add_wall(grain::walls::Plane{});
#else
  return sim.add_wall(grain::walls::Segment{grain::Vec2(0.0, 0.0), grain::Vec2(1.0, 0.0)});
#endif
}
