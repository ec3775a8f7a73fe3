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


def prescribe():
    """tests/prescribe.py: a cube whose velocity (t, 0, 0) and angular velocity (0, 0, t) are
    prescribed by callbacks: VX = OZ = t at every sample."""
    ns = run("tests/prescribe.py")
    t = ns["t"]
    e = max(max(abs(v - s) for s, v in zip(t, ns["vx"])), max(abs(v - s) for s, v in
                                                                zip(t, ns["oz"])))
    print("prescribe.py: %d samples to t = %.2f s, largest error of VX and OZ %.2e" %
          (len(t), t[-1], e))
    return len(t) == 201 and abs(t[-1] - 2.0) < 1E-9 and e < 1E-12


def prescribe_asweep():
    """tests/prescribe_asweep.py: a cube whose acceleration a(t) = sin(2 pi t^2) along x is
    prescribed ('av'): VX = int_0^t a = S(2 t) / 2 (S the Fresnel integral) and
    DX = t VX - (1 - cos(2 pi t^2)) / (4 pi)."""
    ns = run("tests/prescribe_asweep.py")
    t, vx, dx = ns["t"], ns["vx"], ns["dx"]
    # VX by Simpson's rule on a grid 100 times finer than the samples' 0.01 s
    n, exact_v, v, s0 = 100, [0.0], 0.0, 0.0
    for k in range(1, len(t)):
        a, b = t[k - 1], t[k]
        h = (b - a) / n
        f = [math.sin(2 * math.pi * (a + j * h) ** 2) for j in range(n + 1)]
        v += h / 3 * (f[0] + f[-1] + 4 * sum(f[1:-1:2]) + 2 * sum(f[2:-1:2]))
        exact_v.append(v)
    e_v = max(abs(p - q) for p, q in zip(vx, exact_v))
    e_d = max(abs(d - (s * q - (1 - math.cos(2 * math.pi * s * s)) / (4 * math.pi)))
              for s, d, q in zip(t, dx, exact_v))
    print("prescribe_asweep.py: %d samples to t = %.2f s, VX(5) = %.6f (closed form %.6f), "
          "largest errors VX %.2e m/s, DX %.2e m" % (len(t), t[-1], vx[-1], exact_v[-1], e_v, e_d))
    # the midpoint accelerations of 1 ms steps: errors of order h^2 a'' t / 24 (a'' reaches
    # (4 pi t)^2 = 4e3 s^-4 at t = 5 s)
    # (measured 2.6e-6 m/s and 4.2e-8 m)
    return abs(t[-1] - 5.0) < 1E-9 and e_v < 2E-5 and e_d < 1E-6


def history():
    """tests/history.py: a cube spinning at 1 rad/s about z while moving at 1 m/s along x: its
    centre moves DX = t, and its corner (1, 1, 1), at the arm (0.5, 0.5, 0.5),
    DX = t + 0.5 (cos t - sin t) - 0.5 and DY = 0.5 (sin t + cos t) - 0.5; VX = OZ = 1."""
    ns = run("tests/history.py")
    t = ns["t"]
    e = 0.0
    for s, x0, x1, y1, v, o in zip(t, ns["dx0"], ns["dx1"], ns["dy1"], ns["vx"], ns["oz"]):
        e = max(e, abs(x0 - s), abs(x1 - (s + 0.5 * (math.cos(s) - math.sin(s)) - 0.5)),
                abs(y1 - (0.5 * (math.sin(s) + math.cos(s)) - 0.5)), abs(v - 1), abs(o - 1))
    print("history.py: %d samples to t = %.1f s, largest error %.2e" % (len(t), t[-1], e))
    return len(t) == 101 and e < 1E-9


