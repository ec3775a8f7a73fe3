"""Runs DEMLab projects on grain (the command `grain-demlab PROJECT.json`).

A DEMLab project is two files: `ProjectParameters.json` (analysis, solver, search, bounding box,
sinks, conditions, materials, interaction models, output, animations, graphs, prints) and the
model-parts file it names (particles, walls and named groups). This module

1. reads both files and checks every key and value against DEMLab's templates: an error names
   the file, the key (or the line of the model-parts file) and the valid values, before anything
   runs;
2. writes the C++ program of the project's models (`<project>/grain_demlab/program.cpp`, the
   `Interaction<...>` and `Simulation<...>` types, with a CMakeLists.txt to build it by hand) and
   the project's data (`<project>/grain_demlab/<name>.run`, read by the program at run time);
3. builds the program against grain's headers, cached per model combination (a second project with
   the same models starts at once), and runs it;
4. writes DEMLab's graphs (`<title>.txt`, and `<title>.png` where matplotlib is installed), its
   animations (`<title>.gif`, drawn by grain-plot) and grain's VTK series into
   `<project>/<name>_out/`.

Units are the project's own (DEMLab uses consistent units; SI in all its examples).
"""
import fcntl
import hashlib
import json
import math
import os
import shutil
import subprocess
import sys
import time

try:
    from . import _demlab_config as _config
except ImportError:  # the source tree without a build: the compiler on PATH, headers beside
    _config = None


class ProjectError(ValueError):
    """Bad input in a DEMLab project: names the file, the key or line, and the valid values."""


INF = float("inf")

# ---------------------------------------------------------------------------------------------
# DEMLab's keys and values (its templates ProjectParameters_template.json and
# ModelParts_template.txt)

ANALYSES = ("mechanical", "thermal", "thermo_mechanical")
SCHEMES = ("forward_euler", "modified_euler", "taylor_2")
FUNCTION_TYPES = ("constant", "linear", "oscillatory", "table")
INTERPOLATIONS = ("linear", "makima", "pchip", "spline")
SHAPES = ("rectangle", "circle", "polygon")

NORMAL_MODELS = ("viscoelastic_linear", "viscoelastic_nonlinear", "elastoplastic_linear")
TANGENT_MODELS = ("simple_slider", "simple_spring", "simple_dashpot", "spring_slider",
                  "dashpot_slider", "sds_linear", "sds_nonlinear")
STIFF_FORMULAS = ("energy", "overlap", "time")
DAMPING_FORMULAS = ("critical_ratio", "TTI", "KK", "LH")
TANGENT_FORMULAS = ("DD", "LTH", "ZZY", "TTI")
ROLLING_MODELS = ("constant", "viscous")
AREA_MODELS = ("ZYZ", "LMLB", "MPMH")
DIRECT_MODELS = ("bob", "thermal_pipe", "collisional")
INDIRECT_MODELS = ("vononoi_a", "vononoi_b", "surrounding_layer")
CELL_METHODS = ("voronoi_diagram", "porosity_local", "porosity_global")
NUSSELT = ("sphere_hanz_marshall", "sphere_whitaker")

GLOBAL_RESULTS = (
    "velocity_mod_avg", "velocity_rot_avg", "acceleration_mod_avg", "acceleration_rot_avg",
    "velocity_mod_min", "velocity_mod_max", "velocity_rot_min", "velocity_rot_max",
    "acceleration_mod_min", "acceleration_mod_max", "acceleration_rot_min", "acceleration_rot_max",
    "temperature_avg", "temperature_min", "temperature_max", "heat_rate_total",
    "conduction_direct_total", "conduction_indirect_total")
PARTICLE_RESULTS = (
    "radius", "mass", "coordinate_x", "coordinate_y", "orientation", "force_modulus", "force_x",
    "force_y", "torque", "velocity_modulus", "velocity_x", "velocity_y", "velocity_rot",
    "acceleration_modulus", "acceleration_x", "acceleration_y", "acceleration_rot",
    "temperature", "heat_rate")
GRAPH_AXES = ("time", "step") + GLOBAL_RESULTS + PARTICLE_RESULTS
ANIMATION_RESULTS = (
    "radius", "mass", "motion", "coordinate_x", "coordinate_y", "orientation", "force_vector",
    "force_modulus", "force_x", "force_y", "torque", "velocity_vector", "velocity_modulus",
    "velocity_x", "velocity_y", "velocity_rot", "acceleration_vector", "acceleration_modulus",
    "acceleration_x", "acceleration_y", "acceleration_rot", "heat_rate", "temperature")
SAVED_RESULTS = (
    "time", "step", "radius", "mass", "coord_x", "coord_y", "orientation", "wall_position",
    "force_x", "force_y", "torque", "velocity_x", "velocity_y", "velocity_rot", "acceleration_x",
    "acceleration_y", "acceleration_rot", "velocity_mod_avg", "velocity_rot_avg",
    "acceleration_mod_avg", "acceleration_rot_avg", "velocity_mod_min", "velocity_mod_max",
    "velocity_rot_min", "velocity_rot_max", "acceleration_mod_min", "acceleration_mod_max",
    "acceleration_rot_min", "acceleration_rot_max", "temperature", "temperature_avg",
    "temperature_min", "temperature_max", "wall_temperature", "heat_rate", "heat_rate_total",
    "conduction_direct_total", "conduction_indirect_total")
PRINTED_RESULTS = ("position", "velocity", "acceleration", "temperature")

# the keys of each section; the value is the checker's kind (see _Checker.value)
TARGETS = {"particles": "ids", "model_parts": "names"}
WALL_TARGETS = dict(TARGETS, walls="ids")
SECTIONS = {
    "ProblemData": {"name": "name", "analysis_type": ANALYSES, "model_parts_file": "string"},
    "Solver": {"integration_scheme_translation": SCHEMES,
               "integration_scheme_rotation": SCHEMES,
               "integration_scheme_thermal": ("forward_euler",),
               "auto_time_step": "bool", "time_step": "positive", "final_time": "positive",
               "eval_frequency": "count", "parallelization": "bool", "workers": "count"},
    "Search": {"scheme": ("simple_loop", "verlet_list"), "search_frequency": "count",
               "verlet_frequency": "count", "verlet_distance": "positive"},
    "BoundingBox": "region", "Sink": "regions",
    "GlobalCondition": {"gravity": "vector", "damping_translation": "nonnegative",
                        "damping_rotation": "nonnegative", "porosity": "fraction",
                        "fluid_velocity": "vector", "fluid_temperature": "nonnegative"},
    "InitialCondition": {"translational_velocity": "initial_vector",
                         "rotational_velocity": "initial_scalar",
                         "temperature": "initial_temperature"},
    "PrescribedCondition": {"force": "condition_vector", "torque": "condition_scalar",
                            "heat_flux": "condition_scalar", "heat_rate": "condition_scalar"},
    "FixedCondition": {"velocity_translation": "fixed_vector", "velocity_rotation": "fixed_scalar",
                       "temperature": "fixed_scalar"},
    "Material": "materials", "ConvectionModel": "convection", "InteractionModel": "interaction",
    "Output": {"progress_print": "positive", "number_output": "count1", "save_workspace": "bool",
               "saved_results": ("list", SAVED_RESULTS)},
    "Animation": "animations", "Graph": "graphs",
    "Print": {"single_file": "bool", "printed_results": ("list", PRINTED_RESULTS)},
}
INTERACTION = {
    "contact_force_normal": {
        "model": NORMAL_MODELS, "remove_artificial_cohesion": "bool",
        "stiff_formula": STIFF_FORMULAS, "load_stiff_formula": STIFF_FORMULAS,
        "unload_stiff_formula": ("constant", "variable"), "stiff_coeff": "positive",
        "unload_param": "positive", "damping_formula": DAMPING_FORMULAS,
        "damping_coeff": "nonnegative", "ratio": "nonnegative", "restitution_coeff": "restitution"},
    "contact_force_tangent": {
        "model": TANGENT_MODELS, "formula": TANGENT_FORMULAS, "friction_coeff": "nonnegative",
        "damping_coeff": "nonnegative", "stiff_coeff": "positive",
        "restitution_coeff": "restitution0"},
    "rolling_resistance": {"model": ROLLING_MODELS, "resistance_coeff": "nonnegative"},
    "area_correction": {"model": AREA_MODELS},
    "direct_conduction": {"model": DIRECT_MODELS},
    "indirect_conduction": {
        "model": INDIRECT_MODELS, "cell_size_method": CELL_METHODS, "update_frequency": "count",
        "alpha_radius": "positive", "cutoff_distance": "nonnegative", "core_radius": "fraction",
        "min_distance": "positive", "layer_thick": "positive", "tolerance_absolute": "positive",
        "tolerance_relative": "positive"},
}
MATERIAL_KEYS = {"name": "name", "type": ("solid", "fluid"), "density": "positive",
                 "young_modulus": "positive", "young_modulus_real": "positive",
                 "shear_modulus": "positive", "poisson_ratio": "poisson",
                 "thermal_conductivity": "nonnegative", "heat_capacity": "positive",
                 "viscosity": "positive"}
