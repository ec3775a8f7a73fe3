#!/usr/bin/env bash
# Runs one benchmark case of docs/performance.md with grain (1 and 2 OpenMP threads), LIGGGHTS and
# LAMMPS (1 and 2 MPI ranks), one after another, each under /usr/bin/time -v, and prints a table:
# particle-steps per second, grain's speed-up over each peer, maximum resident set size per
# particle, and the end-of-run figures of every run side by side.
#
# Usage: scripts/compare_peers.sh [options] [CASE [SIZE | NX NY [NZ] NWARM NRUN]]
#   CASE   settle3d (default), pack2d or thermal3d (settle3d with heat conduction; LIGGGHTS only
#          among the peers, and the conduction overhead of grain and LIGGGHTS over settle3d
#          measured in the same run)
#   SIZE   1e4 (default) or 1e5, and 1e6 for settle3d and thermal3d: lattice and step counts of
#          the case definition (settle3d 1e4 = 25 25 16, NWARM 1000, NRUN 4000)
#   NX NY [NZ] NWARM NRUN   any other lattice and step counts (NZ for the 3D cases only)
# Options:
#   --peers DIR   folder with the peer inputs liggghts-CASE.in and lammps-CASE.in
#                 (default: $GRAIN_PEERS_DIR, else shared/peers in the folder that holds the
#                 repository)
#   --build DIR   build folder of this script (default: build-peers in the repository); the
#                 logs of each comparison stay in DIR/runs/CASE-N<N>-XXXXXX
#   --codes LIST  comma-separated subset of grain,liggghts,lammps (default: all three)
#   -h, --help    this text
#
# Installs what is missing (liggghts, lammps, OpenMPI, GNU time and grain's build dependencies)
# with apt-get, as root or through sudo, then builds grain's case programs (Release).
set -euo pipefail

repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
peers=${GRAIN_PEERS_DIR:-$repo/../shared/peers}
build=$repo/build-peers
codes=grain,liggghts,lammps

usage() { sed -n '2,24p' "${BASH_SOURCE[0]}" | sed 's/^# \{0,1\}//'; }
die() { echo "compare_peers: $*" >&2; exit 2; }

args=()
while [ $# -gt 0 ]; do
  case $1 in
    --peers) [ $# -ge 2 ] || die "--peers needs a folder"; peers=$2; shift 2 ;;
    --build) [ $# -ge 2 ] || die "--build needs a folder"; build=$2; shift 2 ;;
    --codes) [ $# -ge 2 ] || die "--codes needs a list"; codes=$2; shift 2 ;;
    -h|--help) usage; exit 0 ;;
    -*) die "unknown option $1 (see --help)" ;;
    *) args+=("$1"); shift ;;
  esac
done

case_name=${args[0]:-settle3d}
size=("${args[@]:1}")
case $case_name in
  settle3d|thermal3d) dims=3 ;;
  pack2d) dims=2 ;;
  *) die "unknown case '$case_name' (settle3d, pack2d or thermal3d)" ;;
esac
if [ "$case_name" = thermal3d ] && [[ ,$codes, == *,lammps,* ]] && [ ! -f "$peers/lammps-thermal3d.in" ]; then
  echo "compare_peers: no LAMMPS input for thermal3d; comparing with LIGGGHTS only"
  codes=$(echo ",$codes," | sed 's/,lammps,/,/; s/^,//; s/,$//')
fi
if [ ${#size[@]} -le 1 ]; then
  case $case_name:${size[0]:-1e4} in
    settle3d:1e4|thermal3d:1e4) size=(25 25 16 1000 4000) ;;
    settle3d:1e5|thermal3d:1e5) size=(50 50 40 1000 2000) ;;
    settle3d:1e6|thermal3d:1e6) size=(100 100 100 200 300) ;;
    pack2d:1e4) size=(125 80 1000 4000) ;;
    pack2d:1e5) size=(400 250 1000 2000) ;;
    *) die "unknown size '${size[0]}' for $case_name (1e4, 1e5$([ "$dims" = 3 ] && echo ', 1e6'))" ;;
  esac
