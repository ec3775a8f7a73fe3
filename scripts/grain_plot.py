#!/usr/bin/env python3
"""Graphs and pictures from grain's output files (matplotlib, Debian package python3-matplotlib).

Usage:
  grain_plot.py history FILE.csv [-y COLUMN ...] [-x COLUMN] [-o OUT.png]
      Graphs of the columns of a CSV time history (io::history, io::csv) against time, one panel
      per column (default: every column but time and step), or against column -x.
      Column names may be given without their unit: "mean_temperature" = "mean_temperature [K]".
  grain_plot.py lines FILE.csv [FILE.csv ...] -y COLUMN [-y COLUMN ...] [-x COLUMN]
                [--label NAME ...] [--title TEXT] [-o OUT.png]
      One graph with a curve per file and column -y against time (or column -x), e.g. the
      histories of several runs (io::compare writes one per variant). Curves are labelled
      with --label (one per file, in order; default the file name) and the column when there
      are several -y; solid, dashed and dotted in turn, so that curves that coincide stay
      visible. 8x5 inches at 120 dpi (960x600 pixels).
  grain_plot.py disks FILE_particles_NNNNNN.vtk [-f FIELD] [-o OUT.png] [--range LO HI]
      A 2D picture of the disks of a legacy VTK particle file (io::vtk), coloured by a point
      field (default temperature if present, else the speed), with the walls of the matching
      FILE_walls_NNNNNN.vtk if it exists.
  grain_plot.py animate PREFIX [-f FIELD] [-o OUT.gif] [--fps N]
      An animation (GIF) of the 2D series PREFIX_particles_*.vtk, with one colour scale for all
      frames.
  grain_plot.py spheres FILE_particles_NNNNNN.vtk [-f FIELD] [-o OUT.png] [--range LO HI]
                [--view iso|front|side|top|AZ,EL] [--size WxH] [--renderer auto|povray|matplotlib]
                [--cmap NAME] [--no-floor]
      A 3D picture of the spheres of a legacy VTK particle file (ASCII or binary, read with VTK's
      vtkPolyDataReader, Debian python3-vtk9), coloured by a point field (default temperature if
      present, else the speed; a vector or the orientation by its magnitude, NAME:x|y|z|INDEX
      by one component), with a colour bar, WxH pixels (default 800x600), seen from azimuth AZ
      and elevation EL [deg] (as matplotlib's view_init; iso = -60,30) with z up. Ray-traced by
      POV-Ray (Debian povray: perspective, lights, shadows on a floor) when it is installed,
      else (or with --renderer matplotlib) a matplotlib 3D scatter, orthographic, with markers
      the size of the spheres. Prints the file written and which renderer drew it.

Exit status 0 on success, 2 on bad arguments or unreadable files.
"""

import argparse
import csv
import glob
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time

import matplotlib

matplotlib.use("Agg")
import matplotlib.cm  # noqa: E402
import matplotlib.colors  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402
import numpy  # noqa: E402
from matplotlib import animation  # noqa: E402
from matplotlib.collections import LineCollection, PatchCollection  # noqa: E402
from matplotlib.patches import Circle  # noqa: E402


def fail(message):
    print(f"grain_plot: {message}", file=sys.stderr)
    sys.exit(2)


# ------------------------------------------------------------------ CSV histories
def read_csv(path):
    try:
        with open(path, newline="", encoding="utf-8") as f:
            rows = list(csv.reader(f))
    except OSError as e:
        fail(f"cannot read {path}: {e}")
    if len(rows) < 2:
        fail(f"{path} has no data rows")
    header = rows[0]
    columns = {name: [] for name in header}
    for row in rows[1:]:
        if len(row) != len(header):
            continue  # a row being written when the file was read
        for name, value in zip(header, row):
            columns[name].append(float(value))
    return header, columns


def find_column(header, name):
    if name in header:
        return name
    for h in header:
        if h.split(" [")[0] == name:
            return h
    fail(f"no column '{name}'; columns: {', '.join(header)}")


