#!/usr/bin/env python3
"""Figures and key numbers of the open-ended pile jacked into chalk
(docs/open_pile.md; Ciantia, Previtali, Zheng et al. 2024, Fig. 1-2).

Reads every <label>/results.h5 under RESULTS_DIR that holds an open tube's
forces (the variants of scenarios/open_pile_chalk_reduced.json or
open_pile_chalk.json: one packing each) and writes to --out (default
RESULTS_DIR):

  fig2a_force_displacement.png  installation force against pile displacement with
                                its split into annulus, inner shaft and outer
                                shaft (mean over the packings, shaded min-max)
  plug.png                      soil column length L in the pile and the
                                incremental filling ratio IFR = dL/dh against h
  fig2b_radial_stress.png       sigma_rr (compression positive) on an r-z section
                                at the end of installation: the DEM's ring
                                average inside the core, the FDM's zones beyond
  damage_map.png                mean bond damage D (1 = broken) on the r-z section
                                at the end, with the pile drawn in
  summary.json                  forces at 5, 10 and 20 mm, plug ratios, sigma_rr
                                and damage contrasts, force balance, run times

and into each results file the groups /open_pile_grid/ (sigma_rr, sigma_zz of
the DEM on the r-z grid at every snapshot, tools/centrifuge_foundation.py's
stress_grid) and /open_pile/ (h, plug length, PLR, IFR on a grid of h; the
FDM's sigma_rr and the bond damage on the section at the last snapshot), once
the run that writes the file has ended (before, a second writer would corrupt it).

    tools/open_pile.py RESULTS_DIR [--out DIR]

Exit 0 after writing, 3 when RESULTS_DIR holds no open-pile run, 2 on bad input.
"""
import argparse
import json
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import warnings  # noqa: E402

import numpy as np  # noqa: E402

warnings.filterwarnings("ignore", message="Mean of empty slice")  # band() past the end of a shorter run
warnings.filterwarnings("ignore", message="All-NaN slice encountered")

from centrifuge_foundation import Run, add_group, band, find_study_runs, force_balance, h5py, open_results, spread, stress_grid, study_runs  # noqa: E402

DEPTHS_MM = (5.0, 10.0, 20.0)  # the forces the docs page reports (Ciantia et al. 2024 Fig. 2a runs to 20 mm)
SMOOTHING = 0.5e-3  # m, the running mean of the force curves in Fig. 2a; the forces at 5, 10, 20 mm are means over the same width
IFR_STEP = 1.0e-3  # m, the increment of h over which IFR = dL/dh is taken: about one fine particle diameter at S = 8


class PileRun(Run):
    """One open-pile run: the foundation run's series plus the tube's parts and plug."""

    def __init__(self, label, path):
        super().__init__(label, path)
        with open_results(path) as r:
            pile = r.scenario["participants"]["dem"]["config"]["pile"]
            self.inner_radius = float(pile["radius_m"]) - float(pile["wall_thickness_m"])
            self.failure = r.failure  # None unless the run stopped on an error (it is shown up to there)
        self.inner = self.series["dem_pile_inner_shaft_force_n"]
        self.outer = self.series["dem_pile_outer_shaft_force_n"]
        self.plug = self.series["dem_pile_plug_length_m"]
        # The tip starts on the region's top (the nominal surface): penetration = travel.
        self.h = self.displacement

    def force_near(self, depth):
        """Mean pile force over the records within SMOOTHING / 2 of penetration `depth` (m)."""
        near = np.abs(self.h - depth) <= 0.5 * SMOOTHING
        return float(np.mean(self.force[near])) if near.any() else float("nan")

    def plug_ratios(self):
        """h grid (step IFR_STEP), L, PLR = L/h and IFR = dL/dh on it (IFR over the step that
        ends at each grid point; NaN until the column holds more than its loose top, L > 0)."""
        moving = self.h > 0
        grid = np.arange(IFR_STEP, float(np.max(self.h)) + 1e-12, IFR_STEP)
        length = np.interp(grid, self.h[moving], self.plug[moving])
        before = np.concatenate(([0.0], length[:-1]))
        ifr = np.where(before > 0.0, (length - before) / IFR_STEP, np.nan)
        return grid, length, length / grid, ifr


