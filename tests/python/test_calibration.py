#!/usr/bin/env python3
"""Tests of ./vc calibrate (tools/calibrate.py, tools/calibration/) that run no DEM:

- every file of scenarios/calibration/ passes the check;
- ./vc calibrate --help, and the exit status of a bad file;
- bad calibration files fail with an error that names the key and the fix
  (unknown law, unknown parameter, a bound outside the law's declared bounds,
  missing targets, a target no experiment measures, too few packings);
- what is read back from a periodic REV (UCS as the peak deviator, Young's
  modulus, Poisson's ratio, a run without a peak) and the scenario of a
  triaxial experiment on one packing;
- the dimensionless scaling step (moduli, strengths, the damage bond's
  critical displacements, clipping to the bounds);
- the cache key (one bit of one parameter changes it) and the log-derivatives;
- the whole calibration against tests/python/fake_coupler.py (a closed-form
  stand-in for the coupler): converges, writes every output, a calibration
  killed after some runs continues without rerunning any of them, and runs
  side by side (--jobs) give the same calibration.

    test_calibration.py        (CTest: exit code 77 = skipped when numpy, scipy, h5py or matplotlib are missing)
"""
import contextlib
import glob
import io
import json
import math
import os
import shutil
import subprocess
import sys
import tempfile
import unittest

from dfc_test_support import require_modules

require_modules("numpy", "scipy", "h5py", "matplotlib")

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.abspath(os.path.join(HERE, os.pardir, os.pardir))
sys.path.insert(0, os.path.join(ROOT, "tools"))

import calibrate  # noqa: E402
from calibration import gauss_newton, scaling, search, sensitivity  # noqa: E402
from calibration.calibration_file import CalibrationError, FreeParameter, Target, read_targets  # noqa: E402
from calibration.evaluation_cache import run_key  # noqa: E402
from calibration.evaluation import TENSION, UNCONFINED, Evaluator, experiments_needed, target_value  # noqa: E402
from calibration.experiments import measure, measure_tension  # noqa: E402

FAKE_COUPLER = os.path.join(HERE, "fake_coupler.py")


def softbond_file(**changes):
    """A valid soft-bond calibration on scenarios/ucs_softbond.json, with top-level keys replaced."""
    spec = {
        "name": "test", "law": "soft_bond",
        "sample": {"scenario": os.path.join(ROOT, "scenarios", "ucs_softbond.json"), "packings": [3, 4, 5]},
        "free": {"sb_emod_pa": {"start": 1.4e9, "min": 1e8, "max": 1e11},
                 "sb_coh_pa": {"start": 9e5, "min": 1e4, "max": 1e8}},
        "tied": {"sb_ten_pa": {"to": "sb_coh_pa", "ratio": 1.0}},
        "targets": {"ucs_pa": {"value": 5e5, "tolerance": 0.02}, "young_modulus_pa": {"value": 1.4e9, "tolerance": 0.02}},
        "search": {"max_evaluations": 30},
    }
    spec.update(changes)
    return spec


def prepared(spec):
    """calibrate.prepare of a calibration file holding SPEC (paths in it absolute)."""
    with tempfile.TemporaryDirectory() as folder:
        path = os.path.join(folder, "c.json")
        with open(path, "w") as f:
            json.dump(spec, f)
        return calibrate.prepare(path)


def read_json(path):
    with open(path) as f:
        return json.load(f)


class Folder(unittest.TestCase):
    def setUp(self):
        self.folder = tempfile.mkdtemp(prefix="dfc_calibration_")

    def tearDown(self):
        shutil.rmtree(self.folder, ignore_errors=True)

    def write(self, spec, name="calibration.json"):
        path = os.path.join(self.folder, name)
        with open(path, "w") as f:
            json.dump(spec, f)
        return path


