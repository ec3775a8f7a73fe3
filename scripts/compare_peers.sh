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
#   --repeat R    R rounds of all runs, one round after the other (default 1); the report adds
#                 the median rate of each code and the ratios of each round and their medians,
#                 so that slow and fast phases of a shared machine touch all codes alike
#   -h, --help    this text
#
# Installs what is missing (liggghts, lammps, OpenMPI, GNU time and grain's build dependencies)
# with apt-get, as root or through sudo, then builds grain's case programs (Release).
set -euo pipefail

repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
peers=${GRAIN_PEERS_DIR:-$repo/../shared/peers}
build=$repo/build-peers
codes=grain,liggghts,lammps
repeat=1

usage() { sed -n '2,27p' "${BASH_SOURCE[0]}" | sed 's/^# \{0,1\}//'; }
die() { echo "compare_peers: $*" >&2; exit 2; }

args=()
while [ $# -gt 0 ]; do
  case $1 in
    --peers) [ $# -ge 2 ] || die "--peers needs a folder"; peers=$2; shift 2 ;;
    --build) [ $# -ge 2 ] || die "--build needs a folder"; build=$2; shift 2 ;;
    --codes) [ $# -ge 2 ] || die "--codes needs a list"; codes=$2; shift 2 ;;
    --repeat)
      [ $# -ge 2 ] && [[ $2 =~ ^[1-9][0-9]*$ ]] || die "--repeat needs a number of rounds >= 1"
      repeat=$2; shift 2 ;;
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
# contacts ke rke mean_height after the warm-up steps, then dT_hot dT_cold (thermal3d; 0 otherwise),
# then the round (1 to R; the files of a run carry -rK when R > 1)
results=$run_dir/results
: >"$results"
failed=0
load1() { cut -d' ' -f1 /proc/loadavg; }
suffix() { if [ "$1" != "$case_name" ]; then echo "-$1"; fi; } # file suffix of a side run
round=1
rsuffix() { if [ "$repeat" -gt 1 ]; then echo "-r$round"; fi; } # file suffix of a round
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
  base=$run_dir/grain-$1$(suffix "$c")$(rsuffix)
  load=$(load1)
  echo "grain $c, $t thread(s) ..."
  if ! OMP_NUM_THREADS=$t /usr/bin/time -v -o "$base.time" \
      "$build/bench/case_$c" "${grain_args[@]}" >"$base.out" 2>&1; then
    echo "  failed; see $base.out" >&2
    failed=1
    return 0
  fi
  awk -v p="$t" -v rss="$(rss_kb "$base.time")" -v load="$load" -v cpu="$(cpu_percent "$base.time")" \
      -v round="$round" '
    { v[$1] = $2 }
    END { printf "grain %s %s %s %s %s %s %s %s %s %s %s %s %s %s %s %s %s %s\n", p, v["particle_steps_per_s"],
          v["run_seconds"], rss, load, v["N"], v["contacts"], v["ke"], v["rke"], v["mean_height"], cpu,
          v["warm_contacts"], v["warm_ke"], v["warm_rke"], v["warm_mean_height"],
          v["dT_hot"] + 0, v["dT_cold"] + 0, round }
  ' "$base.out" >>"$results$(suffix "$c")"
}

run_peer() { # code (liggghts | lammps) ranks [case, default the compared one]
  local code=$1 p=$2 c=${3:-$case_name} base exe load cmd
  base=$run_dir/$1-$2$(suffix "$c")$(rsuffix)
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
      -v cpu="$(cpu_percent "$base.time")" -v round="$round" '
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
      printf "%s %s %.6g %s %s %s %s %s %s %s %s %s %s %s %s %s %s %s %s\n", code, p, n * nrun / loop, loop,
             rss, load, atoms, nc, ke, rke, h, cpu, wnc, wke, wrke, wh, dth, dtc, round
    }
  ' "$base.log" >>"$results$(suffix "$c")" || { echo "  no timed run in $base.log" >&2; failed=1; }
}

echo "case $case_name, N = $n (${size[*]}), $repeat round(s), logs in $run_dir"
for ((round = 1; round <= repeat; ++round)); do
  [ "$repeat" -gt 1 ] && echo "round $round of $repeat"
  # thermal3d: the same mechanics without conduction (settle3d, one thread / rank) right after
  # each code's 1-thread thermal3d run, for the overhead of conduction (adjacent runs, so that
  # the drift of the machine's speed within a round does not enter the ratio)
  thermal=$([ "$case_name" = thermal3d ] && echo 1 || echo 0)
  want grain && {
    run_grain 1
    [ "$thermal" = 1 ] && run_grain 1 settle3d
    run_grain 2
  }
  want liggghts && {
    run_peer liggghts 1
    [ "$thermal" = 1 ] && [ -f "$peers/liggghts-settle3d.in" ] && run_peer liggghts 1 settle3d
    run_peer liggghts 2
  }
  want lammps && { run_peer lammps 1; run_peer lammps 2; }
