"""Reads the legacy VTK files of grain::bodies::body_vtk (written by write_bodies_vtk) back with
VTK's own reader and compares them with the expected.json written next to them.

Usage: read_bodies_vtk.py <directory>

For every series (ASCII and binary) and kind (bodies, springs, torsion springs, joints): the files are numbered
000000 ... N-1 with N the number of outputs and listed with their times in the .vtk.series file;
each is legacy polydata in the series' format with 'grain <kind> t = <time>' in its header (a
binary file is first walked with Python's struct); bodies and joints are points with one vertex
each (torsion springs at the centre of their body 1), springs one line each between their two points; the fields have the expected names,
component counts and types, and every value equals the system's to a relative 1e-12 (17
significant digits are written). Uses the helpers of read_vtk.py. Exits with status 1 and a
message per mismatch if anything differs.
"""

import json
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import read_vtk as rv  # noqa: E402

# kind -> (list in a frame, point or cell data, {field: (components, integral, key)})
KINDS = {
    "bodies": ("bodies", "point", {
        "body": (1, True, None), "velocity": (3, False, "velocity"),
        "omega": (3, False, "omega"), "force": (3, False, "force"),
        "torque": (3, False, "torque"), "mass": (1, False, "mass"),
        "orientation": (4, False, "orientation")}),
    "springs": ("springs", "cell", {
        "spring": (1, True, None), "force": (3, False, "force"),
        "total_force": (1, False, "total_force"), "elastic_force": (1, False, "elastic_force"),
        "friction_force": (1, False, "friction_force"), "stroke": (1, False, "stroke"),
        "length": (1, False, "length"), "state": (1, True, "state")}),
    "torsion_springs": ("torsion_springs", "point", {
        "torsion_spring": (1, True, None), "torque": (3, False, "torque"),
        "xdir": (3, False, "xdir"), "ydir": (3, False, "ydir"), "zdir": (3, False, "zdir"),
        "roll": (1, False, "roll"), "pitch": (1, False, "pitch"), "yaw": (1, False, "yaw"),
        "spring_torque": (3, False, "spring_torque"),
        "total_torque": (3, False, "total_torque")}),
    "joints": ("joints", "point", {
        "joint": (1, True, None), "reaction": (3, False, "reaction"), "gap": (1, False, "gap")}),
}


def check_file(path, kind, frame, fmt):
    rv.check_format(path, fmt)
    if fmt == "binary" and not rv.check_binary_layout(path):
        return
    poly, header = rv.read_polydata(path)
    if poly is None:
        return
    rv.check_header(path, header, kind, frame["time"])
    rv.check_points_double(path, poly)
    key, where_data, fields = KINDS[kind]
    items = frame[key]
    n = len(items)
    if kind == "springs":
        want = (0, n, 0, 0)
        points = 2 * n
    else:
        want = (n, 0, 0, 0)
        points = n
    counts = (poly.GetNumberOfVerts(), poly.GetNumberOfLines(), poly.GetNumberOfPolys(),
              poly.GetNumberOfStrips())
    if counts != want or poly.GetNumberOfPoints() != points:
        rv.fail(path, f"(vertices, lines, polygons, strips) = {counts} and "
                      f"{poly.GetNumberOfPoints()} points, expected {want} and {points}")
        return
    data = poly.GetPointData() if where_data == "point" else poly.GetCellData()
    names = {data.GetArrayName(k) for k in range(data.GetNumberOfArrays())}
    if names != set(fields):
        rv.fail(path, f"fields {sorted(names)}, expected {sorted(fields)}")
        return
    arrays = {name: rv.get_array(path, data, name, c, integral)
              for name, (c, integral, _) in fields.items()}
    if any(a is None for a in arrays.values()):
        return
    for i, e in enumerate(items):
        where = f"{path}: {kind[:-1]} {i}"
        if kind == "springs":
            ids = rv.cell_point_ids(poly, i)
            if len(ids) != 2:
                rv.fail(where, f"line points {ids}, expected two")
                continue
            rv.check_vector(where, "point 1", poly.GetPoint(ids[0]), e["p1"])
            rv.check_vector(where, "point 2", poly.GetPoint(ids[1]), e["p2"])
        elif kind == "bodies":
            rv.check_vector(where, "position", poly.GetPoint(i), e["position"])
        else:
            rv.check_vector(where, "point", poly.GetPoint(i), e["point"])
        for name, (c, integral, k) in fields.items():
            got = arrays[name].GetTuple(i)
            if k is None:
                if int(got[0]) != i:
                    rv.fail(where, f"{name} = {got[0]!r}, expected {i}")
            elif integral:
                if int(got[0]) != e[k]:
                    rv.fail(where, f"{name} = {got[0]!r}, expected {e[k]!r}")
            elif c == 3:
                rv.check_vector(where, name, got, e[k])
            elif c == 4:
                if not all(rv.close(g, x, 1.0) for g, x in zip(got, e[k])):
                    rv.fail(where, f"{name} = {list(got)}, expected {e[k]}")
            else:
                rv.check_scalar(where, name, got[0], e[k])


def main():
    if len(sys.argv) != 2:
        print("usage: read_bodies_vtk.py <directory>", file=sys.stderr)
        return 2
    directory = sys.argv[1]
    with open(os.path.join(directory, "expected.json"), encoding="utf-8") as f:
        expected = json.load(f)
    frames = expected["frames"]
    if len(frames) < 3:
        rv.fail(directory, f"only {len(frames)} outputs: the set-up does not test a series")
    wanted = set()
    checked = 0
    for sname, fmt in expected["series"].items():
        for kind in KINDS:
            wanted.add(f"{sname}_{kind}.vtk.series")
            rv.check_series_file(directory, sname, kind, frames)
            for k, frame in enumerate(frames):
                name = f"{sname}_{kind}_{k:06d}.vtk"
                wanted.add(name)
                path = os.path.join(directory, name)
                if not os.path.exists(path):
                    rv.fail(path, "missing")
                    continue
                check_file(path, kind, frame, fmt)
                checked += 1
    for name in sorted(os.listdir(directory)):
        if name not in wanted and name != "expected.json":
            rv.fail(os.path.join(directory, name), "unexpected file")
    # the set-up is not degenerate: some spring is loaded, some joint carries a load
    if not any(abs(s["total_force"]) > 0 for f in frames for s in f["springs"]):
        rv.fail(directory, "no spring carries a force: the set-up does not test the fields")
    if rv.failures:
        for message in rv.failures[:50]:
            print(f"read_bodies_vtk: MISMATCH {message}", file=sys.stderr)
        print(f"read_bodies_vtk: FAILED with {len(rv.failures)} mismatches", file=sys.stderr)
        return 1
    print(f"read_bodies_vtk: {checked} VTK files of {len(expected['series'])} series read back "
          f"and match the body system (relative tolerance {rv.RTOL})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
