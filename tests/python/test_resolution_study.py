#!/usr/bin/env python3
"""Tests of tools/resolution_study.py without running the DEM:

- the verdict: converged only where the two finest resolutions' means differ
  by no more than the larger half-range over packings;
- a resolution finished over two machines: the earlier summary's packings
  merged with the runs present as if all were present;
- `run` on a stand-in coupler (a script that records its arguments): a new
  variant is started with its expanded scenario, one with a checkpoint is
  resumed, one with DONE is skipped, a failed run gets no DONE and makes the
  exit status 1, and --labels picks variants.

    test_resolution_study.py   (CTest: exit code 77 = skipped when numpy is missing)
"""
import json
import os
import stat
import sys
import tempfile
import types
import unittest

from dfc_test_support import require_modules

require_modules("numpy")

ROOT = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir, os.pardir))
sys.path.insert(0, os.path.join(ROOT, "tools"))
import resolution_study  # noqa: E402

FAKE_COUPLER = r'''#!/usr/bin/env python3
import json, os, sys
log = os.path.join(os.path.dirname(os.path.abspath(__file__)), "calls.txt")
with open(log, "a") as f:
    f.write(" ".join(sys.argv[1:]) + "\n")
if sys.argv[1] == "expand":
    print(json.dumps([{"name": "study_" + l, "output": {"directory": "results/study/" + l}, "marker": l} for l in ("a", "b", "c")]))
elif sys.argv[1] == "run":
    folder = sys.argv[sys.argv.index("--out") + 1] if "--out" in sys.argv else sys.argv[sys.argv.index("--resume") + 1]
    os.makedirs(folder, exist_ok=True)
    sys.exit(3 if folder.endswith("/c") else 0)
'''


class Verdict(unittest.TestCase):
    def test_a_difference_inside_the_scatter_is_converged(self):
        fine = {"mean": 10.0, "min": 8.0, "max": 12.0, "n": 3}     # half-range 2
        coarse = {"mean": 11.5, "min": 11.0, "max": 12.0, "n": 3}  # half-range 0.5
        self.assertEqual(resolution_study.verdict(fine, coarse)["verdict"], "converged")

    def test_a_difference_beyond_the_scatter_is_not(self):
        fine = {"mean": 10.0, "min": 9.0, "max": 11.0, "n": 2}
        coarse = {"mean": 13.0, "min": 12.0, "max": 14.0, "n": 2}
        result = resolution_study.verdict(fine, coarse)
        self.assertEqual(result["verdict"], "not converged")
        self.assertAlmostEqual(result["difference"], 3.0)
        self.assertAlmostEqual(result["scatter"], 1.0)

    def test_one_packing_is_not_enough(self):
        self.assertEqual(resolution_study.verdict({"mean": 1.0}, {"mean": 1.0, "min": 0.0, "max": 2.0, "n": 3})["verdict"], "not enough runs")
        one = {"mean": 1.0, "min": 1.0, "max": 1.0, "n": 1}  # what spread() gives for a single run
        self.assertEqual(resolution_study.verdict(one, {"mean": 1.0, "min": 0.0, "max": 2.0, "n": 3})["verdict"], "not enough runs")


class VerdictsByGLevel(unittest.TestCase):
    """Each g-level is judged on its own two finest resolutions: a finer one with
    only some g-levels finished decides those, the rest keep the coarser pair."""

    def test_each_g_level_compares_its_own_two_finest(self):
        def level(mean):
            return {key: {"mean": mean, "min": mean - 1.0, "max": mean + 1.0, "n": 3} for key, _, _ in resolution_study.MEASURES}
        resolutions = {4.0: {"g_levels": {"1": level(10.0), "10": level(13.0)}},
                       3.0: {"g_levels": {"1": level(17.0), "10": level(13.5)}},
                       2.0: {"g_levels": {"1": level(17.5)}}}
        verdicts = resolution_study.verdicts_by_g_level(resolutions, [4.0, 3.0, 2.0])
        self.assertEqual((verdicts["1"]["finest"], verdicts["1"]["next"]), ("2", "3"))
        self.assertEqual((verdicts["10"]["finest"], verdicts["10"]["next"]), ("3", "4"))
        self.assertEqual(verdicts["1"]["mean_force_n_0.25_to_1D"]["verdict"], "converged")       # 0.5 apart, half-range 1
        self.assertEqual(verdicts["10"]["mean_force_n_0.25_to_1D"]["verdict"], "converged")
        resolutions[2.0]["g_levels"]["1"] = level(25.0)
        verdicts = resolution_study.verdicts_by_g_level(resolutions, [4.0, 3.0, 2.0])
        self.assertEqual(verdicts["1"]["mean_force_n_0.25_to_1D"]["verdict"], "not converged")   # 8 apart
        self.assertEqual(resolution_study.verdicts_by_g_level({3.0: resolutions[3.0]}, [3.0]), {})
        one = level(40.0)
        for measure in one.values():
            measure["n"] = 1
        resolutions[2.0]["g_levels"]["10"] = one  # one packing: no scatter, so 3 against 4 still judges 10 g
        verdicts = resolution_study.verdicts_by_g_level(resolutions, [4.0, 3.0, 2.0])
        self.assertEqual((verdicts["10"]["finest"], verdicts["10"]["next"]), ("3", "4"))


