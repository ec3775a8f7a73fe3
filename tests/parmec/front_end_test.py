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
code, out, err, _ = run(CUBE + "HISTORY('PX', p, h5file='x.h5')\n")
check("an argument not supported yet says so", code == 1 and "NotImplementedError: HISTORY: "
      "argument 'h5file' is not supported yet" in err, err)
# OUTPUT: further file families of subsets and modes; bad modes and formats
code, out, err, files = run(CUBE + "q = ANALYTICAL(mass=2.0, position=(5, 0, 0))\n"
                            "SPRING(q, (5, 0, 0), -1, (5, 0, 1), [-1, -1E3, 1, 1E3])\n"
                            "OUTPUT(['NUMBER', 'LINVEL'], [p])\nOUTPUT(mode=['SL'])\n"
                            "DEM(0.1, 0.01, 0.05)\n")
check("OUTPUT families", code == 0 and "deck_bodies_000002.vtk" in files and
      "deck1_bodies_000002.vtk" in files and "deck1_meshes_000002.vtk" in files and
      "deck1_springs_000000.vtk" in files and "deck2_springs_000002.vtk" in files and
      "deck2_bodies_000000.vtk" not in files, out + err + " ".join(files))
code, out, err, _ = run(CUBE + "OUTPUT(mode='XX')\n")
check("OUTPUT mode", code == 1 and "OUTPUT: argument 'mode' = 'XX' is invalid" in err, err)
code, out, err, _ = run(CUBE + "OUTPUT(format='MED')\n")
check("OUTPUT format", code == 1 and "NotImplementedError: OUTPUT: format 'MED'" in err, err)
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
# RESTRAIN, PRESCRIBE, DAMPING and callables: their errors name the argument and the valid values
code, out, err, _ = run(CUBE + "RESTRAIN(p, [1, 0])\n")
check("bad RESTRAIN list", code == 1 and "deck.py:5: TypeError: RESTRAIN: argument 'linear' = "
      "[1, 0] is invalid; valid: a list of 3, 6 or 9 numbers" in err, err)
code, out, err, _ = run(CUBE + "RESTRAIN(p, [1, 0, 0, 2, 0, 0])\n")
check("dependent RESTRAIN directions", code == 1 and "deck.py:5: InputError:" in err and
      "linearly dependent" in err, err)
code, out, err, _ = run(CUBE + "PRESCRIBE(p, lambda t: (1, 0, 0), kind='vx')\n")
check("bad PRESCRIBE kind", code == 1 and "PRESCRIBE: argument 'kind' = 'vx' is invalid; valid "
      "values: 'vv', 'va', 'av', 'aa'" in err, err)
code, out, err, _ = run(CUBE + "PRESCRIBE(p, (0, 1))\n")
check("PRESCRIBE tuple", code == 1 and "PRESCRIBE: argument 'linear' = (0, 1) is invalid; valid: "
      "a tuple of 3 TSERIES numbers or a callback" in err, err)
code, out, err, _ = run(CUBE + "s = TSERIES(1.0)\nDAMPING((s, s, 3), (s, s, s))\n")
check("DAMPING not a TSERIES", code == 1 and "deck.py:6: ValueError: DAMPING: argument 'linear'"
      in err and "3 is not a TSERIES number; valid: [0, 1)" in err, err)
code, out, err, _ = run(CUBE + "PRESCRIBE(p, lambda t: (t, 0))\nDEM(0.1, 0.01)\n")
check("callback returning 2 numbers", code == 1 and "deck.py:5: TypeError: PRESCRIBE: callback "
      "'linear' returned (0" in err and "valid: a tuple of 3 numbers" in err, err)
code, out, err, _ = run(CUBE + "def bad(t):\n  raise RuntimeError('stop at %g' % t)\n"
                        "GRAVITY(0.0, 0.0, bad)\nDEM(0.1, 0.01)\n")
check("an exception in a callback", code == 1 and "deck.py:6: RuntimeError: stop at 0" in err,
      err)
code, out, err, _ = run(CUBE + "DEM(0.1, 0.01, adaptive=2.0)\n")
check("bad adaptive", code == 1 and "DEM: argument 'adaptive' = 2.0 is invalid; valid range: "
      "[0, 1]" in err, err)
# a callable gravity and output interval, a TSERIES interval, a history started between runs,
# an averaged list and a point of a body
code, out, err, _ = run(CUBE + "q = ANALYTICAL(mass=2.0, position=(5, 0, 0))\n"
                        "GRAVITY(0.0, 0.0, lambda t: -10.0)\n"
                        "t = HISTORY('TIME')\nDEM(1.0, 0.01, lambda t: 0.25)\n"
                        "vz = HISTORY('VZ', [p, q])\nc = HISTORY('PX', p, (1, 1, 1))\n"
                        "DEM(0.5, 0.01, TSERIES([0, 0.5, 10, 0.5]))\n"
                        "print(t)\nprint(vz)\nprint(c)\n")
