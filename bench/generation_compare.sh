#!/usr/bin/env bash
# PCRM against conventional generation (docs/dem_generation.md, "PCRM against
# conventional generation"): the same bonded chalk body at 100 g, in the same
# rigid floor and side wall, generated (a) by PCRM and (b) conventionally
# (radius expansion of the whole domain, settling under N g, bonds, settling),
# both to an unbalanced-force ratio of 0.002, on one thread. Prints for each
# route the spheres, bonds, the wall time of each stage, the steps, the
# stress-profile errors against sigma_v = gamma z and sigma_h = K0 gamma z,
# sigma_h / sigma_v, the porosity, and the ratio of the wall times.
#
#   bench/generation_compare.sh [BUILD_DIR] [small|medium|all]   (default ./build, all)
#
# small:  the cylinder of tests/e2e/scenarios/centrifuge_generation_small.json
#         (R = 10 mm, H = 32 mm, S = 10), about 4 400 spheres: ~2 min;
# medium: R = 20 mm, H = 60 mm at S = 10, about 33 000 spheres: about an hour
#         on one busy thread (not run to the end yet: the doc gives a projection).
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
BUILD=${1:-$ROOT/build}
SIZES=${2:-all}
PYTHON=/usr/bin/python3
cmake --build "$BUILD" -j2 --target generation_compare > /dev/null
SCENARIO=$ROOT/tests/e2e/scenarios/centrifuge_generation_small.json
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT
run() {  # name, extra options
  local name=$1
  shift
  echo "generation_compare: $name ($*)" >&2
  "$BUILD/bin/generation_compare" --scenario "$SCENARIO" --threads 1 "$@" > "$OUT/$name.jsonl" 2> "$OUT/$name.log" || {
    cat "$OUT/$name.log" >&2
    exit 1
  }
}
# The conventional expansion targets a porosity of 0.47: at the PCRM body's
# 0.434 (and at the REV's own target, 0.45) the rigid container jams and the
# expansion goes unstable (docs/dem_generation.md §8). Each settling stage is
# capped at 25 000 steps; a route that hits the cap prints eq = NO.
CONVENTIONAL=(--porosity 0.47 --max-steps 25000)
case $SIZES in
  small) run small "${CONVENTIONAL[@]}" ;;
  medium) run medium --radius-m 0.02 --height-m 0.06 "${CONVENTIONAL[@]}" ;;
  all) run small "${CONVENTIONAL[@]}" && run medium --radius-m 0.02 --height-m 0.06 "${CONVENTIONAL[@]}" ;;
  *) echo "usage: $0 [BUILD_DIR] [small|medium|all]" >&2; exit 2 ;;
esac
"$PYTHON" - "$OUT"/*.jsonl <<'PY'
import json, os, sys
rows = []
for path in sys.argv[1:]:
    name = os.path.basename(path)[:-len(".jsonl")]
    routes = {r["route"]: r for r in map(json.loads, open(path))}
    rows.append((name, routes))
print(f"{'domain':7s} {'route':12s} {'spheres':>8s} {'bonds':>7s} {'stages (s)':>34s} {'total s':>8s} {'steps':>8s} {'Mpart-st':>8s} "
      f"{'sv rms/max %':>13s} {'sh rms/max %':>13s} {'sh/sv':>6s} {'poros':>6s} {'floor':>6s} {'eq':>3s}")
for name, routes in rows:
    for route in ("pcrm", "conventional"):
        r = routes[route]
        stages = "+".join(f"{s['seconds']:.1f}" for s in r["stages"].values())
        work = sum(s["particle_steps"] for s in r["stages"].values()) / 1e6
        print(f"{name:7s} {route:12s} {r['spheres']:8d} {r['bonds_intact'] + r['bonds_damaged']:7d} {stages:>34s} {r['seconds']:8.1f} {r['steps']:8d} "
              f"{work:8.1f} {100 * r['sigma_v_error_rms']:6.1f}/{100 * r['sigma_v_error_max']:<6.1f} "
              f"{100 * r['sigma_h_error_rms']:6.1f}/{100 * r['sigma_h_error_max']:<6.1f} {r['k_mean']:6.3f} {r['porosity_interior']:6.3f} "
              f"{r['walls']['floor_weight_share']:6.3f} {'yes' if r['reached'] else 'NO':>3s}")
    ratio = routes["conventional"]["seconds"] / routes["pcrm"]["seconds"]
    print(f"{name:7s} conventional / PCRM wall time: {ratio:.1f} x (target: PCRM >= 20 x faster)")
print("stages: pcrm = REV + replication and scaling + trimming and seating + settling; "
      "conventional = expansion + settling + bonds and settling. Errors over the interior slices (one REV cell high); "
      "floor = share of the weight on the floor (the rest on the side wall).")
PY
