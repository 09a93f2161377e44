#!/usr/bin/env python3
"""Tests of tools/report.py (./vc report), without running any scenario:

- docs/results.md is exactly the page tools/report.py renders from
  docs/results.json, so no figure on it was typed by hand;
- every figure the record names exists under docs/, and every item's scenario
  is a shipped file;
- the stress-strain measure on a results file built here, with closed-form
  curves: peaks, strain at the peak, initial stiffness and their spread.

    test_report.py        (CTest: exit code 77 = skipped when numpy, h5py or matplotlib are missing)
"""
import json
import os
import sys
import tempfile
import unittest

from dfc_test_support import require_modules

require_modules("numpy", "h5py", "matplotlib")

import h5py  # noqa: E402
import numpy as np  # noqa: E402

ROOT = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir, os.pardir))
sys.path.insert(0, os.path.join(ROOT, "tools"))
import report  # noqa: E402

STRING = h5py.string_dtype("utf-8")


def write_curve(path, peak_pa, stiffness_pa):
    """A compression test whose axial stress rises linearly at `stiffness_pa` to `peak_pa`, then falls."""
    os.makedirs(os.path.dirname(path), exist_ok=True)
    strain_at_peak = peak_pa / stiffness_pa
    strain = np.linspace(0.0, 2.0 * strain_at_peak, 41)  # sample 20 is the peak
    stress = np.where(strain <= strain_at_peak, stiffness_pa * strain, peak_pa - 0.5 * stiffness_pa * (strain - strain_at_peak))
    with h5py.File(path, "w") as f:
        f.attrs.create("format", "dfc-results-1", dtype=STRING)
        series = f.create_group("timeseries")
        series.attrs.create("columns", json.dumps(["dem_axial_strain", "dem_axial_stress_pa"]), dtype=STRING)
        for name, values, unit in (("dem_axial_strain", strain, "1"), ("dem_axial_stress_pa", stress, "Pa")):
            series.create_dataset(name, data=values).attrs.create("unit", unit, dtype=STRING)


class Page(unittest.TestCase):
    def test_results_page_is_the_rendering_of_the_record(self):
        with open(report.PAGE) as f:
            page = f.read()
        self.assertEqual(page, report.render_page(report.load_record()),
                         "docs/results.md differs from what tools/report.py renders from docs/results.json: "
                         "edit neither by hand; rerun ./vc report (or ./vc report --page-only after a change of the tool)")

    def test_every_recorded_figure_exists_and_every_scenario_is_shipped(self):
        for name, entry in report.load_record().items():
            self.assertIn(name, {item.name for item in report.ITEMS}, f"the record holds an item the tool no longer has: {name}")
            if entry["figure"]:
                self.assertTrue(os.path.exists(os.path.join(ROOT, "docs", entry["figure"])), entry["figure"])
        for item in report.ITEMS:
            if item.scenario:
                self.assertTrue(os.path.exists(os.path.join(ROOT, item.scenario)), item.scenario)


class StressStrain(unittest.TestCase):
    def test_peaks_stiffness_and_spread_of_two_variants(self):
        with tempfile.TemporaryDirectory() as folder:
            with open(os.path.join(folder, "scenario.json"), "w") as f:
                json.dump({"variants": [{"label": "S1"}, {"label": "S2"}]}, f)
            write_curve(os.path.join(folder, "S1", "results.h5"), 700e3, 1.4e9)
            write_curve(os.path.join(folder, "S2", "results.h5"), 630e3, 1.26e9)
            item = report.Item("probe", "probe", "probe", "0")
            rows, summary, runs = report.stress_strain(item, folder)
        self.assertEqual([r["run"] for r in rows], ["S1", "S2"])
        self.assertEqual([r["peak_kpa"] for r in rows], [700.0, 630.0])
        # Linear below 30 % of the peak, so the least-squares slope is the stiffness (to round-off).
        self.assertEqual([r["stiffness_mpa"] for r in rows], [1400.0, 1260.0])
        self.assertEqual([r["strain_at_peak"] for r in rows], [5e-4, 5e-4])
        # (700 - 630) / 665 = 10.5 %, the same for the stiffness.
        self.assertEqual(summary, ["spread (max − min)/mean of the peaks 10.5 %, of the initial stiffnesses 10.5 %"])
        self.assertEqual(len(runs), 2)


if __name__ == "__main__":
    unittest.main()
