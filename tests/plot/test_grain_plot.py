#!/usr/bin/env python3
"""Tests of scripts/grain_plot.py on small files written here in grain's formats (the legacy VTK
files of include/grain/io/vtk.hpp, ASCII and binary, and a CSV history of io/csv.hpp): colour
bars with units, titles with the time, an animation, walls in 3D pictures (matplotlib and
POV-Ray), and the one-line message of a missing Python module.

python3 tests/plot/test_grain_plot.py [-v]
Exit status 0 if every test passed, 1 if one failed, 77 (skipped) if matplotlib or numpy is
missing (then only the messages of missing modules are checked). The tests of 3D pictures need
VTK's Python module (python3-vtk9), those of POV-Ray pictures povray; without them they are
skipped.
"""

import importlib.util
import os
import shutil
import struct
import subprocess
import sys
import tempfile
import unittest

SCRIPT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scripts",
                      "grain_plot.py")
HAVE_NUMPY = importlib.util.find_spec("numpy") is not None
HAVE_PLOTTING = HAVE_NUMPY and importlib.util.find_spec("matplotlib") is not None
HAVE_VTK = importlib.util.find_spec("vtkmodules") is not None
HAVE_POVRAY = shutil.which("povray") is not None
if HAVE_PLOTTING:
    sys.dont_write_bytecode = True  # no __pycache__ in the source tree
    sys.path.insert(0, os.path.dirname(SCRIPT))
    import grain_plot  # noqa: E402
    import numpy  # noqa: E402
    from matplotlib.collections import LineCollection  # noqa: E402
    from mpl_toolkits.mplot3d.art3d import Line3DCollection, Poly3DCollection  # noqa: E402


# ------------------------------------------------------------------ files in grain's formats
class LegacyVtk:
    """A legacy VTK polydata file as include/grain/io/vtk.hpp (detail::LegacyVtkFile) writes it:
    keyword lines in text; numbers as text, one tuple a line, 17 significant digits, or as
    big-endian binary blocks, each ended by a newline."""

    def __init__(self, kind, time, binary=False):
        self.binary = binary
        self.data = (f"# vtk DataFile Version 3.0\ngrain {kind} t = {time:.17g}\n"
                     f"{'BINARY' if binary else 'ASCII'}\nDATASET POLYDATA\n").encode()

    def line(self, text):
        self.data += (text + "\n").encode()

    def block(self, rows, code):
        """Tuples of numbers, each packed with the struct code (d, i or q) in binary."""
        if self.binary:
            self.data += b"".join(struct.pack(">" + code * len(r), *r) for r in rows) + b"\n"
        else:
            self.data += "".join(" ".join(f"{v:.17g}" if code == "d" else str(v) for v in r)
                                 + "\n" for r in rows).encode()

    def points(self, points):
        self.line(f"POINTS {len(points)} double")
        self.block(points, "d")

    def cells(self, keyword, cells):
        self.line(f"{keyword} {len(cells)} {sum(len(c) + 1 for c in cells)}")
        self.block([(len(c), *c) for c in cells], "i")

    def field(self, name, values, kind="double"):
        """kind: double, long, int (SCALARS 1), vector (VECTORS) or double4 (SCALARS 4)."""
        if kind == "vector":
            self.line(f"VECTORS {name} double")
        else:
            vtk_type = {"long": "vtktypeint64" if self.binary else "long", "int": "int"}.get(
                kind, "double")
            self.line(f"SCALARS {name} {vtk_type} {4 if kind == 'double4' else 1}\n"
                      "LOOKUP_TABLE default")
        rows = [v if isinstance(v, (tuple, list)) else (v,) for v in values]
        self.block(rows, {"long": "q", "int": "i"}.get(kind, "d"))

    def save(self, path):
        with open(path, "wb") as f:
            f.write(self.data)


