#!/usr/bin/env bash
# Builds grain's doctest executables (grain_unit, grain_physics) with AddressSanitizer and
# UndefinedBehaviorSanitizer and runs them; exits non-zero on the first sanitizer report or
# failing test.
#
#   scripts/sanitize.sh [build-folder]      (default: build-asan)
#
# Environment: JOBS (parallel compiles, default 2), CXX (default g++), and CMAKE_CXX_COMPILER_LAUNCHER
# (e.g. ccache) as for any CMake build. Leaks are checked too (LeakSanitizer, with OpenMP on: the
# runtime has given no report, so nothing is suppressed). The build is heavy (about 40 minutes
# on 2 cores): on a shared machine run it under a lock, e.g. flock <lockfile> scripts/sanitize.sh.
set -euo pipefail
cd "$(dirname "$0")/.."
build="${1:-build-asan}"
jobs="${JOBS:-2}"
flags="-O1 -g -fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer"

cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER="${CXX:-g++}" \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="$flags" \
  -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined" \
  -DGRAIN_BUILD_EXAMPLES=OFF -DGRAIN_BUILD_BENCHMARKS=OFF -DGRAIN_BUILD_TESTS=ON
cmake --build "$build" -j "$jobs" --target grain_unit grain_physics

export ASAN_OPTIONS="halt_on_error=1:abort_on_error=0:detect_leaks=1:strict_init_order=1:check_initialization_order=1:print_stacktrace=1"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"
export OMP_WAIT_POLICY=PASSIVE
status=0
for t in grain_unit grain_physics; do
  echo "== sanitize: $t"
  if ! "$build/tests/$t"; then
    echo "sanitize: $t FAILED (test failure or sanitizer report above)"
    status=1
  fi
done
[ "$status" -eq 0 ] && echo "sanitize: grain_unit and grain_physics ran without a sanitizer report"
exit "$status"
