"""The Parmec front end: decks run with the commands in their namespace, Python 2 decks are
translated, and a bad argument names the command, the argument, the valid values and the deck's
line. Run as: front_end_test.py GRAIN_PARMEC (the command to test)."""
import os
import subprocess
import sys
import tempfile

command = sys.argv[1]
failures = []


def run(deck, *args):
    with tempfile.TemporaryDirectory() as d:
        path = os.path.join(d, "deck.py")
        with open(path, "w") as f:
            f.write(deck)
        r = subprocess.run([command, path] + list(args), capture_output=True, text=True, cwd=d)
        return r.returncode, r.stdout, r.stderr.replace(path, "deck.py"), sorted(os.listdir(d))


def check(name, condition, detail=""):
    print(("ok   " if condition else "FAIL ") + name + ("" if condition else ": " + detail))
    if not condition:
        failures.append(name)


CUBE = """
mat = MATERIAL(1E3, 1E9, 0.25)
nodes = [0,0,0, 1,0,0, 1,1,0, 0,1,0, 0,0,1, 1,0,1, 1,1,1, 0,1,1]
p = MESH(nodes, [8, 0,1,2,3,4,5,6,7, mat], mat, 1)
"""

# Python 2: print statements, <>, integer division (7/2 == 3), and true division of floats
code, out, err, _ = run("print 'half', 7/2, 7.0/2, 7//2\nif 1 <> 2: print 'differ'\nx = 9\nx /= 2\nprint x\n")
check("python 2 deck", code == 0 and out.split() == ["half", "3", "3.5", "3", "differ", "4"],
      out + err)
# a Python 3 deck keeps Python 3's division
code, out, err, _ = run("print('half', 7/2)\n")
check("python 3 deck", code == 0 and out.split() == ["half", "3.5"], out + err)
# ARGV
code, out, err, _ = run("print(ARGV())\nprint(ARGV(False)[1:])\n", "a", "-ntasks", "4", "b")
check("ARGV", code == 0 and out.splitlines() == ["['a', 'b']", "['a', '-ntasks', '4', 'b']"],
      out + err)
# numbering from 0 in call order, per kind; RESET starts again
code, out, err, _ = run(CUBE + "q = ANALYTICAL(mass=2.0)\nm2 = MATERIAL(2E3, 1E9, 0.3)\n"
                        "print(p, q, mat, m2, TSERIES(1.0), TSERIES([0, 1, 1, 2]), "
                        "TSERIES([[0, 1], [2, 3]]))\nRESET()\n"
                        "print(MATERIAL(1E3, 1E9, 0.25), ANALYTICAL())\n")
check("numbering and RESET", code == 0 and out.split() == ["0", "1", "0", "1", "0", "1", "2",
                                                            "0", "0"], out + err)
# errors: the deck's line, the command, the argument and the valid values
code, out, err, _ = run(CUBE + "\nVELOCITY(p, (1, 2))\n")
check("bad vector", code == 1 and "deck.py:6: TypeError: VELOCITY: argument 'linear'" in err
      and "a tuple of 3 numbers" in err, err)
code, out, err, _ = run(CUBE + "BALL_JOINT(5, (0, 0, 0))\n")
check("bad particle number", code == 1 and "deck.py:5:" in err and "BALL_JOINT: argument "
      "'part1' = 5 is invalid; valid: [0, 1)" in err, err)
code, out, err, _ = run("MATERIAL(-1.0, 1E9, 0.25)\n")
check("bad density", code == 1 and "deck.py:1:" in err and "'density' = -1.0" in err and
      "(0, inf)" in err, err)
code, out, err, _ = run("m = MATERIAL(1E3, 1E9, 0.25)\nMESH([0,0,0, 1,0,0, 0,1,0, 0,0,1], "
                        "[4, 0,1,2,7, m], m, 1)\n")
check("grain's check of a mesh", code == 1 and "deck.py:2: InputError:" in err, err)
code, out, err, _ = run(CUBE + "HISTORY('PQ', p)\n")
check("bad entity", code == 1 and "HISTORY: argument 'entity' = 'PQ' is invalid; valid values: "
      "TIME, PX" in err, err)