def write_particles(path, time, centres, radii, dimension, binary=False, thermal=True):
    """A particle file of io::vtk with every field (write_particles_vtk, fields::all)."""
    n = len(centres)
    f = LegacyVtk("particles", time, binary)
    f.points(centres)
    f.cells("VERTICES", [(k,) for k in range(n)])
    f.line(f"POINT_DATA {n}")
    f.field("id", range(n), "long")
    f.field("radius", radii)
    f.field("velocity", [(0.1 * k, -0.2, 0.3 * k if dimension == 3 else 0.0) for k in range(n)],
            "vector")
    f.field("omega", [(0.0, 0.0, 2.0 * k) for k in range(n)], "vector")
    f.field("force", [(0.0, -1e-3 * k, 0.0) for k in range(n)], "vector")
    f.field("torque", [(0.0, 0.0, 1e-6) for _ in range(n)], "vector")
    f.field("mass", [1e-3] * n)
    if dimension == 3:
        f.field("orientation", [(1.0, 0.0, 0.0, 0.0)] * n, "double4")
    else:
        f.field("orientation", [0.1 * k for k in range(n)])
    f.field("material", [0] * n, "int")
    if thermal:
        f.field("temperature", [300.0 + 10.0 * k for k in range(n)])
        f.field("heat_rate", [0.5] * n)
        f.field("heat_capacity", [0.4] * n)
    f.save(path)


def write_walls(path, time, points, cells, dimension, binary=False):
    """A wall file of io::vtk (write_walls_vtk): LINES in 2D, POLYGONS in 3D, cell data `wall`,
    `conducts` and `temperature` (a thermal simulation)."""
    f = LegacyVtk("walls", time, binary)
    f.points(points)
    f.cells("LINES" if dimension == 2 else "POLYGONS", cells)
    f.line(f"CELL_DATA {len(cells)}")
    f.field("wall", range(len(cells)), "int")
    f.field("conducts", [1] * len(cells), "int")
    f.field("temperature", [350.0] * len(cells))
    f.save(path)


# a plane (z = 0, normal +z, drawn as a square of side 0.02) and a triangle above it, as
# write_walls_vtk writes them: four corners, then three
WALLS_3D = ([(0.02, 0.0, 0.0), (0.0, 0.02, 0.0), (-0.02, 0.0, 0.0), (0.0, -0.02, 0.0),
             (0.0, 0.0, 0.004), (0.01, 0.0, 0.004), (0.0, 0.01, 0.012)],
            [(0, 1, 2, 3), (4, 5, 6)])
SPHERES = ([(0.0, 0.0, 0.002), (0.004, 0.0, 0.002), (0.0, 0.004, 0.002), (0.002, 0.002, 0.0055)],
           [0.002, 0.002, 0.002, 0.0015])
DISKS = ([(0.0, 0.001, 0.0), (0.002, 0.001, 0.0), (0.004, 0.001, 0.0)], [0.001, 0.001, 0.001])
WALLS_2D = ([(-0.001, 0.0, 0.0), (0.005, 0.0, 0.0), (-0.001, 0.0, 0.0), (-0.001, 0.004, 0.0)],
            [(0, 1), (2, 3)])
HISTORY = ("time [s],step,kinetic_energy [J],mean_temperature [K]\n"
           "0,0,1e-06,300\n0.050000000000000003,50,5.0000000000000004e-07,305\n"
           "0.10000000000000001,100,nan,309\n")


def run_script(*args, env=None):
    return subprocess.run([sys.executable, SCRIPT, *args], capture_output=True, text=True,
                          env=env, timeout=300)


class Files(unittest.TestCase):
    """Writes the files once in a scratch directory."""

    @classmethod
    def setUpClass(cls):
        cls.scratch = tempfile.TemporaryDirectory(prefix="test_grain_plot_")
        cls.dir = cls.scratch.name
        d = cls.dir
        write_particles(os.path.join(d, "bed_particles_000000.vtk"), 0.125, *DISKS, 2)
        write_walls(os.path.join(d, "bed_walls_000000.vtk"), 0.125, *WALLS_2D, 2)
        write_particles(os.path.join(d, "cold_particles_000000.vtk"), 0.5, *DISKS, 2,
                        thermal=False)
        write_particles(os.path.join(d, "pour_particles_000003.vtk"), 0.125, *SPHERES, 3)
        write_walls(os.path.join(d, "pour_walls_000003.vtk"), 0.125, *WALLS_3D, 3)
        write_particles(os.path.join(d, "binpour_particles_000000.vtk"), 2.5, *SPHERES, 3, True)
        write_walls(os.path.join(d, "binpour_walls_000000.vtk"), 2.5, *WALLS_3D, 3, True)
        for k in range(3):  # a series at t = 0, 0.05, 0.1, the disks moving right
            moved = [(x + 0.001 * k, y, z) for x, y, z in DISKS[0]]
            for binary in (False, True):
                write_particles(os.path.join(d, f"{'bin' if binary else 'run'}_particles_"
                                                f"{k:06d}.vtk"), k * 0.05, moved, DISKS[1], 2,
                                binary)
        with open(os.path.join(d, "history.csv"), "w", encoding="utf-8") as f:
            f.write(HISTORY)

    @classmethod
    def tearDownClass(cls):
        cls.scratch.cleanup()

    def path(self, name):
        return os.path.join(self.dir, name)


