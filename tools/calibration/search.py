"""The derivative-free search: Nelder-Mead (scipy.optimize, Nelder & Mead 1965;
bounded as in scipy >= 1.7) on the logarithms of the free parameters.

Why logarithms: the parameters span decades and act multiplicatively (a
strength doubled doubles a peak), so equal steps in ln p are equal relative
changes, the simplex is well-shaped in every direction, and the bounds stay
positive. Coordinates are u_i = ln(p_i / p_i0) about the start p0 (after the
scaling step), so the initial simplex is the start and one point per
parameter at +15 % (ln 1.15), a step large enough to rise above the packing
noise of a few hundred spheres and small enough to stay near the scaled start.

Objective: sum over targets of ((mean - target) / (tolerance * target))^2, the
means over the packings; it is <= 1 per target inside the tolerance. The
search stops as soon as every target is inside its tolerance, or after
max_evaluations evaluations.
"""
import math

import numpy as np
from scipy.optimize import minimize

INITIAL_STEP = math.log(1.15)
PENALTY = 1e6          # objective of an evaluation that measured no value (a run without a peak or a slope)


class Converged(Exception):
    """Every target is inside its tolerance: stop the search here."""


class AtNoiseFloor(Converged):
    """Every target is inside the larger of its tolerance and its mean's standard error
    ("search": {"stop_at_noise": true}): stop, the packings cannot resolve more."""


def objective(targets, means):
    total = 0.0
    for t in targets:
        m = means.get(t.name, float("nan"))
        if not math.isfinite(m):
            return PENALTY
        total += (t.relative_error(m) / t.tolerance) ** 2
    return total


def standard_errors(targets, values):
    """{target name: standard error of the mean over the packings, relative to the target}
    (sample standard deviation / sqrt(n)); NaN with fewer than two packings."""
    out = {}
    for t in targets:
        v = np.asarray(values.get(t.name, []), dtype=float)
        out[t.name] = float(np.std(v, ddof=1) / math.sqrt(len(v)) / abs(t.value)) if len(v) >= 2 else float("nan")
    return out


def within_noise(targets, means, errors):
    """Every target's error inside the larger of its tolerance and its mean's standard
    error (standard_errors): a step from here cannot be told from the packings' noise."""
    return all(math.isfinite(means.get(t.name, float("nan"))) and math.isfinite(errors.get(t.name, float("nan")))
               and abs(t.relative_error(means[t.name])) <= max(t.tolerance, errors[t.name]) for t in targets)


def within_tolerance(targets, means):
    return all(math.isfinite(means.get(t.name, float("nan"))) and abs(t.relative_error(means[t.name])) <= t.tolerance
               for t in targets)


def log_coordinates(free, start):
    """The free parameters' names, their values at start, and the bounds of u = ln(p / p_start)."""
    names = [p.name for p in free]
    p0 = np.array([start[n] for n in names])
    lower = np.array([math.log(p.lower / start[p.name]) for p in free])
    upper = np.array([math.log(p.upper / start[p.name]) for p in free])
    return names, p0, lower, upper


def nelder_mead(free, start, evaluate, max_evaluations):
    """Minimise evaluate({name: value}) -> objective from start {name: value}.
    evaluate raises Converged to stop; returns None (the caller keeps the best)."""
    if max_evaluations <= 0:
        return
    names, p0, lower, upper = log_coordinates(free, start)

    def to_values(u):
        u = np.clip(u, lower, upper)
        return {n: float(v) for n, v in zip(names, p0 * np.exp(u))}

    n = len(names)
    simplex = np.zeros((n + 1, n))
    for i in range(n):
        # Step inwards where +15 % would leave the bounds.
        simplex[i + 1, i] = INITIAL_STEP if upper[i] >= INITIAL_STEP else -INITIAL_STEP
    try:
        minimize(lambda u: evaluate(to_values(u)), np.zeros(n), method="Nelder-Mead",
                 bounds=list(zip(lower, upper)),
                 options={"initial_simplex": simplex, "maxfev": max_evaluations, "xatol": 1e-3, "fatol": 1e-3})
    except Converged:
        pass
