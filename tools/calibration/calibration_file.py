"""CALIBRATION.json: what to calibrate, against what, on which sample.

    {"name": "...", "law": "soft_bond",
     "sample":  {"scenario": "../ucs_upscaling.json", "variant": "S4", "packings": [11, 12, 13], "patch": {}},
     "fixed":   {"friction": 0.5},
     "free":    {"sb_coh_pa": {"start": 9e5, "min": 1e4, "max": 1e7}},
     "tied":    {"sb_ten_pa": {"to": "sb_coh_pa", "ratio": 1.0}},
     "targets": {"ucs_pa": {"value": 5e5, "tolerance": 0.03},
                 "young_modulus_pa": {...}, "poisson_ratio": {...},
                 "triaxial_peak_deviator_pa": [{"confinement_pa": 1e5, "value": 2e6, "tolerance": 0.05}]},
     "search":  {"max_evaluations": 40, "scaling_steps": 3, "method": "nelder_mead", "stop_at_noise": false,
                 "sensitivity": true, "sensitivity_step": 0.1},
     "output":  {"directory": "results/calibration/mine", "material": "../materials/mine.json"}}

Paths are relative to the calibration file, except output.directory (relative to the
working directory, like a scenario's). output.material (optional): a second copy of
the calibrated material file, e.g. into scenarios/materials/ for scenarios to include. Every mistake is a CalibrationError
that names the key path, says what is wrong and how to fix it (docs/calibration_automatic.md).
"""
import json
import math
import os
from dataclasses import dataclass, field


class CalibrationError(Exception):
    """A mistake in a calibration file: the key path, what is wrong, how to fix it."""

    def __init__(self, key, what, fix):
        super().__init__(f"{key}: {what}; {fix}")
        self.key = key


# The quantities the experiments measure (experiments.py), and the unit of each.
TARGETS = {
    "ucs_pa": "Pa",                       # peak axial stress, unconfined
    "young_modulus_pa": "Pa",             # initial slope of the unconfined test
    "poisson_ratio": "-",                 # -lateral / axial strain over the same points (periodic REV only)
    "triaxial_peak_deviator_pa": "Pa",    # peak q = sigma_1 - sigma_3 at each confinement (periodic REV only)
    "tensile_strength_pa": "Pa",          # peak tension of the REV pulled along its axis (periodic REV only)
    "tensile_to_compressive_ratio": "-",  # that tensile strength over the UCS, packing by packing (periodic REV only)
}
# The targets only a periodic REV measures: lateral strains, a confinement, a pull.
PERIODIC_ONLY = ("poisson_ratio", "triaxial_peak_deviator_pa", "tensile_strength_pa", "tensile_to_compressive_ratio")
# search.method: Nelder-Mead (search.py) or the power-law Gauss-Newton (gauss_newton.py).
SEARCH_METHODS = ("nelder_mead", "gauss_newton")
TOP_KEYS = ("name", "law", "sample", "fixed", "free", "tied", "targets", "search", "output", "_comment", "comment")


@dataclass
class Target:
    name: str                 # e.g. "ucs_pa", "triaxial_peak_deviator_pa@100000"
    quantity: str             # a key of TARGETS
    value: float
    tolerance: float          # relative
    confinement_pa: float = 0.0

    def relative_error(self, achieved):
        return (achieved - self.value) / abs(self.value)


@dataclass
class FreeParameter:
    name: str
    start: float
    lower: float
    upper: float


@dataclass
class Calibration:
    path: str
    name: str
    law: str
    scenario_path: str
    variant: str
    packings: list
    sample_patch: dict
    fixed: dict
    free: list
    tied: dict               # {name: (to, ratio)}
    targets: list
    max_evaluations: int = 40
    scaling_steps: int = 3
    method: str = "nelder_mead"
    stop_at_noise: bool = False
    sensitivity: bool = True
    sensitivity_step: float = 0.1
    output_directory: str = ""
    material_copy: str = ""
    raw: dict = field(default_factory=dict)


def _number(value, key, fix):
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        raise CalibrationError(key, f"expected a finite number, got {json.dumps(value)}", fix)
    return float(value)


def _object(value, key, fix):
    if not isinstance(value, dict):
        raise CalibrationError(key, f"expected an object, got {json.dumps(value)[:60]}", fix)
    return value


