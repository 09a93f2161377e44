#!/usr/bin/env bash
# docs/looking_at_a_run.md's figure and size table, in one command:
#   tools/looking_at_a_run_figures.sh BUILD_DIR
# runs the bonded pile of tests/e2e/scenarios/pile_bonded_restart.json for 120
# exchanges with a snapshot every 40, contacts included (what the test
# python.run_view runs; a few seconds) and the demo's open pile (scenarios/demo_open_pile.json,
# about 20 s) and the foundation of docs/centrifuge_foundation.md to
# 0.25 D_f (a minute or two), draws their last snapshots with tools/render.py into
# docs/figures/looking_at_a_run/ and prints the bytes per particle per
# snapshot (tools/snapshot_bytes.py).
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
BUILD=$(cd "${1:?usage: $0 BUILD_DIR}" && pwd)
PYTHON=/usr/bin/python3
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
"$PYTHON" - "$ROOT/tests/e2e/scenarios/pile_bonded_restart.json" "$WORK/scenario.json" <<'PY'
import json, sys
scenario = json.load(open(sys.argv[1]))
scenario["name"] = "run_view"
scenario["run"].update({"exchanges": 120, "snapshot_every": 40, "deadline_s": 300})
# Every optional array, contacts included, so that the size table counts them all.
scenario["participants"]["dem"]["config"]["snapshot"] = {"contents": ["particle_stress", "bonds", "contacts", "walls"]}
json.dump(scenario, open(sys.argv[2], "w"), indent=1)
PY
"$BUILD/bin/coupler" run "$WORK/scenario.json" --out "$WORK/run" --no-progress
FIGURES="$ROOT/docs/figures/looking_at_a_run"
mkdir -p "$FIGURES"
"$PYTHON" "$ROOT/tools/render.py" "$WORK/run" --snapshot -1 --renderer matplotlib --dpi 110 --out "$WORK/pictures"
cp "$WORK"/pictures/snapshot_*.png "$FIGURES/pile_bonded_section.png"
echo "wrote $FIGURES/pile_bonded_section.png"
# The demo's open pile (./vc demo's scenario, about 20 s): its last snapshot.
"$BUILD/bin/coupler" run "$ROOT/scenarios/demo_open_pile.json" --out "$WORK/demo" --no-progress
"$PYTHON" "$ROOT/tools/render.py" "$WORK/demo" --snapshot -1 --renderer matplotlib --dpi 110 --out "$WORK/demo_pictures"
cp "$WORK"/demo_pictures/snapshot_*.png "$FIGURES/demo_open_pile_section.png"
echo "wrote $FIGURES/demo_open_pile_section.png"
# The same snapshot drawn by ParaView (pvbatch, in xvfb-run without a display), where installed.
if command -v pvbatch >/dev/null && { [ -n "${DISPLAY:-}" ] || { command -v xvfb-run >/dev/null && command -v xauth >/dev/null; }; }; then
  "$PYTHON" "$ROOT/tools/render.py" "$WORK/demo" --snapshot -1 --renderer pvbatch --out "$WORK/demo_pvbatch"
  cp "$WORK"/demo_pvbatch/snapshot_*.png "$FIGURES/demo_open_pile_section_pvbatch.png"
  echo "wrote $FIGURES/demo_open_pile_section_pvbatch.png"
else
  echo "pvbatch (or a display / xvfb-run and xauth) not found: $FIGURES/demo_open_pile_section_pvbatch.png kept as it is"
fi
# The foundation of docs/centrifuge_foundation.md (Fig. 7's run: 100 g,
# packing 1) pushed 3 mm (0.25 D_f) at the study's rate, one DEM thread: a
# minute or two. Its last snapshot: the bonds broken beneath the tip.
"$BUILD/bin/coupler" expand "$ROOT/scenarios/centrifuge_pile_gravity.json" > "$WORK/foundation_variants.json"
"$PYTHON" - "$WORK/foundation_variants.json" "$WORK/foundation.json" <<'PY'
import json, sys
scenario = next(s for s in json.load(open(sys.argv[1])) if s["name"].endswith("_g100_p1"))
scenario["name"] = "foundation_view"
scenario["run"]["stop_when"]["at_least"] = 0.003
scenario["participants"]["dem"]["config"]["threads"] = 1
scenario.pop("output", None)
json.dump(scenario, open(sys.argv[2], "w"), indent=1)
PY
"$BUILD/bin/coupler" run "$WORK/foundation.json" --out "$WORK/foundation" --no-progress
"$PYTHON" "$ROOT/tools/render.py" "$WORK/foundation" --snapshot -1 --renderer matplotlib --dpi 110 --out "$WORK/foundation_pictures"
cp "$WORK"/foundation_pictures/snapshot_*.png "$FIGURES/foundation_section.png"
echo "wrote $FIGURES/foundation_section.png"
"$PYTHON" "$ROOT/tools/snapshot_bytes.py" "$WORK/run"