def plot_history(args):
    header, columns = read_csv(args.file)
    x = find_column(header, args.x) if args.x else header[0]
    ys = [find_column(header, y) for y in args.y] if args.y else \
        [h for h in header if h not in (header[0], "step") and h != x]
    if not ys:
        fail("nothing to plot")
    fig, axes = plt.subplots(len(ys), 1, figsize=(7, 2.2 * len(ys) + 0.6), sharex=True,
                             squeeze=False)
    for ax, y in zip(axes[:, 0], ys):
        ax.plot(columns[x], columns[y], lw=1.5)
        ax.set_ylabel(y)
        ax.grid(True, alpha=0.3)
    axes[-1, 0].set_xlabel(x)
    fig.suptitle(os.path.basename(args.file))
    fig.tight_layout()
    out = args.output or os.path.splitext(args.file)[0] + ".png"
    fig.savefig(out, dpi=120)
    print(out)


def plot_lines(args):
    if args.label and len(args.label) != len(args.files):
        fail(f"{len(args.label)} labels for {len(args.files)} files; give one per file or none")
    fig, ax = plt.subplots(figsize=(8, 5))
    x_name = y_label = None
    curves = 0
    for k, path in enumerate(args.files):
        header, columns = read_csv(path)
        x = find_column(header, args.x) if args.x else header[0]
        x_name = x_name or x
        label = args.label[k] if args.label else os.path.splitext(os.path.basename(path))[0]
        for y in args.y:
            y_name = find_column(header, y)
            y_label = y_label or y_name
            # solid, dashed and dotted in turn, so that curves that coincide stay visible
            style = ("-", "--", ":")[curves % 3]
            curves += 1
            ax.plot(columns[x], columns[y_name], lw=1.5, ls=style,
                    label=label if len(args.y) == 1 else f"{label}: {y_name}")
    ax.set_xlabel(x_name)
    if len(args.y) == 1:
        ax.set_ylabel(y_label)
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize="small")
    if args.title:
        ax.set_title(args.title)
    fig.tight_layout()
    out = args.output or os.path.splitext(args.files[0])[0] + "_lines.png"
    fig.savefig(out, dpi=120)
    print(out)


# ------------------------------------------------------------------ legacy VTK (as io::vtk writes it)
def read_vtk_binary(path):
    """The same as read_vtk for a BINARY legacy file, read by VTK's own reader."""
    centres, fields, _ = read_spheres(path)
    try:
        from vtkmodules.vtkCommonCore import vtkIdList
        from vtkmodules.vtkIOLegacy import vtkPolyDataReader
    except ImportError as e:
        fail(f"binary VTK files need Python's vtk module (Debian python3-vtk9): {e}")
    reader = vtkPolyDataReader()
    reader.SetFileName(path)
    reader.Update()
    data = reader.GetOutput()
    cells = []
    for array in (data.GetLines(), data.GetPolys()):
        ids = vtkIdList()
        array.InitTraversal()
        while array.GetNextCell(ids):
            cells.append([ids.GetId(k) for k in range(ids.GetNumberOfIds())])
    out = {}
    for name, v in fields.items():
        out[name] = v[:, 0].tolist() if v.shape[1] == 1 else v.tolist()
    return centres.tolist(), cells, out


def read_vtk(path):
    """Points, point or cell fields and line/polygon cells of a legacy polydata file (ASCII read
    here, BINARY by VTK's reader)."""
    try:
        with open(path, "rb") as f:
            head = [f.readline() for _ in range(3)]
    except OSError as e:
        fail(f"cannot read {path}: {e}")
    if len(head) == 3 and head[2].strip() == b"BINARY":
        return read_vtk_binary(path)
    try:
        with open(path, encoding="utf-8") as f:
            tokens = f.read().split("\n")
    except (OSError, UnicodeDecodeError) as e:
        fail(f"cannot read {path}: {e}")
    lines = iter(tokens)
    points, cells, fields = [], [], {}
    count = 0
    for line in lines:
        words = line.split()
        if not words:
            continue
        key = words[0]
        if key == "POINTS":
            n = int(words[1])
            while len(points) < n:
                v = [float(t) for t in next(lines).split()]
                points.extend(v[k:k + 3] for k in range(0, len(v), 3))
        elif key in ("LINES", "POLYGONS", "VERTICES"):
            for _ in range(int(words[1])):
                ids = [int(t) for t in next(lines).split()]
                if key != "VERTICES":
                    cells.append(ids[1:])
        elif key in ("POINT_DATA", "CELL_DATA"):
            count = int(words[1])
        elif key == "SCALARS":
            name = words[1]
            next(lines)  # LOOKUP_TABLE
            fields[name] = [float(next(lines)) for _ in range(count)]
        elif key == "VECTORS":
            name = words[1]
            fields[name] = [[float(t) for t in next(lines).split()] for _ in range(count)]
    return points, cells, fields


