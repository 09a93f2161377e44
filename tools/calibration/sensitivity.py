"""Sensitivity of each target to each free parameter at the optimum.

The log-derivative (elasticity) d ln y / d ln p by a forward finite difference:
S = [ln y(p (1 + h)) - ln y(p)] / ln(1 + h), with h = search.sensitivity_step
(10 % by default: a smaller step would drown in the scatter of a few hundred
spheres), backward where p (1 + h) leaves the bounds. S = 1 means the target is
proportional to the parameter (a strength for the UCS, the modulus for E);
S = 0 means it does not depend on it. The means over the same packings are
differenced, so the packing scatter largely cancels.
"""
import math


def step_for(p, value, h):
    """The perturbed value of parameter p (FreeParameter) at `value`."""
    up = value * (1.0 + h)
    return up if up <= p.upper else value / (1.0 + h)


def log_derivatives(targets, base_means, perturbed_means, base_value, perturbed_value):
    """{target name: d ln y / d ln p} of one parameter's perturbation."""
    dlnp = math.log(perturbed_value / base_value)
    out = {}
    for t in targets:
        y0, y1 = base_means.get(t.name, float("nan")), perturbed_means.get(t.name, float("nan"))
        out[t.name] = math.log(y1 / y0) / dlnp if y0 > 0 and y1 > 0 else float("nan")
    return out
