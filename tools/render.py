#!/usr/bin/env python3
"""Pictures of a run: a vertical section through the pile axis (the plane y = 0:
the pile of a dem_server scenario stands on the z axis), spheres coloured by
their displacement since the first snapshot or by their mean stress, the bonds
broken since the first snapshot in red, and the walls, the pile and the
coupling surface where the plane cuts them.

    render.py RUN_DIR [--out DIR] [--snapshot N] [--colour displacement|stress]
              [--renderer auto|matplotlib|pvbatch] [--dpi DPI]

RUN_DIR is the run's folder (results.h5 and results.xdmf inside) or its
results.h5. Without --snapshot it writes one PNG per DEM snapshot,
DIR/frame_<nnnnnn>.png, and DIR/run.gif (matplotlib's PillowWriter, when
python3-pil is installed; otherwise the frames only, and it says so); with
--snapshot N (negative counts from the end) one picture,
DIR/snapshot_<nnnnnn>.png. DIR defaults to RUN_DIR/pictures. Prints every
file written and which renderer drew it.

Renderers: pvbatch (ParaView's Python; the same section drawn from
results.xdmf) where it is on PATH, else matplotlib, which reads results.h5
through python/dfc_results. --help says which one `auto` picks on this
machine. docs/looking_at_a_run.md shows the pictures and says what each
array means.

Needs numpy, matplotlib and h5py (Debian: python3-numpy python3-matplotlib python3-h5py).
"""
import argparse
import os
import shutil
import subprocess
import sys
import tempfile

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir, "python"))

BROKEN = (3, 4)  # bond_state: broken in tension, in shear (dem_server bond_state.hpp)
PVBATCH = shutil.which("pvbatch")


def has_pillow():
    try:
        import PIL  # noqa: F401
    except ImportError:
        return False
    return True


def virtual_display_missing():
    """Why pvbatch cannot get an X display here, or None. Debian's ParaView
    renders through X (no offscreen OpenGL): without $DISPLAY it runs in
    xvfb-run, which needs xauth (only a Recommends of Debian's xvfb, so a
    --no-install-recommends install lacks it and xvfb-run fails)."""
    if os.environ.get("DISPLAY"):
        return None
    missing = [tool for tool in ("xvfb-run", "xauth") if shutil.which(tool) is None]
    return f"no X display and {' and '.join(missing)} not installed (apt-get install xvfb xauth)" if missing else None


def in_virtual_display(command, attempt=0):
    """`command` run in a virtual X display (xvfb-run) where there is no $DISPLAY.
    xvfb-run -a alone looks for a free display from :99 up, and two started at
    once (parallel tests) both take :99; starting the search at a number of
    this process's own (and of the attempt) keeps them apart."""
    if os.environ.get("DISPLAY"):
        return list(command)
    return ["xvfb-run", "-n", str(100 + (os.getpid() + 7919 * attempt) % 20000), "-a"] + list(command)


