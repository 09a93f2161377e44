#!/usr/bin/env bash
# Regenerates docs/verification.md: builds fdm_verification and runs every FDM
# verification problem (fdm-physics.md §2) on its finer ("slow") mesh, plus the
# mesh-refinement study, writing the markdown table. Takes ~15 min on one core.
#
#   tools/fdm_verification_table.sh [build-dir]      (default: build)
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="${1:-build}"
cd "$root"
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$build" --target fdm_verification -j"$(nproc)"
"$build/bin/fdm_verification" --level slow --refinement --write docs/verification.md
