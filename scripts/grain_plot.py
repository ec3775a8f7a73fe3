#!/usr/bin/env python3
"""Graphs and pictures from grain's output files (matplotlib, Debian package python3-matplotlib).

Usage:
  grain_plot.py history FILE.csv [-y COLUMN ...] [-x COLUMN] [-o OUT.png]
      Graphs of the columns of a CSV time history (io::history, io::csv) against time, one panel
      per column (default: every column but time and step), or against column -x.
      Column names may be given without their unit: "mean_temperature" = "mean_temperature [K]".
  grain_plot.py disks FILE_particles_NNNNNN.vtk [-f FIELD] [-o OUT.png] [--range LO HI]
      A 2D picture of the disks of a legacy VTK particle file (io::vtk), coloured by a point
      field (default temperature if present, else the speed), with the walls of the matching
      FILE_walls_NNNNNN.vtk if it exists.
  grain_plot.py animate PREFIX [-f FIELD] [-o OUT.gif] [--fps N]
      An animation (GIF) of the 2D series PREFIX_particles_*.vtk, with one colour scale for all
      frames.

Exit status 0 on success, 2 on bad arguments or unreadable files.
"""

import argparse
import csv
import glob
import math
import os
import re
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
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


# ------------------------------------------------------------------ legacy VTK (as io::vtk writes it)
def read_vtk(path):
    """Points, point or cell fields and line/polygon cells of an ASCII legacy polydata file."""
    try:
        with open(path, encoding="utf-8") as f:
            tokens = f.read().split("\n")
    except OSError as e:
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


def main():
    parser = argparse.ArgumentParser(description="Graphs and pictures from grain's output files.")
    sub = parser.add_subparsers(dest="command", required=True)
    h = sub.add_parser("history", help="graphs of a CSV time history")
    h.add_argument("file")
    h.add_argument("-y", action="append", help="column to plot (repeatable)")
    h.add_argument("-x", help="column for the horizontal axis (default: time)")
    h.add_argument("-o", "--output")
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
    args = parser.parse_args()
    {"history": plot_history, "disks": plot_disks, "animate": plot_animation}[args.command](args)
    return 0


if __name__ == "__main__":
    sys.exit(main())
