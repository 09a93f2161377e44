#!/bin/bash
# The real workload's speed: the DEM of the paper-resolution open pile
# (scenarios/open_pile_chalk.json, packing p1: damage_bond chalk in three
# S zones, 549 635 spheres, the pile's 288 facets, local damping 0.7) and a
# medium graded body cut from the same scenario (about 50 000 spheres, runs
# in a minute or two), each built as dem_server builds it and stepped at rest
# from its generated state, at 1 and 2 threads; beside them, in the same run,
# the proxy (the peer packing bonded by linear_pbond, and by damage_bond).
# Prints particle-steps/s, the ratio proxy/real per particle-step, the
# 2-thread speed-up, the Amdahl serial fraction it implies, pairs and bonds per
# particle, memory per particle, whether the thread counts gave the same bits,
# the paper model's projected run on this machine (docs/open_pile.md §5), and
# the time of one rebuild of its neighbour lists (dem_throughput --rebuild-every).
#
#   bench/paper_model.sh [BUILD_DIR]           (default build; builds dem_throughput and coupler)
# Environment: MODELS ("medium paper"), THREADS ("1 2"), PAPER_STEPS (200),
# MEDIUM_STEPS (1000), WARMUP (20: the first steps after the build rebuild the
# lists and install nothing new), PEERS_DIR (the peer packing, as
# bench/dem_peers.sh), RUN_STEPS (the paper run's DEM steps; by default its
# 20 mm at 0.5 m/s in the built model's time step, plus ramp and
# equilibrium: docs/open_pile.md §5), KEEP (a folder to keep the sections and logs in),
# DEM_THROUGHPUT (another build's dem_throughput, to compare two versions on
# the same sections; its state digests must then equal this build's), PROFILE
# (1 where perf is installed: a profile of each model's timed steps at one
# thread, which gives the serial fraction of a step and its Amdahl bound on
# 16 and 64 cores, bench/serial_fraction.py; 0 skips it).
# Each model and thread count runs in a process of its own, so the memory
# figure is that model's alone. Not part of the default test run (./vc bench).
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/.." && pwd)
BUILD=${1:-$ROOT/build}
PEERS=${PEERS_DIR:-$ROOT/../shared/bench/peers}
MODELS=${MODELS:-medium paper}
THREADS=${THREADS:-1 2}
PAPER_STEPS=${PAPER_STEPS:-200}; MEDIUM_STEPS=${MEDIUM_STEPS:-1000}; WARMUP=${WARMUP:-20}
RUN_STEPS=${RUN_STEPS:-}
WORK=${KEEP:-$(mktemp -d)}
mkdir -p "$WORK"
PROXY_DATA=$PEERS/data/pack_12k.data
PROXY_LARGE_DATA=$PEERS/data/pack_50k.data

[ -f "$BUILD/CMakeCache.txt" ] || cmake -S "$ROOT" -B "$BUILD" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$BUILD" --target dem_throughput coupler -j "$(nproc)" >/dev/null
EXE=${DEM_THROUGHPUT:-$BUILD/bin/dem_throughput}

# 1. The DEM sections as the coupler sends them (includes resolved, g·N added).
"$BUILD/bin/coupler" expand "$ROOT/scenarios/open_pile_chalk.json" >"$WORK/paper_expanded.json"
/usr/bin/python3 "$ROOT/bench/real_workload_sections.py" "$WORK" "$WORK/paper_expanded.json"

# "#" delimits: the patterns hold "/" (particle-steps/s).
field() { sed -nE "s#.*$1.*#\\1#p" | head -n 1; }
declare -A rate digest
report=$WORK/report.txt
: >"$report"
for model in $MODELS; do
  [ "$model" = paper ] && steps=$PAPER_STEPS || steps=$MEDIUM_STEPS
  for t in $THREADS; do
    log=$WORK/${model}_t$t.log
    "$EXE" --section "$WORK/$model.json" --threads "$t" --warmup "$WARMUP" --steps "$steps" --digest >"$log" 2>&1 \
      || { echo "paper_model.sh: the $model model at $t thread(s) failed (log $log):" >&2; tail -n 5 "$log" >&2; exit 1; }
    line=$(grep "^threads " "$log")
    rate[$model $t]=$(echo "$line" | field 'threads [0-9]+: ([0-9.eE+-]+) particle-steps.*')
    digest[$model $t]=$(echo "$line" | field '.*state digest ([0-9a-f]+).*')
    echo "$model $line" >>"$report"
  done
done