class EarlierResolutions(unittest.TestCase):
    """A summary keeps the resolutions of an earlier one whose runs are gone:
    they come back with their curves, keyed by S; one without its curves file
    cannot be redrawn and is not kept."""

    def test_kept_with_curves_and_dropped_without(self):
        with tempfile.TemporaryDirectory() as out:
            with open(os.path.join(out, "resolution_summary.json"), "w") as f:
                json.dump({"resolutions": {"4": {"scenario": "s4", "scale_factor": 4.0}, "3": {"scenario": "s3", "scale_factor": 3.0}}}, f)
            with open(os.path.join(out, "curves_S4.json"), "w") as f:
                json.dump({"1": {"mean_n": [1.0, 2.0]}}, f)
            kept = resolution_study.earlier_resolutions(out)
            self.assertEqual(sorted(kept), [4.0])
            self.assertEqual(kept[4.0]["scenario"], "s4")
            self.assertEqual(kept[4.0]["curves"]["1"]["mean_n"], [1.0, 2.0])
            self.assertEqual(resolution_study.earlier_resolutions(os.path.join(out, "none")), {})


class MergedResolutions(unittest.TestCase):
    """A resolution finished over two machines: the earlier summary's packings
    (runs gone) and the runs present are merged g-level by g-level, exactly as if
    all runs were present (mean weighted by the counts, extremes of both); a packing
    run again replaces the earlier aggregate holding it."""

    @staticmethod
    def entry(values_by_g, curve_by_g):
        def spread(values):
            return {"mean": sum(values) / len(values), "min": min(values), "max": max(values), "n": len(values)}
        every = [v for values in values_by_g.values() for v in values.values()]
        return {"scale_factor": 2.0, "mean_diameter_m": 0.002, "particles": spread([3800.0] * len(every)),
                "dem_steps": spread([1.8e6] * len(every)), "wall_time_s": spread([float(v) for v in every]),
                "g_levels": {g: {"packings": sorted(values), "mean_force_n_0.25_to_1D": spread(list(values.values())),
                                 "inertial_number": {"median": 1e-4 * len(values), "max": 1e-3}}
                             for g, values in values_by_g.items()},
                "curves": {g: {"h_over_d": [0.0, 1.0], "packings": len(values), "mean_n": [sum(c) / len(c) for c in zip(*curve_by_g[g])],
                               "min_n": [min(c) for c in zip(*curve_by_g[g])], "max_n": [max(c) for c in zip(*curve_by_g[g])]}
                           for g, values in values_by_g.items()}}

    def test_disjoint_packings_merge_as_if_all_runs_were_present(self):
        earlier = self.entry({"1": {1: 30.0, 2: 36.0}, "100": {1: 64.0}}, {"1": [[0.0, 30.0], [2.0, 36.0]], "100": [[1.0, 64.0]]})
        fresh = self.entry({"100": {2: 50.0}, "10": {1: 40.0}}, {"100": [[3.0, 50.0]], "10": [[0.0, 40.0]]})
        merged = resolution_study.merge_resolution(earlier, fresh, 2.0)
        self.assertEqual(sorted(merged["g_levels"]), ["1", "10", "100"])
        self.assertEqual(merged["g_levels"]["1"], earlier["g_levels"]["1"])        # only the earlier summary has it
        level = merged["g_levels"]["100"]
        self.assertEqual(level["packings"], [1, 2])
        force = level["mean_force_n_0.25_to_1D"]
        self.assertEqual((force["mean"], force["min"], force["max"], force["n"]), (57.0, 50.0, 64.0, 2))
        self.assertEqual(level["inertial_number"]["median"], 1e-4)                 # the larger of the parts' medians
        curve = merged["curves"]["100"]
        self.assertEqual((curve["packings"], curve["mean_n"], curve["min_n"], curve["max_n"]), (2, [2.0, 57.0], [1.0, 50.0], [3.0, 64.0]))
        self.assertEqual(merged["particles"]["n"], 5)                                # 2 + 1 earlier runs kept, 2 fresh

    def test_a_packing_run_again_replaces_the_earlier_aggregate(self):
        earlier = self.entry({"1": {1: 30.0, 2: 36.0}}, {"1": [[0.0, 30.0], [2.0, 36.0]]})
        fresh = self.entry({"1": {2: 33.0, 3: 31.0}}, {"1": [[0.0, 33.0], [0.0, 31.0]]})
        merged = resolution_study.merge_resolution(earlier, fresh, 2.0)
        self.assertEqual(merged["g_levels"]["1"], fresh["g_levels"]["1"])
        self.assertEqual(merged["particles"]["n"], 2)

    def test_a_run_already_summarised_is_recognised_and_not_merged_again(self):
        # A summary committed with g100_p2 in it, and the runs folder given whole
        # again: that run would replace the group of packings 1 and 2 it belongs to.
        run = types.SimpleNamespace(g_level=100.0, seed=2, summary={"wall_time_s": 3336.343885049, "dem_steps": 1810000}, path="/r/g100_p2/results.h5", label="g100_p2")
        again = types.SimpleNamespace(g_level=100.0, seed=2, summary={"wall_time_s": 3401.5, "dem_steps": 1810000}, path="/r/g100_p2/results.h5", label="g100_p2")
        other_g = types.SimpleNamespace(g_level=10.0, seed=2, summary=run.summary, path="/r/g10_p2/results.h5", label="g10_p2")
        earlier = {"g_levels": {"100": {"packings": [1, 2], "runs": {"1": "elsewhere", "2": resolution_study.run_fingerprint(run)}}}}
        self.assertEqual(resolution_study.already_summarised([run, again, other_g], earlier), [run])
        self.assertEqual(resolution_study.already_summarised([run], None), [])
        # Merged groups keep the runs of both parts.
        merged = resolution_study.merge_level({"packings": [1], "runs": {"1": "a"}}, {"packings": [2], "runs": {"2": "b"}})
        self.assertEqual(merged["runs"], {"1": "a", "2": "b"})

    def test_a_missing_point_of_one_band_is_the_others(self):
        a = {"h_over_d": [0.0, 1.0], "packings": 1, "mean_n": [1.0, float("nan")], "min_n": [1.0, float("nan")], "max_n": [1.0, float("nan")]}
        b = {"h_over_d": [0.0, 1.0], "packings": 2, "mean_n": [4.0, 5.0], "min_n": [3.0, 4.0], "max_n": [5.0, 6.0]}
        merged = resolution_study.merge_curve(a, b)
        self.assertEqual((merged["mean_n"], merged["min_n"], merged["max_n"]), ([3.0, 5.0], [1.0, 4.0], [5.0, 6.0]))


