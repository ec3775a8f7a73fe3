# A torsion spring in Parmec's input language: a 1 m cube (MESH, 1000 kg/m^3: J = m a^2 / 6 =
# 166.667 kg m^2 about its centre) on a TORSION_SPRING to the world about z (yaw), table
# [-1, 1E4, 1, -1E4] (Parmec's sign: a restoring torque of 1E4 N m/rad), spun at 1 rad/s:
#   omega_z(t) = cos(w0 t), yaw(t) = sin(w0 t) / w0, w0 = sqrt(k / J) = 7.746 rad/s.
# Then the same with a critical damping ratio xi = 0.1 (dyaw): successive maxima of omega_z
# decay by exp(-2 pi xi / sqrt(1 - xi^2)) per period.
from math import sqrt, cos, sin, exp, pi

k, xi = 1E4, 0.1
J = 1000.0 / 6.0
w0 = sqrt(k / J)
ok = True
for damped in (False, True):
    RESET()
    mat = MATERIAL(1E3, 1E9, 0.25)
    nodes = [0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0, 0, 1, 1, 0, 1, 1, 1, 1, 0, 1, 1]
    p = MESH(nodes, [8, 0, 1, 2, 3, 4, 5, 6, 7, mat], mat, 1)
    if damped:
        TORSION_SPRING(p, -1, (0, 0, 1), (1, 0, 0), kyaw=[-1, 1E4, 1, -1E4], dyaw=xi)
    else:
        TORSION_SPRING(p, -1, (0, 0, 1), (1, 0, 0), kyaw=[-1, 1E4, 1, -1E4])
    VELOCITY(p, angular=(0, 0, 1))
    t = HISTORY('TIME')
    oz = HISTORY('OZ', p)
    yaw = HISTORY('YAW', 0)
    trq = HISTORY('TRQSPR_Y', 0)
    DEM(3.0, 1E-4, (3.0, 1E-3))
    if not damped:
        e_w = max(abs(w - cos(w0 * s)) for s, w in zip(t, oz))
        e_a = max(abs(a - sin(w0 * s) / w0) for s, a in zip(t, yaw))
        # Parmec's torque on the cube: the table's value at the angle, -k yaw
        e_t = max(abs(m + k * a) for a, m in zip(yaw, trq))
        print('undamped: max |oz - cos(w0 t)| = %.2e rad/s, max |yaw - sin(w0 t)/w0| = %.2e rad, '
              'max |TRQSPR_Y + k yaw| = %.2e N m' % (e_w, e_a, e_t))
        # tolerances: the step is 1/8000 of the period; the phase error of the integration
        # after 3.7 periods is measured at 5.5e-7 rad/s
        ok = ok and e_w < 1E-5 and e_a < 1E-6 and e_t < 1E-9 * k
    else:
        peaks = [oz[n] for n in range(1, len(oz) - 1) if oz[n - 1] < oz[n] >= oz[n + 1]]
        ratios = [b / a for a, b in zip(peaks, peaks[1:])]
        expected = exp(-2 * pi * xi / sqrt(1 - xi * xi))
        e_r = max(abs(r / expected - 1) for r in ratios)
        print('damped: %d peak ratios, largest relative error %.2e against %.5f'
              % (len(ratios), e_r, expected))
        # the peaks are sampled every 1e-3 s (1/800 of the period): their values are exact to
        # about (w0 1e-3)^2 / 2 = 3e-5 of the amplitude
        ok = ok and len(ratios) >= 2 and e_r < 1E-4
print('PASSED' if ok else 'FAILED')
