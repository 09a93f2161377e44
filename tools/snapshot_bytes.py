#!/usr/bin/env python3
"""Bytes per particle per snapshot of a run's DEM snapshots (docs/looking_at_a_run.md §4).

    snapshot_bytes.py RUN_DIR [--role dem]

Sums the size of every dataset of every snapshot of the role, raw (its
values at their width) and stored (h5py's storage size: what the file holds
after compression), and divides by the snapshots and by their particles.
Prints a Markdown table: each array, then the arrays the coupler wrote before
issue 44 (the particles, bond midpoints and states, walls) against all of them.
"""
import argparse
import os
import sys

import h5py

# Arrays issue 44 added to a DEM snapshot (dem_server snapshot_pairs.hpp, wall_facet_wall).
ADDED = {"bond_particle_index", "bond_particle_id", "bond_normal_force_n", "bond_shear_force_n", "bond_opening_m", "wall_facet_wall",
         "contact_particle_index", "contact_normal_force_n", "contact_force_n"}


def measure(path, role):
    if os.path.isdir(path):
        path = os.path.join(path, "results.h5")
    sizes, raw, particles, snapshots, bonds, contacts = {}, {}, 0, 0, 0, 0
    with h5py.File(path, "r") as f:
        for name, group in f["snapshots"][role].items():
            snapshots += 1
            particles += group["particle_position"].shape[0]
            bonds += group["bond_state"].shape[0] if "bond_state" in group else 0
            contacts += group["contact_normal_force_n"].shape[0] if "contact_normal_force_n" in group else 0
            for key, item in group.items():
                sizes[key] = sizes.get(key, 0) + item.id.get_storage_size()
                raw[key] = raw.get(key, 0) + item.size * item.dtype.itemsize
    return sizes, raw, particles, snapshots, bonds, contacts


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("run", help="the run's folder or its results.h5")
    parser.add_argument("--role", default="dem")
    args = parser.parse_args(argv)
    sizes, raw, particles, snapshots, bonds, contacts = measure(args.run, args.role)
    if not particles:
        sys.exit(f"{args.run}: no particles in the '{args.role}' snapshots")
    print(f"{snapshots} snapshots, {particles / snapshots:.0f} particles, {bonds / snapshots:.0f} bonds and "
          f"{contacts / snapshots:.0f} contacts per snapshot on average\n")
    print("| array | bytes per particle per snapshot, raw | stored |\n|---|---|---|")
    for key in sorted(sizes):
        print(f"| `{key}`{' (new)' if key in ADDED else ''} | {raw[key] / particles:.1f} | {sizes[key] / particles:.1f} |")
    before = [sum(v for k, v in table.items() if k not in ADDED) / particles for table in (raw, sizes)]
    print(f"| **before** (arrays written before issue 44) | **{before[0]:.1f}** | **{before[1]:.1f}** |")
    print(f"| **after** (all) | **{sum(raw.values()) / particles:.1f}** | **{sum(sizes.values()) / particles:.1f}** |")


if __name__ == "__main__":
    main()
