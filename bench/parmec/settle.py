# Parmec deck of the parmec_settle benchmark: NX x NY x NZ spheres (radius 0.05 m, 1000 kg/m^3)
# on a lattice of spacing 0.11 m settle under gravity in an open box of obstacles (two triangles
# per face), GRANULAR spring 1e5 N/m, damper 0.2, friction 0.3, kskn 0.5; the step is 0.2 of
# CRITICAL. NWARM steps, then NRUN timed ones. The same problem as the C++ program
# bench/cases/parmec_settle.cpp (build/bench/case_parmec_settle), compared by
# bench/parmec/compare.py.
#
#   grain-parmec settle.py [NX NY NZ NWARM NRUN]   (default 25 25 16 200 1000; run a copy in a
#   scratch folder: a deck writes its files next to itself)
#
# Prints "particle_steps_per_second X" for the NRUN steps (the wall time DEM returns).
args = [int(a) for a in ARGV()]
nx, ny, nz, nwarm, nrun = args if len(args) == 5 else [25, 25, 16, 200, 1000]
r, s = 0.05, 0.11
mat = MATERIAL(1000.0, 1E7, 0.3)
for i in range(nx):
    for j in range(ny):
        for k in range(nz):
            SPHERE((s * (i + 0.5), s * (j + 0.5), s * (k + 0.5)), r, mat, 1)
X, Y, Z = s * nx, s * ny, s * (nz + 1)


def face(a, b, c, d):
    return [a + b + c, a + c + d]


box = (face((0, 0, 0), (X, 0, 0), (X, Y, 0), (0, Y, 0)) +
       face((0, 0, 0), (0, 0, Z), (X, 0, Z), (X, 0, 0)) +
       face((0, Y, 0), (X, Y, 0), (X, Y, Z), (0, Y, Z)) +
       face((0, 0, 0), (0, Y, 0), (0, Y, Z), (0, 0, Z)) +
       face((X, 0, 0), (X, 0, Z), (X, Y, Z), (X, Y, 0)))
OBSTACLE(box, 2)
GRANULAR(0, 0, 1E5, 0.2, 0.3, kskn=0.5)
GRAVITY(0.0, 0.0, -9.81)
h = 0.2 * CRITICAL()
DEM(nwarm * h, h, (nwarm * h, nwarm * h))
t = DEM(nrun * h, h, (nrun * h, nrun * h))
print("particles %d" % (nx * ny * nz))
print("step %.9g" % h)
print("particle_steps_per_second %.6g" % (nx * ny * nz * nrun / t))