def find_runs(directory):
    return find_study_runs(directory, lambda r: r.has_series("dem_pile_inner_shaft_force_n"), PileRun)


def pyplot():
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return plt


def smoothed(run, values):
    """Running mean of `values` over SMOOTHING of penetration (the force of a bonded rock
    jumps by tens of per cent from record to record as bonds break)."""
    step = float(np.median(np.diff(run.h[run.h > 0]))) if (run.h > 0).sum() > 1 else 0.0
    n = max(1, int(round(SMOOTHING / step))) if step > 0 else 1
    window = np.ones(n)
    return np.convolve(values, window, mode="same") / np.convolve(np.ones(len(values)), window, mode="same")  # shorter at the ends


def plot_force(runs, out):
    """Fig. 2a: total force and its three parts against h (running means over SMOOTHING),
    mean over packings with min-max band."""
    plt = pyplot()
    fig, ax = plt.subplots(figsize=(6.4, 4.6))
    grid = np.linspace(0.0, max(float(np.max(r.h)) for r in runs), 400)  # each run up to where it got
    for name, values_of in (("total", lambda r: r.force), ("annulus", lambda r: r.tip), ("inner shaft", lambda r: r.inner),
                            ("outer shaft", lambda r: r.outer)):
        mean, low, high = band(runs, grid, lambda r: smoothed(r, values_of(r)))
        line, = ax.plot(1e3 * grid, mean, label=name)
        if len(runs) > 1:
            ax.fill_between(1e3 * grid, low, high, color=line.get_color(), alpha=0.2, lw=0)
    ax.set_xlabel("pile displacement h (mm)")
    ax.set_ylabel("force (N)")
    ax.set_title(f"Installation force and its split ({len(runs)} packing{'s' if len(runs) > 1 else ''}; band: min-max;\n"
                 f"running mean over {1e3 * SMOOTHING:g} mm)", fontsize=10)
    ax.legend()
    ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "fig2a_force_displacement.png"), dpi=130)
    plt.close(fig)


def plot_plug(runs, out):
    plt = pyplot()
    fig, (left, right) = plt.subplots(1, 2, figsize=(10, 4.4))
    top = max(float(np.max(r.h)) for r in runs)
    left.plot([0, 1e3 * top], [0, 1e3 * top], "k:", lw=1, label="L = h (coring, IFR = 1)")
    for run in runs:
        grid, length, _, ifr = run.plug_ratios()
        line, = left.plot(1e3 * run.h, 1e3 * run.plug, lw=1, label=f"{run.label} (packing {run.seed})")
        right.plot(1e3 * (grid - 0.5 * IFR_STEP), ifr, color=line.get_color(), marker=".", lw=1, label=run.label)
    left.set_xlabel("pile displacement h (mm)")
    left.set_ylabel("soil column in the pile L (mm)")
    left.set_title("Plug length")
    left.legend(fontsize=8)
    right.axhline(1.0, color="k", ls=":", lw=1)
    right.set_xlabel("pile displacement h (mm)")
    right.set_ylabel(f"IFR = dL/dh over {1e3 * IFR_STEP:g} mm")
    right.set_title("Incremental filling ratio")
    right.legend(fontsize=8)
    for ax in (left, right):
        ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "plug.png"), dpi=130)
    plt.close(fig)


def fdm_radial_stress(path):
    """The FDM's sigma_rr (compression positive) at its last snapshot, averaged around
    the axis: (r_edges, z_edges, [z, r] values) on the mesh's own rings and layers."""
    with h5py.File(path, "r") as f:
        group = f["snapshots/continuum"]
        snap = group[sorted(group)[-1]]
        nodes = snap["node_position"][()]
        zones = snap["zone_nodes"][()]
        stress = snap["zone_stress"][()]  # xx, xy, xz, yy, yz, zz; tension positive
    node_r = np.hypot(nodes[:, 0], nodes[:, 1])
    r_edges = np.unique(np.round(node_r, 7))
    z_edges = np.unique(np.round(nodes[:, 2], 7))
    centre = nodes[zones].mean(axis=1)
    r = np.hypot(centre[:, 0], centre[:, 1])
    c = centre[:, 0] / r
    s = centre[:, 1] / r
    rr = -(c * c * stress[:, 0] + 2 * c * s * stress[:, 1] + s * s * stress[:, 3])
    ir = np.clip(np.searchsorted(r_edges, r) - 1, 0, len(r_edges) - 2)
    iz = np.clip(np.searchsorted(z_edges, centre[:, 2]) - 1, 0, len(z_edges) - 2)
    total = np.zeros((len(z_edges) - 1, len(r_edges) - 1))
    count = np.zeros_like(total)
    np.add.at(total, (iz, ir), rr)
    np.add.at(count, (iz, ir), 1.0)
    return r_edges, z_edges, np.where(count > 0, total / np.maximum(count, 1), np.nan)


