#!/usr/bin/env python3
"""The foundation study at several particle sizes (docs/resolution.md): runs its
variants in parts that survive a stopped machine, and compares the resolutions.

    tools/resolution_study.py run SCENARIO.json [SCENARIO.json ...] --runs DIR
                                  [--labels g1_p1,g100_p1,...] [--jobs 2] [--bin BUILD/bin]
    tools/resolution_study.py summary DIR [--out docs/figures/resolution]

run: every variant of each scenario (scenarios/centrifuge_pile_gravity.json is
S = 3, scenarios/foundation_resolution_S2.json and _S4.json the others) in
DIR/<scenario name>/<label>/, --jobs at a time (default 2: one DEM thread each
on a 2-core machine). A variant whose folder holds DONE is skipped; one with a
checkpoint (run.checkpoint_every, or Ctrl-C) is continued with `coupler run
--resume`; any other folder is started again. --bin names the folder of the
coupler and the servers: copy a build's bin/ aside for a study that lasts
days, so that rebuilding the project does not change the solver under a
resumed run (the resume would refuse it). Each run's output goes to
DIR/<scenario name>/<label>.log.

summary: for each DIR/<scenario name>/ with finished runs, the figures and
summary.json of tools/centrifuge_foundation.py in that folder, then, in --out,
  resolution_summary.json   per resolution S: particles, d50, steps, wall time,
                            and each measure of the study per g-level (mean,
                            min, max over packings); the inertial number; the
                            verdict per measure (converged or not)
  force_penetration.png     force against h_1/D_f per g-level, one band
                            (min-max over packings) per resolution
  measures_vs_size.png      the study's measures against the particle diameter
  curves_S<S>.json          the bands of force_penetration.png (so the figures
                            can be redrawn without the results files)
  resolution_table.md       the tables of docs/resolution.md
A resolution already in --out (resolution_summary.json and its curves_S<S>.json)
whose runs are not under DIR is kept as it is, so a study whose machine was
lost keeps the resolutions it finished; where DIR has runs of that resolution
too, the earlier packings are merged with them g-level by g-level (means
weighted by the packing counts, ranges and bands widened; a packing run again
replaces the earlier aggregate that held it). So a resolution can be finished
over several machines, one committed summary at a time. A run the earlier
summary already holds (recorded per g-level and packing by its wall time and
DEM steps) is not merged again: the runs folder may be given whole after every
run. --replace drops everything whose runs are not under DIR.

The inertial number of a run (GDR MiDi 2004; da Cruz et al. 2005) is
I = gamma_dot d / sqrt(p / rho_s) with the shear rate gamma_dot = v / D_f of
the foundation, d the mean sphere diameter, p the mean tip pressure
F_tip / (pi D_f^2 / 4) and rho_s the grain density: quasi-static for
I < 1e-3. It is reported along the loading (median and largest over
h_1 = 0.05-1 D_f, after the collapse of the initial peak).

A measure is converged where the two finest resolutions' means differ by no
more than the larger of their half-ranges (per g-level: the two finest that
have finished runs at that g-level) (the scatter over packings): a
difference inside the scatter does not count (docs/resolution.md).

Exit status: 0 done; 1 a run failed; 2 bad input; 3 nothing to summarise.
"""
import argparse
import concurrent.futures
import json
import math
import os
import shutil
import subprocess
import tempfile
import sys
import time

TOOLS = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(TOOLS)


def expand(coupler, scenario):
    out = subprocess.run([coupler, "expand", scenario], capture_output=True, text=True)
    if out.returncode != 0:
        raise SystemExit(f"resolution_study.py: coupler expand {scenario} failed:\n{out.stderr.strip()}")
    documents = json.loads(out.stdout)
    return documents if isinstance(documents, list) else [documents]


def plan(coupler, scenarios, runs_dir, labels):
    """[(label, scenario file to write, document, run folder, log)] in the order given."""
    jobs = []
    for scenario in scenarios:
        with open(scenario) as f:
            name = json.load(f).get("name") or os.path.splitext(os.path.basename(scenario))[0]
        for document in expand(coupler, scenario):
            label = os.path.basename(os.path.normpath(document["output"]["directory"]))
            if labels and label not in labels:
                continue
            folder = os.path.join(runs_dir, name)
            jobs.append((f"{name}/{label}", os.path.join(folder, label + ".json"), document, os.path.join(folder, label),
                         os.path.join(folder, label + ".log")))
    return jobs


