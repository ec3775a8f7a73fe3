#pragma once
/// \file components.hpp
/// The components of a `Simulation` (simulation.hpp) that work on its state: each is a struct of
/// static functions over a `Simulation&`, which declares them friends. They are composed at
/// compile time (no virtual calls, nothing stored); the step order lives in `Simulation`.
///
/// | component             | file               | responsibility                                  |
/// |-----------------------|--------------------|-------------------------------------------------|
/// | `ContactPass<Sim>`    | contact_pass.hpp   | loads of all contacts, then the global loads    |
/// | `HeatStep<Sim>`       | heat.hpp           | conductances, convection, temperature update    |
/// | `Motion<Sim>`         | integration.hpp    | integrator stages, fused Verlet pass, walls     |
/// | `NeighbourRebuild<Sim>` | rebuild.hpp      | when and how the neighbour list is rebuilt      |
/// | `LifecycleStep<Sim>`  | lifecycle.hpp      | removal and activation of particles             |
/// | `Diagnostics<Sim>`    | diagnostics.hpp    | read-only visits of contacts and conductances   |
/// | `TimeStepLimits<Sim>` | time_step.hpp      | the stable limits and the step of a run         |
/// | `VariablePropertyStep<Sim>` | variable_properties.hpp | properties that follow tables, applied |
/// | `StateCheck<Sim>`     | state_check.hpp    | a state gone wrong, overlaps at the start       |
/// | `RadiationStep<Sim>`  | radiation.hpp      | radiation of particles with their surroundings  |
///
/// The public API is declared in `Simulation` (the run: initialize, step, steps, run, the
/// checkpoint, the time step) and in three bases that know their derived class: `SetUp<Sim, D,
/// Contact>` (setup_api.hpp: materials, particles, walls, gravity, damping, bounding box and
/// sinks), `GroupsAndConditions<Sim, D>` (conditions_api.hpp: groups, conditions, variable
/// properties) and `Observables<Sim, D, Contact>` (observables.hpp: wall loads, contact visits,
/// properties, energies).
///
/// The components that own data and need no simulation (tested on their own) are the contact
/// history store (contact/history.hpp), the pair table (pair_table.hpp), the lifecycle decision
/// (lifecycle.hpp), the variable properties (variable_properties.hpp) and the wall loads
/// (wall_loads.hpp).

namespace grain::detail {

template <class Sim>
struct ContactPass;
template <class Sim>
struct HeatStep;
template <class Sim>
struct Motion;
template <class Sim>
struct NeighbourRebuild;
template <class Sim>
struct LifecycleStep;
template <class Sim>
struct Diagnostics;
template <class Sim>
struct TimeStepLimits;
template <class Sim>
struct VariablePropertyStep;
template <class Sim>
struct StateCheck;
template <class Sim>
struct RadiationStep;
template <class Sim, int D, class Contact>
class SetUp;
template <class Sim, int D>
class GroupsAndConditions;
template <class Sim, int D, class Contact>
class Observables;

} // namespace grain::detail
