#!/usr/bin/env bash
# Runs the Google Benchmark programs in Release and writes docs/bench/<machine>/<bench>.{csv,md,png}
# with date, commit, CPU and thread count. Not part of CI: speed is measured here, never asserted.
# Usage: scripts/bench.sh [bench_name ...]   (default: every bench/*_bench.cpp)
set -euo pipefail
cd "$(dirname "$0")/.."

./scripts/deps.sh
if ! dpkg -s gnuplot-nox >/dev/null 2>&1 && ! command -v gnuplot >/dev/null 2>&1; then
  # gnuplot draws the plots; only this script needs it.
  if [ "$(id -u)" -eq 0 ]; then
    apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq gnuplot-nox >/dev/null
  else
    echo "bench: gnuplot missing (apt-get install gnuplot-nox); writing CSV and markdown only" >&2
  fi
fi
build=${SUPERMODAL_BENCH_BUILD_DIR:-build-bench}
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DSUPERMODAL_TESTS=OFF -DSUPERMODAL_BENCH=ON >/dev/null
cmake --build "$build" -j "$(nproc)"

machine=${SUPERMODAL_MACHINE:-$(hostname -s 2>/dev/null || echo unknown)}
out=docs/bench/$machine
mkdir -p "$out"
names=("$@")
if [ ${#names[@]} -eq 0 ]; then
  for f in bench/*_bench.cpp; do names+=("$(basename "$f" .cpp)"); done
fi
for name in "${names[@]}"; do
  echo "bench: $name"
  "$build/bench/$name" --benchmark_format=json --benchmark_repetitions="${SUPERMODAL_BENCH_REPS:-5}" \
    --benchmark_report_aggregates_only=true --benchmark_min_time="${SUPERMODAL_BENCH_MIN_TIME:-0.2}" \
    >"$out/$name.json"
  python3 bench/report.py "$out/$name.json" "$out/$name" "$(git rev-parse --short HEAD)"
done
