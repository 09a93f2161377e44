#!/usr/bin/env python3
"""./vc render with ParaView's pvbatch: the coupler runs the short pile scenario
of the end-to-end tests and tools/render.py --renderer pvbatch draws its last
DEM snapshot from results.xdmf into a PNG that must not be blank. Skipped
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
import tempfile

from dfc_test_support import require_modules

COUPLER, SOURCE, OUT = sys.argv[1:4]
sys.path.insert(0, os.path.join(SOURCE, "tools"))
import render  # noqa: E402

if render.PVBATCH is None:
    print("SKIPPED: pvbatch (ParaView's Python) is not on PATH; tools/render.py uses its matplotlib path here")
    sys.exit(77)
if render.virtual_display_missing():
    print(f"SKIPPED: Debian's pvbatch renders through X: {render.virtual_display_missing()}")
    sys.exit(77)
require_modules("numpy", "h5py", "matplotlib")
# Whether pvbatch starts at all here (a machine whose ParaView or X cannot
# open a window is not this test's subject): a script that only prints.
with tempfile.NamedTemporaryFile("w", suffix=".py", delete=False) as probe:
    probe.write("print('pvbatch runs')\n")
started = subprocess.run(([] if os.environ.get("DISPLAY") else ["xvfb-run", "-a"]) + [render.PVBATCH, probe.name],
                         capture_output=True, text=True)
os.unlink(probe.name)
if started.returncode != 0 or "pvbatch runs" not in started.stdout:
    print(f"SKIPPED: pvbatch does not start here (exit status {started.returncode}): {started.stderr.strip()[-2000:]}")
    sys.exit(77)

import matplotlib.image  # noqa: E402
import numpy as np  # noqa: E402

shutil.rmtree(OUT, ignore_errors=True)
run_dir = os.path.join(OUT, "run")
subprocess.run([COUPLER, "run", os.path.join(SOURCE, "tests/e2e/scenarios/pile_short.json"), "--out", run_dir, "--no-progress"], check=True)
pictures = os.path.join(OUT, "pictures")
render = subprocess.run([sys.executable, os.path.join(SOURCE, "tools/render.py"), run_dir, "--snapshot", "-1", "--renderer", "pvbatch",
                         "--out", pictures], capture_output=True, text=True)
drawn = render.stdout
print(drawn)
if render.returncode != 0:
    # The reason is in pvbatch's (or xvfb-run's) own words: without it a CI log
    # says only "exit status 1".
    print(render.stderr, file=sys.stderr)
    sys.exit(f"tools/render.py --renderer pvbatch failed with exit status {render.returncode} (its stderr above)")
png = [name for name in os.listdir(pictures) if name.endswith(".png")]
if len(png) != 1:
    sys.exit(f"expected one PNG in {pictures}, found {png}")
image = matplotlib.image.imread(os.path.join(pictures, png[0]))
colours = np.unique((image[..., :3] * 255).astype(np.uint8).reshape(-1, 3), axis=0)
if len(colours) < 10:
    sys.exit(f"{png[0]} has {len(colours)} colours: blank")
# Every sphere the plane y = 0 cuts in the last snapshot is drawn (the first
# pvbatch picture sliced the point cloud and showed none).
sys.path.insert(0, os.path.join(SOURCE, "python"))
import dfc_results  # noqa: E402

with dfc_results.open_results(run_dir) as run:
    last = run.snapshots("dem")[-1]
expected = int(np.count_nonzero(np.abs(last.arrays["particle_position"][:, 1]) < last.arrays["particle_radius"]))
match = re.search(r"(\d+) spheres cut by the plane", drawn)
if match is None or int(match.group(1)) != expected or expected == 0:
    sys.exit(f"pvbatch drew {match.group(1) if match else 'no'} spheres; the plane cuts {expected} in the last snapshot")
print(f"pvbatch drew {png[0]}: {image.shape[1]} x {image.shape[0]} pixels, {len(colours)} colours, {expected} spheres cut by the plane")
