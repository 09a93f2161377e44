#!/bin/bash
# Peer DEM benchmark: our DEM (dem_throughput --data) against LAMMPS and LIGGGHTS
# on the same packing (../shared/bench/peers beside the checkout, README there), at 1 and 2
# threads / MPI processes; prints particle-steps/s and our ratios.
#
#   bench/dem_peers.sh [BUILD_DIR]        (default build; builds dem_throughput)
# Environment: SIZE=12k|50k (12k), WARMUP (1000), STEPS (2000), PEERS_DIR.
# Installs the Debian packages lammps liggghts openmpi-bin if missing (needs root).
# Differences of our run from the peers' (docs/dem_benchmarks.md): no periodic
# x/y boundaries (frictionless side walls instead), no tangential dashpot.
# Not part of the default test run.
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/.." && pwd)
BUILD=${1:-$ROOT/build}
PEERS=${PEERS_DIR:-$ROOT/../shared/bench/peers}
SIZE=${SIZE:-12k}; WARMUP=${WARMUP:-1000}; STEPS=${STEPS:-2000}
DATA=$PEERS/data/pack_$SIZE.data
LOGS=$(mktemp -d)
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_btl_vader_single_copy_mechanism=none

# 1. Peers installed?
if ! command -v lmp >/dev/null || ! command -v liggghts >/dev/null || ! command -v mpirun >/dev/null; then
  DEBIAN_FRONTEND=noninteractive apt-get install -y lammps liggghts openmpi-bin >"$LOGS/apt.log" 2>&1 \
    || { echo "dem_peers.sh: could not install lammps liggghts openmpi-bin (see $LOGS/apt.log)" >&2; exit 1; }
fi

# 2. Our DEM.
[ -f "$BUILD/CMakeCache.txt" ] || cmake -S "$ROOT" -B "$BUILD" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$BUILD" --target dem_throughput -j2 >/dev/null
OURS=$("$BUILD/bin/dem_throughput" --data "$DATA" --threads "1 2" --warmup "$WARMUP" --steps "$STEPS")
echo "$OURS" | sed 's/^/ours: /'
ours() { echo "$OURS" | awk -v t="$1" '$1 == "threads" && $2 == t":" {print $3}'; }

# 3. Peers: "Loop time of T on P procs for S steps with N atoms" of the timed run.
peer() {  # $1 = lammps|liggghts, $2 = processes
  local code=$1 p=$2 exe launch log=$LOGS/$1_p$2.log
  [ "$code" = lammps ] && exe=lmp || exe=liggghts
  launch=$exe; [ "$p" -gt 1 ] && launch="mpirun -np $p $exe"
  (cd "$PEERS/$code" && $launch -in bench.in -var data "$DATA" -var nwarm "$WARMUP" -var nrun "$STEPS" -log "$log" >/dev/null 2>&1) || { echo nan; return; }
  # LIGGGHTS appends ", finish time ..." to the line.
  grep "Loop time" "$log" | tail -n 1 | sed -E 's/.*Loop time of ([0-9.eE+-]+) on [0-9]+ procs for ([0-9]+) steps with ([0-9]+) atoms.*/\1 \2 \3/' \
    | awk '{print $3 * $2 / $1}'
}

printf "\n%-10s %-6s %14s %12s\n" code procs particle-steps/s ours/code
for p in 1 2; do
  o=$(ours $p)
  printf "%-10s %-6s %14.3g %12s\n" ours "$p" "$o" "1"
  for code in lammps liggghts; do
    v=$(peer $code $p)
    printf "%-10s %-6s %14.3g %12.3f\n" "$code" "$p" "$v" "$(awk -v a="$o" -v b="$v" 'BEGIN{print (b > 0 ? a / b : 0)}')"
  done
done

# 4. Targets of issue 3 measured in the same run: 1 -> 2 thread speed-up, and
#    bonded (every touching pair bonded by linear_pbond) against unbonded.
BONDED=$("$BUILD/bin/dem_throughput" --data "$DATA" --threads "1 2" --warmup "$WARMUP" --steps "$STEPS" --law linear_pbond)
echo "$BONDED" | sed 's/^/ours bonded: /'
bonded() { echo "$BONDED" | awk -v t="$1" '$1 == "threads" && $2 == t":" {print $3}'; }
printf "\n%-34s %8s %8s\n" "ours" "value" "target"
printf "%-34s %8.3f %8s\n" "speed-up 1 -> 2 threads (linear)" "$(awk -v a="$(ours 2)" -v b="$(ours 1)" 'BEGIN{print a / b}')" ">= 1.7"
for p in 1 2; do
  printf "%-34s %8.3f %8s\n" "bonded / unbonded, $p thread(s)" "$(awk -v a="$(bonded $p)" -v b="$(ours $p)" 'BEGIN{print a / b}')" ">= 0.7"
done
echo "(logs: $LOGS)"
