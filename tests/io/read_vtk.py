"""Reads the legacy VTK files written by write_vtk back with VTK's own reader and compares them
with the expected.json written next to them.

Usage: read_vtk.py <directory>

expected.json has "runs" (the 2D mechanical disks and the 3D thermal spheres: every field of
every particle, the walls, contacts and group members at every output) and "series" (one per
io::vtk writer of a run: its format, fields, group and whether it writes contacts).

Checked for every series and kind (particles, walls, contacts):
- the files are numbered 000000 ... N-1 with N the number of outputs, and nothing else is there;
  the .vtk.series file lists them with their times;
- each file is legacy polydata that VTK reads without an error, in the series' format (the third
  line is ASCII or BINARY), with the time in its header; a binary file is first walked with
  Python's struct (block sizes, big-endian numbers, fixed-size types) before VTK reads it;
- particles: the particles of the series' group (all of them without a group), in the order the
  simulation keeps them, one vertex each, the point positions, and exactly the series' fields
  ("all" = every mechanical field, and the thermal ones in a thermal run) with the right number
  of components and types, each value equal to the simulation's;
- walls: one cell (a line in 2D, a polygon in 3D) per wall, cell fields "wall" = wall index and
  "present" (1 while the wall takes part in contacts) (and,
  for a thermal simulation, "conducts" and "temperature"), and points on the wall geometry
  (segment and triangle corners, circle polygon, plane square);
- contacts: one line per contact (with a group: per contact touching the group), from the
  centre of i (to the centre of j for a particle pair), the cell fields and their values, matched
  by (id_i, id_j, wall);
- the variants are not degenerate: the group has some but not all particles, and at some output
  its contacts are some but not all of them.
Floating-point values are written with 17 significant digits, so they must agree to a relative
tolerance of 1e-12. Exits with status 1 and a message per mismatch if anything differs.
"""

import json
import math
import os
import re
import struct
import sys

from vtkmodules.util.misc import calldata_type
from vtkmodules.vtkCommonCore import (
    VTK_CHAR, VTK_DOUBLE, VTK_ID_TYPE, VTK_INT, VTK_LONG, VTK_LONG_LONG, VTK_SHORT,
    VTK_SIGNED_CHAR, VTK_STRING, VTK_UNSIGNED_CHAR, VTK_UNSIGNED_INT, VTK_UNSIGNED_LONG,
    VTK_UNSIGNED_LONG_LONG, VTK_UNSIGNED_SHORT, vtkCommand, vtkIdList)
from vtkmodules.vtkIOLegacy import vtkPolyDataReader

RTOL = 1e-12
INTEGER_TYPES = {VTK_CHAR, VTK_SIGNED_CHAR, VTK_UNSIGNED_CHAR, VTK_SHORT, VTK_UNSIGNED_SHORT,
                 VTK_INT, VTK_UNSIGNED_INT, VTK_LONG, VTK_UNSIGNED_LONG, VTK_LONG_LONG,
                 VTK_UNSIGNED_LONG_LONG, VTK_ID_TYPE}
# particle fields: name -> (components in 2D, components in 3D, integral)
PARTICLE_FIELDS = {"id": (1, 1, True), "radius": (1, 1, False), "velocity": (3, 3, False),
                   "omega": (3, 3, False), "force": (3, 3, False), "torque": (3, 3, False),
                   "mass": (1, 1, False), "orientation": (1, 4, False),
                   "material": (1, 1, True)}
THERMAL_FIELDS = {"temperature": (1, 1, False), "heat_rate": (1, 1, False),
                  "heat_capacity": (1, 1, False)}
FILE_NAME = re.compile(r"^(?P<series>.+)_(?P<kind>particles|walls|contacts)_(?P<number>\d{6})\.vtk$")
CONTACT_FIELDS = {"wall": 1, "id_i": 1, "id_j": 1, "normal_force": 1, "normal_viscous": 1,
                  "tangential_force": 3,
                  "normal": 3, "force_local": 3, "overlap": 1, "contact_radius": 1}

failures = []


def fail(where, message):
    failures.append(f"{where}: {message}")


