#!/usr/bin/env python3
"""The generated body at any g-level (docs/dem_generation.md, "Changing the g-level").

Runs the small generation scenarios of both bonded rocks, the chalk
(damage_bond, tests/e2e/scenarios/centrifuge_generation_small.json) and the
soft rock (soft_bond, centrifuge_generation_softbond_small.json), with only
gravity.g_level and the REV's seed changed, writes the profiles with
tools/stress_profiles.py and checks:

  - every generation converges and the coupled run reaches its equilibrium;
  - the REV takes the same number of steps at every g-level (its unbonded
    stage runs at the installation stress, its bonded one is elastic);
  - the profile divided by gamma z is the same at every g-level: the body is
    the same state scaled (what failed: sigma_h +45 % at 10 g, +860 % at 1 g);
  - the chalk's interior REV-cell slices are within 10 % of gamma z and
    K0 gamma z (the small core's wall carries part of its weight: the 5 %
    of the generation tests holds on some packings, not all; §9 of
    docs/dem_generation.md).

    test_generation_glevels.py COUPLER SOURCE_DIR OUT_DIR [--quick]
        --quick: the chalk, one packing, at 10 and 100 g (the default suite);
        without it: both rocks, two packings each, at 1, 10, 50, 100 and 200 g
        (ctest python.generation_glevels, label e2e, about 25 s on 2 cores)
        (CTest: exit code 77 = skipped when numpy or h5py are missing)
"""
import contextlib
import io
import json
import os
import shutil
import subprocess
import sys
import unittest
from concurrent.futures import ThreadPoolExecutor

from dfc_test_support import require_modules

require_modules("numpy", "h5py")

import h5py  # noqa: E402
import numpy as np  # noqa: E402

COUPLER, SOURCE, OUT = sys.argv[1:4] if len(sys.argv) >= 4 else (None, None, None)
QUICK = "--quick" in sys.argv
sys.path.insert(0, os.path.join(SOURCE or ".", "tools"))
import stress_profiles  # noqa: E402

SCENARIOS = {"chalk": "tests/e2e/scenarios/centrifuge_generation_small.json",
             "soft": "tests/e2e/scenarios/centrifuge_generation_softbond_small.json"}
if QUICK:
    CASES = [("chalk", 5, g) for g in (10, 100)]
else:
    CASES = [(rock, seed, g) for rock, seeds in (("chalk", (5, 6)), ("soft", (1, 2))) for seed in seeds for g in (1, 10, 50, 100, 200)]
REFERENCE_G = 100  # the g-level the scenarios ship with


def run_case(case):
    """Runs one case; returns its folder (results.h5 inside) and the coupler's output."""
    rock, seed, g = case
    name = f"{rock}_s{seed}_g{g}"
    folder = os.path.join(OUT, name)
    shutil.rmtree(folder, ignore_errors=True)
    scenario = os.path.join(OUT, name + ".json")
    base = os.path.relpath(os.path.join(SOURCE, SCENARIOS[rock]), OUT)
    with open(scenario, "w") as f:
        json.dump({"include": base, "gravity": {"g_level": g},
                   "participants": {"dem": {"config": {"particles": {"rev": {"seed": seed}}}}}}, f)
    run = subprocess.run([COUPLER, "run", scenario, "--out", folder, "--no-progress"], capture_output=True, text=True)
    return folder, run.returncode, run.stdout + run.stderr


