# cmake -DMODE=find_package|add_subdirectory -DGRAIN_SOURCE_DIR=... -DGRAIN_VERSION=...
#       -DCONSUMER_SOURCE_DIR=... -DWORK_DIR=... [-DGENERATOR=...] [-DMAKE_PROGRAM=...]
#       [-DCXX_COMPILER=...] [-DCXX_COMPILER_LAUNCHER=...] -P run_consumer.cmake
#
# find_package:     configures grain alone (tests, examples, benchmarks off), installs it into
#                   WORK_DIR/prefix, checks the files installed (headers, CMake package,
#                   grain-plot, examples), then builds the consumer against that prefix only.
# add_subdirectory: builds the consumer with grain's source tree added as a subdirectory.
# Either way the consumer program is run and must exit with 0.
cmake_minimum_required(VERSION 3.20)

foreach(var MODE GRAIN_SOURCE_DIR GRAIN_VERSION CONSUMER_SOURCE_DIR WORK_DIR)
  if(NOT DEFINED ${var} OR "${${var}}" STREQUAL "")
    message(FATAL_ERROR "run_consumer.cmake: ${var} is not set")
  endif()
endforeach()

set(common_args)
if(GENERATOR)
  list(APPEND common_args -G ${GENERATOR})
endif()
if(MAKE_PROGRAM)
  list(APPEND common_args -DCMAKE_MAKE_PROGRAM=${MAKE_PROGRAM})
endif()
if(CXX_COMPILER)
  list(APPEND common_args -DCMAKE_CXX_COMPILER=${CXX_COMPILER})
endif()
if(CXX_COMPILER_LAUNCHER)
  list(APPEND common_args -DCMAKE_CXX_COMPILER_LAUNCHER=${CXX_COMPILER_LAUNCHER})
endif()

# run(<step> <command...>): runs a command, stops with its output if it fails.
function(run step)
  list(JOIN ARGN " " command)
  message(STATUS "${step}: ${command}")
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${step} failed (${rc}):\n${out}")
  endif()
  set(output "${out}" PARENT_SCOPE)
endfunction()

file(REMOVE_RECURSE ${WORK_DIR})
file(MAKE_DIRECTORY ${WORK_DIR})
set(consumer_build ${WORK_DIR}/consumer-build)

if(MODE STREQUAL "find_package")
  set(prefix ${WORK_DIR}/prefix)
  run("configure grain" ${CMAKE_COMMAND} -S ${GRAIN_SOURCE_DIR} -B ${WORK_DIR}/grain-build
      ${common_args} -DCMAKE_BUILD_TYPE=Release -DCMAKE_INSTALL_PREFIX=${prefix}
      -DGRAIN_BUILD_TESTS=OFF -DGRAIN_BUILD_EXAMPLES=OFF -DGRAIN_BUILD_BENCHMARKS=OFF)
  run("build grain" ${CMAKE_COMMAND} --build ${WORK_DIR}/grain-build)
  run("install grain" ${CMAKE_COMMAND} --install ${WORK_DIR}/grain-build)
  # the headers, the plotting script as a command, and the examples with their headers
  foreach(f include/grain/grain.hpp include/grain/version.hpp bin/grain-plot
            share/grain/examples/example_support.hpp share/grain/examples/drum2d.cpp
            share/grain/examples/servo_wall.hpp)
    if(NOT EXISTS ${prefix}/${f})
      message(FATAL_ERROR "not installed: ${f}")
    endif()
  endforeach()
  file(GLOB_RECURSE config_files ${prefix}/*/grainConfig.cmake)
  if(NOT config_files)
    message(FATAL_ERROR "grainConfig.cmake not installed under ${prefix}")
  endif()
  # the installed package only: no package registries, no source tree
  run("configure consumer" ${CMAKE_COMMAND} -S ${CONSUMER_SOURCE_DIR} -B ${consumer_build}
      ${common_args} -DCMAKE_PREFIX_PATH=${prefix} -DGRAIN_FIND_VERSION=${GRAIN_VERSION}
      -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF -DCMAKE_FIND_USE_SYSTEM_PACKAGE_REGISTRY=OFF)
  file(STRINGS ${consumer_build}/CMakeCache.txt grain_dir REGEX "^grain_DIR:")
  string(REGEX REPLACE "^grain_DIR:[A-Z]+=" "" grain_dir "${grain_dir}")
  file(REAL_PATH "${grain_dir}" grain_dir)
  file(REAL_PATH "${prefix}" real_prefix)
  string(FIND "${grain_dir}/" "${real_prefix}/" at)
  if(NOT at EQUAL 0)
    message(FATAL_ERROR "grain was found in '${grain_dir}', not in the install prefix ${prefix}")
  endif()
  message(STATUS "grain_DIR = ${grain_dir}")
elseif(MODE STREQUAL "add_subdirectory")
  run("configure consumer" ${CMAKE_COMMAND} -S ${CONSUMER_SOURCE_DIR} -B ${consumer_build}
      ${common_args} -DGRAIN_SOURCE_DIR=${GRAIN_SOURCE_DIR})
  if(NOT output MATCHES "grain added from")
    message(FATAL_ERROR "the consumer did not add grain's source tree:\n${output}")
  endif()
else()
  message(FATAL_ERROR "run_consumer.cmake: MODE must be find_package or add_subdirectory, not '${MODE}'")
endif()

run("build consumer" ${CMAKE_COMMAND} --build ${consumer_build})
file(GLOB_RECURSE exe LIST_DIRECTORIES false ${consumer_build}/grain_consumer ${consumer_build}/grain_consumer.exe)
if(NOT exe)
  message(FATAL_ERROR "grain_consumer was not built in ${consumer_build}")
endif()
list(GET exe 0 exe)
# one thread: the program is tiny and ctest may run other tests alongside
run("run consumer" ${CMAKE_COMMAND} -E env OMP_NUM_THREADS=1 ${exe})
message(STATUS "${output}")