def close(a, b, scale=0.0):
    """a and b agree to RTOL relative to the larger of |a|, |b| and scale."""
    return abs(a - b) <= RTOL * max(abs(a), abs(b), scale)


def pad3(v):
    return list(v) + [0.0] * (3 - len(v))


def check_vector(where, name, got, expected):
    """Compares two vectors component-wise, relative to the size of the expected vector."""
    expected = pad3(expected)
    scale = max(abs(x) for x in expected)
    if len(got) != 3 or not all(close(g, e, scale) for g, e in zip(got, expected)):
        fail(where, f"{name} = {list(got)}, expected {expected}")


def check_scalar(where, name, got, expected, scale=0.0):
    if not close(got, expected, scale):
        fail(where, f"{name} = {got!r}, expected {expected!r}")


def read_polydata(path):
    """Reads a legacy VTK polydata file; returns (polydata, header) or (None, None)."""
    errors = []

    @calldata_type(VTK_STRING)
    def on_message(_obj, event, text):
        errors.append(f"{event}: {str(text).strip()}")

    reader = vtkPolyDataReader()
    reader.AddObserver(vtkCommand.ErrorEvent, on_message)
    reader.AddObserver(vtkCommand.WarningEvent, on_message)
    reader.SetFileName(path)
    if not reader.IsFilePolyData():
        fail(path, "VTK does not recognise it as legacy polydata")
        return None, None
    reader.ReadAllScalarsOn()
    reader.ReadAllVectorsOn()
    reader.ReadAllFieldsOn()
    reader.Update()
    for e in errors:
        fail(path, f"VTK reader reported {e}")
    if errors:
        return None, None
    return reader.GetOutput(), reader.GetHeader()


def check_header(path, header, kind, expected_time):
    m = re.fullmatch(rf"grain {kind} t = (\S+)", (header or "").strip())
    if not m:
        fail(path, f"header {header!r}, expected 'grain {kind} t = <time>'")
        return
    try:
        t = float(m.group(1))
    except ValueError:
        fail(path, f"header time {m.group(1)!r} is not a number")
        return
    check_scalar(path, "header time", t, expected_time)


def get_array(path, data, name, components, integral):
    a = data.GetArray(name)
    if a is None:
        fail(path, f"missing field '{name}'")
        return None
    if a.GetNumberOfComponents() != components:
        fail(path, f"field '{name}' has {a.GetNumberOfComponents()} components, expected "
                   f"{components}")
        return None
    if integral and a.GetDataType() not in INTEGER_TYPES:
        fail(path, f"field '{name}' is {a.GetDataTypeAsString()}, expected an integer type")
        return None
    if not integral and a.GetDataType() != VTK_DOUBLE:
        fail(path, f"field '{name}' is {a.GetDataTypeAsString()}, expected double")
        return None
    return a


def cell_point_ids(poly, cell):
    ids = vtkIdList()
    poly.GetCellPoints(cell, ids)
    return [ids.GetId(k) for k in range(ids.GetNumberOfIds())]


def check_points_double(path, poly):
    if poly.GetPoints() is not None and poly.GetPoints().GetDataType() != VTK_DOUBLE:
        fail(path, f"points are {poly.GetPoints().GetData().GetDataTypeAsString()}, "
                   "expected double")


def check_format(path, fmt):
    """The third line of a legacy VTK file names its format: ASCII or BINARY."""
    try:
        with open(path, "rb") as f:
            lines = [f.readline() for _ in range(3)]
    except OSError as e:
        fail(path, f"cannot read: {e}")
        return
    got = lines[2].decode("ascii", "replace").strip()
    if got != fmt.upper():
        fail(path, f"format line {got!r}, expected {fmt.upper()!r}")


BINARY_TYPES = {"double": "d", "int": "i", "vtktypeint64": "q"}  # portable sizes only


