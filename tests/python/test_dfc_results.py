#!/usr/bin/env python3
"""Unit tests of python/dfc_results: a small file built here in the layout the
coupler's ResultsWriter uses (coupler/src/results_writer.cpp), the variants of
one scenario side by side, and, when DFC_RESULTS_SAMPLE names it, the sample
file written by the real ResultsWriter (tests/coupler/results_sample_main.cpp).

    test_dfc_results.py        (CTest: exit code 77 = skipped when numpy or h5py are missing)
"""
import json
import os
import tempfile
import unittest

from dfc_test_support import require_modules

require_modules("numpy", "h5py")

import h5py  # noqa: E402
import numpy as np  # noqa: E402

import dfc_results  # noqa: E402

STRING = h5py.string_dtype("utf-8")  # the writer's attributes are variable-length UTF-8 strings


def write_results(path, name="pile", scale=1.0, summary=True):
    """A results file as the coupler writes it: root attributes, /timeseries with
    units (one of them guessed), a vector column and the declared column order,
    two snapshots of two roles."""
    os.makedirs(os.path.dirname(path), exist_ok=True)
    columns = ["step", "time_s", "dem_pile_force_n", "dem_axial_stress_pa", "interface_force_on_dem_z"]
    with h5py.File(path, "w") as f:
        f.attrs.create("scenario", json.dumps({"schema_version": 1, "name": name}), dtype=STRING)
        f.attrs.create("versions", json.dumps({"coupler": "test"}), dtype=STRING)
        f.attrs.create("created_utc", "2026-01-01T00:00:00Z", dtype=STRING)
        f.attrs.create("format", "dfc-results-1", dtype=STRING)
        if summary:
            f.attrs.create("summary", json.dumps({"rows": 4}), dtype=STRING)
        series = f.create_group("timeseries")
        series.attrs.create("columns", json.dumps(columns), dtype=STRING)
        units = {"step": "1", "time_s": "s", "dem_pile_force_n": "N", "dem_axial_stress_pa": "Pa"}
        for k, column in enumerate(columns):
            values = np.arange(4, dtype=float) * (k + 1) * scale
            if column == "interface_force_on_dem_z":
                values[:] = np.nan  # not applicable in this run: the coupler writes NaN
            dataset = series.create_dataset(column, data=values, maxshape=(None,), chunks=(1024,))
            if column in units:  # the last column has no unit attribute
                dataset.attrs.create("unit", units[column], dtype=STRING)
        series["step"].attrs.create("unit_source", "guessed from the name", dtype=STRING)
        floor = series.create_dataset("dem_wall_floor_force_n", data=np.arange(12, dtype=float).reshape(4, 3) * scale,
                                      maxshape=(None, 3), chunks=(1024, 3))
        floor.attrs.create("unit", "N", dtype=STRING)
        series.attrs.create("columns", json.dumps(columns + ["dem_wall_floor_force_n"]), dtype=STRING)
        snapshots = f.create_group("snapshots")
        for role, kind in (("dem", "particles"), ("continuum", "grid")):
            for index in range(2):
                group = snapshots.require_group(role).create_group(f"{index:06d}")
                group.attrs["step"] = np.int64(10 * index)
                group.attrs["time"] = 0.5 * index
                group.attrs.create("kind", kind, dtype=STRING)
                group.create_dataset("position", data=np.full((3, 3), index, dtype=float))
                group.create_dataset("id", data=np.arange(3, dtype=np.int64))
        f.create_group("xdmf").create_dataset("polyvertex_3", data=np.arange(3, dtype=np.int64))


