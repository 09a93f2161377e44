#!/usr/bin/env bash
# The libFuzzer harnesses of fuzz/ (docs/fuzzing.md), run long:
# configures a clang build folder with DFC_FUZZ=ON (RelWithDebInfo, AddressSanitizer
# and UBSan), builds the two fuzzers and nothing of the solvers, then runs each
# for RUNS executions on its seed corpus (fuzz/corpus/protocol, fuzz/corpus/scenario: only read; new
# inputs go to BUILD/fuzz/bench-corpus/<name>, crash inputs to BUILD/fuzz/artifacts/).
# Prints per fuzzer the executions, executions per second, crashes and wall time;
# exits 1 on any crash, hang, out-of-memory or sanitizer report (its input and
# log are named), 2 on bad usage.
#
#   bench/fuzz.sh [--runs N] [--only protocol_codec|scenario] [--build DIR] [--jobs J]
#     --runs N     executions per fuzzer (default 1000000)
#     --only NAME  run one fuzzer
#     --build DIR  build folder (default build-fuzz in the repository)
#     --jobs J     parallel compile jobs (default: the number of cores)
# Needs clang and libclang-rt-dev (Debian: apt-get install clang libclang-rt-dev libomp-dev).
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
BUILD=$ROOT/build-fuzz
RUNS=1000000
JOBS=$(nproc)
FUZZERS=(protocol_codec scenario)

usage() { sed -n '2,/^set -euo/p' "${BASH_SOURCE[0]}" | sed '$d' | sed 's/^# \{0,1\}//'; }
while [ $# -gt 0 ]; do
  case $1 in
    --help|-h) usage; exit 0 ;;
    --runs) RUNS=${2:?--runs needs a number}; shift 2 ;;
    --only) FUZZERS=("${2:?--only needs protocol_codec or scenario}"); shift 2 ;;
    --build) BUILD=${2:?--build needs a folder}; shift 2 ;;
    --jobs) JOBS=${2:?--jobs needs a number}; shift 2 ;;
    *) echo "bench/fuzz.sh: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
done
case $RUNS in ''|*[!0-9]*) echo "bench/fuzz.sh: --runs expects a positive integer, got '$RUNS'" >&2; exit 2 ;; esac
for name in "${FUZZERS[@]}"; do
  case $name in protocol_codec|scenario) ;; *) echo "bench/fuzz.sh: no fuzzer '$name'; expected protocol_codec or scenario" >&2; exit 2 ;; esac
done
command -v clang++ > /dev/null || { echo "bench/fuzz.sh: clang++ not found (apt-get install clang libclang-rt-dev)" >&2; exit 2; }

echo "== configure and build $BUILD (clang, DFC_FUZZ=ON)"
start=$(date +%s)
mkdir -p "$BUILD"
CC=clang CXX=clang++ cmake -S "$ROOT" -B "$BUILD" -DDFC_FUZZ=ON -DCMAKE_BUILD_TYPE=RelWithDebInfo > "$BUILD/fuzz-configure.log" 2>&1 ||
  { cat "$BUILD/fuzz-configure.log" >&2; exit 1; }
cmake --build "$BUILD" --target dfc_fuzzers -j "$JOBS" > "$BUILD/fuzz-build.log" 2>&1 || { tail -40 "$BUILD/fuzz-build.log" >&2; exit 1; }
echo "   $(( $(date +%s) - start )) s"

failed=0
summary=()
for name in "${FUZZERS[@]}"; do
  corpus=$BUILD/fuzz/bench-corpus/$name
  artifacts=$BUILD/fuzz/artifacts
  log=$BUILD/fuzz/bench-$name.log
  seeds=$ROOT/fuzz/corpus/${name%_codec}  # protocol_codec reads fuzz/corpus/protocol
  mkdir -p "$corpus" "$artifacts"
  echo "== ${name}_fuzzer: $RUNS runs (log: $log)"
  before=$(find "$artifacts" -name "$name-*" | wc -l)
  t0=$(date +%s.%N)
  set +e
  # -timeout: an input that takes a minute is a hang and counts as a failure.
  "$BUILD/bin/${name}_fuzzer" -runs="$RUNS" -rss_limit_mb=2048 -timeout=60 -print_final_stats=1 \
    -artifact_prefix="$artifacts/$name-" "$corpus" "$seeds" > "$log" 2>&1
  status=$?
  set -e
  t1=$(date +%s.%N)
  wall=$(awk -v a="$t0" -v b="$t1" 'BEGIN { printf "%.0f", b - a }')
  executions=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  rate=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log" | tail -1)
  crashes=$(( $(find "$artifacts" -name "$name-*" | wc -l) - before ))
  reports=$(grep -cE 'ERROR: (AddressSanitizer|LeakSanitizer|libFuzzer)|runtime error:|broken promise' "$log" || true)
  line=$(printf '%-16s executions %-9s exec/s %-6s crashes %-3s sanitizer reports %-3s wall %s s' \
    "$name" "${executions:-?}" "${rate:-?}" "$crashes" "$reports" "$wall")
  echo "   $line"
  summary+=("$line")
  if [ "$status" -ne 0 ] || [ "$crashes" -ne 0 ] || [ "$reports" -ne 0 ]; then
    failed=1
    echo "   FAIL: exit status $status; the end of $log:" >&2
    tail -30 "$log" >&2
    find "$artifacts" -name "$name-*" -newer "$BUILD/fuzz-build.log" -printf '   input: %p\n' >&2
  fi
done

echo "== summary"
printf '%s\n' "${summary[@]}"
[ "$failed" -eq 0 ] && echo "OK: no crash, no sanitizer report" || { echo "FAIL: see the logs above" >&2; exit 1; }
