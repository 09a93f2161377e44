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


def auto_renderer():
    # matplotlib even where pvbatch is installed: tried with Debian's ParaView
    # 5.11, the pvbatch slice keeps the continuum grid and walls but not the
    # spheres (docs/looking_at_a_run.md); pvbatch on request only.
    return "matplotlib"


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


# matplotlib -------------------------------------------------------------------

class SectionFigure:
    """Draws snapshots of one run on the same axes, limits and colour scale."""

    def __init__(self, snapshots, colour, dpi):
        self.snapshots = snapshots
        self.colour = colour
        self.dpi = dpi
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

    def draw(self, snap, path):
        import matplotlib.pyplot as plt
        from matplotlib.collections import LineCollection, PatchCollection
        from matplotlib.patches import Circle

        position, radius = snap.arrays["particle_position"], snap.arrays["particle_radius"]
        rows, cut = cut_spheres(position, radius, 0.0)
        values = self.field(snap)[rows]
        width = self.box[1] - self.box[0]
        height = self.box[3] - self.box[2]
        fig, ax = plt.subplots(figsize=(7.0, max(3.0, 7.0 * height / width) + 0.6))
        circles = PatchCollection([Circle((position[r, 0], position[r, 2]), c) for r, c in zip(rows, cut)], cmap="viridis",
                                  edgecolors="none")
        circles.set_array(values)
        circles.set_clim(*self.limits)
        ax.add_collection(circles)
        label = "mean stress (kPa, compression positive)" if self.colour == "stress" else "displacement since the first snapshot (mm)"
        fig.colorbar(circles, ax=ax, label=label, shrink=0.8)

        broken = 0
        if "bond_particle_id" in snap.arrays:
            state = snap.arrays["bond_state"]
            row_of_id = {int(i): r for r, i in enumerate(snap.arrays["particle_id"])}
            reach = float(np.max(radius))
            segments = []
            for (a, b), s in zip(snap.arrays["bond_particle_id"], state):
                if s not in BROKEN or (int(a), int(b)) in self.bonds_at_start:
                    continue
                pa, pb = position[row_of_id[int(a)]], position[row_of_id[int(b)]]
                if abs(0.5 * (pa[1] + pb[1])) < reach:  # bonds near the plane
                    segments.append(((pa[0], pa[2]), (pb[0], pb[2])))
            broken = len(segments)
            if segments:
                ax.add_collection(LineCollection(segments, colors=(1.0, 0.0, 0.0), linewidths=2.0, label="bond broken since the start"))
        if "wall_facets" in snap.arrays:
            walls = cut_triangles(snap.arrays["wall_vertices"], snap.arrays["wall_facets"], 0.0)
            if len(walls):
                ax.add_collection(LineCollection(walls, colors="black", linewidths=2.0, label="walls, pile, coupling surface"))
        ax.set_xlim(self.box[0], self.box[1])
        ax.set_ylim(self.box[2], self.box[3])
        ax.set_aspect("equal")
        ax.set_xlabel("x (m)")
        ax.set_ylabel("z (m)")
        ax.set_title(f"section y = 0, t = {snap.time:.4g} s (step {snap.step}); {broken} bonds broken since the start shown", fontsize=9)
        if ax.collections[1:]:
            ax.legend(loc="lower right", fontsize=8)
        fig.tight_layout()
        fig.savefig(path, dpi=self.dpi)
        plt.close(fig)


def render_matplotlib(run_dir, out, snapshot, colour, dpi):
    import matplotlib
    matplotlib.use("Agg")
    import dfc_results

    with dfc_results.open_results(run_dir) as run:
        snapshots = run.snapshots("dem")
    if not snapshots:
        raise SystemExit(f"render: {run_dir} holds no DEM snapshots (run.snapshot_every)")
    figure = SectionFigure(snapshots, colour, dpi)
    if snapshot is not None:
        snap = snapshots[snapshot]
        path = os.path.join(out, f"snapshot_{snap.index:06d}.png")
        figure.draw(snap, path)
        return [path]
    paths = []
    for snap in snapshots:
        paths.append(os.path.join(out, f"frame_{snap.index:06d}.png"))
        figure.draw(snap, paths[-1])
    if has_pillow():
        paths.append(write_gif(paths, os.path.join(out, "run.gif")))
    else:
        print("render: python3-pil is not installed: frames only, no GIF (apt-get install python3-pil)")
    return paths


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