def run_pvbatch(command, attempts=3):
    """subprocess.run of a pvbatch command in a virtual display where needed,
    its messages passed on. Debian's pvbatch in a fresh Xvfb aborts now and
    then with "bad X server connection" although the server is up (seen in
    about one start in three on a loaded 2-core machine, never with the same
    script once it had started): such a start is tried again, in another
    display, up to `attempts` times in all."""
    for attempt in range(attempts):
        drawn = subprocess.run(in_virtual_display(command, attempt), stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        sys.stdout.write(drawn.stdout)
        sys.stderr.write(drawn.stderr)
        if drawn.returncode == 0 or "bad X server connection" not in drawn.stderr or attempt + 1 == attempts:
            return drawn
        print(f"render.py: pvbatch could not connect to its virtual display; trying again ({attempt + 2} of {attempts})", file=sys.stderr)
    return drawn


def auto_renderer():
    """pvbatch where it is installed and can draw (an X display, or xvfb-run for a virtual one), else matplotlib."""
    return "pvbatch" if PVBATCH and virtual_display_missing() is None else "matplotlib"


def run_folder(path):
    return os.path.dirname(os.path.abspath(path)) if os.path.isfile(path) else os.path.abspath(path)


# Section geometry -------------------------------------------------------------

def cut_spheres(position, radius, plane_y):
    """Rows of the spheres the plane cuts, and the radius of each cut circle."""
    dy = position[:, 1] - plane_y
    rows = np.abs(dy) < radius
    return np.flatnonzero(rows), np.sqrt(radius[rows] ** 2 - dy[rows] ** 2)


def cut_triangles(vertices, facets, plane_y):
    """The segments ((x0, z0), (x1, z1)) where the plane cuts each triangle."""
    segments = []
    d = vertices[:, 1] - plane_y
    for tri in facets:
        points = []
        for a, b in ((tri[0], tri[1]), (tri[1], tri[2]), (tri[2], tri[0])):
            if (d[a] < 0) != (d[b] < 0):
                t = d[a] / (d[a] - d[b])
                p = vertices[a] + t * (vertices[b] - vertices[a])
                points.append((p[0], p[2]))
        if len(points) == 2:
            segments.append((points[0], points[1]))
    return np.array(segments).reshape(-1, 2, 2)


def mean_stress_kpa(stress):
    """kPa, compression positive: particle_stress_pa holds xx, xy, xz, yy, yz, zz, compression positive."""
    return (stress[:, 0] + stress[:, 3] + stress[:, 5]) / 3.0 / 1e3


class Section:
    """What the section shows of one run's snapshots, whichever renderer draws
    it: the colour of each sphere on one scale over the run, and the bonds
    broken since the first snapshot near the plane."""

    def __init__(self, snapshots, colour):
        self.snapshots = snapshots
        self.colour = colour
        self.first = snapshots[0]
        self.first_position = {int(i): p for i, p in zip(self.first.arrays["particle_id"], self.first.arrays["particle_position"])}
        self.bonds_at_start = self.broken_pairs(self.first)  # broken before the first snapshot: not drawn red
        values = [self.field(s) for s in snapshots]
        finite = np.concatenate([v[np.isfinite(v)] for v in values]) if values else np.zeros(1)
        self.limits = (float(np.min(finite)) if len(finite) else 0.0, float(np.max(finite)) if len(finite) else 1.0)
        if self.limits[1] <= self.limits[0]:
            self.limits = (self.limits[0], self.limits[0] + 1.0)
        everything = np.concatenate([s.arrays["particle_position"] for s in snapshots])
        reach = float(np.max(self.first.arrays["particle_radius"]))
        self.box = (everything[:, 0].min() - reach, everything[:, 0].max() + reach, everything[:, 2].min() - reach, everything[:, 2].max() + reach)
        self.label = "mean stress (kPa, compression positive)" if colour == "stress" else "displacement since the first snapshot (mm)"

    def field(self, snap):
        if self.colour == "stress":
            return mean_stress_kpa(snap.arrays["particle_stress_pa"])
        start = np.array([self.first_position.get(int(i), p) for i, p in zip(snap.arrays["particle_id"], snap.arrays["particle_position"])])
        return 1e3 * np.linalg.norm(snap.arrays["particle_position"] - start, axis=1)  # mm

    def broken_pairs(self, snap):
        if "bond_particle_id" not in snap.arrays:
            return set()
        state = snap.arrays["bond_state"]
        return {(int(a), int(b)) for (a, b), s in zip(snap.arrays["bond_particle_id"], state) if s in BROKEN}

    def broken_bonds(self, snap):
        """The bonds near the plane broken since the first snapshot: an array of (centre a, centre b)."""
        segments = []
        if "bond_particle_id" in snap.arrays:
            position, radius = snap.arrays["particle_position"], snap.arrays["particle_radius"]
            row_of_id = {int(i): r for r, i in enumerate(snap.arrays["particle_id"])}
            reach = float(np.max(radius))
            for (a, b), s in zip(snap.arrays["bond_particle_id"], snap.arrays["bond_state"]):
                if s not in BROKEN or (int(a), int(b)) in self.bonds_at_start:
                    continue
                pa, pb = position[row_of_id[int(a)]], position[row_of_id[int(b)]]
                if abs(0.5 * (pa[1] + pb[1])) < reach:  # bonds near the plane
                    segments.append((pa, pb))
        return np.array(segments, dtype=float).reshape(-1, 2, 3)

    def title(self, snap, broken):
        return f"section y = 0, t = {snap.time:.4g} s (step {snap.step}); {broken} bonds broken since the start shown"


# matplotlib -------------------------------------------------------------------

class SectionFigure:
    """Draws snapshots of one run on the same axes, limits and colour scale."""

    def __init__(self, section, dpi):
        self.section = section
        self.dpi = dpi

    def draw(self, snap, path):
        import matplotlib.pyplot as plt
        from matplotlib.collections import LineCollection, PatchCollection
        from matplotlib.patches import Circle

        section = self.section
        position, radius = snap.arrays["particle_position"], snap.arrays["particle_radius"]
        rows, cut = cut_spheres(position, radius, 0.0)
        values = section.field(snap)[rows]
        box = section.box
        width = box[1] - box[0]
        height = box[3] - box[2]
        fig, ax = plt.subplots(figsize=(7.0, max(3.0, 7.0 * height / width) + 0.6))
        circles = PatchCollection([Circle((position[r, 0], position[r, 2]), c) for r, c in zip(rows, cut)], cmap="viridis",
                                  edgecolors="none")
        circles.set_array(values)
        circles.set_clim(*section.limits)
        ax.add_collection(circles)
        fig.colorbar(circles, ax=ax, label=section.label, shrink=0.8)

        bonds = section.broken_bonds(snap)
        if len(bonds):
            ax.add_collection(LineCollection(bonds[:, :, [0, 2]], colors=(1.0, 0.0, 0.0), linewidths=2.0, label="bond broken since the start"))
        if "wall_facets" in snap.arrays:
            walls = cut_triangles(snap.arrays["wall_vertices"], snap.arrays["wall_facets"], 0.0)
            if len(walls):
                ax.add_collection(LineCollection(walls, colors="black", linewidths=2.0, label="walls, pile, coupling surface"))
        ax.set_xlim(box[0], box[1])
        ax.set_ylim(box[2], box[3])
        ax.set_aspect("equal")
        ax.set_xlabel("x (m)")
        ax.set_ylabel("z (m)")
        ax.set_title(section.title(snap, len(bonds)), fontsize=9)
        if ax.collections[1:]:
            ax.legend(loc="lower right", fontsize=8)
        fig.tight_layout()
        fig.savefig(path, dpi=self.dpi)
        plt.close(fig)


def load_section(run_dir, colour):
    import dfc_results

    with dfc_results.open_results(run_dir) as run:
        snapshots = run.snapshots("dem")
    if not snapshots:
        raise SystemExit(f"render: {run_dir} holds no DEM snapshots (run.snapshot_every)")
    return Section(snapshots, colour)


def picture_paths(section, snapshot, out):
    """(snapshot, PNG path) of each picture: every snapshot as frames, or the one asked for."""
    if snapshot is not None:
        snap = section.snapshots[snapshot]
        return [(snap, os.path.join(out, f"snapshot_{snap.index:06d}.png"))]
    return [(snap, os.path.join(out, f"frame_{snap.index:06d}.png")) for snap in section.snapshots]


def with_gif(paths, snapshot, out):
    if snapshot is not None:
        return paths
    if has_pillow():
        return paths + [write_gif(paths, os.path.join(out, "run.gif"))]
    print("render: python3-pil is not installed: frames only, no GIF (apt-get install python3-pil)")
    return paths


def render_matplotlib(run_dir, out, snapshot, colour, dpi):
    import matplotlib
    matplotlib.use("Agg")

    section = load_section(run_dir, colour)
    figure = SectionFigure(section, dpi)
    pictures = picture_paths(section, snapshot, out)
    for snap, path in pictures:
        figure.draw(snap, path)
    return with_gif([path for _, path in pictures], snapshot, out)


def write_gif(frames, path):
    import matplotlib.image
    import matplotlib.pyplot as plt
    from matplotlib.animation import PillowWriter

    first = matplotlib.image.imread(frames[0])
    fig = plt.figure(figsize=(first.shape[1] / 100, first.shape[0] / 100), dpi=100)
    ax = fig.add_axes([0, 0, 1, 1])
    ax.axis("off")
    writer = PillowWriter(fps=4)
    with writer.saving(fig, path, dpi=100):
        for frame in frames:
            ax.clear()
            ax.axis("off")
            ax.imshow(matplotlib.image.imread(frame))
            writer.grab_frame()
    plt.close(fig)
    return path


# pvbatch ----------------------------------------------------------------------

PVBATCH_SIZE = (1600, 1200)  # pixels of a pvbatch picture, width and height


def pvbatch_camera(box):
    """The pvbatch view of the section (x0, x1, z0, z1): the camera looks along
    +y (x to the right, z up) at the box's centre with a parallel projection;
    (centre x, centre z, half the picture's height in m)."""
    x0, x1, z0, z1 = box
    width, height = PVBATCH_SIZE
    return 0.5 * (x0 + x1), 0.5 * (z0 + z1), 0.55 * max(z1 - z0, (x1 - x0) * height / width)


def pvbatch_pixel(box, x, z):
    """Where a pvbatch picture of the section `box` draws the point (x, 0, z):
    (column, row from the top), in pixels."""
    centre_x, centre_z, scale = pvbatch_camera(box)
    width, height = PVBATCH_SIZE
    per_m = 0.5 * height / scale
    return 0.5 * width + (np.asarray(x) - centre_x) * per_m, 0.5 * height - (np.asarray(z) - centre_z) * per_m


PVBATCH_SCRIPT = r'''
# Drawn by pvbatch from results.xdmf: the spheres the plane y = 0 cuts, whole
# by their radius and cut open by the plane; the walls and the pile where the
# plane cuts them; the bonds broken since the first snapshot in red. The
# colours, the broken bonds and the titles come from render.py (job.json:
# the same Section as the matplotlib renderer draws).
import json
import sys
from paraview.simple import *

job = json.load(open(sys.argv[1]))
reader = XDMFReader(FileNames=[job["xdmf"]])
reader.UpdatePipelineInformation()
times = list(reader.TimestepValues) if reader.TimestepValues else [0.0]


def block(name):
    return MergeBlocks(Input=ExtractBlock(Input=reader, Selectors=["/Root/" + name]))


SPHERES = """
import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk
from vtkmodules.vtkCommonCore import vtkPoints
frame = np.load(%r)
x = np.asarray(inputs[0].Points)
r = np.asarray(inputs[0].PointData["particle_radius_m"])
ids = np.asarray(inputs[0].PointData["particle_id"]).astype(np.int64)
keep = np.abs(x[:, 1]) < r
row = np.clip(np.searchsorted(frame["ids"], ids[keep]), 0, len(frame["ids"]) - 1)
points = vtkPoints()
points.SetData(numpy_to_vtk(np.ascontiguousarray(x[keep]), deep=1))
output.VTKObject.SetPoints(points)
output.PointData.append(np.ascontiguousarray(r[keep]), "particle_radius_m")
output.PointData.append(np.ascontiguousarray(frame["values"][row]), "colour")
"""
BONDS = """
import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk
from vtkmodules.vtkCommonCore import vtkPoints
from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkLine
bonds = np.load(%r)["bonds"].reshape(-1, 3)
points = vtkPoints()
points.SetData(numpy_to_vtk(np.ascontiguousarray(bonds), deep=1))
lines = vtkCellArray()
for k in range(0, len(bonds), 2):
    line = vtkLine()
    line.GetPointIds().SetId(0, k)
    line.GetPointIds().SetId(1, k + 1)
    lines.InsertNextCell(line)
output.SetPoints(points)
output.SetLines(lines)
"""

view = CreateRenderView()
view.ViewSize = job["size"]
view.OrientationAxesVisibility = 0
view.Background = [1.0, 1.0, 1.0]
try:
    view.UseColorPaletteForBackground = 0
except AttributeError:
    pass
near = ProgrammableFilter(Input=block("dem_particles"))
near.OutputDataSetType = "vtkPolyData"
spheres = Glyph(Input=near, GlyphType="Sphere")
spheres.ScaleArray = ["POINTS", "particle_radius_m"]
spheres.ScaleFactor = 2.0  # the glyph's radius is 0.5
spheres.GlyphMode = "All Points"
spheres.GlyphType.ThetaResolution = 24
spheres.GlyphType.PhiResolution = 24
section = Clip(Input=spheres, ClipType="Plane")
section.ClipType.Origin = [0.0, 0.0, 0.0]
section.ClipType.Normal = [0.0, -1.0, 0.0]
shown = Show(section, view)
ColorBy(shown, ("POINTS", "colour"))
lut = GetColorTransferFunction("colour")
lut.ApplyPreset("Viridis (matplotlib)", True)
lut.RescaleTransferFunction(job["limits"][0], job["limits"][1])
lut.AutomaticRescaleRangeMode = "Never"
bar = GetScalarBar(lut, view)
bar.Title = job["label"]
bar.ComponentTitle = ""
bar.TitleColor = bar.LabelColor = [0.0, 0.0, 0.0]
shown.SetScalarBarVisibility(view, True)
walls = Slice(Input=block("dem_walls"))
walls.SliceType = "Plane"
walls.SliceType.Origin = [0.0, 0.0, 0.0]
walls.SliceType.Normal = [0.0, 1.0, 0.0]
shown_walls = Show(walls, view)
ColorBy(shown_walls, None)
shown_walls.AmbientColor = shown_walls.DiffuseColor = [0.0, 0.0, 0.0]
shown_walls.LineWidth = 3.0
broken = ProgrammableSource()
broken.OutputDataSetType = "vtkPolyData"
title = Text()
shown_title = Show(title, view)
shown_title.Color = [0.0, 0.0, 0.0]
shown_title.FontSize = 14
shown_title.WindowLocation = "Upper Center"

centre_x, centre_z, scale = job["camera"]
view.CameraParallelProjection = 1
view.CameraFocalPoint = [centre_x, 0.0, centre_z]
view.CameraPosition = [centre_x, -1.0, centre_z]
view.CameraViewUp = [0.0, 0.0, 1.0]
view.CameraParallelScale = scale
shown_broken = None
for frame in job["frames"]:
    near.Script = SPHERES % frame["npz"]
    broken.Script = BONDS % frame["npz"]
    if shown_broken is None:
        shown_broken = Show(broken, view)
        shown_broken.AmbientColor = shown_broken.DiffuseColor = [1.0, 0.0, 0.0]
        shown_broken.LineWidth = 3.0
    title.Text = frame["title"]
    view.ViewTime = times[frame["index"]]
    SaveScreenshot(frame["png"], view)
    near.UpdatePipeline(times[frame["index"]])
    print("pvbatch: %s: %d spheres cut by the plane" % (frame["png"], near.GetDataInformation().GetNumberOfPoints()), flush=True)
'''


def render_pvbatch(run_dir, out, snapshot, colour):
    import json

    section = load_section(run_dir, colour)
    pictures = picture_paths(section, snapshot, out)
    with tempfile.TemporaryDirectory() as work:
        frames = []
        for snap, path in pictures:
            order = np.argsort(snap.arrays["particle_id"])
            npz = os.path.join(work, f"frame_{snap.index:06d}.npz")
            bonds = section.broken_bonds(snap)
            np.savez(npz, ids=np.asarray(snap.arrays["particle_id"])[order].astype(np.int64), values=section.field(snap)[order], bonds=bonds)
            frames.append({"index": snap.index, "png": path, "npz": npz, "title": section.title(snap, len(bonds))})
        job = os.path.join(work, "job.json")
        with open(job, "w") as f:
            json.dump({"xdmf": os.path.join(run_dir, "results.xdmf"), "frames": frames, "limits": section.limits, "label": section.label,
                       "camera": [float(v) for v in pvbatch_camera(section.box)], "size": list(PVBATCH_SIZE)}, f)
        script = os.path.join(work, "section.py")
        with open(script, "w") as f:
            f.write(PVBATCH_SCRIPT)
        # Without a display pvbatch aborts creating its window, so it runs in a virtual one.
        command = [PVBATCH, script, job]
        if virtual_display_missing():
            raise SystemExit(f"render.py: pvbatch needs an X display: {virtual_display_missing()}; or use --renderer matplotlib")
        drawn = run_pvbatch(command)
        if drawn.returncode != 0:
            raise SystemExit(f"render.py: pvbatch failed (exit status {drawn.returncode}; its messages above): {' '.join(command)}")
    return with_gif([path for _, path in pictures], snapshot, out)


def main(argv=None):
    parser = argparse.ArgumentParser(
        description="Pictures of a run: a vertical section through the pile axis (y = 0), spheres coloured by displacement "
                    "or stress, bonds broken since the start in red, walls and pile drawn; PNG frames and a GIF, or one "
                    "snapshot.",
        epilog="--renderer auto uses " + auto_renderer() + " here: pvbatch (ParaView's Python) is "
               + ("on PATH" if PVBATCH else "not on PATH")
               + ("; GIFs are written (python3-pil found)." if has_pillow() else "; no GIF: python3-pil is not installed, frames only.")
               + " docs/looking_at_a_run.md says what is drawn.")
    parser.add_argument("run", help="the run's folder (results.h5, results.xdmf) or its results.h5")
    parser.add_argument("--out", help="folder for the pictures (default RUN_DIR/pictures)")
    parser.add_argument("--snapshot", type=int, help="only this DEM snapshot (0 = first, -1 = last)")
    parser.add_argument("--colour", choices=("displacement", "stress"), default="displacement",
                        help="sphere colour: displacement since the first snapshot (mm) or mean stress (kPa); default displacement")
    parser.add_argument("--renderer", choices=("auto", "matplotlib", "pvbatch"), default="auto",
                        help="default auto: pvbatch where installed (with an X display or xvfb-run), else matplotlib")
    parser.add_argument("--dpi", type=int, default=200,
                        help="resolution of the matplotlib PNGs (default 200, for print); pvbatch draws 1600 x 1200 pixels whatever it is")
    args = parser.parse_args(argv)

    run_dir = run_folder(args.run)
    out = args.out or os.path.join(run_dir, "pictures")
    os.makedirs(out, exist_ok=True)
    renderer = auto_renderer() if args.renderer == "auto" else args.renderer
    if renderer == "pvbatch":
        if not PVBATCH:
            raise SystemExit("render: --renderer pvbatch, but pvbatch (ParaView's Python) is not on PATH; use --renderer matplotlib")
        paths = render_pvbatch(run_dir, out, args.snapshot, args.colour)
    else:
        paths = render_matplotlib(run_dir, out, args.snapshot, args.colour, args.dpi)
    for path in paths:
        print(f"{path}  ({renderer})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