def wall_traction(path, radius):
    """The radial traction on the coupling wall (compression positive), per layer of its
    nodes, from the coupling forces on the FDM's nodes at its last snapshot
    (node_external_force): the stress both bodies share at the wall, which each side's
    zone or ring average approaches from its own side. (z, traction) sorted by z; None
    when the snapshot has no coupling forces (a run of a build before they were written)."""
    with h5py.File(path, "r") as f:
        group = f["snapshots/continuum"]
        snap = group[sorted(group)[-1]]
        if "node_external_force" not in snap:
            return None
        nodes = snap["node_position"][()]
        force = snap["node_external_force"][()]
    r = np.hypot(nodes[:, 0], nodes[:, 1])
    on_wall = np.abs(r - radius) < 1e-6 * radius
    z = np.round(nodes[on_wall, 2], 9)
    radial = (nodes[on_wall, 0] * force[on_wall, 0] + nodes[on_wall, 1] * force[on_wall, 1]) / r[on_wall]
    layers = np.unique(z)
    if len(layers) < 2:
        return None
    # Each layer of nodes carries the wall between the midpoints to its neighbours.
    bounds = np.concatenate(([layers[0]], 0.5 * (layers[1:] + layers[:-1]), [layers[-1]]))
    height = np.diff(bounds)
    per_layer = np.array([radial[z == layer].sum() for layer in layers])
    return layers, per_layer / (2.0 * np.pi * radius * height), height


def band_mean(traction, z_range):
    """The wall traction averaged over the layers in z_range, weighted by their heights."""
    if traction is None:
        return float("nan")
    z, value, height = traction
    pick = (z >= z_range[0]) & (z <= z_range[1])
    return float(np.sum(value[pick] * height[pick]) / np.sum(height[pick])) if pick.any() else float("nan")


def bond_damage_grid(path, r_edges, z_edges):
    """Mean bond damage D (broken = 1) and bond count per ring cell at the last DEM snapshot."""
    with h5py.File(path, "r") as f:
        group = f["snapshots/dem"]
        snap = group[sorted(group)[-1]]
        where = snap["bond_position"][()]
        damage = snap["bond_damage"][()]
    r = np.hypot(where[:, 0], where[:, 1])
    ir = np.digitize(r, r_edges) - 1
    iz = np.digitize(where[:, 2], z_edges) - 1
    ok = (ir >= 0) & (ir < len(r_edges) - 1) & (iz >= 0) & (iz < len(z_edges) - 1)
    total = np.zeros((len(z_edges) - 1, len(r_edges) - 1))
    count = np.zeros_like(total)
    np.add.at(total, (iz[ok], ir[ok]), damage[ok])
    np.add.at(count, (iz[ok], ir[ok]), 1.0)
    return np.where(count > 0, total / np.maximum(count, 1), np.nan), count


def grid_edges(run):
    """The r-z section: rings and layers 1 mm (D/8) wide over the DEM core, from the
    surface to 1.5 D below the final tip."""
    with open_results(run.path) as r:
        core = float(r.scenario["participants"]["dem"]["config"]["particles"]["region"]["radius_m"])
    step = run.diameter / 8.0
    r_edges = np.arange(0.0, core + 1e-12, step)
    depth = float(np.max(run.h)) + 1.5 * run.diameter
    z_edges = run.surface_z - np.arange(0.0, depth + 1e-12, step)[::-1]
    return r_edges, z_edges


