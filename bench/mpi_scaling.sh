#!/bin/bash
# The DEM decomposed over MPI processes on the real workload
# (DistributedSimulation, docs/determinism.md §3): the medium graded body of
# bench/paper_model.sh (about 60 000 spheres of the paper model's generation,
# zones and pile; MODELS="medium paper" adds the paper model) on 1, 2, 4, ...
# P processes of one thread (P = the cores present, RANKS to choose), and one
# process of P threads beside them. Prints particle-steps/s, the efficiency
# against one process and against P threads, the share of the time in the
# halo updates (waits for the slowest process included) and in the
# decompositions, the load imbalance (max/mean owned particles), the halo
# (particles held for others per owned one, bytes sent per step), and checks
# that every run ends with the same state digest (the same bits).
#
# Projection (printed for 16, 64 and 256 processes): a step on P processes
# takes T1 (s + (1 - s)(1 + h_P) / P): each process steps its N/P particles
# and its halo of h_P N/P more (a halo particle costs about what an owned one
# does: its pairs are computed too), and s is the share that does not divide
# (the exchanges' latency, the decompositions' gather, the waits of an
# imbalance), solved from the speed-up S at the largest P measured, m:
# s = (1/S - (1 + h_m)/m) / (1 - (1 + h_m)/m). For boxes of N/P particles the
# halo grows as surface over volume: h_P = h_m (P / m)^(1/3). Both figures
# come from a 2-core machine when that is what ran it; run the script on a
# larger one (the device machine has 16 cores) for a measured curve.
# Rebuilds: a decomposition before every REBUILD_EVERY-th step (270: the
# paper run's rate, docs/dem_benchmarks.md), since a body at rest never rebuilds.
#
#   bench/mpi_scaling.sh [BUILD_DIR]     (default build; needs MPI: libopenmpi-dev openmpi-bin)
# Environment: MODELS (medium), RANKS ("1 2 4 ... up to the cores"), STEPS
# (medium 540, paper 270), REBUILD_EVERY (270), WARMUP (20), REPEAT (3: each
# configuration runs that often and the fastest counts), KEEP (a folder for
# the sections and logs).
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/.." && pwd)
BUILD=${1:-$ROOT/build}
MODELS=${MODELS:-medium}
CORES=$(nproc)
if [ -z "${RANKS:-}" ]; then
  RANKS=""; r=1
  while [ "$r" -le "$CORES" ]; do RANKS="$RANKS $r"; r=$((r * 2)); done
  [ $((r / 2)) -eq "$CORES" ] || RANKS="$RANKS $CORES"
fi
WARMUP=${WARMUP:-20}
REPEAT=${REPEAT:-3}
REBUILD_EVERY=${REBUILD_EVERY:-270}
WORK=${KEEP:-$(mktemp -d)}
mkdir -p "$WORK"
command -v mpiexec >/dev/null || { echo "mpi_scaling.sh: no mpiexec (apt-get install openmpi-bin libopenmpi-dev)" >&2; exit 2; }
[ -f "$BUILD/CMakeCache.txt" ] || cmake -S "$ROOT" -B "$BUILD" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$BUILD" --target dem_mpi_throughput coupler -j "$CORES" >/dev/null \
  || { echo "mpi_scaling.sh: dem_mpi_throughput did not build (is MPI installed? CMake reports it)" >&2; exit 2; }
"$BUILD/bin/coupler" expand "$ROOT/scenarios/open_pile_chalk.json" >"$WORK/paper_expanded.json"
/usr/bin/python3 "$ROOT/bench/real_workload_sections.py" "$WORK" "$WORK/paper_expanded.json"
# OpenMPI refuses root unless told twice (containers, CI).
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1

