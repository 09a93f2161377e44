#!/usr/bin/env python3
"""Golden data for the bonded contact laws (tests/dem/bond_laws_golden_test.cpp).

Writes bond_laws.json next to this script:  python3 bond_laws_golden.py

Each case drives ONE contact between two spheres of radius R = 1 mm, contact
normal +z fixed, through phases of constant per-step increments
(dun: opening, dus: shear along x, dtb: bending rotation about x, dtt: twist
about z) and records after every step the force on the first body (fx, fz),
its couple (cx, cz) and the bond state (0 none, 1 intact, 2 damaged,
3 broken in tension, 4 broken in shear).

The expected values are computed here from the equations of
docs/theory/dem_contact_laws.md, independently of the C++ code:
  linear_pbond  §2.1-2.5  (Potyondy & Cundall 2004), step by step;
  soft_bond     §1.2 inferred form, as documented in docs/dem_bond_laws.md;
  damage_bond   §3 on uniaxial paths, where the return to the envelope is
                the analytic point n = +-1, v = 1 or m = 1, so that e.g. in
                monotonic tension N = sigma_t A exp(-(u - u_t)/u_cn) after
                the peak at u_t = sigma_t/kbar_n (closed form, no iteration);
                one combined N-V return solved by brute-force search on the
                envelope (a method unrelated to the C++ Newton/bisection).
Sign convention: tension positive; loads on the first body.
"""
import json
import math
import os

import numpy as np

R = 1e-3
DT = 1e-6


def section(lam):
    rb = lam * R
    a = math.pi * rb * rb
    i = a * rb * rb / 4.0
    return rb, a, i, 2.0 * i


def phases_to_steps(phases):
    for ph in phases:
        for _ in range(ph["steps"]):
            yield ph


# ---------------------------------------------------------------- linear_pbond
PB = dict(emod_pa=1e9, kratio=2.0, friction=0.5, damping_ratio_normal=0.0, pb_emod_pa=2e9, pb_kratio=2.5, pb_rmul=1.0,
          pb_mcf=1.0, pb_ten_pa=1e6, pb_coh_pa=2e6, pb_fa_deg=30.0, bond_gap_m=0.0)


def pbond_case(name, phases, overlap):
    p = PB
    rb, a, i, j = section(p["pb_rmul"])
    kbn = p["pb_emod_pa"] / (2 * R)
    kbs = kbn / p["pb_kratio"]
    kn = math.pi * p["emod_pa"] * R * R / (2 * R)
    ks = kn / p["kratio"]
    tanphi = math.tan(math.radians(p["pb_fa_deg"]))
    state, n, v, mt, mb, lin = 1, 0.0, 0.0, 0.0, 0.0, 0.0
    out = []
    for ph in phases_to_steps(phases):
        fx = fz = cx = cz = 0.0
        if state == 1:
            n += kbn * a * ph["dun"]
            v += kbs * a * ph["dus"]
            mt += kbs * j * ph["dtt"]
            mb += kbn * i * ph["dtb"]
            sigma = n / a + p["pb_mcf"] * abs(mb) * rb / i
            tau = abs(v) / a + p["pb_mcf"] * abs(mt) * rb / j
            tauc = max(0.0, p["pb_coh_pa"] - min(n / a, p["pb_ten_pa"]) * tanphi)
            if sigma >= p["pb_ten_pa"]:
                state = 3
            elif tau >= tauc:
                state = 4
            if state == 1:
                fx, fz, cx, cz = v, n, mb, mt
            else:
                n = v = mt = mb = 0.0
        if overlap > 0:
            fn = kn * overlap
            lin += ks * ph["dus"]
            lin = max(-p["friction"] * fn, min(p["friction"] * fn, lin))
            fx += lin
            fz -= fn
        out.append([fx, fz, cx, cz, state])
    return dict(name=name, law="linear_pbond", parameters=p, overlap=overlap, phases=phases, expected=out)


# ---------------------------------------------------------------- soft_bond
SB = dict(sb_emod_pa=2.8e9, kratio=2.4, friction=0.5, damping_ratio_normal=0.0, sb_rmul=1.0, sb_mcf=1.0, sb_ten_pa=0.45e6,
          sb_coh_pa=0.45e6, sb_fa_deg=32.0, sb_soft=100.0, sb_cut=0.05, bond_gap_m=0.0)  # Zheng et al. 2023 Table 2