class Run(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.bin = os.path.join(self.tmp.name, "bin")
        os.makedirs(self.bin)
        coupler = os.path.join(self.bin, "coupler")
        with open(coupler, "w") as f:
            f.write(FAKE_COUPLER)
        os.chmod(coupler, stat.S_IRWXU)
        self.scenario = os.path.join(self.tmp.name, "study.json")
        with open(self.scenario, "w") as f:
            json.dump({"name": "study"}, f)
        self.runs = os.path.join(self.tmp.name, "runs")

    def tearDown(self):
        self.tmp.cleanup()

    def calls(self):
        with open(os.path.join(self.bin, "calls.txt")) as f:
            return [line.split() for line in f if line.startswith("run")]

    def run_tool(self, *extra):
        return resolution_study.main(["run", self.scenario, "--runs", self.runs, "--bin", self.bin, "--jobs", "1", *extra])

    def test_start_resume_skip_and_failure(self):
        folder = os.path.join(self.runs, "study")
        os.makedirs(os.path.join(folder, "a"))
        open(os.path.join(folder, "a", "DONE"), "w").close()
        os.makedirs(os.path.join(folder, "b", "checkpoint"))
        self.assertEqual(self.run_tool(), 1)  # c fails
        calls = {call[-2] if "--resume" not in call else call[call.index("--resume") + 1]: call for call in self.calls()}
        self.assertNotIn(os.path.join(folder, "a"), calls, "a finished variant was run again")
        self.assertIn("--resume", calls[os.path.join(folder, "b")])
        started = [c for c in self.calls() if "--out" in c]
        self.assertEqual(len(started), 1)
        self.assertEqual(started[0][started[0].index("--out") + 1], os.path.join(folder, "c"))
        with open(os.path.join(folder, "c.json")) as f:
            self.assertEqual(json.load(f)["marker"], "c")  # the expanded variant, not the whole scenario
        self.assertTrue(os.path.isfile(os.path.join(folder, "b", "DONE")))
        self.assertFalse(os.path.isfile(os.path.join(folder, "c", "DONE")))

    def test_labels_pick_the_variants(self):
        self.assertEqual(self.run_tool("--labels", "b"), 0)
        self.assertEqual([c[-2] for c in self.calls()], [os.path.join(self.runs, "study", "b")])


if __name__ == "__main__":
    unittest.main()