def check_binary_layout(path):
    """Walks a BINARY legacy file with Python's struct, independently of VTK: every block has the
    size its keyword line announces and ends with a newline, the numbers decode as big-endian
    (points finite and within 10 m of the origin, cell sizes and point indices consistent) and
    only types of a fixed size are used. Returns False (after reporting) if VTK should not be
    given the file: a wrong byte order can crash its reader."""
    try:
        with open(path, "rb") as f:
            data = f.read()
    except OSError as e:
        fail(path, f"cannot read: {e}")
        return False
    pos = 0

    def next_line():
        nonlocal pos
        end = data.find(b"\n", pos)
        if end < 0:
            raise ValueError(f"no end of line after byte {pos}")
        line = data[pos:end].decode("ascii")
        pos = end + 1
        return line

    def block(code, count):
        nonlocal pos
        size = struct.calcsize(">" + code) * count
        if data[pos + size:pos + size + 1] != b"\n":
            raise ValueError(f"block of {count} '{code}' at byte {pos} does not end with a newline")
        values = struct.unpack_from(f">{count}{code}", data, pos)
        pos += size + 1
        return values

    try:
        head = [next_line() for _ in range(4)]
        if head[2] != "BINARY" or head[3] != "DATASET POLYDATA":
            raise ValueError(f"header {head[2:]!r}")
        points = 0
        tuples = 0
        while pos < len(data):
            words = next_line().split()
            if not words:
                continue
            key = words[0]
            if key == "POINTS":
                points = int(words[1])
                if words[2] != "double":
                    raise ValueError(f"points of type {words[2]}")
                xyz = block("d", 3 * points)
                if not all(math.isfinite(x) and abs(x) < 10.0 for x in xyz):
                    raise ValueError("points do not decode as big-endian doubles near the origin")
            elif key in ("VERTICES", "LINES", "POLYGONS"):
                cells, size = int(words[1]), int(words[2])
                ints = block("i", size)
                k = 0
                for _ in range(cells):
                    n = ints[k] if k < size else -1
                    if n < 1 or k + 1 + n > size or \
                            not all(0 <= i < points for i in ints[k + 1:k + 1 + n]):
                        raise ValueError(f"{key}: cell at integer {k} does not decode as a "
                                         "big-endian size and point indices")
                    k += 1 + n
                if k != size:
                    raise ValueError(f"{key}: {k} integers used, {size} announced")
            elif key in ("POINT_DATA", "CELL_DATA"):
                tuples = int(words[1])
            elif key == "SCALARS":
                code = BINARY_TYPES.get(words[2])
                if code is None:
                    raise ValueError(f"SCALARS {words[1]} of type {words[2]}, expected one of "
                                     f"{sorted(BINARY_TYPES)}")
                if next_line() != "LOOKUP_TABLE default":
                    raise ValueError(f"SCALARS {words[1]} without 'LOOKUP_TABLE default'")
                values = block(code, tuples * int(words[3]))
                if code == "d" and not all(math.isfinite(x) for x in values):
                    raise ValueError(f"SCALARS {words[1]}: values not finite")
            elif key == "VECTORS":
                if words[2] != "double":
                    raise ValueError(f"VECTORS {words[1]} of type {words[2]}")
                if not all(math.isfinite(x) for x in block("d", 3 * tuples)):
                    raise ValueError(f"VECTORS {words[1]}: values not finite")
            else:
                raise ValueError(f"unexpected keyword line {' '.join(words)!r}")
    except (ValueError, UnicodeDecodeError, struct.error) as e:
        fail(path, f"binary layout: {e}")
        return False
    return True


def series_fields(series, run):
    """The particle fields a series must have: name -> (components, integral)."""
    table = dict(PARTICLE_FIELDS, **(THERMAL_FIELDS if run["thermal"] else {}))
    names = list(table) if "all" in series["fields"] else series["fields"]
    three = run["dimension"] == 3
    return {name: (table[name][1 if three else 0], table[name][2]) for name in names}


def check_particle_field(where, name, got, expected):
    if name in ("id", "material"):
        if int(got[0]) != expected:
            fail(where, f"{name} = {got[0]!r}, expected {expected!r}")
    elif name in ("velocity", "omega", "force", "torque"):
        check_vector(where, name, got, expected)
    elif isinstance(expected, list):  # the 3D orientation quaternion (w, x, y, z)
        if len(got) != len(expected) or not all(close(g, e, 1.0) for g, e in zip(got, expected)):
            fail(where, f"{name} = {list(got)}, expected {expected}")
    else:
        check_scalar(where, name, got[0], expected)


