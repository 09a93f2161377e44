#!/usr/bin/env python3
"""Plot the time series of a dfc results file (HDF5, format "dfc-results-1") as PNGs.

    plot_results.py RESULTS.h5 [--out DIR]
    plot_results.py RESULTS.h5 RESULTS.h5 ... --out DIR     (overlay of several runs)

Writes, for the columns present under /timeseries (either name is accepted;
the second is what the coupler records: "<slot>_<monitor>" and its own columns):
  pile_force_displacement.png  pile force against pile displacement
                               (pile_displacement_m | dem_pile_displacement_m,
                                pile_force_n | dem_pile_force_n)
  interface_force.png          interface force of both sides against time
                               (interface_force_<side>_<axis> | interface_force_on_<side>_<axis>,
                                side dem or continuum, axis x, y, z)
  unbalanced_force.png         unbalanced-force ratios against time, log scale
                               (ufr_<side> | <side>_unbalanced_force_ratio)
  stress_strain.png            axial stress against axial strain of a compression test
                               (dem_axial_strain, dem_axial_stress_pa), with the peak marked;
                               of a triaxial test (dem_deviatoric_stress_pa recorded) the
                               deviator q = sigma_a - sigma_3 instead
With several results files (e.g. the variants of one scenario, or the same pile
run against different continua) it writes overlays instead, one curve per run
labelled by the run's folder name:
  stress_strain_overlay.png    axial stress-strain of every run (the deviator q if every run
                               recorded one), peaks marked, and
                               prints per run: peak stress, strain at peak, initial
                               stiffness (least-squares slope of the pre-peak points
                               below 30 % of the peak) and the spread of both
                               ((max - min) / mean) across the runs
  pile_force_overlay.png       pile force against displacement of every run, and prints per run
                               the mean force over the last third of the push after first
                               contact and the final force (docs/continuum_comparison.md)
A plot whose columns are absent is skipped. The time axis is time_s if present,
else step, else exchange, else the row number. Prints the path of every file written.
The file may still be open in a running coupler: it is read without the HDF5
file lock, and shows what the coupler last flushed.

Needs numpy, matplotlib and h5py (Debian: python3-numpy python3-matplotlib python3-h5py).
"""
import argparse
import os
import sys

# The reading of results files lives in python/dfc_results (one place for the layout).
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir, "python"))

try:
    import matplotlib

    matplotlib.use("Agg")  # files only; no display needed
    import matplotlib.pyplot as plt
    import numpy as np

    import dfc_results
except ImportError as missing:  # pragma: no cover - depends on the machine
    # The Debian packages install for /usr/bin/python3; a python3 found first on
    # PATH (pyenv, venv) may not have them, so try that interpreter once.
    debian_python = "/usr/bin/python3"
    if os.path.realpath(sys.executable) != os.path.realpath(debian_python) and os.path.exists(debian_python) \
            and not os.environ.get("DFC_PLOT_REEXEC"):
        os.environ["DFC_PLOT_REEXEC"] = "1"
        os.execv(debian_python, [debian_python, os.path.abspath(__file__), *sys.argv[1:]])
    sys.exit(f"plot_results.py: {missing}; install python3-numpy python3-matplotlib python3-h5py")

SIDES = ("dem", "continuum")
AXES = ("x", "y", "z")


def column(series, *names):
    """Values of the first of `names` present with any finite value, or None.
    (The coupler records NaN where a quantity does not apply, e.g. interface
    forces in a single-participant run.)"""
    for name in names:
        if name in series and np.isfinite(series[name].values).any():
            return series[name].values
    return None


def pile_columns():
    return ("pile_displacement_m", "dem_pile_displacement_m"), ("pile_force_n", "dem_pile_force_n")


def interface_columns(side, axis):
    return (f"interface_force_{side}_{axis}", f"interface_force_on_{side}_{axis}")


def ufr_columns(side):
    return (f"ufr_{side}", f"{side}_unbalanced_force_ratio")


def time_axis(series):
    for name, label in (("time_s", "time [s]"), ("step", "step"), ("exchange", "exchange")):
        if name in series:
            return series[name].values, label
    length = max((len(s.values) for s in series.values()), default=0)
    return np.arange(length, dtype=float), "row"


def save(fig, out_dir, name):
    path = os.path.join(out_dir, name)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)
    return path