lines = out.splitlines()
ok = code == 0 and len(lines) == 3
if ok:
    t, vz, c = values(lines[0]), values(lines[1]), values(lines[2])
    ok = t == [0.0, 0.25, 0.5, 0.75, 1.0, 1.5] and vz == [-10.0, -15.0] and c == [1.0, 1.0]
check("callables, TSERIES intervals, histories between runs", ok, out + err)
# spheres, obstacles and GRANULAR: two spheres of colours 1 and 2 meet head-on at 2 m/s with the
# law of their pair (damper 0.5: e = exp(-pi 0.5 / sqrt(0.75)) = 0.1630); an obstacle moving at
# 0.1 m/s (a callback) hits a resting sphere with the default law (damper 0: elastic), which
# leaves at 0.2 m/s
code, out, err, files = run("""
mat = MATERIAL(1E3, 1E9, 0.25)
a = SPHERE((0, 0, 0), 0.1, mat, 1)
b = SPHERE((0.25, 0, 0), 0.1, mat, 2)
c = SPHERE((5, 0, 0.1), 0.1, mat, 1)
VELOCITY(a, (1, 0, 0))
VELOCITY(b, (-1, 0, 0))
OBSTACLE([(4, -1, 0, 6, -1, 0, 5, 1, 0)], 3, linear=lambda t: (0, 0, 0.1))
GRANULAR(1, 2, 1E6, 0.5)
GRANULAR(0, 0, 1E6, 0.0)
va, vb, vc = HISTORY('VX', a), HISTORY('VX', b), HISTORY('VZ', c)
h = 0.01 * CRITICAL()
DEM(0.2, h, 0.1)
print(va[-1], vb[-1], vc[-1], a, b, c)
""")
vals = [float(x) for x in out.split()] if code == 0 else []
e = 2.718281828459045 ** (-3.141592653589793 * 0.5 / 0.75 ** 0.5)
check("SPHERE, OBSTACLE, GRANULAR", len(vals) == 6 and abs((vals[1] - vals[0]) / 2 - e) < 2e-3
      and abs(vals[0] + vals[1]) < 1e-12 and abs(vals[2] - 0.2) < 2e-3 and vals[3:] == [0, 1, 2]
      and "deck_particles.vtk.series" in files and "deck_walls_000000.vtk" in files,
      out + err + " ".join(files))
# colours without a GRANULAR law do not interact (the seed's default spring is 0): the spheres
# overlap (by 0.02 m at the end) and keep their velocities; a live region (a box) averages the
# spheres inside it; a sphere turned into an analytical body leaves the contacts
code, out, err, _ = run("mat = MATERIAL(1E3, 1E9, 0.25)\na = SPHERE((0, 0, 0), 0.1, mat, 1)\n"
                        "b = SPHERE((0.3, 0, 0), 0.1, mat, 2)\nGRANULAR(1, 1, 1E6)\n"
                        "VELOCITY(a, (1, 0, 0))\nVELOCITY(b, (-1, 0, 0))\n"
                        "c = SPHERE((5, 0, 0), 0.1, mat, 1)\nd = SPHERE((5, 0, 0.15), 0.1, mat, 1)\n"
                        "VELOCITY(d, (0, 0, -1))\nANALYTICAL(particle=c, mass=2.0)\n"
                        "n = HISTORY('PX', (-1, -1, -1, 0.25, 1, 1))\n"
                        "va, vb, vd = HISTORY('VX', a), HISTORY('VX', b), HISTORY('VZ', d)\n"
                        "DEM(0.06, 1E-4, 0.03)\nprint(va[-1], vb[-1], vd[-1])\nprint(n)\n")
lines = out.splitlines()
ok = code == 0 and len(lines) == 2
if ok:
    v = [float(x) for x in lines[0].split()]
    n = values(lines[1])
    # x of a: 0, 0.03, 0.06; of b: 0.3, 0.27, 0.24 (enters the box x <= 0.25 at the end)
    ok = v == [1.0, -1.0, -1.0] and n == [0.0, 0.03, 0.15]
check("no law, no force; a region history; ANALYTICAL of a sphere", ok, out + err)
code, out, err, _ = run("mat = MATERIAL(1E3, 1E9, 0.25)\nSPHERE((0, 0, 0), 0.1, mat, 0)\n")
check("SPHERE colour", code == 1 and "SPHERE: argument 'color' = 0 is invalid; valid: a positive "
      "integer" in err, err)
code, out, err, _ = run("OBSTACLE([(0, 0, 0, 1, 0, 0)], 1)\n")
check("OBSTACLE triangles", code == 1 and "OBSTACLE: argument 'triangles'" in err and
      "9-tuples" in err, err)
print("%d failure(s)" % len(failures))
sys.exit(1 if failures else 0)