def scalar_field(fields, name):
    if name is None:
        name = "temperature" if "temperature" in fields else "velocity"
    if name not in fields:
        fail(f"no field '{name}'; fields: {', '.join(sorted(fields))}")
    values = fields[name]
    if values and isinstance(values[0], list):
        return f"|{name}|", [math.sqrt(sum(c * c for c in v)) for v in values]
    return name, values


def draw_frame(ax, particles_path, field, value_range):
    points, _, fields = read_vtk(particles_path)
    label, values = scalar_field(fields, field)
    radii = fields.get("radius")
    if radii is None:
        fail(f"{particles_path} has no radius field")
    disks = [Circle((p[0], p[1]), r) for p, r in zip(points, radii)]
    coll = PatchCollection(disks, cmap="inferno", linewidths=0)
    coll.set_array(values)
    if value_range:
        coll.set_clim(*value_range)
    ax.add_collection(coll)
    walls = re.sub(r"_particles_(\d+)\.vtk$", r"_walls_\1.vtk", particles_path)
    xs = [p[0] - r for p, r in zip(points, radii)] + [p[0] + r for p, r in zip(points, radii)]
    ys = [p[1] - r for p, r in zip(points, radii)] + [p[1] + r for p, r in zip(points, radii)]
    if walls != particles_path and os.path.exists(walls):
        wpts, wcells, _ = read_vtk(walls)
        segments = [[(wpts[i][0], wpts[i][1]) for i in c] for c in wcells]
        ax.add_collection(LineCollection(segments, colors="0.3", linewidths=1.5))
        xs += [p[0] for p in wpts]
        ys += [p[1] for p in wpts]
    if xs:
        pad = 0.03 * max(max(xs) - min(xs), max(ys) - min(ys), 1e-12)
        ax.set_xlim(min(xs) - pad, max(xs) + pad)
        ax.set_ylim(min(ys) - pad, max(ys) + pad)
    ax.set_aspect("equal")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    return coll, label


def plot_disks(args):
    fig, ax = plt.subplots(figsize=(6.5, 6))
    coll, label = draw_frame(ax, args.file, args.field, args.range)
    fig.colorbar(coll, ax=ax, label=label)
    ax.set_title(os.path.basename(args.file))
    fig.tight_layout()
    out = args.output or os.path.splitext(args.file)[0] + ".png"
    fig.savefig(out, dpi=120)
    print(out)


def plot_animation(args):
    files = sorted(glob.glob(glob.escape(args.prefix) + "_particles_[0-9][0-9][0-9][0-9][0-9][0-9].vtk"))
    if not files:
        fail(f"no files {args.prefix}_particles_NNNNNN.vtk")
    lo, hi = math.inf, -math.inf
    for path in files:
        _, values = scalar_field(read_vtk(path)[2], args.field)
        lo, hi = min(lo, min(values)), max(hi, max(values))
    if lo == hi:
        hi = lo + 1.0
    fig, ax = plt.subplots(figsize=(6.5, 6))
    coll, label = draw_frame(ax, files[0], args.field, (lo, hi))
    fig.colorbar(coll, ax=ax, label=label)

    def update(k):
        ax.clear()
        draw_frame(ax, files[k], args.field, (lo, hi))
        ax.set_title(f"{os.path.basename(args.prefix)} frame {k}")
        return []

    anim = animation.FuncAnimation(fig, update, frames=len(files), blit=False)
    out = args.output or args.prefix + ".gif"
    anim.save(out, writer=animation.PillowWriter(fps=args.fps))
    print(out)


# ------------------------------------------------------------------ 3D pictures of spheres
VIEWS = {"iso": (-60.0, 30.0), "front": (-90.0, 0.0), "side": (0.0, 0.0), "top": (-90.0, 90.0)}
FIELD_COMPONENTS = {"x": 0, "y": 1, "z": 2}


