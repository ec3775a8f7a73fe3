#pragma once
/// \file io.hpp
/// Input/output helpers. They read a simulation and are never included by the core.
#include <grain/io/checkpoint.hpp>
#include <grain/io/compare.hpp>
#include <grain/io/console.hpp>
#include <grain/io/csv.hpp>
#include <grain/io/state_file.hpp>
#include <grain/io/statistics.hpp>
#include <grain/io/vtk.hpp>
