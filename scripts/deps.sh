#!/usr/bin/env bash
# Installs the Debian packages grain needs for its examples, tests and benchmarks (only those
# that are missing). Uses sudo when not run as root.
set -euo pipefail
# clang and libclang-rt-14-dev (libFuzzer and the sanitizer runtimes) build the fuzz targets of
# fuzz/ (scripts/fuzz.sh, the grain_fuzz_replay test, which is skipped without them)
# pybind11-dev, python3-dev and python3-lib2to3 build the Python module and run Parmec's decks
# (grain-parmec; lib2to3 reads decks written for Python 2; some of Parmec's decks use scipy)
packages=(build-essential cmake libeigen3-dev libboost-dev doctest-dev libbenchmark-dev
          libqhull-dev ccache clang-format clang libclang-rt-14-dev python3-vtk9 python3-numpy
          python3-matplotlib povray pybind11-dev python3-dev python3-lib2to3 python3-scipy)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  apt=(env DEBIAN_FRONTEND=noninteractive apt-get -qq)
  [ "$(id -u)" -eq 0 ] || apt=(sudo "${apt[@]}")
  "${apt[@]}" update
  "${apt[@]}" install -y --no-install-recommends "${missing[@]}" </dev/null
fi