field() { sed -nE "s#.*$1.*#\\1#p" | head -n 1; }
for model in $MODELS; do
  [ "$model" = paper ] && steps=${STEPS:-270} || steps=${STEPS:-540}
  runs=()
  for p in $RANKS; do runs+=("$p 1"); done
  [ "$CORES" -gt 1 ] && runs+=("1 $CORES")
  declare -A rate=() line=()
  for run in "${runs[@]}"; do
    read -r p t <<<"$run"
    # One process of several threads must not be bound to one core (mpiexec's default for 2 processes or fewer).
    bind=(); [ "$t" -gt 1 ] && bind=(--bind-to none)
    for k in $(seq "$REPEAT"); do
      log=$WORK/${model}_p${p}_t${t}_$k.log
      OMP_NUM_THREADS=$t mpiexec -n "$p" "${bind[@]}" "$BUILD/bin/dem_mpi_throughput" --section "$WORK/$model.json" --threads "$t" \
        --warmup "$WARMUP" --steps "$steps" --rebuild-every "$REBUILD_EVERY" >"$log" 2>&1 \
        || { echo "mpi_scaling.sh: $model on $p process(es) of $t thread(s) failed (log $log):" >&2; tail -n 5 "$log" >&2; exit 1; }
      l=$(grep "^ranks " "$log")
      r=$(echo "$l" | field ": ([0-9.eE+-]+) particle-steps.*")
      echo "$model $l"
      # The fastest of the repeats: the one least disturbed by whatever else the machine ran.
      if [ -z "${rate[$p $t]:-}" ] || awk -v a="$r" -v b="${rate[$p $t]}" 'BEGIN{exit !(a > b)}'; then
        rate[$p $t]=$r
        line[$p $t]=$l
      fi
    done
  done
  printf "\n%-8s %6s %8s %16s %11s %13s %7s %7s %9s %12s %14s\n" model ranks threads particle-steps/s efficiency vs-threads halo% decomp% imbalance halo/owned bytes/step
  digests=()
  for run in "${runs[@]}"; do
    read -r p t <<<"$run"
    l=${line[$p $t]}
    r=${rate[$p $t]}
    eff=$(awk -v r="$r" -v one="${rate[1 1]}" -v n=$((p * t)) 'BEGIN{printf "%.3f", r / (one * n)}')
    vs=$(awk -v r="$r" -v th="${rate[1 $CORES]:-0}" -v p="$p" -v c="$CORES" 'BEGIN{print (p == c && th > 0) ? sprintf("%.3f", r / th) : "-"}')
    halo=$(echo "$l" | field 'halo share ([0-9.eE+-]+),.*')
    decomp=$(echo "$l" | field 'decomposition share ([0-9.eE+-]+),.*')
    imbalance=$(echo "$l" | field 'imbalance ([0-9.eE+-]+),.*')
    per=$(echo "$l" | field '\(([0-9.eE+-]+) per owned\).*')
    bytes=$(echo "$l" | field ', ([0-9.eE+-]+) bytes per step.*')
    digests+=("$(echo "$l" | field 'state digest ([0-9a-f]+).*')")
    printf "%-8s %6s %8s %16.4g %11s %13s %7.1f %7.1f %9.3f %12.3f %14.4g\n" "$model" "$p" "$t" "$r" "$eff" "$vs" \
      "$(awk -v x="$halo" 'BEGIN{print 100 * x}')" "$(awk -v x="$decomp" 'BEGIN{print 100 * x}')" "$imbalance" "$per" "$bytes"
  done
  if [ "$(printf '%s\n' "${digests[@]}" | sort -u | wc -l)" -eq 1 ]; then
    echo "state digests: all ${#digests[@]} runs end with the same bits (${digests[0]})"
  else
    echo "state digests DIFFER between the runs: ${digests[*]}" >&2
    exit 1
  fi
  # Projection from the largest process count measured (see the header).
  last=$(echo "$RANKS" | awk '{print $NF}')
  if [ "$last" -gt 1 ]; then
    l=${line[$last 1]}
    per=$(echo "$l" | field '\(([0-9.eE+-]+) per owned\).*')
    awk -v one="${rate[1 1]}" -v r="${rate[$last 1]}" -v m="$last" -v h="$per" 'BEGIN{
      S = r / one; a = (1 + h) / m; s = (1 / S - a) / (1 - a); if (s < 0) s = 0;
      if (s > 1) { s = 1; print "  (no speed-up at all: was the machine busy with other work? the projection means nothing)" }
      printf "projection (serial share s = %.4f from %d processes, halo %.3f per owned there):\n", s, m, h;
      n = split("16 64 256", P, " ");
      for (k = 1; k <= n; ++k) { hp = h * (P[k] / m) ^ (1 / 3); sp = 1 / (s + (1 - s) * (1 + hp) / P[k]);
        printf "  %4d processes: speed-up %.1f, efficiency %.2f (halo %.2f per owned)\n", P[k], sp, sp / P[k], hp }
    }'
  fi
done
