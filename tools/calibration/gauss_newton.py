"""The power-law search ("search": {"method": "gauss_newton"}): Gauss-Newton in
log-log space with a Broyden-updated Jacobian and a trust region.

Why: quasi-statically a bonded assembly's strengths and moduli are close to
power laws of its contact parameters (the dimensional argument of the scaling
steps, scaling.py), y_i ~ C_i prod_j p_j^S_ij, so ln y is close to linear in
ln p and one Jacobian S (the log-derivatives of sensitivity.py) predicts the
step that meets every target at once. The scaling steps are the special case
where S is known from dimensions (1 for a strength against the bond
strengths); this search measures S instead, so it also moves parameters no
rule knows (friction, a strength ratio that sets tension against
compression). Nelder-Mead needs about ten evaluations per free parameter;
this needs one per parameter for S, then a few steps.

Steps, on u = ln(p / p_0) about the best point so far:
  1. S by forward differences, one evaluation per parameter at +15 %
     (inwards at a bound; the step of search.py, above the packing noise);
  2. the step delta minimises sum_i w_i^2 (S delta - r)_i^2 + lambda |delta|^2,
     r_i = ln(target_i / mean_i), w_i = 1 / ln(1 + tolerance_i) (a residual
     of one tolerance weighs 1), lambda = 1e-3 of the largest eigenvalue of
     S^T W^2 S (Levenberg 1944: keeps a parameter no target sees still);
  3. delta is cut to the trust radius (ln 2 at first: at most x2 or /2 per
     parameter) and to the bounds, the point is evaluated, and S takes the
     Broyden (1965) rank-one update from what the step did;
  4. a step that improves the objective (search.objective) is kept and the
     radius grows (x1.5, at most ln 4); one that does not halves the radius
     and the next step starts again from the best point.
It stops when every target is inside its tolerance (the callback raises
search.Converged), after max_evaluations, or when the radius falls below
ln 1.01 (the noise of the packings is then larger than the steps).
"""
import math

import numpy as np

from .search import INITIAL_STEP, log_coordinates

FIRST_RADIUS = math.log(2.0)
LARGEST_RADIUS = math.log(4.0)
SMALLEST_RADIUS = math.log(1.01)
DAMPING = 1e-3


def log_means(targets, means):
    """ln of each target's mean, or None where one is not positive (no power law there)."""
    values = [means.get(t.name, float("nan")) for t in targets]
    if not all(math.isfinite(v) and v > 0 for v in values):
        return None
    return np.log(np.array(values))


def gauss_newton_step(jacobian, residual, weights, radius, lower, upper, u):
    """The damped least-squares step from u (module docstring, 2-3), inside the radius and the bounds."""
    a = jacobian * weights[:, None]
    b = residual * weights
    normal = a.T @ a
    scale = max(float(np.max(np.linalg.eigvalsh(normal))), 1e-12)
    delta = np.linalg.solve(normal + DAMPING * scale * np.eye(len(u)), a.T @ b)
    largest = float(np.max(np.abs(delta)))
    if largest > radius:
        delta *= radius / largest
    return np.clip(u + delta, lower, upper) - u


def broyden_update(jacobian, delta, change):
    """J + (change - J delta) delta^T / |delta|^2: the Jacobian that reproduces the last step."""
    norm2 = float(delta @ delta)
    if norm2 == 0.0:
        return jacobian
    return jacobian + np.outer(change - jacobian @ delta, delta) / norm2


def gauss_newton(free, targets, start, evaluate, max_evaluations):
    """Meet the targets from start {name: value}; evaluate({name: value}) -> (means, objective)
    raises search.Converged to stop. Returns None (the caller keeps the best)."""
    if max_evaluations <= 0:
        return
    names, p0, lower, upper = log_coordinates(free, start)
    goal = np.log(np.array([t.value for t in targets]))
    weights = np.array([1.0 / math.log(1.0 + t.tolerance) for t in targets])
    budget = [max_evaluations + 1]  # + the start, the caller's best point: cached, not run again

    def run(u):
        budget[0] -= 1
        means, objective = evaluate({n: float(v) for n, v in zip(names, p0 * np.exp(u))})
        return log_means(targets, means), objective

    best_u = np.zeros(len(names))
    best_y, best_objective = run(best_u)  # the start: known to the caller already, so cached
    if best_y is None:
        return
    jacobian = np.zeros((len(targets), len(names)))
    columns = []
    for j in range(len(names)):  # every column from the same base, the start
        if budget[0] <= 0:
            return
        u = np.zeros(len(names))
        u[j] = INITIAL_STEP if upper[j] >= INITIAL_STEP else -INITIAL_STEP
        y, objective = run(u)
        if y is None:
            return
        jacobian[:, j] = (y - best_y) / u[j]
        columns.append((objective, u, y))
    objective, u, y = min(columns, key=lambda c: c[0])
    if objective < best_objective:  # a difference point that did better is the base of the first step
        best_u, best_y, best_objective = u, y, objective
    radius = FIRST_RADIUS
    while budget[0] > 0 and radius >= SMALLEST_RADIUS:
        delta = gauss_newton_step(jacobian, goal - best_y, weights, radius, lower, upper, best_u)
        if float(np.max(np.abs(delta))) < 1e-9:
            return  # pinned at the bounds: nothing left to move
        y, objective = run(best_u + delta)
        if y is None:
            radius /= 2.0
            continue
        jacobian = broyden_update(jacobian, delta, y - best_y)
        if objective < best_objective:
            best_u, best_y, best_objective = best_u + delta, y, objective
            radius = min(1.5 * radius, LARGEST_RADIUS)
        else:
            radius /= 2.0
