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
      field, with the walls of the matching FILE_walls_NNNNNN.vtk if it exists.
  grain_plot.py animate PREFIX [-f FIELD] [-o OUT.gif] [--fps N]
      An animation (GIF) of the 2D series PREFIX_particles_*.vtk, with one colour scale for all
      frames, each frame titled with its time.
  grain_plot.py spheres FILE_particles_NNNNNN.vtk [-f FIELD] [-o OUT.png] [--range LO HI]
                [--view iso|front|side|top|AZ,EL] [--size WxH] [--renderer auto|povray|matplotlib]
                [--cmap NAME] [--no-floor] [--no-walls]
      A 3D picture of the spheres of a legacy VTK particle file (ASCII or binary, read with VTK's
      vtkPolyDataReader, Debian python3-vtk9), coloured by a point field, with a colour bar and
      the walls of the matching FILE_walls_NNNNNN.vtk if it exists (translucent, outlined where
      they end or fold; --no-walls leaves them out), WxH pixels (default 800x600), seen from
      azimuth AZ and elevation EL [deg] (as matplotlib's view_init; iso = -60,30) with z up.
      Ray-traced by POV-Ray (Debian povray: perspective, lights, shadows on a floor) when it is
      installed, else (or with --renderer matplotlib) a matplotlib 3D scatter, orthographic, with
      markers the size of the spheres. Prints the file written and which renderer drew it.

FIELD (disks, animate, spheres): a point field of the particle file, by default temperature if
present, else the speed; a vector (velocity, omega, force, torque) or the 3D orientation is drawn
by its magnitude, NAME:x|y|z|INDEX draws one component. The colour bar shows the field with its
SI unit ("temperature [K]", "speed [m/s]", "velocity:z [m/s]"), and pictures and frames are
titled with the time of their file ("t = 0.125 s", from the header line "grain particles t =
0.125" that io::vtk writes).

Needs numpy and matplotlib, and for spheres and binary VTK files VTK's Python module (Debian
python3-numpy, python3-matplotlib, python3-vtk9); a missing one is named in a one-line message.
Exit status 0 on success, 2 on bad arguments, unreadable files or a missing Python module.
"""

import argparse
import collections
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

PROGRAM = os.path.basename(sys.argv[0]) or "grain_plot.py"


def missing(module, debian, who="needs"):
    """Stops (status 2) with one line naming the missing Python module and how to install it."""
    print(f"{PROGRAM}: {who} {module} (Debian: apt-get install {debian}; pip: pip install "
          f"{module})", file=sys.stderr)
    sys.exit(2)


try:  # before matplotlib, which cannot be imported without it
    import numpy
except ImportError:
    missing("numpy", "python3-numpy")
try:
    import matplotlib
except ImportError:
    missing("matplotlib", "python3-matplotlib")
matplotlib.use("Agg")
import matplotlib.cm  # noqa: E402
import matplotlib.colors  # noqa: E402
import matplotlib.image  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib import animation  # noqa: E402
from matplotlib.collections import LineCollection, PatchCollection  # noqa: E402
from matplotlib.patches import Circle  # noqa: E402
from mpl_toolkits.mplot3d import proj3d  # noqa: E402
from mpl_toolkits.mplot3d.art3d import Line3DCollection, Poly3DCollection  # noqa: E402


def fail(message):
    print(f"{PROGRAM}: {message}", file=sys.stderr)
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


# ------------------------------------------------------------------ fields, units and times
# SI units of the particle fields of io::vtk (the table at the top of include/grain/io/vtk.hpp).
# id and material have none, nor has the 3D orientation (a unit quaternion; the 2D one is an
# angle), nor a field not listed here.
UNITS = {"radius": "m", "velocity": "m/s", "omega": "rad/s", "force": "N", "torque": "N m",
         "mass": "kg", "orientation": "rad", "temperature": "K", "heat_rate": "W",
         "heat_capacity": "J/K"}
FIELD_COMPONENTS = {"x": 0, "y": 1, "z": 2}


def field_values(fields, name):
    """The values to colour by (an array) and their label with the unit, e.g. "speed [m/s]": a
    scalar field, the magnitude of a vector (or of the 4 components of the 3D orientation), or
    one component with NAME:x|y|z|INDEX. By default (name None) the temperature if there is one,
    else the speed."""
    if name is None:
        name = "temperature" if "temperature" in fields else "velocity"
    base, _, comp = name.partition(":")
    if base not in fields:
        fail(f"no field '{base}'; fields: {', '.join(sorted(fields))}")
    values = numpy.asarray(fields[base], dtype=float)
    if values.ndim == 1:
        values = values[:, None]
    unit = None if base == "orientation" and values.shape[1] > 1 else UNITS.get(base)
    if comp:
        k = FIELD_COMPONENTS.get(comp, int(comp) if comp.isdigit() else -1)
        if not 0 <= k < values.shape[1]:
            fail(f"field '{base}' has {values.shape[1]} components; no component '{comp}'")
        label, values = name, values[:, k]
    elif values.shape[1] == 1:
        label, values = base, values[:, 0]
    else:
        label = "speed" if base == "velocity" else f"|{base}|"
        values = numpy.sqrt((values * values).sum(axis=1))
    return (f"{label} [{unit}]" if unit else label), values


def header_time(header):
    """The time [s] in the header line of a file of io::vtk ("grain particles t = 0.125"), or
    None."""
    m = re.search(r"\bt = (\S+)", header)
    try:
        return float(m.group(1)) if m else None
    except ValueError:
        return None


def time_text(t):
    """The time t [s] as "t = 0.125 s", to 6 significant digits; "" for an unknown time (None)."""
    return "" if t is None else f"t = {t:.6g} s"


def time_texts(times):
    """time_text of each frame of a series, all with the fewest decimals that tell consecutive
    frames apart ("t = 0.00 s", "t = 0.05 s", "t = 0.10 s")."""
    known = sorted(t for t in times if t is not None)
    steps = [b - a for a, b in zip(known, known[1:]) if b > a]
    if not steps:
        return [time_text(t) for t in times]
    tolerance = 0.05 * min(steps)
    decimals = next((d for d in range(10) if all(abs(round(t, d) - t) <= tolerance
                                                 for t in known)), 9)
    return ["" if t is None else f"t = {t:.{decimals}f} s" for t in times]


def title(name, time_line):
    """A picture's title: the file (or series) name, and the time below it if known."""
    return f"{name}\n{time_line}" if time_line else name


# ------------------------------------------------------------------ legacy VTK (as io::vtk writes it)
# A legacy polydata file: points (N x 3 array), polylines and polygons (lists of point indices),
# fields {name: values} and the time [s] of its header line (None if it has none).
VtkData = collections.namedtuple("VtkData", "points lines polygons fields time")


def read_vtk(path):
    """A legacy polydata file as VtkData, with its point and cell fields: ASCII read here,
    BINARY (point fields only) by VTK's reader."""
    try:
        with open(path, "rb") as f:
            head = [f.readline() for _ in range(3)]
    except OSError as e:
        fail(f"cannot read {path}: {e}")
    if head[2].strip() == b"BINARY":
        return read_polydata(path, "reading a binary VTK file needs")
    try:
        with open(path, encoding="utf-8") as f:
            return parse_ascii_vtk(f.read().split("\n"))
    except (OSError, UnicodeDecodeError) as e:
        fail(f"cannot read {path}: {e}")
    except (ValueError, IndexError, StopIteration):
        fail(f"{path} is not a legacy VTK polydata file as grain writes it")


def parse_ascii_vtk(lines):
    """VtkData of the lines of an ASCII legacy polydata file."""
    lines = iter(lines)
    next(lines)  # "# vtk DataFile Version 3.0"
    header = next(lines)
    points, cells, fields = [], {"LINES": [], "POLYGONS": []}, {}
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
                ids = [int(t) for t in next(lines).split()][1:]
                if key in cells:  # not the vertices, one per particle
                    cells[key].append(ids)
        elif key in ("POINT_DATA", "CELL_DATA"):
            count = int(words[1])
        elif key == "SCALARS":
            next(lines)  # LOOKUP_TABLE
            rows = [[float(t) for t in next(lines).split()] for _ in range(count)]
            components = int(words[3]) if len(words) > 3 else 1
            fields[words[1]] = [r[0] for r in rows] if components == 1 else rows
        elif key == "VECTORS":
            fields[words[1]] = [[float(t) for t in next(lines).split()] for _ in range(count)]
    return VtkData(numpy.array(points, dtype=float).reshape(-1, 3), cells["LINES"],
                   cells["POLYGONS"], fields, header_time(header))


def read_polydata(path, who):
    """VtkData of a legacy polydata file, ASCII or binary, read by VTK's own vtkPolyDataReader
    (Debian python3-vtk9), with its point fields as (N x components) arrays; `who` is what
    needs VTK, for the message if its Python module is missing."""
    if not os.path.isfile(path):
        fail(f"cannot read {path}: no such file")
    try:
        from vtkmodules.util.misc import calldata_type
        from vtkmodules.util.numpy_support import vtk_to_numpy
        from vtkmodules.vtkCommonCore import VTK_STRING, vtkCommand
        from vtkmodules.vtkIOLegacy import vtkPolyDataReader
    except ImportError:
        missing("vtk", "python3-vtk9", who)
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
    points = vtk_to_numpy(data.GetPoints().GetData()).astype(float).reshape(n, 3) if n else \
        numpy.zeros((0, 3))
    cells = []
    for array in (data.GetLines(), data.GetPolys()):
        offsets = vtk_to_numpy(array.GetOffsetsArray()).tolist()
        ids = vtk_to_numpy(array.GetConnectivityArray()).tolist()
        cells.append([ids[a:b] for a, b in zip(offsets, offsets[1:])])
    fields = {}
    pd = data.GetPointData()
    for k in range(pd.GetNumberOfArrays()):
        a = pd.GetArray(k)
        if a is not None and a.GetName():
            fields[a.GetName()] = \
                vtk_to_numpy(a).astype(float).reshape(n, a.GetNumberOfComponents())
    return VtkData(points, cells[0], cells[1], fields, header_time(reader.GetHeader() or ""))


def read_walls(particles_path):
    """VtkData of FILE_walls_NNNNNN.vtk, the walls of FILE_particles_NNNNNN.vtk (io::vtk writes
    one per frame when there are walls: lines in 2D; in 3D planes as squares, triangles as
    triangles), or None if there is none."""
    path = re.sub(r"_particles_(\d+)\.vtk$", r"_walls_\1.vtk", particles_path)
    return read_vtk(path) if path != particles_path and os.path.exists(path) else None


# ------------------------------------------------------------------ 2D pictures of disks
# What a 2D picture shows of a particle file: centres (N x 3), radii, values to colour by and
# their label, time [s] (or None) and walls (VtkData or None).
Disks = collections.namedtuple("Disks", "centres radii values label time walls data")


def read_disks(path, field):
    """Disks of the particle file `path`, coloured by `field` (see field_values)."""
    data = read_vtk(path)
    if "radius" not in data.fields:
        fail(f"{path} has no radius field")
    label, values = field_values(data.fields, field)
    radii = numpy.asarray(data.fields["radius"], dtype=float).reshape(-1)
    return Disks(data.points, radii, values, label, data.time, read_walls(path), data)


class DiskStyle:
    """What a 2D picture adds to the coloured disks (animate's options):
    ids          label each disk with its id
    markers      a radius drawn at each disk's orientation angle (its turning)
    arrows       a vector field drawn as arrows at the centres ("velocity", "force")
    arrow_scale  length [m] of an arrow per unit of the field (None: the longest arrow of the
                 picture is 1.5 times the largest radius)
    window       (xmin, xmax, ymin, ymax) [m] of the view (None: fitted to disks and walls)
    wall_field   colour the walls by this field of the walls' file (e.g. "temperature") on the
                 disks' colour scale, where the file has it"""

    def __init__(self, ids=False, markers=False, arrows=None, arrow_scale=None, window=None,
                 wall_field=None):
        self.ids, self.markers, self.arrows = ids, markers, arrows
        self.arrow_scale, self.window, self.wall_field = arrow_scale, window, wall_field


def arrow_vectors(disks, name):
    """The in-plane components (N x 2) of the vector field `name` of a Disks."""
    if name not in disks.data.fields:
        fail(f"no field '{name}' for arrows; fields: {', '.join(sorted(disks.data.fields))}")
    v = numpy.asarray(disks.data.fields[name], dtype=float)
    if v.ndim != 2 or v.shape[1] < 2:
        fail(f"field '{name}' is not a vector field")
    return v[:, :2]


def draw_disks(ax, disks, value_range, style=None):
    """Draws Disks on `ax`, coloured on value_range (LO, HI) if given, the walls as lines, the
    axes fitted to both (or to style.window); returns the collection of the disks (for a
    colour bar). `style` (a DiskStyle) adds ids, orientation markers, arrows and walls coloured
    by a field."""
    style = style or DiskStyle()
    centres, radii = disks.centres[:, :2], disks.radii
    coll = PatchCollection([Circle(p, r) for p, r in zip(centres, radii)], cmap="inferno",
                           linewidths=0)
    coll.set_array(disks.values)
    if value_range:
        coll.set_clim(*value_range)
    ax.add_collection(coll)
    corners = [centres - radii[:, None], centres + radii[:, None]]
    if disks.walls is not None:
        points = disks.walls.points[:, :2]
        cells = disks.walls.lines + [p + p[:1] for p in disks.walls.polygons]
        lines = LineCollection([points[c] for c in cells], colors="0.3", linewidths=1.5)
        values = disks.walls.fields.get(style.wall_field) if style.wall_field else None
        if values is not None and len(values) == len(cells):
            # the walls on the disks' colour scale (cell data: lines, then polygons)
            lines = LineCollection([points[c] for c in cells], cmap="inferno", linewidths=3.0)
            lines.set_array(numpy.asarray(values, dtype=float))
            lines.set_clim(*(value_range or coll.get_clim()))
        ax.add_collection(lines)
        corners.append(points)
    if style.markers and "orientation" in disks.data.fields:
        theta = numpy.asarray(disks.data.fields["orientation"], dtype=float).reshape(-1)
        if len(theta) == len(radii):
            ends = centres + radii[:, None] * numpy.stack([numpy.cos(theta),
                                                             numpy.sin(theta)], axis=1)
            ax.add_collection(LineCollection(list(zip(centres, ends)), colors="0.85",
                                             linewidths=1.2))
    if style.arrows:
        v = arrow_vectors(disks, style.arrows)
        scale = style.arrow_scale
        if scale is None:
            longest = float(numpy.sqrt((v * v).sum(axis=1)).max()) if len(v) else 0.0
            scale = 1.5 * float(radii.max()) / longest if longest > 0 else 0.0
        if scale > 0:
            ax.quiver(centres[:, 0], centres[:, 1], v[:, 0] * scale, v[:, 1] * scale,
                      angles="xy", scale_units="xy", scale=1.0, color="tab:cyan", width=0.004)
    if style.window:
        ax.set_xlim(style.window[0], style.window[1])
        ax.set_ylim(style.window[2], style.window[3])
    else:
        corners = numpy.concatenate(corners)
        if len(corners):
            lo, hi = corners.min(axis=0), corners.max(axis=0)
            pad = 0.03 * max(float((hi - lo).max()), 1e-12)
            ax.set_xlim(lo[0] - pad, hi[0] + pad)
            ax.set_ylim(lo[1] - pad, hi[1] + pad)
    ax.set_aspect("equal")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    if style.ids and "id" in disks.data.fields:
        # labels sized to the disks as drawn: points per metre of the view
        ax.apply_aspect()
        x0, x1 = ax.get_xlim()
        per_metre = ax.get_window_extent().width / abs(x1 - x0) * 72.0 / ax.figure.dpi
        for (x, y), i, r in zip(centres, disks.data.fields["id"], radii):
            size = 0.8 * r * per_metre
            if size >= 3.0:  # too small to read otherwise
                ax.text(x, y, "%d" % int(i), ha="center", va="center", color="tab:green",
                        fontsize=min(size, 12.0), clip_on=True)
    return coll


def disks_figure(path, field=None, value_range=None):
    """The picture of `disks`: the disks of the 2D particle file `path` coloured by `field`, a
    colour bar labelled with the field and its unit, titled with the file name and the time."""
    disks = read_disks(path, field)
    fig, ax = plt.subplots(figsize=(6.5, 6))
    fig.colorbar(draw_disks(ax, disks, value_range), ax=ax, label=disks.label)
    ax.set_title(title(os.path.basename(path), time_text(disks.time)))
    fig.tight_layout()
    return fig


def plot_disks(args):
    fig = disks_figure(args.file, args.field, args.range)
    out = args.output or os.path.splitext(args.file)[0] + ".png"
    fig.savefig(out, dpi=120)
    print(out)


def disks_animation(prefix, field=None, value_range=None, style=None, heading=None):
    """The animation of `animate`: (figure, draw, number of frames), where draw(k) draws frame k
    of the series PREFIX_particles_NNNNNN.vtk titled with `heading` (default: the prefix's
    name) and its time, every frame on the colour scale value_range (default: the range of all
    frames). `style` is a DiskStyle; its arrows get one scale for all frames."""
    files = sorted(glob.glob(glob.escape(prefix) + "_particles_[0-9][0-9][0-9][0-9][0-9][0-9].vtk"))
    if not files:
        fail(f"no files {prefix}_particles_NNNNNN.vtk")
    frames = [read_disks(path, field) for path in files]
    if value_range:
        lo, hi = value_range
    else:
        values = [f.values for f in frames]
        if style and style.wall_field:  # walls on the same scale: their values count too
            values += [numpy.asarray(f.walls.fields[style.wall_field], dtype=float)
                       for f in frames if f.walls is not None and style.wall_field in
                       f.walls.fields]
        values = numpy.concatenate(values)
        lo, hi = (float(values.min()), float(values.max())) if len(values) else (0.0, 1.0)
    if lo == hi:
        hi = lo + 1.0
    style = style or DiskStyle()
    if style.arrows and style.arrow_scale is None:
        longest = max((float(numpy.sqrt((v * v).sum(axis=1)).max()) for v in
                       (arrow_vectors(f, style.arrows) for f in frames) if len(v)), default=0.0)
        r_max = max((float(f.radii.max()) for f in frames if len(f.radii)), default=0.0)
        style.arrow_scale = 1.5 * r_max / longest if longest > 0 else 0.0
    times = time_texts([f.time for f in frames])
    name = heading or os.path.basename(prefix)
    fig, ax = plt.subplots(figsize=(6.5, 6))
    fig.colorbar(draw_disks(ax, frames[0], (lo, hi), style), ax=ax, label=frames[0].label)

    def draw(k):
        ax.clear()
        draw_disks(ax, frames[k], (lo, hi), style)
        ax.set_title(title(name, times[k]))
        return []

    return fig, draw, len(frames)


def plot_animation(args):
    style = DiskStyle(ids=args.ids, markers=args.markers, arrows=args.arrows,
                      window=args.window, wall_field=args.wall_field)
    if args.window and not (args.window[0] < args.window[1] and args.window[2] < args.window[3]):
        fail(f"--window {args.window}: XMIN < XMAX and YMIN < YMAX")
    if args.range and not args.range[0] < args.range[1]:
        fail(f"--range {args.range}: LO < HI")
    fig, draw, frames = disks_animation(args.prefix, args.field, args.range, style, args.title)
    anim = animation.FuncAnimation(fig, draw, frames=frames, blit=False)
    out = args.output or args.prefix + ".gif"
    anim.save(out, writer=animation.PillowWriter(fps=args.fps))
    print(out)


# ------------------------------------------------------------------ 3D pictures of spheres
VIEWS = {"iso": (-60.0, 30.0), "front": (-90.0, 0.0), "side": (0.0, 0.0), "top": (-90.0, 90.0)}
WALL_FACE = (0.55, 0.62, 0.7)  # colour of the translucent walls
WALL_EDGE = (0.25, 0.27, 0.3)  # and of their outline
FOLD = math.radians(20.0)  # polygons that meet at a larger angle are outlined where they meet


def wall_edges(walls):
    """The segments (2 x 3 arrays) that outline walls (VtkData): every segment of their polylines,
    and the edges of their polygons where a surface ends or folds (two polygons that meet at more
    than FOLD); edges inside a flat surface (between the triangles of a flat mesh) are left out."""
    points = walls.points
    grid = 1e-7 * max(float(numpy.ptp(points, axis=0).max()) if len(points) else 0.0, 1e-300)

    def key(p):
        return tuple(numpy.round(points[p] / grid).astype(numpy.int64))

    edges = {}  # {the edge's two ends: (a point index of each, the normals of its polygons)}
    for polygon in walls.polygons:
        p = points[polygon]
        normal = numpy.cross(p, numpy.roll(p, -1, axis=0)).sum(axis=0)  # Newell's method
        normal /= max(numpy.linalg.norm(normal), 1e-300)
        for a, b in zip(polygon, polygon[1:] + polygon[:1]):
            ends = frozenset((key(a), key(b)))
            if len(ends) == 2:
                edges.setdefault(ends, (a, b, []))[2].append(normal)
    segments = [points[line[k:k + 2]] for line in walls.lines for k in range(len(line) - 1)]
    for a, b, normals in edges.values():
        if len(normals) != 2 or abs(float(normals[0] @ normals[1])) < math.cos(FOLD):
            segments.append(points[[a, b]])
    return segments


def scene_box(centres, radii, walls):
    """Corners (lo, hi) of the box that holds the spheres and the walls (if not None)."""
    lo, hi = (centres - radii[:, None]).min(axis=0), (centres + radii[:, None]).max(axis=0)
    if walls is not None and len(walls.points):
        lo, hi = numpy.minimum(lo, walls.points.min(axis=0)), \
            numpy.maximum(hi, walls.points.max(axis=0))
    return lo, hi


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


def pov_colour(rgb, transmit):
    """A POV-Ray colour: sRGB components and the fraction of light it lets through."""
    return "srgbt <%.3f,%.3f,%.3f,%.3f>" % (*rgb, transmit)


def pov_walls(walls, to_scene, size):
    """POV-Ray objects of walls (VtkData): their polygons as translucent triangles (one mesh) and
    their outline (wall_edges) as thin cylinders, neither casting shadows; to_scene(points) maps
    points to the scene, `size` is the scene's size."""
    triangles = []
    for polygon in walls.polygons:
        p = to_scene(walls.points[polygon])
        for k in range(1, len(p) - 1):  # a fan of triangles from the first corner
            if numpy.linalg.norm(numpy.cross(p[k] - p[0], p[k + 1] - p[0])) > 1e-12 * size ** 2:
                triangles.append(f"triangle{{{pov_vector(p[0])},{pov_vector(p[k])},"
                                 f"{pov_vector(p[k + 1])}}}")
    face = "texture{pigment{" + pov_colour(WALL_FACE, 0.8) + "} finish{ambient 0.3 diffuse 0.5}}"
    edge = "texture{pigment{" + pov_colour(WALL_EDGE, 0.3) + "} finish{ambient 0.5}}"
    scene = ["mesh{" + "\n".join(triangles) + f"\n{face} no_shadow}}"] if triangles else []
    radius = 0.002 * size
    for a, b in (to_scene(s) for s in wall_edges(walls)):
        if numpy.linalg.norm(b - a) > 1e-9 * size:
            scene.append(f"cylinder{{{pov_vector(a)},{pov_vector(b)},{radius:.6g} {edge} "
                         "no_shadow}")
    return scene


def render_povray(povray, centres, radii, colour_index, lut, view, width, height, floor, walls):
    """Renders the spheres, and the walls (VtkData, or None), with POV-Ray; returns the image as an
    array (height x width x 3), or None and the reason."""
    lo, hi = scene_box(centres, radii, walls)
    scale = 10.0 / max(float((hi - lo).max()), 1e-300)  # the scene about 10 units across
    target = 0.5 * (lo + hi)

    def to_scene(points):
        return (points - target) * scale

    c = to_scene(centres)
    r = radii * scale
    lo, hi = to_scene(lo), to_scene(hi)
    size = float((hi - lo).max())
    # what the camera must see whole: the spheres and the corners of the walls
    if walls is not None:
        c = numpy.concatenate([c, to_scene(walls.points)])
        r = numpy.concatenate([r, numpy.zeros(len(walls.points))])
    basis = camera_basis(*view)
    right, up, forward = basis
    half_y = math.radians(15.0)
    half_x = math.atan(math.tan(half_y) * width / height)
    # aim at the middle of the picture of the scene, not of its box: a few corrections
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
    key = eye + distance * (0.9 * up - 0.6 * right) + 2.0 * size * numpy.array([0, 0, 1.0])
    fill = eye + distance * (0.3 * up + 0.8 * right)
    scene = [
        "#version 3.7;",
        "global_settings { assumed_gamma 1.0 max_trace_level 8 }",
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
        top = lo[2] - (0.001 * size if walls is not None else 0.0)  # just below a floor wall
        scene.append(f"box {{ {pov_vector((lo[0] - pad, lo[1] - pad, top - 0.02 * size))}, "
                     f"{pov_vector((hi[0] + pad, hi[1] + pad, top))} "
                     "pigment { color rgb 0.93 } finish { ambient 0.45 diffuse 0.55 } }")
    scene.extend(f"sphere{{{pov_vector(p)},{q:.6g} texture{{T{k}}}}}"
                 for p, q, k in zip(c, r, colour_index))
    if walls is not None:
        scene.extend(pov_walls(walls, to_scene, size))
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
        return matplotlib.image.imread(image_path)[:, :, :3], None


def draw_walls_matplotlib(ax, walls, forward, middle):
    """Adds walls (VtkData) to a 3D axes as translucent polygons and their outline (wall_edges),
    split by the plane through `middle` across the view direction `forward`: what is behind it
    under the spheres (zorder 1), what is in front of it over them (zorder 3)."""
    polygons = [walls.points[p] for p in walls.polygons]
    edges = wall_edges(walls)
    for zorder, behind in ((1, True), (3, False)):
        faces = [p for p in polygons if ((p.mean(axis=0) - middle) @ forward > 0.0) == behind]
        lines = [s for s in edges if ((s.mean(axis=0) - middle) @ forward > 0.0) == behind]
        if faces:
            ax.add_collection3d(Poly3DCollection(faces, facecolors=[(*WALL_FACE, 0.15)],
                                                 edgecolors="none", zorder=zorder))
        if lines:
            ax.add_collection3d(Line3DCollection(lines, colors=[(*WALL_EDGE, 0.7)],
                                                 linewidths=0.8, zorder=zorder))


def render_matplotlib(ax, centres, radii, colours, view, dpi, walls):
    """mplot3d scatter (orthographic), marker diameters scaled to the sphere diameters, with the
    walls (VtkData, or None) drawn by draw_walls_matplotlib."""
    lo, hi = scene_box(centres, radii, walls)
    mid, half = 0.5 * (lo + hi), 0.5 * float((hi - lo).max()) * 1.02
    ax.set_proj_type("ortho")
    ax.view_init(elev=view[1], azim=view[0])
    ax.set_xlim(mid[0] - half, mid[0] + half)
    ax.set_ylim(mid[1] - half, mid[1] + half)
    ax.set_zlim(mid[2] - half, mid[2] + half)
    ax.set_box_aspect((1, 1, 1))
    ax.computed_zorder = False  # drawn in the order of their zorder: far walls, spheres, near ones
    # far spheres first, so that near ones cover them
    right, _, forward = camera_basis(*view)
    order = numpy.argsort(-(centres @ forward))
    coll = ax.scatter(centres[order, 0], centres[order, 1], centres[order, 2], c=colours[order],
                      s=1.0, depthshade=False, edgecolors=(0, 0, 0, 0.35), linewidths=0.3,
                      zorder=2)
    if walls is not None:
        draw_walls_matplotlib(ax, walls, forward, mid)
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.set_zlabel("z [m]")
    for axis in (ax.xaxis, ax.yaxis, ax.zaxis):
        axis.label.set_fontsize("small")
    ax.tick_params(labelsize="x-small")
    # points per metre on the screen, from the projection of a segment along the screen's right
    ax.figure.canvas.draw()
    ends = [proj3d.proj_transform(*(mid + t * right), ax.get_proj()) for t in (0.0, half)]
    pixels = ax.transData.transform([e[:2] for e in ends])
    per_metre = numpy.hypot(*(pixels[1] - pixels[0])) / half * 72.0 / dpi
    coll.set_sizes((2.0 * radii[order] * per_metre) ** 2)
    return coll


def draw_spheres(path, out=None, field=None, value_range=None, view="iso", size="800x600",
                 renderer="auto", cmap="plasma", floor=True, with_walls=True):
    """The picture of `spheres` (the options as on the command line), saved as `out` if given.
    Returns the figure, the renderer that drew it ("povray" or "matplotlib") and the number of
    spheres."""
    width, height = parse_size(size)
    view = parse_view(view)
    data = read_polydata(path, "spheres needs")
    centres = data.points
    if len(centres) == 0:
        fail(f"{path} has no particles")
    if "radius" not in data.fields:
        fail(f"{path} has no radius field; fields: {', '.join(sorted(data.fields))}")
    radii = data.fields["radius"][:, 0]
    label, values = field_values(data.fields, field)
    if value_range and not value_range[1] > value_range[0]:
        fail(f"--range {value_range[0]:g} {value_range[1]:g}: LO must be below HI")
    if cmap not in matplotlib.colormaps:
        fail(f"--cmap '{cmap}': not a matplotlib colormap (e.g. plasma, viridis, coolwarm)")
    lo, hi = value_range if value_range else (float(values.min()), float(values.max()))
    if not hi > lo:  # one value: the middle of the scale
        delta = 0.05 * abs(lo) if lo != 0.0 else 1.0
        lo, hi = lo - delta, hi + delta
    norm = matplotlib.colors.Normalize(lo, hi, clip=True)
    cmap = matplotlib.colormaps[cmap]
    walls = read_walls(path) if with_walls else None

    povray = shutil.which("povray")
    if renderer in ("auto", "povray") and not povray:
        if renderer == "povray":
            fail("povray not found (Debian package povray)")
        renderer = "matplotlib"
    dpi = 100.0
    font = min(max(height / 60.0, 6.0), 11.0)
    bar_width = min(max(int(round(width * 0.15)), int(round(8.5 * font)) + 30), int(0.4 * width))
    scene_width = width - bar_width
    image = None
    if renderer != "matplotlib":
        steps = 256
        lut = cmap(numpy.linspace(0.0, 1.0, steps))
        index = numpy.clip((norm(values).filled(0.0) * steps).astype(int), 0, steps - 1)
        image, error = render_povray(povray, centres, radii, index, lut, view, scene_width, height,
                                     floor, walls)
        if image is None:
            if renderer == "povray":
                fail(f"povray failed ({error})")
            print(f"{PROGRAM}: povray failed ({error}); drawing with matplotlib", file=sys.stderr)
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
            render_matplotlib(ax, centres, radii, cmap(norm(values)), view, dpi, walls)
        fig.text(0.01, 0.99, title(os.path.basename(path), time_text(data.time)), ha="left",
                 va="top", fontsize="small", color="0.25")
        cax = fig.add_axes((frac + 12.0 / width, 0.1, 12.0 / width, 0.8))
        fig.colorbar(matplotlib.cm.ScalarMappable(norm=norm, cmap=cmap), cax=cax, label=label)
        if out:
            fig.savefig(out, dpi=dpi)
    return fig, renderer, len(centres)


def plot_spheres(args):
    out = args.output or os.path.splitext(args.file)[0] + ".png"
    started = time.monotonic()
    _, renderer, count = draw_spheres(args.file, out, args.field, args.range, args.view, args.size,
                                      args.renderer, args.cmap, not args.no_floor,
                                      not args.no_walls)
    print(out)
    print(f"spheres: {count} spheres drawn by {renderer} in {time.monotonic() - started:.2f} s")


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
    a.add_argument("--range", nargs=2, type=float, metavar=("LO", "HI"),
                   help="colour scale (default: the range of all frames)")
    a.add_argument("--title", help="title of the frames (the time is added)")
    a.add_argument("--window", nargs=4, type=float, metavar=("XMIN", "XMAX", "YMIN", "YMAX"),
                   help="the view [m] (default: fitted to the disks and walls)")
    a.add_argument("--ids", action="store_true", help="label the disks with their ids")
    a.add_argument("--markers", action="store_true",
                   help="draw each disk's orientation (a radius at its angle)")
    a.add_argument("--arrows", metavar="FIELD",
                   help="arrows of a vector field at the centres (velocity, force)")
    a.add_argument("--wall-field", metavar="FIELD",
                   help="colour the walls by a field of the walls' files (temperature)")
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
    s.add_argument("--no-walls", action="store_true", help="leave out the walls of the frame")
    args = parser.parse_args()
    {"history": plot_history, "lines": plot_lines, "disks": plot_disks, "animate": plot_animation,
     "spheres": plot_spheres}[args.command](args)
    return 0


if __name__ == "__main__":
    sys.exit(main())
