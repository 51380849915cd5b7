#!/usr/bin/env bash
# Fuzzes the scene loader with libFuzzer (clang from Debian) for SECONDS (default 60), with the seed
# corpus (tests/fuzz/corpus, samples/) and the format's dictionary. New crashes land in
# build-fuzz/crashes/; turn each into a regression test in tests/scene/loader_test.cpp.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-60}

./scripts/deps.sh
need=()
command -v clang++ >/dev/null 2>&1 || need+=(clang)
ls /usr/lib/llvm-*/lib/clang/*/lib/linux/libclang_rt.fuzzer-x86_64.a >/dev/null 2>&1 || need+=(libclang-rt-14-dev)
if [ ${#need[@]} -gt 0 ]; then
  sudo_cmd=(); [ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
  "${sudo_cmd[@]}" apt-get update -qq
  DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${need[@]}"
fi
build=${SUPERMODAL_FUZZ_BUILD_DIR:-build-fuzz}
CXX=clang++ cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DSUPERMODAL_FUZZ=ON \
  -DSUPERMODAL_TESTS=OFF -DSUPERMODAL_BENCH=OFF >/dev/null
cmake --build "$build" -j "$(nproc)" --target scene_fuzz
mkdir -p "$build/corpus" "$build/crashes"
cp -n tests/fuzz/corpus/*.json tests/fuzz/regressions/*.json samples/*.json "$build/corpus/" 2>/dev/null || true
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
set +e
"$build/tests/fuzz/scene_fuzz" "$build/corpus" -dict=tests/fuzz/scene.dict -max_total_time="$seconds" \
  -timeout=10 -rss_limit_mb=2048 -max_len=65536 -artifact_prefix="$build/crashes/" -print_final_stats=1 \
  >"$build/fuzz.log" 2>&1
status=$?
set -e
grep -E "^(#[0-9]+.*DONE|stat::number_of_executed_units|stat::peak_rss|==[0-9]+==ERROR|SUMMARY)" "$build/fuzz.log" || true
if [ "$status" -ne 0 ]; then
  echo "fuzz: libFuzzer exited $status; see $build/fuzz.log and $build/crashes/" >&2
  exit "$status"
fi