MATERIAL_KEYS.update(WALL_TARGETS)
REGION_KEYS = {"shape": SHAPES, "interval": "interval", "limit_min": "vector",
               "limit_max": "vector", "center": "vector", "radius": "positive",
               "points_x": "numbers", "points_y": "numbers"}
FUNCTION_KEYS = {"type": FUNCTION_TYPES, "value": None, "initial_value": None, "slope": None,
                 "base_value": None, "amplitude": None, "period": "positive", "shift": "number",
                 "values": "table", "file": "string", "interpolation": INTERPOLATIONS,
                 "interval": "interval"}
ANIMATION_KEYS = {"title": "string", "auto_play": "bool", "particle_ids": "bool",
                  "bounding_box": "box", "colorbar_range": "range", "result": ANIMATION_RESULTS}
GRAPH_KEYS = {"title": "string", "axis_x": GRAPH_AXES, "axis_y": GRAPH_AXES, "curve": "curves"}
CURVE_KEYS = {"name": "string", "particle_x": "count", "particle_y": "count"}


def _valid(values):
    return ", ".join(values)


def _as_list(v):
    return v if isinstance(v, list) else [v]


class _Checker:
    """Checks values against their kinds; every message names the file and the key path."""

    def __init__(self, path):
        self.path = path

    def fail(self, key, message):
        raise ProjectError("%s: key '%s': %s" % (self.path, key, message))

    def keys(self, obj, allowed, where):
        if not isinstance(obj, dict):
            self.fail(where, "expected an object {...}, got %r" % (obj,))
        for k in obj:
            if k not in allowed:
                self.fail("%s.%s" % (where, k) if where else k,
                          "unknown key; valid keys here: %s" % _valid(allowed))

    def number(self, key, v):
        if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
            self.fail(key, "expected a finite number, got %r" % (v,))
        return float(v)

    def value(self, key, v, kind):
        if isinstance(kind, tuple) and kind and kind[0] == "list":
            for x in _as_list(v):
                if x not in kind[1]:
                    self.fail(key, "%r is not valid; valid values: %s" % (x, _valid(kind[1])))
            return _as_list(v)
        if isinstance(kind, tuple):
            if v not in kind:
                self.fail(key, "%r is not valid; valid values: %s" % (v, _valid(kind)))
            return v
        if kind in ("string", "name"):
            if not isinstance(v, str) or not v:
                self.fail(key, "expected a non-empty string, got %r" % (v,))
            if kind == "name" and any(c.isspace() for c in v):
                self.fail(key, "%r: a name may not contain spaces" % v)
            return v
        if kind == "bool":
            if not isinstance(v, bool):
                self.fail(key, "expected true or false, got %r" % (v,))
            return v
        if kind in ("count", "count1"):
            if isinstance(v, bool) or not isinstance(v, int) and not (
                    isinstance(v, float) and v.is_integer()):
                self.fail(key, "expected a whole number, got %r" % (v,))
            low = 1 if kind == "count1" else 0
            if v < low:
                self.fail(key, "%r is out of range; valid range [%d, inf)" % (v, low))
            return int(v)
        if kind == "number":
            return self.number(key, v)
        if kind in ("positive", "nonnegative", "fraction", "poisson", "restitution",
                    "restitution0"):
            x = self.number(key, v)
            ranges = {"positive": (x > 0, "(0, inf)"), "nonnegative": (x >= 0, "[0, inf)"),
                      "fraction": (0 <= x <= 1, "[0, 1]"),
                      "poisson": (-1 < x < 0.5, "(-1, 0.5)"),
                      "restitution": (0 < x <= 1, "(0, 1]"),
                      "restitution0": (0 <= x <= 1, "[0, 1]")}
            ok, text = ranges[kind]
            if not ok:
                self.fail(key, "%r is out of range; valid range %s" % (v, text))
            return x
        if kind in ("vector", "box", "range", "interval", "numbers"):
            n = {"vector": 2, "box": 4, "range": 2, "interval": 2}.get(kind)
            if not isinstance(v, list) or (n is not None and len(v) != n):
                self.fail(key, "expected a list of %s numbers, got %r" % (n or "several", v))
            xs = [self.number(key, x) for x in v]
            if kind == "interval" and not xs[0] <= xs[1]:
                self.fail(key, "interval %r: the start must not be after the end" % (v,))
            if kind == "range" and not xs[0] < xs[1]:
                self.fail(key, "range %r: the minimum must be below the maximum" % (v,))
            if kind == "box" and not (xs[0] < xs[1] and xs[2] < xs[3]):
                self.fail(key, "bounding box %r must be [xmin, xmax, ymin, ymax] with min < max"
                          % (v,))
            return xs
        if kind == "ids":
            ids = _as_list(v)
            for x in ids:
                if isinstance(x, bool) or not isinstance(x, (int, float)) or \
                        not math.isfinite(x) or x != int(x) or x < 1:
                    self.fail(key, "%r is not a particle or wall id (a whole number >= 1)" % (x,))
            return [int(x) for x in ids]
        if kind == "names":
            names = _as_list(v)
            for x in names:
                if not isinstance(x, str) or not x:
                    self.fail(key, "expected model-part names, got %r" % (x,))
            return names
        raise AssertionError(kind)


# ---------------------------------------------------------------------------------------------
# The model-parts file