class BadInput(Folder):
    def assert_error(self, spec, key, *words):
        with self.assertRaises(CalibrationError) as caught:
            calibrate.prepare(self.write(spec))
        message = str(caught.exception)
        self.assertTrue(message.startswith(key), f"the error should start with the key {key}: {message}")
        for word in words:
            self.assertIn(word, message)

    def test_a_valid_file_passes(self):
        calibration, sample, contact = calibrate.prepare(self.write(softbond_file()))
        self.assertEqual(contact["law"], "soft_bond")
        self.assertEqual(contact["sb_fa_deg"], 32)  # the rest from the sample's material file
        self.assertFalse(sample.periodic)

    def test_every_shipped_calibration_file_passes_the_check(self):
        files = sorted(glob.glob(os.path.join(ROOT, "scenarios", "calibration", "*.json")))
        self.assertTrue(files)
        for path in files:
            calibrate.prepare(path)

    def test_unknown_law_lists_the_bonded_laws(self):
        self.assert_error(softbond_file(law="soft_bonds"), "law", "unknown bonded law 'soft_bonds'", "damage_bond", "linear_pbond")

    def test_unknown_parameter_lists_the_laws_parameters(self):
        spec = softbond_file()
        spec["free"]["sb_strength_pa"] = {"start": 1, "min": 0.5, "max": 2}
        self.assert_error(spec, "free.sb_strength_pa", "unknown parameter 'sb_strength_pa'", "sb_coh_pa", "dem_server --help")
        self.assert_error(softbond_file(fixed={"emod_pa": 1e9}), "fixed.emod_pa", "unknown parameter")

    def test_bound_outside_the_declared_bounds(self):
        spec = softbond_file()
        spec["free"]["sb_cut"] = {"start": 0.5, "min": 0.01, "max": 2.0}   # declared [0, 1]
        self.assert_error(spec, "free.sb_cut.max", "outside the law's declared bounds [0, 1]", "inside the declared bounds")
        self.assert_error(softbond_file(fixed={"sb_fa_deg": 120}), "fixed.sb_fa_deg", "declared bounds [0, 90]")

    def test_missing_targets(self):
        spec = softbond_file()
        del spec["targets"]
        self.assert_error(spec, "targets", "missing")
        self.assert_error(softbond_file(targets={}), "targets", "nothing to calibrate against", "ucs_pa")
        self.assert_error(softbond_file(targets={"ucs_pa": {"tolerance": 0.03}}), "targets.ucs_pa.value", "missing target value")

    def test_targets_the_sample_cannot_measure(self):
        # Platens record no lateral strain, hold no confinement and cannot pull.
        for quantity, value in (("poisson_ratio", 0.2), ("tensile_strength_pa", 1e5), ("tensile_to_compressive_ratio", 0.1)):
            self.assert_error(softbond_file(targets={quantity: {"value": value}}), f"targets.{quantity}",
                              "needs a periodic REV sample", "ucs_upscaling.json")
        self.assert_error(softbond_file(targets={"tensile_strengh_pa": {"value": 1e5}}), "targets.tensile_strengh_pa",
                          "unknown target", "tensile_strength_pa")

    def test_packings_free_and_tied(self):
        spec = softbond_file()
        spec["sample"]["packings"] = [3, 4]
        self.assert_error(spec, "sample.packings", "at least three")
        spec = softbond_file()
        spec["free"]["sb_coh_pa"]["start"] = 1e9
        self.assert_error(spec, "free.sb_coh_pa.start", "outside [min, max]")
        self.assert_error(softbond_file(tied={"sb_ten_pa": {"to": "sb_soft"}}), "tied.sb_ten_pa.to", "not a free parameter")


class CommandLine(Folder):
    def test_help_names_the_method(self):
        result = subprocess.run([os.path.join(ROOT, "vc"), "calibrate", "--help"], stdout=subprocess.PIPE, text=True,
                                env=dict(os.environ, VC_NO_INSTALL="1"))
        self.assertEqual(result.returncode, 0)
        for words in ("calibration", "scaling step", "Nelder-Mead", "--check", "cache"):
            self.assertIn(words, result.stdout)

    def test_a_bad_file_exits_2_with_the_key(self):
        stderr = io.StringIO()
        with contextlib.redirect_stderr(stderr):
            status = calibrate.main([self.write(softbond_file(law="hertz")), "--check"])
        self.assertEqual(status, 2)
        self.assertIn("law: unknown bonded law 'hertz'", stderr.getvalue())
        with contextlib.redirect_stdout(io.StringIO()) as stdout:
            self.assertEqual(calibrate.main([self.write(softbond_file()), "--check"]), 0)
        self.assertIn("OK", stdout.getvalue())


