"""Runs one of Parmec's own decks, unchanged, with grain-parmec's commands and checks its physics
from the deck's own HISTORY lists (the variables it leaves in its namespace) against closed
forms. Usage, from the folder of Parmec's decks: deck_checks.py BUILD_PYTHON_DIR CHECK, CHECK
one of the functions below. Prints the figures and PASSED or FAILED."""
import math
import os
import sys

sys.path.insert(0, sys.argv[1])
from grain import parmec, _deck  # noqa: E402


def run(path):
    parmec._set_deck(path)
    sys.modules["parmec"] = parmec
    namespace = parmec.namespace()
    _deck.run(path, [], namespace)
    return namespace


def ellipk(k):
    """The complete elliptic integral of the first kind K(k) (arithmetic-geometric mean)."""
    a, b = 1.0, math.sqrt(1.0 - k * k)
    for _ in range(40):  # converges quadratically: to the last bit within 6 iterations here
        a, b = 0.5 * (a + b), math.sqrt(a * b)
    return math.pi / (2.0 * a)


def maxima(t, x):
    """Times of the local maxima of x(t) (parabola through the three samples around each)."""
    out = []
    for n in range(1, len(x) - 1):
        if x[n - 1] < x[n] >= x[n + 1]:
            h = t[n + 1] - t[n]
            d = x[n - 1] - 2 * x[n] + x[n + 1]
            out.append(t[n] + 0.5 * h * (x[n - 1] - x[n + 1]) / d if d else t[n])
    return out


def spring():
    """tests/spring.py: a 1 m cube (1000 kg) hangs by a corner from a zero-length spring of
    1e7 N/m and swings from rest with its centre at the corner's height: a compound pendulum of
    amplitude theta0 = arccos(1/sqrt(3)), L = sqrt(3)/2, I_p = m (1/6 + L^2):
    T = 4 sqrt(I_p / (m g L)) K(sin(theta0 / 2)) = 2.1673 s; PZ at its maxima every T/2 is the
    start height 0.5 m, and at its minima 1 - L less the spring's stretch m (g + L w^2) / k."""
    ns = run("tests/spring.py")
    t, z = ns["t"], ns["z"]
    g, L = 10.0, math.sqrt(3.0) / 2.0
    theta0 = math.acos(1.0 / math.sqrt(3.0))
    T = 4.0 * math.sqrt((1.0 / 6.0 + L * L) / (g * L)) * ellipk(math.sin(theta0 / 2.0))
    top = maxima(t, z)
    half = [b - a for a, b in zip(top, top[1:])]
    e_T = max(abs(2.0 * h / T - 1.0) for h in half)
    # at the bottom the angular velocity is w^2 = 2 g L (1 - cos theta0) / (I_p / m)
    w2 = 2.0 * g * L * (1.0 - math.cos(theta0)) / (1.0 / 6.0 + L * L)
    bottom = 1.0 - L - 1000.0 * (g + L * w2) / 1E7
    e_b = abs(min(z) - bottom)
    e_top = max(abs(z[0] - v) for v in z if v > 0.499)
    print("spring.py: %d half periods, largest error %.2e of T/2 = %.5f s; lowest PZ %.6f m "
          "(closed form %.6f m); highest PZ %.6f m" % (len(half), e_T, T / 2, min(z), bottom,
                                                       max(z)))
    # tolerances: the spring's stretch lengthens the pendulum by up to 1.7e-3 m (2e-3 of L);
    # the closed form of the lowest point leaves out the energy the spring stores and its
    # dashpot takes (measured: the stretch there is 8 % below m (g + L w^2) / k); the highest
    # point is the start, 0.5 m (no energy is gained)
    return len(half) >= 3 and e_T < 2E-3 and e_b < 3E-4 and max(z) < 0.5 + 1E-6


def spring_contact():
    """tests/spring_contact.py: a 1 m cube (1000 kg, centre at 1.5 m) falls under g = 10 m/s^2
    onto four contact springs (dead zone over the first metre of stroke, then 1e7 N/m) and comes
    to rest on them: PZ = 1.5 - 5 t^2 until the first corner touches, PZ -> 0.5 - m g / (4 k)."""
    ns = run("tests/spring_contact.py")
    t, z = ns["t"], ns["z"]
    flight = [(s, v) for s, v in zip(t, z) if s < 0.3]
    e_f = max(abs(v - (1.5 - 5.0 * s * s)) for s, v in flight)
    rest = 0.5 - 1000.0 * 10.0 / (4.0 * 1E7)
    e_r = abs(z[-1] - rest)
    print("spring_contact.py: free fall over %d samples, largest error %.2e m; final PZ %.7f m "
          "(closed form %.7f m)" % (len(flight), e_f, z[-1], rest))
    return len(flight) > 100 and e_f < 1E-9 and e_r < 1E-6


def torsion_spring_one():
    """tests/torsion_spring_one.py, its last case (xyz_all_drates): a 1 m cube (J = 166.67 kg
    m^2) on torsion springs of 1e4 N m/rad about x, y, z with damping ratios 0.25 (roll, x),
    1.0 (pitch, y) and 0.5 (yaw, z), spun at (1, 1, 1) rad/s: each component decays as
    exp(-xi w t) (cos w_d t - xi / sqrt(1 - xi^2) sin w_d t) (critical: (1 - w t) exp(-w t)),
    w = sqrt(k / J); the axes couple only at second order in the angles (0.1 rad)."""
    ns = run("tests/torsion_spring_one.py")
    t = ns["t"]
    w = math.sqrt(1E4 / (1000.0 / 6.0))

    def omega(xi, s):
        if xi == 1.0:
            return (1.0 - w * s) * math.exp(-w * s)
        wd = w * math.sqrt(1.0 - xi * xi)
        return math.exp(-xi * w * s) * (math.cos(wd * s) - xi / math.sqrt(1 - xi * xi) *
                                        math.sin(wd * s))
    errors = {}
    for name, xi in (("ox", 0.25), ("oy", 1.0), ("oz", 0.5)):
        errors[name] = max(abs(v - omega(xi, s)) for s, v in zip(t, ns[name]))
    print("torsion_spring_one.py (xyz_all_drates): largest errors %s rad/s" %
          ", ".join("%s %.2e" % kv for kv in sorted(errors.items())))
    # the coupling of the three rotations: of the order of the angles squared, (0.1)^2
    return all(e < 2E-2 for e in errors.values())


if __name__ == "__main__":
    ok = globals()[sys.argv[2]]()
    print("PASSED" if ok else "FAILED")
    sys.exit(0 if ok else 1)
