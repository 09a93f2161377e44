#!/usr/bin/env python3
"""CTest check of tools/plot_results.py: run it on a sample results file, and
on a copy whose columns are named the way the coupler records them, and
require the three PNGs each time, each a real PNG, and their paths on stdout.
Then the overlay mode on both files at once: the pile overlay PNG, and one
summary line per run with the same numbers (the two files hold the same data
under the two naming schemes).

    results_plot_check.py PLOT_RESULTS_PY SAMPLE.h5 OUT_DIR

Exit code 77 (CTest SKIP_RETURN_CODE) when numpy, matplotlib or h5py are missing.
"""
import importlib.util
import os
import shutil
import subprocess
import sys

EXPECTED = ("pile_force_displacement.png", "interface_force.png", "unbalanced_force.png")


# Sample column -> the name the coupler gives the same quantity ("<slot>_<monitor>", interface_force_on_*).
COUPLER_NAMES = {
    "pile_displacement_m": "dem_pile_displacement_m",
    "pile_force_n": "dem_pile_force_n",
    "ufr_dem": "dem_unbalanced_force_ratio",
    "ufr_continuum": "continuum_unbalanced_force_ratio",
    **{f"interface_force_{s}_{a}": f"interface_force_on_{s}_{a}" for s in ("dem", "continuum") for a in "xyz"},
}


def coupler_named_copy(sample, path):
    import h5py

    with h5py.File(sample, "r") as source, h5py.File(path, "w") as target:
        group = target.create_group("timeseries")
        for name, dataset in source["timeseries"].items():
            group.create_dataset(COUPLER_NAMES.get(name, name), data=dataset[...])


def check(tool, sample, out_dir):
    shutil.rmtree(out_dir, ignore_errors=True)
    run = subprocess.run([sys.executable, tool, sample, "--out", out_dir], capture_output=True, text=True)
    print(run.stdout, run.stderr, sep="")
    if run.returncode != 0:
        return [f"plot_results.py exited with {run.returncode} on {sample}"]
    failures = []
    for name in EXPECTED:
        path = os.path.join(out_dir, name)
        if not os.path.isfile(path):
            failures.append(f"{name} was not written")
            continue
        with open(path, "rb") as f:
            if f.read(8) != b"\x89PNG\r\n\x1a\n":
                failures.append(f"{name} is not a PNG")
        if path not in run.stdout:
            failures.append(f"{name} was not printed")
    return [f"{sample}: {failure}" for failure in failures]


def check_overlay(tool, files, out_dir):
    shutil.rmtree(out_dir, ignore_errors=True)
    run = subprocess.run([sys.executable, tool, *files, "--out", out_dir], capture_output=True, text=True)
    print(run.stdout, run.stderr, sep="")
    if run.returncode != 0:
        return [f"overlay: plot_results.py exited with {run.returncode}"]
    failures = []
    path = os.path.join(out_dir, "pile_force_overlay.png")
    if not os.path.isfile(path) or path not in run.stdout:
        failures.append("overlay: pile_force_overlay.png was not written and printed")
    summaries = [line.split(":", 1)[1] for line in run.stdout.splitlines() if "mean pile force over the last third" in line]
    if len(summaries) != len(files):
        failures.append(f"overlay: {len(summaries)} pile summaries for {len(files)} runs")
    elif len(set(summaries)) != 1:
        failures.append(f"overlay: the same data summarised differently: {summaries}")
    return failures


def main():
    tool, sample, out_dir = sys.argv[1:4]
    missing = [m for m in ("numpy", "matplotlib", "h5py") if importlib.util.find_spec(m) is None]
    if missing:
        print(f"SKIPPED: python modules missing: {', '.join(missing)} (install python3-numpy python3-matplotlib python3-h5py)")
        return 77
    failures = check(tool, sample, os.path.join(out_dir, "sample_names"))
    renamed = os.path.join(out_dir, "coupler_names.h5")
    os.makedirs(out_dir, exist_ok=True)
    coupler_named_copy(sample, renamed)
    failures += check(tool, renamed, os.path.join(out_dir, "coupler_names"))
    failures += check_overlay(tool, [sample, renamed], os.path.join(out_dir, "overlay"))
    for failure in failures:
        print("FAIL:", failure)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
