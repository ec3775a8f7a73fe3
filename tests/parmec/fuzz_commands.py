"""Fuzzes the argument parsing of grain-parmec's commands: every command is called many times
with random arguments (numbers including NaN, infinities and huge values, strings, lists and
tuples of random lengths and contents, None, callables that return rubbish or raise, particle
and object numbers in and out of range), on random small models, with short DEM runs in between.
Each call must either work or raise one of the errors a deck may meet (TypeError, ValueError,
grain.InputError, NotImplementedError, ArithmeticError); anything else, or a crash of the
interpreter, is a failure.

Usage: fuzz_commands.py BUILD_PYTHON_DIR [SECONDS [SEED]]   (default 20 s, seed 1)
Prints the number of calls, of accepted calls and of each kind of refusal; exits with 1 on the
first unexpected exception (printing the command and its arguments)."""
import math
import os
import random
import sys
import tempfile
import time
import traceback

sys.path.insert(0, sys.argv[1])
from grain import parmec  # noqa: E402

seconds = float(sys.argv[2]) if len(sys.argv) > 2 else 20.0
rng = random.Random(int(sys.argv[3]) if len(sys.argv) > 3 else 1)
EXPECTED = (TypeError, ValueError, NotImplementedError, ArithmeticError)


def number():
    return rng.choice([0, 1, -1, 2, 3, 0.5, -0.25, 1e-9, 1e9, 1e300, -1e300, math.nan, math.inf,
                       -math.inf, rng.uniform(-10, 10), rng.randint(-5, 20), True])


def callback():
    kind = rng.randrange(5)
    if kind == 0:
        return lambda t: (1.0, 0.0, 0.0)
    if kind == 1:
        return lambda t: rng.choice([1.0, (1, 2), "x", None, (math.nan, 0, 0), [0, 0, 0, 0]])
    if kind == 2:
        def bad(t):
            raise ValueError("callback refuses t = %g" % t)
        return bad
    if kind == 3:
        return lambda t: 0.01
    return lambda: 1.0  # the wrong arity: a TypeError when called


def value(depth=0):
    r = rng.random()
    if r < 0.35 or depth > 2:
        return number()
    if r < 0.45:
        return rng.choice(["", "x", "ON", "OFF", "SF", "TIME", "PX", "vv", "aa", "SUM", "VTK",
                           "XDMF", "roll", "tests/none.txt"])
    if r < 0.55:
        return None
    if r < 0.62:
        return callback()
    n = rng.choice([0, 1, 2, 3, 4, 6, 9, 10])
    items = [value(depth + 1) if rng.random() < 0.2 else number() for _ in range(n)]
    return tuple(items) if rng.random() < 0.5 else items


def particle():
    return rng.choice([0, 1, 2, -1, 5, 100, value()])


CUBE_NODES = [0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0, 0, 1, 1, 0, 1, 1, 1, 1, 0, 1, 1]


def model():
    """A small valid model: a material, a cube, an analytical body, two spheres, an obstacle."""
    c = parmec
    c.RESET()
    m = c.MATERIAL(1E3, 1E9, 0.25)
    c.MESH(CUBE_NODES, [8, 0, 1, 2, 3, 4, 5, 6, 7, m], m, 1)
    c.ANALYTICAL(position=(3, 0, 0))
    if rng.random() < 0.5:
        c.SPHERE((10, 0, 1), 0.1, m, 1)
        c.SPHERE((10, 0, 1.5), 0.1, m, 2)
        c.OBSTACLE([(9, -1, 0, 11, -1, 0, 10, 1, 0)], 3)
        c.GRANULAR(0, 0, 1E5)


