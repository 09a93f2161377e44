#!/usr/bin/env python3
"""./vc report: rerun the scenarios whose figures the documentation quotes and
write docs/results.md (with its figures under docs/figures/) from what they measure.

    tools/report.py BUILD_DIR [ITEM ...]      rerun the items named (default: all of them)
    tools/report.py BUILD_DIR --list          list the items, their scenarios and run times
    tools/report.py BUILD_DIR --page-only     rewrite docs/results.md from docs/results.json
    tools/report.py BUILD_DIR --remeasure [ITEM ...]   read the last runs again (after a change of what is measured)

Every item is one row of ITEMS below: a shipped scenario (or a command), what
it shows, and what is read back from its results. A run stores its measured
values with the date, the commit, the machine and the wall time in
docs/results.json; docs/results.md is written from that record alone, so no
figure on the page is typed by hand. An item that was not rerun keeps its last
record (with its own date and commit). Nothing here decides pass or fail: the
tests do (tests/e2e/ucs_test.cpp guards the calibrated UCS of the small sample).

Needs numpy, matplotlib and h5py (Debian: python3-numpy python3-matplotlib python3-h5py).
"""
import argparse
import datetime
import json
import os
import platform
import shutil
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass, field
from typing import Callable, Optional

ROOT = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir))
sys.path.insert(0, os.path.join(ROOT, "tools"))
sys.path.insert(0, os.path.join(ROOT, "python"))

import numpy as np  # noqa: E402

import dfc_results  # noqa: E402
import plot_results  # noqa: E402  (the same peak, stiffness and overlay code as ./vc plot)

RECORD = os.path.join(ROOT, "docs", "results.json")
PAGE = os.path.join(ROOT, "docs", "results.md")
FIGURES = os.path.join(ROOT, "docs", "figures")
RUNS = os.path.join(ROOT, "results", "report")


@dataclass
class Item:
    """One measured claim: how to produce it and what to read back."""

    name: str
    title: str
    shows: str               # one sentence: what the numbers mean
    minutes: str             # run time on the 2-core development machine, for --list and the page
    scenario: Optional[str] = None           # shipped scenario, run with the coupler
    measure: Optional[Callable] = None       # (item, folder) -> (rows, summary lines, runs for the figure)
    command: Optional[Callable] = None       # (build) -> argv, for items that are not a scenario
    paper: str = ""                          # the value the source reports, if any
    figure: str = ""                         # docs/figures/<figure>.png, written by the measure
    overlay_with: list = field(default_factory=list)  # [(item, label)]: runs of other items drawn in the figure
    missing: Callable = lambda: ""           # () -> why the item cannot run on this machine ("" if it can)


# --- what is read back ----------------------------------------------------------------------------


def variant_runs(folder):
    """[(label, {column: Series}, particles)] of one run or of every variant, in the scenario's order."""
    if os.path.exists(os.path.join(folder, dfc_results.RESULTS_FILE)):
        paths = [("", os.path.join(folder, dfc_results.RESULTS_FILE))]
    else:
        with open(os.path.join(folder, "scenario.json")) as f:
            labels = [v["label"] for v in json.load(f).get("variants", [])]
        paths = [(label, os.path.join(folder, label, dfc_results.RESULTS_FILE)) for label in labels]
    runs = []
    for label, path in paths:
        with dfc_results.open_results(path) as run:
            particles = None
            if "dem" in run.roles and run.snapshot_count("dem"):
                arrays = run.snapshot("dem", 0).arrays
                particles = int(arrays["particle_radius"].shape[0]) if "particle_radius" in arrays else None
            runs.append((label, run.all_series(), particles))
    return runs


def spread(values):
    """(max - min) / mean, as the tests and ./vc plot define it."""
    return plot_results.spread(values)


