#!/usr/bin/env python3
"""./vc render with ParaView's pvbatch: the coupler runs the short pile scenario
of the end-to-end tests and tools/render.py --renderer pvbatch draws its last
DEM snapshot from results.xdmf into a PNG that must show a colour of the
sphere colour map at the centre of the spheres the plane cuts (seven in ten
at least: red bonds and walls cross some; where the
camera of render.py puts it; without the spheres the centres are white
background). A failed drawing is tried once more (pvbatch in xvfb-run failed
now and then on a loaded machine), saying why. Skipped
(exit code 77, with the reason) where pvbatch is not on PATH (Debian's
paraview package is large and not a dependency of the project), where it has
no X display to draw into (no $DISPLAY, and no xvfb-run with xauth), or
where it does not start at all; a failure of the drawing itself fails, with
pvbatch's messages.

    test_render_pvbatch.py COUPLER SOURCE_DIR OUT_DIR
"""
import os
import re
import shutil
import subprocess
import sys

from dfc_test_support import require_modules, require_pvbatch

COUPLER, SOURCE, OUT = sys.argv[1:4]
sys.path.insert(0, os.path.join(SOURCE, "tools"))
import render as render_tool  # noqa: E402

require_pvbatch(display=True)
require_modules("numpy", "h5py", "matplotlib")

import matplotlib.image  # noqa: E402
import numpy as np  # noqa: E402

shutil.rmtree(OUT, ignore_errors=True)
run_dir = os.path.join(OUT, "run")
subprocess.run([COUPLER, "run", os.path.join(SOURCE, "tests/e2e/scenarios/pile_short.json"), "--out", run_dir, "--no-progress"], check=True)
pictures = os.path.join(OUT, "pictures")


def draw():
    return subprocess.run([sys.executable, os.path.join(SOURCE, "tools/render.py"), run_dir, "--snapshot", "-1", "--renderer", "pvbatch",
                           "--out", pictures], capture_output=True, text=True)


drawn = draw()
if drawn.returncode != 0:
    # pvbatch in xvfb-run has failed now and then on a loaded machine (the
    # virtual display not ready in time): once more, saying why.
    print(f"tools/render.py --renderer pvbatch failed with exit status {drawn.returncode}; once more. Its stderr:\n{drawn.stderr[-3000:]}")
    drawn = draw()
print(drawn.stdout)
if drawn.returncode != 0:
    # The reason is in pvbatch's (or xvfb-run's) own words: without it a CI log
    # says only "exit status 1".
    print(drawn.stderr, file=sys.stderr)
    sys.exit(f"tools/render.py --renderer pvbatch failed with exit status {drawn.returncode} (its stderr above)")
if "(pvbatch)" not in drawn.stdout:
    sys.exit("tools/render.py did not say it drew with pvbatch")
png = [name for name in os.listdir(pictures) if name.endswith(".png")]
if len(png) != 1:
    sys.exit(f"expected one PNG in {pictures}, found {png}")
image = matplotlib.image.imread(os.path.join(pictures, png[0]))
colours = np.unique((image[..., :3] * 255).astype(np.uint8).reshape(-1, 3), axis=0)
if len(colours) < 10:
    sys.exit(f"{png[0]} has {len(colours)} colours: blank")
if image.shape[1::-1] != render_tool.PVBATCH_SIZE:
    sys.exit(f"{png[0]} is {image.shape[1]} x {image.shape[0]} pixels, not the {render_tool.PVBATCH_SIZE} the camera is set for")

# Every sphere the plane y = 0 cuts in the last snapshot is drawn (the first
# pvbatch picture sliced the point cloud and showed none).
import dfc_results  # noqa: E402

with dfc_results.open_results(run_dir) as run:
    snapshots = run.snapshots("dem")
last = snapshots[-1]
position, radius = last.arrays["particle_position"], last.arrays["particle_radius"]
rows, cut = render_tool.cut_spheres(position, radius, 0.0)
match = re.search(r"(\d+) spheres cut by the plane", drawn.stdout)
if match is None or int(match.group(1)) != len(rows) or len(rows) == 0:
    sys.exit(f"pvbatch kept {match.group(1) if match else 'no'} spheres; the plane cuts {len(rows)} in the last snapshot")

# ... and shows in the picture: at the centre of each cut circle of a few
# pixels or more the picture has a colour of the sphere colour map (not the
# white background, the black walls, the red bonds, nor the grey of an
# unlit or uncoloured surface). A picture without the spheres has none.
section = render_tool.Section(snapshots, "displacement")
column, row = render_tool.pvbatch_pixel(section.box, position[rows, 0], position[rows, 2])
_, _, scale = render_tool.pvbatch_camera(section.box)
pixels_per_m = 0.5 * render_tool.PVBATCH_SIZE[1] / scale
visible = cut * pixels_per_m >= 4.0
rgb = (image[np.round(row[visible]).astype(int), np.round(column[visible]).astype(int), :3] * 255).astype(int)
red = (rgb[:, 0] > 150) & (rgb[:, 1] < 80) & (rgb[:, 2] < 80)
coloured = (rgb.max(axis=1) - rgb.min(axis=1) >= 15) & ~red
share = np.count_nonzero(coloured) / max(1, len(rgb))
print(f"pvbatch drew {png[0]}: {image.shape[1]} x {image.shape[0]} pixels, {len(colours)} colours, {len(rows)} spheres cut by the plane, "
      f"{np.count_nonzero(coloured)} of the {len(rgb)} of 4 pixels or more coloured at their centre")
# Broken bonds (red) and walls cross some centres; the rest must show.
if len(rgb) < 10 or share < 0.7:
    sys.exit(f"the spheres are missing from {png[0]}: {np.count_nonzero(coloured)} of the {len(rgb)} cut circles of 4 pixels or more "
             "have a sphere colour at their centre")