done
round=1
load_end=$(load1)

# ------------------------------------------------------------------ report
bit_identical=n/a
fig='^(warm_)?(contacts|ke|rke|mean_height|dT_hot|dT_cold) '
for ((round = 1; round <= repeat; ++round)); do
  one=$run_dir/grain-1$(rsuffix).out two=$run_dir/grain-2$(rsuffix).out
  [ -f "$one" ] && [ -f "$two" ] || continue
  if grep -qE "$fig" "$one" && diff <(grep -E "$fig" "$one") <(grep -E "$fig" "$two") >/dev/null; then
    [ "$bit_identical" = no ] || bit_identical=yes
  else
    bit_identical=no
  fi
done
cpu=$(awk -F': ' '/^model name/ {print $2; exit}' /proc/cpuinfo)
echo
echo "## $case_name, N = $n (${size[*]}: NX NY$([ "$dims" = 3 ] && echo ' NZ') NWARM NRUN)"
echo
echo "$(date -u '+%Y-%m-%d %H:%M UTC'), $(nproc) cores ($cpu), 1-minute load average at the start of each run in the table, $load_end at the end"
echo
# awk: the median of the numbers in the blank-separated list s; their sorted list in sorted_
awk_median='
  function median(s,   v, m, a, b, t) {
    m = split(s, v, " ")
    for (a = 2; a <= m; ++a) for (b = a; b > 1 && v[b - 1] + 0 > v[b] + 0; --b) { t = v[b]; v[b] = v[b - 1]; v[b - 1] = t }
    sorted_ = ""
    for (a = 1; a <= m; ++a) sorted_ = sorted_ (a > 1 ? ", " : "") sprintf("%.3g", v[a])
    return m % 2 ? v[(m + 1) / 2] : 0.5 * (v[m / 2] + v[m / 2 + 1])
  }'