class ResultsFileTest(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.path = os.path.join(self.tmp.name, "run", "results.h5")
        write_results(self.path)

    def tearDown(self):
        self.tmp.cleanup()

    def test_metadata(self):
        with dfc_results.open_results(self.path) as run:
            self.assertEqual(run.format, dfc_results.FORMAT)
            self.assertEqual(run.name, "pile")
            self.assertEqual(run.scenario["schema_version"], 1)
            self.assertEqual(run.versions, {"coupler": "test"})
            self.assertEqual(run.created_utc, "2026-01-01T00:00:00Z")
            self.assertEqual(run.summary, {"rows": 4})
            self.assertIsNone(run.failure)

    def test_folder_opens_its_results_file(self):
        with dfc_results.open_results(os.path.dirname(self.path)) as run:
            self.assertEqual(run.path, self.path)

    def test_series_names_in_recorded_order(self):
        with dfc_results.open_results(self.path) as run:
            self.assertEqual(run.series_names,
                             ["step", "time_s", "dem_pile_force_n", "dem_axial_stress_pa", "interface_force_on_dem_z",
                              "dem_wall_floor_force_n"])
            self.assertTrue(run.has_series("time_s"))
            self.assertFalse(run.has_series("nothing"))

    def test_series_with_units(self):
        with dfc_results.open_results(self.path) as run:
            force = run.series("dem_pile_force_n")
            stress = run.series("dem_axial_stress_pa")
            no_unit = run.series("interface_force_on_dem_z")
            everything = run.all_series()
            names = run.series_names
        self.assertEqual(force.name, "dem_pile_force_n")
        self.assertEqual(force.unit, "N")
        self.assertEqual(stress.unit, "Pa")
        self.assertEqual(no_unit.unit, "")
        np.testing.assert_array_equal(force.values, [0.0, 3.0, 6.0, 9.0])
        self.assertEqual(force.values.dtype, np.float64)
        self.assertTrue(np.isnan(no_unit.values).all())
        self.assertEqual(list(everything), names)
        self.assertEqual(everything["time_s"].unit, "s")
        self.assertEqual(run.path, self.path)

    def test_vector_series_has_a_row_per_exchange(self):
        with dfc_results.open_results(self.path) as run:
            floor = run.series("dem_wall_floor_force_n")
        self.assertEqual(floor.values.shape, (4, 3))
        self.assertEqual(floor.unit, "N")
        np.testing.assert_array_equal(floor.values[1], [3.0, 4.0, 5.0])

    def test_guessed_units_are_marked(self):
        with dfc_results.open_results(self.path) as run:
            self.assertTrue(run.series("step").unit_guessed)
            self.assertFalse(run.series("dem_pile_force_n").unit_guessed)

    def test_missing_series_names_those_present(self):
        with dfc_results.open_results(self.path) as run:
            with self.assertRaises(dfc_results.ResultsError) as raised:
                run.series("pile_force")
        self.assertIn("dem_pile_force_n", str(raised.exception))

    def test_snapshots_as_arrays(self):
        with dfc_results.open_results(self.path) as run:
            self.assertEqual(run.roles, ["continuum", "dem"])
            self.assertEqual(run.snapshot_count("dem"), 2)
            last = run.snapshot("dem", -1)
            every = run.snapshots("continuum")
        self.assertEqual((last.role, last.index, last.step, last.time, last.kind), ("dem", 1, 10, 0.5, "particles"))
        self.assertEqual(last.arrays["position"].shape, (3, 3))
        np.testing.assert_array_equal(last.arrays["position"], np.ones((3, 3)))
        self.assertEqual(last.arrays["id"].dtype, np.int64)
        self.assertEqual([s.kind for s in every], ["grid", "grid"])
        self.assertEqual([s.step for s in every], [0, 10])

    def test_missing_snapshots(self):
        with dfc_results.open_results(self.path) as run:
            with self.assertRaises(dfc_results.ResultsError):
                run.snapshots("fdm")
            with self.assertRaises(dfc_results.ResultsError):
                run.snapshot("dem", 5)

    def test_run_in_progress_has_no_summary(self):
        path = os.path.join(self.tmp.name, "going", "results.h5")
        write_results(path, summary=False)
        with dfc_results.open_results(path) as run:
            self.assertIsNone(run.summary)

    def test_groups_are_added_only_once_the_run_has_ended(self):
        # The coupler holds the file open without the HDF5 lock while the run
        # goes on; a tool writing into it then corrupted a run's records
        # ("bad heap free list"). Until an end attribute is there the file
        # must not even be opened for writing: its bytes stay as they were.
        going = os.path.join(self.tmp.name, "going", "results.h5")
        write_results(going, summary=False)
        with open(going, "rb") as handle:
            before = handle.read()
        self.assertIsNone(dfc_results.open_to_add_groups(going))
        with open(going, "rb") as handle:
            self.assertEqual(handle.read(), before)
        with dfc_results.open_results(going) as run:
            self.assertFalse(run.ended)
        for attribute in ("summary", "failure", "interrupted"):  # each is the coupler's last write before it closes
            path = os.path.join(self.tmp.name, attribute, "results.h5")
            write_results(path, summary=False)
            with h5py.File(path, "r+") as f:
                f.attrs.create(attribute, json.dumps("end"), dtype=STRING)
            with dfc_results.open_results(path) as run:
                self.assertTrue(run.ended, attribute)
            target = dfc_results.open_to_add_groups(path)
            self.assertIsNotNone(target, attribute)
            with target:
                target.create_group("derived")["x"] = np.arange(3.0)
            with h5py.File(path, "r") as f:
                self.assertEqual(list(f["derived/x"][()]), [0.0, 1.0, 2.0])
        with self.assertRaises(dfc_results.ResultsError):
            dfc_results.open_to_add_groups(os.path.join(self.tmp.name, "absent.h5"))

    def test_not_a_results_file(self):
        with self.assertRaises(dfc_results.ResultsError):
            dfc_results.open_results(os.path.join(self.tmp.name, "absent.h5"))
        text = os.path.join(self.tmp.name, "text.h5")
        with open(text, "w") as f:
            f.write("not HDF5")
        with self.assertRaises(dfc_results.ResultsError):
            dfc_results.open_results(text)


class VariantsTest(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.dir = self.tmp.name
        for k, label in enumerate(("S1", "S10", "S2")):
            write_results(os.path.join(self.dir, label, "results.h5"), name=f"ucs_{label}", scale=k + 1)
        os.makedirs(os.path.join(self.dir, "plots"))  # a folder without results is not a variant

    def tearDown(self):
        self.tmp.cleanup()

    def open_variants(self, **kwargs):
        runs = dfc_results.open_variants(self.dir, **kwargs)
        for run in runs.values():
            self.addCleanup(run.close)
        return runs

    def test_variants_by_label(self):
        runs = self.open_variants()
        self.assertEqual(list(runs), ["S1", "S10", "S2"])
        self.assertEqual(runs["S2"].name, "ucs_S2")
        self.assertEqual(runs["S10"].series("dem_pile_force_n").values[1], 6.0)

    def test_variants_in_scenario_order(self):
        scenario = os.path.join(self.dir, "scenario.json")
        with open(scenario, "w") as f:
            json.dump({"variants": [{"label": "S1", "patch": {}}, {"label": "S2", "patch": {}},
                                    {"label": "S10", "patch": {}}]}, f)
        self.assertEqual(list(self.open_variants(scenario=scenario)), ["S1", "S2", "S10"])

    def test_variant_missing_from_folder(self):
        scenario = os.path.join(self.dir, "scenario.json")
        with open(scenario, "w") as f:
            json.dump({"variants": [{"label": "S100", "patch": {}}]}, f)
        with self.assertRaises(dfc_results.ResultsError) as raised:
            dfc_results.open_variants(self.dir, scenario=scenario)
        self.assertIn("S100", str(raised.exception))

    def test_folder_without_variants(self):
        with self.assertRaises(dfc_results.ResultsError):
            dfc_results.open_variants(os.path.join(self.dir, "plots"))


@unittest.skipUnless(os.environ.get("DFC_RESULTS_SAMPLE"), "DFC_RESULTS_SAMPLE not set")
class WriterSampleTest(unittest.TestCase):
    """The file written by the C++ ResultsWriter itself (results_sample)."""

    def test_sample(self):
        with dfc_results.open_results(os.environ["DFC_RESULTS_SAMPLE"]) as run:
            self.assertEqual(run.format, dfc_results.FORMAT)
            self.assertEqual(run.name, "sample")
            self.assertEqual(run.summary, {"rows": 60})
            self.assertEqual(run.series_names[:3], ["step", "time_s", "pile_displacement_m"])
            self.assertEqual(run.series("time_s").unit, "s")
            self.assertEqual(run.series("pile_force_n").unit, "N")
            self.assertEqual(run.series("ufr_dem").unit, "")
            self.assertEqual(len(run.series("step").values), 60)
            self.assertEqual(run.roles, ["dem", "fdm"])
            snap = run.snapshot("dem", 2)
            self.assertEqual((snap.step, snap.kind), (40, "particles"))
            self.assertEqual(snap.arrays["particle_position"].shape, (10, 3))
            self.assertEqual(snap.arrays["particle_id"].dtype, np.int64)
            self.assertEqual(run.snapshot("fdm", 0).arrays["zone_nodes"].shape[1], 8)


if __name__ == "__main__":
    unittest.main()
