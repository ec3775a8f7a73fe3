#!/usr/bin/env bash
# A long run and its restart, compared bit for bit (docs/output.md, "Long runs and restarts").
#
# Runs bench/long/long_restart.cpp (target long_restart): settle3d on an NX x NY x NZ lattice
# (default 50 50 40, N = 1e5) for STEPS steps (default 1e5) with binary VTK frames, a CSV history
# and a checkpoint every EVERY steps (default 1e4); then a second process restarts from the
# checkpoint of step MIDDLE (default STEPS / 2) and runs to STEPS. Both on one thread. Prints
# each run's report (wall time, VmHWM and VmRSS after the set-up and at the end, the hash of the
# final positions, velocities and angular velocities), compares the final checkpoints byte for
# byte and the final state hashes, and the output size. Exit status 0 if both are identical.
#
# Usage: scripts/long_run.sh [--build DIR] [--out DIR] [--overlap] [NX NY NZ STEPS EVERY [MIDDLE]]
#   --build DIR  the build folder with long_restart (default: build)
#   --out DIR    where the runs write (default: DIR_OF_BUILD/long_run); emptied first
#   --overlap    start the restart as soon as the middle checkpoint exists, beside the first run
#                (on two free cores: the time of one run instead of one and a half)
set -euo pipefail
cd "$(dirname "$0")/.."
build=build
out=
overlap=0
while [ $# -gt 0 ]; do
  case "$1" in
    --build) build="$2"; shift 2 ;;
    --out) out="$2"; shift 2 ;;
    --overlap) overlap=1; shift ;;
    *) break ;;
  esac
done
nx=${1:-50} ny=${2:-50} nz=${3:-40} steps=${4:-100000} every=${5:-10000}
middle=${6:-$((steps / 2))}
out=${out:-$build/long_run}
program=$build/bench/long_restart
if [ ! -x "$program" ]; then
  echo "long_run: $program not found (cmake --build $build --target long_restart)" >&2
  exit 2
fi
if [ $((middle % every)) -ne 0 ] || [ "$middle" -ge "$steps" ]; then
  echo "long_run: MIDDLE ($middle) must be a multiple of EVERY ($every) below STEPS" >&2
  exit 2
fi
rm -rf "$out"
mkdir -p "$out/full" "$out/restart"
export OMP_NUM_THREADS=1
ckpt() { printf '%s/state_%07d.ckpt' "$1" "$2"; }

start=$(date +%s)
restart() {
  "$program" "$out/restart" "$nx" "$ny" "$nz" "$steps" "$every" "$(ckpt "$out/full" "$middle")" \
    >"$out/restart.txt"
}
echo "== run 1: steps 0 to $steps; run 2: restart from step $middle to $steps"
if [ "$overlap" = 1 ]; then
  "$program" "$out/full" "$nx" "$ny" "$nz" "$steps" "$every" >"$out/full.txt" &
  first=$!
  # the checkpoint appears under its name only once it is whole (written, then renamed)
  while [ ! -e "$(ckpt "$out/full" "$middle")" ]; do
    kill -0 "$first" 2>/dev/null || { wait "$first" || true; echo "long_run: run 1 failed" >&2; exit 1; }
    sleep 5
  done
  restart
  wait "$first"
else
  "$program" "$out/full" "$nx" "$ny" "$nz" "$steps" "$every" >"$out/full.txt"
  restart
fi
echo "== run 1"
cat "$out/full.txt"
echo "== run 2"
cat "$out/restart.txt"
echo "wall time of both: $(($(date +%s) - start)) s"

echo "== comparison"
status=0
if cmp -s "$(ckpt "$out/full" "$steps")" "$(ckpt "$out/restart" "$steps")"; then
  echo "final checkpoints: identical ($(stat -c %s "$(ckpt "$out/full" "$steps")") bytes)"
else
  echo "final checkpoints: DIFFERENT"
  status=1
fi
h1=$(awk '/^state_hash/ {print $2}' "$out/full.txt")
h2=$(awk '/^state_hash/ {print $2}' "$out/restart.txt")
if [ -n "$h1" ] && [ "$h1" = "$h2" ]; then
  echo "final state hash: identical ($h1)"
else
  echo "final state hash: DIFFERENT ($h1, $h2)"
  status=1
fi
echo "output of run 1: $(du -sh "$out/full" | cut -f1) in $(ls "$out/full" | wc -l) files"
echo "output of run 2: $(du -sh "$out/restart" | cut -f1) in $(ls "$out/restart" | wc -l) files"
exit $status