def run_one(coupler, job, nice):
    name, scenario_file, document, folder, log = job
    if os.path.isfile(os.path.join(folder, "DONE")):
        return name, "done before", 0
    os.makedirs(os.path.dirname(scenario_file), exist_ok=True)
    prefix = ["nice", "-n", str(nice)] if nice else []
    if os.path.isdir(os.path.join(folder, "checkpoint")):
        command, how = prefix + [coupler, "run", "--resume", folder, "--no-progress"], "resumed"
    else:
        if os.path.isdir(folder):
            shutil.rmtree(folder)  # a run stopped before its first checkpoint: start again
        with open(scenario_file, "w") as f:
            json.dump(document, f, indent=2)
        command, how = prefix + [coupler, "run", scenario_file, "--out", folder, "--no-progress"], "started"
    start = time.time()
    with open(log, "a") as out:
        out.write(f"\n== {how} {time.strftime('%Y-%m-%d %H:%M:%S')}: {' '.join(command)}\n")
        out.flush()
        code = subprocess.run(command, stdout=out, stderr=subprocess.STDOUT).returncode
    if code == 0:
        with open(os.path.join(folder, "DONE"), "w") as f:
            f.write(f"{time.time() - start:.1f} s of this part\n")
    return name, f"{how}, rc {code}, {time.time() - start:.0f} s", code


def command_run(args):
    coupler = os.path.join(args.bin, "coupler")
    if not os.access(coupler, os.X_OK):
        print(f"resolution_study.py: no coupler in {args.bin} (--bin: a build's bin folder)", file=sys.stderr)
        return 2
    labels = set(args.labels.split(",")) if args.labels else None
    jobs = plan(coupler, args.scenarios, args.runs, labels)
    if not jobs:
        print("resolution_study.py: no variant matches --labels", file=sys.stderr)
        return 2
    failed = 0
    with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as pool:
        for name, what, code in pool.map(lambda job: run_one(coupler, job, args.nice), jobs):
            print(f"{name}: {what}", flush=True)
            failed += code != 0
    return 1 if failed else 0


# ---------------------------------------------------------------- summary

MEASURES = [("mean_force_n_0.25_to_1D", "mean force over h$_1$ = 0.25-1 D$_f$ (N)", "mean force over h₁ = 0.25–1 D_f"),
            ("peak_force_n", "peak force (N)", "peak force"),
            ("broken_fraction_at_collapse_beneath_tip", "broken fraction beneath the tip at the collapse",
             "broken fraction beneath the tip at the collapse")]
QUASI_STATIC_I = 1e-3  # GDR MiDi (2004): below it the stresses no longer depend on the rate


def inertial_numbers(run, grain_density):
    """I along h_1 = 0.05-1 D_f (module docstring), from the run's tip force."""
    import numpy as np
    d = 2.0 * run.mean_radius
    rate = run.velocity / run.diameter
    stage = (run.h >= 0.05 * run.diameter) & (run.h <= 1.0 * run.diameter) & (run.tip > 0)
    pressure = run.tip[stage] / run.area
    return rate * d / np.sqrt(pressure / grain_density)


def load_runs(folder):
    """The finished foundation runs of one resolution, each with its scale factor,
    grain density and mean sphere radius (first DEM snapshot)."""
    import numpy as np
    sys.path.insert(0, TOOLS)
    import centrifuge_foundation as cf
    from dfc_results import open_results
    runs = cf.find_runs(folder)
    for run in runs:
        with open_results(run.path) as r:
            dem = r.scenario["participants"]["dem"]["config"]
            run.scale = float(dem.get("upscaling", {}).get("scale_factor", 1.0))
            run.grain_density = float(dem["particles"].get("density_kg_m3", 2650.0))
            run.mean_radius = float(np.mean(r.snapshot("dem", 0).arrays["particle_radius"]))
    return runs


