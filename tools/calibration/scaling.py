"""The dimensionless scaling step: one jump from a first evaluation to close to the targets.

Why it works. Quasi-statically, a bonded assembly's macroscopic stresses divided
by a modulus depend only on dimensionless groups: the ratios of the moduli
(contact to bond, k_n/k_s), the strengths over the modulus, the critical
displacements over the radius, friction, the packing (Potyondy & Cundall 2004,
§2.5 and §3: "the macroscopic elastic constants are proportional to the
effective moduli at fixed stiffness ratios"; the same argument for the soft
bond, Itasca PFC 6 "Soft-Bond Model", and for the damage bond, Zheng &
Ciantia 2025). Hence, approximately:
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
strength targets (UCS and triaxial peaks). A group is scaled only where the
calibration frees one of its parameters and has a target it governs.
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
STRENGTH_TARGETS = ("ucs_pa", "triaxial_peak_deviator_pa")


def scale_factors(targets, achieved):
    """(a, b): the modulus and strength factors from the achieved means {target name: value};
    1.0 where no target governs the group."""
    a = 1.0
    logs = []
    for t in targets:
        value = achieved.get(t.name)
        if value is None or not value > 0:
            continue
        if t.quantity == "young_modulus_pa":
            a = t.value / value
        elif t.quantity in STRENGTH_TARGETS:
            logs.append(math.log(t.value / value))
    b = math.exp(sum(logs) / len(logs)) if logs else 1.0
    return a, b


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
