#!/usr/bin/env bash
# Builds the engine and the threaded tests (the broadphase on threads, the contact thread pool's hash,
# partition and event tests, the constraint islands, the chair and pile samples on 1 and 2 threads)
# with ThreadSanitizer in build-tsan/ and runs them.
# Called by .ci/run after scripts/sanitize.sh (determinism across threads).
set -euo pipefail
cd "$(dirname "$0")/.."

./scripts/deps.sh clang libclang-rt-14-dev
build=${SUPERMODAL_TSAN_BUILD_DIR:-build-tsan}
# Only the engine and supermodal_thread_tests are built; renderer, editor and benchmarks are off.
CC=clang CXX=clang++ cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -gline-tables-only" -DSUPERMODAL_TSAN=ON -DSUPERMODAL_WERROR=ON \
  -DSUPERMODAL_TESTS=ON -DSUPERMODAL_BENCH=OFF -DSUPERMODAL_RENDER=OFF -DSUPERMODAL_EDITOR=OFF >/dev/null
cmake --build "$build" -j "$(nproc)" --target supermodal_thread_tests
# Any report fails the run: halt_on_error makes the first race exit non-zero.
export TSAN_OPTIONS=halt_on_error=1:second_deadlock_stack=1
# The modal bases' factorization runs on the calling thread, but CHOLMOD (which orders it) is built with
# OpenMP: should a loop of it run on OpenMP threads, libgomp is not built
# with ThreadSanitizer, so its barriers are invisible to it and every such loop reads as a race. A limit
# of one OpenMP thread (CHOLMOD asks for its count per loop, so OMP_NUM_THREADS alone does not do) keeps
# those loops on the calling thread; the engine's own threads are what is tested.
export OMP_THREAD_LIMIT=1
"$build/tests/supermodal_thread_tests" --gtest_brief=1