fi
[ ${#size[@]} -eq $((dims + 2)) ] || die "$case_name needs $([ "$dims" = 3 ] && echo 'NX NY NZ' || echo 'NX NY') NWARM NRUN"
for v in "${size[@]}"; do [[ $v =~ ^[0-9]+$ ]] || die "'$v' is not a non-negative integer"; done
nx=${size[0]} ny=${size[1]}
if [ "$dims" = 3 ]; then nz=${size[2]}; else nz=1; fi
nwarm=${size[$dims]} nrun=${size[$((dims + 1))]}
n=$((nx * ny * nz))
if [ "$n" -eq 0 ] || [ "$nrun" -eq 0 ]; then die "NX, NY, NZ and NRUN must be >= 1"; fi
want() { [[ ,$codes, == *,$1,* ]]; }
for c in ${codes//,/ }; do
  case $c in grain|liggghts|lammps) ;; *) die "unknown code '$c' in --codes" ;; esac
done

# ------------------------------------------------------------------ packages
packages=(time build-essential cmake libeigen3-dev libboost-dev libbenchmark-dev)
if want liggghts || want lammps; then packages+=(openmpi-bin); fi
if want liggghts; then packages+=(liggghts); fi
if want lammps; then packages+=(lammps); fi
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "installing ${missing[*]}"
  apt=(env DEBIAN_FRONTEND=noninteractive apt-get -qq)
  [ "$(id -u)" -eq 0 ] || apt=(sudo "${apt[@]}")
  "${apt[@]}" update
  "${apt[@]}" install -y --no-install-recommends "${missing[@]}" </dev/null
fi
for c in liggghts lammps; do
  if want $c; then
    [ -f "$peers/$c-$case_name.in" ] || die "no $peers/$c-$case_name.in (give the folder of the peer inputs with --peers)"
  fi
done

# ------------------------------------------------------------------ build
if want grain; then
  echo "building grain's case programs in $build"
  cmake -S "$repo" -B "$build" -DCMAKE_BUILD_TYPE=Release -DGRAIN_BUILD_TESTS=OFF \
    -DGRAIN_BUILD_EXAMPLES=OFF -DGRAIN_BUILD_BENCHMARKS=ON >/dev/null
  cmake --build "$build" -j2 --target case_settle3d case_pack2d case_thermal3d >/dev/null
fi
mkdir -p "$build/runs"
run_dir=$(mktemp -d "$build/runs/$case_name-N$n-XXXXXX")

# ------------------------------------------------------------------ runs
# Every run writes run_dir/<code>-<p>.out (its output), .log (peers' log file) and .time
# (/usr/bin/time -v); one line per run goes to run_dir/results:
# code p rate loop_seconds rss_kb load1 atoms contacts ke rke mean_height cpu_percent, then
# contacts ke rke mean_height after the warm-up steps, then dT_hot dT_cold (thermal3d; 0 otherwise)
results=$run_dir/results
: >"$results"
failed=0
load1() { cut -d' ' -f1 /proc/loadavg; }
suffix() { if [ "$1" != "$case_name" ]; then echo "-$1"; fi; } # file suffix of a side run
rss_kb() { awk -F': ' '/Maximum resident set size/ {print $2}' "$1"; }
cpu_percent() { awk -F': ' '/Percent of CPU this job got/ {sub("%", "", $2); print $2}' "$1"; }
vars=(-var NX "$nx" -var NY "$ny")
[ "$dims" = 3 ] && vars+=(-var NZ "$nz")
vars+=(-var NWARM "$nwarm" -var NRUN "$nrun")
grain_args=("$nx" "$ny")
[ "$dims" = 3 ] && grain_args+=("$nz")
grain_args+=("$nwarm" "$nrun")

run_grain() { # threads [case, default the compared one]
  local t=$1 c=${2:-$case_name} base load
  base=$run_dir/grain-$1$(suffix "$c")
  load=$(load1)
  echo "grain $c, $t thread(s) ..."
  if ! OMP_NUM_THREADS=$t /usr/bin/time -v -o "$base.time" \
      "$build/bench/case_$c" "${grain_args[@]}" >"$base.out" 2>&1; then
    echo "  failed; see $base.out" >&2
    failed=1
    return 0
  fi
  awk -v p="$t" -v rss="$(rss_kb "$base.time")" -v load="$load" -v cpu="$(cpu_percent "$base.time")" '
    { v[$1] = $2 }
    END { printf "grain %s %s %s %s %s %s %s %s %s %s %s %s %s %s %s %s %s\n", p, v["particle_steps_per_s"],
          v["run_seconds"], rss, load, v["N"], v["contacts"], v["ke"], v["rke"], v["mean_height"], cpu,
          v["warm_contacts"], v["warm_ke"], v["warm_rke"], v["warm_mean_height"],
          v["dT_hot"] + 0, v["dT_cold"] + 0 }
  ' "$base.out" >>"$results$(suffix "$c")"
}

run_peer() { # code (liggghts | lammps) ranks [case, default the compared one]
  local code=$1 p=$2 c=${3:-$case_name} base exe load cmd
  base=$run_dir/$1-$2$(suffix "$c")
  case $code in liggghts) exe=liggghts ;; lammps) exe=lmp ;; esac
  cp "$peers/$code-$c.in" "$run_dir/$code-$c.in"
  cmd=("$exe" -in "$code-$c.in" "${vars[@]}" -log "$base.log")
  [ "$p" -gt 1 ] && cmd=(mpirun --allow-run-as-root --oversubscribe -np "$p" "${cmd[@]}")
  load=$(load1)
  echo "$code $c, $p rank(s) ..."
  if ! (cd "$run_dir" && OMP_NUM_THREADS=1 /usr/bin/time -v -o "$base.time" "${cmd[@]}" \
      >"$base.out" 2>&1 </dev/null); then
    echo "  failed; see $base.out" >&2
    failed=1
    return 0
  fi
  # thermo rows: Step Atoms ke rke ncont height ... CPU; the timed run is the last one (an input
  # may start with "run 0"), its end the last row before the last "Loop time" line; the end of the
  # warm-up is the first row of step NWARM (the repeated row at the start of the next run can
  # differ: LAMMPS' contact/atom then counts fewer contacts)
  awk -v code="$code" -v p="$p" -v n="$n" -v nwarm="$nwarm" -v nrun="$nrun" \
      -v rss="$(rss_kb "$base.time")" -v load="$load" -v thermal="$(if [ "$c" = thermal3d ]; then echo 1; else echo 0; fi)" \
      -v cpu="$(cpu_percent "$base.time")" '
    $1 == "Step" { thermo = 1; next }
    /^Loop time of/ {
      ++loops; loop = $4; atoms = r[2]; nc = r[5]; ke = r[3]; rke = r[4]; h = r[6]
      dth = thermal ? r[7] : 0; dtc = thermal ? r[8] : 0
      thermo = 0; next
    }
    thermo && $1 ~ /^[0-9]+$/ && NF >= 7 {
      for (k = 1; k <= NF; ++k) r[k] = $k
      if ($1 == nwarm && !warm++) { wnc = $5; wke = $3; wrke = $4; wh = $6 }
    }
    END {
      if (loops < 2) exit 1
      printf "%s %s %.6g %s %s %s %s %s %s %s %s %s %s %s %s %s %s %s\n", code, p, n * nrun / loop, loop,
             rss, load, atoms, nc, ke, rke, h, cpu, wnc, wke, wrke, wh, dth, dtc
    }
  ' "$base.log" >>"$results$(suffix "$c")" || { echo "  no timed run in $base.log" >&2; failed=1; }
}

