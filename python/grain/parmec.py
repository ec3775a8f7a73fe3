"""Parmec's input language on grain.

The commands of Parmec's input decks (ARGV, RESET, TSERIES, MATERIAL, MESH, ANALYTICAL,
VELOCITY, GRAVITY, BALL_JOINT, HISTORY, CRITICAL, DEM, ...) with Parmec's names, arguments,
defaults and return values (object numbers from 0, in call order), on grain's compiled body
model (grain._grain.BodySystem: rigid bodies, meshes, springs and joints). `grain-parmec
DECK.py [ARGS...]` runs a deck with these commands in its namespace; `import parmec` in a deck
or in a module it imports gives the same commands. SI units throughout. docs/parmec.md lists
every command, its grain equivalent and the differences from Parmec.

A command given a wrong argument raises TypeError (wrong kind) or ValueError (wrong value) with
a message naming the command, the argument and the valid values; grain-parmec adds the deck's
file and line.
"""
import numbers
import os
import sys
import time as _time

from . import _grain

__all__ = ["ARGV", "RESET", "TSERIES", "MATERIAL", "SPHERE", "MESH", "ANALYTICAL", "OBSTACLE",
           "GRANULAR", "VELOCITY", "GRAVITY",
           "SPRING", "TORSION_SPRING", "UNSPRING", "BALL_JOINT", "EQM", "RESTRAIN", "PRESCRIBE",
           "DAMPING", "HISTORY", "OUTPUT", "CRITICAL", "DEM"]

# commands of the language that this version does not run yet: calling one is an error that
# says so (never a silent no-op)
NOT_YET = []

_BODY_ENTITIES = ["PX", "PY", "PZ", "|P|", "DX", "DY", "DZ", "|D|", "VX", "VY", "VZ", "|V|",
                  "OX", "OY", "OZ", "|O|", "FX", "FY", "FZ", "|F|", "TX", "TY", "TZ", "|T|"]
_JOINT_ENTITIES = ["JREAC_X", "JREAC_Y", "JREAC_Z", "|JREAC|"]
_SPRING_ENTITIES = ["LENGTH", "STROKE", "F", "SF", "FF", "SS"]
_TORSION_ENTITIES = ["ZDIR_X", "ZDIR_Y", "ZDIR_Z", "XDIR_X", "XDIR_Y", "XDIR_Z", "ROLL", "PITCH",
                     "YAW", "TRQTOT_R", "TRQTOT_P", "TRQTOT_Y", "TRQSPR_R", "TRQSPR_P",
                     "TRQSPR_Y"]
# torques that grain reports with the opposite sign of Parmec's (see TORSION_SPRING)
_NEGATED = {"TRQTOT_R", "TRQTOT_P", "TRQTOT_Y", "TRQSPR_R", "TRQSPR_P", "TRQSPR_Y"}


class _Model:
    """Everything a deck has defined since the start or the last RESET."""

    def __init__(self, prefix):
        self.model = _grain.ParmecModel()
        self.system = self.model.system()
        self.recorder = _grain.Recorder()
        self.tseries = []     # TSERIES: grain TimeFunctions
        self.tseries_points = []  # TSERIES: (times, values), or None for a constant
        self.unsprings = 0
        self.materials = []   # MATERIAL: (density, young, poisson)
        self.particles = []   # parnum -> body index, or None for a sphere that is not a body
        self.spheres = {}     # parnum -> sphere id (SPHERE)
        self.grain_materials = {}  # (MATERIAL number, or -1 for an obstacle; colour) -> index
        self.granular = {}    # (colour1, colour2), colour1 <= colour2 -> GRANULAR's law
        self.obstacles = 0
        self.outputs = 0      # OUTPUT families
        self.applied = None   # the GRANULAR laws and materials last given to the model
        self.joints = 0
        self.torsion_springs = 0
        self.springs = []     # per SPRING: True if point-to-plane (forces reported negated)
        self.histories = []   # (list, recorder column or None for TIME)
        self.gravity = (0.0, 0.0, 0.0)
        self.prefix = prefix
        self.started = False  # a DEM has run


_deck_prefix = "parmec"
_model = _Model(_deck_prefix)


def _set_deck(path):
    """Called by grain-parmec before the deck runs: output files are named after the deck."""
    global _deck_prefix, _model
    _deck_prefix = path[:-3] if path.endswith(".py") else path
    _model = _Model(_deck_prefix)


# ------------------------------------------------------------------------------ argument checks

def _is_number(x):
    return isinstance(x, numbers.Real) and not isinstance(x, bool)


def _number(cmd, name, x):
    if not _is_number(x):
        raise TypeError("%s: argument '%s' = %r is invalid; valid: a number" % (cmd, name, x))
    return float(x)


def _positive(cmd, name, x):
    v = _number(cmd, name, x)
    if not v > 0.0:
        raise ValueError("%s: argument '%s' = %r is invalid; valid range: (0, inf)" % (cmd, name, x))
    return v


def _vector(cmd, name, x):
    if not isinstance(x, (tuple, list)) or len(x) != 3 or not all(_is_number(c) for c in x):
        raise TypeError("%s: argument '%s' = %r is invalid; valid: a tuple of 3 numbers (x, y, z)"
                        % (cmd, name, x))
    return tuple(float(c) for c in x)


def _numbers(cmd, name, x, length=None):
    if not isinstance(x, (tuple, list)) or not all(_is_number(c) for c in x) or \
            (length is not None and len(x) != length):
        valid = "a list of %d numbers" % length if length is not None else "a list of numbers"
        raise TypeError("%s: argument '%s' = %r is invalid; valid: %s" % (cmd, name, x, valid))
    return [float(c) for c in x]


def _integers(cmd, name, x):
    if not isinstance(x, (tuple, list)) or \
            not all(isinstance(c, numbers.Integral) and not isinstance(c, bool) for c in x):
        raise TypeError("%s: argument '%s' = %r is invalid; valid: a list of integers"
                        % (cmd, name, x))
    return [int(c) for c in x]


def _particle(cmd, name, x, allow_none=False):
    n = len(_model.particles)
    if allow_none and x == -1:
        return -1
    if not isinstance(x, numbers.Integral) or isinstance(x, bool) or not 0 <= x < n:
        valid = "[0, %d) (a particle number)" % n if n else "none: no particle has been defined"
        if allow_none and n:
            valid = "-1 (none) or " + valid
        raise ValueError("%s: argument '%s' = %r is invalid; valid: %s" % (cmd, name, x, valid))
    return int(x)


def _body(i):
    """The body index of particle i; a sphere becomes a body of the system (for springs,
    joints, restraints and prescribed motion) the first time one is asked for."""
    b = _model.particles[i]
    if b is None:
        b = _model.model.attach(_model.spheres[i])
        _model.particles[i] = b
    return b