# ------------------------------------------------------------------ tests
@unittest.skipUnless(HAVE_PLOTTING, "needs numpy and matplotlib")
class Labels(Files):
    def test_units_of_the_fields(self):
        fields = grain_plot.read_vtk(self.path("bed_particles_000000.vtk")).fields
        expected = {None: "temperature [K]", "temperature": "temperature [K]",
                    "velocity": "speed [m/s]", "velocity:x": "velocity:x [m/s]",
                    "omega": "|omega| [rad/s]", "omega:z": "omega:z [rad/s]",
                    "force": "|force| [N]", "torque": "|torque| [N m]", "radius": "radius [m]",
                    "mass": "mass [kg]", "orientation": "orientation [rad]",
                    "heat_rate": "heat_rate [W]", "heat_capacity": "heat_capacity [J/K]",
                    "id": "id", "material": "material"}
        for name, label in expected.items():
            self.assertEqual(grain_plot.field_values(fields, name)[0], label, name)
        # the 3D orientation, a unit quaternion (SCALARS orientation double 4), has no unit
        spheres = grain_plot.read_vtk(self.path("pour_particles_000003.vtk")).fields
        self.assertEqual(grain_plot.field_values(spheres, "orientation")[0], "|orientation|")
        self.assertEqual(grain_plot.field_values(spheres, "orientation:0")[0], "orientation:0")
        cold = grain_plot.read_vtk(self.path("cold_particles_000000.vtk")).fields
        self.assertEqual(grain_plot.field_values(cold, None)[0], "speed [m/s]")
        # a field grain does not write has no unit rather than a wrong one
        self.assertEqual(grain_plot.field_values({"porosity": [0.4]}, "porosity")[0], "porosity")

    def test_values(self):
        fields = grain_plot.read_vtk(self.path("bed_particles_000000.vtk")).fields
        _, speed = grain_plot.field_values(fields, "velocity")
        numpy.testing.assert_allclose(speed, numpy.hypot([0.0, 0.1, 0.2], 0.2))
        _, vx = grain_plot.field_values(fields, "velocity:x")
        numpy.testing.assert_allclose(vx, [0.0, 0.1, 0.2])

    def test_time_texts(self):
        self.assertEqual(grain_plot.time_text(0.125), "t = 0.125 s")
        self.assertEqual(grain_plot.time_text(0.10000000000000001), "t = 0.1 s")
        self.assertEqual(grain_plot.time_text(None), "")
        self.assertEqual(grain_plot.time_texts([0.0, 0.05, 0.10000000000000001, 0.15]),
                         ["t = 0.00 s", "t = 0.05 s", "t = 0.10 s", "t = 0.15 s"])
        self.assertEqual(grain_plot.time_texts([1.0, 2.0]), ["t = 1 s", "t = 2 s"])
        self.assertEqual(grain_plot.time_texts([0.0102, 0.0201]), ["t = 0.01 s", "t = 0.02 s"])


@unittest.skipUnless(HAVE_PLOTTING, "needs numpy and matplotlib")
class Disks(Files):
    def test_colour_bar_title_and_walls(self):
        fig = grain_plot.disks_figure(self.path("bed_particles_000000.vtk"))
        ax, bar = fig.axes
        self.assertEqual(bar.get_ylabel(), "temperature [K]")
        self.assertEqual(ax.get_title(), "bed_particles_000000.vtk\nt = 0.125 s")
        walls = [c for c in ax.collections if isinstance(c, LineCollection)]
        self.assertEqual(len(walls), 1)
        self.assertEqual(len(walls[0].get_segments()), 2)

    def test_binary_file(self):
        fig = grain_plot.disks_figure(self.path("bin_particles_000002.vtk"), "velocity:y")
        self.assertEqual(fig.axes[1].get_ylabel(), "velocity:y [m/s]")
        self.assertEqual(fig.axes[0].get_title(), "bin_particles_000002.vtk\nt = 0.1 s")

    def test_picture_written(self):
        out = self.path("bed.png")
        run = run_script("disks", self.path("bed_particles_000000.vtk"), "-f", "omega", "-o", out)
        self.assertEqual(run.returncode, 0, run.stderr)
        with open(out, "rb") as f:
            self.assertEqual(f.read(4), b"\x89PNG")


