"""The dimensionless scaling steps: from the first evaluations to close to the targets.

Why it works. Quasi-statically, a bonded assembly's macroscopic stresses divided
by a modulus depend only on dimensionless groups: the ratios of the moduli
(contact to bond, k_n/k_s), the strengths over the modulus, the critical
displacements over the radius, friction, the packing (dimensional analysis;
the calibration procedure of Potyondy & Cundall 2004 for the bonded-particle
model rests on the same observation: the moduli set the elastic constants,
the bond strengths the strength). Hence, approximately:
  - Young's modulus is proportional to the contact and bond moduli when all
    of them are multiplied by one factor a (the elastic response, before bonds
    break, does not see the strengths);
  - the peak strengths are proportional to the bond strengths multiplied by one
    factor b (the peak is reached when the bonds' stresses reach their
    strengths; the forces that carry a given macroscopic stress do not depend
    on the moduli in a packing that stays small-strain);
  - for the damage bond the critical displacements are multiplied by b/a, so
    that u_c E / (sigma_c R) — the ductility of a bond — is unchanged.
The first two are exact for an elastic-brittle assembly; softening, friction
after breakage and the change of the strain at the peak make them approximate,
and the search (search.py) removes what remains.

a = E_target / E_achieved, b = the geometric mean of target/achieved over the
strength targets (UCS, triaxial peaks, tensile strength; the ratio of the
tensile strength to the UCS does not change under b and is left to the search). A group is scaled only where the
calibration frees one of its parameters and has a target it governs.

Later steps (search.scaling_steps, default 3 in all) use the exponent measured
between the last two evaluations instead of 1: where only the strengths are
free, the strength-to-modulus ratio changes and the rule is no longer exact
(the soft bond's UCS grew as its strengths^1.26 between the first two
evaluations of the calibration in docs/calibration_automatic.md §4); with y ~ p^n, the factor (target/y)^(1/n)
is a secant step in log-log space. The steps stop when an evaluation does
not improve on the best one, and Nelder-Mead takes over.
"""
import math

# The groups of each law's parameters (names as the laws declare them, dem_server --help).
MODULI = {
    "soft_bond": ("sb_emod_pa",),
    "linear_pbond": ("emod_pa", "pb_emod_pa"),
    "damage_bond": ("emod_pa", "bond_emod_pa"),
}
STRENGTHS = {
    "soft_bond": ("sb_ten_pa", "sb_coh_pa"),
    "linear_pbond": ("pb_ten_pa", "pb_coh_pa"),
    "damage_bond": ("ten_pa", "coh_pa", "com_pa"),
}
DISPLACEMENTS = {"damage_bond": ("ucn_m", "ucs_m")}
STRENGTH_TARGETS = ("ucs_pa", "triaxial_peak_deviator_pa", "tensile_strength_pa")


EXPONENT_RANGE = (0.25, 4.0)   # a measured exponent outside this is noise, not a law


def log_misfits(targets, achieved):
    """(ln E_target/E, mean of ln target/y over the strength targets); None where no target governs."""
    modulus, strengths = None, []
    for t in targets:
        value = achieved.get(t.name)
        if value is None or not value > 0:
            continue
        if t.quantity == "young_modulus_pa":
            modulus = math.log(t.value / value)
        elif t.quantity in STRENGTH_TARGETS:
            strengths.append(math.log(t.value / value))
    return modulus, (sum(strengths) / len(strengths) if strengths else None)


def scale_factors(targets, achieved, exponents=(1.0, 1.0)):
    """(a, b): the modulus and strength factors from the achieved means {target name: value},
    for responses y ~ p^n with n = exponents; 1.0 where no target governs the group."""
    return tuple(1.0 if misfit is None else math.exp(misfit / n)
                 for misfit, n in zip(log_misfits(targets, achieved), exponents))


def group_log_change(law, before, after):
    """(ln of the modulus group's factor, ln of the strength group's factor) between two
    parameter sets, from the first free parameter of each group (0.0 where none is free)."""
    out = []
    for group in (MODULI.get(law, ()), STRENGTHS.get(law, ())):
        names = [n for n in group if n in before]
        out.append(math.log(after[names[0]] / before[names[0]]) if names else 0.0)
    return tuple(out)


def measured_exponents(law, targets, previous, current):
    """(n_modulus, n_strength): d ln y / d ln p of each group between two evaluations
    (records with "parameters" and "means"); 1.0 where a group did not move or no target governs it."""
    exponents = []
    for dp, y0, y1 in zip(group_log_change(law, previous["parameters"], current["parameters"]),
                          log_misfits(targets, previous["means"]), log_misfits(targets, current["means"])):
        if abs(dp) < 1e-3 or y0 is None or y1 is None:
            exponents.append(1.0)
            continue
        n = (y0 - y1) / dp    # the misfit ln(target/y) falls by n dp
        exponents.append(min(max(n, EXPONENT_RANGE[0]), EXPONENT_RANGE[1]))
    return tuple(exponents)


def scaled_start(law, free, values, a, b):
    """The free parameters' values after the step, clipped to their bounds.
    `free` is [FreeParameter], `values` {name: value}."""
    factor = {}
    for name in MODULI.get(law, ()):
        factor[name] = a
    for name in STRENGTHS.get(law, ()):
        factor[name] = b
    for name in DISPLACEMENTS.get(law, ()):
        factor[name] = b / a
    out = {}
    for p in free:
        v = values[p.name] * factor.get(p.name, 1.0)
        out[p.name] = min(max(v, p.lower), p.upper)
    return out
