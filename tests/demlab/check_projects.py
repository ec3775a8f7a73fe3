"""Runs DEMLab projects with grain-demlab and checks their graphs against closed forms.

Usage: check_projects.py GRAIN_DEMLAB PROJECTS_COPY CASE
  PROJECTS_COPY  a copy of DEMLab's projects (mechanical/, thermal/, thermomechanical/)
  CASE           bounce_straight | collision_binary | thermo_collision_binary | resting_single |
                 pack1_regular_400

Each case reads the graph tables grain-demlab writes (<project>/<name>_out/<title>.txt: a curve's
name, then "x y" rows, a blank line between curves), so the whole chain is checked: the project
read, the generated program, the run and the graphs.
"""
import json
import math
import os
import subprocess
import sys

tool, root, case = sys.argv[1], sys.argv[2], sys.argv[3]
failures = 0


def check(name, ok, detail):
    global failures
    print("%s %s: %s" % ("ok  " if ok else "FAIL", name, detail))
    failures += 0 if ok else 1


def run(project, *args):
    """Runs a project (its animations only for resting_single: they take a while)."""
    path = os.path.join(root, project, "ProjectParameters.json")
    if case != "resting_single":
        args += ("--no-animations",)
    r = subprocess.run([sys.executable, tool, path] + list(args))
    if r.returncode != 0:
        print("FAIL grain-demlab %s: status %d" % (project, r.returncode))
        sys.exit(1)
    with open(path) as f:
        name = json.load(f)["ProblemData"]["name"]
    return os.path.join(root, project, name + "_out")


def graph(out, title):
    """{curve name: (xs, ys)} of a graph table."""
    curves, name = {}, None
    with open(os.path.join(out, title + ".txt")) as f:
        for line in f:
            fields = line.split()
            if not fields:
                name = None
            elif name is None:
                name = line.strip()
                curves[name] = ([], [])
            else:
                curves[name][0].append(float(fields[0]))
                curves[name][1].append(float(fields[1]))
    return curves


def clamped_restitution(e):
    """Restitution of a linear spring-dashpot whose damping gives e, with the force clamped at
    zero (no attraction, DEMLab's remove_artificial_cohesion): the contact ends where
    k x + eta x' = 0, before the overlap returns to zero. With x = (v0/w) exp(-g t) sin(w t),
    g / w = -ln(e) / pi: the end is at w t = pi - atan(2 g w / (w^2 - g^2)) and the exit speed
    v0 exp(-g t) |cos(w t) - (g / w) sin(w t)|."""
    r = -math.log(e) / math.pi
    wt = math.pi - math.atan(2 * r / (1 - r * r))
    return math.exp(-r * wt) * abs(math.cos(wt) - r * math.sin(wt))


def apex(ts, ys, k):
    """The top of the parabola through samples k-1, k, k+1 (exact for a free flight)."""
    t0, t1, t2 = ts[k - 1:k + 2]
    y0, y1, y2 = ys[k - 1:k + 2]
    h = t1 - t0
    a = (y0 - 2 * y1 + y2) / (2 * h * h)
    b = (y2 - y0) / (2 * h)
    return y1 - b * b / (4 * a)


if case == "bounce_straight":
    # a disk (R = 0.5, centre at y = 2) dropped on a wall at y = 0, linear model with e = 0.9
    # and no attraction: each flight rises to e_c^2 of the previous height above the contact
    # height y = R (e_c = 0.90202, the clamped model's restitution)
    out = run("mechanical/bounce_straight", "--final-time", "3")
    ts, ys = graph(out, "Vertical Position")["particle 1"]
    peaks = [k for k in range(1, len(ys) - 1) if ys[k] > ys[k - 1] and ys[k] >= ys[k + 1]]
    heights = [2.0] + [apex(ts, ys, k) for k in peaks]
    r1 = (heights[1] - 0.5) / (heights[0] - 0.5)
    r2 = (heights[2] - 0.5) / (heights[1] - 0.5)
    e2 = clamped_restitution(0.9) ** 2
    check("first rebound height ratio = e_c^2 = %.5f (tolerance 0.5 %%)" % e2,
          abs(r1 / e2 - 1) < 0.005, "%.5f" % r1)
    check("second rebound height ratio = e_c^2 = %.5f (tolerance 0.5 %%)" % e2,
          abs(r2 / e2 - 1) < 0.005, "%.5f" % r2)
    t_contact = math.sqrt(2 * 1.5 / 9.81)
    before = [(t, y) for t, y in zip(ts, ys) if t < t_contact - 0.01]
    err = max(abs(y - (2 - 0.5 * 9.81 * t * t)) for t, y in before)
    # forward Euler: y_n = y0 - g dt^2 n (n - 1) / 2, off the parabola by g t dt / 2 <= 3e-4 m
    check("free fall before the contact follows y = 2 - g t^2 / 2 (forward Euler: within "
          "g t dt / 2 = 3e-4 m)", err < 3e-4, "largest difference %.2e m" % err)