@unittest.skipUnless(HAVE_PLOTTING, "needs numpy and matplotlib")
class Animate(Files):
    def test_each_frame_shows_its_time(self):
        fig, draw, frames = grain_plot.disks_animation(self.path("run"), "velocity")
        self.assertEqual(frames, 3)
        self.assertEqual(fig.axes[1].get_ylabel(), "speed [m/s]")
        for k, expected in enumerate(("t = 0.00 s", "t = 0.05 s", "t = 0.10 s")):
            draw(k)
            self.assertEqual(fig.axes[0].get_title(), "run\n" + expected)

    def test_gif_written(self):
        out = self.path("run.gif")
        run = run_script("animate", self.path("run"), "-f", "temperature", "-o", out)
        self.assertEqual(run.returncode, 0, run.stderr)
        with open(out, "rb") as f:
            self.assertEqual(f.read(6), b"GIF89a")
        from PIL import Image

        with Image.open(out) as gif:
            self.assertEqual(gif.n_frames, 3)


@unittest.skipUnless(HAVE_PLOTTING, "needs numpy and matplotlib")
class History(Files):
    def test_graph_written(self):
        out = self.path("history.png")
        run = run_script("history", self.path("history.csv"), "-y", "mean_temperature", "-o",
                         out)
        self.assertEqual(run.returncode, 0, run.stderr)
        with open(out, "rb") as f:
            self.assertEqual(f.read(4), b"\x89PNG")


@unittest.skipUnless(HAVE_PLOTTING, "needs numpy and matplotlib")
class WallEdges(unittest.TestCase):
    def walls(self, points, polygons):
        return grain_plot.VtkData(numpy.array(points, dtype=float), [], [list(p) for p in polygons],
                                  {}, None)

    def test_separate_polygons_are_outlined_whole(self):
        self.assertEqual(len(grain_plot.wall_edges(self.walls(*WALLS_3D))), 7)

    def test_no_edge_inside_a_flat_mesh(self):
        # a square of two triangles, each with its own corners (as write_walls_vtk writes them)
        square = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 0, 0), (1, 1, 0), (0, 1, 0)]
        self.assertEqual(len(grain_plot.wall_edges(self.walls(square, [(0, 1, 2), (3, 4, 5)]))),
                         4)

    def test_fold_outlined_once(self):
        # a floor and a side meeting at a right angle: 4 + 4 edges, the common one drawn once
        corners = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0, 0, 0), (0, 1, 0), (0, 1, 1),
                   (0, 0, 1)]
        edges = grain_plot.wall_edges(self.walls(corners, [(0, 1, 2, 3), (4, 5, 6, 7)]))
        self.assertEqual(len(edges), 7)