class ModelParts:
    """Particles, walls and named model parts of a DEMLab model-parts file."""

    def __init__(self):
        self.particles = {}  # id -> dict(kind, x, y, orientation, radius, length, line)
        self.walls = {}  # id -> dict(kind, coordinates, line)
        self.parts = {}  # name -> (particle ids, wall ids)

    @classmethod
    def read(cls, path):
        mp = cls()
        try:
            with open(path) as f:
                lines = f.read().splitlines()
        except OSError as e:
            raise ProjectError("%s: cannot read the model-parts file: %s" % (path, e.strerror))
        tokens = []  # (line number, fields)
        for k, line in enumerate(lines, 1):
            fields = line.split()
            if fields:
                tokens.append((k, fields))
        pos = 0

        def fail(k, message):
            raise ProjectError("%s:%d: %s" % (path, k, message))

        def take(where):
            nonlocal pos
            if pos >= len(tokens):
                fail(len(lines), "unexpected end of file in %s" % where)
            pos += 1
            return tokens[pos - 1]

        def numbers(k, fields, n, what):
            if len(fields) != n:
                fail(k, "%s: expected %d values, got %d: %s" % (what, n, len(fields),
                                                                " ".join(fields)))
            out = []
            for x in fields:
                try:
                    v = float(x)
                except ValueError:
                    fail(k, "%s: %r is not a number" % (what, x))
                if not math.isfinite(v):
                    fail(k, "%s: %r is not a finite number" % (what, x))
                out.append(v)
            return out

        def count(k, fields, what):
            if len(fields) != 1 or not fields[0].isdigit():
                fail(k, "%s: expected the number of entries, got %r" % (what, " ".join(fields)))
            return int(fields[0])

        def whole_id(k, v, what):
            if v != int(v) or v < 1:
                fail(k, "%s: the id %r must be a whole number >= 1" % (what, v))
            return int(v)

        blocks = ("%PARTICLES.SPHERE", "%PARTICLES.CYLINDER", "%WALLS.LINE", "%WALLS.CIRCLE",
                  "%MODELPART")
        while pos < len(tokens):
            k, fields = take("a block")
            tag = fields[0]
            if tag not in blocks:
                fail(k, "unknown block %r; valid blocks: %s" % (tag, _valid(blocks)))
            if tag == "%MODELPART":
                k2, f2 = take(tag)
                if len(f2) != 2 or f2[0] != "NAME":
                    fail(k2, "%MODELPART: expected 'NAME <name>'")
                name = f2[1]
                if name in ("PARTICLES", "WALLS"):
                    fail(k2, "%MODELPART: the names PARTICLES and WALLS are reserved")
                if name in mp.parts:
                    fail(k2, "%%MODELPART: the name %r is used twice" % name)
                pids, wids = [], []
                while pos < len(tokens) and tokens[pos][1][0] in ("PARTICLES", "WALLS"):
                    k3, f3 = take(tag)
                    if len(f3) != 2 or not f3[1].isdigit():
                        fail(k3, "%%MODELPART %s: expected '%s <count>'" % (name, f3[0]))
                    n = int(f3[1])
                    ids = []
                    while len(ids) < n:
                        k4, f4 = take("%MODELPART " + name)
                        for x in numbers(k4, f4, len(f4), "%MODELPART " + name):
                            ids.append(whole_id(k4, x, "%MODELPART " + name))
                        if len(ids) > n:
                            fail(k4, "%%MODELPART %s: more ids than the count %d" % (name, n))
                    (pids if f3[0] == "PARTICLES" else wids).extend(ids)
                mp.parts[name] = (pids, wids, k2)
                continue
            kc, fc = take(tag)
            n = count(kc, fc, tag)
            width = {"%PARTICLES.SPHERE": 5, "%PARTICLES.CYLINDER": 6, "%WALLS.LINE": 5,
                     "%WALLS.CIRCLE": 4}[tag]
            for _ in range(n):
                kl, fl = take(tag)
                if fl[0].startswith("%"):
                    fail(kl, "%s: %d entries announced, fewer given" % (tag, n))
                v = numbers(kl, fl, width, tag)
                i = whole_id(kl, v[0], tag)
                if tag.startswith("%PARTICLES"):
                    if i in mp.particles:
                        fail(kl, "%s: particle id %d is used twice (first on line %d)"
                             % (tag, i, mp.particles[i]["line"]))
                    if tag == "%PARTICLES.SPHERE":
                        x, y, th, r = v[1:]
                        length = 0.0
                    else:
                        x, y, th, length, r = v[1:]
                        if length <= 0:
                            fail(kl, "%s: the length %g of particle %d must be > 0"
                                 % (tag, length, i))
                    if r <= 0:
                        fail(kl, "%s: the radius %g of particle %d must be > 0; valid range "
                             "(0, inf)" % (tag, r, i))
                    mp.particles[i] = {"kind": tag.split(".")[1].lower(), "x": x, "y": y,
                                       "orientation": th, "radius": r, "length": length,
                                       "line": kl}
                else:
                    if i in mp.walls:
                        fail(kl, "%s: wall id %d is used twice (first on line %d)"
                             % (tag, i, mp.walls[i]["line"]))
                    if tag == "%WALLS.LINE":
                        if v[1] == v[3] and v[2] == v[4]:
                            fail(kl, "%s: wall %d has two equal end points" % (tag, i))
                    elif v[3] <= 0:
                        fail(kl, "%s: the radius %g of wall %d must be > 0" % (tag, v[3], i))
                    mp.walls[i] = {"kind": tag.split(".")[1].lower(), "coordinates": v[1:],
                                   "line": kl}
        for name, (pids, wids, k) in mp.parts.items():
            for i in pids:
                if i not in mp.particles:
                    fail(k, "%%MODELPART %s: there is no particle %d" % (name, i))
            for i in wids:
                if i not in mp.walls:
                    fail(k, "%%MODELPART %s: there is no wall %d" % (name, i))
        kinds = {p["kind"] for p in mp.particles.values()}
        if len(kinds) > 1:
            raise ProjectError("%s: spheres and cylinders in one model (DEMLab refuses their "
                               "interactions too); use one kind" % path)
        lengths = {p["length"] for p in mp.particles.values() if p["kind"] == "cylinder"}
        if len(lengths) > 1:
            raise ProjectError("%s: cylinders of different lengths (%s); grain's Disk has one "
                               "length per simulation" % (path, ", ".join(
                                   "%g" % x for x in sorted(lengths))))
        return mp


# ---------------------------------------------------------------------------------------------
# The project


