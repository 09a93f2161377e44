#!/usr/bin/env python3
"""Tests of tools/resolution_study.py without running the DEM:

- the verdict: converged only where the two finest resolutions' means differ
  by no more than the larger half-range over packings;
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