def stress_strain(item, folder):
    """Peak (deviator of a triaxial test, else axial stress), strain at the peak and
    initial stiffness of every run; the spread across runs when there are several."""
    runs = variant_runs(folder)
    deviator = all(plot_results.is_triaxial(series) for _, series, _ in runs)
    rows, peaks, stiffnesses = [], [], []
    for label, series, particles in runs:
        strain, stress = plot_results.stress_strain_columns(series, deviator)
        at_peak = int(np.argmax(stress))
        stiffness = plot_results.initial_stiffness(strain, stress)
        peaks.append(stress[at_peak])
        stiffnesses.append(stiffness)
        rows.append({"run": label or item.name, "particles": particles, "stress": "deviator q" if deviator else "axial stress",
                     "peak_kpa": round(stress[at_peak] / 1e3, 1),
                     "strain_at_peak": float(f"{strain[at_peak]:.3e}"), "stiffness_mpa": round(stiffness / 1e6, 1)})
    summary = []
    if len(runs) > 1:
        summary.append(f"spread (max − min)/mean of the peaks {spread(peaks) * 100:.1f} %, "
                       f"of the initial stiffnesses {spread(stiffnesses) * 100:.1f} %")
    return rows, summary, [(label or item.name, series) for label, series, _ in runs]


def pile_forces(item, folder):
    """Mean pile force over the last third of the push, and the final force, per run."""
    runs = variant_runs(folder)
    rows = []
    names = plot_results.pile_columns()[1]
    for label, series, _ in runs:
        late_mean, final = plot_results.pile_force_summary(plot_results.column(series, *names))
        rows.append({"run": label, "late_mean_force_n": round(late_mean, 3), "final_force_n": round(final, 3)})
    return rows, [], [(label, series) for label, series, _ in runs]


def verification_table(item, folder):
    """The rows of docs/verification.md that fdm_verification just wrote: how many, how many pass,
    and the largest error as a fraction of its tolerance."""
    rows, worst = [], 0.0
    with open(os.path.join(ROOT, "docs", "verification.md")) as f:
        for line in f:
            cells = [c.strip() for c in line.strip().strip("|").split("|")]
            if len(cells) == 10 and cells[5].endswith("%") and cells[6].endswith("%"):
                error, tolerance = float(cells[5].rstrip(" %")), float(cells[6].rstrip(" %"))
                worst = max(worst, error / tolerance)
                rows.append(cells[7] == "pass")
    summary = [f"{sum(rows)} of {len(rows)} rows pass; the largest error is {worst * 100:.0f} % of its tolerance "
               "(the whole table: [verification.md](verification.md))"]
    return [], summary, []


def peer_output(item, folder):
    """The summary that bench/dem_peers.sh prints after its rounds, as it printed it."""
    with open(os.path.join(folder, "output.txt")) as f:
        text = f.read()
    start = text.find("best of")
    return [], ["```", text[start:].strip() if start >= 0 else text.strip(), "```"], []


def peers_missing():
    """bench/dem_peers.sh needs LAMMPS, LIGGGHTS, MPI and the peer packing (PEERS_DIR)."""
    absent = [exe for exe in ("lmp", "liggghts", "mpirun") if shutil.which(exe) is None]
    peers = os.environ.get("PEERS_DIR", os.path.join(ROOT, os.pardir, "shared", "bench", "peers"))
    if not os.path.exists(os.path.join(peers, "data", "pack_12k.data")):
        absent.append(f"the peer packing ({peers}/data/pack_12k.data; set PEERS_DIR)")
    return ", ".join(absent)


