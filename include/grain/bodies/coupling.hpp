#pragma once
/// \file coupling.hpp
/// A body system (system.hpp: springs, torsion springs, ball joints, unspring rules) inside a
/// particle simulation, as a stage: spheres that collide and are held by springs and joints, next
/// to bodies without contact (analytical and meshed bodies). This is how Parmec treats its
/// particles: every particle is a rigid body of one integrator, spheres are the ones with a
/// shape that takes part in contact.
///
/// ```cpp
/// using Sim = grain::Simulation<grain::Sphere, grain::search::LinkedCells, Contact,
///                               grain::stages<grain::bodies::Coupling>>;
/// auto& c = sim.stage<grain::bodies::Coupling>();
/// const auto b = c.attach(sim, id);                       // the particle becomes body b
/// c.system().add_ball_joint(static_cast<long>(b), pivot); // a pendulum
/// sim.run(1.0);
/// ```
///
/// ## Attached particles
/// `attach(sim, id)` makes a particle of the simulation a body of the system (mass, inertia,
/// orientation, position and velocities from the particle). The particle keeps its shape and
/// its contacts, but forces no longer move it (it becomes `fixed`): the system integrates it.
/// Each step of the simulation (velocity Verlet) runs the system's step around its force
/// evaluation:
///
/// - before the neighbour search (`before_search`): the system's first kick, joint impulses and
///   drift (`BodySystem::begin_step`); the particle is placed at the body's position and
///   orientation, with the velocities the forces of the step should see (the half-step
///   velocities plus half a kick with the forces of the last step, as velocity Verlet predicts
///   them for the other particles);
/// - after the forces (`after_forces`): the particle's contact forces and torques (every load
///   the simulation applied to it except its weight) become the body's external load
///   (`BodySystem::set_external_load`), then gravity, springs and torsion springs, the second
///   kick, the joint impulses and the unspring rules (`BodySystem::finish_step`); the particle
///   takes the body's velocities.
///
/// The system falls under the simulation's gravity (taken again whenever `set_gravity` changes
/// it); its own global damping (`BodySystem::set_damping`) acts on all its bodies, the
/// simulation's on the forces of attached particles. Contact laws see the particle's mass (the
/// body's). A stage that adds forces to attached particles in `after_forces` must come before
/// `Coupling` in the stage list. Attaching or converting a particle between runs re-initialises
/// the simulation; after adding springs or joints between runs, call `sim.initialize()` to have
/// them checked before the next run. An attached particle must not be under a prescribed motion or
/// restraint of the simulation (`fix_velocity`, `fix_omega`, `prescribe_motion`, `restrain`): the
/// body places it every step, so `initialize` refuses the combination (InputError naming the id).
///
/// ## Converted particles
/// `convert(sim, id, options)` turns a particle into an analytical body (Parmec's ANALYTICAL
/// with `particle`): the particle leaves the simulation (with its contacts) and becomes a body
/// without contact, with the particle's mass, inertia, orientation, position and velocities or
/// the values given in `options`; its radius is kept as the body's display radius, so its
/// motion is in the body output (`write_bodies_vtk`, point data `radius`).
///
/// ## Time step
/// The simulation's step is the system's. `initialize` checks it against the system's critical
/// step (`BodySystem::critical`, from the springs and torsion springs) and throws InputError if
/// it is larger; the simulation's automatic step knows only the contacts, so set `time_step`
/// when springs are stiffer than the contacts.
///
/// Requires a 3D simulation integrated with velocity Verlet. Units: SI (m, kg, s, N, rad).

#include <grain/bodies/rigid_body.hpp>
#include <grain/bodies/system.hpp>
#include <grain/core/error.hpp>
#include <grain/core/stages.hpp>
#include <grain/core/vector.hpp>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace grain::bodies {

/// Per-particle field of the coupling stage: the body a particle is (-1: a plain particle).
struct BodyLink {
  std::int32_t body = -1;
};
} // namespace grain::bodies

namespace grain {
/// A particle of a rigid body has an inverse mass of 0 but moves under its contact forces: it is
/// not a fixed particle.
template <>
struct field_traits<bodies::BodyLink> {
  static bool driven(const bodies::BodyLink& f) { return f.body >= 0; }
};
} // namespace grain

namespace grain::bodies {

/// What a converted particle keeps or gets instead (Parmec's ANALYTICAL parameters); an empty
/// member keeps the particle's value.
struct AnalyticalOptions {
  std::optional<double> mass{};              ///< [kg]
  std::optional<Eigen::Matrix3d> inertia{};  ///< about the centre, reference frame [kg m^2]
  std::optional<Eigen::Matrix3d> rotation{}; ///< reference frame -> world (orthonormal)
  std::optional<Vec3> position{};            ///< [m]
  std::string name{};                        ///< default "analytical body (particle <id>)"
};

/// The coupling stage: `grain::stages<grain::bodies::Coupling>`.
class Coupling {
public:
  using fields = grain::fields<BodyLink>;