def check_particles(path, frame, series, run):
    """The particles of the series' group (all without one), in the simulation's order."""
    poly, header = read_polydata(path)
    if poly is None:
        return
    check_header(path, header, "particles", frame["time"])
    check_points_double(path, poly)
    by_id = {p["id"]: p for p in frame["particles"]}
    if len(by_id) != run["particle_count"]:
        fail(path, f"expected.json lists {len(by_id)} distinct ids, expected "
                   f"{run['particle_count']}")
    group = series["group"]
    expected = [by_id[i] for i in frame["groups"][group]] if group else frame["particles"]
    count = len(expected)
    n = poly.GetNumberOfPoints()
    if n != count:
        fail(path, f"{n} points, expected {count} particles")
        return
    counts = (poly.GetNumberOfVerts(), poly.GetNumberOfLines(), poly.GetNumberOfPolys(),
              poly.GetNumberOfStrips())
    if counts != (count, 0, 0, 0):
        fail(path, f"(vertices, lines, polygons, strips) = {counts}, expected ({count}, 0, 0, 0)")
    else:
        used = sorted(k for c in range(poly.GetNumberOfCells()) for k in cell_point_ids(poly, c))
        if used != list(range(count)):
            fail(path, f"vertex cells use points {used}, expected each of 0..{count - 1} once")
    pd = poly.GetPointData()
    names = {pd.GetArrayName(k) for k in range(pd.GetNumberOfArrays())}
    fields = series_fields(series, run)
    if names != set(fields):
        fail(path, f"point fields {sorted(names)}, expected {sorted(fields)}")
    arrays = {name: get_array(path, pd, name, c, integral)
              for name, (c, integral) in fields.items()}
    if any(a is None for a in arrays.values()):
        return
    for name, a in arrays.items():
        if a.GetNumberOfTuples() != count:
            fail(path, f"field '{name}' has {a.GetNumberOfTuples()} values, expected {count}")
            return
    for i, e in enumerate(expected):
        where = f"{path}: point {i} (particle id {e['id']})"
        check_vector(where, "position", poly.GetPoint(i), e["position"])
        for name, a in arrays.items():
            check_particle_field(where, name, a.GetTuple(i), e[name])


def check_wall_cell(where, pts, ids, wall, circle_segments, plane_size):
    kind = wall["type"]
    if kind in ("segment", "triangle"):
        corners = ["a", "b"] if kind == "segment" else ["a", "b", "c"]
        if len(ids) != len(corners):
            fail(where, f"{kind} cell has {len(ids)} points, expected {len(corners)}")
            return
        for k, corner in zip(ids, corners):
            check_vector(where, f"corner {corner}", pts(k), wall[corner])
    elif kind == "circle":
        if len(ids) != circle_segments + 1 or ids[0] != ids[-1] or \
                len(set(ids[:-1])) != circle_segments:
            fail(where, f"circle cell has point ids {ids}, expected a closed polyline of "
                        f"{circle_segments} distinct points")
            return
        cx, cy = wall["center"]
        r = wall["radius"]
        for k, pid in enumerate(ids[:-1]):
            a = 2.0 * math.pi * k / circle_segments
            check_vector(where, f"circle point {k}", pts(pid),
                         [cx + r * math.cos(a), cy + r * math.sin(a)])
    elif kind == "plane":
        if len(ids) != 4 or len(set(ids)) != 4:
            fail(where, f"plane cell has point ids {ids}, expected 4 distinct corners")
            return
        p0 = wall["point"]
        normal = wall["normal"]
        corners = [pts(k) for k in ids]
        scale = max(plane_size, *(abs(x) for x in p0))
        centroid = [sum(c[d] for c in corners) / 4.0 for d in range(3)]
        for d in range(3):
            check_scalar(where, f"plane square centre[{d}]", centroid[d], p0[d], scale)
        for k, c in enumerate(corners):
            height = sum((c[d] - p0[d]) * normal[d] for d in range(3))
            check_scalar(where, f"distance of plane corner {k} from the plane", height, 0.0,
                         scale)
            nxt = corners[(k + 1) % 4]
            check_scalar(where, f"plane square side {k}", math.dist(c, nxt), plane_size, scale)
        for k in range(2):
            check_scalar(where, f"plane square diagonal {k}", math.dist(corners[k], corners[k + 2]),
                         math.sqrt(2.0) * plane_size, scale)
    else:
        fail(where, f"expected.json has an unknown wall type {kind!r}")


