#pragma once
/// \file version.hpp
/// The single source of grain's version (CMake reads it from here).
#define GRAIN_VERSION_MAJOR 0
#define GRAIN_VERSION_MINOR 1
#define GRAIN_VERSION_PATCH 0
