"""One evaluation: a parameter set, every experiment on every packing, averaged.

The targets need at most 1 + (number of confinements) experiments (the
unconfined test gives UCS, Young's modulus and Poisson's ratio at once), each
run on every packing of the sample; the target's value is the mean over the
packings, reported with its min and max (the scatter of the packings).
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

from .evaluation_cache import run_key
from .experiments import measure


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


def confinements(targets):
    """The experiments the targets need: 0.0 (unconfined) and every triaxial sigma_3."""
    return sorted({t.confinement_pa for t in targets})


# Which measured value (experiments.measure) each target quantity is.
MEASURED_AS = {"ucs_pa": "peak_pa", "triaxial_peak_deviator_pa": "peak_pa",
               "young_modulus_pa": "young_modulus_pa", "poisson_ratio": "poisson_ratio"}


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

    def run_one(self, scenario):
        """The measured values of one scenario: from the cache, else by running the coupler."""
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
            measured = measure(run.all_series(), self.sample.periodic)
        return self.cache.put(scenario, measured, wall), True

    def evaluate(self, free_values):
        contact = contact_for(self.base_contact, free_values, self.calibration.tied)
        values = {t.name: [] for t in self.calibration.targets}
        evaluation = Evaluation(dict(free_values), contact, values)
        experiments = [(sigma3, seed) for sigma3 in confinements(self.calibration.targets) for seed in self.calibration.packings]
        scenarios = [self.sample.scenario_for(contact, seed, sigma3) for sigma3, seed in experiments]
        # The runs are independent: side by side where jobs > 1, in the same order either way.
        with ThreadPoolExecutor(max_workers=self.jobs) as pool:
            results = list(pool.map(self.run_one, scenarios))
        for (sigma3, seed), (entry, new) in zip(experiments, results):
            evaluation.runs.append(entry["key"])
            evaluation.new_runs += int(new)
            m = entry["measured"]
            if not m.get("peak_reached", True):
                evaluation.warnings.append(f"packing {seed}, sigma_3 {sigma3:g} Pa: the stress still rises at the last "
                                           "point (no peak): lengthen the sample's run.exchanges")
            for t in self.calibration.targets:
                if t.confinement_pa == sigma3:
                    values[t.name].append(float(m.get(MEASURED_AS[t.quantity], float("nan"))))
        return evaluation
