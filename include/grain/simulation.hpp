#pragma once
/// \file simulation.hpp
/// `Simulation<Shape, Search, Contact, Options...>`: particles, walls, materials and the solution
/// loop, assembled at compile time with no run-time dispatch. `Options` are optional, in any
/// order: an integrator from grain::integrate (default velocity Verlet), a convection model from
/// grain::convection (default none), a radiation model from grain::radiation (default none), a
/// cell-size method (Voronoi conduction), user stages
/// `grain::stages<S...>` whose hooks run inside the step, and per-particle fields
/// `grain::fields<F...>` (core/stages.hpp), and the order in which contact loads are summed,
/// `grain::sums<grain::by_id>` (core/sums.hpp; default `grain::by_list`).
///
/// One step, in this order:
/// 1. (Verlet only) half kick and drift of particles; walls move;
/// 2. neighbour search: the candidate list is rebuilt if the search says so (never late);
/// 3. per-contact pipeline for particle pairs and particle-wall pairs (forces, torques and, in a
///    thermal simulation, conductances and heat rates);
/// 4. prescribed conditions (forces, torques, heat fluxes and rates of groups); global conditions:
///    gravity, damping (all possibly time functions); convection; radiation; restraints remove the
///    restrained force and torque components;
/// 5. integration (Euler family: particles advance, then walls move; Verlet: second half kick);
///    prescribed motion replaces the integrated motion of its particles; temperatures advance by
///    forward Euler, T += dt Q / (m c); fixed temperatures are set;
/// 6. time advances; wall temperatures follow their time functions;
/// 7. lifecycle: particles that left the bounding box, entered a sink or reached their
///    destruction time are removed (with their contacts), particles whose creation time has come
///    are activated, insertions place the particles due (setup/insertion.hpp); the neighbour
///    list is rebuilt when that happens.
/// User stages: `begin_step` before 1, `before_search` between 1 and 2, `after_forces` between 4
/// and 5, `end_of_step` after 7.
///
/// Analyses (`SimulationParams::analysis`): mechanical (no heat), thermo-mechanical (both, every
/// step; the default when the contact has a conduction model) and thermal (particles never move:
/// contacts and conductances are computed once and reused, only temperatures advance).
///
/// Force accumulation is race-free and deterministic: rows of the half list are cut into chunks
/// whose length depends only on N and on the largest index distance of a pair, never on the
/// number of threads; an odd chunk runs only after the even chunks on both sides, so each
/// particle receives its contributions in a fixed order and the results are bit-identical for
/// any thread count.

