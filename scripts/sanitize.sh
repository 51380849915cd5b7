#!/usr/bin/env bash
# Builds the unit tests with AddressSanitizer + UndefinedBehaviorSanitizer in build-asan/ and runs them.
# Called by .ci/run after scripts/test.sh.
set -euo pipefail
cd "$(dirname "$0")/.."

./scripts/deps.sh clang libclang-rt-14-dev
build=${SUPERMODAL_ASAN_BUILD_DIR:-build-asan}
# clang, where test.sh builds with g++: a second compiler's warnings and sanitizers, and it compiles
# this code about twice as fast as g++ with full debug info (the build was most of CI's time).
# Debug keeps the engine's asserts on; -O1 (what the ASan docs advise) runs the suite ~3x faster than
# -O0; line tables are all a report's stack needs.
CC=clang CXX=clang++ cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Debug \
  -DCMAKE_CXX_FLAGS_DEBUG="-gline-tables-only -O1" -DCMAKE_C_FLAGS_DEBUG="-gline-tables-only -O1" \
  -DSUPERMODAL_SANITIZE=ON -DSUPERMODAL_WERROR=ON \
  -DSUPERMODAL_TESTS=ON -DSUPERMODAL_BENCH=OFF >/dev/null
cmake --build "$build" -j "$(nproc)"
./scripts/gltf_validator.sh "$build" # tests/gltf checks the sanitized exporter's GLBs too
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1:strict_string_checks=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
# The install test rebuilds a host program outside the sanitized flags; it is covered by test.sh.
ctest --test-dir "$build" --output-on-failure -j "$(nproc)" --timeout 900 -E '^Install\.'