class Scaling(unittest.TestCase):
    def test_factors_from_the_first_evaluation(self):
        targets = read_targets({"ucs_pa": {"value": 5e5}, "young_modulus_pa": {"value": 2e9},
                                "triaxial_peak_deviator_pa": [{"confinement_pa": 1e5, "value": 8e5}]})
        achieved = {"ucs_pa": 2.5e5, "young_modulus_pa": 1e9, "triaxial_peak_deviator_pa@100000": 2e5}
        a, b = scaling.scale_factors(targets, achieved)
        self.assertAlmostEqual(a, 2.0)
        self.assertAlmostEqual(b, math.sqrt(2.0 * 4.0))   # geometric mean over the strength targets

    def test_later_steps_use_the_measured_exponent(self):
        targets = read_targets({"ucs_pa": {"value": 5e5}, "young_modulus_pa": {"value": 1e9}})
        previous = {"parameters": {"sb_coh_pa": 9e5, "sb_emod_pa": 1e9}, "means": {"ucs_pa": 1.44e6, "young_modulus_pa": 1e9}}
        ucs = 1.44e6 * (1 / 3) ** 1.5           # UCS ~ strength^1.5: the first step (x 1/3) undershoots
        current = {"parameters": {"sb_coh_pa": 3e5, "sb_emod_pa": 1e9}, "means": {"ucs_pa": ucs, "young_modulus_pa": 1e9}}
        n_modulus, n_strength = scaling.measured_exponents("soft_bond", targets, previous, current)
        self.assertEqual(n_modulus, 1.0)         # the moduli did not move
        self.assertAlmostEqual(n_strength, 1.5)
        a, b = scaling.scale_factors(targets, current["means"], (n_modulus, n_strength))
        self.assertAlmostEqual(ucs * b ** 1.5, 5e5)   # the secant step lands on the target

    def test_moduli_strengths_and_displacements(self):
        free = [FreeParameter("bond_emod_pa", 1e9, 1e7, 1e11), FreeParameter("ten_pa", 1e6, 1e4, 1.5e6),
                FreeParameter("ucn_m", 2e-5, 1e-7, 1e-3), FreeParameter("friction", 0.5, 0.1, 1.0)]
        start = {"bond_emod_pa": 1e9, "ten_pa": 1e6, "ucn_m": 2e-5, "friction": 0.5}
        out = scaling.scaled_start("damage_bond", free, start, 2.0, 3.0)
        self.assertAlmostEqual(out["bond_emod_pa"], 2e9)
        self.assertEqual(out["ten_pa"], 1.5e6)                 # 3e6 clipped to the upper bound
        self.assertAlmostEqual(out["ucn_m"], 2e-5 * 1.5)        # b/a: the bond's ductility kept
        self.assertEqual(out["friction"], 0.5)                 # dimensionless: not scaled


class Series:
    def __init__(self, values):
        self.values = values