def interval():
    """tests/interval.py: histories sampled at an interval given by a callable of time (scipy's
    interp1d), evaluated at each step as Parmec does: a sample at the first step t (of 0.1 s)
    with t >= t_k + dt(t), then t_(k+1) = t_k + dt(t); OZ stays 1."""
    ns = run("tests/interval.py")
    t, o = ns["t"], ns["o"]
    dt = ns["dt_hist"]
    expected, due = [0.0], 0.0
    for k in range(1, 101):
        s = 0.1 * k
        d = float(dt(s))
        if s + 1E-4 >= due + d:
            due += d
            expected.append(s)
    if abs(expected[-1] - 10.0) > 1E-9:
        expected.append(10.0)
    e_t = max(abs(a - b) for a, b in zip(t, expected)) if len(t) == len(expected) else 1.0
    e_o = max(abs(v - 1.0) for v in o)
    print("interval.py: %d samples (expected %d), largest time error %.2e s, OZ error %.2e" %
          (len(t), len(expected), e_t, e_o))
    return len(t) == len(expected) and e_t < 1E-9 and e_o < 1E-12


def restrain():
    """tests/restrain.py: seven cubes started at v = (1, 1, 1) m/s, w = (1, 1, 1) rad/s, restrained
    along none, x, x and y, all, then in rotation only: after 5 s each centre has moved 5 m along
    its free directions and not at all along the restrained ones."""
    run("tests/restrain.py")
    system = parmec._model.system
    moves = [(1, 1, 1), (0, 1, 1), (0, 0, 1), (0, 0, 0), (1, 1, 1), (1, 1, 1), (1, 1, 1)]
    e = 0.0
    for i, m in enumerate(moves):
        x = system.position(i)
        start = (2 * i + 0.5, 2 * i + 0.5, 0.5)
        e = max(e, max(abs(x[k] - start[k] - 5.0 * m[k]) for k in range(3)))
    print("restrain.py: largest error of the centres after 5 s %.2e m" % e)
    return e < 1E-12


def spring_planar():
    """tests/spring_planar.py: a 1 m cube (1000 kg) restrained to the x-y plane and in rotation,
    on a zero-length planar spring (k = 1e5 N/m, dashpot 8e3 N s/m) to its start point, started
    at v0 = (0.5, 1, 0): DX = (v0x / wd) exp(-xi w t) sin(wd t), DY = 2 DX, w = 10 rad/s,
    xi = 0.4, wd = w sqrt(1 - xi^2). Run as it is (step 0.3 of the critical one) and with the
    step 30 times smaller (the deck's text with 0.01 in place of 0.3)."""
    w, xi = 10.0, 0.4
    wd = w * math.sqrt(1 - xi * xi)
    ok = True
    with open("tests/spring_planar.py") as f:
        text = f.read()
    fine = "tests/spring_planar_fine_step.py"
    with open(fine, "w") as f:
        f.write(text.replace("h = 0.3 * CRITICAL()", "h = 0.01 * CRITICAL()"))
    for path, tol in (("tests/spring_planar.py", 0.2), (fine, 0.01)):
        ns = run(path)
        t, dx, dy, h = ns["t"], ns["dx"], ns["dy"], ns["h"]
        exact = [0.5 / wd * math.exp(-xi * w * s) * math.sin(wd * s) for s in t]
        e_x = max(abs(a - b) for a, b in zip(dx, exact))
        e_y = max(abs(b - 2 * a) for a, b in zip(dx, dy))
        print("%s: step %.5f s (w h = %.3f), largest error of DX %.2e m = %.3f of the amplitude "
              "%.4f m, |DY - 2 DX| %.2e m" % (path, h, w * h, e_x, e_x / max(exact), max(exact),
                                               e_y))
        # the dashpot sees the half-step velocity: a first-order error of about xi w h of the
        # amplitude (0.16 at the deck's step, measured 0.14; 0.005 at the fine one, measured
        # 0.004); the motion stays on the line y = 2 x (to 1e-8 m, reached after 4.7 s when the
        # spring's points are 1e-9 m apart)
        ok = ok and e_x < tol * max(exact) and e_y < 1E-6 * max(exact)
    os.remove(fine)
    return ok