ITEMS = [
    Item("ucs_softbond", "UCS of the soft-bond rock between platens",
         "uniaxial compressive strength of the rock of Zheng et al. (2023) Table 2 with the packing and bond gap "
         "calibrated here ([dem_ucs.md](dem_ucs.md))", "2",
         scenario="scenarios/ucs_softbond.json", measure=stress_strain, paper="UCS about 500 kPa (Zheng et al. 2023)",
         figure="ucs_softbond"),
    Item("ucs_upscaling", "The same rock as a periodic REV at S = 1, 2, 4",
         "the calibration survives particle upscaling when peaks and initial stiffness agree across S "
         "([dem_upscaling.md](dem_upscaling.md))", "6–15",
         scenario="scenarios/ucs_upscaling.json", measure=stress_strain, figure="ucs_upscaling"),
    Item("triaxial_damagebond", "Damage-bond chalk, triaxial at 100 kPa, S = 1, 10, 100",
         "the chalk of Ciantia et al. (2024) Table 1 in similar periodic cells ([dem_upscaling.md](dem_upscaling.md))", "7",
         scenario="scenarios/triaxial_damagebond.json", measure=stress_strain, figure="triaxial_damagebond_upscaling"),
    Item("triaxial_damagebond_samecell", "The same chalk at S = 1, 2, 4 in one 3 mm periodic cell",
         "upscaling in one cell, the test of the rules at fixed sample size ([dem_upscaling.md](dem_upscaling.md))", "7",
         scenario="scenarios/triaxial_damagebond_samecell.json", measure=stress_strain,
         figure="triaxial_damagebond_samecell"),
    Item("triaxial_periodic_example", "Bonded periodic REV, triaxial at σ3 = 100 kPa",
         "radius expansion, isotropic servo, bonds, triaxial shearing in about 1000 spheres "
         "([dem_periodic.md](dem_periodic.md))", "0.2",
         scenario="scenarios/triaxial_periodic_example.json", measure=stress_strain),
    Item("triaxial_walls", "The chalk between six rigid walls at three strain rates",
         "the laboratory-like test: sides servo-controlled to 100 kPa, the rate halved twice (quasi-static check), "
         "against the periodic REV S1 of triaxial_damagebond ([dem_triaxial_walls.md](dem_triaxial_walls.md))", "19",
         scenario="scenarios/triaxial_walls.json", measure=stress_strain, figure="triaxial_walls",
         overlay_with=[("triaxial_damagebond", "S1")]),
    Item("pile_compare", "The demo pile against three continua",
         "the same DEM bed and pile against fdm_server, elastic_reference_server and rigid walls "
         "([continuum_comparison.md](continuum_comparison.md))", "1",
         scenario="scenarios/pile_compare.json", measure=pile_forces, figure="pile_force_continua"),
    Item("fdm_verification", "FDM against seven closed-form solutions",
         "the continuum's errors against the closed forms of [theory/fdm.md](theory/fdm.md) §2, with mesh refinement",
         "10", measure=verification_table,
         command=lambda build: [os.path.join(build, "bin", "fdm_verification"), "--level", "slow", "--refinement",
                                "--write", os.path.join(ROOT, "docs", "verification.md")]),
    Item("dem_peers", "DEM throughput against LAMMPS and LIGGGHTS",
         "particle-steps per second on the same 12 544-sphere packing and law as the peers, at 1 and 2 threads, "
         "the bonded (linear_pbond) rate against the unbonded one, and the kinetic-energy cross-check "
         "([dem_benchmarks.md](dem_benchmarks.md))", "15", measure=peer_output, missing=peers_missing,
         command=lambda build: [os.path.join(ROOT, "bench", "dem_peers.sh"), build]),
]


# --- running ----------------------------------------------------------------------------------------


def machine():
    """CPU model and core count, and the operating system."""
    model = platform.processor() or "unknown CPU"
    try:
        with open("/proc/cpuinfo") as f:
            model = next(line.split(":", 1)[1].strip() for line in f if line.startswith("model name"))
    except (OSError, StopIteration):
        pass
    return f"{model}, {os.cpu_count()} cores, {platform.system()} {platform.release()}"


def commit():
    """The checkout's commit, with "+changes" when the working tree differs from it."""
    def git(*args):
        return subprocess.run(["git", "-C", ROOT, *args], capture_output=True, text=True).stdout.strip()
    head = git("rev-parse", "--short=12", "HEAD") or "unknown"
    return head + ("+changes" if git("status", "--porcelain", "--untracked-files=no") else "")