def verdict(fine, coarse):
    """Converged where the two finest resolutions' means differ by no more than
    the larger of their half-ranges (module docstring)."""
    if not all(math.isfinite(x.get(k, float("nan"))) for x in (fine, coarse) for k in ("mean", "min", "max")) \
            or min(fine.get("n", 0), coarse.get("n", 0)) < 2:
        return {"verdict": "not enough runs"}  # a scatter needs two packings at least
    difference = abs(fine["mean"] - coarse["mean"])
    scatter = max(fine["max"] - fine["min"], coarse["max"] - coarse["min"]) / 2.0
    return {"verdict": "converged" if difference <= scatter else "not converged", "difference": difference, "scatter": scatter}


def packings_at(level):
    """The number of packings behind a g-level's measures."""
    return min((m.get("n", 0) for m in level.values() if isinstance(m, dict) and "n" in m), default=0)


def verdicts_by_g_level(resolutions, scales):
    """{g: {"finest", "next", measure: verdict}}: each g-level's two finest resolutions with
    at least two packings there compared (a finer resolution may have only some g-levels
    finished yet, or one packing of them)."""
    verdicts = {}
    levels = sorted({g for s in scales for g in resolutions[s]["g_levels"]}, key=float)
    for g in levels:
        # coarse to fine; a scatter needs two packings, so a resolution with one run there waits
        having = [s for s in scales if g in resolutions[s]["g_levels"] and packings_at(resolutions[s]["g_levels"][g]) >= 2]
        if len(having) < 2:
            continue
        fine, coarse = resolutions[having[-1]]["g_levels"][g], resolutions[having[-2]]["g_levels"][g]
        verdicts[g] = {"finest": f"{having[-1]:g}", "next": f"{having[-2]:g}",
                       **{key: verdict(fine.get(key, {}), coarse.get(key, {})) for key, _, _ in MEASURES}}
    return verdicts


def earlier_resolutions(out):
    """The resolutions of an earlier summary in OUT, each with its curves, keyed by S;
    {} where there is none (module docstring)."""
    path = os.path.join(out, "resolution_summary.json")
    if not os.path.isfile(path):
        return {}
    with open(path) as f:
        earlier = json.load(f).get("resolutions", {})
    kept = {}
    for key, entry in earlier.items():
        curves = os.path.join(out, f"curves_S{float(key):g}.json")
        if not os.path.isfile(curves):
            continue  # the figures cannot be redrawn without the bands: recompute or drop
        with open(curves) as f:
            kept[float(key)] = dict(entry, curves=json.load(f))
    return kept


def merge_spread(a, b):
    """Two spreads of tools/centrifuge_foundation.py (mean, min, max, n) over disjoint
    packings as one: the mean weighted by the counts, the extremes of both."""
    def count(x):
        return x.get("n", 0) if math.isfinite(x.get("mean", float("nan"))) else 0
    na, nb = count(a), count(b)
    if na == 0 or nb == 0:
        return dict(b if na == 0 else a)
    mean = (na * a["mean"] + nb * b["mean"]) / (na + nb)
    low, high = min(a["min"], b["min"]), max(a["max"], b["max"])
    return {"mean": mean, "min": low, "max": high, "spread": (high - low) / mean if mean else float("nan"), "n": na + nb}


def merge_curve(a, b):
    """Two force bands of the same grid over disjoint packings as one (pointwise
    weighted mean, extremes of both; a point one band lacks is the other's)."""
    import numpy as np
    na, nb = a["packings"], b["packings"]
    merged = {"h_over_d": a["h_over_d"], "packings": na + nb}
    for key, combine in (("mean_n", None), ("min_n", np.fmin), ("max_n", np.fmax)):
        x, y = np.asarray(a[key], dtype=float), np.asarray(b[key], dtype=float)
        if combine is None:
            both = (na * x + nb * y) / (na + nb)
            value = np.where(np.isnan(x), y, np.where(np.isnan(y), x, both))
        else:
            value = combine(x, y)  # fmin/fmax ignore a NaN on one side
        merged[key] = [float(v) for v in value]
    return merged