def _colour(cmd, name, x):
    if not isinstance(x, numbers.Integral) or isinstance(x, bool) or not x > 0:
        raise ValueError("%s: argument '%s' = %r is invalid; valid: a positive integer (a "
                         "surface colour)" % (cmd, name, x))
    return int(x)


def _grain_material(material, colour):
    """grain's material of a MATERIAL number (-1: an obstacle) and a colour: the colour selects
    the GRANULAR law, the material the density."""
    key = (material, colour)
    if key not in _model.grain_materials:
        if material < 0:
            d, e, nu = 1000.0, 1E9, 0.25  # an obstacle's: not used by GRANULAR's law
            name = "obstacle colour %d" % colour
        else:
            d, e, nu = _model.materials[material]
            name = "MATERIAL %d colour %d" % (material, colour)
        _model.grain_materials[key] = _model.model.add_material(d, e, nu, name)
    return _model.grain_materials[key]


def _material(cmd, name, x):
    n = len(_model.materials)
    if not isinstance(x, numbers.Integral) or isinstance(x, bool) or not 0 <= x < n:
        valid = "[0, %d) (a MATERIAL number)" % n if n else "none: no MATERIAL has been defined"
        raise ValueError("%s: argument '%s' = %r is invalid; valid: %s" % (cmd, name, x, valid))
    return int(x)


def _time_function(cmd, name, x):
    """A float constant, or a TSERIES number (an integer that numbers a TSERIES; any other
    integer is a constant)."""
    if isinstance(x, numbers.Integral) and not isinstance(x, bool) and 0 <= x < len(_model.tseries):
        return _model.tseries[int(x)]
    if _is_number(x):
        return _grain.TimeFunction.constant(float(x))
    if callable(x):
        return _grain.TimeFunction.callable(_scalar_callback(cmd, name, x))
    raise TypeError("%s: argument '%s' = %r is invalid; valid: a number, a TSERIES number or a "
                    "callable of time" % (cmd, name, x))


def _scalar_callback(cmd, name, f):
    """f(t) checked to return a number (a numpy scalar or 0-d array counts)."""
    def call(t):
        v = f(t)
        try:
            return float(v)
        except (TypeError, ValueError):
            raise TypeError("%s: callback '%s' returned %r at t = %g; valid: a number"
                            % (cmd, name, v, t))
    return call


def _vector_callback(cmd, name, f):
    """f(t) checked to return three numbers."""
    def call(t):
        v = f(t)
        try:
            if len(v) == 3:
                return (float(v[0]), float(v[1]), float(v[2]))
        except (TypeError, ValueError):
            pass
        raise TypeError("%s: callback '%s' returned %r at t = %g; valid: a tuple of 3 numbers"
                        % (cmd, name, v, t))
    return call


def _vector_history(cmd, name, x):
    """A tuple (i, j, k) of TSERIES numbers, or a callback of time returning 3 numbers: as the
    binding takes it (3 TimeFunctions, or a checked callable)."""
    if callable(x):
        return _vector_callback(cmd, name, x)
    if isinstance(x, (tuple, list)):
        if len(x) != 3:
            raise ValueError("%s: argument '%s' = %r is invalid; valid: a tuple of 3 TSERIES "
                             "numbers or a callback" % (cmd, name, x))
        out = []
        for c in x:
            if not isinstance(c, numbers.Integral) or isinstance(c, bool) or \
                    not 0 <= c < len(_model.tseries):
                raise ValueError("%s: argument '%s' = %r is invalid: %r is not a TSERIES number; "
                                 "valid: [0, %d)" % (cmd, name, x, c, len(_model.tseries)))
            out.append(_model.tseries[int(c)])
        return tuple(out)
    raise TypeError("%s: argument '%s' = %r is invalid; valid: a tuple of 3 TSERIES numbers or a "
                    "callback" % (cmd, name, x))


# ------------------------------------------------------------------------------------ commands

def ARGV(nonparmec=True):
    """The command line arguments of the deck: without grain-parmec's own (the deck's path and
    `-ntasks n`) if `nonparmec`, else all but the executable."""
    if not isinstance(nonparmec, bool):
        raise TypeError("ARGV: argument 'nonparmec' = %r is invalid; valid: True or False"
                        % (nonparmec,))
    args = list(sys.argv)
    if not nonparmec:
        return args
    out, skip = [], False
    for a in args:
        if skip:
            skip = False
        elif a == "-ntasks":
            skip = True
        elif not a.endswith(".py"):
            out.append(a)
    return out


def RESET():
    """Erases everything defined so far; numbering starts again from 0."""
    global _model
    _model = _Model(_deck_prefix)


def TSERIES(points):
    """A time series: a constant, a flat list [t0, v0, t1, v1, ...], a list of pairs
    [[t0, v0], ...] or the path of a file of `t v` lines (`#` starts a comment). Returns its
    number."""
    n = len(_model.tseries)
    name = "TSERIES %d" % n
    if _is_number(points):
        f = _grain.TimeFunction.constant(float(points))
    else:
        if isinstance(points, str):
            t, v = [], []
            try:
                with open(points) as fh:
                    for k, line in enumerate(fh, 1):
                        line = line.split("#", 1)[0].split()
                        if not line:
                            continue
                        if len(line) != 2:
                            raise ValueError("TSERIES: file '%s' line %d: %d values; valid: "
                                             "two numbers 't v'" % (points, k, len(line)))
                        t.append(float(line[0]))
                        v.append(float(line[1]))
            except OSError as e:
                raise ValueError("TSERIES: file '%s' cannot be read (%s)" % (points, e.strerror))
        elif isinstance(points, (list, tuple)) and points and \
                all(isinstance(p, (list, tuple)) for p in points):
            if not all(len(p) == 2 and _is_number(p[0]) and _is_number(p[1]) for p in points):
                raise TypeError("TSERIES: argument 'points' = %r is invalid; valid: pairs "
                                "[t, v] of numbers" % (points,))
            t = [float(p[0]) for p in points]
            v = [float(p[1]) for p in points]
        elif isinstance(points, (list, tuple)):
            flat = _numbers("TSERIES", "points", points)
            if len(flat) % 2:
                raise ValueError("TSERIES: argument 'points' has %d values; valid: an even "
                                 "number [t0, v0, t1, v1, ...]" % len(flat))
            t, v = flat[0::2], flat[1::2]
        else:
            raise TypeError("TSERIES: argument 'points' = %r is invalid; valid: a number, a list "
                            "[t0, v0, ...], a list of pairs [[t0, v0], ...] or a file path"
                            % (points,))
        f = _grain.TimeFunction.table(t, v, name)
    _model.tseries.append(f)
    _model.tseries_points.append(None if _is_number(points) else (t, v))
    return n


def MATERIAL(density, young, poisson):
    """A material: density [kg/m^3], Young's modulus [Pa], Poisson's ratio. Returns its number."""
    d = _positive("MATERIAL", "density", density)
    e = _positive("MATERIAL", "young", young)
    p = _number("MATERIAL", "poisson", poisson)
    if not -1.0 < p < 0.5:
        raise ValueError("MATERIAL: argument 'poisson' = %r is invalid; valid range: (-1, 0.5)"
                         % (poisson,))
    _model.materials.append((d, e, p))
    return len(_model.materials) - 1