def points_of(wall, circle_segments):
    return {"segment": 2, "circle": circle_segments, "plane": 4, "triangle": 3}[wall["type"]]


def check_walls(path, frame, run, circle_segments, plane_size):
    poly, header = read_polydata(path)
    if poly is None:
        return
    check_header(path, header, "walls", frame["time"])
    check_points_double(path, poly)
    walls = frame["walls"]
    if len(walls) != run["wall_count"]:
        fail(path, f"expected.json lists {len(walls)} walls, expected {run['wall_count']}")
        return
    cells = run["wall_cells"]
    counts = (poly.GetNumberOfVerts(), poly.GetNumberOfLines(), poly.GetNumberOfPolys(),
              poly.GetNumberOfStrips())
    want = (0, cells, 0, 0) if run["dimension"] == 2 else (0, 0, cells, 0)
    if counts != want:
        fail(path, f"(vertices, lines, polygons, strips) = {counts}, expected {want}")
        return
    n_points = sum(points_of(w, circle_segments) for w in walls)
    if poly.GetNumberOfPoints() != n_points:
        fail(path, f"{poly.GetNumberOfPoints()} points, expected {n_points}")
    cd = poly.GetCellData()
    names = {cd.GetArrayName(k) for k in range(cd.GetNumberOfArrays())}
    thermal = "temperature" in walls[0]
    want_names = {"wall", "present", "conducts", "temperature"} if thermal else {"wall", "present"}
    if names != want_names:
        fail(path, f"cell fields {sorted(names)}, expected {sorted(want_names)}")
    present = get_array(path, cd, "present", 1, True)
    if present is not None:
        for c in range(min(cells, len(walls))):
            if int(present.GetTuple1(c)) != walls[c]["present"]:
                fail(f"{path}: wall {c}", f"present = {int(present.GetTuple1(c))}, "
                                          f"expected {walls[c]['present']}")
    if thermal:
        conducts = get_array(path, cd, "conducts", 1, True)
        temperature = get_array(path, cd, "temperature", 1, False)
        if conducts is not None and temperature is not None:
            for c in range(min(cells, len(walls))):
                where = f"{path}: wall {c}"
                if int(conducts.GetTuple1(c)) != walls[c]["conducts"]:
                    fail(where, f"conducts = {int(conducts.GetTuple1(c))}, "
                                f"expected {walls[c]['conducts']}")
                check_scalar(where, "temperature", temperature.GetTuple1(c),
                             walls[c]["temperature"])
    owner = get_array(path, cd, "wall", 1, True)
    if owner is None:
        return
    if owner.GetNumberOfTuples() != cells:
        fail(path, f"field 'wall' has {owner.GetNumberOfTuples()} values, expected {cells}")
        return
    for c in range(cells):
        w = int(owner.GetTuple1(c))
        if w != c:
            fail(path, f"cell {c} has wall = {w}, expected {c}")
            continue
        check_wall_cell(f"{path}: wall {w} ({walls[w]['type']})", poly.GetPoint,
                        cell_point_ids(poly, c), walls[w], circle_segments, plane_size)


def group_contacts(frame, group):
    """The contacts of a frame that touch the group (all of them without a group)."""
    if not group:
        return frame["contacts"]
    ids = set(frame["groups"][group])
    return [c for c in frame["contacts"]
            if c["id_i"] in ids or (c["wall"] < 0 and c["id_j"] in ids)]


