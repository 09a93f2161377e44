#!/usr/bin/env python3
"""Draw the pile force-penetration curves of several runs on one PNG, to compare
the same DEM model against different continua (docs/continuum_comparison.md).

    plot_continuum_comparison.py LABEL=RESULTS.h5 [LABEL=RESULTS.h5 ...] --out FILE.png

Each RESULTS.h5 is a coupler results file ("dfc-results-1"); the curve is
/timeseries/dem_pile_force_n against the penetration /timeseries/dem_pile_displacement_m
(positive downwards). Besides the PNG it prints, per run, the mean pile force
over the last third of the samples after first contact and the final force,
the numbers docs/continuum_comparison.md quotes.

Needs numpy, matplotlib and h5py (Debian: python3-numpy python3-matplotlib python3-h5py).
"""
import argparse
import os
import sys

os.environ.setdefault("HDF5_USE_FILE_LOCKING", "FALSE")  # as tools/plot_results.py: read a run in progress

try:
    import h5py
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np
except ImportError as missing:  # pragma: no cover - depends on the machine
    sys.exit(f"plot_continuum_comparison.py needs numpy, matplotlib and h5py: {missing}")


def pile_curve(path):
    with h5py.File(path, "r") as results:
        series = results["timeseries"]
        for column in ("dem_pile_displacement_m", "dem_pile_force_n"):
            if column not in series:
                sys.exit(f"{path}: no /timeseries/{column}; is this a pile run?")
        return np.asarray(series["dem_pile_displacement_m"]), np.asarray(series["dem_pile_force_n"])


def summary(force):
    """Mean force over the last third of the samples after first contact, and the final force."""
    contact = np.flatnonzero(force > 0.0)
    pushed = force[contact[0]:] if contact.size else force
    return pushed[-max(1, pushed.size // 3):].mean(), force[-1]


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("runs", nargs="+", metavar="LABEL=RESULTS.h5")
    parser.add_argument("--out", required=True, help="PNG file to write")
    args = parser.parse_args()

    figure, axes = plt.subplots(figsize=(7, 4.5))
    for run in args.runs:
        label, sep, path = run.partition("=")
        if not sep:
            sys.exit(f"expected LABEL=RESULTS.h5, got '{run}'")
        penetration, force = pile_curve(path)
        late_mean, final = summary(force)
        print(f"{label}: mean pile force over the last third of the push {late_mean:.3f} N, final {final:.3f} N")
        axes.plot(1e3 * penetration, force, lw=1.0, label=label)
    axes.set_xlabel("pile displacement (downwards) [mm]")
    axes.set_ylabel("pile force [N]")
    axes.set_title("Pile force against penetration: the same DEM bed, three continua")
    axes.grid(True, alpha=0.3)
    axes.legend()
    figure.tight_layout()
    os.makedirs(os.path.dirname(os.path.abspath(args.out)), exist_ok=True)
    figure.savefig(args.out, dpi=120)
    print(args.out)


if __name__ == "__main__":
    main()
