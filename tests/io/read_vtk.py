"""Reads the legacy VTK files written by write_vtk back with VTK's own reader and compares them
with the expected.json written next to them.

Usage: read_vtk.py <directory>

Checked for every series (disks, spheres) and kind (particles, walls):
- the files are numbered 000000 ... N-1 with N the number of outputs, and nothing else is there;
- each file is legacy polydata that VTK reads without an error, with the time in its header;
- particles: one vertex per point, the point fields id, radius, velocity, omega and force with
  the right number of components and types, and the values of every file (the last one is the
  state at the end of the run) equal to those of the simulation, matched by id;
  (and, for a thermal simulation, temperature and heat_rate);
- walls: one cell (a line in 2D, a polygon in 3D) per wall, cell field "wall" = wall index (and,
  for a thermal simulation, "conducts" and "temperature"), and points on the wall geometry
  (segment and triangle corners, circle polygon, plane square).
Floating-point values are written with 17 significant digits, so they must agree to a relative
tolerance of 1e-12. Exits with status 1 and a message per mismatch if anything differs.
"""

import json
import math
import os
import re
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
PARTICLE_FIELDS = {"id": 1, "radius": 1, "velocity": 3, "omega": 3, "force": 3}
THERMAL_FIELDS = {"temperature": 1, "heat_rate": 1}
FILE_NAME = re.compile(r"^(?P<series>.+)_(?P<kind>particles|walls|contacts)_(?P<number>\d{6})\.vtk$")
CONTACT_FIELDS = {"wall": 1, "id_i": 1, "id_j": 1, "normal_force": 1, "tangential_force": 3,
                  "overlap": 1, "contact_radius": 1}

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


def check_particles(path, frame, count):
    poly, header = read_polydata(path)
    if poly is None:
        return
    check_header(path, header, "particles", frame["time"])
    check_points_double(path, poly)
    expected = {p["id"]: p for p in frame["particles"]}
    if len(expected) != count:
        fail(path, f"expected.json lists {len(expected)} distinct ids, expected {count}")
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
    thermal = "temperature" in frame["particles"][0]
    fields = dict(PARTICLE_FIELDS, **(THERMAL_FIELDS if thermal else {}))
    if names != set(fields):
        fail(path, f"point fields {sorted(names)}, expected {sorted(fields)}")
    arrays = {name: get_array(path, pd, name, c, name == "id")
              for name, c in fields.items()}
    if any(a is None for a in arrays.values()):
        return
    for name, a in arrays.items():
        if a.GetNumberOfTuples() != count:
            fail(path, f"field '{name}' has {a.GetNumberOfTuples()} values, expected {count}")
            return
    ids = [int(arrays["id"].GetTuple1(i)) for i in range(count)]
    if sorted(ids) != sorted(expected):
        fail(path, f"ids {sorted(ids)}, expected {sorted(expected)}")
        return
    for i, pid in enumerate(ids):
        e = expected[pid]
        where = f"{path}: particle id {pid}"
        check_vector(where, "position", poly.GetPoint(i), e["position"])
        check_scalar(where, "radius", arrays["radius"].GetTuple1(i), e["radius"])
        for name in ("velocity", "omega", "force"):
            check_vector(where, name, arrays[name].GetTuple3(i), e[name])
        if thermal:
            for name in THERMAL_FIELDS:
                check_scalar(where, name, arrays[name].GetTuple1(i), e[name])


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


