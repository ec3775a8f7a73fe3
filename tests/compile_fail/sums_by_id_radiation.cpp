// Sums by id do not yet cover the domains of a radiation model.
#include <grain/grain.hpp>
#include <grain/models/conduction/batchelor_obrien.hpp>
#include <grain/models/radiation/zhou_yu_zulli.hpp>

using Contact = grain::Interaction<grain::normal::Hertz<>, grain::tangent::None,
                                   grain::rolling::None, grain::conduction::BatchelorOBrien>;
#ifdef GRAIN_SHOULD_FAIL
using Sim = grain::Simulation<grain::Sphere, grain::search::CellList, Contact,
                              grain::radiation::ZhouYuZulli, grain::sums<grain::by_id>>;
#else
using Sim =
    grain::Simulation<grain::Sphere, grain::search::CellList, Contact, grain::sums<grain::by_id>>;
#endif

std::size_t compile_fail_sums_by_id_radiation() {
  Sim sim;
  return sim.size();
}
