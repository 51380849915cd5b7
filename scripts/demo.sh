#!/usr/bin/env bash
# The README's demo command: install what is missing, build Release, run the default sample headless
# and write its summary, trace and rendered frames (PNG, plus out/demo.mp4 when ffmpeg is installed)
# into out/. Idempotent.
set -euo pipefail
cd "$(dirname "$0")/.."

./scripts/deps.sh
build=${SUPERMODAL_DEMO_BUILD_DIR:-build-release}
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DSUPERMODAL_TESTS=OFF -DSUPERMODAL_BENCH=OFF >/dev/null
cmake --build "$build" -j "$(nproc)" --target supermodal
mkdir -p out/frames
rm -f out/frames/frame_*.png
scene=${1:-samples/chair_with_dummy.json}
# 640x360 every 40 steps: 25 frames per simulated second at the sample's 1 ms step.
capture=(--frames out/frames --every "${SUPERMODAL_DEMO_EVERY:-40}" --size 640x360)
video=""
if command -v ffmpeg >/dev/null 2>&1; then
  capture+=(--video out/demo.mp4)
  video=", out/demo.mp4"
else
  echo "demo: ffmpeg not found, writing PNG frames only (apt-get install ffmpeg for out/demo.mp4)"
fi
"$build/tools/supermodal" run "$scene" --json out/summary.json --csv out/trace.csv "${capture[@]}"
frames=$(find out/frames -name 'frame_*.png' | wc -l)
echo "demo: wrote out/summary.json, out/trace.csv, $frames frames in out/frames/$video from $scene"