def read_spheres(path):
    """Centres (N x 3), point fields {name: array} and header of a legacy VTK particle file,
    ASCII or binary, read by VTK's own vtkPolyDataReader (Debian python3-vtk9)."""
    if not os.path.isfile(path):
        fail(f"cannot read {path}: no such file")
    try:
        from vtkmodules.util.misc import calldata_type
        from vtkmodules.util.numpy_support import vtk_to_numpy
        from vtkmodules.vtkCommonCore import VTK_STRING, vtkCommand
        from vtkmodules.vtkIOLegacy import vtkPolyDataReader
    except ImportError as e:
        fail(f"the spheres picture needs Python's vtk module (Debian python3-vtk9): {e}")
    errors = []

    @calldata_type(VTK_STRING)
    def on_message(_obj, event, text):
        errors.append(f"{event}: {str(text).strip()}")

    reader = vtkPolyDataReader()
    reader.AddObserver(vtkCommand.ErrorEvent, on_message)
    reader.AddObserver(vtkCommand.WarningEvent, on_message)
    reader.SetFileName(path)
    if not reader.IsFilePolyData():
        fail(f"{path} is not a legacy VTK polydata file")
    reader.ReadAllScalarsOn()
    reader.ReadAllVectorsOn()
    reader.ReadAllFieldsOn()
    reader.Update()
    if errors:
        fail(f"VTK cannot read {path}: {errors[0]}")
    data = reader.GetOutput()
    n = data.GetNumberOfPoints()
    centres = vtk_to_numpy(data.GetPoints().GetData()).astype(float).reshape(n, 3) if n else \
        numpy.zeros((0, 3))
    fields = {}
    pd = data.GetPointData()
    for k in range(pd.GetNumberOfArrays()):
        a = pd.GetArray(k)
        if a is not None and a.GetName():
            fields[a.GetName()] = \
                vtk_to_numpy(a).astype(float).reshape(n, a.GetNumberOfComponents())
    return centres, fields, (reader.GetHeader() or "").strip()


def sphere_values(fields, name):
    """The values to colour by and their label: a scalar field, the magnitude of a vector (or of
    the 4 components of the 3D orientation), or one component with NAME:x|y|z|INDEX."""
    if name is None:
        name = "temperature" if "temperature" in fields else "velocity"
    base, _, comp = name.partition(":")
    if base not in fields:
        fail(f"no field '{base}'; fields: {', '.join(sorted(fields))}")
    values = fields[base]
    if comp:
        k = FIELD_COMPONENTS.get(comp, int(comp) if comp.isdigit() else -1)
        if not 0 <= k < values.shape[1]:
            fail(f"field '{base}' has {values.shape[1]} components; no component '{comp}'")
        return name, values[:, k]
    if values.shape[1] == 1:
        return base, values[:, 0]
    return f"|{base}|", numpy.sqrt((values * values).sum(axis=1))


def parse_view(text):
    if text in VIEWS:
        return VIEWS[text]
    try:
        azimuth, elevation = (float(t) for t in text.split(","))
    except ValueError:
        fail(f"--view '{text}': give {', '.join(VIEWS)} or AZIMUTH,ELEVATION in degrees")
    if not -90.0 <= elevation <= 90.0:
        fail(f"--view '{text}': the elevation must be in [-90, 90] degrees")
    return azimuth, elevation


def parse_size(text):
    m = re.fullmatch(r"(\d+)[xX](\d+)", text)
    if not m or not (160 <= int(m.group(1)) <= 8192 and 120 <= int(m.group(2)) <= 8192):
        fail(f"--size '{text}': give WIDTHxHEIGHT in pixels, at least 160x120, at most 8192 each")
    return int(m.group(1)), int(m.group(2))


def camera_basis(azimuth, elevation):
    """Unit vectors right, up (on the screen) and forward (into it) of a camera that looks at
    the scene from azimuth/elevation [deg] (as matplotlib's view_init), with z up."""
    az, el = math.radians(azimuth), math.radians(elevation)
    forward = -numpy.array([math.cos(el) * math.cos(az), math.cos(el) * math.sin(az), math.sin(el)])
    right = numpy.array([-math.sin(az), math.cos(az), 0.0])
    return right, numpy.cross(right, forward), forward