class Experiments(unittest.TestCase):
    def test_the_periodic_revs_ucs_modulus_and_poisson_ratio(self):
        import numpy as np
        strain = np.linspace(0.0, 2e-3, 41)                     # the peak at sample 20, strain 1e-3
        q = np.where(strain <= 1e-3, 1e9 * strain, 1e6 - 5e8 * (strain - 1e-3))
        series = {"dem_cell_strain_zz": Series(strain), "dem_cell_stress_zz_pa": Series(q + 1e4),
                  "dem_cell_stress_xx_pa": Series(np.full(41, 1e4)), "dem_cell_stress_yy_pa": Series(np.full(41, 1e4)),
                  "dem_cell_strain_xx": Series(-0.25 * strain), "dem_cell_strain_yy": Series(-0.25 * strain)}
        m = measure(series, periodic=True)
        self.assertAlmostEqual(m["peak_pa"], 1e6)               # the deviator: sigma_3 taken off
        self.assertAlmostEqual(m["young_modulus_pa"] / 1e9, 1.0)
        self.assertAlmostEqual(m["poisson_ratio"], 0.25)
        self.assertTrue(m["peak_reached"])
        series["dem_cell_stress_zz_pa"] = Series(1e9 * strain)   # still rising at the end: no peak
        self.assertFalse(measure(series, periodic=True)["peak_reached"])

    def test_a_triaxial_experiment_of_a_periodic_sample(self):
        spec = {"law": "damage_bond", "targets": {"triaxial_peak_deviator_pa": [{"confinement_pa": 3e5, "value": 1e6}]},
                "sample": {"scenario": os.path.join(ROOT, "scenarios", "triaxial_damagebond_samecell.json"), "variant": "S4",
                           "packings": [5, 6, 7]},
                "free": {"ten_pa": {"start": 1e6, "min": 1e5, "max": 1e7}}}
        calibration, sample, contact = prepared(spec)
        self.assertTrue(sample.periodic)
        self.assertEqual(contact["com_pa"], 5e7)                 # from the sample's contact block
        scenario = sample.scenario_for(dict(contact, ten_pa=2e6), 6, 3e5)
        dem = scenario["participants"]["dem"]["config"]
        self.assertEqual((dem["particles"]["seed"], dem["threads"], dem["contact"]["ten_pa"]), (6, 1, 2e6))
        self.assertEqual(dem["periodic"]["loading"]["stress_pa"], 3e5)
        self.assertEqual(dem["periodic"]["consolidation"]["stress_pa"], 3e5)
        self.assertEqual(dem["upscaling"]["scale_factor"], 4)    # the variant's patch applied
        self.assertNotIn("variants", scenario)


    def test_the_tensile_strength_of_a_pulled_rev(self):
        import numpy as np
        strain = np.linspace(0.0, -2e-3, 41)                    # extension: compression-positive strain < 0
        tension = np.where(strain >= -5e-4, -4e8 * strain, 2e5 - 1e8 * (-strain - 5e-4))
        series = {"dem_cell_strain_zz": Series(strain), "dem_cell_stress_zz_pa": Series(-tension)}
        m = measure_tension(series)
        self.assertAlmostEqual(m["tensile_strength_pa"], 2e5)
        self.assertAlmostEqual(m["strain_at_peak"], -5e-4)
        self.assertTrue(m["peak_reached"])
        series["dem_cell_stress_zz_pa"] = Series(4e8 * strain)  # the tension still rising at the end
        self.assertFalse(measure_tension(series)["peak_reached"])

    def test_tension_targets_pull_the_rev_and_the_ratio_is_taken_packing_by_packing(self):
        spec = {"law": "soft_bond", "sample": {"scenario": os.path.join(ROOT, "scenarios", "ucs_upscaling.json"), "variant": "S2",
                                               "packings": [1, 2, 3]},
                "free": {"sb_ten_pa": {"start": 4e5, "min": 1e4, "max": 1e8}},
                "targets": {"tensile_strength_pa": {"value": 1e5}, "tensile_to_compressive_ratio": {"value": 0.1},
                            "ucs_pa": {"value": 1e6}}}
        calibration, sample, contact = prepared(spec)
        self.assertEqual(experiments_needed(calibration.targets), [UNCONFINED, TENSION])   # each once
        rate = sample.scenario["participants"]["dem"]["config"]["periodic"]["loading"]["axial_strain_rate_per_s"]
        pulled = sample.scenario_for(contact, 2, 0.0, tension=True)["participants"]["dem"]["config"]["periodic"]["loading"]
        self.assertEqual((pulled["axial_strain_rate_per_s"], pulled["stress_pa"]), (-abs(rate), 0.0))
        pressed = sample.scenario_for(contact, 2, 0.0)["participants"]["dem"]["config"]["periodic"]["loading"]
        self.assertEqual(pressed["axial_strain_rate_per_s"], rate)
        measured = {UNCONFINED: {"peak_pa": 8e5}, TENSION: {"tensile_strength_pa": 1e5}}
        values = {t.quantity: target_value(t, measured) for t in calibration.targets}
        self.assertEqual(values, {"tensile_strength_pa": 1e5, "tensile_to_compressive_ratio": 0.125, "ucs_pa": 8e5})

    def test_a_target_no_run_could_measure_stops_the_calibration_with_the_fix(self):
        # An early peak leaves fewer than two points below 30 % of it: no modulus (NaN).
        # Fed to Nelder-Mead, a NaN objective wanders; the evaluation must stop and
        # say how to record more points.
        spec = {"law": "damage_bond", "targets": {"young_modulus_pa": {"value": 1e9}},
                "sample": {"scenario": os.path.join(ROOT, "scenarios", "triaxial_damagebond_samecell.json"), "variant": "S4",
                           "packings": [5, 6, 7]},
                "free": {"bond_emod_pa": {"start": 1e9, "min": 1e7, "max": 1e11}}}
        calibration, sample, contact = prepared(spec)

        class Cache:  # every run already done: packing 6's modulus unmeasurable
            def get(self, scenario):
                seed = scenario["participants"]["dem"]["config"]["particles"]["seed"]
                return {"key": str(seed), "measured": {"peak_pa": 1e6, "young_modulus_pa": float("nan") if seed == 6 else 1e9}}

        evaluator = Evaluator(calibration, sample, contact, Cache(), "no-coupler", "no-folder")
        with self.assertRaises(CalibrationError) as raised:
            evaluator.evaluate({"bond_emod_pa": 1e9})
        self.assertIn("targets.young_modulus_pa: packing 6", str(raised.exception))
        self.assertIn("exchange_interval", str(raised.exception))