# command -> a function giving random arguments (args, kwargs)
COMMANDS = {
    "TSERIES": lambda: ([value()], {}),
    "MATERIAL": lambda: ([number(), number(), number()], {}),
    "SPHERE": lambda: ([value(), number(), rng.choice([0, 1, -1, value()]), value()], {}),
    "MESH": lambda: ([rng.choice([CUBE_NODES, value()]),
                      rng.choice([[8, 0, 1, 2, 3, 4, 5, 6, 7, 0], value()]), rng.choice([0, 3]),
                      value()], {}),
    "ANALYTICAL": lambda: ([], {k: value() for k in rng.sample(
        ["inertia", "mass", "rotation", "position", "material", "particle"], rng.randint(0, 3))}),
    "OBSTACLE": lambda: ([value(), value()], {k: value() for k in rng.sample(
        ["point", "linear", "angular"], rng.randint(0, 2))}),
    "SPRING": lambda: ([particle(), value(), particle(), value(),
                        rng.choice([[-1, -1E3, 1, 1E3], value()])],
                       {k: value() for k in rng.sample(
                           ["dashpot", "direction", "planar", "unload", "ylim", "inactive",
                            "offset", "friction", "kskn"], rng.randint(0, 3))}),
    "TORSION_SPRING": lambda: ([particle(), particle(), value(), value()],
                               {k: value() for k in rng.sample(
                                   ["kroll", "kpitch", "kyaw", "droll", "dpitch", "dyaw", "cone",
                                    "refpnt"], rng.randint(0, 3))}),
    "UNSPRING": lambda: ([value(), value(), value()], {k: value() for k in rng.sample(
        ["entity", "operator", "abs", "nsteps", "nfreq", "unload", "activate"],
        rng.randint(0, 3))}),
    "BALL_JOINT": lambda: ([particle(), value()], {"part2": particle()} if rng.random() < 0.5
                           else {}),
    "EQM": lambda: ([particle(), value()], {k: value() for k in rng.sample(
        ["part2", "point2", "direction"], rng.randint(0, 2))}),
    "GRANULAR": lambda: ([value(), value(), number()], {k: value() for k in rng.sample(
        ["damper", "friction", "rolling", "drilling", "kskn"], rng.randint(0, 3))}),
    "RESTRAIN": lambda: ([particle()], {k: value() for k in rng.sample(
        ["linear", "angular"], rng.randint(0, 2))}),
    "PRESCRIBE": lambda: ([particle()], {k: value() for k in rng.sample(
        ["linear", "angular", "kind"], rng.randint(0, 3))}),
    "VELOCITY": lambda: ([particle()], {k: value() for k in rng.sample(
        ["linear", "angular"], rng.randint(0, 2))}),
    "GRAVITY": lambda: ([value(), value(), value()], {}),
    "DAMPING": lambda: ([value(), value()], {}),
    "HISTORY": lambda: ([rng.choice(["TIME", "PX", "|V|", "F", "ROLL", "JREAC_X", value()])],
                        {k: value() for k in rng.sample(["source", "point"],
                                                        rng.randint(0, 2))}),
    "OUTPUT": lambda: ([], {k: value() for k in rng.sample(
        ["entities", "subset", "mode", "format"], rng.randint(0, 3))}),
    "CRITICAL": lambda: ([], {k: value() for k in rng.sample(
        ["perspring", "perparticle"], rng.randint(0, 2))}),
    "DEM": lambda: ([rng.choice([0.002, value()]), rng.choice([1E-3, value()])],
                    {k: value() for k in rng.sample(["interval", "prefix", "adaptive"],
                                                    rng.randint(0, 2))}),
    "ARGV": lambda: ([value()] if rng.random() < 0.5 else [], {}),
}

counts = {"calls": 0, "accepted": 0}
start = time.time()
with tempfile.TemporaryDirectory() as d:
    os.chdir(d)
    parmec._set_deck(os.path.join(d, "fuzz.py"))
    while time.time() - start < seconds:
        model()
        for _ in range(rng.randint(1, 12)):
            name = rng.choice(list(COMMANDS))
            args, kwargs = COMMANDS[name]()
            if name == "DEM":  # keep the runs short
                try:
                    if not (0 < float(args[0]) <= 0.01 and float(args[1]) >= 1E-4):
                        args[0], args[1] = 0.002, 1E-3
                except (TypeError, ValueError):
                    pass
            counts["calls"] += 1
            if os.environ.get("FUZZ_TRACE"):
                print(name, args, kwargs, flush=True)
            try:
                getattr(parmec, name)(*args, **kwargs)
                counts["accepted"] += 1
            except EXPECTED as e:
                counts[type(e).__name__] = counts.get(type(e).__name__, 0) + 1
            except Exception:
                print("FAILED: %s(*%r, **%r) raised an unexpected exception:" % (name, args,
                                                                                  kwargs))
                traceback.print_exc()
                sys.exit(1)
print("fuzz_commands: %d calls in %.0f s, %d accepted; refused: %s" % (
    counts["calls"], time.time() - start, counts["accepted"],
    ", ".join("%s %d" % kv for kv in sorted(counts.items()) if kv[0] not in ("calls",
                                                                            "accepted"))))
print("PASSED")
