#!/usr/bin/env bash
# Stability map (docs/stability.md): builds bench/stability_map (Release), sweeps every slice into
# docs/stability/stability_map.csv and draws the heat maps next to it (bench/stability_report.py, gnuplot);
# the markdown tables go to docs/stability/tables.md. About 30 s of CPU. Results: docs/stability.md.
# Usage: scripts/stability.sh [SLICE...]   (default: all slices)
set -euo pipefail
cd "$(dirname "$0")/.."

build=${SUPERMODAL_BENCH_BUILD_DIR:-build-bench}
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DSUPERMODAL_TESTS=OFF -DSUPERMODAL_BENCH=ON >/dev/null
cmake --build "$build" -j "$(nproc)" --target stability_map

out=docs/stability
mkdir -p "$out"
"$build/bench/stability_map" "$@" >"$out/stability_map.csv"
python3 bench/stability_report.py "$out/stability_map.csv" "$out" >"$out/tables.md"
echo "stability: $(($(wc -l <"$out/stability_map.csv") - 1)) cells -> $out" >&2