def merge_level(earlier, fresh):
    """A g-level's measures over the earlier packings and the fresh ones (disjoint):
    each spread merged; the inertial number's median is the larger of the two parts'
    medians (the runs behind the earlier median are gone; the larger one is the
    conservative side of the quasi-static criterion) and its maximum the larger one."""
    merged = {}
    for key in set(earlier) | set(fresh):
        a, b = earlier.get(key), fresh.get(key)
        if key == "packings":
            merged[key] = sorted(set(a or []) | set(b or []))
        elif key == "runs":
            merged[key] = {**(a or {}), **(b or {})}
        elif key == "inertial_number":
            parts = [x for x in (a, b) if x]
            merged[key] = {k: max(x[k] for x in parts) for k in ("median", "max")} if parts else {}
        elif isinstance(a, dict) and isinstance(b, dict) and "mean" in a and "mean" in b:
            merged[key] = merge_spread(a, b)
        else:
            merged[key] = b if b is not None else a
    return merged


def run_fingerprint(run):
    """What tells one run from another of the same variant: its wall time and
    DEM steps to the last digit (a run made again differs at least in its wall time)."""
    return f"{float(run.summary.get('wall_time_s', float('nan'))):.17g}/{float(run.summary.get('dem_steps', float('nan'))):.17g}"


def already_summarised(runs, earlier):
    """The runs an earlier summary's entry of their resolution holds already (the
    same packing and g-level, the same fingerprint): summarised again, each would
    replace the whole group that holds it and drop that group's other packings."""
    levels = (earlier or {}).get("g_levels", {})
    return [r for r in runs if levels.get(f"{r.g_level:g}", {}).get("runs", {}).get(str(r.seed)) == run_fingerprint(r)]


def linked_subset(folder, runs, into):
    """A folder `into` of links to the given runs of `folder` (their results
    folders, scenario and log files): what centrifuge_foundation.py summarises."""
    os.makedirs(into, exist_ok=True)
    for run in runs:
        label = run.label  # the run's folder: <folder>/<label>/results.h5
        for name in (label, label + ".json", label + ".log"):
            if os.path.exists(os.path.join(folder, name)):
                os.symlink(os.path.abspath(os.path.join(folder, name)), os.path.join(into, name))
    return into


def merge_resolution(earlier, fresh, scale):
    """One resolution from an earlier summary's entry (whose runs are gone) and the
    runs present now: a g-level only one side has is taken as it is; one both have
    is merged where their packings are disjoint; where the fresh runs repeat packings
    of the earlier ones, the fresh runs replace them (an earlier aggregate cannot be
    split: its other packings are dropped, and said)."""
    merged = dict(fresh, g_levels=dict(fresh["g_levels"]), curves=dict(fresh["curves"]))
    added = 0
    for g, level in earlier["g_levels"].items():
        if g not in earlier.get("curves", {}):
            print(f"S = {scale:g}, {g} g: the earlier summary has no force band for it (curves_S{scale:g}.json): not kept")
            continue
        if g not in fresh["g_levels"]:
            merged["g_levels"][g], merged["curves"][g] = level, earlier["curves"][g]
            added += len(level.get("packings", []))
            print(f"S = {scale:g}, {g} g: packings {level.get('packings')} kept from the earlier summary (their runs are gone)")
            continue
        old, new = set(level.get("packings", [])), set(fresh["g_levels"][g].get("packings", []))
        if old & new:
            if old - new:
                print(f"S = {scale:g}, {g} g: the runs present repeat packings {sorted(old & new)} of the earlier summary, "
                      f"whose packings {sorted(old - new)} cannot be separated from them: dropped")
            continue
        merged["g_levels"][g] = merge_level(level, fresh["g_levels"][g])
        merged["curves"][g] = merge_curve(earlier["curves"][g], fresh["curves"][g])
        added += len(old)
        print(f"S = {scale:g}, {g} g: packings {sorted(old)} of the earlier summary merged with the runs present {sorted(new)}")
    if added:
        for key in ("particles", "dem_steps", "wall_time_s"):
            merged[key] = merge_spread(earlier[key], fresh[key])
        runs = fresh["particles"].get("n", 0)
        merged["mean_diameter_m"] = (runs * fresh["mean_diameter_m"] + added * earlier["mean_diameter_m"]) / (runs + added)
    return merged