def MESH(nodes, elements, material, colors):
    """A meshed particle from nodes [x0, y0, z0, ...], elements [n, i1 .. in, material, ...]
    (n = 4, 5, 6 or 8) and surface colours [gcolor, f, i1 .. if, color, ...] or gcolor; it has
    the mass and inertia of its elements. Returns its particle number."""
    xyz = _numbers("MESH", "nodes", nodes)
    elems = _integers("MESH", "elements", elements)
    _material("MESH", "material", material)
    if isinstance(colors, numbers.Integral) and not isinstance(colors, bool):
        colors = [colors]
    cols = _integers("MESH", "colors", colors)
    if any(e < 0 for e in elems):
        raise ValueError("MESH: argument 'elements' holds a negative entry; valid: node counts, "
                         "node numbers and MATERIAL numbers >= 0")
    densities = [m[0] for m in _model.materials]
    n = len(_model.particles)
    b = _model.system.add_mesh(xyz, elems, densities, cols, "MESH particle %d" % n)
    _model.particles.append(b)
    return n


def ANALYTICAL(inertia=None, mass=None, rotation=None, position=None, material=None,
               particle=None):
    """A particle without shape: inertia [Ixx, Iyy, Izz, Ixy, Ixz, Iyz] [kg m^2] (default
    [1, 1, 1, 0, 0, 0]), mass [kg] (default 1), rotation [e1x, e1y, e1z, e2x, ...] (the
    columns of the reference frame's rotation, default identity), position (x, y, z) [m]
    (default the origin). Returns its particle number."""
    j = _numbers("ANALYTICAL", "inertia", inertia, 6) if inertia is not None else None
    m = _positive("ANALYTICAL", "mass", mass) if mass is not None else None
    r = _numbers("ANALYTICAL", "rotation", rotation, 9) if rotation is not None else None
    x = _vector("ANALYTICAL", "position", position) if position is not None else None
    if material is not None:
        _material("ANALYTICAL", "material", material)
    if particle is not None:
        k = _particle("ANALYTICAL", "particle", particle)
        if k in _model.spheres:
            # a sphere leaves the contacts and becomes a body with its own values or those given
            if _model.particles[k] is not None:
                raise ValueError("ANALYTICAL: argument 'particle' = %r is invalid: the sphere is "
                                 "held by a spring, joint or restraint already; valid: a sphere "
                                 "converted before those" % (particle,))
            _model.particles[k] = _model.model.convert(_model.spheres[k], m, j, r, x,
                                                       "ANALYTICAL particle %d" % k)
            del _model.spheres[k]
            return k
        # a MESH or ANALYTICAL particle is a body without contact already: it stays as it is
        if any(v is not None for v in (inertia, mass, rotation, position)):
            raise NotImplementedError("ANALYTICAL: new inertia, mass, rotation or position for a "
                                      "MESH or ANALYTICAL particle are not supported yet by "
                                      "grain-parmec (for a SPHERE they are)")
        return k
    j = j if j is not None else [1.0, 1.0, 1.0, 0.0, 0.0, 0.0]
    m = m if m is not None else 1.0
    r = r if r is not None else [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0]
    x = x if x is not None else (0.0, 0.0, 0.0)
    n = len(_model.particles)
    b = _model.system.add_analytical(j, m, r, x, "ANALYTICAL particle %d" % n)
    _model.particles.append(b)
    return n


def VELOCITY(parnum, linear=(0.0, 0.0, 0.0), angular=(0.0, 0.0, 0.0)):
    """Initial linear [m/s] and angular [rad/s] velocity of a particle (world axes)."""
    i = _particle("VELOCITY", "parnum", parnum)
    v, w = _vector("VELOCITY", "linear", linear), _vector("VELOCITY", "angular", angular)
    if _model.particles[i] is None:  # a sphere of the particle simulation
        _model.model.set_sphere_velocity(_model.spheres[i], v, w)
    else:
        _model.system.set_velocity(_model.particles[i], v, w)


def SPHERE(center, radius, material, color):
    """A spherical particle: centre (x, y, z) [m], radius [m], MATERIAL number and a positive
    surface colour (which selects the GRANULAR law of its contacts). Returns its number."""
    cmd = "SPHERE"
    c = _vector(cmd, "center", center)
    r = _positive(cmd, "radius", radius)
    m = _material(cmd, "material", material)
    col = _colour(cmd, "color", color)
    if _model.started and not _model.model.particles():
        raise ValueError("SPHERE: a sphere after a DEM of bodies alone is invalid; valid: "
                         "spheres and obstacles defined before the first DEM (or after RESET)")
    sid = _model.model.add_sphere(c, r, _grain_material(m, col))
    _model.particles.append(None)
    n = len(_model.particles) - 1
    _model.spheres[n] = sid
    return n


def OBSTACLE(triangles, color, point=(0.0, 0.0, 0.0), linear=None, angular=None):
    """An obstacle of triangles [(x1, y1, z1, x2, y2, z2, x3, y3, z3), ...] [m] with a positive
    colour, or one colour per triangle, moving with the velocity linear(t) [m/s] of its
    reference point `point` and the angular velocity angular(t) [rad/s] about it (callbacks
    returning 3 numbers; default: at rest)."""
    cmd = "OBSTACLE"
    if not isinstance(triangles, (list, tuple)) or not triangles or \
            not all(isinstance(t, (list, tuple)) and len(t) == 9 and all(_is_number(c) for c in t)
                    for t in triangles):
        raise TypeError("%s: argument 'triangles' = %r is invalid; valid: a list of 9-tuples "
                        "(x1, y1, z1, x2, y2, z2, x3, y3, z3)" % (cmd, triangles))
    if isinstance(color, (list, tuple)):
        if len(color) != len(triangles):
            raise ValueError("%s: argument 'color' has %d colours for %d triangles; valid: one "
                             "colour, or one per triangle" % (cmd, len(color), len(triangles)))
        colours = [_colour(cmd, "color", c) for c in color]
    else:
        colours = [_colour(cmd, "color", color)] * len(triangles)
    p = _vector(cmd, "point", point)
    for name, f in (("linear", linear), ("angular", angular)):
        if f is not None and not callable(f):
            raise TypeError("%s: argument '%s' = %r is invalid; valid: a callback of time "
                            "returning (x, y, z)" % (cmd, name, f))
    if _model.started and not _model.model.particles():
        raise ValueError("OBSTACLE: an obstacle after a DEM of bodies alone is invalid; valid: "
                         "spheres and obstacles defined before the first DEM (or after RESET)")
    _model.model.add_obstacle([tuple(float(c) for c in t) for t in triangles],
                              [_grain_material(-1, c) for c in colours], p,
                              None if linear is None else _vector_callback(cmd, "linear", linear),
                              None if angular is None else
                              _vector_callback(cmd, "angular", angular),
                              "OBSTACLE %d" % _model.obstacles)
    _model.obstacles += 1