def fit_distance(centres, radii, target, basis, half_x, half_y, margin=0.06):
    """Smallest distance from `target` of a perspective camera with half angles half_x, half_y
    [rad] that sees every sphere whole, with a margin on each side."""
    right, up, forward = basis
    rel = centres - target
    depth = rel @ forward
    need = 0.0
    for axis, half in ((right, half_x), (up, half_y)):
        t = math.tan(half) * (1.0 - margin)
        need = max(need, numpy.max((numpy.abs(rel @ axis) + radii / math.cos(half)) / t - depth))
    return max(need, numpy.max(radii - depth) * 1.01)


def pov_vector(v):
    """A scene vector (z up, right-handed) in POV-Ray's left-handed, y-up coordinates."""
    return f"<{v[0]:.6g},{v[2]:.6g},{v[1]:.6g}>"


def render_povray(povray, centres, radii, colour_index, lut, view, width, height, floor):
    """Renders the spheres with POV-Ray; returns the image as an array (height x width x 3)."""
    import matplotlib.image as mpimg

    lo, hi = (centres - radii[:, None]).min(axis=0), (centres + radii[:, None]).max(axis=0)
    scale = 10.0 / max(float((hi - lo).max()), 1e-300)  # the scene about 10 units across
    target = 0.5 * (lo + hi)
    c = (centres - target) * scale
    r = radii * scale
    lo, hi = (lo - target) * scale, (hi - target) * scale
    basis = camera_basis(*view)
    right, up, forward = basis
    half_y = math.radians(15.0)
    half_x = math.atan(math.tan(half_y) * width / height)
    # aim at the middle of the picture of the spheres, not of their box: a few corrections
    aim = numpy.zeros(3)
    for _ in range(3):
        distance = fit_distance(c, r, aim, basis, half_x, half_y)
        rel = c - aim
        depth = distance + rel @ forward
        for axis in (right, up):
            along = rel @ axis
            aim = aim + axis * 0.5 * distance * \
                (numpy.max((along + r) / depth) + numpy.min((along - r) / depth))
    distance = fit_distance(c, r, aim, basis, half_x, half_y)
    eye = aim - distance * forward
    size = float((hi - lo).max())
    key = eye + distance * (0.9 * up - 0.6 * right) + 2.0 * size * numpy.array([0, 0, 1.0])
    fill = eye + distance * (0.3 * up + 0.8 * right)
    scene = [
        "#version 3.7;",
        "global_settings { assumed_gamma 1.0 max_trace_level 5 }",
        "background { color rgb 1 }",
        f"camera {{ perspective location {pov_vector(eye)} look_at {pov_vector(aim)} "
        f"sky {pov_vector(up)} right x*{width / height:.6g} "
        f"angle {math.degrees(2 * half_x):.6g} }}",
        f"light_source {{ {pov_vector(key)} color rgb 0.85 }}",  # hard shadows: 3x faster
        f"light_source {{ {pov_vector(fill)} color rgb 0.3 shadowless }}",
        "#declare F = finish { ambient 0.22 diffuse 0.7 specular 0.25 roughness 0.03 }",
    ]
    for k, (red, green, blue, _) in enumerate(lut):
        scene.append(f"#declare T{k} = texture {{ pigment {{ srgb <{red:.4f},{green:.4f},"
                     f"{blue:.4f}> }} finish {{ F }} }}")
    if floor and view[1] > 0.0:
        pad = 0.35 * size
        scene.append(f"box {{ {pov_vector((lo[0] - pad, lo[1] - pad, lo[2] - 0.02 * size))}, "
                     f"{pov_vector((hi[0] + pad, hi[1] + pad, lo[2]))} "
                     "pigment { color rgb 0.93 } finish { ambient 0.45 diffuse 0.55 } }")
    scene.extend(f"sphere{{{pov_vector(p)},{q:.6g} texture{{T{k}}}}}"
                 for p, q, k in zip(c, r, colour_index))
    with tempfile.TemporaryDirectory(prefix="grain_plot_") as tmp:
        # relative names in a scratch working directory: POV-Ray's file I/O restrictions
        # (/etc/povray/3.7/povray.conf) always allow the current directory
        with open(os.path.join(tmp, "scene.pov"), "w", encoding="utf-8") as f:
            f.write("\n".join(scene) + "\n")
        command = [povray, "+Iscene.pov", "+Oimage.png", "+FN", f"+W{width}", f"+H{height}",
                   "-D", "-P", "+A0.1", "+AM2", "+R3", "+Q9", "-V"]
        try:
            run = subprocess.run(command, cwd=tmp, stdin=subprocess.DEVNULL,
                                 capture_output=True, text=True, errors="replace")
        except OSError as e:
            return None, str(e)
        image_path = os.path.join(tmp, "image.png")
        if run.returncode != 0 or not os.path.exists(image_path):
            tail = [line for line in run.stderr.splitlines() if line.strip()][-6:]
            return None, f"exit status {run.returncode}: " + " / ".join(tail)
        return mpimg.imread(image_path)[:, :, :3], None