#include <grain/conditions/conditions.hpp>
#include <grain/conditions/regions.hpp>
#include <grain/conditions/variable_property.hpp>
#include <grain/contact/frame.hpp>
#include <grain/contact/history.hpp>
#include <grain/core/error.hpp>
#include <grain/core/observer.hpp>
#include <grain/core/stages.hpp>
#include <grain/core/sums.hpp>
#include <grain/core/time_function.hpp>
#include <grain/core/vector.hpp>
#include <grain/integrate/integrators.hpp>
#include <grain/interaction.hpp>
#include <grain/models/convection/none.hpp>
#include <grain/models/radiation/none.hpp>
#include <grain/particles/material.hpp>
#include <grain/particles/shape.hpp>
#include <grain/particles/storage.hpp>
#include <grain/search/periodic.hpp>
#include <grain/search/search.hpp>
#include <grain/setup/insertion.hpp>
#include <grain/simulation/components.hpp>
#include <grain/simulation/conditions_api.hpp>
#include <grain/simulation/contact_pass.hpp>
#include <grain/simulation/diagnostics.hpp>
#include <grain/simulation/heat.hpp>
#include <grain/simulation/id_sums.hpp>
#include <grain/simulation/integration.hpp>
#include <grain/simulation/lifecycle.hpp>
#include <grain/simulation/observables.hpp>
#include <grain/simulation/pair_table.hpp>
#include <grain/simulation/parallel.hpp>
#include <grain/simulation/params.hpp>
#include <grain/simulation/radiation.hpp>
#include <grain/simulation/rebuild.hpp>
#include <grain/simulation/setup_api.hpp>
#include <grain/simulation/stage_hooks.hpp>
#include <grain/simulation/state_check.hpp>
#include <grain/simulation/time_step.hpp>
#include <grain/simulation/variable_properties.hpp>
#include <grain/simulation/wall_loads.hpp>
#include <grain/thermal/cells.hpp>
#include <grain/walls/walls.hpp>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <numbers>
#include <numeric>
#include <optional>
#include <string>
#include <string_view>
#include <thread>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace grain {
template <class Shape, class SearchT, class Contact, class... Options>
class Simulation
    : public detail::SetUp<Simulation<Shape, SearchT, Contact, Options...>,
                           detail::dimension_of<Shape>, Contact>,
      public detail::GroupsAndConditions<Simulation<Shape, SearchT, Contact, Options...>,
                                         detail::dimension_of<Shape>>,
      public detail::Observables<Simulation<Shape, SearchT, Contact, Options...>,
                                 detail::dimension_of<Shape>, Contact> {
  static_assert(
      (detail::is_option<Options>::value && ...),
      "grain::Simulation<Shape, Search, Contact, Options...>: each option must be an "
      "integrator from grain::integrate (e.g. integrate::VelocityVerlet), a "
      "convection model from grain::convection (e.g. convection::RanzMarshall), a "
      "radiation model from grain::radiation (e.g. radiation::ZhouYuZulli), a "
      "cell-size method from grain::cells (e.g. cells::LocalPorosity), a list of user "
      "stages grain::stages<S...>, a list of per-particle fields grain::fields<F...> or a "
      "summation order grain::sums<grain::by_id>");
  static_assert((0 + ... + int(detail::is_integrator<Options>::value)) <= 1 &&
                    (0 + ... + int(detail::is_convection<Options>::value)) <= 1 &&
                    (0 + ... + int(detail::is_radiation<Options>::value)) <= 1 &&
                    (0 + ... + int(detail::is_cell_method<Options>::value)) <= 1 &&
                    (0 + ... + int(detail::is_stages<Options>::value)) <= 1 &&
                    (0 + ... + int(detail::is_sums<Options>::value)) <= 1,
                "grain::Simulation: give at most one integrator, one convection model, one "
                "radiation model, one cell-size method, one grain::stages<...> list and one "
                "grain::sums<...> order");
  static_assert((0 + ... + int(detail::is_cell_method<Options>::value)) == 0 ||
                    Contact::needs_cell_radius,
                "grain::Simulation: a cell-size method is used only by the Voronoi conduction "
                "models (conduction::VoronoiA, conduction::VoronoiB); remove it or use one of "
                "them");

public:
  using IntegratorT =
      typename detail::pick<detail::is_integrator, integrate::VelocityVerlet, Options...>::type;
  using ConvectionT =
      typename detail::pick<detail::is_convection, convection::None, Options...>::type;
  using RadiationT = typename detail::pick<detail::is_radiation, radiation::None, Options...>::type;
  using CellSizeT =
      typename detail::pick<detail::is_cell_method, cells::GlobalPorosity, Options...>::type;
  /// The summation order of the contact loads (grain::sums<grain::by_list> unless given).
  using SumsT = typename detail::pick<detail::is_sums, sums<by_list>, Options...>::type;
  /// True if each particle sums its pair loads in ascending partner id (grain::sums<by_id>).
  static constexpr bool sums_by_id = std::is_same_v<typename SumsT::order, by_id>;
  /// The user stages (grain::stages<S...>) and per-particle fields (grain::fields<F...>, those of
  /// the options first, then those the stages declare).
  using StageList = typename detail::pick<detail::is_stages, stages<>, Options...>::type;
  using FieldList =
      typename detail::all_fields<StageList,
                                  typename detail::field_options<Options...>::type>::type;

private:
  static_assert(ParticleShape<Shape>,
                "grain::Simulation: the 1st argument must be a particle shape, grain::Disk (2D) "
                "or grain::Sphere (3D)");
  static_assert(search::Search<SearchT, detail::dimension_of<Shape>>,
                "grain::Simulation: the 2nd argument must be a neighbour search, "
                "search::AllPairs, search::VerletList or search::CellList, or a search of your "
                "own with validate, skin, due and build (docs/concepts.md)");
  static_assert(ConvectionT::active == false || Contact::thermal,
                "grain::Simulation: a convection model needs a thermal contact: give the "
                "Interaction a conduction model such as conduction::BatchelorOBrien");
  static_assert(!sums_by_id || (!Contact::needs_cell_radius && !RadiationT::active),
                "grain::Simulation: grain::sums<grain::by_id> does not yet cover the fluid cells "
                "of the Voronoi conduction models nor the domains of a radiation model (they sum "
                "over neighbours in search order); use grain::sums<grain::by_list> (the default) "
                "with them");
  static_assert(RadiationT::active == false || Contact::thermal,
                "grain::Simulation: a radiation model needs a thermal contact: give the "
                "Interaction a conduction model such as conduction::BatchelorOBrien");

public:
  static constexpr int dimension = Shape::dimension;
  static constexpr int D = dimension;
  using shape_type = Shape;
  using search_type = SearchT;
  using contact_type = Contact;
  using integrator_type = IntegratorT;
  using convection_type = ConvectionT;
  using radiation_type = RadiationT;
  /// True if particles carry temperatures (the contact has a conduction model).
  static constexpr bool thermal = Contact::thermal;
  using Params = SimulationParams<D, Contact, SearchT, ConvectionT, CellSizeT, RadiationT>;
  /// Particle storage: mechanical fields, plus the thermal state in a thermal simulation.
  using Particles = std::conditional_t<thermal, ThermalParticleArrays<D>, ParticleArrays<D>>;
  using History = typename Contact::template History<D>;
  using V = Vec<D>;
  using A = Angular<D>;
  /// Loops over fewer particles than this run on one thread (a parallel region costs more).
  static constexpr long parallel_threshold = detail::parallel_threshold;
  /// The contact loop (rows from the last down) requests the data of the row 2 x prefetch_rows
  /// rows ahead, and of the partners beyond the chunk of the row prefetch_rows rows ahead...
  static constexpr long prefetch_rows = 16;
  /// ... if the particles of one list span (largest j - i) hold more than prefetch_span_bytes
  /// of the data a row reads or writes per partner (row_bytes [B]). Measured (docs/performance.md):
  /// settle3d N = 1e5 (680 kB) 1.16 x faster, N = 1e6 1.17 x; settle3d N = 1e4 (170 kB) and
  /// pack2d N = 1e5 (64 kB) 3 to 6 % slower with it: their partners come from the caches.
  static constexpr double row_bytes = 3 * sizeof(V) + 2 * sizeof(A) + 2 * sizeof(double);
  static constexpr double prefetch_span_bytes = 256 * 1024;

  explicit Simulation(Params params = {}, Shape shape = {})
      : params_(std::move(params)), shape_(shape) {
    shape_.validate();
    Contact::validate(params_.contact);
    SearchT::validate(params_.search);
    for (int d = 0; d < D; ++d)
      detail::require_finite("Simulation", "gravity component", params_.gravity[d]);
    detail::require_non_negative("Simulation", "damping_translational",
                                 params_.damping_translational);
    detail::require_non_negative("Simulation", "damping_rotational", params_.damping_rotational);
    detail::require_non_negative("Simulation", "time_step", params_.time_step);
    detail::require_in("Simulation", "auto_time_step_factor", params_.auto_time_step_factor, 1e-6,
                       1.0, "(0, 1]");
    detail::require_positive("Simulation", "reference_velocity", params_.reference_velocity);
    detail::require(params_.max_start_overlap >= 0.0, "Simulation", "max_start_overlap",
                    params_.max_start_overlap, "[0, inf] (a fraction of the smaller radius)");
    detail::require(params_.max_step_travel > 0.0, "Simulation", "max_step_travel",
                    params_.max_step_travel, "(0, inf] (a fraction of the radius)");
    if (params_.analysis == Analysis::thermal || params_.analysis == Analysis::thermo_mechanical)
      if (!thermal)
        throw InputError("Simulation: analysis = thermal or thermo-mechanical needs a contact "
                         "with a conduction model; valid for this contact: mechanical or automatic "
                         "(give the Interaction a conduction model such as "
                         "conduction::BatchelorOBrien)");
    detail::require(std::isfinite(params_.initial_temperature) && params_.initial_temperature >= 0,
                    "Simulation", "initial_temperature", params_.initial_temperature, "[0, inf) K");
    params_.fluid.validate();
    detail::require_in("Simulation", "dissipation_heating", params_.dissipation_heating, 0.0, 1.0,
                       "[0, 1]");
    ConvectionT::validate(params_.convection);
    RadiationT::validate(params_.radiation);
    CellSizeT::validate(params_.cells);
    if constexpr (Contact::indirect)
      detail::require_positive("Fluid (conduction through the fluid)", "conductivity",
                               params_.fluid.conductivity);
    if constexpr (ConvectionT::active) {
      detail::require_positive("Fluid (convection)", "viscosity", params_.fluid.viscosity);
      detail::require_positive("Fluid (convection)", "density", params_.fluid.density);
      detail::require_positive("Fluid (convection)", "conductivity", params_.fluid.conductivity);
      detail::require_positive("Fluid (convection)", "heat_capacity", params_.fluid.heat_capacity);
    }
  }

  // ---------------------------------------------------------------- time step
  /// Rayleigh time pi R sqrt(rho/G)/(0.1631 nu + 0.8766) of the smallest particle [s].
  double rayleigh_time() const { return Limits::rayleigh_time(*this); }

  /// Contact-stiffness limit 2 sqrt(m*/k) of the stiffest, lightest contact that can occur [s]
  /// (the stability limit of the undamped oscillator for the symplectic schemes).
  double contact_time_step() const { return Limits::contact_time_step(*this); }

  /// Mechanical critical time step: min(Rayleigh time, contact limit) [s].
  double mechanical_time_step() const { return std::min(rayleigh_time(), contact_time_step()); }

  /// Thermal time scale of the particles, min R^2 rho c / k [s] (infinite without conduction):
  /// the time heat takes to diffuse across a particle. The automatic time step stays below
  /// `auto_time_step_factor` times it.
  double thermal_time_step() const { return Limits::thermal_time_step(*this); }

  /// Stability limit of the explicit temperature update over the contacts of the current
  /// neighbour list (after initialisation; infinite before): 2 / lambda_max [s], lambda_max the
  /// largest eigenvalue of C^-1 (L + K), estimated from above (see simulation/time_step.hpp).
  double conduction_time_step() const { return Limits::conduction_time_step(*this); }
  /// A bound below the conduction limit: min over particles of C_i / (sum_j H_ij + K_i) [s],
  /// K_i the conductance to walls and to the fluid (h_i S_i). A step below it is stable.
  double conduction_bound() const { return Limits::conduction_bound(*this); }

  /// The critical time step [s]: the mechanical one if forces move particles (a moving analysis
  /// with at least one particle that is not fixed, present or to come), and the conduction limit
  /// if temperatures advance.
  double critical_time_step() const {
    double t = std::numeric_limits<double>::infinity();
    if (forces_move()) t = mechanical_time_step();
    if (heats()) t = std::min(t, conduction_time_step());
    return t;
  }

  /// The analysis in use (`automatic` resolved).
  Analysis analysis() const {
    if (params_.analysis != Analysis::automatic) return params_.analysis;
    return thermal ? Analysis::thermo_mechanical : Analysis::mechanical;
  }
  /// True if particles move (every analysis but thermal).
  bool moves() const { return analysis() != Analysis::thermal; }
  /// True if forces move particles: the analysis moves them and some particle, present or to
  /// come, is not fixed (ParticleSpec::fixed). Only then does the mechanical limit bound the
  /// time step.
  bool forces_move() const {
    if (!moves()) return false;
    if (inserts_.active()) return true; // particles to come that are not fixed
    for (std::size_t i = 0; i < particles_.size(); ++i)
      if (!fixed_particle(i)) return true;
    for (const auto& s : life_.pending)
      if (!s.fixed) return true;
    return false;
  }
  /// True if temperatures advance (thermal and thermo-mechanical analyses).
  bool heats() const { return thermal && analysis() != Analysis::mechanical; }

  /// The time step in use [s] (after initialisation).
  double time_step() const { return dt_; }

  // ---------------------------------------------------------------- running
  /// Validates the set-up, fixes the time step, builds the neighbour list and computes the
  /// initial forces. Called by run() and step() when needed; raises InputError on bad input.
  void initialize() {
    Motion::settle_kick(*this);
    // not initialised until the end: the stages' initial evaluation (after_forces) sees a set-up,
    // not a step, and a set-up that throws is checked again by the next run
    initialized_ = false;
    // a re-initialisation (after adding particles, walls or materials) continues the time
    time_offset_ = time_;
    step0_ = step_;
    check_materials();
    // the walls' temperatures and speeds first: wall properties may follow them
    for (auto& w : walls_) {
      w.update_temperature(time_);
      w.update_motion(time_);
    }
    VPStep::apply(*this, true);
    size_search();
    check_periodic();
    if (gravity_fn_) gravity_now_ = (*gravity_fn_)(time_);
    Life::update_walls(*this, time_);
    Neighbours::initial_build(*this);
    // particles outside the bounding box or inside a sink at the start never take part
    if (life_.bounding_box || !life_.sinks.empty()) Life::lifecycle(*this, false);
    Check::start_overlaps(*this);
    ensure_groups();
    cond_.restrain_velocities(particles_);
    if constexpr (thermal) cond_.fix_temperatures(particles_, time_);
    dt_ = Limits::choose(*this);
    start_limits_ = Check::limits_text(*this);
    if constexpr (thermal) {
      if (analysis() == Analysis::thermal) Heat::store_conductances(*this);
    }
    if (params_.track_dissipation && std::isnan(elastic_start_))
      elastic_start_ = this->elastic_energy();
    if (moves()) {
      if constexpr (IntegratorT::drift_before_forces) {
        // forces at the initial positions; histories are not advanced by this evaluation (only
        // the entries with a history are kept aside: at a first start there are none)
        const auto saved = hist_.save();
        Pass::compute_forces(*this, time_, false);
        hist_.restore_all(saved);
        call_stages<Hook::after_forces>();
      }
    }
    initialized_ = true;
    try {
      call_stages<Hook::initialize>();
    } catch (...) {
      initialized_ = false; // a stage rejected the set-up: the next run checks again
      throw;
    }
  }

  /// Advances one time step.
  void step() { advance(false); }

private:
  /// Throws InputError if particles or walls have no material, or a particle of a heated
  /// simulation no heat capacity; warns of particle materials that do not conduct.
  void check_materials() const {
    if (table_.empty() && (particles_.size() > 0 || !walls_.empty()))
      throw InputError("Simulation: no material was added; add_material() first");
    if constexpr (thermal) {
      if (heats()) {
        for (std::size_t i = 0; i < particles_.size(); ++i) {
          const Material& m = table_.material(particles_.material[i]);
          if (!(m.heat_capacity > 0))
            throw InputError("Material '" + m.name +
                             "': heat_capacity = " + detail::to_text(m.heat_capacity) +
                             " J/(kg K) is invalid for a particle of a thermal simulation; valid "
                             "range: (0, inf) J/(kg K)");
        }
        check_conductivities();
        if constexpr (RadiationT::active) {
          bool radiates = false;
          for (std::size_t k = 0; k < table_.size(); ++k)
            radiates = radiates || table_.material(k).emissivity > 0.0;
          if (!radiates && particles_.size() > 0)
            throw InputError(std::string("Simulation (radiation model ") + RadiationT::name +
                             "): every material has emissivity = 0, so no particle radiates; "
                             "valid: an emissivity in (0, 1] for the radiating materials "
                             "(Material::emissivity), or no radiation model");
        }
      }
    }
  }
  /// In a heated simulation whose contacts conduct directly, a particle material of
  /// conductivity 0 (the default) makes the contacts of its particles conduct nothing through
  /// the built-in laws (they insulate): a warning names those materials, once for the same set
  /// (not an error: a program's own conduction law may not use the conductivity).
  void check_conductivities() const {
    if constexpr (thermal && !Contact::indirect) {
      std::vector<char> used(table_.size(), 0);
      for (const auto k : particles_.material)
        used[k] = 1;
      for (const auto& spec : life_.pending)
        used[spec.material] = 1;
      std::string insulating;
      bool any_conducts = false;
      for (std::size_t k = 0; k < used.size(); ++k) {
        if (!used[k]) continue;
        const Material& m = table_.material(static_cast<std::uint32_t>(k));
        if (m.conductivity > 0.0)
          any_conducts = true;
        else
          insulating += (insulating.empty() ? "'" : ", '") + m.name + "'";
      }
      if (insulating.empty()) return;
      if (warned_insulating_ != insulating) {
        warned_insulating_ = insulating;
        detail::warn("Material " + insulating +
                     ": conductivity = 0 W/(m K) (the default) in a thermal simulation: " +
                     (any_conducts ? std::string("its particles conduct no heat through their "
                                                 "contacts (they insulate)")
                                   : std::string("no particle conducts heat through its "
                                                 "contacts")) +
                     "; give Material::conductivity [W/(m K)] if they should conduct");
      }
    }
  }
  /// Throws InputError if the periodic boundaries cannot work with this set-up: a box shorter
  /// than twice the reach of a pair, Lees-Edwards without x and y periodic, a search that does
  /// not list pairs across periodic boundaries, fluid cells (not periodic); sets the image offset.
  void check_periodic() {
    if (periodic_.shear_rate != 0.0 && !(periodic_.axis[0] && periodic_.axis[1]))
      throw InputError("Simulation::set_lees_edwards: a shear with x or y not periodic is "
                       "invalid; valid: set_periodic along x and y first");
    if (!periodic_.on) return;
    if constexpr (!search::PeriodicSearch<SearchT, D>)
      throw InputError(std::string("Simulation::set_periodic: search = '") + SearchT::name +
                       "' is invalid with periodic boundaries; valid: a search with a periodic "
                       "build (search::CellList, VerletList or AllPairs; docs/periodic.md)");
    if constexpr (Contact::needs_cell_radius)
      if (heat_on_)
        throw InputError("Simulation::set_periodic: periodic boundaries with a conduction model "
                         "that needs fluid cells (Voronoi or porosity cell radii) are invalid; "
                         "valid: a conduction model without cell radii");
    const double need = 2.0 * (2.0 * r_max_ + skin_ + std::max(cutoff_, gap_reach_));
    static constexpr const char* names = "xyz";
    for (int d = 0; d < D; ++d)
      if (periodic_.axis[d] && !(periodic_.length[d] >= need))
        throw InputError(std::string("Simulation::set_periodic: the box length along ") + names[d] +
                         " = " + detail::to_text(periodic_.length[d]) +
                         " m is invalid; valid: at least 2 (2 R_max + reach) = " +
                         detail::to_text(need) + " m (R_max = " + detail::to_text(r_max_) +
                         " m; reach = skin + the largest gap a pair acts across)");
    // clumps and rigid bodies place their members from a centre that does not wrap
    for (std::size_t i = 0; i < particles_.size(); ++i)
      if (std::apply([i](const auto&... f) { return (detail::field_driven(f[i]) || ... || false); },
                     fields_))
        throw InputError("Simulation::set_periodic: particle " + std::to_string(particles_.id[i]) +
                         " is moved by a clump or a rigid body, which is invalid with periodic "
                         "boundaries; valid: periodic boundaries with free particles (and walls)");
    image_.resize(particles_.size());
    shear_shift_.resize(particles_.size());
    periodic_.move_to(time_);
  }
  /// The largest radius present or to come, the skin and the conduction cutoff of the search.
  void size_search() {
    // the largest radius present or to come (the actual radii: for_each_size gives the smallest
    // radii of the time-step estimate when a radius varies)
    r_max_ = 0.0;
    for (double r : particles_.radius)
      r_max_ = std::max(r_max_, r);
    for (const auto& s : life_.pending)
      r_max_ = std::max(r_max_, s.radius);
    r_max_ = std::max(r_max_, vprops_.largest_radius());
    r_max_ = std::max(r_max_, inserts_.largest_radius());
    skin_ = moves() ? SearchT::skin(params_.search, r_max_) : 0.0;
    heat_on_ = heats();
    cutoff_ = heats() ? largest_cutoff() : 0.0;
    gap_reach_ = largest_gap_reach();
  }

public:
  /// True if an exception left the state part-way through a step (particles drifted, loads or
  /// histories partly updated, the time not advanced): stepping and saving a checkpoint then
  /// throw InputError; loading a checkpoint continues from whole steps.
  bool interrupted() const { return interrupted_; }
  /// Throws InputError naming `who` if interrupted().
  void require_whole_steps(const char* who) const {
    if (!interrupted_) return;
    throw InputError(std::string(who) +
                     ": simulation = interrupted by an exception in the step from t = " +
                     detail::to_text(time_) + " s (step " + std::to_string(step_) +
                     ") is invalid; its particles are part-way through that step. Valid: a "
                     "simulation at whole steps (load a checkpoint to continue)");
  }

private:
  /// One step; `defer_kick`: the caller steps again before anyone looks at the state, so the
  /// last half kick may be left to the next step's fused pass (see fuse_kick).
  void advance(bool defer_kick) {
    require_whole_steps("Simulation::step");
    if (!initialized_) initialize();
    const auto t0 = std::chrono::steady_clock::now();
    const double dt = dt_;
    if constexpr (thermal)
      for (auto& w : walls_)
        w.update_temperature(time_);
    ensure_groups();
    call_stages<Hook::begin_step>();
    {
      // walls that appear or disappear by the time the step's forces are evaluated
      const double tf = moves() && IntegratorT::drift_before_forces ? time_ + dt : time_;
      if (tf >= next_wall_event_) Life::wall_events(*this, tf);
    }
    // the loads of the step are checked before anything moves (a damping function that turns
    // negative stops the run at whole steps)
    if (moves()) global_loads(IntegratorT::drift_before_forces ? time_ + dt : time_);
    interrupted_ = true; // until the step is complete: an exception leaves part of a step
    if (moves()) {
      if constexpr (IntegratorT::drift_before_forces) {
        Motion::integrate_before(*this, dt);
        Motion::move_walls(*this, dt);
      }
      if constexpr (stages_move) {
        call_stages<Hook::before_search>();
        ensure_groups();
      }
      if (periodic_.sheared())
        periodic_.move_to(IntegratorT::drift_before_forces ? time_ + dt : time_);
      Neighbours::update_neighbors(*this);
      ensure_groups();
      if (heat_on_) Heat::maybe_update_cells(*this);
      Pass::compute_forces(*this, IntegratorT::drift_before_forces ? time_ + dt : time_, true);
      call_stages<Hook::after_forces>();
      if (defer_kick && Motion::fuse_kick(*this))
        kick_pending_ = true;
      else
        Motion::integrate_after(*this, dt);
      if constexpr (!IntegratorT::drift_before_forces) Motion::move_walls(*this, dt);
    } else {
      if constexpr (thermal) Heat::static_heat_rates(*this);
      call_stages<Hook::after_forces>();
    }
    if constexpr (thermal) {
      // with the half kick left pending, the temperatures advance in the same pass (nothing
      // reads them before it; fixed temperatures are set after the update, so not then)
      if (heats()) {
        if (kick_pending_ && cond_.temperatures.empty())
          heat_pending_ = true;
        else
          Heat::integrate_temperature(*this, dt);
      }
    }
    ++step_;
    // time counts whole steps since the last initialisation (no drift from summing dt)
    time_ = static_cast<double>(step_ - step0_) * dt_ + time_offset_;
    // the sliding images at the end of the step (what rebuilds after it and queries see)
    if (periodic_.sheared()) periodic_.move_to(time_);
    interrupted_ = false;
    if constexpr (thermal) {
      for (auto& w : walls_)
        w.update_temperature(time_); // current for output and queries
      if (heats() && !cond_.temperatures.empty()) cond_.fix_temperatures(particles_, time_);
    }
    if (lifecycle_due()) Life::lifecycle(*this);
    if (!vprops_.empty()) VPStep::apply(*this, false);
    call_stages<Hook::end_of_step>();
    counters_.steps += 1;
    counters_.particle_steps += static_cast<double>(particles_.size());
    counters_.wall_seconds +=
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  }

public:
  /// Runs n steps, calling each observer after every step (see io::every).
  template <class... Observers>
  void steps(long n, Observers&&... obs) {
    require(n >= 0, "Simulation::steps", "n", n, "[0, inf)");
    if (!initialized_) initialize();
    if (start_limits_.empty()) start_limits_ = Check::limits_text(*this); // after a load
    (detail::start_observer(obs, *this), ...);
    for (long k = 0; k < n; ++k) {
      if constexpr (sizeof...(Observers) == 0) {
        // nobody looks at the state between these steps: the last half kick of a step may join
        // the next step's first one (the same arithmetic, one pass over the particles less)
        try {
          advance(k + 1 < n);
        } catch (...) {
          Motion::settle_kick(*this);
          throw;
        }
      } else {
        step();
      }
      (obs(*this), ...);
    }
    if (n > 0) Check::particles(*this); // before the last output
    (detail::finish_observer(obs, *this), ...);
  }

  /// Throws NumericalError if the state has gone wrong: a quantity that is not finite, a
  /// particle moving more than its radius per step, the centre of a particle inside another or
  /// behind a plane wall (simulation/state_check.hpp). The output actions (io::every,
  /// io::every_steps) call it before they write; `steps` checks the particles at its end.
  void check_state() const {
    Check::particles(*this);
    Check::overlaps(*this);
  }

  /// Runs for `duration` seconds of simulated time, rounded up to whole steps (a quotient
  /// duration / dt within rounding of a whole number counts as that number, see detail::steps_for).
  template <class... Observers>
  void run(double duration, Observers&&... obs) {
    detail::require_non_negative("Simulation::run", "duration", duration);
    if (!initialized_) initialize();
    const long n = detail::steps_for(duration, dt_);
    end_time_ = time_ + static_cast<double>(n) * dt_;
    steps(n, std::forward<Observers>(obs)...);
  }

  // ---------------------------------------------------------------- checkpoint
  /// Visits the whole run state (not the set-up: materials, walls' options, groups, conditions
  /// and variable properties are made again by the program) with an archive `ar` that reads or
  /// writes each item; used by io::save_checkpoint / io::load_checkpoint. After reading, the
  /// simulation continues exactly as the one that wrote it.
  template <class Archive>
  void serialize(Archive& ar) {
    auto& p = particles_;
    ar(p.id, p.position, p.velocity, p.omega, p.orientation, p.force, p.torque, p.radius, p.mass,
       p.inv_mass, p.inertia, p.inv_inertia, p.material);
    if constexpr (thermal) ar(p.temperature, p.heat_rate, p.heat_capacity, p.inv_heat_capacity);
    std::apply([&](auto&... f) { (ar(f), ...); }, fields_);
    // stages with state to keep across a restart visit it themselves
    detail::serialize_stages(stages_, ar);
    for (auto& w : walls_)
      ar(w.geometry, w.snapshot, w.pivot, w.options.velocity, w.options.omega, w.temperature,
         w.options.active, w.removed, w.present);
    ar(list_.offsets, list_.partners, list_.wall_offsets, list_.walls, list_.max_span);
    id_sums_.invalidate();
    ++list_generation_;
    ar(hist_.pair, hist_.wall, snapshot_);
    ar(dt_, time_, time_offset_, end_time_, r_max_, skin_, reach_, cutoff_, heat_on_);
    if constexpr (Contact::cohesive) ar(gap_reach_);
    ar(static_pairs_, static_walls_, cell_pair_, cell_wall_, steps_since_cells_);
    ar(step_, steps_since_rebuild_, step0_, next_id_, gravity_now_);
    for (auto* v : {&vprops_.values, &vprops_.wall_values})
      ar((*v)[0], (*v)[1], (*v)[2], (*v)[3], (*v)[4], (*v)[5]);
    ar(life_.pending, life_.doomed, life_.removed_ids);
    // reading: the inserted ids join their groups again (at most the particles present or gone)
    inserts_.serialize(ar, cond_.groups, particles_.size() + life_.removed_ids.size());
    ar(counters_.steps, counters_.rebuilds, counters_.particle_steps, work_in_, elastic_start_);
    if (periodic_.on) { // a periodic set-up: its state, marked
      char mark[8] = {'P', 'E', 'R', 'I', 'O', 'D', 'I', 'C'};
      const char expected[8] = {'P', 'E', 'R', 'I', 'O', 'D', 'I', 'C'};
      ar(mark);
      if constexpr (Archive::reading) {
        if (std::memcmp(mark, expected, 8) != 0) {
          const std::string what = "no periodic state (written by a simulation without "
                                   "periodic boundaries)";
          if constexpr (requires { ar.corrupt(what); })
            ar.corrupt(what);
          else
            throw InputError("Simulation: the state read has " + what);
        }
      }
      ar(image_, shear_shift_, periodic_.slide, periodic_.time, periodic_.built_slide);
      if constexpr (Archive::reading) {
        if (image_.size() != particles_.size() || shear_shift_.size() != particles_.size()) {
          const std::string what = "periodic image counts of " + std::to_string(image_.size()) +
                                   " particles for " + std::to_string(particles_.size());
          if constexpr (requires { ar.corrupt(what); })
            ar.corrupt(what);
          else
            throw InputError("Simulation: the state read has " + what);
        }
      }
    }
    ar(initialized_); // true in a checkpoint; false in the copy a load falls back on
    if constexpr (Archive::reading) {
      // what later steps index with or divide by: a corrupt file fails here, not in a step
      if (const std::string bad = Check::loaded(*this); !bad.empty()) {
        if constexpr (requires { ar.corrupt(bad); })
          ar.corrupt(bad);
        else
          throw InputError("Simulation: the state read has " + bad + ", which is invalid");
      }
      Pass::find_fixed(*this);
      if (periodic_.on) periodic_.move_to(time_);
      Neighbours::measure_span(*this);
      interrupted_ = false; // a checkpoint holds whole steps
      wall_loads_.clear(list_.walls.size());
      origin_.clear();
      life_.removal_requests.clear(); // the state read is complete
      fresh_ids_.clear();             // a continued state, not a start
      checked_walls_ = walls_.size();
      next_wall_event_ = -std::numeric_limits<double>::infinity(); // times checked at the next step
      start_limits_.clear(); // computed by the next run, once the loaded state is checked
      groups_dirty_ = true;
      if (vprops_.per_particle && initialized_) Neighbours::refresh_pair_cache(*this);
    }
  }

  /// Sets SimulationParams::time_step [s] of the next runs (0: automatic); checked against the
  /// stable limits when the next run starts. Throws InputError for a step that is not finite
  /// and >= 0.
  void set_time_step(double dt) {
    detail::require(std::isfinite(dt) && dt >= 0.0, "Simulation::set_time_step", "time_step", dt,
                    "[0, inf) s (0: automatic)");
    if (dt == params_.time_step) return;
    params_.time_step = dt;
    initialized_ = false;
  }

  // ---------------------------------------------------------------- read access
  const Particles& particles() const { return particles_; }
  Particles& particles() { return particles_; }
  const std::vector<Wall<D>>& walls() const { return walls_; }
  std::vector<Wall<D>>& walls() { return walls_; }
  const std::vector<Material>& materials() const { return table_.materials(); }
  const Params& params() const { return params_; }
  const Shape& shape() const { return shape_; }
  const NeighborList& neighbor_list() const { return list_; }
  const std::vector<History>& histories() const { return hist_.pair; }
  double time() const { return time_; }
  long step_count() const { return step_; }
  /// True once initialize() has run for the current set-up.
  bool initialized() const { return initialized_; }
  /// End time of the current run() (for progress reports), or the current time.
  double end_time() const { return std::max(end_time_, time_); }
  double skin() const { return skin_; }
  const RunCounters& counters() const { return counters_; }
  /// True if particle i (current index) is fixed (ParticleSpec::fixed): it moves with its
  /// velocities whatever the forces, like a wall. Not a particle that a field marks as driven
  /// (field_traits: a clump member, a particle moved by a rigid-body system), whose inverse mass
  /// is 0 too, but which moves under its contact forces.
  bool fixed_particle(std::size_t i) const {
    if (particles_.inv_mass[i] != 0.0) return false;
    return !std::apply(
        [i](const auto&... f) { return (detail::field_driven(f[i]) || ... || false); }, fields_);
  }

  // ---------------------------------------------------------------- periodic boundaries
  /// Makes axis `axis` (0 = x, 1 = y, 2 = z) periodic over [lo, hi) [m] (docs/periodic.md): a
  /// particle leaving through one side enters through the other, and pairs interact through the
  /// nearest image. Walls stay where they are (they have no images). The length hi - lo must be
  /// at least 2 (2 R_max + reach), checked when the run starts. Particles outside the box are
  /// wrapped into it at the start (their image counts keep their positions).
  void set_periodic(int axis, double lo, double hi) {
    detail::require(axis >= 0 && axis < D, "Simulation::set_periodic", "axis", axis,
                    D == 2 ? "0 (x) or 1 (y)" : "0 (x), 1 (y) or 2 (z)");
    detail::require_finite("Simulation::set_periodic", "lo", lo);
    detail::require_finite("Simulation::set_periodic", "hi", hi);
    detail::require(hi > lo, "Simulation::set_periodic", "hi", hi,
                    "(lo, inf) m, lo = " + detail::to_text(lo) + " m");
    periodic_.set_axis(axis, lo, hi - lo);
    image_.resize(particles_.size());
    shear_shift_.resize(particles_.size());
    initialized_ = false;
  }
  /// Lees-Edwards boundaries: the periodic images above and below the box slide along x at
  /// +-shear_rate L_y [m/s], driving a simple shear flow v_x = shear_rate y [1/s]. x and y must
  /// be periodic (set_periodic).
  void set_lees_edwards(double shear_rate) {
    detail::require_finite("Simulation::set_lees_edwards", "shear_rate", shear_rate);
    periodic_.move_to(time_); // the images slide at the new rate from now on
    periodic_.shear_rate = shear_rate;
    initialized_ = false;
  }
  /// The periodic box (PeriodicBox::on is false without periodic boundaries).
  const PeriodicBox<D>& periodic() const { return periodic_; }
  /// The separation x_j - x_i of particles i and j [m], through the nearest periodic image.
  V separation(std::size_t i, std::size_t j) const {
    return periodic_.separation(particles_.position[i], particles_.position[j]);
  }
  /// The number of periodic boxes particle i has crossed along each axis since it was added
  /// (positive: towards +axis); zero along the axes that are not periodic.
  std::array<std::int32_t, D> image(std::size_t i) const {
    return i < image_.size() ? image_[i] : std::array<std::int32_t, D>{};
  }
  /// The position of particle i as if it had never been wrapped [m]: position + image L (under
  /// Lees-Edwards plus the travel of the sliding boxes along x). Its change over time is the
  /// particle's true displacement.
  V unwrapped_position(std::size_t i) const {
    V x = particles_.position[i];
    if (i >= image_.size()) return x;
    for (int d = 0; d < D; ++d)
      if (periodic_.axis[d]) x[d] += static_cast<double>(image_[i][d]) * periodic_.length[d];
    if (periodic_.sheared()) // the box of image_y slides at image_y gamma L_y
      x[0] += shear_shift_[i] + static_cast<double>(image_[i][1]) * periodic_.slide;
    return x;
  }

  // ---------------------------------------------------------------- stages and fields
  /// The object of user stage S (one of the grain::stages<...> option): set its parameters
  /// before a run, read its results after one.
  template <class S>
  S& stage() {
    static_assert(has_stage<S>(), "Simulation::stage<S>(): S is not one of this simulation's "
                                  "stages; add it to the grain::stages<...> option");
    return std::get<S>(stages_);
  }
  template <class S>
  const S& stage() const {
    static_assert(has_stage<S>(), "Simulation::stage<S>(): S is not one of this simulation's "
                                  "stages; add it to the grain::stages<...> option");
    return std::get<S>(stages_);
  }
  /// The per-particle field F (current particle order; F{} for new particles).
  template <class F>
  std::vector<F>& field() {
    static_assert(FieldStore::template contains<F>,
                  "Simulation::field<F>(): F is not a field of this simulation; add "
                  "grain::fields<F> to its options or declare it in a stage's `using fields = "
                  "grain::fields<...>`");
    return std::get<std::vector<F>>(fields_);
  }
  template <class F>
  const std::vector<F>& field() const {
    static_assert(FieldStore::template contains<F>,
                  "Simulation::field<F>(): F is not a field of this simulation; add "
                  "grain::fields<F> to its options or declare it in a stage's `using fields = "
                  "grain::fields<...>`");
    return std::get<std::vector<F>>(fields_);
  }

private:
  /// Largest gap across which an adhesive normal model acts over all pairs of materials, with an
  /// effective radius up to the largest radius (a particle on a flat wall) [m]; 0 for the others.
  double largest_gap_reach() const { return largest_gap_reach(r_max_); }
  /// The same for particles of radius up to r [m].
  double largest_gap_reach(double r) const {
    if constexpr (Contact::cohesive) {
      double c = 0.0;
      const auto& all = table_.all_parameters();
      for (std::size_t k = 0; k < all.size(); ++k)
        c = std::max(c, Contact::reach(all[k], table_.properties(k), r));
      return c;
    } else {
      return 0.0;
    }
  }
  /// Largest gap across which heat flows over all pairs of materials [m].
  double largest_cutoff() const { return largest_cutoff(r_max_); }
  /// The same for particles of radius up to r [m].
  double largest_cutoff(double r) const {
    double c = Contact::cutoff(params_.contact, r);
    for (const auto& cp : table_.all_parameters())
      c = std::max(c, Contact::cutoff(cp, r));
    return c;
  }
  /// The neighbour distance of a particle of radius r [m]: the largest gap across which the
  /// models act on it (the first seed's NeighbourDistance), with heat if heat flows.
  double neighbour_distance(double r) const {
    return std::max(heat_on_ ? largest_cutoff(r) : 0.0, largest_gap_reach(r));
  }
  static std::string to_text(const V& v) {
    std::string s = "(";
    for (int d = 0; d < D; ++d)
      s += detail::to_text(v[d]) + (d + 1 < D ? ", " : ")");
    return s;
  }
  bool has_particle(std::int64_t id) const {
    if (this->is_active(id)) return true;
    for (const auto& s : life_.pending)
      if (s.id == id) return true;
    return false;
  }
  bool in_group(const std::string& group, std::int64_t id) const {
    const Group& g = this->group(group);
    return g.everything || std::binary_search(g.ids.begin(), g.ids.end(), id);
  }
  std::vector<std::uint32_t> group_walls(std::size_t g) const {
    if (!cond_.groups[g].everything) return cond_.groups[g].walls;
    std::vector<std::uint32_t> all(walls_.size());
    for (std::size_t w = 0; w < all.size(); ++w)
      all[w] = static_cast<std::uint32_t>(w);
    return all;
  }
  /// Refreshes the current indices of the groups (after indices changed or conditions were added).
  void ensure_groups() const {
    if (!groups_dirty_) return;
    groups_dirty_ = false;
    cond_.refresh(particles_.id);
  }
  bool has_conditions() const {
    return cond_.any_prescribed() || !cond_.linear_motion.empty() ||
           !cond_.angular_motion.empty() || !cond_.restraints.empty() ||
           !cond_.temperatures.empty();
  }

  static History history_at(const std::vector<History>& h, std::size_t e) {
    if constexpr (Contact::template stateless<D>)
      return History{};
    else
      return h[e];
  }

  // ---------------------------------------------------------------- neighbours

  /// True if heat crosses wall w: it has a temperature and its material a conductivity above 0
  /// (a wall of zero conductivity insulates, for direct and indirect conduction models alike).
  bool wall_conducts(std::size_t w) const {
    return walls_[w].conducts() &&
           vprops_.wall_conductivity_of(
               w, table_.material(walls_[w].options.material).conductivity) > 0.0;
  }

  /// Throws NumericalError naming the first particle with a quantity that is not finite or a
  /// speed beyond one radius per step (StateCheck::particles). A displacement that is not finite
  /// counts as infinite, so such a particle forces a rebuild, which calls this before sorting by
  /// cell.
  void require_finite_state() const { Check::particles(*this); }

  template <class T>
  static void permute_values(std::vector<T>& v, const std::vector<std::uint32_t>& perm) {
    detail::permute_in_place(v, perm);
  }

  // ---------------------------------------------------------------- loads, shared by the components
  /// Velocities the forces see. With velocity Verlet the state holds v(n+1/2) while forces are
  /// computed; forces use the prediction v(n+1/2) + a(n) dt/2, so that velocity-dependent forces
  /// (dashpots, global damping) are second-order accurate, and tangential springs still
  /// integrate the half-step velocity that moved the particles (ContactGeometry::slip_velocity).
  /// With integrate::VelocityVerletHalfStep every force sees v(n+1/2).
  static constexpr bool predicts_velocity = integrate::predicts_velocity_v<IntegratorT>;

  /// Gravity [m/s^2] and the global damping coefficients (translational [N s/m], rotational
  /// [N m s]) at time t.
  std::tuple<V, double, double> global_loads(double t) {
    if (gravity_fn_) gravity_now_ = (*gravity_fn_)(t);
    double ct = params_.damping_translational, cr = params_.damping_rotational;
    if (damping_fn_) {
      ct = damping_fn_->first(t);
      cr = damping_fn_->second(t);
      if (ct < 0 || cr < 0)
        throw InputError("Simulation::set_damping: damping = " + detail::to_text(std::min(ct, cr)) +
                         " at t = " + detail::to_text(t) + " s is invalid; valid range: [0, inf)");
    }
    return {this->gravity(), ct, cr};
  }

  /// Surface of a particle of radius r [m^2] (a 2D disk: its lateral surface, perimeter times
  /// thickness; a sphere-mass disk: a sphere's).
  double surface_area(double r) const { return shape_.surface(r); }

  const std::vector<V>& force_velocity() const {
    if constexpr (predicts_velocity)
      return vf_;
    else
      return particles_.velocity;
  }
  const std::vector<A>& force_omega() const {
    if constexpr (predicts_velocity && Contact::has_torque)
      return wf_;
    else
      return particles_.omega;
  }

  History& hist(std::vector<History>& h, std::size_t e) {
    if constexpr (Contact::template stateless<D>) {
      static thread_local History empty;
      return empty;
    } else {
      return h[e];
    }
  }

  /// True if angular velocities are integrated from torques: a contact model makes torques, or
  /// a prescribed torque acts.
  bool spins_() const { return Contact::has_torque || !cond_.torques.empty(); }

  // ---------------------------------------------------------------- lifecycle
  bool lifecycle_due() const { return life_.active() || (!inserts_.empty() && inserts_.active()); }
  static constexpr std::uint32_t none = std::numeric_limits<std::uint32_t>::max();

  // ---------------------------------------------------------------- stages and fields
  using StageTuple = typename detail::stage_tuple<StageList>::type;
  using FieldStore = detail::field_tuple<FieldList>;
  using Hook = detail::Hook;
  template <class S>
  static constexpr bool has_stage() {
    return detail::has_stage_in<S, StageList>;
  }
  /// True without user stages (the last half kick of a step may then join the next step's).
  static constexpr bool no_stages = detail::no_stages_in<StageList>;
  /// True if a stage moves particles or walls between the drift and the search: the fused
  /// velocity-Verlet pass (which measures displacements and predicts velocities before it) is
  /// then not used.
  static constexpr bool stages_move = detail::stages_move_in<StageList, Simulation>;
  /// Calls hook H of every stage that has it, in list order.
  template <Hook H>
  void call_stages() {
    detail::call_stages<H>(stages_, *this);
  }
  /// Applies a particle permutation (or removal: a shorter perm) to the fields.
  void permute_fields(const std::vector<std::uint32_t>& perm) {
    std::apply([&](auto&... f) { (permute_values(f, perm), ...); }, fields_);
    if (periodic_.on) {
      permute_values(image_, perm);
      permute_values(shear_shift_, perm);
    }
  }
  /// True if a field excludes pairs from the list (field_traits<F>::excluded).
  static constexpr bool excluding_fields = []<class... F>(fields<F...>) {
    return (detail::excluding_field<F> || ... || false);
  }(FieldList{});
  void check_wall(std::size_t w, const char* what) const {
    if (w >= walls_.size())
      throw InputError(std::string("Simulation::") + what + ": wall index " + std::to_string(w) +
                       " is invalid; valid range: [0, " + std::to_string(walls_.size()) + ")");
  }

  // the components that work on the state (simulation/components.hpp)
  using Pass = detail::ContactPass<Simulation>;
  using Heat = detail::HeatStep<Simulation>;
  using Motion = detail::Motion<Simulation>;
  using Neighbours = detail::NeighbourRebuild<Simulation>;
  using Life = detail::LifecycleStep<Simulation>;
  using Diag = detail::Diagnostics<Simulation>;
  using Limits = detail::TimeStepLimits<Simulation>;
  using VPStep = detail::VariablePropertyStep<Simulation>;
  using Check = detail::StateCheck<Simulation>;
  using Radiation = detail::RadiationStep<Simulation>;
  friend Pass;
  friend Heat;
  friend Motion;
  friend Neighbours;
  friend Life;
  friend Diag;
  friend Limits;
  friend VPStep;
  friend Check;
  friend Radiation;
  friend detail::SetUp<Simulation, D, Contact>;
  friend detail::GroupsAndConditions<Simulation, D>;
  friend detail::Observables<Simulation, D, Contact>;

  StageTuple stages_{};
  typename FieldStore::type fields_{};
  /// What the particles exerted on the walls at the last force evaluation (summed lazily).
  WallLoads<D> wall_loads_;
  void collect_wall_loads() const { wall_loads_.collect(list_, particles_.id, walls_, sums_by_id); }

  Params params_;
  Shape shape_;
  /// The materials, and the properties and contact parameters of their pairs.
  PairTable<Contact> table_{params_.contact, params_.fluid.conductivity};
  Particles particles_;
  std::vector<Wall<D>> walls_;
  NeighborList list_;
  using Histories = ContactHistories<History>;
  Histories hist_; ///< the contact histories of the list entries
  /// With sums by id: the pair loads per list entry and each particle's entries by partner id.
  [[no_unique_address]] std::conditional_t<
      sums_by_id, detail::IdSums<D, Contact::has_torque, thermal>, detail::NoIdSums>
      id_sums_;
  bool kick_pending_ = false; ///< the last step's second half kick is left to the next step
  bool heat_pending_ = false; ///< the last step's temperature update is left to the next step
  History blank_history_{};   ///< a value-initialised history (what a pair without contact has)
  std::vector<V> snapshot_;
  std::vector<V> vf_; ///< velocities seen by the forces (velocity Verlet)
  std::vector<A> wf_; ///< angular velocities seen by the forces (velocity Verlet)
  /// True between `fused_before` and `compute_forces`: vf_, wf_ and the force arrays (gravity,
  /// global damping) are filled, and fused_d2_ holds the largest squared displacement since the
  /// last list build (< 0: not measured).
  bool prefilled_ = false;
  double fused_d2_ = 0.0;
  /// True if some particle is fixed (fixed_particle): the contact pass then checks each touching
  /// pair for the effective mass (found at every list build and checkpoint load).
  bool has_fixed_ = false;
  /// True from the first change of the state in a step until the step is complete: after an
  /// exception inside a step, the simulation refuses to continue or to be saved.
  bool interrupted_ = false;
  double dt_ = 0.0, time_ = 0.0, time_offset_ = 0.0, end_time_ = 0.0;
  double r_max_ = 0.0, skin_ = 0.0, reach_ = 0.0;
  double cutoff_ = 0.0;     ///< largest gap across which heat flows [m]
  double gap_reach_ = 0.0;  ///< largest gap across which an adhesive normal model acts [m]
  PeriodicBox<D> periodic_; ///< periodic boundaries (set_periodic)
  std::vector<std::array<std::int32_t, D>> image_; ///< boxes crossed, per particle (periodic)
  std::vector<double> shear_shift_;                ///< Lees-Edwards shift along x, per particle [m]
  /// The force loop's list span with periodic boundaries, and the rows paired across the slowest
  /// axis of the order (NeighbourRebuild::measure_span).
  std::uint32_t near_span_ = 0, ring_rows_ = 0, ring_from_ = 0;
  /// The first far entry (paired across the slowest axis) of each of the rows [0, ring_rows_).
  std::vector<std::uint32_t> ring_split_;
  /// The periodic image of each list entry's partner, and the shifts of the 3^D images
  /// (NeighbourRebuild::measure_span).
  std::vector<std::uint8_t> image_code_;
  std::array<V, 27> image_shift_{};
  bool heat_on_ = false;
  /// A conducting pair of a static packing (thermal analysis): particles i and j (or wall j).
  struct StaticConductance {
    std::uint32_t i, j;
    double conductance;
  };
  std::vector<StaticConductance> static_pairs_, static_walls_;
  std::vector<double> cell_pair_, cell_wall_; ///< fluid-cell radius per list entry [m]
  long steps_since_cells_ = 0;
  long step_ = 0, steps_since_rebuild_ = 0;
  long step0_ = 0; ///< step count at the last initialisation (time is counted from there)
  std::int64_t next_id_ = 0;
  bool initialized_ = false;
  // variable properties
  VariableProperties<D> vprops_;          ///< properties that follow tables, per-particle values
  detail::RadiationDomains<D> radiation_; ///< candidates of the radiation domains (if a model)
  std::vector<PairProperties> pair_cache_,
      wall_pair_cache_; ///< per list entry, when vprops_.per_particle
  // energy bookkeeping (SimulationParams::track_dissipation)
  bool tracking_ = false;         ///< accumulating in the current force evaluation
  std::vector<double> work_rows_; ///< power delivered by the contacts of each row and damping [W]
  double work_in_ = 0.0;          ///< work delivered to the bodies by contacts and damping [J]
  double elastic_start_ = std::numeric_limits<double>::quiet_NaN(); ///< elastic energy at start [J]
  mutable detail::ConditionSet<D> cond_; ///< (its indices are refreshed lazily)
  mutable bool groups_dirty_ = true;
  std::optional<VectorTimeFunction<D>> gravity_fn_;
  std::uint64_t gravity_revision_ = 0;
  V gravity_now_ = V::Zero();
  std::optional<std::pair<TimeFunction, TimeFunction>> damping_fn_;
  std::optional<std::pair<VectorTimeFunction<D>, AngularTimeFunction<D>>> mass_damping_;
  // lifecycle
  Lifecycle<D> life_;             ///< particles to come, destruction times, bounding box, sinks
  detail::Insertions<D> inserts_; ///< insertions of particles during the run, and their state
  /// After removal / activation: the index in the neighbour list's arrays of the particle now at
  /// index k (`none` for a new one); empty = unchanged indices.
  std::vector<std::uint32_t> origin_;
  RunCounters counters_;
  /// Counts the neighbour lists made (and read from checkpoints): what was made from a list
  /// notes the count it was made for.
  std::uint64_t list_generation_ = 0;
  // state checks (StateCheck)
  std::vector<std::int64_t> fresh_ids_; ///< particles added since the last start
  std::size_t checked_walls_ = 0;       ///< walls below this index were there at the last start
  double next_wall_event_ = std::numeric_limits<double>::infinity(); ///< a wall (dis)appears
  std::string start_limits_;              ///< the stable limits at the start, for messages
  mutable std::string warned_insulating_; ///< the materials of the last conductivity warning
};

} // namespace grain
