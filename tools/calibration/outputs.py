"""What a calibration writes into its output folder:

  material.json      the calibrated contact block, for "contact": {"include": ".../material.json"}
  summary.json/.md   parameters, achieved values with their scatter over the packings (mean, min, max),
                     the number of DEM runs and the wall time
  history.json/.png  every evaluation: phase, parameters, means, objective (the convergence history)
  sensitivity.json/.md/.png   d ln(target) / d ln(parameter) at the optimum
"""
import json
import os

import matplotlib

matplotlib.use("Agg")  # files only
import matplotlib.pyplot as plt  # noqa: E402


def write_json(path, data):
    tmp = path + ".tmp"
    with open(tmp, "w") as f:
        json.dump(data, f, indent=1)
        f.write("\n")
    os.replace(tmp, path)


def write_material(path, law, contact, comment):
    """The contact block in the layout of scenarios/materials/*.json."""
    material = {"_comment": comment, "law": law}
    material.update({k: v for k, v in sorted(contact.items()) if k != "law"})
    os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
    write_json(path, material)


def achieved_table(targets, evaluation):
    rows = []
    for t in targets:
        s = evaluation.scatter(t.name)
        rows.append({"target": t.name, "value": t.value, "tolerance": t.tolerance, "mean": s["mean"], "min": s["min"], "max": s["max"],
                     "relative_error": t.relative_error(s["mean"]), "within_tolerance": abs(t.relative_error(s["mean"])) <= t.tolerance})
    return rows


def convergence_phrase(summary):
    """Converged (every target inside its tolerance), stopped at the noise floor (inside the
    larger of tolerance and standard error: search.within_noise), or not converged."""
    if summary["converged"]:
        return "Converged"
    if summary.get("stopped_at_noise_floor"):
        return "Stopped at the noise floor (every target within its tolerance or its mean's standard error over the packings)"
    return "NOT converged"


def write_summary_md(path, summary):
    lines = [f"# Calibration {summary['name']} ({summary['law']})", "",
             f"{convergence_phrase(summary)}: {summary['evaluations']} evaluations, "
             f"{summary['dem_runs']} DEM runs ({summary['dem_runs_this_session']} run in this session, the rest from the cache), "
             f"DEM wall time {summary['dem_wall_s']:.0f} s over all runs, this session {summary['session_wall_s']:.0f} s.", "",
             "| parameter | start | calibrated |", "|---|---:|---:|"]
    for name, value in summary["parameters"].items():
        lines.append(f"| {name} | {summary['start'][name]:.4g} | {value:.4g} |")
    lines += ["", "| target | value | tolerance | mean | min | max | error |", "|---|---:|---:|---:|---:|---:|---:|"]
    for r in summary["achieved"]:
        lines.append(f"| {r['target']} | {r['value']:.4g} | {r['tolerance'] * 100:.1f} % | {r['mean']:.4g} | {r['min']:.4g} | "
                     f"{r['max']:.4g} | {r['relative_error'] * 100:+.1f} % |")
    lines += ["", f"Material file: {summary['material']}"]
    lines += [f"Warning: {w}" for w in summary.get("warnings", [])]
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")


def plot_history(path, targets, history):
    fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(7, 6), sharex=True)
    index = [h["evaluation"] for h in history]
    ax1.semilogy(index, [max(h["objective"], 1e-6) for h in history], "o-", color="k")
    ax1.axhline(len(targets), color="grey", ls=":", label="every target at its tolerance")
    ax1.set_ylabel("objective")
    ax1.legend(fontsize=8)
    for t in targets:
        # The mean's error, and the packings' min and max as the bar.
        error = [100 * t.relative_error(h["scatter"][t.name]["mean"]) for h in history]
        low = [e - 100 * t.relative_error(h["scatter"][t.name]["min"]) for e, h in zip(error, history)]
        high = [100 * t.relative_error(h["scatter"][t.name]["max"]) - e for e, h in zip(error, history)]
        ax2.errorbar(index, error, yerr=[low, high], fmt="o-", capsize=2, label=t.name)
        ax2.axhspan(-100 * t.tolerance, 100 * t.tolerance, alpha=0.08)
    ax2.set_ylabel("error of the mean [%]\n(bars: packings' min-max)")
    ax2.set_xlabel("evaluation (each: every experiment on every packing)")
    ax2.legend(fontsize=8)
    for before, h in zip([None] + history[:-1], history):
        if before is None or h["phase"] != before["phase"]:   # where each phase begins
            ax1.annotate(h["phase"], (h["evaluation"], max(h["objective"], 1e-6)), fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def write_sensitivity(folder, targets, names, table):
    """table: {parameter: {target: d ln y / d ln p}}."""
    write_json(os.path.join(folder, "sensitivity.json"), table)
    lines = ["| d ln(target) / d ln(parameter) | " + " | ".join(names) + " |", "|---|" + "---:|" * len(names)]
    for t in targets:
        lines.append(f"| {t.name} | " + " | ".join(f"{table[n][t.name]:+.2f}" for n in names) + " |")
    with open(os.path.join(folder, "sensitivity.md"), "w") as f:
        f.write("\n".join(lines) + "\n")
    grid = [[table[n][t.name] for n in names] for t in targets]
    fig, ax = plt.subplots(figsize=(1.6 + 1.4 * len(names), 1.2 + 0.6 * len(targets)))
    image = ax.imshow(grid, cmap="RdBu_r", vmin=-1.5, vmax=1.5, aspect="auto")
    ax.set_xticks(range(len(names)), names, rotation=20, fontsize=8)
    ax.set_yticks(range(len(targets)), [t.name for t in targets], fontsize=8)
    for i, row in enumerate(grid):
        for j, v in enumerate(row):
            ax.text(j, i, f"{v:+.2f}", ha="center", va="center", fontsize=8)
    fig.colorbar(image, ax=ax, label="d ln y / d ln p")
    ax.set_title("Sensitivity at the optimum", fontsize=9)
    fig.tight_layout()
    fig.savefig(os.path.join(folder, "sensitivity.png"), dpi=110)
    plt.close(fig)