@unittest.skipUnless(HAVE_PLOTTING and HAVE_VTK, "needs numpy, matplotlib and vtk")
class Spheres(Files):
    def picture(self, name="pour_particles_000003.vtk", **options):
        fig, renderer, count = grain_plot.draw_spheres(self.path(name), size="320x240",
                                                       **options)
        self.addCleanup(grain_plot.plt.close, fig)
        return fig, renderer, count

    def test_matplotlib_draws_the_walls(self):
        fig, renderer, count = self.picture(renderer="matplotlib", field="velocity:z")
        self.assertEqual((renderer, count), ("matplotlib", 4))
        ax, bar = fig.axes
        self.assertEqual(bar.get_ylabel(), "velocity:z [m/s]")
        self.assertEqual(fig.texts[0].get_text(), "pour_particles_000003.vtk\nt = 0.125 s")
        fig.canvas.draw()
        faces = [c for c in ax.collections if isinstance(c, Poly3DCollection)]
        self.assertEqual(sum(len(c.get_paths()) for c in faces), 2)  # the plane and the triangle
        self.assertTrue(all(c.get_facecolor()[0][3] < 0.5 for c in faces))  # translucent
        edges = [c for c in ax.collections if isinstance(c, Line3DCollection)]
        self.assertEqual(sum(len(c.get_segments()) for c in edges), 7)

    def test_no_walls(self):
        fig, _, _ = self.picture(renderer="matplotlib", with_walls=False)
        ax = fig.axes[0]
        self.assertFalse([c for c in ax.collections
                          if isinstance(c, (Poly3DCollection, Line3DCollection))])

    def test_binary_files(self):
        fig, _, _ = self.picture("binpour_particles_000000.vtk", renderer="matplotlib",
                                 field="omega")
        self.assertEqual(fig.axes[1].get_ylabel(), "|omega| [rad/s]")
        self.assertEqual(fig.texts[0].get_text(), "binpour_particles_000000.vtk\nt = 2.5 s")
        fig.canvas.draw()
        faces = [c for c in fig.axes[0].collections if isinstance(c, Poly3DCollection)]
        self.assertEqual(sum(len(c.get_paths()) for c in faces), 2)

    def test_pov_ray_scene_of_the_walls(self):
        walls = grain_plot.read_walls(self.path("pour_particles_000003.vtk"))
        scene = grain_plot.pov_walls(walls, lambda p: p * 100.0, 4.0)
        mesh = [s for s in scene if s.startswith("mesh{")]
        self.assertEqual(len(mesh), 1)
        self.assertEqual(mesh[0].count("triangle{"), 3)  # the square in two, the triangle
        self.assertIn("no_shadow", mesh[0])
        self.assertEqual(sum(s.startswith("cylinder{") for s in scene), 7)

    @unittest.skipUnless(HAVE_POVRAY, "needs povray")
    def test_pov_ray_draws_the_walls(self):
        images = []
        for with_walls in (True, False):
            fig, renderer, _ = self.picture(renderer="povray", field="temperature",
                                            with_walls=with_walls)
            self.assertEqual(renderer, "povray")
            self.assertEqual(fig.axes[1].get_ylabel(), "temperature [K]")
            images.append(numpy.asarray(fig.axes[0].get_images()[0].get_array(), dtype=float))
        # the walls change a good part of the picture
        changed = (numpy.abs(images[0] - images[1]).max(axis=2) > 0.05).mean()
        self.assertGreater(changed, 0.05)

    def test_command_line(self):
        out = self.path("pour.png")
        run = run_script("spheres", self.path("pour_particles_000003.vtk"), "--renderer",
                         "matplotlib", "--size", "320x240", "-o", out)
        self.assertEqual(run.returncode, 0, run.stderr)
        self.assertIn("4 spheres drawn by matplotlib", run.stdout)
        with open(out, "rb") as f:
            self.assertEqual(f.read(4), b"\x89PNG")


class MissingModules(Files):
    """A module that cannot be imported (a module of that name on PYTHONPATH that raises
    ImportError) gives one line naming it and how to install it, and exit status 2."""

    def run_without(self, module, *args):
        blocked = tempfile.mkdtemp(dir=self.dir)
        package = os.path.join(blocked, module)
        os.mkdir(package)
        with open(os.path.join(package, "__init__.py"), "w", encoding="utf-8") as f:
            f.write(f"raise ImportError('{module} blocked by the test')\n")
        env = dict(os.environ, PYTHONPATH=blocked)
        return run_script(*args, env=env)

    def check(self, run, message):
        self.assertEqual(run.returncode, 2, run.stderr)
        self.assertEqual(run.stderr, message + "\n")

    @unittest.skipUnless(HAVE_NUMPY, "needs numpy (checked first)")
    def test_matplotlib(self):
        self.check(self.run_without("matplotlib", "disks", self.path("bed_particles_000000.vtk")),
                   "grain_plot.py: needs matplotlib (Debian: apt-get install python3-matplotlib; "
                   "pip: pip install matplotlib)")

    def test_numpy(self):
        self.check(self.run_without("numpy", "history", self.path("history.csv")),
                   "grain_plot.py: needs numpy (Debian: apt-get install python3-numpy; "
                   "pip: pip install numpy)")

    @unittest.skipUnless(HAVE_PLOTTING, "needs numpy and matplotlib")
    def test_vtk_for_spheres(self):
        out = self.path("blocked.png")
        self.check(self.run_without("vtkmodules", "spheres",
                                    self.path("pour_particles_000003.vtk"), "-o", out),
                   "grain_plot.py: spheres needs vtk (Debian: apt-get install python3-vtk9; "
                   "pip: pip install vtk)")
        self.assertFalse(os.path.exists(out))


if __name__ == "__main__":
    passed = unittest.main(exit=False).result.wasSuccessful()
    sys.exit(1 if not passed else 0 if HAVE_PLOTTING else 77)
