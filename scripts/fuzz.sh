#!/usr/bin/env bash
# Builds grain's libFuzzer targets (fuzz/*_fuzz.cpp, one per reader) with clang++ and runs them.
#
#   scripts/fuzz.sh [seconds-per-target]   fuzz each target for that long (default 60) on a copy
#                                          of its corpus fuzz/corpus/<target>
#   scripts/fuzz.sh --replay               run each target once over its committed corpus only
#                                          (regression check, a few seconds)
#   scripts/fuzz.sh --seeds                rewrite the checkpoint seeds of fuzz/corpus/checkpoint_fuzz
#                                          (after a change of the checkpoint format)
#
# Environment: BUILD (build folder, default build-fuzz), CLANGXX (default clang++), TARGETS
# (space-separated target names, default all). Exits non-zero if a target crashes, leaks, times
# out, exceeds its memory limit, throws anything but grain::InputError or trips a sanitizer; the
# input that did it is left as <build>/crash-*, leak-*, timeout-* or oom-* (minimise it with
# `<build>/<target> -minimize_crash=1 -runs=10000 <file>` and add it to the corpus).
set -euo pipefail
cd "$(dirname "$0")/.."
mode=fuzz
seconds=60
case "${1:-}" in
  --replay) mode=replay ;;
  --seeds) mode=seeds ;;
  "") ;;
  *[!0-9]*) echo "usage: scripts/fuzz.sh [seconds-per-target | --replay | --seeds]" >&2; exit 2 ;;
  *) seconds="$1" ;;
esac
build="${BUILD:-build-fuzz}"
cxx="${CLANGXX:-clang++}"
targets=(${TARGETS:-$(cd fuzz && ls *_fuzz.cpp | sed 's/\.cpp$//')})
# the largest input each target is given (bytes)
max_len() {
  case "$1" in
    checkpoint_fuzz) echo 16384 ;;
    state_csv_fuzz | state_vtk_fuzz) echo 4096 ;;
    mesh_file_fuzz) echo 4096 ;; # a binary STL has 84 + 50 n bytes, a cube in ASCII about 2000
    demlab_runfile_fuzz) echo 4096 ;; # the run files of DEMLab's small projects: 600 to 3500
    *) echo 1024 ;;
  esac
}
flags=(-std=c++20 -O1 -g -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=undefined
       -I include -isystem /usr/include/eigen3
       -Wno-c++2b-extensions) # clang: a lambda of the library without "()" (valid C++23)
# compiles go through the launcher of the CMake builds (ccache) when one is set
launcher=(${CMAKE_CXX_COMPILER_LAUNCHER:-})
mkdir -p "$build"
# without clang++ and its libFuzzer runtime (Debian: clang, libclang-rt-14-dev) nothing is run:
# exit 77, which ctest reports as skipped
probe="$build/probe"
if ! command -v "$cxx" >/dev/null ||
  ! printf '%s\n' '#include <cstddef>' '#include <cstdint>' \
    'extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t*, std::size_t) { return 0; }' |
  "$cxx" -x c++ -fsanitize=fuzzer,address,undefined - -o "$probe" >/dev/null 2>&1; then
  echo "fuzz: $cxx with libFuzzer (-fsanitize=fuzzer) not available; skipped"
  exit 77
fi
for t in "${targets[@]}"; do
  # rebuilt when its source or any header of include/ or fuzz/ is newer than the binary
  if [ ! -x "$build/$t" ] || [ -n "$(find fuzz include -newer "$build/$t" -name '*.[ch]pp' | head -1)" ]; then
    echo "fuzz: building $t"
    "${launcher[@]}" "$cxx" "${flags[@]}" -c "fuzz/$t.cpp" -o "$build/$t.o"
    "$cxx" -fsanitize=fuzzer,address,undefined "$build/$t.o" -o "$build/$t"
  fi
done

# the targets' scratch files (fuzz_support.hpp) go below the build folder, where a run that ends
# in a crash leaves them
mkdir -p "$build/tmp"
TMPDIR="$(cd "$build/tmp" && pwd)"
export TMPDIR
export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1}"
status=0
for t in "${targets[@]}"; do
  corpus="fuzz/corpus/$t"
  case "$mode" in
    seeds)
      [ "$t" = checkpoint_fuzz ] || continue
      GRAIN_FUZZ_WRITE_SEEDS="$corpus" "$build/$t"
      ;;
    replay)
      echo "== fuzz: $t: replay of $(ls "$corpus" | wc -l) inputs"
      if ! "$build/$t" -runs=0 -timeout=10 -rss_limit_mb=2048 -artifact_prefix="$build/" \
        "$corpus" >"$build/$t.replay.log" 2>&1; then
        tail -n 40 "$build/$t.replay.log"
        echo "fuzz: $t FAILED on its corpus"
        status=1
      fi
      ;;
    fuzz)
      work="$build/corpus/$t"
      rm -rf "$work"
      mkdir -p "$work"
      cp "$corpus"/* "$work"/
      echo "== fuzz: $t for $seconds s"
      if ! "$build/$t" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
        -max_len="$(max_len "$t")" -print_final_stats=1 -artifact_prefix="$build/" \
        "$work" >"$build/$t.log" 2>&1; then
        tail -n 60 "$build/$t.log"
        echo "fuzz: $t FAILED"
        status=1
      else
        grep -E '^#[0-9]+[[:space:]]+DONE|stat::number_of_executed_units' "$build/$t.log" || true
      fi
      ;;
  esac
done
exit "$status"