def GRANULAR(color1, color2, spring, damper=1.0, friction=0.0, rolling=0.0, drilling=0.0,
             kskn=0.5):
    """The contact law of a pair of surface colours (color1 = color2 = 0: of the pairs not given
    otherwise): a linear normal spring [N/m] with a damper given as a critical damping ratio
    (of each contact's effective mass), Coulomb friction mu or (mu_s, mu_d), and a tangential
    spring and dashpot kskn times the normal ones. `rolling` and `drilling` are accepted and,
    as in Parmec, act on nothing yet."""
    cmd = "GRANULAR"
    if (color1, color2) != (0, 0):
        c1, c2 = _colour(cmd, "color1", color1), _colour(cmd, "color2", color2)
    else:
        c1 = c2 = 0
    k = _positive(cmd, "spring", spring)
    d = _number(cmd, "damper", damper)
    if not d >= 0.0:
        raise ValueError("%s: argument 'damper' = %r is invalid; valid range: [0, inf) (a "
                         "critical damping ratio)" % (cmd, damper))
    if isinstance(friction, (tuple, list)):
        if len(friction) != 2 or not all(_is_number(f) for f in friction):
            raise TypeError("%s: argument 'friction' = %r is invalid; valid: a number or a pair "
                            "(mu_s, mu_d)" % (cmd, friction))
        mus, mud = float(friction[0]), float(friction[1])
    else:
        mus = mud = _number(cmd, "friction", friction)
    if not 0.0 <= mud <= mus:
        raise ValueError("%s: argument 'friction' = %r is invalid; valid: 0 <= mu_d <= mu_s"
                         % (cmd, friction))
    _number(cmd, "rolling", rolling)
    _number(cmd, "drilling", drilling)
    r = _positive(cmd, "kskn", kskn)
    _model.granular[(min(c1, c2), max(c1, c2))] = (k, float(d), mus, mud, r)


def _apply_granular():
    """GRANULAR's laws for every pair of grain materials of which one is a sphere's (again only
    when a law or a material has been added since: setting them re-initialises the run)."""
    state = (tuple(sorted(_model.granular.items())), len(_model.grain_materials))
    if state == _model.applied:
        return
    _model.applied = state
    keys = list(_model.grain_materials.items())
    for a, ((ma, ca), ka) in enumerate(keys):
        for (mb, cb), kb in keys[a:]:
            if ma < 0 and mb < 0:
                continue  # two obstacles never touch
            # the seed's defaults for pairs without a law: spring 0 (no force), damper 1,
            # no friction, kskn 0.5
            law = _model.granular.get((min(ca, cb), max(ca, cb)),
                                      _model.granular.get((0, 0), (0.0, 1.0, 0.0, 0.0, 0.5)))
            _model.model.set_pair(ka, kb, *law)


def GRAVITY(gx, gy, gz):
    """The gravitational acceleration [m/s^2]: each component a number, a TSERIES number or a
    callable of time."""
    _model.model.set_gravity(_time_function("GRAVITY", "gx", gx),
                              _time_function("GRAVITY", "gy", gy),
                              _time_function("GRAVITY", "gz", gz))


def _directions(cmd, name, x):
    """A list of 3, 6 or 9 numbers: up to three directions (zero vectors are none)."""
    if not isinstance(x, (tuple, list)) or len(x) not in (3, 6, 9) or \
            not all(_is_number(c) for c in x):
        raise TypeError("%s: argument '%s' = %r is invalid; valid: a list of 3, 6 or 9 numbers "
                        "(one to three directions [x1, y1, z1, ...])" % (cmd, name, x))
    dirs = [tuple(float(c) for c in x[k:k + 3]) for k in range(0, len(x), 3)]
    return [d for d in dirs if any(c != 0.0 for c in d)]


def RESTRAIN(parnum, linear=(0.0, 0.0, 0.0), angular=(0.0, 0.0, 0.0)):
    """Restrains the motion of a particle along up to three `linear` directions and its spatial
    rotation about up to three `angular` axes (lists [x1, y1, z1, x2, ...]; world axes)."""
    i = _particle("RESTRAIN", "parnum", parnum)
    _model.system.restrain(_body(i), _directions("RESTRAIN", "linear", linear),
                           _directions("RESTRAIN", "angular", angular))


def PRESCRIBE(parnum, linear=None, angular=None, kind="vv"):
    """Prescribes the motion of a particle: `linear` and `angular` each a tuple (i, j, k) of
    TSERIES numbers or a callback of time returning (x, y, z), read as velocities [m/s], [rad/s]
    or accelerations [m/s^2], [rad/s^2] as `kind` says ('vv' default, 'va', 'av', 'aa'; linear
    first). It overrides the dynamics and the restraints of the components it gives."""
    i = _particle("PRESCRIBE", "parnum", parnum)
    if kind not in ("vv", "va", "av", "aa"):
        raise ValueError("PRESCRIBE: argument 'kind' = %r is invalid; valid values: 'vv', 'va', "
                         "'av', 'aa'" % (kind,))
    if linear is None and angular is None:
        raise ValueError("PRESCRIBE: arguments 'linear' and 'angular' are both missing; valid: "
                         "at least one history")
    lin = None if linear is None else _vector_history("PRESCRIBE", "linear", linear)
    ang = None if angular is None else _vector_history("PRESCRIBE", "angular", angular)
    _model.system.prescribe(_body(i), lin, ang, kind)


def DAMPING(linear, angular):
    """Global damping: `linear` and `angular` each a callback of time returning the coefficients
    (dx, dy, dz) [1/s] or a tuple (i, j, k) of TSERIES numbers; force -m d_v v, torque
    -J d_w omega per world axis."""
    _model.system.set_damping(_vector_history("DAMPING", "linear", linear),
                              _vector_history("DAMPING", "angular", angular))


# Parmec continues its lookup tables linearly beyond their end points; grain's tables hold their
# end values. A table is therefore extended along its first and last segments out to this many
# times its span on either side.
_EXTEND = 1E3


def _extended(xs, ys):
    span = xs[-1] - xs[0]
    lo, hi = xs[0] - _EXTEND * span, xs[-1] + _EXTEND * span
    y_lo = ys[0] + (lo - xs[0]) * (ys[1] - ys[0]) / (xs[1] - xs[0])
    y_hi = ys[-1] + (hi - xs[-1]) * (ys[-1] - ys[-2]) / (xs[-1] - xs[-2])
    return [lo] + xs + [hi], [y_lo] + ys + [y_hi]


