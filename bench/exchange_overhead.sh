#!/usr/bin/env bash
# The cost of a coupling exchange (docs/exchange_cost.md): the demo pile
# (scenarios/demo_pile.json: 112 interface nodes) run with 1 and with 10 DEM
# steps per exchange, on an idle machine and beside a two-process CPU load,
# with the servers' OpenMP threads sleeping between advances (the coupler's
# default, OMP_WAIT_POLICY=PASSIVE) and spinning (libgomp's default,
# GOMP_SPINCOUNT=300000). For each run it prints the wall time per exchange,
# the solvers' own time per advance (each server logs it at shutdown), the
# overhead (exchange minus both solvers) and its ratio to two protocol round
# trips measured by bench/zmq_round_trip on the same machine under the same
# load: one whose server computes as long as the DEM did before it answers,
# one as long as the FDM (an exchange's waits, in which the waiting process
# sleeps and must be woken), and, on the header line, the back-to-back
# ping-pong floor. Each figure is the median of REPEATS runs.
#
#   bench/exchange_overhead.sh [BUILD_DIR] [REPEATS]     (default ./build, 3; builds nothing)
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
BUILD=${1:-$ROOT/build}
REPEATS=${2:-3}
for program in coupler dem_server fdm_server zmq_round_trip; do
  [ -x "$BUILD/bin/$program" ] || { echo "exchange_overhead.sh: $BUILD/bin/$program is missing: build first (./vc build)" >&2; exit 2; }
done
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT

/usr/bin/python3 - "$ROOT" "$BUILD" "$REPEATS" "$OUT" <<'PY'
import json, os, re, signal, statistics, subprocess, sys
import h5py

root, build, repeats, out = sys.argv[1], sys.argv[2], int(sys.argv[3]), sys.argv[4]
SOLVER = re.compile(r"(\d+) advances \((\d+) steps\): solver ([0-9.eE+-]+) s")

def scenario(dem_steps, exchanges):
    document = json.load(open(os.path.join(root, "scenarios/demo_pile.json")))
    document["coupling"]["exchange_interval"] = dem_steps
    document["run"].update({"exchanges": exchanges, "snapshot_every": 0, "deadline_s": 600})
    document.pop("output", None)
    path = os.path.join(out, f"demo_pile_{dem_steps}.json")
    json.dump(document, open(path, "w"), indent=1)
    return path

def solver_us(log):
    match = SOLVER.search(open(log).read())
    if not match:
        sys.exit(f"exchange_overhead.sh: no solver timing in {log}")
    return float(match.group(3)) / int(match.group(1)) * 1e6

def coupled_run(path, environment):
    folder = os.path.join(out, "run")
    subprocess.run(["rm", "-rf", folder], check=True)
    env = {k: v for k, v in os.environ.items() if k not in ("OMP_WAIT_POLICY", "GOMP_SPINCOUNT")}
    env.update(environment)
    done = subprocess.run([os.path.join(build, "bin/coupler"), "run", path, "--out", folder, "--no-progress"],
                          env=env, capture_output=True, text=True)
    if done.returncode != 0:
        sys.exit(f"exchange_overhead.sh: the run failed:\n{done.stdout}{done.stderr}")
    wall = h5py.File(os.path.join(folder, "results.h5"), "r")["timeseries/wall_time_s"][:]
    exchange = (wall[-1] - wall[0]) / (len(wall) - 1) * 1e6  # the loop only: start-up and shutdown are not exchanges
    return exchange, solver_us(os.path.join(folder, "logs/dem.stderr.log")), solver_us(os.path.join(folder, "logs/continuum.stderr.log"))

def dem_monitor_count(path):
    folder = os.path.join(out, "probe")
    subprocess.run([os.path.join(build, "bin/coupler"), "run", path, "--out", folder, "--no-progress"], capture_output=True, check=True)
    return sum(1 for name in h5py.File(os.path.join(folder, "results.h5"), "r")["timeseries"] if name.startswith("dem_"))

def round_trip_us(monitors, work_us=0.0):
    done = subprocess.run([os.path.join(build, "bin/zmq_round_trip"), "--round-trips", "3000", "--nodes", "112", "--monitors", str(monitors),
                           "--server-work-us", f"{work_us:.1f}"], capture_output=True, text=True, check=True)
    return float(re.search(r"mean ([0-9.]+)", done.stdout).group(1))

load = []
def set_load(on):
    global load
    for process in load:
        process.send_signal(signal.SIGKILL)
        process.wait()
    load = [subprocess.Popen(["sh", "-c", "while :; do :; done"]) for _ in range(2)] if on else []

cases = [(1, 3000), (10, 600)]
policies = [("sleeping (coupler default)", {}), ("spinning (libgomp default)", {"GOMP_SPINCOUNT": "300000"})]
monitors = dem_monitor_count(scenario(1, 20))
print(f"cores {os.cpu_count()}, demo pile: 112 interface nodes, {monitors} DEM monitors; median of {repeats} runs; times in microseconds")
print("2 trips: two round trips whose servers compute as long as the DEM and the FDM did (the exchange's waits)")
print(f"{'load':<10} {'DEM steps':>9} {'OpenMP threads idle':<28} {'exchange':>9} {'DEM':>8} {'FDM':>8} {'overhead':>9} {'2 trips':>8} {'ratio':>6}")
try:
    for loaded in (False, True):
        set_load(loaded)
        floor = 2 * statistics.median(round_trip_us(monitors) for _ in range(repeats))
        print(f"{'2 busy' if loaded else 'idle':<10} two back-to-back round trips (ping-pong, no work between): {floor:.0f}", flush=True)
        for dem_steps, exchanges in cases:
            path = scenario(dem_steps, exchanges)
            for label, environment in policies:
                runs = [coupled_run(path, environment) for _ in range(repeats)]
                exchange, dem, fdm = (statistics.median(r[i] for r in runs) for i in range(3))
                overhead = statistics.median(r[0] - r[1] - r[2] for r in runs)
                trips = statistics.median(round_trip_us(monitors, dem) + round_trip_us(monitors, fdm) for _ in range(repeats))
                print(f"{'2 busy' if loaded else 'idle':<10} {dem_steps:>9} {label:<28} {exchange:>9.0f} {dem:>8.0f} {fdm:>8.0f} {overhead:>9.0f} "
                      f"{trips:>8.0f} {overhead / trips:>6.2f}", flush=True)
finally:
    set_load(False)
PY
