#!/usr/bin/env python3
"""ParaView reads the snapshots of results.xdmf as they are stored (chunked,
deflated): the coupler runs the small bonded pile of python.run_view
(tests/e2e/scenarios/pile_bonded_restart.json, 120 exchanges, a snapshot every
40, contacts asked for) and ParaView's XDMF Reader, in pvbatch, reads every
snapshot of the blocks dem_particles, dem_bonds, dem_contacts, dem_walls and
continuum_grid. The test checks that the datasets the sidecar names are
chunked and deflated (else it would not test what it says), and that for
every block and snapshot ParaView has the points, the cells (their node rows)
and every array with the values h5py reads from those datasets.

Skipped (exit code 77, with the reason) where pvbatch is not on PATH or does
not start (dfc_test_support.require_pvbatch); reading needs no display.

    test_xdmf_pvbatch.py COUPLER SOURCE_DIR OUT_DIR
"""
import json
import os
import subprocess
import sys

from dfc_test_support import bonded_pile_scenario, require_modules, require_pvbatch

COUPLER, SOURCE, OUT = sys.argv[1:4]
require_modules("numpy", "h5py")
PVBATCH = require_pvbatch(display=False)

import h5py  # noqa: E402
import numpy as np  # noqa: E402

from dfc_results.sidecar import read_sidecar  # noqa: E402

BLOCKS = ("dem_particles", "dem_bonds", "dem_contacts", "dem_walls", "continuum_grid")
# VTK's XDMF reader makes a Tensor6 attribute (xx, xy, xz, yy, yz, zz) a full,
# symmetric 3 x 3 tensor, row by row.
TENSOR6_AS_9 = [0, 1, 2, 1, 3, 4, 2, 4, 5]

# Runs in pvbatch: every (block, time) asked for, as ParaView's XDMF Reader
# gives it, into one .npz.
READ = r'''
import json
import sys

import numpy as np
from paraview import servermanager
from paraview.simple import XDMFReader
from vtkmodules.util.numpy_support import vtk_to_numpy

job = json.load(open(sys.argv[1]))
reader = XDMFReader(FileNames=[job["xdmf"]])
reader.UpdatePipelineInformation()
out = {}
for key, block, time in job["requests"]:
    reader.UpdatePipeline(time)
    data = servermanager.Fetch(reader)
    names = [data.GetMetaData(i).Get(data.NAME()) for i in range(data.GetNumberOfBlocks())]
    if block not in names:
        print("pvbatch: no block %s at t = %g; the reader has %s" % (block, time, names))
        continue
    grid = data.GetBlock(names.index(block))
    out[key + "/points"] = vtk_to_numpy(grid.GetPoints().GetData()) if grid.GetPoints() else np.zeros((0, 3))
    out[key + "/cells"] = vtk_to_numpy(grid.GetCells().GetConnectivityArray()).astype(np.int64)
    out[key + "/offsets"] = vtk_to_numpy(grid.GetCells().GetOffsetsArray()).astype(np.int64)
    for centre, fields in (("point", grid.GetPointData()), ("cell", grid.GetCellData())):
        for i in range(fields.GetNumberOfArrays()):
            out["%s/%s/%s" % (key, centre, fields.GetArrayName(i))] = vtk_to_numpy(fields.GetArray(i))
np.savez(job["out"], **out)
print("pvbatch: read %d grids" % len({k.split("/")[0] for k in out}))
'''


def run_pile():
    path = bonded_pile_scenario(SOURCE, OUT, "xdmf_pvbatch")
    folder = os.path.join(OUT, "run")
    subprocess.run([COUPLER, "run", path, "--out", folder, "--no-progress"], check=True)
    return folder


def check_stored_compressed(folder, blocks):
    """Every snapshot dataset the sidecar names is chunked and deflated."""
    with h5py.File(os.path.join(folder, "results.h5"), "r") as f:
        for name, grids in blocks.items():
            for grid in grids:
                for reference in grid.references:
                    path = reference.partition(":")[2]
                    if not path.startswith("/snapshots/"):
                        continue  # the shared index arrays of /xdmf
                    dataset = f[path]
                    if dataset.chunks is None or dataset.compression != "gzip":
                        sys.exit(f"{path} ({name}) is stored with chunks {dataset.chunks}, compression {dataset.compression}: "
                                 "not what this test reads")


def compare(what, paraview, stored):
    paraview = np.asarray(paraview)
    stored = np.asarray(stored)
    if paraview.shape != stored.shape or not np.array_equal(paraview, stored):
        sys.exit(f"{what}: ParaView read {paraview.shape} {paraview.ravel()[:6]}..., the HDF5 file holds {stored.shape} "
                 f"{stored.ravel()[:6]}...")


def main():
    folder = run_pile()
    blocks = read_sidecar(folder)
    missing = [name for name in BLOCKS if not blocks.get(name)]
    if missing:
        sys.exit(f"results.xdmf lacks the blocks {missing}; it has {sorted(blocks)}")
    check_stored_compressed(folder, blocks)
    requests = [[f"{name}:{k}", name, grid.time] for name in BLOCKS for k, grid in enumerate(blocks[name])]
    job = os.path.join(OUT, "read.json")
    dump = os.path.join(OUT, "paraview.npz")
    with open(job, "w") as f:
        json.dump({"xdmf": os.path.join(folder, "results.xdmf"), "out": dump, "requests": requests}, f)
    script = os.path.join(OUT, "read.py")
    with open(script, "w") as f:
        f.write(READ)
    read = subprocess.run(PVBATCH + [script, job], capture_output=True, text=True)
    print(read.stdout)
    if read.returncode != 0:
        print(read.stderr, file=sys.stderr)
        sys.exit(f"pvbatch failed reading results.xdmf (exit status {read.returncode}; its stderr above)")
    paraview = np.load(dump)
    compared = 0
    for key, name, _ in requests:
        grid = blocks[name][int(key.split(":")[1])]
        if key + "/points" not in paraview:
            sys.exit(f"ParaView has no {name} at t = {grid.time} (snapshot {grid.name})")
        compare(f"{key} points", paraview[key + "/points"], grid.points)
        offsets = paraview[key + "/offsets"]
        compare(f"{key} nodes per cell", np.diff(offsets), np.full(len(grid.connectivity), grid.connectivity.shape[1]))
        compare(f"{key} cells", paraview[key + "/cells"].reshape(grid.connectivity.shape), grid.connectivity)
        for centre, arrays in (("point", grid.point_arrays), ("cell", grid.cell_arrays)):
            for array, stored in arrays.items():
                read_back = paraview.get(f"{key}/{centre}/{array}")
                if read_back is None:
                    sys.exit(f"ParaView has no {centre} array {array} in {key}")
                if stored.ndim == 2 and stored.shape[1] == 6 and read_back.ndim == 2 and read_back.shape[1] == 9:
                    stored = stored[:, TENSOR6_AS_9]
                compare(f"{key} {centre} array {array}", read_back, stored.reshape(read_back.shape) if stored.size == read_back.size else stored)
                compared += 1
    print(f"ParaView's XDMF Reader read {len(requests)} grids of {len(BLOCKS)} blocks and {compared} arrays, every value as h5py reads it "
          f"from the chunked, deflated datasets")


if __name__ == "__main__":
    main()