awk -v n="$n" -v nwarm="$nwarm" -v identical="$bit_identical" -v rounds="$repeat" "$awk_median"'
  { code[NR] = $1; p[NR] = $2; rate[NR] = $3; rss[NR] = $5; load[NR] = $6; atoms[NR] = $7
    nc[NR] = $8; ke[NR] = $9; rke[NR] = $10; h[NR] = $11; cpu[NR] = $12
    wnc[NR] = $13; wke[NR] = $14; wrke[NR] = $15; wh[NR] = $16; dth[NR] = $17; dtc[NR] = $18
    rd[NR] = $19
    if ($1 == "grain") grain[$19, $2] = $3
    else if (!(($19, $2) in best) || $3 > best[$19, $2]) best[$19, $2] = $3
    if (!(($1, $2) in runs)) order[++nkeys] = $1 SUBSEP $2
    runs[$1, $2] = runs[$1, $2] " " $3
    if ($1 == "liggghts" && $2 == 1 && !ref) ref = NR }
  function name(c) { return c == "grain" ? "grain" : c == "liggghts" ? "LIGGGHTS" : "LAMMPS" }
  function rel(a, b) { return b == 0 ? "n/a" : sprintf("%+.2f %%", 100 * (a - b) / b) }
  # ratios grain[r, a] / other[r, b] of the rounds that have both, as a blank-separated list
  function per_round(which, a, b,   r, s) {
    s = ""
    for (r = 1; r <= rounds; ++r) {
      if (which == "peer" && ((r, a) in grain) && ((r, b) in best)) s = s " " grain[r, a] / best[r, b]
      if (which == "self" && ((r, a) in grain) && ((r, b) in grain)) s = s " " grain[r, a] / grain[r, b]
    }
    return s
  }
  function report(label, s,   m, rs) {
    if (s == "") return
    m = median(s)
    if (rounds == 1) printf "%s: %.2f", label, m
    else printf "%s, per round (sorted): %s; median %.2f", label, sorted_, m
  }
  END {
    if (NR == 0) exit
    printf "| code | threads / ranks |%s particle-steps/s | grain/this | max RSS [B/particle] | CPU | load | contacts | KE [J] | rot. KE [J] | mean height [m] |\n", (rounds > 1 ? " round |" : "")
    printf "|---|---|%s---|---|---|---|---|---|---|---|---|\n", (rounds > 1 ? "---|" : "")
    for (k = 1; k <= NR; ++k) {
      ratio = code[k] == "grain" ? "" : ((rd[k], p[k]) in grain ? sprintf("%.2f", grain[rd[k], p[k]] / rate[k]) : "n/a")
      printf "| %s | %s |%s %.3e | %s | %.0f | %s %% | %s | %s | %.6g | %.6g | %.7g |\n", name(code[k]), p[k],
             (rounds > 1 ? " " rd[k] " |" : ""), rate[k], ratio, rss[k] * 1024 / n, cpu[k], load[k], nc[k], ke[k], rke[k], h[k]
      if (atoms[k] != n) printf "\nwarning: %s with %s process(es) ended with %s of %d particles\n\n", name(code[k]), p[k], atoms[k], n
    }
    if (rounds > 1) {
      print ""
      printf "Particle-steps/s over the %d rounds:\n\n", rounds
      print "| code | threads / ranks | median | all runs (sorted) |"
      print "|---|---|---|---|"
      for (k = 1; k <= nkeys; ++k) {
        split(order[k], cp, SUBSEP)
        m = median(runs[order[k]])
        printf "| %s | %s | %.3e | %s |\n", name(cp[1]), cp[2], m, sorted_
      }
    }
    if (ref) {
      print ""
      printf "End-of-run figures relative to LIGGGHTS (1 rank)%s:\n", (rounds > 1 ? ", round 1" : "")
      print ""
      print "| code | threads / ranks | contacts | KE | rot. KE | mean height |"
      print "|---|---|---|---|---|---|"
      for (k = 1; k <= NR; ++k) if (k != ref && rd[k] == 1) # the figures repeat in every round
        printf "| %s | %s | %s | %s | %s | %+.2e |\n", name(code[k]), p[k], rel(nc[k], nc[ref]),
               rel(ke[k], ke[ref]), rel(rke[k], rke[ref]), (h[k] - h[ref]) / h[ref]
    }
    print ""
    printf "Figures after the %d warm-up steps%s:\n\n", nwarm, (rounds > 1 ? " (round 1)" : "")
    print "| code | threads / ranks | contacts | KE [J] | rot. KE [J] | mean height [m] |"
    print "|---|---|---|---|---|---|"
    for (k = 1; k <= NR; ++k) if (rd[k] == 1)
      printf "| %s | %s | %s | %.6g | %.6g | %.7g |\n", name(code[k]), p[k], wnc[k], wke[k], wrke[k], wh[k]
    print ""
    s = per_round("peer", 1, 1); if (s != "") { report("grain 1 thread / faster peer on 1 rank", s); print "" }
    s = per_round("peer", 2, 2); if (s != "") { report("grain 2 threads / faster peer on 2 ranks", s); print "" }
    s = per_round("self", 2, 1)
    if (s != "") { report("grain 2 threads / 1 thread", s); printf "; end-of-run figures bit-identical: %s\n", identical }
    if (thermal) {
      print ""
      print "Mean temperature changes of the initially hot (400 K) and cold (300 K) groups:"
      print ""
      print "| code | threads / ranks | dT_hot [K] | dT_cold [K] |"
      print "|---|---|---|---|"
      for (k = 1; k <= NR; ++k) if (rd[k] == 1) printf "| %s | %s | %.6g | %.6g |\n", name(code[k]), p[k], dth[k], dtc[k]
    }
  }
' thermal="$([ "$case_name" = thermal3d ] && echo 1 || echo 0)" "$results"
if [ "$case_name" = thermal3d ] && [ -f "$results-settle3d" ]; then
  echo
  # per round: code settle3d-rate thermal3d-rate; the overhead of each round and their median
  awk '{ print $1 "-" $19, $3 }' "$results-settle3d" | sort >"$run_dir/settle3d-rates"
  awk '$2 == 1 { print $1 "-" $19, $3 }' "$results" | sort >"$run_dir/thermal3d-rates"
  join "$run_dir/settle3d-rates" "$run_dir/thermal3d-rates" | awk "$awk_median"'
    { split($1, c, "-"); o = 100 * ($2 / $3 - 1); list[c[1]] = list[c[1]] sprintf(" %+.1f", o); ++m[c[1]]
      all[c[1]] = all[c[1]] " " o; s[c[1]] = $2; t[c[1]] = $3 }
    END {
      for (code in m) {
        k = m[code]
        med = median(all[code])
        who = code == "grain" ? "grain 1 thread" : "LIGGGHTS 1 rank"
        if (k == 1)
          printf "conduction overhead, %s: settle3d %.3e, thermal3d %.3e particle-steps/s: %+.1f %%\n", who, s[code], t[code], med
        else
          printf "conduction overhead, %s, per round:%s %%; median %+.1f %%\n", who, list[code], med
      }
    }' | sort
fi
exit $failed