def _table(cmd, name, x, what):
    """A lookup table [x0, y0, x1, y1, ...] with increasing abscissae, as (xs, ys) extended
    linearly beyond its end points as Parmec reads it."""
    flat = _numbers(cmd, name, x)
    if len(flat) < 4 or len(flat) % 2:
        raise ValueError("%s: argument '%s' has %d values; valid: an even number, at least 4 "
                         "([%s0, %s0, %s1, %s1, ...])" % (cmd, name, len(flat), what[0], what[1],
                                                           what[0], what[1]))
    xs, ys = flat[0::2], flat[1::2]
    if any(b <= a for a, b in zip(xs, xs[1:])):
        raise ValueError("%s: argument '%s' has %s values %r that do not increase; valid: "
                         "strictly increasing" % (cmd, name, what[0], xs))
    return _extended(xs, ys)


def _point_or_plane(cmd, x):
    """geom2 of SPRING: a point (x, y, z), or a plane [(point), (normal)]."""
    if isinstance(x, (tuple, list)) and len(x) == 2 and all(isinstance(v, (tuple, list))
                                                            for v in x):
        return _vector(cmd, "geom2[0]", x[0]), _vector(cmd, "geom2[1]", x[1])
    if isinstance(x, (tuple, list)) and len(x) == 3:
        return _vector(cmd, "geom2", x), None
    raise TypeError("%s: argument 'geom2' = %r is invalid; valid: a point (x, y, z) or a plane "
                    "[(x, y, z), (nx, ny, nz)]" % (cmd, x))


def SPRING(part1, point1, part2, geom2, spring, dashpot=None, direction=None, planar="OFF",
           unload=None, ylim=(0.0, 0.0), inactive=False, offset=-1, friction=0.0, kskn=0.0):
    """A translational spring from `point1` of part1 to `geom2` of part2 (-1: fixed): a point
    (x, y, z), or a plane [(point), (normal)]; `spring` the force-stroke table [s, f, ...]
    [m, N] (positive f pulls the points together), `dashpot` a force-velocity table [v, f, ...]
    [m/s, N] or a critical damping ratio >= 0, `direction` a constant direction (with
    planar='ON': the spring acts in the plane normal to it), `unload` the unloading curve,
    `ylim` = (fyc <= 0, fyt >= 0) the yield forces, `inactive` a dormant spring, `offset` a
    TSERIES number shifting the stroke, `friction` >= 0 and `kskn` >= 0. Points at the same
    place (a zero-length spring) act once they separate. Returns its number."""
    cmd = "SPRING"
    i = _particle(cmd, "part1", part1)
    p1 = _vector(cmd, "point1", point1)
    j = _particle(cmd, "part2", part2, allow_none=True)
    p2, normal = _point_or_plane(cmd, geom2)
    spec = _grain.SpringSpec()
    xs, ys = _table(cmd, "spring", spring, ("stroke", "force"))
    plane = normal is not None
    # a point-to-plane spring: Parmec's force on part1 is +f n and its dashpot velocity
    # n . (v2 - v1); grain's are f e, e = -n, and e . (v2 - v1): the force table is negated and
    # the dashpot table mirrored, f_d(v) -> -f_d(-v) (the yield limits swap and change sign)
    spec.spring_x, spec.spring_y = xs, [-y if plane else y for y in ys]
    if dashpot is not None:
        if _is_number(dashpot):
            if not dashpot >= 0:
                raise ValueError("SPRING: argument 'dashpot' = %r is invalid; valid range: "
                                 "[0, inf) (a critical damping ratio)" % (dashpot,))
            spec.ratio = float(dashpot)
        else:
            xs, ys = _table(cmd, "dashpot", dashpot, ("velocity", "force"))
            if plane:
                xs, ys = [-x for x in reversed(xs)], [-y for y in reversed(ys)]
            spec.dashpot_x, spec.dashpot_y = xs, ys
    if plane:
        spec.geometry = "point_to_plane"
    elif direction is not None:
        spec.direction = _vector(cmd, "direction", direction)
        if planar not in ("ON", "OFF"):
            raise ValueError("SPRING: argument 'planar' = %r is invalid; valid values: 'ON', 'OFF'"
                             % (planar,))
        spec.geometry = "planar" if planar == "ON" else "constant_direction"
    if unload is not None:
        if plane:
            raise NotImplementedError("SPRING: argument 'unload' with a plane (geom2) is not "
                                      "supported yet by grain-parmec")
        spec.unload_x, spec.unload_y = _table(cmd, "unload", unload, ("stroke", "force"))
    if not isinstance(ylim, (tuple, list)) or len(ylim) != 2 or \
            not all(_is_number(y) for y in ylim):
        raise TypeError("SPRING: argument 'ylim' = %r is invalid; valid: a pair (fyc <= 0, "
                        "fyt >= 0)" % (ylim,))
    fyc, fyt = float(ylim[0]), float(ylim[1])
    spec.fyc, spec.fyt = (-fyt, -fyc) if plane else (fyc, fyt)
    if not isinstance(inactive, bool):
        raise TypeError("SPRING: argument 'inactive' = %r is invalid; valid: True or False"
                        % (inactive,))
    spec.inactive = inactive
    if offset != -1:
        if not isinstance(offset, numbers.Integral) or isinstance(offset, bool) or \
                not 0 <= offset < len(_model.tseries):
            raise ValueError("SPRING: argument 'offset' = %r is invalid; valid: -1 (none) or "
                             "[0, %d) (a TSERIES number)" % (offset, len(_model.tseries)))
        spec.offset = _model.tseries[int(offset)]
    spec.friction = _number(cmd, "friction", friction)
    spec.kskn = _number(cmd, "kskn", kskn)
    n = len(_model.springs)
    _model.system.add_spring(spec, _body(i), p1,
                             _body(j) if j >= 0 else -1, p2,
                             normal if plane else (0.0, 0.0, 0.0), "SPRING %d" % n)
    _model.springs.append(plane)
    return n