def plot_pile(series, out_dir):
    displacement_names, force_names = pile_columns()
    displacement = column(series, *displacement_names)
    force = column(series, *force_names)
    if displacement is None or force is None:
        return None
    n = min(len(displacement), len(force))
    displacement, force = displacement[:n], force[:n]
    fig, ax = plt.subplots(figsize=(6, 4.5))
    # Geotechnical convention: penetration downwards, in mm; force in kN.
    ax.plot(force / 1e3, displacement * 1e3, color="tab:blue")
    ax.set_xlabel("pile force [kN]")
    ax.set_ylabel("pile displacement [mm]")
    ax.invert_yaxis()
    ax.grid(True, alpha=0.3)
    ax.set_title("Pile load-displacement")
    return save(fig, out_dir, "pile_force_displacement.png")


def plot_interface(series, out_dir):
    present = [(side, axis, column(series, *interface_columns(side, axis))) for side in SIDES for axis in AXES]
    present = [entry for entry in present if entry[2] is not None]
    if not present:
        return None
    t, t_label = time_axis(series)
    fig, ax = plt.subplots(figsize=(7, 4.5))
    colours = {"x": "tab:red", "y": "tab:green", "z": "tab:blue"}
    for side, axis, values in present:
        n = min(len(t), len(values))
        # Action and reaction: the continuum side is drawn dashed on top of the DEM side.
        ax.plot(t[:n], values[:n], color=colours[axis], linestyle="-" if side == "dem" else "--", label=f"{side} {axis}")
    ax.set_xlabel(t_label)
    ax.set_ylabel("interface force [N]")
    ax.grid(True, alpha=0.3)
    ax.legend(ncol=2, fontsize="small")
    ax.set_title("Interface force, both sides")
    return save(fig, out_dir, "interface_force.png")


def plot_unbalanced(series, out_dir):
    present = [(side, column(series, *ufr_columns(side))) for side in SIDES]
    present = [entry for entry in present if entry[1] is not None]
    if not present:
        return None
    t, t_label = time_axis(series)
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for side, values in present:
        n = min(len(t), len(values))
        positive = values[:n] > 0  # a log axis cannot show zeros (a rigid reference side reports 0)
        ax.plot(t[:n][positive], values[:n][positive], label=side)
    ax.set_yscale("log")
    ax.set_xlabel(t_label)
    ax.set_ylabel("unbalanced-force ratio [-]")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend()
    ax.set_title("Unbalanced-force ratio")
    return save(fig, out_dir, "unbalanced_force.png")


def plot_stress_strain(series, out_dir):
    columns = stress_strain_columns(series)
    if columns is None:
        return None
    strain, stress = columns
    triaxial = is_triaxial(series)
    peak = int(np.argmax(stress))
    fig, ax = plt.subplots(figsize=(6, 4.5))
    ax.plot(strain * 100, stress / 1e3, color="tab:blue")
    ax.plot([strain[peak] * 100], [stress[peak] / 1e3], "o", color="tab:red", label=f"peak {stress[peak] / 1e3:.1f} kPa")
    ax.set_xlabel("axial strain [%]")
    ax.set_ylabel("deviator stress q [kPa]" if triaxial else "axial stress [kPa]")
    ax.grid(True, alpha=0.3)
    ax.legend()
    ax.set_title("Triaxial compression" if triaxial else "Uniaxial compression")
    return save(fig, out_dir, "stress_strain.png")


def stress_strain_columns(series, deviator=True):
    """(axial strain, stress) of a compression test: the deviator q = sigma_a - sigma_3
    of a triaxial test when recorded and `deviator`, else the axial stress."""
    strain = column(series, "axial_strain", "dem_axial_strain")
    stress = column(series, "deviatoric_stress_pa", "dem_deviatoric_stress_pa") if deviator else None
    if stress is None:
        stress = column(series, "axial_stress_pa", "dem_axial_stress_pa")
    if strain is None or stress is None:
        return None
    n = min(len(strain), len(stress))
    return strain[:n], stress[:n]


def is_triaxial(series):
    return column(series, "deviatoric_stress_pa", "dem_deviatoric_stress_pa") is not None


def initial_stiffness(strain, stress):
    """Least-squares slope through the pre-peak points below 30 % of the peak (Pa)."""
    peak = int(np.argmax(stress))
    pre = np.arange(peak + 1)
    mask = stress[pre] <= 0.3 * stress[peak]
    if mask.sum() < 2:
        return float("nan")
    return float(np.polyfit(strain[pre][mask], stress[pre][mask], 1)[0])


def spread(values):
    values = np.asarray(values, dtype=float)
    return float((values.max() - values.min()) / values.mean()) if len(values) and values.mean() != 0 else float("nan")