def run_item(item, build):
    """Runs the item; returns its record."""
    folder = os.path.join(RUNS, item.name)
    if item.scenario:
        shutil.rmtree(folder, ignore_errors=True)
        argv = [os.path.join(build, "bin", "coupler"), "run", os.path.join(ROOT, item.scenario), "--out", folder, "--no-progress"]
        shown = f"./vc run {item.scenario} --out results/report/{item.name}"
    else:
        argv = item.command(build)
        shown = " ".join(os.path.relpath(a, ROOT) if a.startswith(ROOT) else a for a in argv)
    print(f"[report] {item.name}: {shown}", file=sys.stderr, flush=True)
    checkout = commit()  # before the run: the sources the build was brought up to date with
    start = time.monotonic()
    if item.command:  # its output is what the measure reads
        os.makedirs(folder, exist_ok=True)
        with open(os.path.join(folder, "output.txt"), "w") as log:
            status = subprocess.run(argv, cwd=ROOT, stdout=log).returncode
    else:
        status = subprocess.run(argv, cwd=ROOT).returncode
    wall = time.monotonic() - start
    if status != 0:
        raise RuntimeError(f"{item.name}: '{shown}' exited with status {status}")
    if item.scenario:  # the scenario as run, so that the variants are read in its order
        shutil.copyfile(os.path.join(ROOT, item.scenario), os.path.join(folder, "scenario.json"))
    entry = {"date_utc": datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC"),
             "commit": checkout, "machine": machine(), "wall_s": round(wall, 1), "command": shown,
             "load_average": round(os.getloadavg()[1], 1)}  # over the last 5 min: wall times on a busy machine are long
    return measure_item(item, entry)


def measure_item(item, entry):
    """Reads the item's last run (results/report/<item>) into `entry`: its rows, summary and figure."""
    folder = os.path.join(RUNS, item.name)
    rows, summary, runs = item.measure(item, folder)
    if item.figure:
        for other, label in item.overlay_with:
            other_folder = os.path.join(RUNS, other)
            extra = [(f"{other} {l}", s) for l, s, _ in variant_runs(other_folder) if l == label] if os.path.isdir(other_folder) else []
            if not extra:
                summary.append(f"(the figure lacks {other} {label}: run `./vc report {other}` first)")
            runs = runs + extra
        write_figure(runs, item.figure)
    return dict(entry, rows=rows, summary=summary, figure=f"figures/{item.figure}.png" if item.figure else "")


def write_figure(runs, name):
    """The overlay ./vc plot draws (one curve per run), saved as docs/figures/<name>.png."""
    with tempfile.TemporaryDirectory() as scratch:
        if len(runs) == 1:
            written = [plot_results.plot_stress_strain(runs[0][1], scratch)]
        else:
            written = plot_results.plot_overlays(runs, scratch)
        written = [w for w in written if w]
        if not written:
            raise RuntimeError(f"no figure could be drawn for {name}")
        os.makedirs(FIGURES, exist_ok=True)
        shutil.copyfile(written[0], os.path.join(FIGURES, name + ".png"))


# --- the page ---------------------------------------------------------------------------------------

COLUMNS = [("run", "run", "{}"), ("particles", "spheres", "{:,}"), ("stress", "stress", "{}"), ("peak_kpa", "peak [kPa]", "{:.1f}"),
           ("strain_at_peak", "axial strain at peak", "{:.2e}"), ("stiffness_mpa", "initial stiffness [MPa]", "{:.1f}"),
           ("late_mean_force_n", "mean pile force, last third of the push [N]", "{:.3f}"),
           ("final_force_n", "final pile force [N]", "{:.3f}")]


def table(rows):
    keys = [c for c in COLUMNS if any(row.get(c[0]) is not None for row in rows)]
    lines = ["| " + " | ".join(c[1] for c in keys) + " |", "|" + "---|" * len(keys)]
    for row in rows:
        cells = [c[2].format(row[c[0]]).replace(",", " ") if row.get(c[0]) is not None else "" for c in keys]
        lines.append("| " + " | ".join(cells) + " |")
    return lines