class GaussNewton(unittest.TestCase):
    """The power-law search (calibration/gauss_newton.py) on closed-form stand-ins for the DEM:
    four parameters, five targets, the chalk calibration's shape (strengths coupled
    through two bond strengths and friction, the modulus through the moduli)."""

    EXPONENTS = [[0.0, 0.2, 0.45, 0.3],    # UCS: tension and cohesion strengths, friction
                 [0.0, 0.5, 0.3, 0.05],    # tensile strength
                 [1.0, 0.0, 0.0, 0.0],     # Young's modulus
                 [0.0, 0.2, 0.45, 0.35],   # peak at 100 kPa
                 [0.0, 0.2, 0.4, 0.45]]    # peak at 300 kPa
    TRUE = [1.0e9, 4.0e5, 3.0e5, 0.6]

    def setUp(self):
        self.free = [FreeParameter("e", 2e9, 1e7, 1e11), FreeParameter("t", 2e5, 1e4, 1e8),
                     FreeParameter("c", 5e5, 1e4, 1e8), FreeParameter("f", 0.5, 0.1, 2.0)]
        self.targets = [Target(f"y{i}", "ucs_pa", self.model(self.TRUE, i, bend=0.0), 0.03) for i in range(5)]

    def model(self, values, i, bend):
        """A power law, bent by bend * (ln p)^2 terms where bend > 0 (not a power law: S changes along the way)."""
        logs = [math.log(v / t) for v, t in zip(values, [1e9, 1e5, 1e5, 0.5])]
        return math.exp(sum(a * l + bend * a * l * l for a, l in zip(self.EXPONENTS[i], logs)))

    def search(self, bend):
        calls = []

        def evaluate(values):
            calls.append(values)
            means = {t.name: self.model([values[n] for n in "etcf"], i, bend) for i, t in enumerate(self.targets)}
            if search.within_tolerance(self.targets, means):
                raise search.Converged()
            return means, search.objective(self.targets, means)
        try:
            gauss_newton.gauss_newton(self.free, self.targets, {p.name: p.start for p in self.free}, evaluate, 30)
        except search.Converged:
            return len(calls), True
        return len(calls), False

    def test_a_power_law_is_met_after_the_jacobian_and_one_step(self):
        calls, converged = self.search(bend=0.0)
        self.assertTrue(converged)
        self.assertLessEqual(calls, 1 + 4 + 1)   # the start (cached by the caller), S, one exact step

    def test_a_bent_law_is_met_in_a_few_broyden_steps(self):
        calls, converged = self.search(bend=0.1)
        self.assertTrue(converged)
        self.assertLessEqual(calls, 1 + 4 + 8)   # Nelder-Mead needs about 10 per parameter

    def test_the_step_stays_inside_the_radius_and_the_bounds(self):
        import numpy as np
        radius, lower, upper = math.log(2.0), np.array([-1.0, -0.05]), np.array([1.0, 1.0])
        step = gauss_newton.gauss_newton_step(np.eye(2), np.array([5.0, 1.0]), np.ones(2), radius, lower, upper, np.zeros(2))
        self.assertAlmostEqual(step[0], radius, places=3)            # the whole step scaled to the radius
        self.assertAlmostEqual(step[1] / step[0], 0.2, places=3)     # in the same direction
        step = gauss_newton.gauss_newton_step(np.eye(2), np.array([0.5, -0.1]), np.ones(2), radius, lower, upper, np.zeros(2))
        self.assertAlmostEqual(step[1], -0.05)                       # cut to the bound
        jacobian = gauss_newton.broyden_update(np.zeros((1, 2)), np.array([0.5, 0.0]), np.array([1.0]))
        self.assertEqual(jacobian.tolist(), [[2.0, 0.0]])          # reproduces the step it saw


