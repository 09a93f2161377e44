#!/usr/bin/env python3
"""./vc calibrate: the contact parameters of a bonded law from a rock's target strengths and stiffness.

    tools/calibrate.py CALIBRATION.json [--build DIR] [--out DIR] [--jobs N] [--check]

Reads the calibration file (the law, the free parameters with bounds, the
targets with tolerances, the sample scenario and its packings;
scenarios/calibration/ has examples), then
  1. evaluates the start: every experiment the targets need on every packing
     (the DEM runs of ./vc run, through build/bin/coupler),
  2. takes a dimensionless scaling step (moduli by E_target/E, strengths
     by target/achieved peak; calibration/scaling.py), and up to two more
     with the exponents measured between the last two evaluations,
  3. searches the rest on the logarithms of the free parameters until every
     target is inside its tolerance: Nelder-Mead, or with "search": {"method":
     "gauss_newton"} Gauss-Newton on power laws (measured log-derivatives,
     Broyden updates, a trust region; calibration/gauss_newton.py); with
     "stop_at_noise": true it also stops where every target is within the
     larger of its tolerance and its mean's standard error over the packings,
  4. measures the sensitivity d ln(target)/d ln(parameter) at the optimum,
  5. writes material.json (for "contact": {"include": ...}; a copy where
     output.material says), summary.json/.md
     (achieved values with their scatter over the packings, DEM runs, wall
     time), history.json/.png and sensitivity.json/.md/.png into the output folder.
Every DEM run is cached in OUT/cache by its scenario: run the same command
again after a kill and it continues without rerunning finished runs.
--check: read and check the file (law, parameter names and bounds, targets, sample) and stop.
docs/calibration_automatic.md explains the method.

Needs numpy, scipy, matplotlib and h5py (Debian: python3-numpy python3-scipy python3-matplotlib python3-h5py).
"""
import argparse
import datetime
import os
import sys
import time

ROOT = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir))
sys.path.insert(0, os.path.join(ROOT, "tools"))
sys.path.insert(0, os.path.join(ROOT, "python"))

from calibration import gauss_newton, outputs, scaling, search, sensitivity  # noqa: E402
from calibration.calibration_file import CalibrationError, check_against_law, read_calibration  # noqa: E402
from calibration.evaluation import Evaluator  # noqa: E402
from calibration.evaluation_cache import EvaluationCache  # noqa: E402
from calibration.experiments import Sample  # noqa: E402
from calibration.law_parameters import law_parameters  # noqa: E402


def prepare(path):
    """The checked calibration, its sample and the base contact block (CalibrationError on a mistake)."""
    calibration = read_calibration(path)
    check_against_law(calibration, law_parameters(calibration.law))
    sample = Sample(calibration)
    sample.check_targets(calibration.targets)
    return calibration, sample, sample.base_contact(calibration.law, calibration.fixed)


class Calibrator:
    """The evaluations of one calibration, in order, with their history."""

    def __init__(self, calibration, evaluator, out, log):
        self.calibration = calibration
        self.evaluator = evaluator
        self.out = out
        self.log = log
        self.history = []
        self.best = None
        self.seen = {}   # parameters -> (evaluation, record): Nelder-Mead asks for its start again
        self.stopped_at_noise = False

    def evaluate(self, values, phase):
        known = self.seen.get(tuple(sorted(values.items())))
        if known is not None:
            return known
        e = self.evaluator.evaluate(values)
        targets = self.calibration.targets
        means = {t.name: e.mean(t.name) for t in targets}
        record = {"evaluation": len(self.history) + 1, "phase": phase, "parameters": values, "means": means,
                  "scatter": {t.name: e.scatter(t.name) for t in targets},
                  "standard_error": search.standard_errors(targets, e.values),
                  "objective": search.objective(targets, means), "within_tolerance": search.within_tolerance(targets, means),
                  "new_dem_runs": e.new_runs, "runs": e.runs}
        record["within_noise"] = search.within_noise(targets, means, record["standard_error"])
        self.history.append(record)
        if phase != "sensitivity" and (self.best is None or record["objective"] < self.best[1]["objective"]):
            self.best = (e, record)
        outputs.write_json(os.path.join(self.out, "history.json"), self.history)
        errors = ", ".join(f"{t.name} {100 * t.relative_error(means[t.name]):+.1f} %" for t in targets)
        self.log(f"evaluation {record['evaluation']} ({phase}): " +
                 ", ".join(f"{k} {v:.4g}" for k, v in values.items()) + f" -> {errors}" +
                 (f" ({e.new_runs} DEM runs)" if e.new_runs else " (cached)"))
        for w in e.warnings:
            self.log(f"warning: {w}")
        self.seen[tuple(sorted(values.items()))] = (e, record)
        return e, record


