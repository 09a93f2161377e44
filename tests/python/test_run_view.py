#!/usr/bin/env python3
"""What ParaView sees of a small bonded pile run (docs/looking_at_a_run.md): the
coupler runs tests/e2e/scenarios/pile_bonded_restart.json (soft-bonded grains, a
pile driven from the first step, the FDM around them) with a snapshot every 40
exchanges, and the test reads results.xdmf with dfc_results.sidecar and checks:

  - every DataItem names a dataset of the results file with the stated shape,
    and each block's times are its snapshots' times;
  - every bond line joins the two particles whose ids the bond names, at their
    positions in that snapshot (looked up by id, not by the line's own index),
    its midpoint is on it and its opening is the gap between their surfaces;
  - the bond states of the last snapshot add up to the DEM's bond monitors;
  - the contact lines hold every bonded pair that carries a force, with the
    bond's normal force (the sign reversed: contacts count compression
    positive), and the force vector's part along each line;
  - the walls block holds the pile, which moves by the pile's displacement
    (the monitor pile_displacement_m) from the first snapshot to the last,
    while the floor stays, and the file names the moving wall "pile";
  - ./vc render (tools/render.py, the matplotlib path) draws one snapshot of
    the run into a PNG that is not blank.

    test_run_view.py COUPLER SOURCE_DIR OUT_DIR
        (CTest: exit code 77 = skipped when numpy or h5py are missing)
"""
import os
import subprocess
import sys
import unittest

from dfc_test_support import bonded_pile_scenario, require_modules

require_modules("numpy", "h5py")

import numpy as np  # noqa: E402

import dfc_results  # noqa: E402
from dfc_results.sidecar import read_sidecar  # noqa: E402

COUPLER, SOURCE, OUT = sys.argv[1:4] if len(sys.argv) >= 4 else (None, None, None)