# 2. The proxy in the same run: the peer packing (12 544 spheres) with every
#    pair within 10 um bonded, by linear_pbond (what the kernels were tuned
#    on) and by damage_bond, with the studies' local damping.
if [ -f "$PROXY_DATA" ]; then
  for law in linear_pbond damage_bond; do
    log=$WORK/proxy_$law.log
    "$EXE" --data "$PROXY_DATA" --law "$law" --local-damping 0.7 --threads "$THREADS" --warmup 1000 --steps 2000 >"$log" 2>&1 \
      || { echo "paper_model.sh: the proxy ($law) failed (log $log)" >&2; exit 1; }
    for t in $THREADS; do rate[proxy_$law $t]=$(grep "^threads $t:" "$log" | field 'threads [0-9]+: ([0-9.eE+-]+) particle-steps.*'); done
    grep "^threads " "$log" | sed "s/^/proxy $law /" >>"$report"
  done
  # The same proxy four times as large (50 176 spheres, about 95 MB: out of
  # the last-level cache like the real models), to tell the cost of size from
  # that of the workload.
  if [ -f "$PROXY_LARGE_DATA" ]; then
    log=$WORK/proxy50k_linear_pbond.log
    "$EXE" --data "$PROXY_LARGE_DATA" --law linear_pbond --local-damping 0.7 --threads "$THREADS" --warmup 1000 --steps 1000 >"$log" 2>&1 \
      || { echo "paper_model.sh: the 50k proxy failed (log $log)" >&2; exit 1; }
    for t in $THREADS; do rate[proxy50k_linear_pbond $t]=$(grep "^threads $t:" "$log" | field 'threads [0-9]+: ([0-9.eE+-]+) particle-steps.*'); done
    grep "^threads " "$log" | sed "s/^/proxy50k linear_pbond /" >>"$report"
  fi
else
  echo "paper_model.sh: no peer packing at $PROXY_DATA (set PEERS_DIR); the proxy columns are left out" >&2
fi

ratio() { awk -v a="$1" -v b="$2" 'BEGIN{print (a > 0 && b > 0) ? a / b : "nan"}'; }
printf "\n%-28s %8s %16s %14s %10s\n" model threads particle-steps/s proxy/real speed-up
for model in $MODELS proxy_linear_pbond proxy_damage_bond proxy50k_linear_pbond; do
  for t in $THREADS; do
    r=${rate[$model $t]:-}
    [ -n "$r" ] || continue
    one=${rate[$model 1]:-0}
    printf "%-28s %8s %16.3g %14s %10s\n" "$model" "$t" "$r" "$(ratio "${rate[proxy_linear_pbond $t]:-0}" "$r")" "$(ratio "$r" "$one")"
  done
done
# Per bond-step: the real models hold more bonds per particle than the proxy
# (a PCRM body bonds every pair within its bond gap), and a bond costs far
# more than an idle pair; the rate per bond, against the proxy as large as
# they are, is the cost of the code on the same work.
bonds_per_particle() {
  case $1 in
    proxy*) grep -m 1 "^${1%%_*} linear_pbond threads" "$report" | sed -nE 's/.* steps of ([0-9]+) particles.* bonds intact ([0-9]+).*/\2 \1/p' | awk '{print $1 / $2}' ;;
    *) grep -m 1 "^$1 threads" "$report" | field '.*first step [0-9.eE+-]+ pair candidates and ([0-9.eE+-]+) bonds per particle.*' ;;
  esac
}
if [ -n "${rate[proxy50k_linear_pbond 1]:-}${rate[proxy50k_linear_pbond 2]:-}" ]; then
  printf "\n%-28s %8s %16s %14s %22s\n" model threads bonds/particle bond-steps/s "proxy50k/real per bond"
  for model in $MODELS proxy_linear_pbond proxy50k_linear_pbond; do
    b=$(bonds_per_particle "$model")
    for t in $THREADS; do
      r=${rate[$model $t]:-}
      [ -n "$r" ] && [ -n "$b" ] || continue
      per_bond=$(awk -v r="$r" -v b="$b" 'BEGIN{print r * b}')
      large=$(awk -v r="${rate[proxy50k_linear_pbond $t]:-0}" -v b="$(bonds_per_particle proxy50k_linear_pbond)" 'BEGIN{print r * b}')
      printf "%-28s %8s %16.3g %14.3g %22s\n" "$model" "$t" "$b" "$per_bond" "$(ratio "$large" "$per_bond")"
    done
  done
fi
printf "\n%-28s %s\n" "damage_bond/linear_pbond" "proxy, per particle-step: $(for t in $THREADS; do printf "%s thread(s) %s  " "$t" "$(ratio "${rate[proxy_damage_bond $t]:-0}" "${rate[proxy_linear_pbond $t]:-0}")"; done)"
for model in $MODELS; do
  s2=$(ratio "${rate[$model 2]:-0}" "${rate[$model 1]:-0}")
  # Amdahl: t2/t1 = f + (1 - f)/2, so f = 2 t2/t1 - 1 = 2/speed-up - 1.
  printf "%-28s %s\n" "$model serial fraction" "$(awk -v s="$s2" 'BEGIN{print (s > 0) ? 2 / s - 1 : "nan"}') (Amdahl, from the 1- and 2-thread rates)"
  same=yes
  for t in $THREADS; do [ "${digest[$model $t]}" = "${digest[$model 1]}" ] || same=no; done
  printf "%-28s %s\n" "$model same bits" "$same (state digests: $(for t in $THREADS; do printf "%s " "${digest[$model $t]}"; done))"
