#pragma once
/// \file io.hpp
/// Input/output helpers: outputs that read a simulation, checkpoints, and triangle meshes from
/// mesh files. They are never included by the core.
#include <grain/io/checkpoint.hpp>
#include <grain/io/compare.hpp>
#include <grain/io/console.hpp>
#include <grain/io/contact_records.hpp>
#include <grain/io/csv.hpp>
#include <grain/io/mesh_file.hpp>
#include <grain/io/state_file.hpp>
#include <grain/io/statistics.hpp>
#include <grain/io/vtk.hpp>