def check_contacts(path, frame, contacts, count, thermal):
    poly, header = read_polydata(path)
    if poly is None:
        return
    check_header(path, header, "contacts", frame["time"])
    check_points_double(path, poly)
    expected = {(c["id_i"], c["id_j"], c["wall"]): c for c in contacts}
    walls = sum(1 for c in contacts if c["wall"] >= 0)
    if poly.GetNumberOfPoints() != count + walls:
        fail(path, f"{poly.GetNumberOfPoints()} points, expected {count} centres + {walls} "
                   "wall contact points")
    if poly.GetNumberOfLines() != len(expected) or poly.GetNumberOfCells() != len(expected):
        fail(path, f"{poly.GetNumberOfLines()} lines, expected {len(expected)} contacts")
        return
    if not expected:
        return
    cd = poly.GetCellData()
    names = {cd.GetArrayName(k) for k in range(cd.GetNumberOfArrays())}
    fields = dict(CONTACT_FIELDS, **({"heat_rate": 1} if thermal else {}))
    if names != set(fields):
        fail(path, f"cell fields {sorted(names)}, expected {sorted(fields)}")
        return
    arrays = {name: get_array(path, cd, name, c, name in ("wall", "id_i", "id_j"))
              for name, c in fields.items()}
    if any(a is None for a in arrays.values()):
        return
    positions = {p["id"]: p["position"] for p in frame["particles"]}
    seen = set()
    for c in range(len(expected)):
        key = (int(arrays["id_i"].GetTuple1(c)), int(arrays["id_j"].GetTuple1(c)),
               int(arrays["wall"].GetTuple1(c)))
        if key not in expected or key in seen:
            fail(path, f"contact {key} unexpected or repeated")
            continue
        seen.add(key)
        e = expected[key]
        where = f"{path}: contact {key}"
        for name in ("normal_force", "normal_viscous", "overlap", "contact_radius") + (
                ("heat_rate",) if thermal else ()):
            check_scalar(where, name, arrays[name].GetTuple1(c), e[name])
        check_vector(where, "tangential_force", arrays["tangential_force"].GetTuple3(c),
                     e["tangential_force"])
        check_vector(where, "normal", arrays["normal"].GetTuple3(c), e["normal"])
        # the force in the contact frame: its normal component is minus the repulsion, its
        # tangential components have the friction force's length (the frame is orthonormal)
        n, t, local = e["normal"], e["tangential_force"], arrays["force_local"].GetTuple3(c)
        scale = max(abs(e["normal_force"]), math.sqrt(sum(x * x for x in t)))
        check_scalar(where, "force_local[0]", local[0], -e["normal_force"], scale)
        check_scalar(where, "|force_local[1:]|", math.hypot(local[1], local[2]),
                     math.sqrt(sum(x * x for x in t)), scale)
        ids = cell_point_ids(poly, c)
        if len(ids) != 2 or ids[1] == ids[0]:
            fail(where, f"line points {ids}, expected two distinct points")
            continue
        check_vector(where, "line start", poly.GetPoint(ids[0]), positions[key[0]])
        if key[2] < 0:
            check_vector(where, "line end", poly.GetPoint(ids[1]), positions[key[1]])


def check_series_file(directory, sname, kind, frames):
    path = os.path.join(directory, f"{sname}_{kind}.vtk.series")
    try:
        with open(path, encoding="utf-8") as f:
            series = json.load(f)
    except (OSError, ValueError) as e:
        fail(path, f"cannot read the series file: {e}")
        return
    files = series.get("files", [])
    want = [(f"{sname}_{kind}_{k:06d}.vtk", fr["time"]) for k, fr in enumerate(frames)]
    got = [(f.get("name"), f.get("time")) for f in files]
    if series.get("file-series-version") != "1.0" or len(got) != len(want) or any(
            g[0] != w[0] or not close(g[1], w[1]) for g, w in zip(got, want)):
        fail(path, f"files {got}, expected {want}")


