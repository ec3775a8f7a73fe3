"""Reads the legacy VTK files of grain::bodies::body_vtk (written by write_bodies_vtk) back with
VTK's own reader and compares them with the expected.json written next to them.

Usage: read_bodies_vtk.py <directory>

For every series (ASCII and binary) and kind (bodies, meshes, springs, torsion springs, joints): the files are numbered
000000 ... N-1 with N the number of outputs and listed with their times in the .vtk.series file;
each is legacy polydata in the series' format with 'grain <kind> t = <time>' in its header (a
binary file is first walked with Python's struct); bodies and joints are points with one vertex
each (torsion springs at the midpoint of their bodies' centres), springs one line each between their two points; the fields have the expected names,
component counts and types, and every value equals the system's to a relative 1e-12 (17
significant digits are written). The meshes file holds the boundary faces of the mesh body as
polygons: 10 quadrilaterals, each on four of the mesh's nodes at their world positions (1e-12),
turning counter-clockwise about the outward normal, with cell data `body`, `color` (the listed
faces' colours, the global colour elsewhere) and `velocity` (v + omega x (centroid - c)). Uses
the helpers of read_vtk.py. Exits with status 1 and a
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
        "orientation": (4, False, "orientation"), "radius": (1, False, "radius"),
        "displacement": (3, False, "displacement")}),
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


MESH_FIELDS = {"body": (1, True), "color": (1, True), "velocity": (3, False)}


def check_meshes(path, frame, fmt, expected):
    rv.check_format(path, fmt)
    if fmt == "binary" and not rv.check_binary_layout(path):
        return
    poly, header = rv.read_polydata(path)
    if poly is None:
        return
    rv.check_header(path, header, "meshes", frame["time"])
    rv.check_points_double(path, poly)
    (mesh,) = frame["meshes"]
    faces = expected["mesh_faces"]
    counts = (poly.GetNumberOfVerts(), poly.GetNumberOfLines(), poly.GetNumberOfPolys(),
              poly.GetNumberOfStrips())
    if counts != (0, 0, faces, 0):
        rv.fail(path, f"(vertices, lines, polygons, strips) = {counts}, expected (0, 0, {faces}, 0)")
        return
    data = poly.GetCellData()
    names = {data.GetArrayName(k) for k in range(data.GetNumberOfArrays())}
    if names != set(MESH_FIELDS):
        rv.fail(path, f"fields {sorted(names)}, expected {sorted(MESH_FIELDS)}")
        return
    arrays = {name: rv.get_array(path, data, name, c, integral)
              for name, (c, integral) in MESH_FIELDS.items()}
    if any(a is None for a in arrays.values()):
        return
    nodes = mesh["nodes"]
    scale = max(abs(x) for n in nodes for x in n)
    listed = {frozenset(f): c for f, c in expected["listed_faces"]}
    colours = {}
    seen = set()
    c = mesh["position"]
    v, w = mesh["velocity"], mesh["omega"]
    for cell in range(faces):
        where = f"{path}: face {cell}"
        ids = rv.cell_point_ids(poly, cell)
        pts = [poly.GetPoint(k) for k in ids]
        # every point is the world position of a mesh node (relative 1e-12)
        face = []
        for p in pts:
            match = [n for n, x in enumerate(nodes)
                     if all(abs(a - b) <= rv.RTOL * scale for a, b in zip(p, x))]
            if len(match) != 1:
                rv.fail(where, f"point {p} is not the world position of one mesh node")
                break
            face.append(match[0])
        else:
            key = frozenset(face)
            if len(face) != 4 or len(key) != 4 or key in seen:
                rv.fail(where, f"nodes {face}: expected four different nodes of a new face")
            seen.add(key)
            colour = int(arrays["color"].GetTuple(cell)[0])
            colours[colour] = colours.get(colour, 0) + 1
            want = listed.get(key, expected["global_colour"])
            if colour != want:
                rv.fail(where, f"nodes {sorted(face)}: color {colour}, expected {want}")
        if int(arrays["body"].GetTuple(cell)[0]) != mesh["body"]:
            rv.fail(where, f"body {arrays['body'].GetTuple(cell)[0]}, expected {mesh['body']}")
        # the outward normal (Newell's) points away from the centre of the (convex) body
        centroid = [sum(p[k] for p in pts) / len(pts) for k in range(3)]
        normal = [0.0, 0.0, 0.0]
        for a, b in zip(pts, pts[1:] + pts[:1]):
            normal[0] += (a[1] - b[1]) * (a[2] + b[2])
            normal[1] += (a[2] - b[2]) * (a[0] + b[0])
            normal[2] += (a[0] - b[0]) * (a[1] + b[1])
        if sum(n * (x - y) for n, x, y in zip(normal, centroid, c)) <= 0.0:
            rv.fail(where, f"normal {normal} points into the body")
        # the velocity of the material point at the face centroid: v + omega x (x - c)
        r = [x - y for x, y in zip(centroid, c)]
        want = [v[0] + w[1] * r[2] - w[2] * r[1], v[1] + w[2] * r[0] - w[0] * r[2],
                v[2] + w[0] * r[1] - w[1] * r[0]]
        rv.check_vector(where, "velocity", arrays["velocity"].GetTuple(cell), want)
    want_counts = {expected["global_colour"]: faces - len(listed)}
    for colour in listed.values():
        want_counts[colour] = want_counts.get(colour, 0) + 1
    if colours != want_counts:
        rv.fail(path, f"colour counts {colours}, expected {want_counts}")


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
        wanted.add(f"{sname}_meshes.vtk.series")
        rv.check_series_file(directory, sname, "meshes", frames)
        for k, frame in enumerate(frames):
            name = f"{sname}_meshes_{k:06d}.vtk"
            wanted.add(name)
            path = os.path.join(directory, name)
            if not os.path.exists(path):
                rv.fail(path, "missing")
                continue
            check_meshes(path, frame, fmt, expected)
            checked += 1
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
    # some body has a display radius, and the mesh body turns and moves
    if not any(b["radius"] > 0 for f in frames for b in f["bodies"]):
        rv.fail(directory, "no body has a radius: the set-up does not test the field")
    first, last = frames[0]["meshes"][0]["nodes"], frames[-1]["meshes"][0]["nodes"]
    if max(abs(a - b) for x, y in zip(first, last) for a, b in zip(x, y)) < 1e-4:
        rv.fail(directory, "the mesh body does not move: the set-up does not test the poses")
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
