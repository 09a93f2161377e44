"""One evaluation: a parameter set, every experiment on every packing, averaged.

The targets need at most 2 + (number of confinements) experiments (the
unconfined test gives UCS, Young's modulus and Poisson's ratio at once; the
pull, the tensile strength; the ratio of the two is taken packing by
packing), each run on every packing of the sample; the target's value is the
mean over the packings, reported with its min and max (the scatter of the
packings).
"""
import json
import os
import shutil
import subprocess
import time
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field

import numpy as np

import dfc_results  # noqa: E402  (python/: the results reader)

from .calibration_file import CalibrationError
from .evaluation_cache import run_key
from .experiments import measure, measure_tension


@dataclass
class Evaluation:
    parameters: dict                  # the free parameters' values
    contact: dict                     # the whole contact block run
    values: dict                      # {target name: [value per packing]}
    runs: list = field(default_factory=list)   # cache entries used
    new_runs: int = 0                 # DEM runs this evaluation started (not cached)
    warnings: list = field(default_factory=list)

    def mean(self, name):
        return float(np.mean(self.values[name]))

    def scatter(self, name):
        v = self.values[name]
        return {"mean": float(np.mean(v)), "min": float(np.min(v)), "max": float(np.max(v))}


def contact_for(base_contact, free_values, tied):
    """The contact block of a parameter set: the base, the free values, the tied ones."""
    contact = dict(base_contact)
    contact.update(free_values)
    for name, (to, ratio) in tied.items():
        contact[name] = ratio * free_values[to]
    return contact


# An experiment: (kind, sigma_3), kind "compression" (unconfined at sigma_3 0) or "tension".
UNCONFINED = ("compression", 0.0)
TENSION = ("tension", 0.0)


def experiments_for(target):
    """The experiments a target reads."""
    if target.quantity == "tensile_strength_pa":
        return [TENSION]
    if target.quantity == "tensile_to_compressive_ratio":
        return [TENSION, UNCONFINED]
    return [("compression", target.confinement_pa)]


def experiments_needed(targets):
    """Every experiment the targets need, each once, in a fixed order."""
    return sorted({e for t in targets for e in experiments_for(t)})


# Which measured value (experiments.measure, measure_tension) each target quantity is.
MEASURED_AS = {"ucs_pa": "peak_pa", "triaxial_peak_deviator_pa": "peak_pa", "young_modulus_pa": "young_modulus_pa",
               "poisson_ratio": "poisson_ratio", "tensile_strength_pa": "tensile_strength_pa"}


# Why a measured value can be missing, and the fix (CalibrationError of Evaluator.evaluate).
UNMEASURED_HINT = {
    "young_modulus_pa": "fewer than two recorded points lie below 30 % of the peak (it comes early for the record "
                        "interval); record more often: in \"sample\": {\"patch\": ...} divide coupling.exchange_interval by 4 "
                        "and multiply run.exchanges by 4 (the same strain, four times the records)",
    "poisson_ratio": "fewer than two recorded points lie below 30 % of the peak; record more often (sample.patch "
                     "coupling.exchange_interval, with run.exchanges raised in proportion)",
}


def target_value(target, measured):
    """A target's value on one packing from {experiment: measured values} of that packing."""
    if target.quantity == "tensile_to_compressive_ratio":
        return measured[TENSION].get("tensile_strength_pa", float("nan")) / measured[UNCONFINED].get("peak_pa", float("nan"))
    return float(measured[experiments_for(target)[0]].get(MEASURED_AS[target.quantity], float("nan")))


class Evaluator:
    """Runs (or finds in the cache) the experiments of a parameter set."""

    def __init__(self, calibration, sample, base_contact, cache, coupler, runs_folder, jobs=1):
        self.calibration = calibration
        self.sample = sample
        self.base_contact = base_contact
        self.cache = cache
        self.coupler = coupler
        self.runs_folder = runs_folder
        self.jobs = jobs      # DEM runs at once (each one thread)

    def run_one(self, job):
        """The measured values of one experiment (tension, scenario): from the cache, else by running the coupler."""
        tension, scenario = job
        entry = self.cache.get(scenario)
        if entry is not None:
            return entry, False
        folder = os.path.join(self.runs_folder, run_key(scenario))
        shutil.rmtree(folder, ignore_errors=True)   # what a killed calibration left of this run
        os.makedirs(folder)
        path = os.path.join(folder, "scenario.json")
        with open(path, "w") as f:
            json.dump(scenario, f, indent=1)
        start = time.monotonic()
        result = subprocess.run([self.coupler, "run", path, "--out", os.path.join(folder, "out"), "--no-progress"],
                                stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        wall = time.monotonic() - start
        if result.returncode != 0:
            raise RuntimeError(f"the DEM run {path} failed (exit {result.returncode}):\n{result.stdout[-3000:]}")
        with dfc_results.open_results(os.path.join(folder, "out", dfc_results.RESULTS_FILE)) as run:
            measured = measure_tension(run.all_series()) if tension else measure(run.all_series(), self.sample.periodic)
        return self.cache.put(scenario, measured, wall), True

    def evaluate(self, free_values):
        contact = contact_for(self.base_contact, free_values, self.calibration.tied)
        values = {t.name: [] for t in self.calibration.targets}
        evaluation = Evaluation(dict(free_values), contact, values)
        experiments = [(experiment, seed) for experiment in experiments_needed(self.calibration.targets) for seed in self.calibration.packings]
        jobs = [(kind == "tension", self.sample.scenario_for(contact, seed, sigma3, tension=kind == "tension"))
                for (kind, sigma3), seed in experiments]
        # The runs are independent: side by side where jobs > 1, in the same order either way.
        with ThreadPoolExecutor(max_workers=self.jobs) as pool:
            results = list(pool.map(self.run_one, jobs))
        measured = {seed: {} for seed in self.calibration.packings}
        for ((kind, sigma3), seed), (entry, new) in zip(experiments, results):
            evaluation.runs.append(entry["key"])
            evaluation.new_runs += int(new)
            measured[seed][(kind, sigma3)] = entry["measured"]
            if not entry["measured"].get("peak_reached", True):
                evaluation.warnings.append(f"packing {seed}, {kind} at sigma_3 {sigma3:g} Pa: the stress still rises at the last "
                                           "point (no peak): lengthen the sample's run.exchanges")
        for seed in self.calibration.packings:
            for t in self.calibration.targets:
                value = target_value(t, measured[seed])
                if not np.isfinite(value):
                    # A search on a NaN objective wanders; stop and say how to measure it.
                    raise CalibrationError(f"targets.{t.name}", f"packing {seed} gave no value at {free_values}",
                                           UNMEASURED_HINT.get(t.quantity, "look at the run's results in the output folder's runs/"))
                values[t.name].append(value)
        return evaluation