def draw_pile(ax, run):
    """The pile's wall (inner to outer radius) from its final tip upwards, in mm."""
    from matplotlib.patches import Rectangle
    tip = 1e3 * (run.surface_z - float(np.max(run.h)))
    ax.add_patch(Rectangle((1e3 * run.inner_radius, tip), 1e3 * (0.5 * run.diameter - run.inner_radius), 1e3 * run.surface_z + 5 - tip,
                           color="0.4"))


def plot_section(run, out, name, r_edges, z_edges, dem, title, label, fdm=None, cmap="viridis"):
    plt = pyplot()
    fig, ax = plt.subplots(figsize=(7.5, 5.2))
    values = [dem[np.isfinite(dem)]] + ([fdm[2][np.isfinite(fdm[2])]] if fdm else [])
    values = np.concatenate(values)
    vmin, vmax = (float(np.percentile(values, 2)), float(np.percentile(values, 98))) if values.size else (0.0, 1.0)
    scale = 1e-6 if label.endswith("(MPa)") else 1.0
    mesh = ax.pcolormesh(1e3 * r_edges, 1e3 * z_edges, scale * dem, vmin=scale * vmin, vmax=scale * vmax, cmap=cmap, shading="flat")
    if fdm:
        ax.pcolormesh(1e3 * fdm[0], 1e3 * fdm[1], scale * fdm[2], vmin=scale * vmin, vmax=scale * vmax, cmap=cmap, shading="flat")
        ax.axvline(1e3 * r_edges[-1], color="w", lw=1, ls="--")
        ax.set_ylim(1e3 * z_edges[0], 1e3 * z_edges[-1] + 1)
        ax.set_xlim(0, 1e3 * fdm[0][-1])
    draw_pile(ax, run)
    fig.colorbar(mesh, ax=ax, label=label)
    ax.set_xlabel("r (mm)")
    ax.set_ylabel("z (mm)")
    ax.set_title(title)
    fig.tight_layout()
    fig.savefig(os.path.join(out, name), dpi=130)
    plt.close(fig)


def ring_mean(grid, r_edges, z_edges, r_range, z_range):
    """Mean of the cells whose centres fall in r_range x z_range (NaN cells ignored)."""
    rc = 0.5 * (r_edges[1:] + r_edges[:-1])
    zc = 0.5 * (z_edges[1:] + z_edges[:-1])
    pick = grid[np.ix_((zc >= z_range[0]) & (zc <= z_range[1]), (rc >= r_range[0]) & (rc <= r_range[1]))]
    return float(np.nanmean(pick)) if np.isfinite(pick).any() else float("nan")


def fdm_at_wall(fdm, radius, z_range):
    """The FDM's sigma_rr at `radius` (the coupling wall) from the means of its first two zone
    rings over z_range: the axisymmetric elastic form A + B/r^2 (Lame's thick cylinder;
    Timoshenko & Goodier 1970, docs/theory/fdm.md §2(b)) fitted to the two means as ring
    averages (the area average of 1/r^2 over r0..r1 is 2 ln(r1/r0) / (r1^2 - r0^2)). The zone
    centres lie half a zone out from the wall, where a stress that decays outwards is already
    lower; tests/e2e/open_pile_test.cpp computes the same."""
    r_edges, z_edges, grid = fdm
    means = [ring_mean(grid, r_edges, z_edges, (r_edges[i], r_edges[i + 1]), z_range) for i in (0, 1)]
    if not all(np.isfinite(means)):
        return float("nan")
    inverse_square = [2.0 * np.log(r_edges[i + 1] / r_edges[i]) / (r_edges[i + 1] ** 2 - r_edges[i] ** 2) for i in (0, 1)]
    b = (means[0] - means[1]) / (inverse_square[0] - inverse_square[1])
    return float(means[0] - b * inverse_square[0] + b / radius ** 2)