def _read_target(name, spec, key, quantity, confinement=0.0):
    _object(spec, key, 'give {"value": V, "tolerance": 0.03}')
    if "value" not in spec:
        raise CalibrationError(f"{key}.value", "missing target value", 'give {"value": V, "tolerance": 0.03}')
    value = _number(spec["value"], f"{key}.value", "give the measured value in the target's unit")
    if value <= 0:
        raise CalibrationError(f"{key}.value", f"must be positive, got {value:g}", "give the measured value in the target's unit")
    tolerance = _number(spec.get("tolerance", 0.05), f"{key}.tolerance", "give a relative tolerance, e.g. 0.03 for 3 %")
    if not 0 < tolerance < 1:
        raise CalibrationError(f"{key}.tolerance", f"must be in (0, 1), got {tolerance:g}", "give a relative tolerance, e.g. 0.03 for 3 %")
    return Target(name, quantity, value, tolerance, confinement)


def read_targets(targets, key="targets"):
    _object(targets, key, "give at least one target, e.g. {\"ucs_pa\": {\"value\": 5e5, \"tolerance\": 0.03}}")
    if not targets:
        raise CalibrationError(key, "missing targets: nothing to calibrate against",
                               'give at least one, e.g. {"ucs_pa": {"value": 5e5, "tolerance": 0.03}}')
    read = []
    for quantity, spec in targets.items():
        if quantity not in TARGETS:
            raise CalibrationError(f"{key}.{quantity}", "unknown target", f"use one of {', '.join(TARGETS)}")
        if quantity == "triaxial_peak_deviator_pa":
            if not isinstance(spec, list) or not spec:
                raise CalibrationError(f"{key}.{quantity}", "expected a list of confinements",
                                       'give [{"confinement_pa": 1e5, "value": V, "tolerance": 0.05}, ...]')
            for i, point in enumerate(spec):
                point_key = f"{key}.{quantity}[{i}]"
                _object(point, point_key, 'give {"confinement_pa": 1e5, "value": V, "tolerance": 0.05}')
                if "confinement_pa" not in point:
                    raise CalibrationError(f"{point_key}.confinement_pa", "missing", "give sigma_3 in Pa (> 0)")
                sigma3 = _number(point["confinement_pa"], f"{point_key}.confinement_pa", "give sigma_3 in Pa (> 0)")
                if sigma3 <= 0:
                    raise CalibrationError(f"{point_key}.confinement_pa", f"must be > 0, got {sigma3:g}",
                                           "give sigma_3 in Pa; the unconfined peak is the target ucs_pa")
                read.append(_read_target(f"{quantity}@{sigma3:g}", point, point_key, quantity, sigma3))
        else:
            read.append(_read_target(quantity, spec, f"{key}.{quantity}", quantity))
    return read