def check_variants(sname, series, run):
    """The group of a series is a proper, non-empty subset at every output (or, for the group
    "nobody", empty), and at some output its contacts are some but not all of them."""
    group = series["group"]
    if not group:
        return
    sizes = {len(f["groups"][group]) for f in run["frames"]}
    if group == "nobody":
        if sizes != {0}:
            fail(sname, f"group {group!r} has {sorted(sizes)} particles, expected none")
        return
    if not all(0 < k < run["particle_count"] for k in sizes):
        fail(sname, f"group {group!r} has {sorted(sizes)} particles, expected some but not all")
    if series["contacts"] and not any(
            0 < len(group_contacts(f, group)) < len(f["contacts"]) for f in run["frames"]):
        fail(sname, f"the contacts of group {group!r} are none or all of them at every output: "
                    "the set-up does not test the restriction")


def main():
    if len(sys.argv) != 2:
        print("usage: read_vtk.py <directory>", file=sys.stderr)
        return 2
    directory = sys.argv[1]
    with open(os.path.join(directory, "expected.json"), encoding="utf-8") as f:
        expected = json.load(f)
    circle_segments = expected["circle_segments"]
    plane_size = expected["plane_size"]
    all_series = expected["series"]
    runs = expected["runs"]

    found = {}
    series_files = set()
    for name in sorted(os.listdir(directory)):
        if name.endswith(".vtk.series"):
            series_files.add(name)
            continue
        if not name.endswith(".vtk"):
            continue
        m = FILE_NAME.match(name)
        if not m or m.group("series") not in all_series:
            fail(os.path.join(directory, name), "unexpected file")
            continue
        found.setdefault((m.group("series"), m.group("kind")), []).append(int(m.group("number")))

    checked = 0
    wanted_series_files = set()
    for sname, series in all_series.items():
        run = runs[series["run"]]
        frames = run["frames"]
        if len(frames) != run["files"]:
            fail(sname, f"expected.json has {len(frames)} frames, expected {run['files']}")
            continue
        if frames[-1]["time"] != run["final_time"]:
            fail(sname, f"last output at t = {frames[-1]['time']!r}, expected the end of the run, "
                        f"t = {run['final_time']!r}")
        check_variants(sname, series, run)
        kinds = ("particles",) + (("walls",) if run["wall_count"] else ()) + \
            (("contacts",) if series["contacts"] else ())
        for kind in ("particles", "walls", "contacts"):
            if kind not in kinds and found.get((sname, kind)):
                fail(f"{directory}/{sname}_{kind}_*.vtk", "unexpected files")
        for kind in kinds:
            wanted_series_files.add(f"{sname}_{kind}.vtk.series")
            check_series_file(directory, sname, kind, frames)
            numbers = sorted(found.get((sname, kind), []))
            if numbers != list(range(run["files"])):
                fail(f"{directory}/{sname}_{kind}_*.vtk",
                     f"file numbers {numbers}, expected 0..{run['files'] - 1}")
                continue
            for k, frame in enumerate(frames):
                path = os.path.join(directory, f"{sname}_{kind}_{k:06d}.vtk")
                check_format(path, series["format"])
                checked += 1
                if series["format"] == "binary" and not check_binary_layout(path):
                    continue
                if kind == "particles":
                    check_particles(path, frame, series, run)
                elif kind == "contacts":
                    check_contacts(path, frame, group_contacts(frame, series["group"]),
                                   run["particle_count"], run["thermal"])
                else:
                    check_walls(path, frame, run, circle_segments, plane_size)
    for name in sorted(series_files - wanted_series_files):
        fail(os.path.join(directory, name), "unexpected file")

    if failures:
        limit = 50
        for message in failures[:limit]:
            print(f"read_vtk: MISMATCH {message}", file=sys.stderr)
        if len(failures) > limit:
            print(f"read_vtk: ... and {len(failures) - limit} more", file=sys.stderr)
        print(f"read_vtk: FAILED with {len(failures)} mismatches", file=sys.stderr)
        return 1
    formats = sorted({s["format"] for s in all_series.values()})
    print(f"read_vtk: {checked} VTK files of {len(all_series)} series ({', '.join(formats)}) "
          f"from {len(runs)} runs read back and match the simulation (relative tolerance {RTOL})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
