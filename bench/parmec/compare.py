"""The Python layer's cost: runs the Parmec deck bench/parmec/settle.py with grain-parmec and the
same problem written in C++ (case_parmec_settle) alternately, REPS times each, and prints the
particle-steps per second of each run, their medians and the median of the per-round ratios
deck / C++ (this machine's speed drifts between rounds; only same-round ratios count).

    python3 bench/parmec/compare.py BUILD_DIR [REPS [NX NY NZ NWARM NRUN]]

Run from a scratch folder: the deck is copied there, and both write their VTK files
(parmec_settle_*, settle_*) there.
Threads: OMP_NUM_THREADS, as set for both."""
import os
import shutil
import statistics
import subprocess
import sys

build = sys.argv[1]
reps = int(sys.argv[2]) if len(sys.argv) > 2 else 5
size = sys.argv[3:8] if len(sys.argv) >= 8 else ["25", "25", "16", "200", "1000"]
# a deck writes its files next to itself: run a copy in the working folder
deck = shutil.copy(os.path.join(os.path.dirname(os.path.abspath(__file__)), "settle.py"),
                   "settle.py")
commands = {"deck": [os.path.join(build, "bin", "grain-parmec"), deck] + size,
            "c++": [os.path.join(build, "bench", "case_parmec_settle")] + size}


def rate(cmd):
    out = subprocess.run(cmd, capture_output=True, text=True, check=True).stdout
    values = dict(line.split(None, 1) for line in out.splitlines() if " " in line)
    return float(values["particle_steps_per_second"]), values["step"].strip()


rates = {k: [] for k in commands}
ratios = []
for r in range(reps):
    order = list(commands) if r % 2 == 0 else list(reversed(list(commands)))
    got = {}
    for k in order:
        got[k] = rate(commands[k])
        rates[k].append(got[k][0])
    if got["deck"][1] != got["c++"][1]:
        sys.exit("the deck's step %s differs from the C++ program's %s" % (got["deck"][1],
                                                                          got["c++"][1]))
    ratios.append(got["deck"][0] / got["c++"][0])
    print("round %d: deck %.4g, C++ %.4g particle-steps/s, ratio %.3f" %
          (r + 1, got["deck"][0], got["c++"][0], ratios[-1]))
print("medians: deck %.4g, C++ %.4g particle-steps/s; median ratio deck / C++ %.3f" %
      (statistics.median(rates["deck"]), statistics.median(rates["c++"]),
       statistics.median(ratios)))
