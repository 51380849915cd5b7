#!/usr/bin/env bash
# supermodal against Bullet: the pile (bench/peer_pile.cpp) and the stacks (bench/stack_bench.cpp), both
# engines in one run on one thread, Release. Appends the pile on the penalty solver to
# docs/bench/peer_pile.csv and on the soft solver (the engine's default) to docs/bench/peer_pile_soft.csv;
# writes the penalty solver's stacks to docs/bench/stack.csv and docs/bench/stack.png. Bullet (libbullet-dev) is installed for these benchmarks only; the engine never
# links it. Not part of CI: speed is measured here, never asserted.
# Usage: scripts/bench_peer.sh [N [substeps]]   (pile bodies, default 1000; supermodal substeps, default 1)
set -euo pipefail
cd "$(dirname "$0")/.."

./scripts/deps.sh libbullet-dev
build=${SUPERMODAL_BENCH_BUILD_DIR:-build-bench}
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DSUPERMODAL_TESTS=OFF -DSUPERMODAL_BENCH=ON >/dev/null
cmake --build "$build" -j "$(nproc)" --target peer_pile stack_bench

mkdir -p docs/bench
"$build/bench/peer_pile" "${1:-1000}" "${2:-1}" --solver penalty --csv docs/bench/peer_pile.csv
"$build/bench/peer_pile" "${1:-1000}" "${2:-1}" --csv docs/bench/peer_pile_soft.csv
"$build/bench/stack_bench" --solver penalty --csv docs/bench/stack.csv
python3 bench/stack_report.py docs/bench/stack.csv
