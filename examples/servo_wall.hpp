#pragma once
/// \file servo_wall.hpp
/// A user stage: a wall whose velocity follows the stress the particles exert on it.
///
/// Each step, after the forces, the stage reads the force on its wall (Simulation::wall_force),
/// turns it into a stress sigma = F . (-d) / A (d the unit direction in which the wall
/// compresses, A the loaded area [m^2]) and sets the wall's velocity along d to
///   v = clamp(gain (sigma_target - sigma), -v_max, v_max)      [m/s],
/// a proportional controller (gain in m/(s Pa)): the wall advances while the stress is below the
/// target and backs off above it. The wall moves with that velocity over the next step.
///
/// The stage knows nothing of the library's loop: it is a plain struct with one hook,
/// `after_forces(sim)`, given to the simulation as `grain::stages<ServoWall<D>>`.

#include <grain/grain.hpp>

#include <algorithm>
#include <cstddef>
#include <stdexcept>
#include <string>

template <int D>
struct ServoWall {
  std::size_t wall = 0;                              ///< index returned by add_wall
  grain::Vec<D> direction = -grain::Vec<D>::UnitY(); ///< unit compression direction
  double area = 1.0;      ///< loaded area [m^2] (2D: wall length x disk thickness)
  double target = 0.0;    ///< target stress [Pa]
  double gain = 0.0;      ///< [m/(s Pa)]
  double max_speed = 0.0; ///< largest wall speed [m/s]
  double stress = 0.0;    ///< stress at the last force evaluation [Pa]

  template <class Sim>
  void after_forces(Sim& sim) {
    if (!(area > 0.0 && gain >= 0.0 && max_speed >= 0.0))
      throw std::invalid_argument("ServoWall: area, gain and max_speed must be > 0, >= 0, >= 0");
    stress = sim.wall_force(wall).dot(-direction) / area;
    const double v = std::clamp(gain * (target - stress), -max_speed, max_speed);
    sim.walls()[wall].options.velocity = v * direction;
  }
};