class Project:
    """A checked DEMLab project: its parameters, model parts and the choices made from them."""

    def __init__(self, path, final_time=None):
        self.path = os.path.abspath(path)
        self.folder = os.path.dirname(self.path)
        self.check = _Checker(path)
        try:
            with open(path) as f:
                text = f.read()
        except OSError as e:
            raise ProjectError("%s: cannot read the project: %s" % (path, e.strerror))
        try:
            self.json = json.loads(text)
        except json.JSONDecodeError as e:
            raise ProjectError("%s:%d: not valid JSON: %s" % (path, e.lineno, e.msg))
        self.notes = []
        self._check_sections()
        self.name = self.json["ProblemData"]["name"]
        self.analysis = self.json["ProblemData"]["analysis_type"]
        self.mechanical = self.analysis != "thermal"
        self.thermal = self.analysis != "mechanical"
        mp_file = os.path.join(self.folder, self.json["ProblemData"]["model_parts_file"])
        self.mp_path = mp_file
        self.parts = ModelParts.read(mp_file)
        if not self.parts.particles:
            raise ProjectError("%s: the model has no particles" % mp_file)
        ids = sorted(self.parts.particles)
        if ids != list(range(1, len(ids) + 1)):
            have = set(ids)
            missing = [i for i in range(1, min(ids[-1], len(ids) + 10) + 1) if i not in have]
            raise ProjectError("%s: particle ids must be 1..N without gaps (DEMLab's rule); "
                               "missing: %s" % (mp_file, missing[:10]))
        self.final_time = self.json["Solver"]["final_time"]
        if final_time is not None:
            if not final_time > 0:
                raise ProjectError("--final-time %r: valid range (0, inf)" % final_time)
            self.final_time = min(final_time, self.final_time)
        self._materials()
        self._models()

    # -- sections --------------------------------------------------------------------------
    def _check_sections(self):
        c, d = self.check, self.json
        c.keys(d, SECTIONS, "")
        for section in ("ProblemData", "Solver"):
            if section not in d:
                c.fail(section, "the section is required")
        for section, spec in SECTIONS.items():
            if section not in d:
                continue
            v = d[section]
            if isinstance(spec, dict):
                c.keys(v, spec, section)
                for k, kind in spec.items():
                    if k in v:
                        if isinstance(kind, str) and kind.startswith(("initial_", "condition_",
                                                                       "fixed_")):
                            v[k] = [self._condition(section + "." + k, x, kind)
                                    for x in _as_list(v[k])]
                        else:
                            v[k] = c.value(section + "." + k, v[k], kind)
            elif spec == "region":
                d[section] = self._region(section, v)
            elif spec == "regions":
                d[section] = [self._region("%s[%d]" % (section, i), x)
                              for i, x in enumerate(_as_list(v))]
            elif spec == "materials":
                d[section] = [self._material("%s[%d]" % (section, i), x)
                              for i, x in enumerate(_as_list(v))]
            elif spec == "convection":
                out = []
                for i, x in enumerate(_as_list(v)):
                    where = "%s[%d]" % (section, i)
                    c.keys(x, dict(TARGETS, nusselt_correlation=None), where)
                    if "nusselt_correlation" not in x:
                        c.fail(where + ".nusselt_correlation", "required; valid values: %s"
                               % _valid(NUSSELT))
                    c.value(where + ".nusselt_correlation", x["nusselt_correlation"], NUSSELT)
                    out.append(self._targets(where, x, TARGETS))
                d[section] = out
            elif spec == "interaction":
                c.keys(v, INTERACTION, section)
                for k, keys in INTERACTION.items():
                    if k in v:
                        c.keys(v[k], keys, section + "." + k)
                        for kk, kind in keys.items():
                            if kk in v[k]:
                                v[k][kk] = c.value("%s.%s.%s" % (section, k, kk), v[k][kk], kind)
            elif spec == "animations":
                out = []
                for i, x in enumerate(_as_list(v)):
                    where = "%s[%d]" % (section, i)
                    c.keys(x, ANIMATION_KEYS, where)
                    for k, kind in ANIMATION_KEYS.items():
                        if k in x:
                            x[k] = c.value(where + "." + k, x[k], kind)
                    if "result" not in x:
                        c.fail(where + ".result", "required; valid values: %s"
                               % _valid(ANIMATION_RESULTS))
                    out.append(x)
                d[section] = out
            elif spec == "graphs":
                out = []
                for i, x in enumerate(_as_list(v)):
                    where = "%s[%d]" % (section, i)
                    c.keys(x, GRAPH_KEYS, where)
                    for k in ("axis_x", "axis_y"):
                        if k not in x:
                            c.fail(where + "." + k, "required; valid values: %s"
                                   % _valid(GRAPH_AXES))
                        c.value(where + "." + k, x[k], GRAPH_AXES)
                    x.setdefault("title", "Graph_%d" % (i + 1))
                    c.value(where + ".title", x["title"], "string")
                    curves = []
                    for j, cv in enumerate(_as_list(x.get("curve", []))):
                        cw = "%s.curve[%d]" % (where, j)
                        c.keys(cv, CURVE_KEYS, cw)
                        for k, kind in CURVE_KEYS.items():
                            if k in cv:
                                cv[k] = c.value(cw + "." + k, cv[k], kind)
                        for axis, key in (("axis_x", "particle_x"), ("axis_y", "particle_y")):
                            if x[axis] in PARTICLE_RESULTS and not cv.get(key):
                                c.fail(cw + "." + key, "required: %s %r is a particle's result"
                                       % (axis, x[axis]))
                        cv.setdefault("name", "curve %d" % (j + 1))
                        curves.append(cv)
                    if not curves:
                        if x["axis_x"] in PARTICLE_RESULTS or x["axis_y"] in PARTICLE_RESULTS:
                            c.fail(where + ".curve", "required: a particle's result needs a "
                                   "curve with particle_x / particle_y")
                        curves = [{"name": x["title"]}]
                    x["curve"] = curves
                    out.append(x)
                d[section] = out
        solver = d["Solver"]
        if "final_time" not in solver:
            c.fail("Solver.final_time", "required; valid range (0, inf)")
        if "time_step" not in solver and not solver.get("auto_time_step", False):
            solver["auto_time_step"] = True  # DEMLab's rule
        for k in ("name", "analysis_type", "model_parts_file"):
            if k not in d["ProblemData"]:
                c.fail("ProblemData." + k, "required")

    def _targets(self, where, x, allowed):
        out = {"particles": [], "walls": [], "model_parts": []}
        for k in allowed:
            if k in x:
                out[k] = self.check.value(where + "." + k, x[k], allowed[k])
        out["where"] = where
        return dict(x, **out)

    def _region(self, where, v):
        c = self.check
        c.keys(v, REGION_KEYS, where)
        shape = c.value(where + ".shape", v.get("shape", "rectangle"), SHAPES)
        r = {"shape": shape, "interval": [0.0, INF]}
        if "interval" in v:
            r["interval"] = c.value(where + ".interval", v["interval"], "interval")
        if shape == "rectangle":  # a missing limit is open (DEMLab's default)
            r["limit_min"], r["limit_max"] = [-INF, -INF], [INF, INF]
        need = {"rectangle": (), "circle": ("center", "radius"),
                "polygon": ("points_x", "points_y")}[shape]
        for k in ("limit_min", "limit_max") if shape == "rectangle" else ():
            if k in v:
                r[k] = c.value(where + "." + k, v[k], REGION_KEYS[k])
        for k in need:
            if k not in v:
                c.fail(where + "." + k, "required for shape %r" % shape)
            r[k] = c.value(where + "." + k, v[k], REGION_KEYS[k])
        if shape == "rectangle" and not all(a < b for a, b in zip(r["limit_min"],
                                                                   r["limit_max"])):
            c.fail(where + ".limit_max", "must be above limit_min in x and y")
        if shape == "polygon":
            xs, ys = r["points_x"], r["points_y"]
            if len(xs) != len(ys) or len(xs) < 3:
                c.fail(where + ".points_x", "points_x and points_y need the same length, >= 3")
            area = 0.5 * abs(sum(xs[i] * ys[i - 1] - xs[i - 1] * ys[i] for i in range(len(xs))))
            if not area > 0:
                c.fail(where + ".points_x", "the polygon has no area (its points are on a line)")
        return r

    def _material(self, where, v):
        c = self.check
        c.keys(v, MATERIAL_KEYS, where)
        m = {k: c.value(where + "." + k, v[k], kind) for k, kind in MATERIAL_KEYS.items()
             if k in v and k not in WALL_TARGETS}
        m.setdefault("type", "solid")
        m.setdefault("name", where)
        m["where"] = where
        m.update(self._targets(where, v, WALL_TARGETS) if m["type"] == "solid" else {})
        return m

    def _condition(self, where, x, kind):
        c = self.check
        scalar = kind.endswith(("scalar", "temperature"))
        initial = kind.startswith("initial_")
        targets = WALL_TARGETS if (kind.startswith("fixed_") or kind == "initial_temperature") \
            else TARGETS
        keys = dict(targets, value=None) if initial else dict(FUNCTION_KEYS, **targets)
        c.keys(x, keys, where)
        cond = self._targets(where, x, targets)

        def val(k):
            if k not in x:
                c.fail(where + "." + k, "required")
            if scalar:
                return [c.number(where + "." + k, x[k])]
            return c.value(where + "." + k, x[k], "vector")

        temperature = where.endswith(".temperature")

        def kelvin(key, values):
            if temperature and any(t < 0 for t in values):
                c.fail(where + "." + key, "%r: a temperature in K; valid range [0, inf)"
                       % (x[key],))
            return values

        if initial:
            cond["function"] = "constant"
            cond["params"] = kelvin("value", val("value"))
            return cond
        t = c.value(where + ".type", x.get("type", "constant"), FUNCTION_TYPES)
        n = 1 if scalar else 2
        cond["function"] = t
        cond["interval"] = c.value(where + ".interval", x["interval"], "interval") \
            if "interval" in x else [0.0, INF]
        if t == "constant":
            cond["params"] = kelvin("value", val("value"))
        elif t == "linear":
            init = val("initial_value") if "initial_value" in x else [0.0] * n
            cond["params"] = init + val("slope")
        elif t == "oscillatory":
            base, amp = val("base_value"), val("amplitude")
            if any(a < 0 for a in amp):
                c.fail(where + ".amplitude", "%r: valid range [0, inf)" % (x["amplitude"],))
            if "period" not in x:
                c.fail(where + ".period", "required; valid range (0, inf)")
            cond["params"] = base + amp + [c.value(where + ".period", x["period"], "positive"),
                                           c.number(where + ".shift", x.get("shift", 0.0))]
        else:
            interp = x.get("interpolation", "linear")
            if interp != "linear":
                c.fail(where + ".interpolation",
                       "%r is not available in grain (tables interpolate linearly); valid "
                       "values: linear" % interp)
            if "values" in x:
                rows = x["values"]
                source = where + ".values"
            elif "file" in x:
                fp = os.path.join(self.folder, c.value(where + ".file", x["file"], "string"))
                try:
                    with open(fp) as f:
                        rows = [[float(s) for s in line.split()] for line in f if line.split()]
                except (OSError, ValueError) as e:
                    c.fail(where + ".file", "cannot read the table %s: %s" % (fp, e))
                source = fp
            else:
                c.fail(where + ".values", "a table needs 'values' or 'file'")
            if not isinstance(rows, list) or len(rows) < 2:
                c.fail(source, "a table needs at least 2 rows [t, value...]")
            flat = []
            for i, row in enumerate(rows):
                if not isinstance(row, list) or len(row) != n + 1:
                    c.fail(source, "row %d: expected %d numbers [t, value...], got %r"
                           % (i + 1, n + 1, row))
                nums = [c.number(source, v) for v in row]
                if i and not nums[0] > flat[-(n + 1)]:
                    c.fail(source, "row %d: the times must increase (%g after %g)"
                           % (i + 1, nums[0], flat[-(n + 1)]))
                flat += nums
            cond["params"] = [len(rows)] + flat
        return cond

    # -- materials and models -------------------------------------------------------------
    def _resolve(self, where, x):
        """Particle and wall ids named by a condition's or material's targets."""
        pids, wids = set(x.get("particles", [])), set(x.get("walls", []))
        for i in pids:
            if i not in self.parts.particles:
                self.check.fail(where + ".particles", "there is no particle %d in %s"
                                % (i, self.mp_path))
        for i in wids:
            if i not in self.parts.walls:
                self.check.fail(where + ".walls", "there is no wall %d in %s" % (i, self.mp_path))
        for name in x.get("model_parts", []):
            if name == "PARTICLES":
                pids |= set(self.parts.particles)
            elif name == "WALLS":
                wids |= set(self.parts.walls)
            elif name in self.parts.parts:
                pids |= set(self.parts.parts[name][0])
                wids |= set(self.parts.parts[name][1])
            else:
                self.check.fail(where + ".model_parts", "there is no model part %r in %s; "
                                "valid names: %s" % (name, self.mp_path, _valid(
                                    ["PARTICLES", "WALLS"] + sorted(self.parts.parts))))
        return sorted(pids), sorted(wids)

    def _materials(self):
        mats = self.json.get("Material", [])
        solids = [m for m in mats if m["type"] == "solid"]
        fluids = [m for m in mats if m["type"] == "fluid"]
        if len(fluids) > 1:
            self.check.fail("Material", "at most one fluid material (DEMLab's rule)")
        self.fluid = fluids[0] if fluids else None
        if not solids:
            self.check.fail("Material", "no solid material")
        need = (["density", "young_modulus", "poisson_ratio"] if self.mechanical else []) + \
            (["density", "thermal_conductivity", "heat_capacity"] if self.thermal else [])
        for m in solids:
            for k in need:
                if k not in m:
                    if k == "young_modulus" and "young_modulus_real" in m:
                        m["young_modulus"] = m["young_modulus_real"]  # DEMLab's rule
                        continue
                    self.check.fail(m["where"] + "." + k, "required in a %s analysis"
                                    % self.analysis)
        self.material_of_particle, self.material_of_wall = {}, {}
        for index, m in enumerate(solids):
            pids, wids = self._resolve(m["where"], m)
            for i in pids:
                self.material_of_particle[i] = index
            for i in wids:
                self.material_of_wall[i] = index
        missing = sorted(set(self.parts.particles) - set(self.material_of_particle))
        if missing:
            self.check.fail("Material", "particles without a material: %s" % missing[:10])
        self.solids = solids

    def _models(self):
        im = self.json.get("InteractionModel", {})
        self.normal = im.get("contact_force_normal") if self.mechanical else None
        self.tangent = im.get("contact_force_tangent") if self.mechanical else None
        self.rolling = im.get("rolling_resistance") if self.mechanical else None
        self.area = im.get("area_correction")
        self.direct = im.get("direct_conduction") if self.thermal else None
        self.indirect = im.get("indirect_conduction") if self.thermal else None
        c = self.check
        for key, block in (("contact_force_normal", self.normal),
                           ("contact_force_tangent", self.tangent),
                           ("rolling_resistance", self.rolling),
                           ("area_correction", self.area),
                           ("direct_conduction", self.direct),
                           ("indirect_conduction", self.indirect)):
            if block is not None and "model" not in block:
                c.fail("InteractionModel.%s.model" % key, "required; valid values: %s"
                       % _valid(INTERACTION[key]["model"]))
        if self.mechanical and self.normal is None:
            c.fail("InteractionModel.contact_force_normal",
                   "required in a %s analysis" % self.analysis)
        if self.thermal and self.direct is None and self.indirect is None:
            c.fail("InteractionModel.direct_conduction", "a %s analysis needs direct_conduction "
                   "or indirect_conduction" % self.analysis)
        n = self.normal
        if n:
            w = "InteractionModel.contact_force_normal."
            if n["model"] == "viscoelastic_linear":
                if "stiff_coeff" not in n and "restitution_coeff" not in n and \
                        n.get("stiff_formula", "energy") != "energy":
                    c.fail(w + "restitution_coeff", "required by stiff_formula %r"
                           % n["stiff_formula"])
                if "damping_coeff" not in n and "restitution_coeff" not in n:
                    c.fail(w + "restitution_coeff", "required unless damping_coeff is given")
            elif n["model"] == "viscoelastic_nonlinear":
                f = n.get("damping_formula", "TTI")
                if f == "critical_ratio" and "ratio" not in n:
                    c.fail(w + "ratio", "required by damping_formula critical_ratio")
                if f in ("KK", "LH") and "damping_coeff" not in n:
                    c.fail(w + "damping_coeff", "required by damping_formula %s" % f)
                if f == "TTI" and "damping_coeff" in n:
                    c.fail(w + "damping_coeff", "not available with damping_formula TTI in grain "
                           "(grain's Tsuji damping takes the restitution_coeff, through the "
                           "Norouzi fit DEMLab uses, or a dimensionless alpha); give "
                           "restitution_coeff instead")
                if f == "TTI" and "restitution_coeff" not in n:
                    c.fail(w + "restitution_coeff", "required by damping_formula TTI")
                n["damping_formula"] = f  # written to the run file: the program's model
            else:
                if "restitution_coeff" not in n:
                    c.fail(w + "restitution_coeff", "required by elastoplastic_linear")
                if n.get("unload_stiff_formula") == "variable" and "unload_param" not in n:
                    c.fail(w + "unload_param", "required by unload_stiff_formula variable")
        t = self.tangent
        if t:
            w = "InteractionModel.contact_force_tangent."
            m = t["model"]
            if m in ("simple_slider", "spring_slider", "dashpot_slider", "sds_linear",
                     "sds_nonlinear") and "friction_coeff" not in t:
                c.fail(w + "friction_coeff", "required by %s" % m)
            if m in ("simple_dashpot", "dashpot_slider") and not t.get("damping_coeff", 0) > 0:
                c.fail(w + "damping_coeff", "required by %s, > 0; valid range (0, inf)" % m)
            if m == "sds_linear" and "damping_coeff" not in t and "restitution_coeff" not in t:
                c.fail(w + "damping_coeff", "sds_linear needs damping_coeff or restitution_coeff "
                       "(the tangential restitution)")
            if m == "sds_nonlinear":
                if "formula" not in t:
                    c.fail(w + "formula", "required by sds_nonlinear; valid values: %s"
                           % _valid(TANGENT_FORMULAS))
                if t["formula"] in ("LTH", "ZZY") and "damping_coeff" not in t:
                    c.fail(w + "damping_coeff", "required by formula %s" % t["formula"])
        if self.indirect and math.isfinite(self.indirect.get("alpha_radius", INF)):
            c.fail("InteractionModel.indirect_conduction.alpha_radius",
                   "%r: grain's porosity hulls are convex hulls; valid values: not given (inf)"
                   % self.indirect["alpha_radius"])
        if self.rolling and "resistance_coeff" not in self.rolling:
            c.fail("InteractionModel.rolling_resistance.resistance_coeff",
                   "required by the rolling resistance models")
        s = self.json["Solver"]
        self.scheme = s.get("integration_scheme_translation", "forward_euler")
        rot = s.get("integration_scheme_rotation", "forward_euler")
        if self.mechanical and rot != self.scheme:
            self.notes.append("the rotation scheme %s differs from the translation scheme %s: "
                              "grain integrates both with %s" % (rot, self.scheme, self.scheme))
        if s.get("eval_frequency", 1) > 1:
            self.notes.append("eval_frequency %d: grain evaluates the forces at every step"
                              % s["eval_frequency"])
        search = self.json.get("Search", {})
        if search.get("search_frequency", 1) > 1 or search.get("scheme") == "verlet_list":
            self.notes.append(
                "search %s every %d steps: grain's cell list finds every contact at the step it "
                "starts (DEMLab's periodic search finds new contacts up to %d steps late)"
                % (search.get("scheme", "simple_loop"), search.get("search_frequency", 1),
                   max(0, search.get("search_frequency", 1) - 1)))
        self.convection = self.json.get("ConvectionModel", []) if self.thermal else []
        if len({x["nusselt_correlation"] for x in self.convection}) > 1:
            c.fail("ConvectionModel", "grain has one convection model per simulation; the "
                   "project names %s" % _valid(sorted({x["nusselt_correlation"]
                                                       for x in self.convection})))
        if self.convection and self.fluid is None:
            c.fail("Material", "convection needs a fluid material (type fluid)")
        if self.convection:
            for k in ("density", "viscosity", "thermal_conductivity", "heat_capacity"):
                if k not in self.fluid:
                    c.fail(self.fluid["where"] + "." + k, "required by the convection model")
            covered = set()
            for x in self.convection:
                covered |= set(self._resolve(x["where"], x)[0])
            left = sorted(set(self.parts.particles) - covered)
            if left:
                c.fail("ConvectionModel", "grain applies one convection model to every particle; "
                       "particles without one: %s" % left[:10])

    # -- the generated program --------------------------------------------------------------
    def types(self):
        """The C++ types of the project's models: (contact, simulation options)."""
        n, t = self.normal, self.tangent
        normal = "grain::normal::LinearSpringDashpot"
        if n:
            if n["model"] == "viscoelastic_linear":
                normal = "grain::normal::LinearSpringDashpot" if "stiff_coeff" in n else \
                    "grain::normal::LinearSpringDashpotPerContact"
            elif n["model"] == "viscoelastic_nonlinear":
                damping = {"critical_ratio": "CriticalRatioDamping", "TTI": "TsujiDamping",
                           "KK": "KuwabaraKonoDamping", "LH": "LeeHerrmannDamping"}[
                               n.get("damping_formula", "TTI")]
                normal = "grain::normal::Hertz<grain::normal::%s>" % damping
            else:
                normal = "grain::normal::WaltonBraun" if "stiff_coeff" in n else \
                    "grain::normal::WaltonBraunPerContact"
        tangent = "grain::tangent::None"
        if t:
            m = t["model"]
            if m == "sds_nonlinear":
                tangent = {"DD": "DiRenzoDiMaio", "LTH": "LangstonTuzunHeyes",
                           "ZZY": "ZhengZhuYu", "TTI": "Tsuji"}[t["formula"]]
            else:
                tangent = {"simple_slider": "Slider", "simple_spring": "Spring",
                           "simple_dashpot": "Dashpot", "spring_slider": "SpringSlider",
                           "dashpot_slider": "DashpotSlider",
                           "sds_linear": "SpringDashpotSlider"}[m]
            tangent = "grain::tangent::" + tangent
        rolling = "grain::rolling::None"
        if self.rolling:
            rolling = "grain::rolling::" + {"constant": "Constant", "viscous": "Viscous"}[
                self.rolling["model"]]
        direct = {"bob": "BatchelorOBrien", "thermal_pipe": "ThermalPipe",
                  "collisional": "Collisional"}.get((self.direct or {}).get("model"))
        indirect = {"vononoi_a": "VoronoiA", "vononoi_b": "VoronoiB",
                    "surrounding_layer": "SurroundingLayer"}.get(
                        (self.indirect or {}).get("model"))
        if direct and indirect:
            conduction = "grain::conduction::Combined<grain::conduction::%s, " \
                         "grain::conduction::%s>" % (direct, indirect)
        elif direct or indirect:
            conduction = "grain::conduction::" + (direct or indirect)
        else:
            conduction = "grain::conduction::None"
        # DEMLab's contact radius is the half chord of the two undeformed circles
        # (area::Geometric); a correction replaces it in thermo-mechanical analyses
        # (a correction replaces it wherever heat is conducted; it is not used in a mechanical
        # analysis)
        area = "grain::area::Geometric" if self.thermal else "grain::area::None"
        if self.area and self.thermal:
            area = "grain::area::" + {"ZYZ": "ZhouYuZulli", "LMLB": "LuMorrisLiBenyahia",
                                      "MPMH": "MorrisPannalaMaHrenya"}[self.area["model"]]
            note = "area_correction %s: " % self.area["model"] + {
                "ZYZ": "grain scales the Hertz radius sqrt(R* delta) by (E*/E*_0)^(1/5); "
                       "DEMLab scales the half chord, about sqrt(2) larger",
                "LMLB": "grain's radius is the real Hertz radius at the elastic force, "
                        "(3 F_el R*/(4 E*_0))^(1/3) (Lu et al. 2017); DEMLab's code writes "
                        "(K_n a / K_hz,0)^(2/3), with the radius in place of the overlap",
                "MPMH": "grain's radius is (3 F R*/(4 E*_0))^(1/3), the Hertz radius at the "
                        "force (Morris et al. 2016); DEMLab's leaves out the 3/4"}[
                            self.area["model"]]
            if note not in self.notes:
                self.notes.append(note)
        args = [normal, tangent, rolling, conduction, area]
        while len(args) > 1 and args[-1].endswith("::None"):
            args.pop()
        contact = "grain::Interaction<%s>" % ",\n                                   ".join(args)
        options = ["grain::integrate::" + {"forward_euler": "ForwardEuler",
                                           "modified_euler": "SymplecticEuler",
                                           "taylor_2": "Taylor2"}[self.scheme]]
        ind = (self.indirect or {}).get("model")
        if ind in ("vononoi_a", "vononoi_b"):
            method = self.indirect.get("cell_size_method", "porosity_global")
            options.append({"porosity_global": "grain::cells::GlobalPorosity",
                            "porosity_local": "grain::cells::LocalPorosity",
                            "voronoi_diagram": "grain::cells::VoronoiDiagram"}[method])
        if self.convection:
            options.append("grain::convection::" + {
                "sphere_hanz_marshall": "RanzMarshall",
                "sphere_whitaker": "Whitaker"}[self.convection[0]["nusselt_correlation"]])
        return contact, options

    def program(self):
        contact, options = self.types()
        return (
            "// The models of a DEMLab project (written by grain-demlab): one program serves every\n"
            "// project with these models. Run: program RUNFILE OUTPUT_FOLDER\n"
            "#include <grain/demlab/driver.hpp>\n%s\n"
            "using Contact = %s;\n"
            "using Sim = grain::Simulation<grain::Disk, grain::search::CellList, Contact,\n"
            "                              %s>;\n\n"
            "int main(int argc, char** argv) { return grain::demlab::main<Sim>(argc, argv); }\n"
            % ("#include <grain/thermal/voronoi.hpp> // cells::VoronoiDiagram, "
               "qhull\n" if _QHULL_MARK in " ".join(options) else "", contact,
               ",\n                              ".join(options)))

    # -- the run file ------------------------------------------------------------------------
    def run_file(self, output_count_override=None):
        d, lines = self.json, []
        f = _fmt

        def ids(xs):
            return "%d %s" % (len(xs), " ".join(str(i) for i in xs))

        def interval(iv):
            return "%s %s" % (f(iv[0]), "inf" if math.isinf(iv[1]) else f(iv[1]))

        lines.append("grain-demlab-run 1")
        lines.append("name " + self.name)
        lines.append("analysis " + self.analysis)
        kinds = {p["kind"] for p in self.parts.particles.values()}
        if "cylinder" in kinds:
            lines.append("shape cylinder " + f(next(iter(self.parts.particles.values()))["length"]))
        else:
            lines.append("shape sphere")
        s = d["Solver"]
        lines.append("time_step " + f(0.0 if s.get("auto_time_step") else s["time_step"]))
        lines.append("final_time " + f(self.final_time))
        out = d.get("Output", {})
        lines.append("output_count %d" % (output_count_override or out.get("number_output", 100)))
        lines.append("progress " + f(out.get("progress_print", 1.0)))
        g = d.get("GlobalCondition", {})
        if self.mechanical:
            lines.append("gravity %s %s" % tuple(f(x) for x in g.get("gravity", [0.0, 0.0])))
            lines.append("damping %s %s" % (f(g.get("damping_translation", 0.0)),
                                            f(g.get("damping_rotation", 0.0))))
        if self.fluid is not None or "fluid_temperature" in g or "porosity" in g:
            fl = self.fluid or {}
            v = g.get("fluid_velocity", [0.0, 0.0])
            lines.append("fluid " + " ".join(f(x) for x in (
                fl.get("density", 0.0), fl.get("viscosity", 0.0),
                fl.get("thermal_conductivity", 0.0), fl.get("heat_capacity", 0.0), v[0], v[1],
                g.get("fluid_temperature", 0.0), g.get("porosity", -1.0))))
        for key, word in (("BoundingBox", "bbox"), ("Sink", "sink")):
            if key not in d:
                continue
            for r in _as_list(d[key]):
                head = "%s %s %s" % (word, r["shape"], interval(r["interval"]))
                if r["shape"] == "rectangle":
                    lines.append(head + " " + " ".join(f(x) for x in r["limit_min"] +
                                                       r["limit_max"]))
                elif r["shape"] == "circle":
                    lines.append(head + " " + " ".join(f(x) for x in r["center"] +
                                                       [r["radius"]]))
                else:
                    pts = [f(v) for xy in zip(r["points_x"], r["points_y"]) for v in xy]
                    lines.append(head + " %d " % len(r["points_x"]) + " ".join(pts))
        n, t, r = self.normal or {}, self.tangent or {}, self.rolling or {}
        for index, m in enumerate(self.solids):
            lines.append("material %d %s %s" % (index, m["name"].replace(" ", "_"), " ".join(
                f(m.get(k, 0.0)) for k in ("density", "young_modulus", "young_modulus_real",
                                           "shear_modulus", "poisson_ratio",
                                           "thermal_conductivity", "heat_capacity")) + " " +
                " ".join(f(x) for x in (n.get("restitution_coeff", 0.0),
                                        t.get("friction_coeff", 0.0),
                                        r.get("resistance_coeff", 0.0)))))
        for i in sorted(self.parts.particles):
            p = self.parts.particles[i]
            lines.append("particle %d %s %s %s %s %d" % (i, f(p["x"]), f(p["y"]),
                                                         f(p["orientation"]), f(p["radius"]),
                                                         self.material_of_particle[i]))
        for i in sorted(self.parts.walls):
            w = self.parts.walls[i]
            lines.append("wall %s %d %s %d" % (w["kind"], i, " ".join(f(x) for x in
                                                                      w["coordinates"]),
                                               self.material_of_wall.get(i, -1)))
        ic = d.get("InitialCondition", {})
        for key, word in (("translational_velocity", "velocity"), ("rotational_velocity", "omega"),
                          ("temperature", "temperature")):
            if key == "temperature" and not self.thermal:
                continue
            for cond in ic.get(key, []):
                pids, wids = self._resolve(cond["where"], cond)
                line = "initial %s %s P %s" % (word, " ".join(f(x) for x in cond["params"]),
                                               ids(pids))
                if word == "temperature":
                    line += " W " + ids(wids)
                lines.append(line)
        for section, kinds in (("PrescribedCondition", (("force", "force"), ("torque", "torque"),
                                                        ("heat_flux", "heat_flux"),
                                                        ("heat_rate", "heat_rate"))),
                               ("FixedCondition", (("velocity_translation", "fix_velocity"),
                                                   ("velocity_rotation", "fix_omega"),
                                                   ("temperature", "fix_temperature")))):
            for key, kind in kinds:
                thermal_kind = kind in ("heat_flux", "heat_rate", "fix_temperature")
                if thermal_kind and not self.thermal or not thermal_kind and not self.mechanical:
                    if d.get(section, {}).get(key):
                        self.notes.append("%s.%s is ignored in a %s analysis (DEMLab's rule)"
                                          % (section, key, self.analysis))
                    continue
                for cond in d.get(section, {}).get(key, []):
                    pids, wids = self._resolve(cond["where"], cond)
                    if section == "PrescribedCondition":
                        wids = []  # a model part's walls: prescribed conditions act on particles
                    lines.append("condition %s %s %s %s P %s W %s" % (
                        kind, cond["function"], interval(cond["interval"]),
                        " ".join(f(x) if not isinstance(x, int) else str(x)
                                 for x in cond["params"]), ids(pids), ids(wids)))
        for key, block in (("normal", self.normal), ("tangent", self.tangent),
                           ("rolling", self.rolling), ("area", self.area),
                           ("direct", self.direct), ("indirect", self.indirect)):
            for k, v in (block or {}).items():
                if isinstance(v, bool):
                    v = "1" if v else "0"
                elif isinstance(v, (int, float)):
                    v = f(v)
                lines.append("param %s.%s %s" % (key, k, v))
        if self.convection:
            pids = set()
            for x in self.convection:
                pids |= set(self._resolve(x["where"], x)[0])
            lines.append("param convection.model " + self.convection[0]["nusselt_correlation"])
            lines.append("param convection.particles " + ids(sorted(pids)))
        for column in self.columns():
            lines.append("record " + column)
        lines.append("vtk %d" % (1 if d.get("Animation") else 0))
        pr = d.get("Print")
        if pr and pr.get("printed_results"):  # DEMLab prints nothing without a list
            res = pr["printed_results"]
            lines.append("print %d %d %s" % (1 if pr.get("single_file") else 0, len(res),
                                             " ".join(res)))
        return "\n".join(lines) + "\n"

    def columns(self):
        """The record lines the graphs need, in order, without repeats."""
        out = []
        for gph in self.json.get("Graph", []):
            for cv in gph["curve"]:
                for axis, key in (("axis_x", "particle_x"), ("axis_y", "particle_y")):
                    q = gph[axis]
                    if q in ("time", "step"):
                        continue
                    col = "particle %s %d" % (q, cv[key]) if q in PARTICLE_RESULTS \
                        else "global " + q
                    if not self.thermal and q in ("temperature", "heat_rate",
                                                  "temperature_avg", "temperature_min",
                                                  "temperature_max", "heat_rate_total",
                                                  "conduction_direct_total",
                                                  "conduction_indirect_total"):
                        self.check.fail("Graph %r" % gph["title"], "%s: a thermal result in a "
                                        "mechanical analysis" % q)
                    if q in PARTICLE_RESULTS and cv[key] not in self.parts.particles:
                        self.check.fail("Graph %r curve %r" % (gph["title"], cv["name"]),
                                        "there is no particle %d" % cv[key])
                    if col not in out:
                        out.append(col)
        return out


