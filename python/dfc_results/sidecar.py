"""Read the XDMF sidecar (results.xdmf) the way ParaView does: its blocks, and for
each block the meshes over time with their connectivity, points and arrays
resolved from the HDF5 file they point into.

    from dfc_results.sidecar import read_sidecar

    blocks = read_sidecar("results/foundation")          # the folder, or the .xdmf itself
    for grid in blocks["dem_bonds"]:                     # one SidecarGrid per snapshot, in time order
        lines = grid.points[grid.connectivity]           # (bonds, 2, 3): each bond's two sphere centres
        grid.cell_arrays["bond_normal_force_n"]          # one value per bond

Used by the tests of the sidecar and by tools/render.py; docs/looking_at_a_run.md
says what each block and array is.
"""
import os
import xml.etree.ElementTree as ElementTree
from typing import NamedTuple

import h5py
import numpy as np

__all__ = ["SidecarGrid", "read_sidecar", "SIDECAR_FILE"]

SIDECAR_FILE = "results.xdmf"


class SidecarGrid(NamedTuple):
    """One uniform grid (one snapshot of one block)."""

    name: str
    time: float
    topology: str           # "Polyvertex", "Polyline", "Triangle", "Hexahedron"
    connectivity: np.ndarray  # (cells, nodes per cell) int64, rows of `points`
    points: np.ndarray        # (n, 3)
    point_arrays: dict        # name as ParaView shows it -> array
    cell_arrays: dict
    references: dict          # every DataItem's "file:/path" -> the dimensions it states


def _read_item(item, folder, handles, references):
    text = item.text.strip()
    file_name, _, path = text.partition(":")
    dims = tuple(int(d) for d in item.get("Dimensions").split())
    references[text] = dims
    if file_name not in handles:
        handles[file_name] = h5py.File(os.path.join(folder, file_name), "r")
    return np.asarray(handles[file_name][path][...])


def read_sidecar(path):
    """{block name: [SidecarGrid, ...]} in the order of the file."""
    path = os.fspath(path)
    if os.path.isdir(path):
        path = os.path.join(path, SIDECAR_FILE)
    folder = os.path.dirname(os.path.abspath(path))
    domain = ElementTree.parse(path).getroot().find("Domain")
    handles = {}
    blocks = {}
    try:
        for collection in domain.findall("Grid"):
            grids = []
            for grid in collection.findall("Grid"):
                references = {}
                topology = grid.find("Topology")
                connectivity = _read_item(topology.find("DataItem"), folder, handles, references)
                cells = int(topology.get("NumberOfElements"))
                connectivity = connectivity.reshape(cells, -1)
                points = _read_item(grid.find("Geometry").find("DataItem"), folder, handles, references)
                arrays = {"Node": {}, "Cell": {}}
                for attribute in grid.findall("Attribute"):
                    arrays[attribute.get("Center")][attribute.get("Name")] = _read_item(attribute.find("DataItem"), folder, handles, references)
                grids.append(SidecarGrid(grid.get("Name"), float(grid.find("Time").get("Value")), topology.get("TopologyType"),
                                         connectivity, points, arrays["Node"], arrays["Cell"], references))
            blocks[collection.get("Name")] = grids
    finally:
        for handle in handles.values():
            handle.close()
    return blocks