elif case == "collision_binary":
    # two equal disks at -2 and 2 m/s meet at t = 0.75 s; linear model with e = 0.7 and no
    # attraction (restitution e_c = 0.71816)
    out = run("mechanical/collision_binary")
    ts, vs = graph(out, "Horizontal Velocity")["particle 1"]
    v_after = -2 * clamped_restitution(0.7)
    check("velocity after the collision = -e_c v = %.5f m/s (tolerance 0.3 %%)" % v_after,
          abs(vs[-1] / v_after - 1) < 0.003, "%.6f m/s" % vs[-1])
    check("velocity before the collision is 2 m/s", all(abs(v - 2) < 1e-12 for t, v in
                                                     zip(ts, vs) if t < 0.74),
          "%s" % [v for t, v in zip(ts, vs) if t < 0.74][:3])
    ts, xs = graph(out, "Horizontal Position")["particle 1"]
    err = max(abs(x - (-2 + 2 * t)) for t, x in zip(ts, xs) if t < 0.74)
    check("position before the collision is -2 + 2 t (1e-9 m)", err < 1e-9, "%.2e m" % err)
elif case == "thermo_collision_binary":
    # two equal disks at 300 K and 400 K collide: the heat one loses the other gains
    out = run("thermomechanical/collision_binary")
    c = graph(out, "Temperature")
    t1, t2 = c["particle 1"][1], c["particle 2"][1]
    drift = max(abs(a + b - 700.0) for a, b in zip(t1, t2))
    check("T1 + T2 = 700 K at every output (equal m c; tolerance 1e-9 K)", drift < 1e-9,
          "largest drift %.2e K" % drift)
    check("heat flowed from the hot to the cold disk during the contact",
          300.0 < t1[-1] < 350.0 and 350.0 < t2[-1] < 400.0, "T1 %.4f K, T2 %.4f K"
          % (t1[-1], t2[-1]))
elif case == "resting_single":
    # one disk (R = 1, centre 0.99 above a wall at 400 K, k = 1000) in a fluid at 250 K:
    # Batchelor-O'Brien through the contact (a = the half chord), the surrounding layer's
    # analytic wall form (Morris et al.), and Ranz-Marshall convection at rest (Nu = 2); a
    # lumped particle relaxes to the weighted mean. DEMLab's formula sheet leaves out the
    # annulus a < r < r_in where the fluid gap is below S (held at S): k_f pi (r_in^2 - a^2)/S =
    # 62.2 W/K here; grain counts it, so grain's initial heat rate is that much times 100 K
    # above DEMLab's stored 123867 W.
    out = run("thermal/resting_single")
    R, d, k_eff, k_f, S, layer = 1.0, 0.99, 500.0, 10.0, 2.75e-8, 0.4
    a = math.sqrt(R * R - d * d)
    h_bob = 4 * k_eff * a
    L = layer * R
    ab = (d - R) / R
    r_in = 0.0 if d > R + S else math.sqrt(1 - (S / R - ab - 1) ** 2)
    r_out = math.sqrt(((R + L) / R) ** 2 - (ab + 1) ** 2) \
        if ab > math.sqrt(((R + L) / R) ** 2 - 1) - 1 else 1.0
    b, c = math.sqrt(1 - r_out ** 2), math.sqrt(1 - r_in ** 2)
    h_sl = 2 * math.pi * k_f * R * ((ab + 1) * math.log(abs(b - ab - 1) / abs(ab - c + 1)) + b - c)
    h_disc = k_f * math.pi * ((r_in * R) ** 2 - a * a) / S
    h_conv = 2 * k_f / (2 * R) * 4 * math.pi * R * R
    demlab_q0 = (h_bob + h_sl) * (400 - 300) + h_conv * (250 - 300)
    check("DEMLab's stored 123867 W from the formula sheet (tolerance 1 W)",
          abs(demlab_q0 - 123867) < 1, "%.1f W" % demlab_q0)
    h = h_bob + h_sl + h_disc
    q0 = h * (400 - 300) + h_conv * (250 - 300)
    steady = (h * 400 + h_conv * 250) / (h + h_conv)
    ts, qs = graph(out, "Rate of Heat Transfer")["particle 1"]
    check("heat rate at t = 0: %.1f W from the closed forms (tolerance 1e-6)" % q0,
          abs(qs[0] / q0 - 1) < 1e-6, "%.1f W" % qs[0])
    ts, Ts = graph(out, "Temperature")["particle 1"]
    # forward Euler with constant conductances: T_n - T_ss shrinks by a constant factor per
    # output interval; the steady state from three late outputs
    x0, x1, x2 = Ts[-3:]
    fitted = x2 - (x2 - x1) ** 2 / ((x2 - x1) - (x1 - x0))
    gif = os.path.join(out, "Temperature.gif")
    check("the animation Temperature.gif is written", os.path.isfile(gif) and
          open(gif, "rb").read(6) in (b"GIF87a", b"GIF89a"), gif)
    check("steady temperature %.4f K = (H 400 + h A 250)/(H + h A) (tolerance 1e-6)" % steady,
          abs(fitted / steady - 1) < 1e-6, "%.4f K" % fitted)