def print_now(line):
    """A progress line, flushed: a calibration runs for minutes to hours, often with its output in a file."""
    print(line, flush=True)


def calibrate(calibration, sample, base_contact, coupler, out, log=print_now, jobs=1):
    """Steps 1-5 of the module's docstring; returns the summary (also written to OUT/summary.json)."""
    started = time.monotonic()
    os.makedirs(out, exist_ok=True)
    cache = EvaluationCache(os.path.join(out, "cache"))
    evaluator = Evaluator(calibration, sample, base_contact, cache, coupler, os.path.join(out, "runs"), jobs)
    run = Calibrator(calibration, evaluator, out, log)

    start = {p.name: p.start for p in calibration.free}
    first = run.evaluate(start, "start")[1]
    take_scaling_steps(run, first, log)
    search_the_rest(run)
    table = measure_sensitivity(run)
    return write_outputs(run, cache, start, table, time.monotonic() - started)


def take_scaling_steps(run, first, log):
    """2. Moduli and strengths multiplied by the factors the last evaluation asks for
    (calibration/scaling.py): the dimensionless rules first, then the exponents measured
    between the last two evaluations, while each step improves on the best."""
    calibration = run.calibration
    previous, current, exponents = None, first, (1.0, 1.0)
    for _ in range(calibration.scaling_steps):
        if run.best[1]["within_tolerance"] or current is not run.best[1] or len(run.history) >= calibration.max_evaluations:
            return
        if previous is not None:
            exponents = scaling.measured_exponents(calibration.law, calibration.targets, previous, current)
        a, b = scaling.scale_factors(calibration.targets, current["means"], exponents)
        point = scaling.scaled_start(calibration.law, calibration.free, current["parameters"], a, b)
        if point == current["parameters"]:
            return
        log(f"scaling step: moduli x {a:.3f}, strengths x {b:.3f} (exponents {exponents[0]:.2f}, {exponents[1]:.2f})")
        previous, current = current, run.evaluate(point, "scaling")[1]


def search_the_rest(run):
    """3. From the best point so far until every target is inside its tolerance:
    Nelder-Mead (search.py) or the power-law Gauss-Newton (gauss_newton.py), as search.method says."""
    if run.best[1]["within_tolerance"]:
        return
    if run.calibration.stop_at_noise and run.best[1]["within_noise"]:
        run.stopped_at_noise = True
        return

    def evaluate(values):
        _, record = run.evaluate(values, "search")
        if record["within_tolerance"]:
            raise search.Converged()
        if run.calibration.stop_at_noise and record["within_noise"] and record is run.best[1]:
            run.log(f"evaluation {record['evaluation']}: every target inside the larger of its tolerance and its mean's "
                    "standard error over the packings: stopping at the noise floor")
            run.stopped_at_noise = True
            raise search.AtNoiseFloor()
        return record["means"], record["objective"]
    budget = run.calibration.max_evaluations - len(run.history)
    try:
        if run.calibration.method == "gauss_newton":
            gauss_newton.gauss_newton(run.calibration.free, run.calibration.targets, run.best[1]["parameters"], evaluate, budget)
        else:
            search.nelder_mead(run.calibration.free, run.best[1]["parameters"], lambda values: evaluate(values)[1], budget)
    except search.Converged:
        pass


def measure_sensitivity(run):
    """4. {parameter: {target: d ln y / d ln p}} at the best point (empty when switched off)."""
    calibration = run.calibration
    if not calibration.sensitivity:
        return {}
    best = run.best[1]
    table = {}
    for p in calibration.free:
        moved = dict(best["parameters"])
        moved[p.name] = sensitivity.step_for(p, best["parameters"][p.name], calibration.sensitivity_step)
        _, record = run.evaluate(moved, "sensitivity")
        table[p.name] = sensitivity.log_derivatives(calibration.targets, best["means"], record["means"],
                                                    best["parameters"][p.name], moved[p.name])
    outputs.write_sensitivity(run.out, calibration.targets, [p.name for p in calibration.free], table)
    return table