def read_calibration(path):
    """The Calibration of a file; CalibrationError on the first mistake."""
    try:
        with open(path) as f:
            raw = json.load(f)
    except FileNotFoundError:
        raise CalibrationError(path, "no such file", "give the path of a calibration file (scenarios/calibration/)") from None
    except json.JSONDecodeError as e:
        raise CalibrationError(path, f"not JSON ({e})", "fix the syntax") from None
    _object(raw, "(top level)", "a calibration file is one JSON object")
    for key in raw:
        if key not in TOP_KEYS and not key.startswith("_"):
            raise CalibrationError(key, "unknown key", f"use the keys {', '.join(k for k in TOP_KEYS if k[0] != '_' and k != 'comment')}")
    for key in ("law", "sample", "free", "targets"):
        if key not in raw:
            raise CalibrationError(key, "missing", "see scenarios/calibration/ for a complete file")
    here = os.path.dirname(os.path.abspath(path))

    sample = _object(raw["sample"], "sample", 'give {"scenario": "...json", "packings": [1, 2, 3]}')
    if "scenario" not in sample:
        raise CalibrationError("sample.scenario", "missing", "name the scenario to start from (relative to this file)")
    scenario_path = os.path.normpath(os.path.join(here, sample["scenario"]))
    if not os.path.exists(scenario_path):
        raise CalibrationError("sample.scenario", f"no such file {scenario_path}", "give a path relative to the calibration file")
    packings = sample.get("packings")
    if not isinstance(packings, list) or len(packings) < 3 or not all(isinstance(s, int) and not isinstance(s, bool) for s in packings):
        raise CalibrationError("sample.packings", f"expected at least three integer seeds, got {json.dumps(packings)}",
                               "give the particles.seed of each packing, e.g. [11, 12, 13] (the scatter needs three)")
    if len(set(packings)) != len(packings):
        raise CalibrationError("sample.packings", "a seed is repeated", "give distinct seeds")

    free = []
    for name, spec in _object(raw["free"], "free", 'give {"NAME": {"start": x, "min": a, "max": b}}').items():
        key = f"free.{name}"
        _object(spec, key, '{"start": x, "min": a, "max": b}')
        for part in ("start", "min", "max"):
            if part not in spec:
                raise CalibrationError(f"{key}.{part}", "missing", '{"start": x, "min": a, "max": b}')
        start, lower, upper = (_number(spec[p], f"{key}.{p}", "a number in the parameter's unit") for p in ("start", "min", "max"))
        if not 0 < lower < upper:
            raise CalibrationError(key, f"needs 0 < min < max, got min {lower:g}, max {upper:g}",
                                   "the search runs on the logarithm of each free parameter")
        if not lower <= start <= upper:
            raise CalibrationError(f"{key}.start", f"{start:g} is outside [min, max] = [{lower:g}, {upper:g}]", "move start or widen the bounds")
        free.append(FreeParameter(name, start, lower, upper))
    if not free:
        raise CalibrationError("free", "no free parameter", "name at least one parameter of the law with its bounds")

    tied = {}
    for name, spec in _object(raw.get("tied", {}), "tied", '{"NAME": {"to": "FREE_NAME", "ratio": 1.0}}').items():
        _object(spec, f"tied.{name}", '{"to": "FREE_NAME", "ratio": 1.0}')
        to = spec.get("to")
        if to not in {p.name for p in free}:
            raise CalibrationError(f"tied.{name}.to", f"'{to}' is not a free parameter", f"tie to one of {', '.join(p.name for p in free)}")
        tied[name] = (to, _number(spec.get("ratio", 1.0), f"tied.{name}.ratio", "a positive number"))

    fixed = _object(raw.get("fixed", {}), "fixed", '{"NAME": value}')
    search = _object(raw.get("search", {}), "search", '{"max_evaluations": 40}')
    for key in search:
        if key not in ("max_evaluations", "scaling_steps", "method", "stop_at_noise", "sensitivity", "sensitivity_step"):
            raise CalibrationError(f"search.{key}", "unknown key",
                                   "use max_evaluations, scaling_steps, method, stop_at_noise, sensitivity, sensitivity_step")
    method = search.get("method", "nelder_mead")
    if method not in SEARCH_METHODS:
        raise CalibrationError("search.method", f"unknown method {json.dumps(method)}", f"use one of {', '.join(SEARCH_METHODS)}")
    output = _object(raw.get("output", {}), "output", '{"directory": "results/calibration/NAME"}')
    for key in output:
        if key not in ("directory", "material"):
            raise CalibrationError(f"output.{key}", "unknown key", "use directory and material")
    name = raw.get("name", os.path.splitext(os.path.basename(path))[0])
    return Calibration(
        path=os.path.abspath(path), name=name, law=raw["law"], scenario_path=scenario_path,
        variant=sample.get("variant", ""), packings=packings, sample_patch=sample.get("patch", {}),
        fixed=fixed, free=free, tied=tied, targets=read_targets(raw["targets"]),
        max_evaluations=int(search.get("max_evaluations", 40)), scaling_steps=int(search.get("scaling_steps", 3)), method=method,
        stop_at_noise=bool(search.get("stop_at_noise", False)),
        sensitivity=bool(search.get("sensitivity", True)), sensitivity_step=float(search.get("sensitivity_step", 0.1)),
        output_directory=output.get("directory", os.path.join("results", "calibration", name)),
        material_copy=os.path.normpath(os.path.join(here, output["material"])) if "material" in output else "", raw=raw)


def check_against_law(calibration, parameters):
    """Every named parameter is one the law declares, within its declared bounds.
    `parameters` is law_parameters.law_parameters(calibration.law)."""
    def known(name, key):
        if name not in parameters:
            raise CalibrationError(key, f"unknown parameter '{name}' of law {calibration.law}",
                                   f"use one of {', '.join(sorted(parameters))} (build/bin/dem_server --help gives units)")
        return parameters[name]

    for p in calibration.free:
        declared = known(p.name, f"free.{p.name}")
        for part, value in (("min", p.lower), ("max", p.upper)):
            if not declared.admits(value):
                raise CalibrationError(f"free.{p.name}.{part}", f"{value:g} is outside the law's declared bounds {declared.bounds_text()}",
                                       "keep the search range inside the declared bounds")
    for name in calibration.tied:
        known(name, f"tied.{name}")
        if name in {p.name for p in calibration.free}:
            raise CalibrationError(f"tied.{name}", "is also free", "a parameter is either free or tied")
    for name, value in calibration.fixed.items():
        declared = known(name, f"fixed.{name}")
        if isinstance(value, (int, float)) and not isinstance(value, bool) and not declared.admits(float(value)):
            raise CalibrationError(f"fixed.{name}", f"{value:g} is outside the law's declared bounds {declared.bounds_text()}", "give a value inside them")