_QHULL_MARK = "grain::cells::VoronoiDiagram"


def _fmt(x):
    if isinstance(x, float) and math.isinf(x):
        return "inf" if x > 0 else "-inf"
    return "%.17g" % x


# ---------------------------------------------------------------------------------------------
# Build and run


def _cache_root():
    root = os.environ.get("GRAIN_DEMLAB_CACHE")
    if root:
        return root
    base = os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache")
    return os.path.join(base, "grain-demlab")


def _compiler():
    """(command prefix, include flags, header folder) for building a generated program."""
    if _config is not None:
        cxx, includes, flags = _config.CXX, list(_config.INCLUDE_DIRS), list(_config.FLAGS)
    else:
        cxx, includes, flags = os.environ.get("CXX", "c++"), [], ["-std=c++20", "-O2",
                                                                  "-fopenmp", "-DNDEBUG"]
        here = os.path.dirname(os.path.abspath(__file__))
        includes = [os.path.join(here, "..", "..", "include"), "/usr/include/eigen3"]
    cxx = os.environ.get("GRAIN_DEMLAB_CXX", cxx)
    launcher = []
    if os.environ.get("GRAIN_DEMLAB_CCACHE", "1") != "0" and shutil.which("ccache"):
        launcher = ["ccache"]
    grain_include = next((d for d in includes if os.path.isfile(
        os.path.join(d, "grain", "grain.hpp"))), None)
    if grain_include is None:
        raise ProjectError("grain's headers were not found in %s" % ", ".join(includes))
    return launcher + [cxx], ["-I" + d for d in includes], flags, grain_include