def check_walls(path, frame, series, circle_segments, plane_size):
    poly, header = read_polydata(path)
    if poly is None:
        return
    check_header(path, header, "walls", frame["time"])
    check_points_double(path, poly)
    walls = frame["walls"]
    if len(walls) != series["wall_count"]:
        fail(path, f"expected.json lists {len(walls)} walls, expected {series['wall_count']}")
        return
    cells = series["wall_cells"]
    counts = (poly.GetNumberOfVerts(), poly.GetNumberOfLines(), poly.GetNumberOfPolys(),
              poly.GetNumberOfStrips())
    want = (0, cells, 0, 0) if series["dimension"] == 2 else (0, 0, cells, 0)
    if counts != want:
        fail(path, f"(vertices, lines, polygons, strips) = {counts}, expected {want}")
        return
    n_points = sum(points_of(w, circle_segments) for w in walls)
    if poly.GetNumberOfPoints() != n_points:
        fail(path, f"{poly.GetNumberOfPoints()} points, expected {n_points}")
    cd = poly.GetCellData()
    names = {cd.GetArrayName(k) for k in range(cd.GetNumberOfArrays())}
    thermal = "temperature" in walls[0]
    want_names = {"wall", "conducts", "temperature"} if thermal else {"wall"}
    if names != want_names:
        fail(path, f"cell fields {sorted(names)}, expected {sorted(want_names)}")
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


def check_contacts(path, frame, count, thermal):
    poly, header = read_polydata(path)
    if poly is None:
        return
    check_header(path, header, "contacts", frame["time"])
    expected = {(c["id_i"], c["id_j"], c["wall"]): c for c in frame["contacts"]}
    walls = sum(1 for c in frame["contacts"] if c["wall"] >= 0)
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
        for name in ("normal_force", "overlap", "contact_radius") + (("heat_rate",) if thermal else ()):
            check_scalar(where, name, arrays[name].GetTuple1(c), e[name])
        check_vector(where, "tangential_force", arrays["tangential_force"].GetTuple3(c),
                     e["tangential_force"])
        ids = cell_point_ids(poly, c)
        if len(ids) != 2 or ids[1] == ids[0]:
            fail(where, f"line points {ids}, expected two distinct points")


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

    found = {}
    for name in sorted(os.listdir(directory)):
        if name.endswith(".vtk.series"):
            if not any(name.startswith(s + "_") for s in all_series):
                fail(os.path.join(directory, name), "unexpected file")
            continue
        if not name.endswith(".vtk"):
            continue
        m = FILE_NAME.match(name)
        if not m or m.group("series") not in all_series:
            fail(os.path.join(directory, name), "unexpected file")
            continue
        found.setdefault((m.group("series"), m.group("kind")), []).append(int(m.group("number")))

    checked = 0
    for sname, series in all_series.items():
        frames = series["frames"]
        if len(frames) != series["files"]:
            fail(sname, f"expected.json has {len(frames)} frames, expected {series['files']}")
            continue
        if frames[-1]["time"] != series["final_time"]:
            fail(sname, f"last output at t = {frames[-1]['time']!r}, expected the end of the run, "
                        f"t = {series['final_time']!r}")
        kinds = ("particles", "walls") + (("contacts",) if "contacts" in frames[0] else ())
        for kind in kinds:
            check_series_file(directory, sname, kind, frames)
            numbers = sorted(found.get((sname, kind), []))
            if numbers != list(range(series["files"])):
                fail(f"{directory}/{sname}_{kind}_*.vtk",
                     f"file numbers {numbers}, expected 0..{series['files'] - 1}")
                continue
            for k, frame in enumerate(frames):
                path = os.path.join(directory, f"{sname}_{kind}_{k:06d}.vtk")
                if kind == "particles":
                    check_particles(path, frame, series["particle_count"])
                elif kind == "contacts":
                    thermal = "temperature" in frame["particles"][0]
                    check_contacts(path, frame, series["particle_count"], thermal)
                else:
                    check_walls(path, frame, series, circle_segments, plane_size)
                checked += 1

    if failures:
        limit = 50
        for message in failures[:limit]:
            print(f"read_vtk: MISMATCH {message}", file=sys.stderr)
        if len(failures) > limit:
            print(f"read_vtk: ... and {len(failures) - limit} more", file=sys.stderr)
        print(f"read_vtk: FAILED with {len(failures)} mismatches", file=sys.stderr)
        return 1
    print(f"read_vtk: {checked} VTK files of {len(all_series)} series read back and match "
          f"the simulation (relative tolerance {RTOL})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
