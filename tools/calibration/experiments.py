"""The experiments a calibration runs, built from the sample scenario, and what
is read back from each.

Two kinds of sample (docs/calibrating.md):
- a periodic REV (`periodic` block, `loading.mode` "triaxial"; e.g.
  scenarios/ucs_upscaling.json): unconfined compression with the lateral stress
  servo-held at 0 gives the UCS, Young's modulus and Poisson's ratio (the cell's
  lateral strains), the same REV at sigma_3 > 0 gives a triaxial peak, and the
  same REV pulled along its axis (a negative axial strain rate, the lateral
  stress held at 0: direct tension) gives the tensile strength;
- a sample between platens (`ucs` block; e.g. scenarios/ucs_softbond.json):
  the UCS and Young's modulus only (no lateral strain is recorded).

One experiment on one packing is one scenario: the sample with the contact
parameters of the evaluation, the packing's particles.seed, one thread (the
result does not depend on it; docs/dem_architecture.md) and the experiment's
confinement.
"""
import copy
import json
import os

import numpy as np

from .calibration_file import PERIODIC_ONLY, CalibrationError

import plot_results  # noqa: E402  (tools/: the initial stiffness that ./vc plot and ./vc report use)


def merge_patch(target, patch):
    """RFC 7386 JSON merge patch, the semantics of a scenario's variants
    (nlohmann::json::merge_patch in coupler/src/scenario_variants.cpp)."""
    if not isinstance(patch, dict):
        return copy.deepcopy(patch)
    result = copy.deepcopy(target) if isinstance(target, dict) else {}
    for key, value in patch.items():
        if value is None:
            result.pop(key, None)
        else:
            result[key] = merge_patch(result.get(key), value)
    return result


def absolute_includes(node, folder):
    """Every "include" made absolute, so the scenario can be written anywhere
    (the coupler resolves an include relative to the including file)."""
    if isinstance(node, dict):
        out = {}
        for key, value in node.items():
            if key == "include" and isinstance(value, str):
                out[key] = os.path.normpath(os.path.join(folder, value))
            else:
                out[key] = absolute_includes(value, folder)
        return out
    if isinstance(node, list):
        return [absolute_includes(v, folder) for v in node]
    return node


def resolved_contact(contact, folder):
    """The contact block with its include read in (keys given beside the include win)."""
    if "include" not in contact:
        return dict(contact)
    path = os.path.normpath(os.path.join(folder, contact["include"]))
    with open(path) as f:
        included = resolved_contact(json.load(f), os.path.dirname(path))
    merged = {k: v for k, v in included.items() if not k.startswith("_")}
    merged.update({k: v for k, v in contact.items() if k != "include"})
    return merged