def TORSION_SPRING(part1, part2, zdir, xdir, kroll=None, kpitch=None, kyaw=None, droll=None,
                   dpitch=None, dyaw=None, cone=None, refpnt=None):
    """A torsion spring between part1 and part2 (-1: a fixed frame) with the directions zdir
    (yaw) and xdir (roll, orthogonal to zdir) now; pitch about y = z x x. k-tables [angle,
    torque, ...] [rad, N m] and d-tables [rate, torque, ...] [rad/s, N m] or critical damping
    ratios >= 0, each default zero; `cone` couples two or three angles ('roll', 'pitch',
    'yaw'); `refpnt` the point where the output shows it (it moves with part1; default: the
    midpoint of the two centres). Torques on part1 as in Parmec: a restoring table has a
    negative slope. Returns its number."""
    cmd = "TORSION_SPRING"
    i = _particle(cmd, "part1", part1)
    j = _particle(cmd, "part2", part2, allow_none=True)
    z = _vector(cmd, "zdir", zdir)
    x = _vector(cmd, "xdir", xdir)
    ref = None if refpnt is None else _vector(cmd, "refpnt", refpnt)
    axes = []
    for k_name, k, d_name, d in (("kroll", kroll, "droll", droll),
                                 ("kpitch", kpitch, "dpitch", dpitch),
                                 ("kyaw", kyaw, "dyaw", dyaw)):
        a = _grain.TorsionAxis()
        # Parmec's torque on part1 is +table(angle); grain's is -table(angle): the tables are
        # negated (a damping ratio is a ratio either way)
        if k is not None:
            xs, ys = _table(cmd, k_name, k, ("angle", "torque"))
            a.spring_x, a.spring_y = xs, [-y for y in ys]
        if d is not None:
            if _is_number(d):
                if not d >= 0:
                    raise ValueError("%s: argument '%s' = %r is invalid; valid range: [0, inf) "
                                     "(a critical damping ratio)" % (cmd, d_name, d))
                a.ratio = float(d)
            else:
                xs, ys = _table(cmd, d_name, d, ("rate", "torque"))
                a.dashpot_x, a.dashpot_y = xs, [-y for y in ys]
        axes.append(a)
    flags = [False, False, False]
    if cone is not None:
        names = ("roll", "pitch", "yaw")
        if not isinstance(cone, (tuple, list)) or len(cone) not in (2, 3) or \
                not all(c in names for c in cone) or len(set(cone)) != len(cone):
            raise ValueError("%s: argument 'cone' = %r is invalid; valid: ('roll', 'yaw'), "
                             "('roll', 'pitch'), ('pitch', 'yaw') or ('roll', 'pitch', 'yaw')"
                             % (cmd, cone))
        flags = [n in cone for n in names]
    n = _model.torsion_springs
    _model.system.add_torsion_spring(_body(i), _body(j) if j >= 0 else -1,
                                     z, x, axes, flags, "TORSION_SPRING %d" % n, ref)
    _model.torsion_springs += 1
    return n


def _spring_numbers(cmd, name, x):
    n = len(_model.springs)
    if not isinstance(x, (tuple, list)) or not x or \
            not all(isinstance(k, numbers.Integral) and not isinstance(k, bool) and 0 <= k < n
                    for k in x) or len(set(x)) != len(x):
        raise ValueError("%s: argument '%s' = %r is invalid; valid: a non-empty list of distinct "
                         "SPRING numbers in [0, %d)" % (cmd, name, x, n))
    return [int(k) for k in x]


def UNSPRING(tsprings, msprings, limits, entity="SF", operator="SUM", abs=False, nsteps=1,
             nfreq=1, unload=None, activate=None):
    """A rule that undoes the springs `msprings` once the `entity` ('STROKE', 'F', 'SF' or
    'FF') of the springs `tsprings`, combined by `operator` ('SUM', 'MIN' or 'MAX'; of absolute
    values if `abs`), leaves `limits` = (min, max) (either None) for `nfreq` checks made every
    `nsteps` steps; `unload` = {spring: TSERIES number} unloads a spring gradually along that
    curve, `activate` lists dormant springs switched on then. Returns its number."""
    cmd = "UNSPRING"
    t = _spring_numbers(cmd, "tsprings", tsprings)
    m = _spring_numbers(cmd, "msprings", msprings)
    if not isinstance(limits, (tuple, list)) or len(limits) != 2 or \
            not all(v is None or _is_number(v) for v in limits) or limits == (None, None):
        raise ValueError("UNSPRING: argument 'limits' = %r is invalid; valid: (min, max), either "
                         "None, numbers with min < max" % (limits,))
    lo, hi = [None if v is None else float(v) for v in limits]
    if entity not in ("STROKE", "F", "SF", "FF"):
        raise ValueError("UNSPRING: argument 'entity' = %r is invalid; valid values: 'STROKE', "
                         "'F', 'SF', 'FF'" % (entity,))
    if operator not in ("SUM", "MIN", "MAX"):
        raise ValueError("UNSPRING: argument 'operator' = %r is invalid; valid values: 'SUM', "
                         "'MIN', 'MAX'" % (operator,))
    if entity in ("F", "SF") and any(_model.springs[k] for k in t):
        # a point-to-plane spring: grain's forces are Parmec's negated
        if not all(_model.springs[k] for k in t) or abs:
            raise NotImplementedError("UNSPRING: a force test over point-to-plane springs mixed "
                                      "with others, or of absolute values, is not supported yet "
                                      "by grain-parmec")
        lo, hi = (None if hi is None else -hi), (None if lo is None else -lo)
        operator = {"MIN": "MAX", "MAX": "MIN"}.get(operator, operator)
    curves = []
    for spring, series in (unload or {}).items():
        if spring not in m:
            raise ValueError("UNSPRING: argument 'unload' has spring %r; valid: one of msprings %r"
                             % (spring, m))
        if not isinstance(series, numbers.Integral) or not 0 <= series < len(_model.tseries) or \
                _model.tseries_points[series] is None:
            raise ValueError("UNSPRING: argument 'unload' = {%r: %r} is invalid; valid: a TSERIES "
                             "number of a table" % (spring, series))
        xs, ys = _model.tseries_points[series]
        curves.append((spring, xs, ys))
    act = [] if activate is None else _spring_numbers(cmd, "activate", activate)
    n = _model.unsprings
    _model.system.add_unspring(t, m, lo, hi, entity, operator, bool(abs),
                               int(nsteps), int(nfreq), curves, act, "UNSPRING %d" % n)
    _model.unsprings += 1
    return n


def BALL_JOINT(part1, point, part2=-1):
    """A ball joint at `point` [m] between part1 and part2 (-1: part1 pinned to the point).
    Returns its number."""
    i = _particle("BALL_JOINT", "part1", part1)
    p = _vector("BALL_JOINT", "point", point)
    j = _particle("BALL_JOINT", "part2", part2, allow_none=True)
    _model.system.add_ball_joint(_body(i), p,
                                 _body(j) if j >= 0 else -1)
    _model.joints += 1
    return _model.joints - 1


def EQM(part1, point1, part2=None, point2=None, direction=None):
    """The equivalent point mass [kg] of part1 at point1 (relative to point2 of part2 if given;
    along `direction` if given, else the smallest over all directions)."""
    i = _particle("EQM", "part1", part1)
    p1 = _vector("EQM", "point1", point1)
    j = -1
    p2 = (0.0, 0.0, 0.0)
    if part2 is not None:
        j = _body(_particle("EQM", "part2", part2))
        if point2 is None:
            raise ValueError("EQM: argument 'point2' is missing; valid: a point (x, y, z) of "
                             "part2")
        p2 = _vector("EQM", "point2", point2)
    d = None if direction is None else _vector("EQM", "direction", direction)
    return _model.system.equivalent_mass(_body(i), p1, j, p2, d)


