#!/usr/bin/env bash
# The README's demo command: install what is missing, build Release, run the default sample headless
# and write its summary and trace into out/. Idempotent.
set -euo pipefail
cd "$(dirname "$0")/.."

./scripts/deps.sh
build=${SUPERMODAL_DEMO_BUILD_DIR:-build-release}
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DSUPERMODAL_TESTS=OFF -DSUPERMODAL_BENCH=OFF >/dev/null
cmake --build "$build" -j "$(nproc)" --target supermodal
mkdir -p out
scene=${1:-samples/chair_with_dummy.json}
"$build/tools/supermodal" run "$scene" --json out/summary.json --csv out/trace.csv
echo "demo: wrote out/summary.json and out/trace.csv from $scene"