def render_matplotlib(ax, centres, radii, colours, view, dpi):
    """mplot3d scatter (orthographic), marker diameters scaled to the sphere diameters."""
    lo, hi = (centres - radii[:, None]).min(axis=0), (centres + radii[:, None]).max(axis=0)
    mid, half = 0.5 * (lo + hi), 0.5 * float((hi - lo).max()) * 1.02
    ax.set_proj_type("ortho")
    ax.view_init(elev=view[1], azim=view[0])
    ax.set_xlim(mid[0] - half, mid[0] + half)
    ax.set_ylim(mid[1] - half, mid[1] + half)
    ax.set_zlim(mid[2] - half, mid[2] + half)
    ax.set_box_aspect((1, 1, 1))
    # far spheres first, so that near ones cover them
    _, _, forward = camera_basis(*view)
    order = numpy.argsort(-(centres @ forward))
    coll = ax.scatter(centres[order, 0], centres[order, 1], centres[order, 2], c=colours[order],
                      s=1.0, depthshade=False, edgecolors=(0, 0, 0, 0.35), linewidths=0.3)
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.set_zlabel("z [m]")
    for axis in (ax.xaxis, ax.yaxis, ax.zaxis):
        axis.label.set_fontsize("small")
    ax.tick_params(labelsize="x-small")
    # points per metre on the screen, from the projection of a segment along the screen's right
    ax.figure.canvas.draw()
    right, _, _ = camera_basis(*view)
    from mpl_toolkits.mplot3d import proj3d

    ends = [proj3d.proj_transform(*(mid + t * right), ax.get_proj()) for t in (0.0, half)]
    pixels = ax.transData.transform([e[:2] for e in ends])
    per_metre = numpy.hypot(*(pixels[1] - pixels[0])) / half * 72.0 / dpi
    coll.set_sizes((2.0 * radii[order] * per_metre) ** 2)
    return coll