def command_summary(args):
    import numpy as np
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    sys.path.insert(0, TOOLS)
    import centrifuge_foundation as cf
    if not os.path.isdir(args.runs):
        print(f"resolution_study.py: no such folder '{args.runs}'", file=sys.stderr)
        return 2
    resolutions = {}
    earlier = {} if args.replace else earlier_resolutions(args.out)
    scratch = tempfile.TemporaryDirectory()
    for name in sorted(os.listdir(args.runs)):
        folder = os.path.join(args.runs, name)
        if not os.path.isdir(folder):
            continue
        runs = load_runs(folder)
        if not runs:
            continue
        # Runs a committed summary already holds are not summarised again (each
        # would replace its whole group): the rest are, from a folder of links.
        known = already_summarised(runs, earlier.get(runs[0].scale))
        if known:
            print(f"S = {runs[0].scale:g}: {', '.join(r.label for r in known)} "
                  f"already in {args.out}/resolution_summary.json: not merged again")
            runs = [r for r in runs if r not in known]
            if not runs:
                continue
            folder = linked_subset(folder, runs, os.path.join(scratch.name, name))
        if subprocess.run([sys.executable, os.path.join(TOOLS, "centrifuge_foundation.py"), folder]).returncode != 0:
            print(f"resolution_study.py: centrifuge_foundation.py failed on {folder}", file=sys.stderr)
            return 1
        with open(os.path.join(folder, "summary.json")) as f:
            study = json.load(f)
        groups, _ = cf.study_groups(runs)
        scale = runs[0].scale
        entry = {"scenario": name, "scale_factor": scale, "mean_diameter_m": float(np.mean([2 * r.mean_radius for r in runs])),
                 "particles": cf.spread([float(r.series["dem_particle_count"][-1]) for r in runs]),
                 "dem_steps": cf.spread([float(r.summary.get("dem_steps", float("nan"))) for r in runs]),
                 "wall_time_s": cf.spread([float(r.summary.get("wall_time_s", float("nan"))) for r in runs]),
                 "g_levels": {}, "curves": {}}
        for g, members in groups.items():
            level = dict(study["g_levels"][f"{g:g}"])
            numbers = np.concatenate([inertial_numbers(r, r.grain_density) for r in members])
            level["inertial_number"] = {"median": float(np.median(numbers)), "max": float(np.max(numbers))} if len(numbers) else {}
            # The runs the level holds, by packing (summarise_once).
            level["runs"] = {str(r.seed): run_fingerprint(r) for r in members}
            entry["g_levels"][f"{g:g}"] = level
            grid = np.linspace(0.0, 1.15, 231) * members[0].diameter
            mean, low, high = cf.band(members, grid, lambda r: r.force)
            entry["curves"][f"{g:g}"] = {"h_over_d": (grid / members[0].diameter).tolist(), "mean_n": mean.tolist(),
                                         "min_n": low.tolist(), "max_n": high.tolist(), "packings": len(members)}
        resolutions[scale] = entry
    if not args.replace:
        for scale, entry in earlier.items():
            if scale not in resolutions:
                print(f"S = {scale:g}: kept from {args.out}/resolution_summary.json (its runs are not under {args.runs})")
                resolutions[scale] = entry
            else:
                resolutions[scale] = merge_resolution(entry, resolutions[scale], scale)
    if not resolutions:
        print(f"resolution_study.py: no finished foundation run under {args.runs}", file=sys.stderr)
        return 3
    os.makedirs(args.out, exist_ok=True)
    scales = sorted(resolutions, reverse=True)  # coarse to fine
    for s in scales:
        with open(os.path.join(args.out, f"curves_S{s:g}.json"), "w") as f:
            json.dump(resolutions[s].pop("curves"), f)
    verdicts = verdicts_by_g_level(resolutions, scales)
    ordering = {f"{s:g}": [g for g, _ in sorted(resolutions[s]["g_levels"].items(),
                                                key=lambda item: item[1]["mean_force_n_0.25_to_1D"]["mean"])] for s in scales}
    summary = {"resolutions": {f"{s:g}": resolutions[s] for s in scales},
               "verdicts": {"by_g_level": verdicts},
               "g_levels_by_mean_force": ordering, "quasi_static_inertial_number": QUASI_STATIC_I}
    with open(os.path.join(args.out, "resolution_summary.json"), "w") as f:
        json.dump(summary, f, indent=1)
    plot_summary(args.out, scales, plt)
    with open(os.path.join(args.out, "resolution_table.md"), "w") as f:
        f.write(markdown_tables(summary, scales))
    for s in scales:
        e = resolutions[s]
        print(f"S = {s:g}: d = {1e3 * e['mean_diameter_m']:.2f} mm, {e['particles']['mean']:.0f} spheres, "
              f"{e['dem_steps']['mean']:.3g} steps, {e['wall_time_s']['mean'] / 60:.1f} min per run; g-levels by mean force: {ordering[f'{s:g}']}")
    print(f"wrote {args.out}/resolution_summary.json, force_penetration.png, measures_vs_size.png")
    return 0