def HISTORY(entity, source=0, point=None, h5file=None, h5last=False):
    """A list filled during DEM with the time ('TIME') or an entity of a particle (PX .. |T|)
    or joint (JREAC_X .. |JREAC|) `source`, sampled at DEM's history interval."""
    if not isinstance(entity, str):
        raise TypeError("HISTORY: argument 'entity' = %r is invalid; valid: a string"
                        % (entity,))
    if h5file is not None:
        raise NotImplementedError("HISTORY: argument 'h5file' is not supported yet by "
                                  "grain-parmec")
    out = []
    if entity == "TIME":
        if not _model.particles:
            raise ValueError("HISTORY: no particle has been defined; valid: HISTORY after a "
                             "particle command")
        if _model.started:  # requested between runs: from the current time on
            out.append(_model.model.time())
        _model.histories.append((out, None))
        return out
    if entity in _BODY_ENTITIES:
        if isinstance(source, tuple):
            if len(source) not in (4, 6) or not all(_is_number(c) for c in source):
                raise ValueError("HISTORY: argument 'source' = %r is invalid; valid: a particle "
                                 "number, a list of them, a sphere (x, y, z, r) or a box (xmin, "
                                 "ymin, zmin, xmax, ymax, zmax)" % (source,))
            # a live region: a sphere (x, y, z, r) or a box (xmin, ymin, zmin, xmax, ymax, zmax)
            if point is not None:
                raise ValueError("HISTORY: argument 'point' is invalid with a region source; "
                                 "valid: a point of a single particle")
            region = [float(c) for c in source]
            if len(region) == 4 and not region[3] > 0 or \
                    len(region) == 6 and not all(region[k] <= region[k + 3] for k in range(3)):
                raise ValueError("HISTORY: argument 'source' = %r is invalid; valid: a sphere "
                                 "(x, y, z, r > 0) or a box (xmin, ymin, zmin, xmax, ymax, zmax) "
                                 "with min <= max" % (source,))
            column = _model.recorder.add_region(_model.model, region, entity)
        elif isinstance(source, list):
            # a list of particles: the average of their values
            if point is not None:
                raise ValueError("HISTORY: argument 'point' is invalid with a list of sources; "
                                 "valid: a point of a single particle")
            if not source:
                raise ValueError("HISTORY: argument 'source' = %r is invalid; valid: a particle "
                                 "number or a non-empty list of them" % (source,))
            column = [_particle_column(_particle("HISTORY", "source", i), entity)
                      for i in source]
        else:
            i = _particle("HISTORY", "source", source)
            if point is not None:
                p = _vector("HISTORY", "point", point)
                column = _model.recorder.add_point(_model.system, _body(i), p, entity)
            else:
                column = _particle_column(i, entity)
    elif entity in _SPRING_ENTITIES:
        if not isinstance(source, numbers.Integral) or not 0 <= source < len(_model.springs):
            raise ValueError("HISTORY: argument 'source' = %r is invalid; valid: [0, %d) (a "
                             "SPRING number)" % (source, len(_model.springs)))
        column = _model.recorder.add(_model.system, "spring", int(source), entity)
        if _model.springs[source] and entity in ("F", "SF"):
            column = -1 - column  # a point-to-plane spring: Parmec's sign (see SPRING)
    elif entity in _TORSION_ENTITIES:
        if not isinstance(source, numbers.Integral) or not 0 <= source < _model.torsion_springs:
            raise ValueError("HISTORY: argument 'source' = %r is invalid; valid: [0, %d) (a "
                             "TORSION_SPRING number)" % (source, _model.torsion_springs))
        column = _model.recorder.add(_model.system, "torsion_spring", int(source), entity)
        if entity in _NEGATED:
            column = -1 - column
    elif entity in _JOINT_ENTITIES:
        if not isinstance(source, numbers.Integral) or not 0 <= source < _model.joints:
            raise ValueError("HISTORY: argument 'source' = %r is invalid; valid: [0, %d) (a "
                             "BALL_JOINT number)" % (source, _model.joints))
        column = _model.recorder.add(_model.system, "joint", int(source), entity)
    else:
        raise ValueError("HISTORY: argument 'entity' = %r is invalid; valid values: TIME, %s"
                         % (entity, ", ".join(_BODY_ENTITIES + _SPRING_ENTITIES +
                                              _TORSION_ENTITIES + _JOINT_ENTITIES)))
    if _model.started:
        # requested between runs: the list starts with the current value (the next run's first
        # sample is at the same time and is not repeated)
        out.extend(_values(column, [[_model.recorder.value(c)] for c in
                                    range(_model.recorder.size())]))
    _model.histories.append((out, column))
    return out


def _particle_column(i, entity):
    """A recorder column of an entity of particle i (a body, or a sphere that is not one)."""
    if _model.particles[i] is None:
        return _model.recorder.add_particle(_model.model, _model.spheres[i], entity)
    return _model.recorder.add(_model.system, "body", _model.particles[i], entity)


def _values(column, values):
    """The samples of a history's column(s) in Parmec's sign: `values` per recorder column."""
    if isinstance(column, list):  # the average over a list of particles
        n = len(column)
        return [sum(c) / n for c in zip(*(values[k] for k in column))]
    if column < 0:  # a quantity grain reports with the opposite sign of Parmec's
        return [-v for v in values[-1 - column]]
    return list(values[column])


_OUTPUT_ENTITIES = ["NUMBER", "COLOR", "DISPL", "LENGTH", "ORIENT", "ORIENT1", "ORIENT2",
                    "ORIENT3", "LINVEL", "ANGVEL", "FORCE", "TORQUE", "F", "FN", "FT", "SF", "FF",
                    "SS", "AREA", "PAIR", "XDIR", "YDIR", "ZDIR", "TRQROT", "TRQTOT", "TRQSPR",
                    "JREAC"]
# OUTPUT modes: (body files of grain::bodies::BodyVtkFiles, spheres, contacts)
_OUTPUT_MODES = {"SPH": (0, True, False), "MESH": (2, False, False), "RB": (1, False, False),
                 "CD": (0, True, True), "SL": (4, False, False), "ST": (8, False, False),
                 "TS": (8, False, False), "JT": (16, False, False)}


