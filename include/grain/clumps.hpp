#pragma once
/// \file clumps.hpp
/// Clumps: rigid aggregates of overlapping spheres or disks as a simulation stage
/// (`grain::stages<grain::Clumps<D>>`), and the mass properties of unions of spheres and disks.
/// Not included by grain.hpp; see docs/clumps.md.

#include <grain/clumps/clumps.hpp>
#include <grain/clumps/union_mass.hpp>