class Sample:
    """The sample scenario of a calibration, its variant and patch applied."""

    def __init__(self, calibration):
        with open(calibration.scenario_path) as f:
            scenario = json.load(f)
        folder = os.path.dirname(calibration.scenario_path)
        variants = {v["label"]: v.get("patch", {}) for v in scenario.pop("variants", [])}
        if calibration.variant:
            if calibration.variant not in variants:
                raise CalibrationError("sample.variant", f"the scenario has no variant '{calibration.variant}'",
                                       f"use one of {', '.join(variants) or '(none: remove the key)'}")
            scenario = merge_patch(scenario, variants[calibration.variant])
        elif variants:
            raise CalibrationError("sample.variant", "missing: the scenario has variants", f"pick one of {', '.join(variants)}")
        scenario = merge_patch(scenario, calibration.sample_patch)
        dem = scenario.get("participants", {}).get("dem", {}).get("config")
        if dem is None:
            raise CalibrationError("sample.scenario", "has no participants.dem.config", "start from a DEM element-test scenario")
        self.contact = resolved_contact(dem.get("contact", {}), folder)
        dem.pop("contact", None)
        self.scenario = absolute_includes(scenario, folder)
        self.periodic = "periodic" in dem and dem["periodic"].get("loading", {}).get("mode") == "triaxial"
        if not self.periodic and "ucs" not in dem:
            raise CalibrationError("sample.scenario", "is neither a periodic REV in triaxial loading nor a UCS between platens",
                                   "start from scenarios/ucs_upscaling.json or scenarios/ucs_softbond.json (docs/calibrating.md)")
        self.name = os.path.splitext(os.path.basename(calibration.scenario_path))[0]

    def check_targets(self, targets):
        if self.periodic:
            return
        for t in targets:
            if t.quantity in PERIODIC_ONLY:
                raise CalibrationError(f"targets.{t.quantity}", "needs a periodic REV sample (platens record no lateral strain, "
                                       "hold no confinement and cannot pull)", "start from scenarios/ucs_upscaling.json, or remove the target")

    def base_contact(self, law, fixed):
        """The law's parameters the sample gives (if it uses the same law), then the calibration's fixed values."""
        contact = dict(self.contact) if self.contact.get("law") == law else {"law": law}
        contact.update(fixed)
        return contact

    def scenario_for(self, contact, seed, confinement_pa, tension=False):
        """The scenario of one experiment (unconfined if confinement_pa is 0;
        with `tension`, the REV pulled at the sample's axial strain rate) on one packing."""
        scenario = copy.deepcopy(self.scenario)
        dem = scenario["participants"]["dem"]["config"]
        dem["contact"] = contact
        dem["particles"]["seed"] = seed
        dem["threads"] = 1
        if self.periodic:
            loading = dem["periodic"]["loading"]
            loading["stress_pa"] = confinement_pa
            if tension:  # direct tension (docs/dem_periodic.md): the axial edge lengthens
                loading["axial_strain_rate_per_s"] = -abs(loading["axial_strain_rate_per_s"])
            if confinement_pa > 0 and dem["periodic"].get("consolidation", {}).get("mode") == "isotropic":
                # Consolidated to sigma_3 before bonding, as scenarios/triaxial_damagebond.json does.
                dem["periodic"]["consolidation"]["stress_pa"] = confinement_pa
        scenario.setdefault("run", {})["snapshot_every"] = 0
        return scenario


def _column(series, name):
    s = series.get(name)
    return None if s is None else np.asarray(s.values, dtype=float)


def measure_tension(series):
    """The tensile strength of a pulled REV: its largest tension, minus the
    smallest axial stress (compression positive), and whether it came before the end."""
    axial = _column(series, "dem_cell_strain_zz")
    tension = -_column(series, "dem_cell_stress_zz_pa")
    n = min(len(axial), len(tension))
    peak = int(np.argmax(tension[:n]))
    return {"tensile_strength_pa": float(tension[peak]), "strain_at_peak": float(axial[peak]), "peak_reached": bool(peak < n - 1)}


def measure(series, periodic):
    """{quantity: value} of one run's time series ({column: Series}).

    Peak: the largest axial (unconfined) or deviator stress. Young's modulus:
    the least-squares slope of the pre-peak points below 30 % of the peak
    (plot_results.initial_stiffness, what ./vc plot prints). Poisson's ratio:
    minus the slope of the mean lateral strain against the axial strain over
    the same points (strains compression positive, docs/dem_periodic.md)."""
    if periodic:
        axial = _column(series, "dem_cell_strain_zz")
        sigma_a = _column(series, "dem_cell_stress_zz_pa")
        lateral = 0.5 * (_column(series, "dem_cell_strain_xx") + _column(series, "dem_cell_strain_yy"))
        sigma_3 = 0.5 * (_column(series, "dem_cell_stress_xx_pa") + _column(series, "dem_cell_stress_yy_pa"))
        q = sigma_a - sigma_3
    else:
        axial = _column(series, "dem_axial_strain")
        q = _column(series, "dem_axial_stress_pa")
        lateral = None
    n = min(len(axial), len(q))
    axial, q = axial[:n], q[:n]
    peak = int(np.argmax(q))
    # A peak at the last point is no peak: the run stopped before failure.
    out = {"peak_pa": float(q[peak]), "strain_at_peak": float(axial[peak]), "peak_reached": bool(peak < n - 1),
           "young_modulus_pa": plot_results.initial_stiffness(axial, q)}
    if lateral is not None:
        pre = np.arange(peak + 1)
        mask = q[pre] <= 0.3 * q[peak]
        if mask.sum() >= 2:
            out["poisson_ratio"] = float(-np.polyfit(axial[pre][mask], lateral[:n][pre][mask], 1)[0])
    return out