class BondedPileView(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        path = bonded_pile_scenario(SOURCE, OUT, "run_view")
        cls.folder = os.path.join(OUT, "run")
        run = subprocess.run([COUPLER, "run", path, "--out", cls.folder, "--no-progress"], capture_output=True, text=True)
        if run.returncode != 0:
            raise AssertionError(f"coupler exited with {run.returncode}:\n{run.stdout}\n{run.stderr}")
        cls.blocks = read_sidecar(cls.folder)
        with dfc_results.open_results(cls.folder) as results:
            cls.snapshots = results.snapshots("dem")
            cls.series = results.all_series()
            cls.wall_names = results.wall_names("dem")

    def row_of_step(self, step):
        rows = np.flatnonzero(self.series["step_dem"].values == step)
        self.assertEqual(len(rows), 1, f"no time-series row at step {step}")
        return rows[0]

    def test_every_reference_exists_with_its_shape(self):
        import h5py
        with h5py.File(os.path.join(self.folder, "results.h5"), "r") as f:
            for name, grids in self.blocks.items():
                for grid in grids:
                    for reference, dims in grid.references.items():
                        with self.subTest(block=name, item=reference):
                            path = reference.partition(":")[2]
                            self.assertIn(path, f)
                            self.assertEqual(f[path].shape, dims)

    def test_blocks_follow_the_snapshots(self):
        self.assertGreaterEqual(len(self.snapshots), 3)
        for name in ("dem_particles", "dem_walls"):
            with self.subTest(block=name):
                self.assertEqual([g.time for g in self.blocks[name]], [s.time for s in self.snapshots])
        # Bonds are installed at the first step: a snapshot before it has none, and no bond grid.
        bonded = [s.time for s in self.snapshots if len(s.arrays["bond_state"]) > 0]
        self.assertEqual([g.time for g in self.blocks["dem_bonds"]], bonded)
        self.assertGreaterEqual(len(bonded), 2)
        self.assertIn("continuum_grid", self.blocks)
        particles = self.blocks["dem_particles"][-1]
        self.assertIn("particle_radius_m", particles.point_arrays)  # for the Glyph filter's scale
        self.assertIn("particle_id", particles.point_arrays)

    def test_bond_lines_join_the_particles_the_bond_names(self):
        checked = 0
        bonded = [s for s in self.snapshots if len(s.arrays["bond_state"]) > 0]
        for snap, grid in zip(bonded, self.blocks["dem_bonds"]):
            with self.subTest(snapshot=snap.index):
                self.assertEqual(grid.topology, "Polyline")
                ids = snap.arrays["particle_id"]
                position = snap.arrays["particle_position"]
                radius = snap.arrays["particle_radius"]
                row_of_id = {int(i): r for r, i in enumerate(ids)}
                named = snap.arrays["bond_particle_id"]
                self.assertEqual(grid.connectivity.shape, named.shape)
                self.assertGreater(len(named), 0)
                rows = np.array([[row_of_id[int(a)], row_of_id[int(b)]] for a, b in named])
                ends = grid.points[grid.connectivity]  # what ParaView draws: (bonds, 2, 3)
                np.testing.assert_array_equal(ends, position[rows])
                # The midpoint the file also holds lies on the line, between the surfaces.
                mid = snap.arrays["bond_position"]
                a, b = ends[:, 0], ends[:, 1]
                length = np.linalg.norm(b - a, axis=1)
                t = np.einsum("ij,ij->i", mid - a, b - a) / length ** 2
                np.testing.assert_allclose(a + t[:, None] * (b - a), mid, atol=1e-12)
                np.testing.assert_allclose(t, radius[rows[:, 0]] / radius[rows].sum(axis=1), rtol=1e-9)
                opening = grid.cell_arrays["bond_opening_m"]
                np.testing.assert_allclose(opening, length - radius[rows].sum(axis=1), atol=1e-12)
                checked += len(named)
        self.assertGreater(checked, 0)

    def test_contacts_are_the_pairs_that_carry_force(self):
        # Every bonded pair with a force is a contact line too, its normal
        # force the bond's with the sign of a contact (compression positive).
        snap, grid = self.snapshots[-1], self.blocks["dem_contacts"][-1]
        self.assertEqual(grid.topology, "Polyline")
        ends = grid.points[grid.connectivity]
        np.testing.assert_array_equal(ends, snap.arrays["particle_position"][snap.arrays["contact_particle_index"]])
        contact = {tuple(pair): f for pair, f in zip(grid.connectivity.tolist(), grid.cell_arrays["contact_normal_force_n"])}
        bond_normal = snap.arrays["bond_normal_force_n"]
        loaded = np.flatnonzero((bond_normal != 0) | (snap.arrays["bond_shear_force_n"] != 0))
        self.assertGreater(len(loaded), 0)
        for b in loaded:
            self.assertEqual(contact[tuple(snap.arrays["bond_particle_index"][b])], -bond_normal[b])
        # (In this short run every touching pair is a bonded one: no unbonded contact to count apart.)
        force = grid.cell_arrays["contact_force_n"]
        axis = ends[:, 1] - ends[:, 0]
        # The normal force is the force vector's part along the line (on the first sphere: compression pushes it away from the second).
        np.testing.assert_allclose(-np.einsum("ij,ij->i", force, axis) / np.linalg.norm(axis, axis=1),
                                   grid.cell_arrays["contact_normal_force_n"], rtol=1e-9, atol=1e-12 * np.abs(force).max())

    def test_bond_states_add_up_to_the_monitors(self):
        snap, grid = self.snapshots[-1], self.blocks["dem_bonds"][-1]
        state = grid.cell_arrays["bond_state"]
        row = self.row_of_step(snap.step)
        for code, monitor in ((1, "bonds_intact"), (2, "bonds_damaged"), (3, "bonds_broken_tension"), (4, "bonds_broken_shear")):
            with self.subTest(monitor=monitor):
                self.assertEqual(np.count_nonzero(state == code), self.series[f"dem_{monitor}"].values[row])
        self.assertGreater(np.count_nonzero(state >= 3), 0, "the pile should break bonds in this run")
        # Broken pairs well apart carry nothing; bonded pairs carry forces. (The
        # forces are those of the last step, evaluated before its move: a pair
        # that parted in that step, microns apart now, may still show one.)
        normal, shear = grid.cell_arrays["bond_normal_force_n"], grid.cell_arrays["bond_shear_force_n"]
        apart = (state >= 3) & (grid.cell_arrays["bond_opening_m"] > 1e-4)
        self.assertGreater(np.count_nonzero(apart), 0)
        self.assertTrue(np.all(normal[apart] == 0) and np.all(shear[apart] == 0))
        self.assertGreater(np.count_nonzero(normal[state <= 2]), 0)

    def test_the_pile_surface_moves_by_the_pile_displacement(self):
        # From the first snapshot with a time-series row (the series start after the first exchange).
        first, last = self.blocks["dem_walls"][1], self.blocks["dem_walls"][-1]
        self.assertEqual(first.topology, "Triangle")
        wall = first.cell_arrays["wall_index"]
        moved = last.points - first.points
        rigid = {}
        for w in np.unique(wall):
            nodes = np.unique(first.connectivity[wall == w])
            shift = moved[nodes]
            if np.allclose(shift, shift[0], atol=1e-12):
                rigid[int(w)] = shift[0]
        still = [w for w, s in rigid.items() if np.all(s == 0)]
        moving = [w for w, s in rigid.items() if np.any(s != 0)]
        self.assertEqual(len(still), 1, "the floor")
        self.assertEqual(len(moving), 1, "the pile")
        # The file names the walls by their index: the one that moves is the pile.
        self.assertEqual(self.wall_names[moving[0]], "pile", self.wall_names)
        self.assertEqual(self.wall_names[-1], "coupling surface", self.wall_names)
        self.assertEqual(len(self.wall_names), int(np.max(wall)) + 1, self.wall_names)
        d0 = self.series["dem_pile_displacement_m"].values[self.row_of_step(self.snapshots[1].step)]
        d1 = self.series["dem_pile_displacement_m"].values[self.row_of_step(self.snapshots[-1].step)]
        self.assertGreater(d1 - d0, 0.0)
        # The pile is driven along -z: penetration is its travel downwards.
        np.testing.assert_allclose(rigid[moving[0]], [0.0, 0.0, -(d1 - d0)], rtol=1e-9, atol=1e-12)

    def test_render_draws_a_snapshot(self):
        out = os.path.join(OUT, "render")
        run = subprocess.run([sys.executable, os.path.join(SOURCE, "tools", "render.py"), self.folder, "--snapshot", "-1",
                              "--out", out, "--renderer", "matplotlib"], capture_output=True, text=True)
        self.assertEqual(run.returncode, 0, run.stdout + run.stderr)
        png = [name for name in os.listdir(out) if name.endswith(".png")]
        self.assertEqual(len(png), 1, png)
        import matplotlib.image
        image = matplotlib.image.imread(os.path.join(out, png[0]))
        self.assertGreater(image.shape[0], 300)
        # Not blank: many distinct colours (spheres coloured by a field, red bonds, the pile).
        colours = np.unique((image[..., :3] * 255).astype(np.uint8).reshape(-1, 3), axis=0)
        self.assertGreater(len(colours), 50)
        red = np.all(image[..., :3] == np.array([1.0, 0.0, 0.0]), axis=-1) if image.dtype != np.uint8 else None
        self.assertTrue(red is None or np.count_nonzero(red) > 0, "the bonds broken since the start are drawn in red")


if __name__ == "__main__":
    unittest.main(argv=sys.argv[:1], verbosity=2)
