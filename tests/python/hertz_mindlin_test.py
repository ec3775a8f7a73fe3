"""grain's usual API from Python (grain._grain.HertzMindlin, one compiled preset): a sphere
meeting a plane at 1 m/s rebounds with the restitution coefficient of its material, a sphere
dropped from rest falls as z = z0 - g t^2 / 2 until it touches, the output files are written,
and bad input is a ValueError naming the object, the value and the range.
Run as: hertz_mindlin_test.py BUILD_PYTHON_DIR (the folder holding the grain package)."""
import os
import sys
import tempfile

sys.path.insert(0, sys.argv[1])
from grain import _grain  # noqa: E402

failures = []


def check(name, condition, detail=""):
    print(("ok   " if condition else "FAIL ") + name + ("" if condition else ": " + str(detail)))
    if not condition:
        failures.append(name)


# restitution: Hertz with Tsuji's damping from e = 0.5, a 1 mm steel-like sphere against a plane
sim = _grain.HertzMindlin()
glass = sim.add_material("glass", density=2500.0, young=1e8, poisson=0.3, restitution=0.5,
                         friction=0.3)
sim.add_plane((0, 0, 0), (0, 0, 1), glass)
r = 1e-3
sim.add_particle((0, 0, r * (1 - 1e-9)), r, glass, velocity=(0, 0, -1.0))
sim.set_time_step(0.02 * sim.critical_time_step())
sim.run(2e-4)
vz = sim.velocities()[0][2]
check("restitution 0.5 against a plane", abs(vz - 0.5) < 5e-3, vz)
# free fall under gravity, VTK files and a CSV history
with tempfile.TemporaryDirectory() as d:
    sim = _grain.HertzMindlin(gravity=(0, 0, -9.81))
    m = sim.add_material("rubber", density=1000.0, young=1e7)
    sim.add_plane((0, 0, 0), (0, 0, 1), m)
    sim.add_particle((0, 0, 1.0), 0.01, m)
    sim.set_time_step(1e-4)
    sim.run(0.2, vtk=os.path.join(d, "drop"), interval=0.1, history=os.path.join(d, "drop.csv"))
    z = sim.positions()[0][2]
    check("free fall", abs(z - (1.0 - 0.5 * 9.81 * sim.time() ** 2)) < 1e-9,
          (z, sim.time()))
    files = sorted(os.listdir(d))
    check("output files", "drop_particles.vtk.series" in files and "drop.csv" in files and
          "drop_particles_000002.vtk" in files, files)
    with open(os.path.join(d, "drop.csv")) as f:
        rows = f.read().splitlines()
    check("history rows", len(rows) == 4 and rows[0].startswith("time [s]"), rows[:2])
# a fixed velocity from a callable, and the automatic step
sim = _grain.HertzMindlin()
m = sim.add_material("steel", density=7800.0, young=2e11)
ids = [sim.add_particle((0.1 * k, 0, 0), 0.01, m) for k in range(3)]
sim.add_group("moved", ids[:1])
sim.fix_velocity("moved", lambda t: (1.0, 0.0, 0.0))
sim.run(0.01)
check("fixed velocity from a callable", abs(sim.positions()[0][0] - sim.time()) < 1e-12 and
      sim.time_step() > 0, sim.positions()[0])
# bad input
try:
    sim.add_material("bad", density=-1.0, young=1e9)
    check("bad density", False, "no error")
except ValueError as e:
    check("bad density", "Material 'bad'" in str(e) and "density" in str(e) and
          "(0, inf)" in str(e), e)
print("%d failure(s)" % len(failures))
sys.exit(1 if failures else 0)