echo "case $case_name, N = $n (${size[*]}), logs in $run_dir"
want grain && { run_grain 1; run_grain 2; }
want liggghts && { run_peer liggghts 1; run_peer liggghts 2; }
want lammps && { run_peer lammps 1; run_peer lammps 2; }
if [ "$case_name" = thermal3d ]; then
  # the same mechanics without conduction, one thread / rank, for the overhead of conduction
  want grain && run_grain 1 settle3d
  want liggghts && [ -f "$peers/liggghts-settle3d.in" ] && run_peer liggghts 1 settle3d
fi
load_end=$(load1)

# ------------------------------------------------------------------ report
bit_identical=n/a
if [ -f "$run_dir/grain-1.out" ] && [ -f "$run_dir/grain-2.out" ]; then
  fig='^(warm_)?(contacts|ke|rke|mean_height|dT_hot|dT_cold) '
  if grep -qE "$fig" "$run_dir/grain-1.out" &&
     diff <(grep -E "$fig" "$run_dir/grain-1.out") <(grep -E "$fig" "$run_dir/grain-2.out") >/dev/null; then
    bit_identical=yes
  else
    bit_identical=no
  fi
fi
cpu=$(awk -F': ' '/^model name/ {print $2; exit}' /proc/cpuinfo)
echo
echo "## $case_name, N = $n (${size[*]}: NX NY$([ "$dims" = 3 ] && echo ' NZ') NWARM NRUN)"
echo
echo "$(date -u '+%Y-%m-%d %H:%M UTC'), $(nproc) cores ($cpu), 1-minute load average at the start of each run in the table, $load_end at the end"
echo
awk -v n="$n" -v nwarm="$nwarm" -v identical="$bit_identical" '
  { code[NR] = $1; p[NR] = $2; rate[NR] = $3; rss[NR] = $5; load[NR] = $6; atoms[NR] = $7
    nc[NR] = $8; ke[NR] = $9; rke[NR] = $10; h[NR] = $11; cpu[NR] = $12
    wnc[NR] = $13; wke[NR] = $14; wrke[NR] = $15; wh[NR] = $16; dth[NR] = $17; dtc[NR] = $18
    if ($1 == "grain") grain[$2] = $3
    else if (!($2 in best) || $3 > best[$2]) best[$2] = $3
    if ($1 == "liggghts" && $2 == 1) ref = NR }
  function name(c) { return c == "grain" ? "grain" : c == "liggghts" ? "LIGGGHTS" : "LAMMPS" }
  function rel(a, b) { return b == 0 ? "n/a" : sprintf("%+.2f %%", 100 * (a - b) / b) }
  END {
    if (NR == 0) exit
    print "| code | threads / ranks | particle-steps/s | grain/this | max RSS [B/particle] | CPU | load | contacts | KE [J] | rot. KE [J] | mean height [m] |"
    print "|---|---|---|---|---|---|---|---|---|---|---|"
    for (k = 1; k <= NR; ++k) {
      ratio = code[k] == "grain" ? "" : (p[k] in grain ? sprintf("%.2f", grain[p[k]] / rate[k]) : "n/a")
      printf "| %s | %s | %.3e | %s | %.0f | %s %% | %s | %s | %.6g | %.6g | %.7g |\n", name(code[k]), p[k],
             rate[k], ratio, rss[k] * 1024 / n, cpu[k], load[k], nc[k], ke[k], rke[k], h[k]
      if (atoms[k] != n) printf "\nwarning: %s with %s process(es) ended with %s of %d particles\n\n", name(code[k]), p[k], atoms[k], n
    }
    if (ref) {
      print ""
      print "End-of-run figures relative to LIGGGHTS (1 rank):"
      print ""
      print "| code | threads / ranks | contacts | KE | rot. KE | mean height |"
      print "|---|---|---|---|---|---|"
      for (k = 1; k <= NR; ++k) if (k != ref)
        printf "| %s | %s | %s | %s | %s | %+.2e |\n", name(code[k]), p[k], rel(nc[k], nc[ref]),
               rel(ke[k], ke[ref]), rel(rke[k], rke[ref]), (h[k] - h[ref]) / h[ref]
    }
    print ""
    printf "Figures after the %d warm-up steps:\n\n", nwarm
    print "| code | threads / ranks | contacts | KE [J] | rot. KE [J] | mean height [m] |"
    print "|---|---|---|---|---|---|"
    for (k = 1; k <= NR; ++k)
      printf "| %s | %s | %s | %.6g | %.6g | %.7g |\n", name(code[k]), p[k], wnc[k], wke[k], wrke[k], wh[k]
    print ""
    if ((1 in grain) && (1 in best))
      printf "grain 1 thread / faster peer on 1 rank: %.2f\n", grain[1] / best[1]
    if ((2 in grain) && (2 in best))
      printf "grain 2 threads / faster peer on 2 ranks: %.2f\n", grain[2] / best[2]
    if ((1 in grain) && (2 in grain))
      printf "grain 2 threads / 1 thread: %.2f; end-of-run figures bit-identical: %s\n", grain[2] / grain[1], identical
    if (thermal) {
      print ""
      print "Mean temperature changes of the initially hot (400 K) and cold (300 K) groups:"
      print ""
      print "| code | threads / ranks | dT_hot [K] | dT_cold [K] |"
      print "|---|---|---|---|"
      for (k = 1; k <= NR; ++k) printf "| %s | %s | %.6g | %.6g |\n", name(code[k]), p[k], dth[k], dtc[k]
    }
  }
' thermal="$([ "$case_name" = thermal3d ] && echo 1 || echo 0)" "$results"
if [ "$case_name" = thermal3d ] && [ -f "$results-settle3d" ]; then
  echo
  awk '{ rate[$1] = $3 } END { for (c in rate) print c, rate[c] }' "$results-settle3d" | sort >"$run_dir/settle3d-rates"
  awk '$2 == 1 { print $1, $3 }' "$results" | sort >"$run_dir/thermal3d-rates"
  join "$run_dir/settle3d-rates" "$run_dir/thermal3d-rates" | awk '
    { printf "conduction overhead, %s 1 %s: settle3d %.3e, thermal3d %.3e particle-steps/s: %+.1f %%\n",
             $1 == "grain" ? "grain" : "LIGGGHTS", $1 == "grain" ? "thread" : "rank", $2, $3,
             100 * ($2 / $3 - 1) }'
fi
exit $failed
