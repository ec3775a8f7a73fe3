// A per-particle field must be declared (grain::fields<F> option or a stage's `fields`).
#include <grain/grain.hpp>

struct Charge {
  double value = 0.0; // [C]
};
struct Work {
  double value = 0.0; // [J]
};

using Contact = grain::Interaction<grain::normal::Hertz<>>;

std::size_t compile_fail_undeclared_field() {
  grain::Simulation<grain::Sphere, grain::search::CellList, Contact, grain::fields<Charge>> sim;
#ifdef GRAIN_SHOULD_FAIL
  return sim.field<Work>().size();
#else
  return sim.field<Charge>().size();
#endif
}
