#!/usr/bin/env python3
"""python/dfc_results on a file from a real run: the coupler runs the short pile
scenario of the end-to-end tests (DEM and FDM over ZeroMQ, a few seconds) and the
package reads the time series with their units and the snapshots of both sides.

    test_dfc_results_e2e.py COUPLER SCENARIO.json OUT_DIR
        (CTest: exit code 77 = skipped when numpy or h5py are missing)
"""
import shutil
import subprocess
import sys
import unittest

from dfc_test_support import require_modules

require_modules("numpy", "h5py")

import numpy as np  # noqa: E402

import dfc_results  # noqa: E402

COUPLER, SCENARIO, OUT = sys.argv[1:4] if len(sys.argv) >= 4 else (None, None, None)


class PileRunTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        shutil.rmtree(OUT, ignore_errors=True)
        run = subprocess.run([COUPLER, "run", SCENARIO, "--out", OUT, "--no-progress"], capture_output=True, text=True)
        if run.returncode != 0:
            raise AssertionError(f"coupler exited with {run.returncode}:\n{run.stdout}\n{run.stderr}")
        cls.run_results = dfc_results.open_results(OUT)

    @classmethod
    def tearDownClass(cls):
        cls.run_results.close()

    def test_metadata(self):
        run = self.run_results
        self.assertEqual(run.format, dfc_results.FORMAT)
        self.assertIsInstance(run.scenario, dict)
        self.assertIsNotNone(run.summary)
        self.assertIsNone(run.failure)

    def test_series_and_units(self):
        run = self.run_results
        time = run.series("time_s")
        force = run.series("dem_pile_force_n")
        self.assertEqual(time.unit, "s")
        self.assertEqual(force.unit, "N")
        self.assertEqual(len(time.values), len(force.values))
        self.assertGreater(len(time.values), 1)
        self.assertTrue(np.all(np.diff(time.values) > 0))
        for name in run.series_names:
            self.assertIsInstance(run.unit(name), str)

    def test_every_column_has_its_declared_unit(self):
        """Both servers declare their units (SPEC.md §6.3): no column is left to a
        guess, and the name suffixes agree with what was declared."""
        run = self.run_results
        rows = len(run.series("time_s").values)
        suffix_units = {"_pa": "Pa", "_n": "N", "_m": "m", "_nm": "N m", "_j": "J", "_w": "W", "_s": "s", "_n_s": "N s"}
        for name in run.series_names:
            series = run.series(name)
            with self.subTest(column=name):
                self.assertFalse(series.unit_guessed)
                self.assertEqual(series.values.shape[0], rows)
                for suffix in sorted(suffix_units, key=len, reverse=True):  # the longest match: _n_s before _s
                    if name.endswith(suffix):
                        self.assertEqual(series.unit, suffix_units[suffix])
                        break

    def test_wall_force_is_a_vector_per_exchange(self):
        run = self.run_results
        rows = len(run.series("time_s").values)
        for name, unit in (("dem_wall_floor_force_n", "N"), ("dem_wall_floor_moment_nm", "N m")):
            series = run.series(name)
            self.assertEqual(series.values.shape, (rows, 3))
            self.assertEqual(series.unit, unit)
            self.assertTrue(np.all(np.isfinite(series.values)))

    def test_snapshots_of_both_sides(self):
        run = self.run_results
        self.assertIn("dem", run.roles)
        self.assertIn("continuum", run.roles)
        for role in ("dem", "continuum"):
            snaps = run.snapshots(role)
            self.assertGreaterEqual(len(snaps), 2)  # the first and the last at least
            self.assertLessEqual(snaps[0].time, snaps[-1].time)
            self.assertTrue(snaps[-1].arrays)
            for array in snaps[-1].arrays.values():
                self.assertIsInstance(array, np.ndarray)


if __name__ == "__main__":
    unittest.main(argv=sys.argv[:1])