code, out, err, _ = run(CUBE + "TORSION_SPRING(p, -1, (0, 0, 1), (1, 0, 0), kyaw=[1, 0, -1, 0])\n")
check("table abscissae must increase", code == 1 and "deck.py:5: ValueError: TORSION_SPRING: "
      "argument 'kyaw' has angle values [1.0, -1.0] that do not increase" in err, err)
code, out, err, _ = run(CUBE + "TORSION_SPRING(p, -1, (0, 0, 1), (1, 0, 0), cone=('roll',))\n")
check("bad cone", code == 1 and "argument 'cone' = ('roll',) is invalid; valid: ('roll', 'yaw')"
      in err, err)
code, out, err, _ = run(CUBE + "TORSION_SPRING(p, -1, (0, 0, 1), (1, 0, 1))\n")
check("grain's check of torsion directions", code == 1 and "deck.py:5: InputError:" in err, err)
code, out, err, _ = run(CUBE + "OBSTACLE([(0, 0, 0, 1, 0, 0, 0, 1, 0)], 1)\n")
check("a command not run yet says so", code == 1 and "OBSTACLE is not supported yet" in err, err)
code, out, err, _ = run(CUBE + "UNSPRING([0], [0], (None, 1.0))\n")
check("UNSPRING of a spring not defined", code == 1 and "deck.py:5: ValueError: UNSPRING: "
      "argument 'tsprings' = [0] is invalid; valid: a non-empty list of distinct SPRING numbers "
      "in [0, 0)" in err, err)
code, out, err, _ = run(CUBE + "SPRING(p, (0, 0, 0), -1, (0, 0, 0), [-1, -1, 1, 1], "
                        "planar='YES', direction=(0, 0, 1))\n")
check("bad planar switch", code == 1 and "deck.py:5: ValueError: SPRING: argument 'planar' = "
      "'YES' is invalid; valid values: 'ON', 'OFF'" in err, err)
# CRITICAL: a zero-length spring of 1e4 N/m holding the 1000 kg cube at its centre:
# 2 / sqrt(k / m) at its stiffest; lists of (step, number, omega, xi)
code, out, err, _ = run(CUBE + "SPRING(p, (0.5, 0.5, 0.5), -1, (0.5, 0.5, 0.5), [-1, -1E4, 1, 1E4])"
                        "\nprint(CRITICAL())\nprint(CRITICAL(1, 1))\n")
lines = out.splitlines()
check("CRITICAL", code == 0 and abs(float(lines[0]) / (2 / (1E4 / 1E3) ** 0.5) - 1) < 1e-12 and
      lines[1].startswith("([(0.6324555320336") and ", 0, 3.16227766016838" in lines[1],
      out + err)
# a run: histories sampled at the interval, continued by a second DEM, files named after the deck
code, out, err, files = run(CUBE + "VELOCITY(p, (1, 0, 0))\nt = HISTORY('TIME')\n"
                            "dx = HISTORY('DX', p)\nDEM(1.0, 0.01, (0.5, 0.25))\n"
                            "DEM(0.5, 0.01, (0.5, 0.25))\nprint(t)\nprint(dx)\n")
lines = out.splitlines()
def values(line):
    return [round(float(x), 9) for x in line.strip("[]").split(",")]


expected = [0.0, 0.25, 0.5, 0.75, 1.0, 1.25, 1.5]
check("DEM and HISTORY", code == 0 and len(lines) == 2 and values(lines[0]) == expected and
      values(lines[1]) == expected, out + err)
check("output files", "deck_bodies.vtk.series" in files and "deck_meshes_000000.vtk" in files,
      " ".join(files))
# EQM: the cube (1000 kg, J = m / 6 about its centre) at a corner, arm r = (0.5, 0.5, 0.5):
# along the arm the mass is m; across it, 1 / (1 / m + |r|^2 / J) = m / 5.5
code, out, err, _ = run(CUBE + "print(EQM(p, (1, 1, 1), direction=(1, 1, 1)))\n"
                        "print(EQM(p, (1, 1, 1), direction=(1, -1, 0)))\n")
values_eqm = [float(x) for x in out.split()] if code == 0 else []
check("EQM", len(values_eqm) == 2 and abs(values_eqm[0] / 1000 - 1) < 1e-12 and
      abs(values_eqm[1] / (1000 / 5.5) - 1) < 1e-12, out + err)
print("%d failure(s)" % len(failures))
sys.exit(1 if failures else 0)