def soft_case(name, phases, overlap, params=None):
    p = dict(SB, **(params or {}))
    rb, a, i, j = section(p["sb_rmul"])
    kn = p["sb_emod_pa"] / (2 * R)
    ks = kn / p["kratio"]
    st, zeta, gamma, beta = p["sb_ten_pa"], p["sb_soft"], p["sb_cut"], p["sb_mcf"]
    tanphi = math.tan(math.radians(p["sb_fa_deg"]))
    uc = st / kn
    state, n, v, mt, mb, e, emax, lin = 1, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0
    out = []
    for ph in phases_to_steps(phases):
        fx = fz = cx = cz = 0.0
        if state in (1, 2):
            mb_before = abs(mb)
            n += kn * a * ph["dun"]
            v += ks * a * ph["dus"]
            mt += ks * j * ph["dtt"]
            mb += kn * i * ph["dtb"]
            e += ph["dun"] + beta * rb * (abs(mb) - mb_before) / (kn * i)
            emax = max(emax, e)
            trial = n / a + beta * abs(mb) * rb / i
            cap = st if emax <= uc else (st - kn / zeta * (emax - uc) if zeta > 0 else 0.0)
            if trial >= st or emax > uc:
                state = 3 if (emax >= uc * (1 + zeta * (1 - gamma)) or cap <= gamma * st) else 2
            if state in (1, 2) and trial > cap:
                if n > 0:
                    n *= cap / trial
                    mb *= cap / trial
                else:
                    mb *= (cap - n / a) / (beta * abs(mb) * rb / i)
            if state in (1, 2):
                tau = abs(v) / a + beta * abs(mt) * rb / j
                if tau >= max(0.0, p["sb_coh_pa"] - min(n / a, st) * tanphi):
                    state = 4
            if state in (1, 2):
                fx, fz, cx, cz = v, n, mb, mt
            else:
                n = v = mt = mb = e = emax = 0.0
        if state not in (1, 2) and overlap > 0:
            kc = kn * a
            fn = kc * overlap
            lin += kc / p["kratio"] * ph["dus"]
            lin = max(-p["friction"] * fn, min(p["friction"] * fn, lin))
            fx += lin
            fz -= fn
        out.append([fx, fz, cx, cz, state])
    return dict(name=name, law="soft_bond", parameters=p, overlap=overlap, phases=phases, expected=out)


# ---------------------------------------------------------------- damage_bond
DB = dict(emod_pa=1.7e9, kratio=5.0, friction=0.5, damping_ratio_normal=0.0, bond_emod_pa=1.7e9, bond_kratio=5.0, bond_rmul=1.0,
          ten_pa=1e6, com_pa=50e6, coh_pa=2e6, ucn_m=2e-5, ucs_m=2e-5, theta_c_rad=6e-3, bond_gap_m=0.0)  # Ciantia et al. 2024 Table 1


def damage_uniaxial_case(name, component, phases):
    """One component loaded alone: the return is to the axis intercept of the
    envelope (n = +-1, v = 1 or m = 1), so the plastic displacement is the
    excess over the elastic limit and D = 1 - exp(-accumulated/char)."""
    p = DB
    rb, a, i, j = section(p["bond_rmul"])
    kn = p["bond_emod_pa"] / (2 * R)
    ks = kn / p["bond_kratio"]
    total = plastic = acc = 0.0
    d, state = 0.0, 1
    out = []
    for ph in phases_to_steps(phases):
        inc = {"normal": ph["dun"], "shear": ph["dus"], "bend": ph["dtb"]}[component]
        fx = fz = cx = cz = 0.0
        if state in (1, 2):
            total += inc
            el = total - plastic
            if component == "normal":
                k, lim = kn, (p["ten_pa"] if el >= 0 else p["com_pa"]) / kn
                char = p["ucn_m"]
            elif component == "shear":
                k, lim, char = ks, p["coh_pa"] / ks, p["ucs_m"]
            else:
                k, lim, char = kn, p["ten_pa"] / (kn * rb), p["theta_c_rad"]
            if abs(el) > lim:
                new = math.copysign(lim, el)
                acc += abs(el - new)
                plastic += el - new
                el = new
                d = max(d, 1 - math.exp(-acc / char))
            if d > 0.99:  # broken: the bond is removed, fully damaged
                state = 3 if (component == "normal" and el >= 0) else 4
                d = 1.0
            else:
                state = 2 if d > 0 else 1
                if component == "normal":
                    fz = (1 - d) * k * a * el
                elif component == "shear":
                    fx = (1 - d) * k * a * el
                else:
                    cx = (1 - d) * k * i * el
        out.append([fx, fz, cx, cz, state, d])
    return dict(name=name, law="damage_bond", parameters=p, overlap=-1e-9, phases=phases, expected=out)


