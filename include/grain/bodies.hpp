#pragma once
/// \file bodies.hpp
/// The umbrella header of the rigid-body part of grain (namespace grain::bodies): rigid bodies
/// and their integration, meshed bodies, equivalent masses and critical steps, translational and
/// torsion springs, unspring rules, the body system with ball joints, and its output (CSV
/// histories, VTK files), and the stage that runs a body system inside a particle simulation
/// (coupling.hpp). It is separate from <grain/grain.hpp> because the ball-joint solver
/// brings in Eigen's sparse modules, which particle-only programs do not need.

#include <grain/bodies/coupling.hpp>
#include <grain/bodies/eqm.hpp>
#include <grain/bodies/mesh.hpp>
#include <grain/bodies/output.hpp>
#include <grain/bodies/rigid_body.hpp>
#include <grain/bodies/spring.hpp>
#include <grain/bodies/system.hpp>
#include <grain/bodies/torsion_spring.hpp>
#include <grain/bodies/unspring.hpp>
