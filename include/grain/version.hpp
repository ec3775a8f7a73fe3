#pragma once
/// \file version.hpp
/// The single source of grain's version (CMake reads it from here).
#define GRAIN_VERSION_MAJOR 0
#define GRAIN_VERSION_MINOR 1
#define GRAIN_VERSION_PATCH 0

#define GRAIN_DETAIL_STRINGIFY2(x) #x
#define GRAIN_DETAIL_STRINGIFY(x) GRAIN_DETAIL_STRINGIFY2(x)
/// "major.minor.patch"
#define GRAIN_VERSION_STRING                                                                       \
  GRAIN_DETAIL_STRINGIFY(GRAIN_VERSION_MAJOR)                                                      \
  "." GRAIN_DETAIL_STRINGIFY(GRAIN_VERSION_MINOR) "." GRAIN_DETAIL_STRINGIFY(GRAIN_VERSION_PATCH)
