// Bodies coupled to a simulation are 3D rigid bodies: a 2D simulation cannot carry them.
#include <grain/bodies/coupling.hpp>
#include <grain/grain.hpp>

using Contact = grain::Interaction<grain::normal::Hertz<>>;
#ifdef GRAIN_SHOULD_FAIL
using Shape = grain::Disk;
#else
using Shape = grain::Sphere;
#endif

long compile_fail_coupling_3d() {
  grain::Simulation<Shape, grain::search::CellList, Contact, grain::stages<grain::bodies::Coupling>>
      sim;
  sim.stage<grain::bodies::Coupling>().attach(sim, 0);
  sim.steps(1);
  return sim.step_count();
}
