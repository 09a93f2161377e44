#!/usr/bin/env bash
# Exact restart at random points (docs/checkpoints.md): the bonded coupled pile
# of the test suite (tests/e2e/scenarios/pile_bonded_restart.json) run once
# without interruption, then REPEATS times with run.checkpoint_every = k for a
# random k, killed with SIGKILL (coupler and both servers) a random moment
# after its first checkpoint, and resumed with `coupler run --resume`. Each
# resumed results file must equal the uninterrupted one bit for bit (every
# time-series column but wall_time_s, every snapshot array). Prints one line
# per repeat and the checkpoint's size and write time.
#
#   bench/restart_exact.sh [BUILD_DIR] [REPEATS]     (default ./build, 20; builds nothing)
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
BUILD=${1:-$ROOT/build}
REPEATS=${2:-20}
PYTHON=/usr/bin/python3
SCENARIO=$ROOT/tests/e2e/scenarios/pile_bonded_restart.json
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT
EXCHANGES=$("$PYTHON" -c 'import json,sys; print(json.load(open(sys.argv[1]))["run"]["exchanges"])' "$SCENARIO")

"$BUILD/bin/coupler" run "$SCENARIO" --out "$OUT/uninterrupted" --no-progress > "$OUT/uninterrupted.log" 2>&1

compare() {  # prints "identical" or the first differing dataset
  "$PYTHON" - "$1" "$2" <<'PY'
import sys, h5py, numpy as np
a, b = h5py.File(sys.argv[1], "r"), h5py.File(sys.argv[2], "r")
names = []
a.visititems(lambda n, o: names.append(n) if isinstance(o, h5py.Dataset) else None)
other = []
b.visititems(lambda n, o: other.append(n) if isinstance(o, h5py.Dataset) else None)
if sorted(names) != sorted(other):
    print("different datasets:", sorted(set(names) ^ set(other))[:5]); sys.exit(1)
for n in names:
    if n == "timeseries/wall_time_s":
        continue
    x, y = a[n][()], b[n][()]
    if x.shape != y.shape or x.tobytes() != y.tobytes():
        print("differs:", n); sys.exit(1)
print("identical")
PY
}

failures=0
printf '%-6s %-8s %-10s %-12s %s\n' repeat k killed_at resumed_at result
for r in $(seq 1 "$REPEATS"); do
  k=$(( (RANDOM % (EXCHANGES - 1)) + 1 ))
  run=$OUT/run$r
  "$PYTHON" -c 'import json,sys; s=json.load(open(sys.argv[1])); s["run"]["checkpoint_every"]=int(sys.argv[2]); json.dump(s, open(sys.argv[3], "w"))' \
    "$SCENARIO" "$k" "$OUT/k$r.json"
  "$BUILD/bin/coupler" run "$OUT/k$r.json" --out "$run" --no-progress > "$OUT/run$r.log" 2>&1 &
  pid=$!
  while [ ! -e "$run/checkpoint/coupler.checkpoint" ] && kill -0 "$pid" 2>/dev/null; do sleep 0.002; done
  sleep "0.0$((RANDOM % 10))"  # a random moment after the first checkpoint
  killed=no
  if kill -STOP "$pid" 2>/dev/null; then
    for child in $(cat "/proc/$pid/task/"*/children 2>/dev/null); do kill -KILL "$child" 2>/dev/null || true; done
    kill -KILL "$pid" 2>/dev/null && killed=yes
  fi
  wait "$pid" 2>/dev/null || true
  "$BUILD/bin/coupler" run --resume "$run" --no-progress > "$OUT/resume$r.log" 2>&1 || { echo "resume $r failed:"; cat "$OUT/resume$r.log"; exit 1; }
  resumed_at=$(grep -o 'after exchange [0-9]*' "$OUT/resume$r.log" | grep -o '[0-9]*$' || echo "?")
  result=$(compare "$OUT/uninterrupted/results.h5" "$run/results.h5") || failures=$((failures + 1))
  printf '%-6s %-8s %-10s %-12s %s\n' "$r" "$k" "$killed" "$resumed_at" "$result"
done
size=$(du -cb "$OUT/run1/checkpoint/"*.checkpoint | tail -1 | cut -f1)
echo "checkpoint folder: $size bytes ($(ls "$OUT/run1/checkpoint/" | tr '\n' ' '))"
echo "$failures of $REPEATS resumed runs differ from the uninterrupted one"
[ "$failures" -eq 0 ]