def plot_overlays(runs, out_dir):
    """runs: [(label, series)]; one curve per run."""
    written = []
    # The deviator when every run recorded one (triaxial tests), else the axial stress of all.
    deviator = all(is_triaxial(series) for _, series in runs)
    curves = [(label, stress_strain_columns(series, deviator)) for label, series in runs]
    curves = [(label, c) for label, c in curves if c is not None]
    if curves:
        fig, ax = plt.subplots(figsize=(6.5, 4.8))
        peaks, stiffnesses = [], []
        print(f"{'run':<24} {'peak [kPa]':>11} {'strain at peak':>15} {'E_initial [MPa]':>16}")
        for label, (strain, stress) in curves:
            peak = int(np.argmax(stress))
            stiffness = initial_stiffness(strain, stress)
            peaks.append(stress[peak])
            stiffnesses.append(stiffness)
            print(f"{label:<24} {stress[peak] / 1e3:>11.2f} {strain[peak]:>15.4e} {stiffness / 1e6:>16.2f}")
            line, = ax.plot(strain * 100, stress / 1e3, label=f"{label}: peak {stress[peak] / 1e3:.1f} kPa")
            ax.plot([strain[peak] * 100], [stress[peak] / 1e3], "o", color=line.get_color())
        print(f"spread (max - min) / mean: peak {spread(peaks) * 100:.2f} %, initial stiffness {spread(stiffnesses) * 100:.2f} %")
        ax.set_xlabel("axial strain [%]")
        ax.set_ylabel("deviator stress q [kPa]" if deviator else "axial stress [kPa]")
        ax.grid(True, alpha=0.3)
        ax.legend()
        title = "Stress-strain, " + ", ".join(label for label, _ in curves)
        ax.set_title(title if len(title) <= 60 else f"Stress-strain, {len(curves)} runs")
        written.append(save(fig, out_dir, "stress_strain_overlay.png"))
    displacement_names, force_names = pile_columns()
    piles = [(label, column(series, *displacement_names), column(series, *force_names)) for label, series in runs]
    piles = [(label, d, f) for label, d, f in piles if d is not None and f is not None]
    if piles:
        fig, ax = plt.subplots(figsize=(6.5, 4.8))
        for label, displacement, force in piles:
            n = min(len(displacement), len(force))
            late_mean, final = pile_force_summary(force[:n])
            print(f"{label}: mean pile force over the last third of the push {late_mean:.3f} N, final {final:.3f} N")
            ax.plot(force[:n] / 1e3, displacement[:n] * 1e3, label=label)
        ax.set_xlabel("pile force [kN]")
        ax.set_ylabel("pile displacement [mm]")
        ax.invert_yaxis()
        ax.grid(True, alpha=0.3)
        ax.legend()
        ax.set_title("Pile load-displacement")
        written.append(save(fig, out_dir, "pile_force_overlay.png"))
    return written


def pile_force_summary(force):
    """Mean force over the last third of the samples after first contact, and the final force (N)."""
    contact = np.flatnonzero(force > 0.0)
    pushed = force[contact[0]:] if contact.size else force
    return float(pushed[-max(1, pushed.size // 3):].mean()), float(force[-1])


def run_label(path):
    """The run's folder name (a variant's label), else the file name."""
    folder = os.path.basename(os.path.dirname(os.path.abspath(path)))
    return folder or os.path.basename(path)


def load(path):
    """All time series of one results file, {name: dfc_results.Series}."""
    try:
        with dfc_results.open_results(path) as results:
            return results.all_series()
    except dfc_results.ResultsError as error:
        sys.exit(f"plot_results.py: {error}")


def main(argv=None):
    parser = argparse.ArgumentParser(description="Plot a dfc results file (HDF5) as PNGs; several files: overlays.")
    parser.add_argument("results", nargs="+", help="results file(s) written by the coupler (.h5)")
    parser.add_argument("--out", default=None, help="output directory (default: next to the (first) results file)")
    args = parser.parse_args(argv)

    out_dir = args.out if args.out else (os.path.dirname(os.path.abspath(args.results[0])))
    os.makedirs(out_dir, exist_ok=True)
    if len(args.results) > 1:
        written = plot_overlays([(run_label(path), load(path)) for path in args.results], out_dir)
        if not written:
            print("plot_results.py: the runs have no stress-strain or pile columns to overlay")
        for path in written:
            print(path)
        return 0
    args.results = args.results[0]
    series = load(args.results)

    plots = (plot_pile, plot_interface, plot_unbalanced, plot_stress_strain)
    written = [path for path in (plot(series, out_dir) for plot in plots) if path]
    if not written:
        print(f"plot_results.py: no plottable columns in '{args.results}' (have: {', '.join(sorted(series)) or 'none'})")
    for path in written:
        print(path)
    return 0


if __name__ == "__main__":
    sys.exit(main())