class GenerationAtAnyGLevel(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        os.makedirs(OUT, exist_ok=True)
        with ThreadPoolExecutor(max_workers=2) as pool:  # each run is three processes, the DEM one busy
            cls.runs = dict(zip(CASES, pool.map(run_case, CASES)))
        cls.profiles = {}
        for case, (folder, status, _) in cls.runs.items():
            results = os.path.join(folder, "results.h5")
            if status != 0 or not os.path.exists(results):
                continue
            with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(io.StringIO()):
                stress_profiles.main([results, "--png", os.path.join(folder, "profiles.png")])
            with h5py.File(results, "r") as f:
                p = f["profiles"]
                gen = json.loads(f.attrs["versions"])["dem"]["configured"]["generation"]
                cls.profiles[case] = {
                    "summary": json.loads(f.attrs["summary"]),
                    "rev_steps": gen["rev_steps"],
                    "cell": {k: p[k][()] for k in ("sigma_v_pa", "sigma_h_pa", "sigma_v_theory_pa", "sigma_h_theory_pa")},
                    "thin": {k: p["thin"][k][()] for k in ("depth_m", "sigma_v_pa", "sigma_h_pa", "interior")},
                    "gamma": gen["unit_weight_n_m3"], "k0": gen["k0"],
                }

    def test_every_generation_converges_and_reaches_equilibrium(self):
        for case, (_, status, output) in self.runs.items():
            with self.subTest(case=case):
                self.assertEqual(status, 0, output[-3000:])
                self.assertTrue(self.profiles[case]["summary"].get("equilibrium_reached"), self.profiles[case]["summary"])

    def test_the_rev_takes_the_same_steps_at_every_g_level(self):
        # Measured: the same count to the step at every g-level (45 902 and
        # 32 902 for the chalk's packings, 12 502 and 10 602 for the soft
        # rock's); 2 % leaves room for a last check interval of the servo.
        for rock, seed in {(r, s) for r, s, _ in CASES}:
            steps = [self.profiles[(rock, seed, g)]["rev_steps"] for r, s, g in CASES if (r, s) == (rock, seed) and (r, s, g) in self.profiles]
            with self.subTest(rock=rock, seed=seed):
                self.assertEqual(len(steps), len([c for c in CASES if c[:2] == (rock, seed)]))
                self.assertLessEqual(max(steps), 1.02 * min(steps), steps)

    def test_the_profile_scales_with_the_g_level(self):
        # sigma / (gamma z) per thin slice against the same packing at 100 g.
        # Measured: within 0.1 % from 1 to 100 g; at 200 g within 1.4 %
        # (the bonds carry twice the stresses of 100 g and a few of the body's
        # yield during the equilibration). 2.5 % would still have caught the
        # fault this checks: +45 % at 10 g and +860 % at 1 g on one packing.
        for case, prof in self.profiles.items():
            rock, seed, g = case
            ref = self.profiles.get((rock, seed, REFERENCE_G))
            if g == REFERENCE_G or ref is None:
                continue
            for key, k0 in (("sigma_v_pa", 1.0), ("sigma_h_pa", prof["k0"])):
                t, r = prof["thin"], ref["thin"]
                inner = t["interior"]
                mine = t[key][inner] / (k0 * prof["gamma"] * t["depth_m"][inner])
                theirs = r[key][inner] / (k0 * ref["gamma"] * r["depth_m"][inner])
                with self.subTest(case=case, stress=key):
                    np.testing.assert_allclose(mine, theirs, rtol=0.0, atol=0.025)

    def test_the_chalks_interior_rev_cell_slices_are_near_the_theory(self):
        # Not the 5 % of tests/e2e/generation_test.cpp: the small core (11
        # diameters across) hangs 10-20 % of its weight on the coupling wall
        # by friction, which the g-level does not change. Measured over ten
        # REVs (seeds 5-14, 100 g; docs/dem_generation.md §9): sigma_v -0.3
        # to -9.3 %, sigma_h -4.5 to +6.2 %; seeds 5 and 6 here -0.3..+0.5 and
        # -7.2..-6.8 % in sigma_v at every g-level. 10 % still catches the
        # fault of the issue (+45 % at 10 g, +860 % at 1 g). The soft rock's
        # REV cell (18 mm at S = 3) fits twice in its 30 mm core, so it has no
        # interior slice of that height; its thin slices are checked for
        # scaling above.
        for case, prof in self.profiles.items():
            if case[0] != "chalk":
                continue
            c = prof["cell"]
            for key, theory in (("sigma_v_pa", "sigma_v_theory_pa"), ("sigma_h_pa", "sigma_h_theory_pa")):
                with self.subTest(case=case, stress=key):
                    np.testing.assert_allclose(c[key][1:-1], c[theory][1:-1], rtol=0.10)

    def test_a_run_not_ended_gets_its_figure_but_no_group(self):
        # stress_profiles.py on a file whose run still goes on (no summary:
        # the coupler holds it open unlocked) must leave it alone: a second
        # writer corrupted such a file. A finished run's copy, its end undone.
        case = next(iter(self.profiles), None)
        self.assertIsNotNone(case, "no run finished")
        folder = os.path.join(OUT, "not_ended")
        os.makedirs(folder, exist_ok=True)
        results = os.path.join(folder, "results.h5")
        shutil.copyfile(os.path.join(self.runs[case][0], "results.h5"), results)
        with h5py.File(results, "r+") as f:
            del f["profiles"]
            del f.attrs["summary"]
        png = os.path.join(folder, "profiles.png")
        err = io.StringIO()
        with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(err):
            status = stress_profiles.main([results, "--png", png])
        self.assertEqual(status, 0)
        self.assertTrue(os.path.isfile(png))
        self.assertIn("has not ended", err.getvalue())
        with h5py.File(results, "r") as f:
            self.assertNotIn("profiles", f)


if __name__ == "__main__":
    unittest.main(argv=sys.argv[:1])
