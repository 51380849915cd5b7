#!/usr/bin/env bash
# Fuzzes with libFuzzer (clang from Debian) for SECONDS (default 60). TARGET (default scene_fuzz): the
# scene loader, with the seed corpus (tests/fuzz/corpus, tests/fuzz/regressions, samples/) and the
# format's dictionary; mesh_fuzz: mesh import (tests/fuzz/mesh_corpus, each seed behind the byte that
# picks its extension); or cli_fuzz: the command line's arguments (tests/fuzz/cli_corpus, cli.dict).
# New crashes land in build-fuzz/crashes/; a fixed one goes to tests/fuzz/regressions/ (replayed by
# ctest, FuzzReplay.*), tests/fuzz/mesh_regressions/ or tests/fuzz/cli_regressions/.
# SUPERMODAL_FUZZ_RUNS=N also stops the run after N inputs (whichever of the two limits comes first).
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-60}
target=${2:-scene_fuzz}
case "$target" in scene_fuzz | mesh_fuzz | cli_fuzz) ;; *) echo "fuzz: unknown target '$target' (scene_fuzz, mesh_fuzz, cli_fuzz)" >&2; exit 2 ;; esac

./scripts/deps.sh clang libclang-rt-14-dev # libFuzzer and the sanitizer runtimes
build=${SUPERMODAL_FUZZ_BUILD_DIR:-build-fuzz}
# Line tables are all a report's stack needs; full debug info made the build ~30% slower.
CXX=clang++ cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DSUPERMODAL_FUZZ=ON \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O2 -gline-tables-only -DNDEBUG" \
  -DSUPERMODAL_TESTS=OFF -DSUPERMODAL_BENCH=OFF >/dev/null
cmake --build "$build" -j "$(nproc)" --target "$target"
mkdir -p "$build/crashes"
if [ "$target" = scene_fuzz ]; then
  corpus=$build/corpus log=$build/fuzz.log extra=(-dict=tests/fuzz/scene.dict)
  mkdir -p "$corpus"
  cp -n tests/fuzz/corpus/*.json tests/fuzz/regressions/*.json samples/*.json "$corpus/" 2>/dev/null || true
elif [ "$target" = cli_fuzz ]; then
  # stdout closed: the commands print their summaries there.
  corpus=$build/cli_corpus log=$build/cli_fuzz.log extra=(-dict=tests/fuzz/cli.dict -close_fd_mask=1)
  mkdir -p "$corpus"
  cp -n tests/fuzz/cli_corpus/* tests/fuzz/cli_regressions/* "$corpus/" 2>/dev/null || true
else
  corpus=$build/mesh_corpus log=$build/mesh_fuzz.log extra=()
  mkdir -p "$corpus"
  i=0
  for ext in obj stl ply gltf glb fbx; do # the harness's k_extensions order
    for seed in tests/fuzz/mesh_corpus/*."$ext" tests/fuzz/mesh_regressions/*."$ext"; do
      [ -e "$seed" ] || continue
      { printf "\\$(printf %03o "$i")"; cat "$seed"; } >"$corpus/seed_$(basename "$seed")"
    done
    i=$((i + 1))
  done
fi
# Debian's assimp 5.2 leaks on some malformed files (its STL reader: upstream assimp/assimp#5946,
# fixed after 5.2), which we cannot mend: mesh_fuzz runs without leak checks; ASan and UBSan stay on.
leaks=1
[ "$target" = mesh_fuzz ] && leaks=0
export ASAN_OPTIONS=detect_leaks=$leaks:abort_on_error=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
set +e
[ -n "${SUPERMODAL_FUZZ_RUNS:-}" ] && extra+=(-runs="$SUPERMODAL_FUZZ_RUNS")
"$build/tests/fuzz/$target" "$corpus" "${extra[@]}" -max_total_time="$seconds" \
  -timeout=10 -rss_limit_mb=2048 -max_len=65536 -artifact_prefix="$build/crashes/" -print_final_stats=1 \
  >"$log" 2>&1
status=$?
set -e
grep -E "^(#[0-9]+.*DONE|stat::number_of_executed_units|stat::peak_rss|==[0-9]+==ERROR|SUMMARY)" "$log" || true
if [ "$status" -ne 0 ]; then
  echo "fuzz: libFuzzer exited $status; see $log and $build/crashes/" >&2
  exit "$status"
fi