def plot_spheres(args):
    width, height = parse_size(args.size)
    view = parse_view(args.view)
    centres, fields, header = read_spheres(args.file)
    if len(centres) == 0:
        fail(f"{args.file} has no particles")
    if "radius" not in fields:
        fail(f"{args.file} has no radius field; fields: {', '.join(sorted(fields))}")
    radii = fields["radius"][:, 0]
    label, values = sphere_values(fields, args.field)
    if args.range and not args.range[1] > args.range[0]:
        fail(f"--range {args.range[0]:g} {args.range[1]:g}: LO must be below HI")
    if args.cmap not in matplotlib.colormaps:
        fail(f"--cmap '{args.cmap}': not a matplotlib colormap (e.g. plasma, viridis, coolwarm)")
    lo, hi = args.range if args.range else (float(values.min()), float(values.max()))
    if not hi > lo:  # one value: the middle of the scale
        delta = 0.05 * abs(lo) if lo != 0.0 else 1.0
        lo, hi = lo - delta, hi + delta
    norm = matplotlib.colors.Normalize(lo, hi, clip=True)
    cmap = matplotlib.colormaps[args.cmap]
    out = args.output or os.path.splitext(args.file)[0] + ".png"

    renderer = args.renderer
    povray = shutil.which("povray")
    if renderer in ("auto", "povray") and not povray:
        if renderer == "povray":
            fail("povray not found (Debian package povray)")
        renderer = "matplotlib"
    dpi = 100.0
    font = min(max(height / 60.0, 6.0), 11.0)
    bar_width = min(max(int(round(width * 0.15)), int(round(8.5 * font)) + 30), int(0.4 * width))
    scene_width = width - bar_width
    started = time.monotonic()
    image = None
    if renderer != "matplotlib":
        steps = 256
        lut = cmap(numpy.linspace(0.0, 1.0, steps))
        index = numpy.clip((norm(values).filled(0.0) * steps).astype(int), 0, steps - 1)
        image, error = render_povray(povray, centres, radii, index, lut, view, scene_width, height,
                                     not args.no_floor)
        if image is None:
            if renderer == "povray":
                fail(f"povray failed ({error})")
            print(f"grain_plot: povray failed ({error}); drawing with matplotlib", file=sys.stderr)
        renderer = "povray" if image is not None else "matplotlib"

    with plt.rc_context({"font.size": font}):
        fig = plt.figure(figsize=(width / dpi, height / dpi), dpi=dpi)
        frac = scene_width / width
        if image is not None:
            ax = fig.add_axes((0.0, 0.0, frac, 1.0))
            ax.imshow(image, interpolation="none", aspect="auto")
            ax.set_axis_off()
        else:
            ax = fig.add_axes((0.0, 0.0, frac, 1.0), projection="3d")
            render_matplotlib(ax, centres, radii, cmap(norm(values)), view, dpi)
        m = re.search(r"t = (\S+)", header)
        title = os.path.basename(args.file) + (f"\nt = {float(m.group(1)):.4g} s" if m else "")
        fig.text(0.01, 0.99, title, ha="left", va="top", fontsize="small", color="0.25")
        cax = fig.add_axes((frac + 12.0 / width, 0.1, 12.0 / width, 0.8))
        fig.colorbar(matplotlib.cm.ScalarMappable(norm=norm, cmap=cmap), cax=cax, label=label)
        fig.savefig(out, dpi=dpi)
        plt.close(fig)
    print(out)
    print(f"spheres: {len(centres)} spheres drawn by {renderer} in "
          f"{time.monotonic() - started:.2f} s")


def main():
    parser = argparse.ArgumentParser(description="Graphs and pictures from grain's output files.")
    sub = parser.add_subparsers(dest="command", required=True)
    h = sub.add_parser("history", help="graphs of a CSV time history")
    h.add_argument("file")
    h.add_argument("-y", action="append", help="column to plot (repeatable)")
    h.add_argument("-x", help="column for the horizontal axis (default: time)")
    h.add_argument("-o", "--output")
    n = sub.add_parser("lines", help="curves of several CSV files in one graph")
    n.add_argument("files", nargs="+")
    n.add_argument("-y", action="append", required=True, help="column to plot (repeatable)")
    n.add_argument("-x", help="column for the horizontal axis (default: time)")
    n.add_argument("--label", action="append", help="name of a file's curve (one per file)")
    n.add_argument("--title")
    n.add_argument("-o", "--output")
    d = sub.add_parser("disks", help="a picture of 2D disks coloured by a field")
    d.add_argument("file")
    d.add_argument("-f", "--field")
    d.add_argument("-o", "--output")
    d.add_argument("--range", nargs=2, type=float, metavar=("LO", "HI"))
    a = sub.add_parser("animate", help="a GIF of a 2D VTK series")
    a.add_argument("prefix")
    a.add_argument("-f", "--field")
    a.add_argument("-o", "--output")
    a.add_argument("--fps", type=int, default=10)
    s = sub.add_parser("spheres", help="a 3D picture of the spheres of a VTK file")
    s.add_argument("file")
    s.add_argument("-f", "--field")
    s.add_argument("-o", "--output")
    s.add_argument("--range", nargs=2, type=float, metavar=("LO", "HI"))
    s.add_argument("--view", default="iso",
                   help="iso (default), front, side, top or AZIMUTH,ELEVATION in degrees "
                   "(--view=-60,30 when AZIMUTH is negative)")
    s.add_argument("--size", default="800x600", help="WIDTHxHEIGHT in pixels (default 800x600)")
    s.add_argument("--renderer", choices=("auto", "povray", "matplotlib"), default="auto")
    s.add_argument("--cmap", default="plasma", help="matplotlib colormap (default plasma)")
    s.add_argument("--no-floor", action="store_true")
    args = parser.parse_args()
    {"history": plot_history, "lines": plot_lines, "disks": plot_disks, "animate": plot_animation,
     "spheres": plot_spheres}[args.command](args)
    return 0


if __name__ == "__main__":
    sys.exit(main())
