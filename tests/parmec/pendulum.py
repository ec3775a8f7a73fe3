# A compound pendulum in Parmec's input language: a cube of side a = 0.2 m (MESH, 1000 kg/m^3)
# hangs from a ball joint at a corner-free point L = 1 m above its centre and swings in the
# x-z plane with a small amplitude (theta0 = 0.02 rad). Its period is
#   T = 2 pi sqrt(I_p / (m g L)) (1 + theta0^2 / 16),  I_p = m a^2 / 6 + m L^2
# (2.012792 s for g = 9.81 m/s^2; the factor is the first amplitude correction of the period).
# The deck measures T from the zero crossings of x (HISTORY 'PX') and the joint's distance to
# the centre from PX, PZ, and checks both.
from math import pi, sqrt, sin, cos

a, L, g, theta0 = 0.2, 1.0, 9.81, 0.02
mat = MATERIAL(1000.0, 1E9, 0.25)
# the cube's centre at (L sin theta0, 0, -L cos theta0), the pivot at the origin
cx, cz = L * sin(theta0), -L * cos(theta0)
h = a / 2
nodes = []
for (x, y, z) in [(-h, -h, -h), (h, -h, -h), (h, h, -h), (-h, h, -h),
                  (-h, -h, h), (h, -h, h), (h, h, h), (-h, h, h)]:
    nodes += [cx + x, y, cz + z]
p = MESH(nodes, [8, 0, 1, 2, 3, 4, 5, 6, 7, mat], mat, 1)
BALL_JOINT(p, (0.0, 0.0, 0.0))
GRAVITY(0.0, 0.0, -g)
t = HISTORY('TIME')
px = HISTORY('PX', p)
pz = HISTORY('PZ', p)
DEM(6.0, 1E-3, (1.0, 1E-3))

m = 1000.0 * a ** 3
T = 2 * pi * sqrt((m * a * a / 6 + m * L * L) / (m * g * L)) * (1 + theta0 ** 2 / 16)
# downward zero crossings of x (linear interpolation between samples)
cross = [t[k] + (t[k + 1] - t[k]) * px[k] / (px[k] - px[k + 1])
         for k in range(len(t) - 1) if px[k] > 0 >= px[k + 1]]
periods = [b - a_ for a_, b in zip(cross, cross[1:])]
T_measured = sum(periods) / len(periods)
gap = max(abs(sqrt(x * x + z * z) - L) for x, z in zip(px, pz))
print('period: measured %.6f s, closed form %.6f s, relative error %.2e'
      % (T_measured, T, abs(T_measured / T - 1)))
print('largest change of the pivot-centre distance: %.2e m' % gap)
# tolerances: the next amplitude term is 11 theta0^4 / 3072 = 6e-10; the step (1e-3 s, about
# T / 2000) and the sampling of the crossings add less than 5e-6; the joint holds the distance
# to 1e-9 m
ok = len(periods) >= 2 and abs(T_measured / T - 1) < 5E-6 and gap < 1E-9
print('PASSED' if ok else 'FAILED')