  BodySystem& system() noexcept { return system_; }
  const BodySystem& system() const noexcept { return system_; }

  /// Makes the particle with this id a body of the system (it keeps colliding); returns the body
  /// index. Call before the run starts or between runs. Throws InputError for an unknown or
  /// already attached particle.
  template <class Sim>
  std::size_t attach(Sim& sim, std::int64_t id) {
    require_simulation<Sim>();
    if constexpr (fits<Sim>) return attach_particle(sim, id);
    return 0;
  }

  /// Turns the particle with this id into an analytical body (it leaves the simulation, see the
  /// file comment); returns the body index. Throws InputError for an unknown or attached
  /// particle and for invalid overrides (RigidBodies::add).
  template <class Sim>
  std::size_t convert(Sim& sim, std::int64_t id, const AnalyticalOptions& o = {}) {
    require_simulation<Sim>();
    if constexpr (fits<Sim>) return convert_particle(sim, id, o);
    return 0;
  }

private:
  template <class Sim>
  std::size_t attach_particle(Sim& sim, std::int64_t id) {
    grain::detail::require(sim.is_active(id), "Coupling::attach", "particle id", id,
                           "the id of an active particle of the simulation");
    const std::size_t i = sim.index_of(id);
    auto& link = sim.template field<BodyLink>();
    grain::detail::require(link[i].body < 0, "Coupling::attach", "particle id", id,
                           "a particle that is not a body yet (it is body " +
                               std::to_string(link[i].body) + ")");
    auto& p = sim.particles();
    RigidBody b = sphere_body(p, i);
    b.radius = 0.0; // drawn by the particle output (the body output shows converted spheres)
    b.name = "body of particle " + std::to_string(id);
    const std::size_t k = system_.add_body(b);
    p.inv_mass[i] = 0.0; // the system moves it
    p.inv_inertia[i] = 0.0;
    link[i].body = static_cast<std::int32_t>(k);
    particle_.resize(system_.bodies().size(), -1);
    particle_[k] = id;
    attached_.push_back(k);
    if (sim.initialized()) sim.initialize(); // between runs: loads and checks now
    return k;
  }

  template <class Sim>
  std::size_t convert_particle(Sim& sim, std::int64_t id, const AnalyticalOptions& o) {
    grain::detail::require(sim.is_active(id), "Coupling::convert", "particle id", id,
                           "the id of an active particle of the simulation");
    const std::size_t i = sim.index_of(id);
    grain::detail::require(sim.template field<BodyLink>()[i].body < 0, "Coupling::convert",
                           "particle id", id, "a particle that is not an attached body");
    RigidBody b = sphere_body(sim.particles(), i);
    if (o.mass) b.mass = *o.mass;
    if (o.inertia) b.inertia = *o.inertia;
    if (o.rotation) b.rotation = *o.rotation;
    if (o.position) b.position = *o.position;
    b.name = o.name.empty() ? "analytical body (particle " + std::to_string(id) + ")" : o.name;
    const std::size_t k = system_.add_body(b); // validates before the particle goes
    sim.remove_particle(id);
    particle_.resize(system_.bodies().size(), -1);
    if (sim.initialized()) sim.initialize(); // between runs: loads and checks now
    return k;
  }

public:
  /// The id of the particle that body b is (attached), or -1.
  std::int64_t particle_of(std::size_t b) const { return b < particle_.size() ? particle_[b] : -1; }
  /// The attached bodies, in the order they were attached.
  const std::vector<std::size_t>& attached() const noexcept { return attached_; }

  // ------------------------------------------------------------------ hooks
  /// Checks the time step against the system's critical step, and that no attached particle is
  /// under a prescribed motion or restraint of the simulation (its body moves it).
  template <class Sim>
  void initialize(Sim& sim) {
    require_simulation<Sim>();
    if constexpr (fits<Sim>) {
      for (const std::size_t k : attached_) {
        const std::int64_t id = particle_[k];
        if (sim.is_active(id) && sim.motion_controlled(id))
          throw InputError("Coupling: particle id = " + std::to_string(id) + " (body " +
                           std::to_string(k) +
                           ") is under a prescribed motion or restraint of the simulation, which "
                           "its body would override; valid: an attached particle without "
                           "fix_velocity, fix_omega, prescribe_motion or restrain (give the "
                           "body's motion in the body system)");
      }
      if (sim.moves()) check_step(sim);
    }
  }

  /// The system's first kick, joint impulses and drift; attached particles placed.
  template <class Sim>
  void before_search(Sim& sim) {
    require_simulation<Sim>();
    if constexpr (fits<Sim>) begin(sim);
  }

  /// Contact loads to the bodies, the system's forces, second kick and joint impulses; attached
  /// particles take the bodies' velocities.
  template <class Sim>
  void after_forces(Sim& sim) {
    require_simulation<Sim>();
    if constexpr (fits<Sim>) finish(sim);
  }