def analyse(run, out, figures):
    r_edges, z_edges = grid_edges(run)
    sigma_rr = stress_grid(run, r_edges=r_edges, z_edges=z_edges, group_name="open_pile_grid")[0][-1]
    fdm = fdm_radial_stress(run.path)
    traction = wall_traction(run.path, fdm[0][0])
    damage, bonds = bond_damage_grid(run.path, r_edges, z_edges)
    grid, length, plr, ifr = run.plug_ratios()
    def fill(g):
        g.attrs["description"] = ("plug: soil column length in the pile on a grid of pile displacement h, PLR = L/h, IFR = dL/dh over "
                                  f"{IFR_STEP} m; fdm_sigma_rr_pa [z, r] (compression positive) and bond_damage [z, r] at the last "
                                  "snapshot (tools/open_pile.py)")
        g["h_m"], g["plug_length_m"], g["plug_length_ratio"], g["incremental_filling_ratio"] = grid, length, plr, ifr
        g["fdm_r_edges_m"], g["fdm_z_edges_m"], g["fdm_sigma_rr_pa"] = fdm
        g["r_edges_m"], g["z_edges_m"], g["bond_damage"], g["bond_count"] = r_edges, z_edges, damage, bonds
    add_group(run.path, "open_pile", fill)
    tip = run.surface_z - float(np.max(run.h))
    d, ro, ri = run.diameter, 0.5 * run.diameter, run.inner_radius
    near_tip = (tip - 0.25 * d, tip + 0.25 * d)
    within_1d = (tip - d, min(tip + d, run.surface_z))
    result = {
        "sigma_rr_pa_at_tip": {"outside_next_to_wall": ring_mean(sigma_rr, r_edges, z_edges, (ro, ro + 0.125 * d), near_tip),
                               "outside_1D_out": ring_mean(sigma_rr, r_edges, z_edges, (ro + 0.75 * d, ro + d), near_tip),
                               "inside_plug": ring_mean(sigma_rr, r_edges, z_edges, (0.0, ri), near_tip)},
        "damage": {"below_annulus": ring_mean(damage, r_edges, z_edges, (ri - 0.125 * d, ro + 0.125 * d), (tip - 0.5 * d, tip)),
                   "far_field": ring_mean(damage, r_edges, z_edges, (r_edges[-1] - 0.25 * d, r_edges[-1]), (z_edges[0], tip - d))},
        "fdm_sigma_rr_pa_next_to_core_at_tip": ring_mean(fdm[2], fdm[0], fdm[1], (r_edges[-1], r_edges[-1] + 0.25 * d), near_tip),
        "dem_sigma_rr_pa_core_edge_at_tip": ring_mean(sigma_rr, r_edges, z_edges, (r_edges[-1] - 0.25 * d, r_edges[-1]), near_tip),
        # The same rings over the band within 1 D of the tip's depth (cut at the surface): about 90 of the DEM's
        # coarse grains instead of 30, so that the DEM's ring average is representative (docs/open_pile.md §4).
        "dem_sigma_rr_pa_core_edge_within_1D": ring_mean(sigma_rr, r_edges, z_edges, (r_edges[-1] - 0.25 * d, r_edges[-1]), within_1d),
        "fdm_sigma_rr_pa_next_to_core_within_1D": ring_mean(fdm[2], fdm[0], fdm[1], (r_edges[-1], r_edges[-1] + 0.25 * d), within_1d),
        # The stress at the wall itself, which both bodies share: the coupling forces on the wall's nodes
        # per unit wall area, over the same bands. Each side's average above lies up to D/4 away from it.
        "wall_traction_pa_at_tip": band_mean(traction, near_tip),
        "wall_traction_pa_within_1D": band_mean(traction, within_1d),
        # The FDM's stress field carried to the wall from its first two zone rings (fdm_at_wall): the
        # FDM's radial stress at the coupling wall, which the check compares with the DEM's (the
        # traction its particles put on the wall) over the band within 1 D (docs/open_pile.md §6).
        "fdm_sigma_rr_pa_at_wall_at_tip": fdm_at_wall(fdm, fdm[0][0], near_tip),
        "fdm_sigma_rr_pa_at_wall_within_1D": fdm_at_wall(fdm, fdm[0][0], within_1d),
    }
    result["fdm_at_wall_over_wall_traction_within_1D"] = result["fdm_sigma_rr_pa_at_wall_within_1D"] / result["wall_traction_pa_within_1D"]
    if figures:
        plot_section(run, out, "fig2b_radial_stress.png", r_edges, z_edges, sigma_rr,
                     f"$\\sigma_{{rr}}$ at the end (h = {1e3 * np.max(run.h):.1f} mm; {run.label}); FDM beyond the dashed line",
                     "$\\sigma_{rr}$, compression positive (MPa)", fdm=fdm, cmap="magma")
        plot_section(run, out, "damage_map.png", r_edges, z_edges, damage,
                     f"Mean bond damage D at the end (h = {1e3 * np.max(run.h):.1f} mm; {run.label})", "D (broken = 1)", cmap="inferno")
    return result


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("results_dir", help="the output folder of scenarios/open_pile_chalk_reduced.json (one folder per packing)")
    parser.add_argument("--out", help="folder for the figures and summary.json (default: RESULTS_DIR)")
    args, runs, out = study_runs(parser, argv, find_runs, "open_pile.py")
    if isinstance(runs, int):
        return runs
    plot_force(runs, out)
    plot_plug(runs, out)
    summary = {"diameter_m": runs[0].diameter, "wall_thickness_m": 0.5 * runs[0].diameter - runs[0].inner_radius, "runs": {}}
    section = max(runs, key=lambda r: float(np.max(r.h)))  # Fig. 2b and the damage map: the first run that got furthest
    for run in runs:
        grid, length, plr, ifr = run.plug_ratios()
        last = (grid >= grid[-1] - 5e-3 + 1e-12) & np.isfinite(ifr)
        summary["runs"][run.label] = {
            "seed": run.seed, "velocity_m_s": run.velocity,
            "particles": float(run.series["dem_particle_count"][-1]),
            "dem_steps": run.summary.get("dem_steps"), "wall_time_s": run.summary.get("wall_time_s"),
            "final_displacement_m": float(np.max(run.h)), "failure": run.failure,
            "force_n": {f"{d:g}mm": run.force_near(1e-3 * d) for d in DEPTHS_MM},
            "mean_force_n_5_to_20mm": float(np.mean(run.force[(run.h >= 5e-3) & (run.h <= 20e-3)])) if np.max(run.h) >= 20e-3 else float("nan"),
            "final_force_n": {"total": float(run.force[-1]), "annulus": float(run.tip[-1]), "inner_shaft": float(run.inner[-1]),
                              "outer_shaft": float(run.outer[-1])},
            "split_max_abs_error_n": float(np.max(np.abs(run.tip + run.inner + run.outer - run.force))),
            "final_plug_length_m": float(length[-1]), "final_plug_length_ratio": float(plr[-1]),
            "ifr_last_5mm": float(np.mean(ifr[last])),
            "force_balance": force_balance(run),
            **analyse(run, out, figures=run is section),
        }
    entries = summary["runs"].values()
    summary["packings"] = {
        **{f"force_n_at_{d:g}mm": spread([e["force_n"][f"{d:g}mm"] for e in entries]) for d in DEPTHS_MM},
        "mean_force_n_5_to_20mm": spread([e["mean_force_n_5_to_20mm"] for e in entries]),
        "final_plug_length_ratio": spread([e["final_plug_length_ratio"] for e in entries if e["final_displacement_m"] >= 0.02 - 1e-4]),
        "ifr_last_5mm": spread([e["ifr_last_5mm"] for e in entries]),
        "fdm_at_wall_over_wall_traction_within_1D": spread([e["fdm_at_wall_over_wall_traction_within_1D"] for e in entries]),
        "wall_time_s": spread([e["wall_time_s"] or float("nan") for e in entries]),
    }
    with open(os.path.join(out, "summary.json"), "w", encoding="utf-8") as handle:
        json.dump(summary, handle, indent=1, default=float)
    for label, e in summary["runs"].items():
        forces = ", ".join(f"{k} {v:.1f} N" if math.isfinite(v) else f"{k} not reached" for k, v in e["force_n"].items())
        wall = f"wall time {e['wall_time_s']:.0f} s" if e["wall_time_s"] is not None else f"stopped at {1e3 * e['final_displacement_m']:.1f} mm"
        print(f"{label}: {forces}; final PLR {e['final_plug_length_ratio']:.2f}, IFR over the last 5 mm {e['ifr_last_5mm']:.2f}; {wall}")
    print(f"figures and summary.json in {out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