PVBATCH_SCRIPT = r'''
import sys
from paraview.simple import *
xdmf, out, first, last = sys.argv[1], sys.argv[2], int(sys.argv[3]), int(sys.argv[4])
reader = XDMFReader(FileNames=[xdmf])
reader.UpdatePipelineInformation()
times = list(reader.TimestepValues) if reader.TimestepValues else [0.0]
view = CreateRenderView()
view.ViewSize = [1600, 1200]
view.OrientationAxesVisibility = 0
section = Slice(Input=reader)
section.SliceType = "Plane"
section.SliceType.Origin = [0.0, 0.0, 0.0]
section.SliceType.Normal = [0.0, 1.0, 0.0]
display = Show(section, view)
ColorBy(display, ("POINTS", "particle_radius_m"))
view.CameraPosition = [0.0, -1.0, 0.0]
view.CameraViewUp = [0.0, 0.0, 1.0]
view.ResetCamera()
for k in range(first, last):
    view.ViewTime = times[k]
    SaveScreenshot(out % k, view)
'''


def render_pvbatch(run_dir, out, snapshot):
    xdmf = os.path.join(run_dir, "results.xdmf")
    import dfc_results
    with dfc_results.open_results(run_dir) as run:
        count = run.snapshot_count("dem")
    first, last = (0, count) if snapshot is None else ((snapshot % count), (snapshot % count) + 1)
    pattern = os.path.join(out, ("frame_%06d.png" if snapshot is None else "snapshot_%06d.png"))
    with tempfile.NamedTemporaryFile("w", suffix=".py", delete=False) as script:
        script.write(PVBATCH_SCRIPT)
    # Debian's ParaView renders through X (no offscreen OpenGL): without a
    # display pvbatch aborts creating its window, so it runs in a virtual one.
    command = [PVBATCH, script.name, xdmf, pattern, str(first), str(last)]
    if not os.environ.get("DISPLAY"):
        if shutil.which("xvfb-run") is None:
            raise SystemExit("render.py: pvbatch needs an X display and there is none; install xvfb (xvfb-run) or use --renderer matplotlib")
        command = ["xvfb-run", "-a"] + command
    try:
        subprocess.run(command, check=True)
    finally:
        os.unlink(script.name)
    return [pattern % k for k in range(first, last)]


def main(argv=None):
    parser = argparse.ArgumentParser(
        description="Pictures of a run: a vertical section through the pile axis (y = 0), spheres coloured by displacement "
                    "or stress, bonds broken since the start in red, walls and pile drawn; PNG frames and a GIF, or one "
                    "snapshot.",
        epilog="--renderer auto uses matplotlib; pvbatch (ParaView's Python) is "
               + ("on PATH" if PVBATCH else "not on PATH")
               + ("; GIFs are written (python3-pil found)." if has_pillow() else "; no GIF: python3-pil is not installed, frames only.")
               + " docs/looking_at_a_run.md says what is drawn.")
    parser.add_argument("run", help="the run's folder (results.h5, results.xdmf) or its results.h5")
    parser.add_argument("--out", help="folder for the pictures (default RUN_DIR/pictures)")
    parser.add_argument("--snapshot", type=int, help="only this DEM snapshot (0 = first, -1 = last)")
    parser.add_argument("--colour", choices=("displacement", "stress"), default="displacement",
                        help="sphere colour: displacement since the first snapshot (mm) or mean stress (kPa); default displacement")
    parser.add_argument("--renderer", choices=("auto", "matplotlib", "pvbatch"), default="auto",
                        help="default auto: matplotlib (the pvbatch picture lacks the spheres so far)")
    parser.add_argument("--dpi", type=int, default=200, help="resolution of the PNGs (default 200, for print)")
    args = parser.parse_args(argv)

    run_dir = run_folder(args.run)
    out = args.out or os.path.join(run_dir, "pictures")
    os.makedirs(out, exist_ok=True)
    renderer = auto_renderer() if args.renderer == "auto" else args.renderer
    if renderer == "pvbatch":
        if not PVBATCH:
            raise SystemExit("render: --renderer pvbatch, but pvbatch (ParaView's Python) is not on PATH; use --renderer matplotlib")
        paths = render_pvbatch(run_dir, out, args.snapshot)
    else:
        paths = render_matplotlib(run_dir, out, args.snapshot, args.colour, args.dpi)
    for path in paths:
        print(f"{path}  ({renderer})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