def OUTPUT(entities=None, subset=None, mode=None, format=None):
    """A further family of output files, `<prefix>1_...`, `<prefix>2_...` in call order (the
    default family of DEM is always written): of the particles `subset` (a number or a list;
    default all) and the files of `mode` (SPH spheres, MESH meshes, RB bodies, CD spheres with
    their contacts, SL springs, ST/TS torsion springs, JT joints; a string or a list; default
    all). `entities` are checked against Parmec's list; each file carries all of grain's fields
    for its kind (a superset). `format`: 'VTK' or Parmec's default 'XDMF' write grain's legacy
    VTK files with ParaView series files."""
    cmd = "OUTPUT"
    if entities is not None:
        names = [entities] if isinstance(entities, str) else entities
        if not isinstance(names, (list, tuple)) or not names or \
                not all(e in _OUTPUT_ENTITIES for e in names):
            raise ValueError("%s: argument 'entities' = %r is invalid; valid: a list of %s"
                             % (cmd, entities, ", ".join(_OUTPUT_ENTITIES)))
    modes = list(_OUTPUT_MODES) if mode is None else [mode] if isinstance(mode, str) else mode
    if not isinstance(modes, (list, tuple)) or not modes or \
            not all(m in _OUTPUT_MODES for m in modes):
        raise ValueError("%s: argument 'mode' = %r is invalid; valid: SPH, MESH, RB, CD, SL, ST, "
                         "TS, JT or a list of them" % (cmd, mode))
    formats = [format] if format is None or isinstance(format, str) else format
    for f in formats:
        if f in ("MED", "DUMP"):
            raise NotImplementedError("%s: format '%s' is not supported by grain-parmec; valid: "
                                      "'VTK' (or 'XDMF', written as VTK)" % (cmd, f))
        if f not in (None, "VTK", "XDMF"):
            raise ValueError("%s: argument 'format' = %r is invalid; valid: 'VTK', 'XDMF', "
                             "'MED', 'DUMP' or a list of them" % (cmd, format))
    if subset is None:
        parts = []
    elif isinstance(subset, (list, tuple)):
        parts = [_particle(cmd, "subset", k) for k in subset]
    else:
        parts = [_particle(cmd, "subset", subset)]
    bodies = [_model.particles[k] for k in parts if _model.particles[k] is not None]
    spheres = [_model.spheres[k] for k in parts if k in _model.spheres]
    if parts and not spheres:
        spheres = [-1]  # a subset without spheres shows none of them
    files, spheres_on, contacts = 0, False, False
    for m in modes:
        f, sp, cd = _OUTPUT_MODES[m]
        files |= f
        spheres_on |= sp
        contacts |= cd
    if parts and not bodies:
        files = 0  # a subset of spheres only: no body files
    _model.outputs += 1
    _model.model.add_output(_model.outputs, bodies, [s for s in spheres if s >= 0], files,
                            spheres_on and (not parts or any(s >= 0 for s in spheres)),
                            contacts)


def CRITICAL(perspring=None, perparticle=None):
    """The critical time step estimate [s] at the stiffest state of every spring (infinity when
    nothing limits the step); with `perspring` = n and/or `perparticle` = n, the n lowest
    per-spring and per-particle estimates as lists of (step, number, omega, xi), ascending (both:
    a pair of lists)."""
    if perspring is None and perparticle is None:
        h = _model.system.critical()
        if _model.spheres:
            _apply_granular()
            h = min(h, _model.model.critical_contacts())
        return h
    counts = []
    for name, value, total in (("perspring", perspring, len(_model.springs)),
                               ("perparticle", perparticle, len(_model.particles))):
        if value is None:
            counts.append(0)
            continue
        if not isinstance(value, numbers.Integral) or isinstance(value, bool) or \
                not 0 <= value <= total:
            raise ValueError("CRITICAL: argument '%s' = %r is invalid; valid range: [0, %d]"
                             % (name, value, total))
        counts.append(int(value))
    springs, bodies = _model.system.critical_lists(counts[0], counts[1])
    parnum = {b: k for k, b in enumerate(_model.particles) if b is not None}
    particles = [(h, parnum[b], w, xi) for h, b, w, xi in bodies]
    springs = [tuple(x) for x in springs]
    if perspring is not None and perparticle is not None:
        return springs, particles
    return springs if perspring is not None else particles


def _interval(value, step, name):
    """An output interval: a number, a TSERIES number or a callable of time [s]."""
    if value is None:
        return _grain.TimeFunction.constant(step)
    if isinstance(value, numbers.Integral) and not isinstance(value, bool) and \
            0 <= value < len(_model.tseries):
        return _model.tseries[int(value)]
    if callable(value):
        return _grain.TimeFunction.callable(_scalar_callback("DEM", name, value))
    return _grain.TimeFunction.constant(_positive("DEM", name, value))


def DEM(duration, step, interval=None, prefix=None, adaptive=None):
    """Runs the simulation for `duration` [s] with time steps `step` [s]; `interval` is the
    output interval [s] of the files and the histories, or a pair (files, histories) (default:
    the step); `prefix` names the output files (default: the deck's path without .py). Runs
    continue from where the last one stopped. Returns the wall-clock time taken [s]."""
    d = _positive("DEM", "duration", duration)
    h = _positive("DEM", "step", step)
    if not h <= d:
        raise ValueError("DEM: argument 'step' = %r is invalid; valid range: (0, duration = %r] s"
                         % (step, duration))
    if isinstance(interval, (tuple, list)):
        if len(interval) != 2:
            raise ValueError("DEM: argument 'interval' = %r is invalid; valid: a number or a "
                             "pair (files, histories)" % (interval,))
        files, history = _interval(interval[0], h, "interval[0]"), \
            _interval(interval[1], h, "interval[1]")
    else:
        files = history = _interval(interval, h, "interval")
    if prefix is not None:
        if not isinstance(prefix, str) or not prefix:
            raise TypeError("DEM: argument 'prefix' = %r is invalid; valid: a non-empty string"
                            % (prefix,))
        if _model.started and prefix != _model.prefix:
            raise ValueError("DEM: argument 'prefix' = %r is invalid after a run; valid: the "
                             "prefix of the first DEM (%r) until RESET" % (prefix, _model.prefix))
        _model.prefix = prefix
    if adaptive is not None:
        a = _number("DEM", "adaptive", adaptive)
        if not 0.0 <= a <= 1.0:
            raise ValueError("DEM: argument 'adaptive' = %r is invalid; valid range: [0, 1] (0: "
                             "off)" % (adaptive,))
        if a > 0.0 and _model.model.particles():
            raise NotImplementedError("DEM: argument 'adaptive' with spheres or obstacles is not "
                                      "supported yet by grain-parmec (bodies alone: it is)")
        _model.system.set_adaptive(a)
    if not _model.particles:
        raise ValueError("DEM: no particle has been defined; valid: DEM after a particle command")
    directory = os.path.dirname(_model.prefix)
    if directory:
        os.makedirs(directory, exist_ok=True)
    start = _time.perf_counter()
    if _model.model.particles():
        _apply_granular()
    _model.model.run(d, h, files, history, _model.recorder, _model.prefix)
    _model.started = True
    times, values = _model.recorder.take()
    for out, column in _model.histories:
        out.extend(times if column is None else _values(column, values))
    return _time.perf_counter() - start


def _not_yet(name):
    def command(*args, **kwargs):
        raise NotImplementedError("%s is not supported yet by grain-parmec (docs/parmec.md lists "
                                  "the commands it runs)" % name)
    command.__name__ = name
    return command


for _name in NOT_YET:
    globals()[_name] = _not_yet(_name)
    __all__.append(_name)


def namespace():
    """The commands, as a deck sees them."""
    return {name: globals()[name] for name in __all__}