done
if [[ " $MODELS " == *" paper "* ]]; then
  n=$(grep "^paper threads" "$report" | head -n 1 | sed -nE 's/.* steps of ([0-9]+) particles.*/\1/p')
  dt=$(grep "^paper threads" "$report" | head -n 1 | sed -nE 's/.* dt ([0-9.eE+-]+) s.*/\1/p')
  # The run's steps: travel / speed / dt of the scenario's time step (its
  # timestep.stiffness_bound), plus the ramp and the equilibrium (run.txt).
  read -r travel speed extra <"$WORK/run.txt"
  [ -n "$RUN_STEPS" ] || RUN_STEPS=$(awk -v l="$travel" -v v="$speed" -v dt="$dt" -v e="$extra" 'BEGIN{printf "%.4g", l / v / dt + e}')
  printf "%-28s %s\n" "paper run steps" "$RUN_STEPS ($travel m at $speed m/s in steps of $dt s, plus $extra steps of ramp and equilibrium)"
  for t in $THREADS; do
    printf "%-28s %s\n" "paper run, $t thread(s)" "$(awk -v n="$n" -v s="$RUN_STEPS" -v r="${rate[paper $t]}" 'BEGIN{printf "%.1f days (%g steps x %d spheres at %.3g particle-steps/s)", n * s / r / 86400, s, n, r}')"
  done
  # 3. The neighbour-list rebuild: serial work a run pays whenever a particle
  #    has moved half the skin (in the coupled paper model after generation,
  #    about every 270 steps). 40 steps with a rebuild before every 10th, less
  #    the same steps at the rate without rebuilds.
  t=${THREADS##* }
  log=$WORK/paper_rebuild_t$t.log
  "$EXE" --section "$WORK/paper.json" --threads "$t" --warmup "$WARMUP" --steps 40 --rebuild-every 10 >"$log" 2>&1 \
    || { echo "paper_model.sh: the rebuild timing failed (log $log)" >&2; exit 1; }
  secs=$(grep "^threads " "$log" | field '.*particle-steps/s \(([0-9.eE+-]+) s for.*')
  printf "%-28s %s\n" "paper rebuild, $t thread(s)" "$(awk -v s="$secs" -v n="$n" -v r="${rate[paper $t]}" 'BEGIN{printf "%.2f s per rebuild of the lists (4 rebuilds in %.1f s of 40 steps, less 40 steps at %.3g particle-steps/s)", (s - 40 * n / r) / 4, s, r}')"
  grep "^threads " "$log" | sed "s/^/paper rebuild-every-10 /" >>"$report"
fi
# 4. The serial fraction of a step: a profile of the timed steps alone (perf
#    enabled through its control FIFOs, so not the model's build) at one
#    thread; samples outside the OpenMP regions are the serial work.
PROFILE=${PROFILE:-$(command -v perf >/dev/null && echo 1 || echo 0)}
if [ "$PROFILE" = 1 ]; then
  for model in $MODELS; do
    [ "$model" = paper ] && steps=$PAPER_STEPS || steps=$MEDIUM_STEPS
    rm -f "$WORK/perf.ctl" "$WORK/perf.ack"; mkfifo "$WORK/perf.ctl" "$WORK/perf.ack"
    log=$WORK/${model}_profile.log
    perf record -D -1 --control "fifo:$WORK/perf.ctl,$WORK/perf.ack" -e cpu-clock -F 250 --call-graph dwarf,16384 \
      -o "$WORK/${model}_perf.data" -- "$EXE" --section "$WORK/$model.json" --threads 1 --warmup "$WARMUP" --steps "$steps" \
      --perf-control "$WORK/perf.ctl,$WORK/perf.ack" >"$log" 2>&1 \
      || { echo "paper_model.sh: the profile of the $model model failed (log $log)" >&2; exit 1; }
    perf script --no-demangle -F comm,ip,sym -i "$WORK/${model}_perf.data" 2>/dev/null | /usr/bin/python3 "$ROOT/bench/serial_fraction.py" >"$WORK/${model}_serial.txt"
    printf "\n%s model, 1 thread, %s timed steps profiled:\n" "$model" "$steps"
    cat "$WORK/${model}_serial.txt"
  done
fi
printf "\nper run (pairs and bonds per particle, memory):\n"
cat "$report"
echo "(sections and logs: $WORK)"