class NoiseFloor(unittest.TestCase):
    """"stop_at_noise": a point whose every error is inside the larger of the tolerance and
    the standard error of its mean over the packings cannot be improved on visibly."""

    def test_standard_error_and_the_floor(self):
        target = [Target("ucs_pa", "ucs_pa", 1.0, 0.05)]
        noisy = search.standard_errors(target, {"ucs_pa": [0.9, 1.1, 1.3]})
        self.assertAlmostEqual(noisy["ucs_pa"], 0.2 / math.sqrt(3.0))         # sample std 0.2 over sqrt(3)
        self.assertTrue(search.within_noise(target, {"ucs_pa": 1.1}, noisy))   # 10 % off, 11.5 % of noise
        quiet = search.standard_errors(target, {"ucs_pa": [1.05, 1.1, 1.15]})
        self.assertFalse(search.within_noise(target, {"ucs_pa": 1.1}, quiet))  # 10 % off, 2.9 % of noise, 5 % tolerance
        self.assertTrue(math.isnan(search.standard_errors(target, {"ucs_pa": [1.0]})["ucs_pa"]))
        self.assertFalse(search.within_noise(target, {"ucs_pa": 1.0}, {"ucs_pa": float("nan")}))  # one packing: no floor

    def test_the_key_is_read_and_checked(self):
        spec = {"law": "damage_bond", "targets": {"ucs_pa": {"value": 1e6}},
                "sample": {"scenario": os.path.join(ROOT, "scenarios", "triaxial_damagebond_samecell.json"), "variant": "S4",
                           "packings": [5, 6, 7]},
                "free": {"ten_pa": {"start": 1e6, "min": 1e5, "max": 1e7}},
                "search": {"method": "gauss_newton", "stop_at_noise": True}}
        calibration, _, _ = prepared(spec)
        self.assertEqual((calibration.method, calibration.stop_at_noise), ("gauss_newton", True))
        spec["search"] = {"method": "simplex"}
        with self.assertRaises(CalibrationError) as raised:
            prepared(spec)
        self.assertIn("search.method", str(raised.exception))


class CacheAndSensitivity(unittest.TestCase):
    def test_the_key_changes_with_one_bit_of_one_parameter(self):
        scenario = {"participants": {"dem": {"config": {"contact": {"sb_coh_pa": 4.5e5}, "particles": {"seed": 3}}}}}
        moved = json.loads(json.dumps(scenario))
        moved["participants"]["dem"]["config"]["contact"]["sb_coh_pa"] = math.nextafter(4.5e5, 1e6)
        self.assertEqual(run_key(scenario), run_key(json.loads(json.dumps(scenario))))
        self.assertNotEqual(run_key(scenario), run_key(moved))

    def test_log_derivatives_of_power_laws(self):
        targets = read_targets({"ucs_pa": {"value": 1.0}, "young_modulus_pa": {"value": 1.0}})
        p = FreeParameter("sb_coh_pa", 1.0, 0.1, 1.05)
        moved = sensitivity.step_for(p, 1.0, 0.1)
        self.assertAlmostEqual(moved, 1.0 / 1.1)                # +10 % would leave the bounds: backwards
        d = sensitivity.log_derivatives(targets, {"ucs_pa": 2.0, "young_modulus_pa": 3.0},
                                        {"ucs_pa": 2.0 * moved ** 1.5, "young_modulus_pa": 3.0}, 1.0, moved)
        self.assertAlmostEqual(d["ucs_pa"], 1.5)
        self.assertAlmostEqual(d["young_modulus_pa"], 0.0)