  /// The coupling and its body system in a checkpoint (the program makes the same system and
  /// attaches and converts the same particles before loading).
  template <class Archive>
  void serialize(Archive& ar) {
    std::uint64_t n = attached_.size();
    ar(n);
    if (n != attached_.size())
      throw InputError("checkpoint: attached particles = " + std::to_string(n) +
                       " is invalid; valid: " + std::to_string(attached_.size()) +
                       " (the particles this program attaches, in the same order)");
    ar(particle_, attached_);
    system_.serialize(ar);
    if constexpr (Archive::reading) gravity_set_ = false; // taken again from the simulation
  }

private:
  template <class Sim>
  static constexpr bool fits = Sim::dimension == 3 && Sim::integrator_type::drift_before_forces;

  template <class Sim>
  void check_step(Sim& sim) {
    const double hc = system_.critical();
    if (sim.time_step() > hc)
      throw InputError("Simulation: time_step = " + grain::detail::to_text(sim.time_step()) +
                       " s is above the critical step of the coupled body system; valid range: "
                       "(0, " +
                       grain::detail::to_text(hc) +
                       "] s (the springs' and torsion springs' limit, BodySystem::critical)");
  }

  template <class Sim>
  void begin(Sim& sim) {
    if (!gravity_set_ || gravity_seen_ != sim.gravity_revision()) take_gravity(sim);
    const double h = sim.time_step();
    // half a kick with the loads of the last evaluation (begin_step clears them)
    const RigidBodies& b = system_.bodies();
    kick_v_.resize(b.size());
    kick_w_.resize(b.size());
    for (std::size_t k : attached_) {
      kick_v_[k] = (0.5 * h * b.inv_mass[k]) * b.force[k];
      kick_w_[k] = 0.5 * h * (inverse_world_inertia(b, k) * b.torque[k]);
    }
    system_.set_time(sim.time());
    system_.begin_step(h);
    auto& p = sim.particles();
    const auto& link = sim.template field<BodyLink>();
    for (std::size_t i = 0; i < p.size(); ++i) {
      if (link[i].body < 0) continue;
      const auto k = static_cast<std::size_t>(link[i].body);
      p.position[i] = b.position[k];
      p.orientation[i] = b.orientation[k] * b.axes[k].conjugate();
      // velocities the forces will see: half-step velocities plus half a kick
      p.velocity[i] = b.velocity[k] + kick_v_[k];
      p.omega[i] = b.omega[k] + kick_w_[k];
    }
  }

  template <class Sim>
  void finish(Sim& sim) {
    if (!sim.moves()) return; // a thermal analysis: nothing moves
    auto& p = sim.particles();
    const auto& link = sim.template field<BodyLink>();
    // a particle removed by the simulation (sink, bounding box) leaves its body without load
    for (std::size_t k : attached_)
      system_.set_external_load(k, Vec3::Zero(), Vec3::Zero());
    const Vec3 g = sim.gravity();
    for (std::size_t i = 0; i < p.size(); ++i) {
      if (link[i].body < 0) continue;
      const auto k = static_cast<std::size_t>(link[i].body);
      system_.set_external_load(k, p.force[i] - p.mass[i] * g, p.torque[i]);
    }
    if (sim.initialized()) {
      system_.finish_step(sim.time_step());
    } else { // the initial evaluation of Simulation::initialize
      take_gravity(sim);
      system_.set_time(sim.time());
      system_.initialize();
    }
    const RigidBodies& b = system_.bodies();
    for (std::size_t i = 0; i < p.size(); ++i) {
      if (link[i].body < 0) continue;
      const auto k = static_cast<std::size_t>(link[i].body);
      p.velocity[i] = b.velocity[k];
      p.omega[i] = b.omega[k];
    }
  }

  template <class Sim>
  static void require_simulation() {
    static_assert(Sim::dimension == 3, "grain::bodies::Coupling: rigid bodies are 3D; use it "
                                       "with a 3D simulation (grain::Sphere)");
    static_assert(Sim::integrator_type::drift_before_forces,
                  "grain::bodies::Coupling: the body system is integrated with velocity Verlet; "
                  "use integrate::VelocityVerlet (the default) as the simulation's integrator");
  }
  /// The system takes the simulation's gravity (a change between runs acts from the next force
  /// evaluation on, as for the particles).
  template <class Sim>
  void take_gravity(Sim& sim) {
    system_.replace_gravity(sim.gravity_function());
    gravity_seen_ = sim.gravity_revision();
    gravity_set_ = true;
  }

  BodySystem system_{};
  std::vector<std::int64_t> particle_{}; ///< per body: the attached particle's id, or -1
  std::vector<std::size_t> attached_{};
  std::vector<Vec3> kick_v_{}, kick_w_{}; ///< half kicks of the attached bodies [m/s], [rad/s]
  std::uint64_t gravity_seen_ = 0;
  bool gravity_set_ = false;
};

} // namespace grain::bodies
