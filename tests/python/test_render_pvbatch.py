#!/usr/bin/env python3
"""./vc render with ParaView's pvbatch: the coupler runs the short pile scenario
of the end-to-end tests and tools/render.py --renderer pvbatch draws its last
DEM snapshot from results.xdmf into a PNG that must not be blank. Skipped
(exit code 77) where pvbatch is not on PATH: Debian's paraview package is
large and not a dependency of the project.

    test_render_pvbatch.py COUPLER SOURCE_DIR OUT_DIR
"""
import os
import re
import shutil
import subprocess
import sys

from dfc_test_support import require_modules

if shutil.which("pvbatch") is None:
    print("SKIPPED: pvbatch (ParaView's Python) is not on PATH; tools/render.py uses its matplotlib path here")
    sys.exit(77)
if not os.environ.get("DISPLAY") and shutil.which("xvfb-run") is None:
    print("SKIPPED: no X display and no xvfb-run; Debian's pvbatch renders through X")
    sys.exit(77)
require_modules("numpy", "h5py", "matplotlib")

import matplotlib.image  # noqa: E402
import numpy as np  # noqa: E402

COUPLER, SOURCE, OUT = sys.argv[1:4]
shutil.rmtree(OUT, ignore_errors=True)
run_dir = os.path.join(OUT, "run")
subprocess.run([COUPLER, "run", os.path.join(SOURCE, "tests/e2e/scenarios/pile_short.json"), "--out", run_dir, "--no-progress"], check=True)
pictures = os.path.join(OUT, "pictures")
drawn = subprocess.run([sys.executable, os.path.join(SOURCE, "tools/render.py"), run_dir, "--snapshot", "-1", "--renderer", "pvbatch",
                        "--out", pictures], check=True, capture_output=True, text=True).stdout
print(drawn)
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
