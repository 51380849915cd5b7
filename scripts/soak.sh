#!/usr/bin/env bash
# Soak (docs/reliability.md): runs the chair scene and the pile for an hour of simulated time each (Release),
# one CSV row per simulated minute, and plots resident memory and step time against simulated time
# into docs/soak/. Not part of CI (hours of wall time); results are recorded in docs/reliability.md.
# Usage: scripts/soak.sh [SIMULATED_SECONDS] [REPORT_EVERY_SECONDS]   (default 3600 60)
set -euo pipefail
cd "$(dirname "$0")/.."

seconds=${1:-3600}
every=${2:-60}
./scripts/deps.sh
build=${SUPERMODAL_BENCH_BUILD_DIR:-build-bench}
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DSUPERMODAL_TESTS=OFF -DSUPERMODAL_BENCH=ON >/dev/null
cmake --build "$build" -j "$(nproc)" --target soak

out=docs/soak
mkdir -p "$out"
for scene in pile chair_with_dummy; do
  echo "soak: $scene, ${seconds} s simulated" >&2
  "$build/bench/soak" "samples/$scene.json" "$seconds" "$every" >"$out/$scene.csv"
done

python3 - "$out" <<'PY'
import csv, sys
out = sys.argv[1]
for name in ("chair_with_dummy", "pile"):
    rows = list(csv.DictReader(open(f"{out}/{name}.csv")))
    rss = [int(r["rss_kib"]) for r in rows]
    cpu = [float(r["cpu_ms"]) for r in rows]
    print(f"{name}: {rows[-1]['steps']} steps, rss first/last/max {rss[0]}/{rss[-1]}/{max(rss)} KiB, "
          f"cpu ms/step first/last/max {cpu[0]:.3f}/{cpu[-1]:.3f}/{max(cpu):.3f}, "
          f"all finite {all(r['finite'] == '1' for r in rows)}")
PY

if command -v gnuplot >/dev/null 2>&1; then
  gnuplot <<GP
set terminal pngcairo size 900,420 noenhanced
set datafile separator ","
set key autotitle columnhead
set xlabel "simulated time [s]"
set output "$out/soak.png"
set multiplot layout 1,2
set ylabel "resident memory [KiB]"
set yrange [0:*]
plot "$out/chair_with_dummy.csv" using 1:7 with lines title "chair", "$out/pile.csv" using 1:7 with lines title "pile (100)"
set ylabel "CPU time per step [ms]"
plot "$out/chair_with_dummy.csv" using 1:6 with lines title "chair", "$out/pile.csv" using 1:6 with lines title "pile (100)"
unset multiplot
GP
fi
