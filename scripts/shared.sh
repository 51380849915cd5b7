#!/usr/bin/env bash
# The shared libraries (SUPERMODAL_SHARED=ON, docs/libraries.md) in build-shared/: builds the four
# libraries, the command line and the Blender zip (all of which install), then runs the Install.*
# tests (each sample host built against the installed shared package and run; physics_only's link
# checked for assimp, JSON and GL) and Api.* (every public declaration marked SM_API). Called by
# .ci/run after scripts/sanitize.sh.
cd "$(dirname "$0")/.."

./scripts/deps.sh clang
build=${SUPERMODAL_SHARED_BUILD_DIR:-build-shared}
# What is checked is what the libraries export and link, not their speed: clang at -O0 without debug
# info, no unit tests, benchmarks or editor (test.sh covers those on the static libraries).
CC=clang CXX=clang++ cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Debug \
  -DCMAKE_CXX_FLAGS_DEBUG="-O0" -DCMAKE_C_FLAGS_DEBUG="-O0" -DSUPERMODAL_SHARED=ON \
  -DSUPERMODAL_WERROR=ON -DSUPERMODAL_TESTS=ON -DSUPERMODAL_BENCH=OFF -DSUPERMODAL_EDITOR=OFF \
  -DSUPERMODAL_PYTHON=OFF >/dev/null
cmake --build "$build" -j "$(nproc)" --target supermodal supermodal_c supermodal_blender_zip
ctest --test-dir "$build" --output-on-failure -j "$(nproc)" --timeout 600 -R '^(Install|Api)\.'