def render_page(record):
    """docs/results.md as text, from the record alone."""
    out = ["# Measured results",
           "",
           "Written by `./vc report` (`tools/report.py`) from runs of the shipped scenarios; do not edit by hand.",
           "`./vc report ITEM` reruns one item and keeps the others as they were, each with the date, commit and",
           "machine of its own run (`+changes`: the working tree differed from that commit). The values are in",
           "[results.json](results.json) too. Tests guard what must not drift (e.g. the calibrated UCS of the",
           "small sample, `tests/e2e/ucs_test.cpp`); this page shows what the full scenarios give. Run times are",
           "wall times on the machine named; on a shared machine (a load average above its cores) they are",
           "several times the idle times docs/calibrating.md gives.",
           ""]
    for item in ITEMS:
        entry = record.get(item.name)
        out += [f"## {item.title} (`{item.name}`)", "", f"What it shows: {item.shows}."]
        if item.paper:
            out.append(f"Source value: {item.paper}.")
        out.append("")
        if entry is None:
            out += [f"Not measured yet: run `./vc report {item.name}` (about {item.minutes} min).", ""]
            continue
        if entry["rows"]:
            out += table(entry["rows"]) + [""]
        out += [line + "." if not line.endswith((".", ")")) else line for line in entry["summary"]]
        if entry["summary"]:
            out.append("")
        if entry["figure"]:
            out += [f"![{item.name}]({entry['figure']})", ""]
        load = f" at a load average of {entry['load_average']}" if "load_average" in entry else ""
        out += [f"Measured {entry['date_utc']}, commit {entry['commit']}, {entry['machine']}; "
                f"{entry['wall_s'] / 60:.1f} min{load}. Command: `{entry['command']}`.", ""]
    return "\n".join(out).rstrip() + "\n"


def write_page(record):
    with open(PAGE, "w") as f:
        f.write(render_page(record))


def load_record():
    if not os.path.exists(RECORD):
        return {}
    with open(RECORD) as f:
        return json.load(f)


def save_record(record):
    with open(RECORD, "w") as f:
        json.dump(record, f, indent=1, sort_keys=True, ensure_ascii=False)
        f.write("\n")


def main(argv=None):
    parser = argparse.ArgumentParser(description="Rerun the documented scenarios and write docs/results.md.")
    parser.add_argument("build", help="the build folder (holds bin/coupler)")
    parser.add_argument("items", nargs="*", help="items to rerun (default: all); --list names them")
    parser.add_argument("--list", action="store_true", help="list the items and exit")
    parser.add_argument("--page-only", action="store_true", help="rewrite docs/results.md from docs/results.json; run nothing")
    parser.add_argument("--remeasure", action="store_true",
                        help="read the items' last runs (results/report/ITEM) again, keeping when, where and how they ran; run nothing")
    args = parser.parse_args(argv)
    by_name = {item.name: item for item in ITEMS}
    if args.list:
        for item in ITEMS:
            print(f"{item.name:<30} ~{item.minutes:>5} min  {item.scenario or os.path.basename(item.command('build')[0])}")
        print(f"{'all':<30} ~{sum(float(i.minutes.split('–')[-1]) for i in ITEMS):>5.0f} min at most")
        return 0
    unknown = [n for n in args.items if n not in by_name]
    if unknown:
        print(f"report.py: unknown item(s) {', '.join(unknown)}; the items are {', '.join(by_name)}", file=sys.stderr)
        return 2
    record = load_record()
    if args.remeasure:
        for name in args.items or [n for n in by_name if n in record]:
            record[name] = measure_item(by_name[name], record[name])
        save_record(record)
    elif not args.page_only:
        for name in args.items or list(by_name):
            why = by_name[name].missing()
            if why:
                print(f"[report] {name}: skipped, this machine lacks {why}; its last record is kept", file=sys.stderr)
                continue
            record[name] = run_item(by_name[name], os.path.abspath(args.build))
            save_record(record)  # after each item, so an interrupted report keeps what it measured
            write_page(record)
    write_page(record)
    print(f"[report] wrote {os.path.relpath(PAGE, ROOT)}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