def spherical_joint():
    """tests/spherical_joint.py: a 0.5 x 0.5 x 2 m column (500 kg) on a stiff zero-length spring
    and a torsion spring to a support whose velocity is prescribed (reversing every 2.5 s) and
    whose rotation is restrained; the torsion spring's roll-pitch cone is free to 0.25 rad and
    stiff (5e6 N m/rad) beyond, its yaw stiff throughout. The column leans into the cone stop
    and stays there: the radial angle stays below 0.25 rad plus the stop's deflection under the
    swings (an impact of the order of 1e3 J on 5e6 N m/rad: 0.02 rad), the yaw below 2e-3 rad."""
    ns = run("tests/spherical_joint.py")
    radial = max(math.hypot(a, b) for a, b in zip(ns["roll"], ns["pitch"]))
    yaw = max(abs(y) for y in ns["yaw"])
    print("spherical_joint.py: %d samples, largest radial angle %.4f rad (cone 0.25 rad), largest "
          "|yaw| %.2e rad" % (len(ns["t"]), radial, yaw))
    return len(ns["t"]) == 20001 and 0.2 < radial < 0.27 and yaw < 2E-3


def bounce():
    """examples/bounce.py: a sphere (r = 0.5 m, 1000 kg/m^3, m = 523.6 kg) falls from 0.5 m onto
    a triangle obstacle under g = 10 m/s^2 with GRANULAR's spring 1e6 N/m and critical damping
    (damper = 1): PZ = 1 - 5 t^2 until it touches at t = sqrt(0.1) = 0.316 s, no rebound
    (critically damped: PZ stays below 0.5 m), rest at PZ = 0.5 - m g / k = 0.494764 m. The deck
    records nothing; its DEM is wrapped to record PZ."""
    rec = {}
    parmec._set_deck("examples/bounce.py")
    sys.modules["parmec"] = parmec
    namespace = parmec.namespace()
    dem = namespace["DEM"]

    def recorded_dem(*args, **kwargs):
        if not rec:
            rec["t"], rec["z"] = parmec.HISTORY("TIME"), parmec.HISTORY("PZ", 0)
        return dem(*args, **kwargs)
    namespace["DEM"] = recorded_dem
    _deck.run("examples/bounce.py", [], namespace)
    t, z = rec["t"], rec["z"]
    m = 1000.0 * 4.0 / 3.0 * math.pi * 0.125
    t0 = math.sqrt(0.1)
    e_f = max(abs(v - (1.0 - 5.0 * s * s)) for s, v in zip(t, z) if s < t0)
    after = [v for s, v in zip(t, z) if s > t0 + 0.02]
    rest = 0.5 - m * 10.0 / 1E6
    print("bounce.py: %d samples, free fall error %.2e m, highest PZ after the impact %.6f m, "
          "final PZ %.7f m (closed form %.7f m)" % (len(t), e_f, max(after), z[-1], rest))
    return e_f < 1E-9 and max(after) < 0.5 and abs(z[-1] - rest) < 1E-6


def damping():
    """tests/damping.py: a projectile under global damping d = 1/s and gravity:
    PX = (v0x / d)(1 - exp(-d t)), PZ = ((v0z + g / d) / d)(1 - exp(-d t)) - g t / d."""
    ns = run("tests/damping.py")
    t, g, v0 = ns["T"], ns["gravity"], ns["v0"]
    X, Z = ns["X"], ns["Z"]  # the deck converted them to inches
    e = 0.0
    for s, x, z in zip(t, X, Z):
        px = v0[0] * (1 - math.exp(-s))
        pz = (v0[2] + g) * (1 - math.exp(-s)) - g * s
        e = max(e, abs(x * 0.0254 - px), abs(z * 0.0254 - pz))
    print("damping.py: %d samples, largest error of PX, PZ %.2e m (range %.3f m)" %
          (len(t), e, X[-1] * 0.0254))
    # the damping force sees the half-step velocity: errors of order d h / 2 = 1e-3 of the motion
    # (measured 2.9e-3 of the highest PZ, 5.1 m, at the end, where PZ has fallen back to 0)
    zmax = max(Z) * 0.0254
    print("damping.py: highest PZ %.3f m" % zmax)
    return e < 5E-3 * zmax


if __name__ == "__main__":
    ok = globals()[sys.argv[2]]()
    print("PASSED" if ok else "FAILED")
    sys.exit(0 if ok else 1)