class WholeCalibration(Folder):
    """calibrate() against the closed-form stand-in: peak ~ coh^0.95 E^0.05, E ~ emod."""

    def run_calibration(self, path, out, fail_after=None, jobs=1):
        os.environ["FAKE_COUPLER_COUNT"] = os.path.join(self.folder, "count")
        if jobs > 1:
            del os.environ["FAKE_COUPLER_COUNT"]   # its counter file is not safe for runs side by side
        os.environ.pop("FAKE_COUPLER_FAIL_AFTER", None)
        if fail_after is not None:
            os.environ["FAKE_COUPLER_FAIL_AFTER"] = str(fail_after)
        calibration, sample, contact = calibrate.prepare(path)
        with contextlib.redirect_stdout(io.StringIO()):
            return calibrate.calibrate(calibration, sample, contact, self.coupler(), out, jobs=jobs)

    def coupler(self):
        """An executable that runs fake_coupler.py with this interpreter (the one with numpy and h5py)."""
        path = os.path.join(self.folder, "coupler")
        with open(path, "w") as f:
            f.write(f'#!/bin/sh\nexec "{sys.executable}" "{FAKE_COUPLER}" "$@"\n')
        os.chmod(path, 0o755)
        return path

    def runs_so_far(self):
        with open(os.path.join(self.folder, "count")) as f:
            return int(f.read())

    def test_converges_writes_its_outputs_and_resumes_after_a_kill(self):
        path = self.write(softbond_file(output={"material": "materials/calibrated.json"}))
        out = os.path.join(self.folder, "out")
        with self.assertRaises(RuntimeError):      # killed after 10 runs: 3 evaluations and one run of the fourth
            self.run_calibration(path, out, fail_after=10)
        self.assertEqual(self.runs_so_far(), 10)
        summary = self.run_calibration(path, out)
        self.assertTrue(summary["converged"], summary["achieved"])
        self.assertEqual(summary["dem_runs_this_session"], summary["dem_runs"] - 10, "the resumed calibration reran a finished run")
        self.assertEqual(self.runs_so_far(), summary["dem_runs"])
        for row in summary["achieved"]:
            self.assertLessEqual(abs(row["relative_error"]), row["tolerance"])
            self.assertLess(row["min"], row["mean"])   # the packings' scatter is reported
        # The closed form: E = 0.5 emod exactly, so the modulus is found by the scaling step alone.
        self.assertAlmostEqual(summary["parameters"]["sb_emod_pa"], 2.8e9, delta=2.8e9 * 0.02)
        history = read_json(os.path.join(out, "history.json"))
        self.assertEqual([h["phase"] for h in history[:2]], ["start", "scaling"])
        self.assertEqual(summary["evaluations"], len(history))
        material = read_json(os.path.join(out, "material.json"))
        self.assertEqual(read_json(os.path.join(self.folder, "materials", "calibrated.json")), material)
        self.assertEqual(material["law"], "soft_bond")
        self.assertEqual(material["sb_ten_pa"], material["sb_coh_pa"])   # tied
        self.assertEqual(material["sb_fa_deg"], 32)                      # fixed, from the sample
        table = read_json(os.path.join(out, "sensitivity.json"))
        self.assertAlmostEqual(table["sb_coh_pa"]["ucs_pa"], 0.95, places=2)
        self.assertAlmostEqual(table["sb_emod_pa"]["young_modulus_pa"], 1.0, places=2)
        self.assertAlmostEqual(table["sb_emod_pa"]["ucs_pa"], 0.05, places=2)
        for name in ("summary.md", "history.png", "sensitivity.md", "sensitivity.png"):
            self.assertTrue(os.path.exists(os.path.join(out, name)), name)
        # A third run finds everything in the cache.
        again = self.run_calibration(path, out)
        self.assertEqual(again["dem_runs_this_session"], 0)
        self.assertEqual(again["parameters"], summary["parameters"])

    def test_max_evaluations_counts_the_scaling_steps(self):
        path = self.write(softbond_file(search={"max_evaluations": 2, "sensitivity": False}))
        summary = self.run_calibration(path, os.path.join(self.folder, "out"))
        self.assertEqual(summary["evaluations"], 2)
        self.assertFalse(summary["converged"])

    def test_runs_side_by_side_give_the_same_calibration(self):
        path = self.write(softbond_file(search={"max_evaluations": 5, "sensitivity": False}))
        one = self.run_calibration(path, os.path.join(self.folder, "one"))
        two = self.run_calibration(path, os.path.join(self.folder, "two"), jobs=3)
        self.assertEqual(one["parameters"], two["parameters"])
        self.assertEqual(one["achieved"], two["achieved"])
        self.assertEqual(one["dem_runs"], two["dem_runs"])


if __name__ == "__main__":
    unittest.main()