def write_outputs(run, cache, start, table, session_wall_s):
    """5. material.json, summary.json/.md and history.png (history.json is written after every evaluation)."""
    calibration, out = run.calibration, run.out
    best_evaluation, best = run.best
    entries = {e["key"]: e for e in cache.entries()}
    used = {key for h in run.history for key in h["runs"]}  # this calibration's runs (the cache may hold others)
    summary = {
        "name": calibration.name, "law": calibration.law, "calibration_file": calibration.path,
        "sample": {"scenario": calibration.scenario_path, "variant": calibration.variant, "packings": calibration.packings},
        "converged": best["within_tolerance"], "stopped_at_noise_floor": run.stopped_at_noise,
        "start": start, "parameters": best["parameters"],
        "achieved": outputs.achieved_table(calibration.targets, best_evaluation),
        "evaluations": len(run.history),
        "dem_runs": len(used), "dem_runs_this_session": cache.misses,
        "dem_wall_s": sum(entries[k]["wall_s"] for k in used),
        "session_wall_s": session_wall_s,
        "material": os.path.join(out, "material.json"),
        "sensitivity": table, "warnings": sorted(set(best_evaluation.warnings)),
        "date": datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC"),
    }
    achieved = ", ".join(f"{r['target']} {r['value']:g} (achieved {r['mean']:.4g}, {r['min']:.4g}-{r['max']:.4g} "
                         f"over {len(calibration.packings)} packings)" for r in summary["achieved"])
    comment = (f"Calibrated by ./vc calibrate {os.path.relpath(calibration.path, ROOT)} ({summary['date']}): law {calibration.law}, "
               f"free {', '.join(p.name for p in calibration.free)}; targets {achieved}; "
               f"sample {os.path.relpath(calibration.scenario_path, ROOT)}. The calibration's summary.json has the history and sensitivities.")
    outputs.write_material(summary["material"], calibration.law, best_evaluation.contact, comment)
    if calibration.material_copy:
        outputs.write_material(calibration.material_copy, calibration.law, best_evaluation.contact, comment)
        summary["material_copy"] = calibration.material_copy
    outputs.write_json(os.path.join(out, "summary.json"), summary)
    outputs.write_summary_md(os.path.join(out, "summary.md"), summary)
    outputs.plot_history(os.path.join(out, "history.png"), calibration.targets, run.history)
    return summary


def main(argv=None):
    parser = argparse.ArgumentParser(prog="./vc calibrate", description=__doc__.split("\n\n", 2)[2],
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("calibration", help="the calibration file (JSON; scenarios/calibration/ has examples)")
    parser.add_argument("--build", default=os.path.join(ROOT, "build"), help="the build folder with bin/coupler (default: ./build)")
    parser.add_argument("--out", help="output folder (default: the file's output.directory)")
    parser.add_argument("--check", action="store_true", help="check the file and stop")
    parser.add_argument("--jobs", type=int, default=1,
                        help="DEM runs at once, one thread each (default 1; the runs of an evaluation are independent)")
    args = parser.parse_args(argv)
    try:
        calibration, sample, base_contact = prepare(args.calibration)
    except CalibrationError as e:
        print(f"calibrate: error in {args.calibration}: {e}", file=sys.stderr)
        return 2
    if args.check:
        print(f"{args.calibration}: OK ({calibration.law}, free {', '.join(p.name for p in calibration.free)}, "
              f"{len(calibration.targets)} targets, {len(calibration.packings)} packings of {sample.name})")
        return 0
    coupler = os.path.join(args.build, "bin", "coupler")
    if not os.path.exists(coupler):
        print(f"calibrate: {coupler} not found: build first (./vc build) or give --build", file=sys.stderr)
        return 2
    out = os.path.abspath(args.out or calibration.output_directory)
    if args.jobs < 1:
        print(f"calibrate: --jobs {args.jobs}: give at least 1", file=sys.stderr)
        return 2
    try:
        summary = calibrate(calibration, sample, base_contact, coupler, out, jobs=args.jobs)
    except CalibrationError as e:  # a run that cannot measure a target: the cache keeps what ran
        print(f"calibrate: error in {args.calibration}: {e}", file=sys.stderr)
        return 2
    print(f"{outputs.convergence_phrase(summary)} after {summary['evaluations']} evaluations, "
          f"{summary['dem_runs']} DEM runs ({summary['dem_runs_this_session']} new), {summary['session_wall_s']:.0f} s; "
          f"{os.path.join(out, 'summary.md')}, material {summary['material']}")
    return 0 if summary["converged"] or summary["stopped_at_noise_floor"] else 1


if __name__ == "__main__":
    sys.exit(main())