def damage_nv_return():
    """Trial (n, v) outside the envelope with m = 0: on f = 0, v = sqrt(1 - n^2).
    Closest point in the energy metric w = (st^2/kn, C^2/ks) by dense search in
    n, then refined by golden-section search."""
    p = DB
    kn = p["bond_emod_pa"] / (2 * R)
    ks = kn / p["bond_kratio"]
    w_n, w_v = p["ten_pa"] ** 2 / kn, p["coh_pa"] ** 2 / ks
    tn, tv = 0.9, 0.8  # f = 0.81 + 0.4096/0.19 - 1 > 0

    def dist(n):
        return w_n * (n - tn) ** 2 + w_v * (math.sqrt(max(0.0, 1 - n * n)) - tv) ** 2

    grid = np.linspace(0.0, 1.0, 200001)
    vals = w_n * (grid - tn) ** 2 + w_v * (np.sqrt(np.clip(1 - grid ** 2, 0, None)) - tv) ** 2
    k = int(np.argmin(vals))
    lo, hi = grid[max(k - 1, 0)], grid[min(k + 1, len(grid) - 1)]
    g = (math.sqrt(5) - 1) / 2
    for _ in range(200):
        c, d2 = hi - g * (hi - lo), lo + g * (hi - lo)
        if dist(c) < dist(d2):
            hi = d2
        else:
            lo = c
    n = 0.5 * (lo + hi)
    return dict(trial=[tn, tv, 0.0], weights=[w_n, w_v, p["ten_pa"] ** 2 / (4 * kn)], expected=[n, math.sqrt(1 - n * n), 0.0])


def ph(steps, dun=0.0, dus=0.0, dtb=0.0, dtt=0.0):
    return dict(steps=steps, dun=dun, dus=dus, dtb=dtb, dtt=dtt)


def main():
    cases = [
        # linear_pbond: elastic limit sigma_c / kbar_n = 1e6 / 1e12 = 1e-6 m opening
        pbond_case("pbond_tension_to_failure", [ph(30, dun=4.1e-8)], -1e-9),
        pbond_case("pbond_shear_to_failure", [ph(60, dus=1.01e-7)], -1e-9),
        pbond_case("pbond_bending_to_failure", [ph(40, dtb=5.1e-5)], -1e-9),
        pbond_case("pbond_combined_nvm_with_linear_part", [ph(120, dun=-1e-8, dus=5e-8, dtb=2e-5, dtt=2e-5)], 2e-7),
        pbond_case("pbond_cyclic_unload_reload", [ph(10, dun=5e-8), ph(20, dun=-5e-8), ph(25, dun=5e-8)], -1e-9),
        # soft_bond, Zheng et al. 2023 Table 2: u_c = sigma_t / k_n = 0.45e6 / 1.4e12 m
        soft_case("soft_tension_softening_to_failure", [ph(1300, dun=0.45e6 / 1.4e12 / 9.7)], -1e-9),
        soft_case("soft_cyclic_unload_reload", [ph(100, dun=0.45e6 / 1.4e12 / 9.7), ph(40, dun=-0.45e6 / 1.4e12 / 9.7),
                                                  ph(80, dun=0.45e6 / 1.4e12 / 9.7)], -1e-9),
        soft_case("soft_shear_brittle", [ph(40, dus=2e-8)], 1e-8),
        soft_case("soft_bending_softening", [ph(300, dtb=2e-5)], -1e-9, {"sb_soft": 10.0}),
        soft_case("soft_combined_compression_shear_twist", [ph(50, dun=-2e-8, dus=2e-8, dtt=1e-5)], -1e-9),
        # damage_bond, Ciantia et al. 2024 Table 1 (elastic limit in tension sigma_t/kbar_n = 1.18e-6 m)
        damage_uniaxial_case("damage_tension_to_failure", "normal", [ph(1000, dun=1e-7)]),
        damage_uniaxial_case("damage_compression", "normal", [ph(400, dun=-2e-7)]),
        damage_uniaxial_case("damage_shear_to_failure", "shear", [ph(1200, dus=1e-7)]),
        damage_uniaxial_case("damage_bending_to_failure", "bend", [ph(1000, dtb=3e-5)]),
        damage_uniaxial_case("damage_cyclic_tension", "normal", [ph(100, dun=1e-7), ph(30, dun=-1e-7), ph(200, dun=1e-7)]),
    ]
    data = dict(radius_m=R, dt_s=DT, cases=cases, damage_nv_return=damage_nv_return())
    path = os.path.join(os.path.dirname(os.path.abspath(__file__)), "bond_laws.json")
    with open(path, "w") as f:
        json.dump(data, f, indent=None, separators=(",", ":"))
        f.write("\n")
    print("wrote", path, "with", len(cases), "cases")


if __name__ == "__main__":
    main()