elif case == "pack1_regular_400":
    # 400 disks at 300 K on a square lattice, walls at 400 K: a discrete maximum principle
    out = run("thermal/pack1_regular_400", "--final-time", "2")
    tmin = graph(out, "Minimum Temperature")["min. temp."][1]
    tmax = graph(out, "Maximum Temperature")["max. temp."][1]
    tavg = graph(out, "Average Temperature")["avg. temp."][1]
    check("temperatures stay within [300, 400] K", min(tmin) >= 300 - 1e-9 and
          max(tmax) <= 400 + 1e-9, "min %.6f K, max %.6f K" % (min(tmin), max(tmax)))
    check("the mean temperature rises at every output", all(b >= a for a, b in
                                                             zip(tavg, tavg[1:])),
          "%.4f K -> %.4f K" % (tavg[0], tavg[-1]))
elif case == "print":
    # DEMLab's Print: one .pos file per output, or all in one; collision_binary with 4 outputs
    import shutil
    for single in (False, True):
        folder = "mechanical/print_%s" % ("single" if single else "files")
        shutil.rmtree(os.path.join(root, folder), ignore_errors=True)
        shutil.copytree(os.path.join(root, "mechanical/collision_binary"),
                        os.path.join(root, folder))
        path = os.path.join(root, folder, "ProjectParameters.json")
        with open(path) as f:
            d = json.load(f)
        d["Output"]["number_output"] = 4
        d["Print"] = {"single_file": single, "printed_results": [
            "position", "velocity", "acceleration", "temperature"]}
        with open(path, "w") as f:
            json.dump(d, f)
        out = run(folder)
        blocks = []  # (step, {section: {id: values}})
        names = ["colliding_balls.pos"] if single else [
            "colliding_balls_%d.pos" % k for k in (0, 50000, 100000, 150000, 200000)]
        for name in names:
            with open(os.path.join(out, name)) as f:
                section = None
                for line in f:
                    w = line.split()
                    if not w or w[0].startswith("---"):
                        continue
                    if w[0] == "%STEP":
                        blocks.append((int(w[1]), {}))
                    elif w[0].startswith("%"):
                        section = w[0]
                        blocks[-1][1][section] = {}
                        if len(w) > 1:
                            blocks[-1][1][section] = float(w[1])
                    else:
                        blocks[-1][1][section][int(w[0])] = [float(x) for x in w[1:]]
        label = "single file" if single else "one file per output"
        check("%s: outputs at steps 0, 50000, ..., 200000" % label,
              [b[0] for b in blocks] == [0, 50000, 100000, 150000, 200000],
              str([b[0] for b in blocks]))
        first, last = blocks[0][1], blocks[-1][1]
        check("%s: at t = 0 the disks are at -2 and 2 m, at 2 and -2 m/s, not accelerated"
              % label,
              first["%PARTICLE_COORDINATE_ORIENTATION"][1][0] == -2.0 and
              first["%PARTICLE_COORDINATE_ORIENTATION"][2][0] == 2.0 and
              first["%PARTICLE_VELOCITY"][1][0] == 2.0 and
              first["%PARTICLE_ACCELERATION"][1] == [0.0, 0.0, 0.0], str(first)[:300])
        v_after = -2 * clamped_restitution(0.7)
        check("%s: the last velocity is -e_c v (0.3 %%)" % label,
              abs(last["%PARTICLE_VELOCITY"][1][0] / v_after - 1) < 3e-3,
              str(last["%PARTICLE_VELOCITY"]))
        check("%s: no temperature block in a mechanical analysis" % label,
              "%PARTICLE_TEMPERATURE" not in last, str(list(last)))
else:
    print("unknown case %r" % case)
    sys.exit(2)
print("PASSED" if failures == 0 else "FAILED (%d)" % failures)
sys.exit(1 if failures else 0)
