#!/usr/bin/env python3
"""Runs benchmark commands alternately and compares their speeds within each round.

    scripts/alternate.py ROUNDS THREADS "label|command" ["label|command" ...]

Each round runs every command once, in the order given, with OMP_NUM_THREADS=THREADS and pinned
to the first THREADS cores (taskset). A command must print "particle_steps_per_s VALUE" (the
benchmark cases and the hand-written loop do). The script prints, per command, the median rate
and the runs, and, for every command after the first, the median over rounds of its rate
divided by the first command's rate in the same round: on a machine whose speed drifts, only
such same-round ratios are meaningful (docs/performance.md).
"""
import os
import re
import statistics
import subprocess
import sys


def main():
    if len(sys.argv) < 4:
        sys.exit(__doc__)
    rounds, threads = int(sys.argv[1]), int(sys.argv[2])
    cases = [a.split("|", 1) for a in sys.argv[3:]]
    if any(len(c) != 2 for c in cases):
        sys.exit("each command is given as \"label|command\"")
    env = dict(os.environ, OMP_NUM_THREADS=str(threads))
    cpus = "0" if threads == 1 else "0-%d" % (threads - 1)
    rates = {label: [] for label, _ in cases}
    for _ in range(rounds):
        for label, command in cases:
            out = subprocess.run("taskset -c %s %s" % (cpus, command), shell=True,
                                 capture_output=True, text=True, env=env).stdout
            found = re.findall(r"particle_steps_per_s (\S+)", out)
            rates[label].append(float(found[0]) if found else float("nan"))
    first = cases[0][0]
    for label, _ in cases:
        runs = " ".join("%.4g" % x for x in rates[label])
        print("%-24s median %.4g  runs %s" % (label, statistics.median(rates[label]), runs))
    for label, _ in cases[1:]:
        ratios = [a / b for a, b in zip(rates[label], rates[first]) if a == a and b == b]
        if ratios:
            print("%-24s / %-12s per-round median %.3f  (%s)" % (
                label, first, statistics.median(ratios), " ".join("%.3f" % r for r in ratios)))


if __name__ == "__main__":
    main()
