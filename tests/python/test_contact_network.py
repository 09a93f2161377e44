#!/usr/bin/env python3
"""The contact network and the DEM section's "snapshot" block
(docs/looking_at_a_run.md): a resting column of spheres, read back from
results.xdmf with dfc_results.sidecar.

The column is 2 x 2 stacks of LAYERS equal spheres (radius R, density RHO)
on a floor under gravity G, the stacks a little apart so that only the
spheres of one stack touch. At rest each sphere carries the ones above it,
so the contact normal forces between layer k and layer k + 1 (counting from
the floor) sum to the weight of the LAYERS - 1 - k layers above: the closed
form (LAYERS - 1 - k) * 4 * RHO * 4/3 pi R^3 * G. The test checks:

  - the block dem_contacts holds one line per touching pair, joining the two
    sphere centres, with that normal force (compression positive) and a
    force vector along the line;
  - contacts_min_force_n between one and two spheres' weight drops the
    contacts under the top layer and keeps every other;
  - "contents": ["walls"] leaves the stress, the contacts and their block out;
  - an unknown entry of "contents" fails before the run, naming the entry's
    key path and the entries allowed.

    test_contact_network.py COUPLER SOURCE_DIR OUT_DIR
        (CTest: exit code 77 = skipped when numpy or h5py are missing)
"""
import json
import math
import os
import shutil
import subprocess
import sys
import unittest

from dfc_test_support import require_modules

require_modules("numpy", "h5py")

import numpy as np  # noqa: E402

import dfc_results  # noqa: E402
from dfc_results.sidecar import read_sidecar  # noqa: E402

COUPLER, SOURCE, OUT = sys.argv[1:4] if len(sys.argv) >= 4 else (None, None, None)
R, RHO, G, LAYERS = 0.001, 2650.0, 9.81, 5
PITCH = 2.1 * R  # between the stacks: they do not touch
WEIGHT = RHO * 4.0 / 3.0 * math.pi * R ** 3 * G  # N, one sphere


def scenario(name, snapshot):
    spheres = [[x, y, R + 2 * R * k, R] for k in range(LAYERS) for x in (-PITCH / 2, PITCH / 2) for y in (-PITCH / 2, PITCH / 2)]
    dem = {
        "particles": {"generator": "list", "density_kg_m3": RHO, "spheres": spheres},
        "contact": {"law": "linear", "kn_n_m": 1e4, "ks_n_m": 5e3, "friction": 0.5, "damping_ratio_normal": 0.3},
        "damping": {"local": 0.7},
        "timestep": {"fraction_of_critical": 0.3},
        "walls": [{"type": "plane", "name": "floor", "point_m": [0, 0, 0], "normal": [0, 0, 1], "half_size_m": 0.01}],
        "threads": 1,
    }
    if snapshot is not None:
        dem["snapshot"] = snapshot
    return {
        "schema_version": 1,
        "name": name,
        "gravity": {"g_m_s2": G, "g_level": 1},
        "participants": {"dem": {"program": "dem_server", "config": dem}},
        "coupling": {"exchange_interval": 100},
        "run": {"exchanges": 40, "deadline_s": 300, "snapshot_every": 0},
    }


def run(name, snapshot, check_only=False):
    path = os.path.join(OUT, name + ".json")
    with open(path, "w") as f:
        json.dump(scenario(name, snapshot), f, indent=1)
    folder = os.path.join(OUT, name)
    command = [COUPLER, "check", path] if check_only else [COUPLER, "run", path, "--out", folder, "--no-progress"]
    return subprocess.run(command, capture_output=True, text=True), folder


class RestingColumn(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        shutil.rmtree(OUT, ignore_errors=True)
        os.makedirs(OUT)
        cls.folders = {}
        for name, snapshot in (("all", {"contents": ["particle_stress", "contacts", "walls"]}),
                               ("threshold", {"contents": ["contacts"], "contacts_min_force_n": 1.5 * WEIGHT}),
                               ("walls_only", {"contents": ["walls"]})):
            result, folder = run(name, snapshot)
            if result.returncode != 0:
                raise AssertionError(f"coupler exited with {result.returncode}:\n{result.stdout}\n{result.stderr}")
            cls.folders[name] = folder

    def last(self, name):
        with dfc_results.open_results(self.folders[name]) as results:
            snap = results.snapshots("dem")[-1]
        return snap, read_sidecar(self.folders[name])

    def layer(self, z):
        return np.rint((z - R) / (2 * R)).astype(int)

    def test_contact_forces_carry_the_weight_above(self):
        snap, blocks = self.last("all")
        grid = blocks["dem_contacts"][-1]
        self.assertEqual(grid.topology, "Polyline")
        np.testing.assert_array_equal(grid.connectivity, snap.arrays["contact_particle_index"])
        ends = grid.points[grid.connectivity]  # (contacts, 2, 3): what ParaView draws
        np.testing.assert_array_equal(ends, snap.arrays["particle_position"][grid.connectivity])
        # Only the spheres of one stack, one above the other, touch.
        self.assertEqual(len(ends), 4 * (LAYERS - 1))
        np.testing.assert_allclose(ends[:, 0, :2], ends[:, 1, :2], atol=1e-12)
        lower = self.layer(ends[:, :, 2].min(axis=1))
        np.testing.assert_array_equal(self.layer(ends[:, :, 2].max(axis=1)), lower + 1)
        normal = grid.cell_arrays["contact_normal_force_n"]
        force = grid.cell_arrays["contact_force_n"]
        for k in range(LAYERS - 1):
            with self.subTest(interface=k):
                self.assertAlmostEqual(normal[lower == k].sum() / (4 * (LAYERS - 1 - k) * WEIGHT), 1.0, delta=1e-9)
        # The force is along the line, its size the normal force.
        np.testing.assert_allclose(np.linalg.norm(force, axis=1), normal, rtol=1e-9)
        np.testing.assert_allclose(force[:, :2], 0.0, atol=1e-9 * WEIGHT)
        self.assertIn("particle_stress_pa", blocks["dem_particles"][-1].point_arrays)
        self.assertIn("dem_walls", blocks)

    def test_threshold_drops_the_small_contacts(self):
        snap, blocks = self.last("threshold")
        normal = blocks["dem_contacts"][-1].cell_arrays["contact_normal_force_n"]
        self.assertEqual(len(normal), 4 * (LAYERS - 2), "the contacts under the top layer (one weight each) are left out")
        self.assertTrue(np.all(normal >= 1.5 * WEIGHT))
        self.assertNotIn("particle_stress_pa", snap.arrays)
        self.assertNotIn("dem_walls", blocks)

    def test_contents_leave_arrays_out(self):
        snap, blocks = self.last("walls_only")
        for name in ("particle_stress_pa", "contact_particle_index", "contact_normal_force_n"):
            self.assertNotIn(name, snap.arrays)
        for name in ("particle_position", "particle_radius", "particle_velocity", "particle_id", "wall_vertices"):
            self.assertIn(name, snap.arrays)  # protocol/SPEC.md §6.4 requires the first four
        self.assertNotIn("dem_contacts", blocks)
        self.assertIn("dem_walls", blocks)

    def test_an_unknown_entry_is_named_with_the_choices(self):
        result, _ = run("unknown", {"contents": ["walls", "contact"]}, check_only=True)
        self.assertNotEqual(result.returncode, 0)
        message = result.stdout + result.stderr
        self.assertIn("snapshot.contents[1]", message)
        self.assertIn('unknown value "contact"', message)
        self.assertIn('"contacts"', message)


if __name__ == "__main__":
    unittest.main(argv=sys.argv[:1], verbosity=2)
