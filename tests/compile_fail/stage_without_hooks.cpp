// A user stage must have at least one hook taking the simulation (a misspelt hook is not one).
#include <grain/grain.hpp>

struct Servo {
#ifdef GRAIN_SHOULD_FAIL
  template <class Sim>
  void after_force(Sim&) {} // misspelt: after_forces
#else
  template <class Sim>
  void after_forces(Sim&) {}
#endif
};

using Contact = grain::Interaction<grain::normal::Hertz<>>;

long compile_fail_stage_without_hooks() {
  grain::Simulation<grain::Sphere, grain::search::CellList, Contact, grain::stages<Servo>> sim;
  sim.steps(1);
  return sim.step_count();
}
