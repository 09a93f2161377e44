#!/usr/bin/env bash
# Generation benchmark (docs/dem_generation.md): builds the virtual-centrifuge
# model by PCRM at 100 g, the small variant and the paper's geometry, and
# prints the particle counts, the wall time of each stage and the stress
# profile error against sigma_v = gamma z, sigma_h = K0 sigma_v.
#
#   bench/generation.sh [BUILD_DIR]      (default ./build; builds nothing)
#
# The comparison with conventional generation (radius expansion of the whole
# domain and settling under N g) is bench/generation_compare.sh.
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
BUILD=${1:-$ROOT/build}
PYTHON=/usr/bin/python3
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT
"$PYTHON" - "$ROOT/scenarios/centrifuge_generation.json" "$OUT/full.json" <<'PY'
import json, sys
scenario = json.load(open(sys.argv[1]))
scenario.pop("variants")
scenario["name"] = "centrifuge_generation_g100"
json.dump(scenario, open(sys.argv[2], "w"))
PY
printf '%-30s %10s %10s %8s %8s %10s %10s %9s %9s\n' scenario spheres bonds "REV s" "repl s" "equil s" "steps" "sv rms%" "sh rms%"
for name in small full; do
  case $name in
    small) scenario=$ROOT/tests/e2e/scenarios/centrifuge_generation_small.json ;;
    full) scenario=$OUT/full.json ;;
  esac
  "$BUILD/bin/coupler" run "$scenario" --out "$OUT/$name" --no-progress > "$OUT/$name.log" 2>&1
  "$PYTHON" "$ROOT/tools/stress_profiles.py" "$OUT/$name/results.h5" > /dev/null
  "$PYTHON" - "$OUT/$name" "$name" <<'PY'
import json, re, sys
import h5py, numpy as np
out, name = sys.argv[1], sys.argv[2]
log = open(out + "/logs/dem.stderr.log").read()
rev = float(re.search(r"pcrm REV: .* ([0-9.e+-]+) s$", log, re.M).group(1))
rep = float(re.search(r"pcrm replication: .* ([0-9.e+-]+) s$", log, re.M).group(1))
with h5py.File(out + "/results.h5", "r") as f:
    summary = json.loads(f.attrs["summary"])
    t = f["timeseries"]
    g = f["profiles"]
    ev = (g["sigma_v_pa"][1:-1] - g["sigma_v_theory_pa"][1:-1]) / g["sigma_v_theory_pa"][1:-1]
    eh = (g["sigma_h_pa"][1:-1] - g["sigma_h_theory_pa"][1:-1]) / g["sigma_h_theory_pa"][1:-1]
    print(f"{name:30s} {int(t['dem_particle_count'][-1]):10d} {int(t['dem_bonds_intact'][-1] + t['dem_bonds_damaged'][-1]):10d} "
          f"{rev:8.1f} {rep:8.1f} {summary['wall_time_s']:10.1f} {summary['dem_steps']:10d} "
          f"{100 * np.sqrt((ev ** 2).mean()):9.2f} {100 * np.sqrt((eh ** 2).mean()):9.2f}")
PY
done