def markdown_tables(summary, scales):
    """The tables of docs/resolution.md: one row per resolution and g-level, then the verdicts."""
    def band(x, scale=1.0, digits=1):
        if not x or "min" not in x:
            return f"{scale * x.get('mean', float('nan')):.{digits}f}" if x else ""
        return f"{scale * x['mean']:.{digits}f} ({scale * x['min']:.{digits}f}–{scale * x['max']:.{digits}f})"
    lines = ["| S | d (mm) | spheres | DEM steps | min per run | g | packings | mean force 0.25–1 D_f (N) | peak force (N) "
             "| broken beneath tip at collapse | balance without damping (%) | inertial number, median / max |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for s in scales:
        e = summary["resolutions"][f"{s:g}"]
        for g, level in sorted(e["g_levels"].items(), key=lambda item: float(item[0])):
            i = level.get("inertial_number", {})
            lines.append(f"| {s:g} | {1e3 * e['mean_diameter_m']:.2f} | {e['particles']['mean']:.0f} | {e['dem_steps']['mean']:.3g} "
                         f"| {e['wall_time_s']['mean'] / 60:.1f} | {float(g):g} | {level['mean_force_n_0.25_to_1D'].get('n', 1)} "
                         f"| {band(level['mean_force_n_0.25_to_1D'])} | {band(level['peak_force_n'], digits=0)} "
                         f"| {band(level['broken_fraction_at_collapse_beneath_tip'], digits=2)} "
                         f"| {band(level['balance_without_damping'], 100.0, 2)} "
                         f"| {i.get('median', float('nan')):.1e} / {i.get('max', float('nan')):.1e} |")
    verdicts = summary["verdicts"]
    if verdicts["by_g_level"]:
        lines += ["", "Verdicts, each g-level's two finest resolutions (converged: the means differ by no more than "
                  "the larger half-range over packings):", "",
                  "| g | S compared | " + " | ".join(text for _, _, text in MEASURES) + " |",
                  "|---|---|" + "---|" * len(MEASURES)]
        for g, by_measure in sorted(verdicts["by_g_level"].items(), key=lambda item: float(item[0])):
            cells = []
            for key, _, _ in MEASURES:
                v = by_measure[key]
                cells.append(v["verdict"] if "difference" not in v else f"{v['verdict']} ({v['difference']:.3g} against {v['scatter']:.3g})")
            lines.append(f"| {float(g):g} | {by_measure['finest']} against {by_measure['next']} | " + " | ".join(cells) + " |")
    lines += ["", "g-levels by mean force 0.25–1 D_f, lowest first: " +
              "; ".join(f"S = {s}: {', '.join(g + ' g' for g in order)}" for s, order in summary["g_levels_by_mean_force"].items())]
    return "\n".join(lines) + "\n"


def plot_summary(out, scales, plt):
    """force_penetration.png and measures_vs_size.png from the files in `out`."""
    with open(os.path.join(out, "resolution_summary.json")) as f:
        summary = json.load(f)
    curves = {s: json.load(open(os.path.join(out, f"curves_S{s:g}.json"))) for s in scales}
    g_levels = sorted({g for s in scales for g in curves[s]}, key=float)
    fig, axes = plt.subplots(1, len(g_levels), figsize=(3.6 * len(g_levels), 3.8), sharey=True, squeeze=False)
    for ax, g in zip(axes[0], g_levels):
        for s in scales:
            if g not in curves[s]:
                continue
            c = curves[s][g]
            line, = ax.plot(c["h_over_d"], c["mean_n"], lw=1.2, label=f"S = {s:g} ({c['packings']})")
            ax.fill_between(c["h_over_d"], c["min_n"], c["max_n"], color=line.get_color(), alpha=0.2, lw=0)
        ax.set_title(f"{float(g):g} g")
        ax.set_xlabel("h$_1$ / D$_f$")
        # The initial peak (several hundred newtons, a measure of its own) is cut so
        # that the post-collapse resistance the resolutions are compared on shows.
        after = [max(v for h, v in zip(curves[s][g]["h_over_d"], curves[s][g]["max_n"]) if h > 0.1 and v == v)
                 for s in scales if g in curves[s]]
        ax.set_ylim(0, 1.3 * max(after) if after else None)
        ax.grid(alpha=0.3)
    axes[0][0].set_ylabel("foundation force (N; initial peak cut)")
    axes[0][0].legend(fontsize=8, title="upscaling (packings)", title_fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "force_penetration.png"), dpi=130)
    plt.close(fig)
    fig, axes = plt.subplots(1, len(MEASURES), figsize=(4.0 * len(MEASURES), 3.6), squeeze=False)
    widest = 1e3 * max(summary["resolutions"][f"{s:g}"]["mean_diameter_m"] for s in scales)
    for ax, (key, label, _) in zip(axes[0], MEASURES):
        for g in g_levels:
            xs, ms, lo, hi = [], [], [], []
            for s in scales:
                level = summary["resolutions"][f"{s:g}"]["g_levels"].get(g)
                if level and key in level and "min" in level[key]:
                    xs.append(1e3 * summary["resolutions"][f"{s:g}"]["mean_diameter_m"])
                    ms.append(level[key]["mean"])
                    lo.append(level[key]["mean"] - level[key]["min"])
                    hi.append(level[key]["max"] - level[key]["mean"])
            if xs:
                ax.errorbar(xs, ms, yerr=[lo, hi], marker="o", capsize=3, label=f"{float(g):g} g")
        ax.set_xlabel("mean sphere diameter d (mm)")
        ax.set_ylabel(label, fontsize=8)
        ax.set_xlim(0, 1.15 * widest)
        ax.grid(alpha=0.3)
    axes[0][0].legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "measures_vs_size.png"), dpi=130)
    plt.close(fig)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0], formatter_class=argparse.RawDescriptionHelpFormatter,
                                     epilog=__doc__.split("\n\n", 1)[1])
    sub = parser.add_subparsers(dest="command", required=True)
    run = sub.add_parser("run", help="run the variants of the scenarios, resuming where checkpoints exist")
    run.add_argument("scenarios", nargs="+")
    run.add_argument("--runs", required=True, help="folder of the runs (outside the work tree: they outlive a session)")
    run.add_argument("--labels", help="comma-separated variant labels to run (default: all)")
    run.add_argument("--jobs", type=int, default=2)
    run.add_argument("--nice", type=int, default=0, help="niceness of the runs (0: as this process)")
    run.add_argument("--bin", default=os.path.join(ROOT, "build", "bin"))
    summary = sub.add_parser("summary", help="compare the resolutions of finished runs")
    summary.add_argument("runs")
    summary.add_argument("--out", default=os.path.join(ROOT, "docs", "figures", "resolution"))
    summary.add_argument("--replace", action="store_true",
                         help="drop what an earlier summary in --out holds of runs that are not under RUNS (by default it is kept or merged)")
    args = parser.parse_args(argv)
    return command_run(args) if args.command == "run" else command_summary(args)


if __name__ == "__main__":
    sys.exit(main())