def _headers_digest(include):
    h = hashlib.sha256()
    root = os.path.join(include, "grain")
    for folder, dirs, files in sorted(os.walk(root)):
        dirs.sort()
        for name in sorted(files):
            p = os.path.join(folder, name)
            h.update(p[len(root):].encode())
            with open(p, "rb") as fh:
                h.update(fh.read())
    return h.hexdigest()


def build(source, verbose=True):
    """The executable of a generated program: from the cache, or compiled into it."""
    command, includes, flags, grain_include = _compiler()
    key = hashlib.sha256()
    for part in [source] + command + includes + flags + [_headers_digest(grain_include)]:
        key.update(part.encode() + b"\0")
    folder = os.path.join(_cache_root(), key.hexdigest()[:20])
    exe = os.path.join(folder, "program")
    os.makedirs(folder, exist_ok=True)
    with open(os.path.join(folder, ".lock"), "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)  # one build per combination at a time
        if os.path.isfile(exe):
            return exe, True
        src = os.path.join(folder, "program.cpp")
        with open(src, "w") as f:
            f.write(source)
        cmd = command + flags + includes + [src, "-o", exe + ".tmp"]
        if _QHULL_MARK in source:
            cmd.append("-lqhull_r")  # grain::voronoi
        if verbose:
            print("grain-demlab: building the program of this model combination (once; cached "
                  "in %s)" % folder, flush=True)
        r = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        if r.returncode != 0:
            raise ProjectError("the generated program did not compile (%s):\n%s"
                               % (" ".join(cmd), r.stdout[-6000:]))
        os.replace(exe + ".tmp", exe)
    return exe, False


def _read_results(path):
    with open(path) as f:
        header = f.readline().strip().split(",")
        rows = [[float(x) for x in line.split(",")] for line in f if line.strip()]
    return {name: [row[k] for row in rows] for k, name in enumerate(header)}


def write_graphs(project, results, out):
    """DEMLab's graphs: `<title>.txt` (a curve's name, then `x y` rows, a blank line between
    curves) and `<title>.png` where matplotlib is installed."""
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        plt = None
    written = []
    for gph in project.json.get("Graph", []):
        curves = []
        for cv in gph["curve"]:
            def column(axis, key):
                q = gph[axis]
                if q in ("time", "step"):
                    return results[q]
                if q in PARTICLE_RESULTS:
                    return results["%s:%d" % (q, cv[key])]
                return results[q]
            curves.append((cv["name"], column("axis_x", "particle_x"),
                           column("axis_y", "particle_y")))
        base = os.path.join(out, gph["title"].replace("/", "_"))
        with open(base + ".txt", "w") as f:
            for k, (name, xs, ys) in enumerate(curves):
                if k:
                    f.write("\n")
                f.write(name + "\n")
                for x, y in zip(xs, ys):
                    f.write("%.10e %.10e\n" % (x, y))
        written.append(base + ".txt")
        if plt is not None:
            fig, ax = plt.subplots(figsize=(6, 4))
            for name, xs, ys in curves:
                ax.plot(xs, ys, label=name)
            ax.set_title(gph["title"])
            ax.set_xlabel(gph["axis_x"])
            ax.set_ylabel(gph["axis_y"])
            ax.grid(True, alpha=0.3)
            ax.legend()
            fig.tight_layout()
            fig.savefig(base + ".png", dpi=100)
            plt.close(fig)
            written.append(base + ".png")
    if plt is None and project.json.get("Graph"):
        print("grain-demlab: note: matplotlib is not installed (Debian python3-matplotlib): the "
              "graphs are written as text only")
    return written


# DEMLab's animation results -> (the field of grain's particle VTK files that grain-plot colours
# the disks by or None for plain disks, the vector field drawn as arrows or None); a vector
# field colours by its magnitude
ANIMATION_FIELDS = {
    "radius": ("radius", None), "mass": ("mass", None), "motion": (None, None),
    "orientation": ("orientation", None), "force_vector": ("force", "force"),
    "force_modulus": ("force", None), "force_x": ("force:x", None), "force_y": ("force:y", None),
    "torque": ("torque", None), "velocity_vector": ("velocity", "velocity"),
    "velocity_modulus": ("velocity", None), "velocity_x": ("velocity:x", None),
    "velocity_y": ("velocity:y", None), "velocity_rot": ("omega:z", None),
    "acceleration_vector": (None, "force"), "heat_rate": ("heat_rate", None),
    "temperature": ("temperature", None)}


def _plot_script():
    if _config is not None and os.path.isfile(getattr(_config, "PLOT", "")):
        return _config.PLOT
    here = os.path.dirname(os.path.abspath(__file__))
    for p in (os.path.join(here, "..", "..", "scripts", "grain_plot.py"),
              shutil.which("grain-plot") or ""):
        if os.path.isfile(p):
            return p
    return None


def write_animations(project, out):
    """Each Animation as `<title>.gif`: the disks of the VTK series coloured by the result's
    field (grain-plot animate)."""
    written = []
    script = _plot_script()
    for k, anim in enumerate(project.json.get("Animation", [])):
        result = anim["result"]
        field, arrows = ANIMATION_FIELDS.get(result, (None, None))
        if result not in ANIMATION_FIELDS:
            print("grain-demlab: note: animation result %r: grain's VTK files have no "
                  "coordinate or acceleration fields; the disks are drawn plain" % result)
        if result == "acceleration_vector":
            print("grain-demlab: note: animation result acceleration_vector: drawn as force "
                  "arrows (the acceleration's direction; grain's VTK files hold the force)")
        if field in ("temperature", "heat_rate") and not project.thermal:
            field = None
        title = anim.get("title", "Animation_%d" % (k + 1))
        gif = os.path.join(out, title.replace("/", "_") + ".gif")
        if script is None:
            print("grain-demlab: note: grain-plot was not found: no animation %s" % gif)
            continue
        cmd = [sys.executable, script, "animate", os.path.join(out, "vtk", project.name),
               "-o", gif, "--title", title]
        if field:
            cmd += ["-f", field]
        if arrows:
            cmd += ["--arrows", arrows]
        if result == "motion":
            cmd += ["--markers"]  # DEMLab's motion: disks with their orientation
        if field == "temperature":
            cmd += ["--wall-field", "temperature"]
        if anim.get("particle_ids"):
            cmd += ["--ids"]
        if "bounding_box" in anim:
            cmd += ["--window"] + ["%.17g" % v for v in anim["bounding_box"]]
        if "colorbar_range" in anim:
            cmd += ["--range"] + ["%.17g" % v for v in anim["colorbar_range"]]
        r = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        if r.returncode != 0:
            print("grain-demlab: note: the animation %s was not written: %s"
                  % (gif, r.stdout.strip()[-300:]))
            continue
        written.append(gif)
    return written


def run(path, final_time=None, output=None, check_only=False, verbose=True, animations=True):
    """Runs the project at `path`; returns (project, results, output folder)."""
    project = Project(path, final_time)
    gen = os.path.join(project.folder, "grain_demlab")
    out = output or os.path.join(project.folder, project.name + "_out")
    source = project.program()
    runfile = project.run_file()
    if check_only:
        return project, None, out
    os.makedirs(gen, exist_ok=True)
    os.makedirs(out, exist_ok=True)
    with open(os.path.join(gen, "program.cpp"), "w") as f:
        f.write(source)
    with open(os.path.join(gen, "CMakeLists.txt"), "w") as f:
        f.write(_CMAKE % (project.name, "grain::voronoi" if _QHULL_MARK in source
                          else "grain::grain"))
    run_path = os.path.join(gen, project.name + ".run")
    with open(run_path, "w") as f:
        f.write(runfile)
    for note in project.notes:
        print("grain-demlab: note: " + note)
    exe, cached = build(source, verbose)
    if verbose:
        print("grain-demlab: %s (%s); program %s%s" % (project.name, project.analysis,
                                                     os.path.join(gen, "program.cpp"),
                                                     " (cached build)" if cached else ""),
              flush=True)
    start = time.time()
    r = subprocess.run([exe, run_path, out])
    if r.returncode != 0:
        raise ProjectError("the run of %s stopped (status %d)" % (project.name, r.returncode))
    results = _read_results(os.path.join(out, "results.csv"))
    written = write_graphs(project, results, out)
    if animations:
        written += write_animations(project, out)
    if verbose:
        if written:
            print("grain-demlab: graphs and animations: %s"
                  % ", ".join(os.path.basename(w) for w in written))
        print("grain-demlab: %s: done (%.1f s); results in %s" % (project.name,
                                                                time.time() - start, out))
    return project, results, out


_CMAKE = """# Builds the program of a DEMLab project's models against an installed grain:
#   cmake -S . -B build && cmake --build build && build/program %s.run OUTPUT_FOLDER
cmake_minimum_required(VERSION 3.21)
project(grain_demlab_program LANGUAGES CXX)
find_package(grain REQUIRED)
if(NOT CMAKE_BUILD_TYPE)
  set(CMAKE_BUILD_TYPE Release)
endif()
add_executable(program program.cpp)
target_link_libraries(program PRIVATE %s)
"""


def main(argv):
    import argparse
    ap = argparse.ArgumentParser(
        prog="grain-demlab",
        description="Runs a DEMLab project (ProjectParameters.json + its model-parts file) on "
                    "grain. The generated program is kept in <project>/grain_demlab/, the "
                    "results go to <project>/<name>_out/.")
    ap.add_argument("project", help="the project's ProjectParameters.json")
    ap.add_argument("--final-time", type=float, help="stop earlier than the project's final_time")
    ap.add_argument("--output", help="the output folder (default <project>/<name>_out)")
    ap.add_argument("--no-animations", action="store_true",
                    help="skip the animations (GIF files drawn from the VTK series)")
    ap.add_argument("--check", action="store_true",
                    help="check the project and print the generated program; run nothing")
    a = ap.parse_args(argv[1:])
    try:
        project, _, _ = run(a.project, a.final_time, a.output, a.check,
                            animations=not a.no_animations)
        if a.check:
            for note in project.notes:
                print("grain-demlab: note: " + note)
            print(project.program(), end="")
            print("grain-demlab: %s: the project is valid" % a.project)
    except ProjectError as e:
        print("grain-demlab: error: %s" % e, file=sys.stderr)
        return 1
    return 0
