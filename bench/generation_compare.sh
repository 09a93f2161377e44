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
#   bench/generation_compare.sh [BUILD_DIR] [RUNS]   (default ./build, all; RUNS: names below, space-separated)
#   GENERATION_COMPARE_OUT=DIR keeps each run's JSON lines (DIR/NAME.jsonl) and progress log.
#
# Runs (each also runs the PCRM route, the reference of its ratio):
#   small_strict    the cylinder of tests/e2e/scenarios/centrifuge_generation_small.json
#                   (R = 10 mm, H = 32 mm, S = 10), about 4 400 spheres, the conventional
#                   settling before bonding to the ratio as the procedure says, capped at
#                   400 000 steps (it does not get there: the unbonded packing creeps): ~15 min;
#   small_early     the same, bonded after 20 000 steps of settling (the bonds then
#                   bring it to the ratio): ~2 min;
#   medium_early    R = 20 mm, H = 60 mm at S = 10, about 33 000 spheres, bonded early: ~30 min.
#   small = small_early small_strict; medium = medium_early; all = all three.
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
BUILD=${1:-$ROOT/build}
SIZES=${2:-all}
PYTHON=/usr/bin/python3
cmake --build "$BUILD" -j2 --target generation_compare > /dev/null
SCENARIO=$ROOT/tests/e2e/scenarios/centrifuge_generation_small.json
if [[ -n ${GENERATION_COMPARE_OUT:-} ]]; then  # keep the JSON lines and logs there
  OUT=$GENERATION_COMPARE_OUT
  mkdir -p "$OUT"
else
  OUT=$(mktemp -d)
  trap 'rm -rf "$OUT"' EXIT
fi
run() {  # name, extra options
  local name=$1
  shift
  echo "generation_compare: $name ($*)" >&2
  "$BUILD/bin/generation_compare" --scenario "$SCENARIO" --threads 1 "$@" > "$OUT/$name.jsonl" 2> "$OUT/$name.log" || {
    cat "$OUT/$name.log" >&2
    exit 1
  }
}
# The conventional expansion targets a porosity of 0.47 (the medium domain
# 0.5): at the PCRM body's 0.434 (and at the REV's own target, 0.45) the rigid
# container jams and the expansion goes unstable, the medium domain already at
# 0.47 (docs/dem_generation.md §8). The relaxation, each
# settling stage and the settling after bonding are capped at 400 000 steps;
# a route that hits a cap prints eq = NO.
CONVENTIONAL=(--porosity 0.47 --max-steps 400000)
MEDIUM=(--radius-m 0.02 --height-m 0.06 --porosity 0.5)  # after CONVENTIONAL: the later --porosity counts
for size in $SIZES; do
  case $size in
    small_strict) run small_strict "${CONVENTIONAL[@]}" ;;
    small_early) run small_early "${CONVENTIONAL[@]}" --unbonded-max-steps 20000 ;;
    medium_early | medium) run medium_early "${CONVENTIONAL[@]}" "${MEDIUM[@]}" --unbonded-max-steps 20000 ;;
    small) "$0" "$BUILD" "small_early small_strict"; exit ;;
    all) "$0" "$BUILD" "small_early medium_early small_strict"; exit ;;
    *) echo "usage: $0 [BUILD_DIR] ['small|medium|all|small_strict|small_early|medium_early ...']" >&2; exit 2 ;;
  esac
done
"$PYTHON" - "$OUT"/*.jsonl <<'PY'
import json, os, sys
rows = []
for path in sys.argv[1:]:
    name = os.path.basename(path)[:-len(".jsonl")]
    routes = {r["route"]: r for r in map(json.loads, open(path))}
    rows.append((name, routes))
STAGES = {"pcrm": ("rev", "replication_and_scaling", "trimming_and_seating", "settling"),
          "conventional": ("expansion", "relaxation", "settling", "bonding_and_settling")}
print(f"{'run':12s} {'route':12s} {'spheres':>8s} {'bonds':>7s} {'stages (s)':>30s} {'total s':>8s} {'CPU s':>7s} {'steps':>8s} {'Mpart-st':>8s} "
      f"{'ratio':>7s} {'sv rms/max %':>13s} {'sh rms/max %':>13s} {'sh/sv':>6s} {'poros':>6s} {'floor':>6s} {'eq':>3s}")
work = lambda r: sum(s["particle_steps"] for s in r["stages"].values())
for name, routes in rows:
    for route in ("pcrm", "conventional"):
        r = routes[route]
        stages = "+".join(f"{r['stages'][s]['seconds']:.1f}" for s in STAGES[route])
        ratio_before = (f" (before bonding {r['ratio_before_bonding']:.3f}, {'at' if r['settled_before_bonding'] else 'capped above'} the ratio)"
                        if route == "conventional" else "")
        print(f"{name:12s} {route:12s} {r['spheres']:8d} {r['bonds_intact'] + r['bonds_damaged']:7d} {stages:>30s} {r['seconds']:8.1f} {r['cpu_seconds']:7.1f} {r['steps']:8d} "
              f"{work(r) / 1e6:8.1f} {r['unbalanced_force_ratio']:7.4f} {100 * r['sigma_v_error_rms']:6.1f}/{100 * r['sigma_v_error_max']:<6.1f} "
              f"{100 * r['sigma_h_error_rms']:6.1f}/{100 * r['sigma_h_error_max']:<6.1f} {r['k_mean']:6.3f} {r['porosity_interior']:6.3f} "
              f"{r['walls']['floor_weight_share']:6.3f} {'yes' if r['reached'] else 'NO':>3s}{ratio_before}")
    conventional, pcrm = routes["conventional"], routes["pcrm"]
    print(f"{name:12s} conventional / PCRM: wall time {conventional['seconds'] / pcrm['seconds']:.1f} x, "
          f"CPU time {conventional['cpu_seconds'] / pcrm['cpu_seconds']:.1f} x, "
          f"particle-steps {work(conventional) / work(pcrm):.1f} x (target: PCRM >= 20 x faster)")
print("stages (wall time): pcrm = REV + replication and scaling + trimming and seating + settling; conventional = expansion + "
      "relaxation with the lid + settling under N g + bonds and settling. ratio: the final unbalanced-force ratio "
      "(target 0.002). Errors over the interior slices (one REV cell high); floor = share of the weight on the floor "
      "(the rest on the side wall).")
PY
