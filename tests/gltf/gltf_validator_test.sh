#!/usr/bin/env bash
# gltf_validator_test.sh CLI SOURCE VALIDATOR_DIR OUT: exports GLBs with the CLI into OUT and checks
# each with the Khronos glTF validator installed in VALIDATOR_DIR (scripts/gltf_validator.sh):
# zero errors and zero warnings. Exit 0 when all pass, 1 otherwise (missing tools included).
set -euo pipefail
cli=$1 src=$2 validator=$3 out=$4

if ! command -v node >/dev/null 2>&1; then
  echo "FAIL: node is not installed (scripts/deps.sh installs nodejs and npm)" >&2
  exit 1
fi
if [ ! -f "$validator/node_modules/gltf-validator/package.json" ]; then
  echo "FAIL: the glTF validator is not installed in $validator: run scripts/gltf_validator.sh $(dirname "$validator")" >&2
  exit 1
fi
rm -rf "$out"
mkdir -p "$out"
# Modal bodies with morph targets, and rigid bodies only.
"$cli" export "$src/samples/ball_on_board.json" --seconds 0.1 --out "$out/ball_on_board.glb"
"$cli" export "$src/samples/ball_on_board.json" --seconds 0.1 --no-morph --out "$out/ball_on_board_rigid.glb"
"$cli" export "$src/samples/chair_with_dummy.json" --seconds 0.05 --out "$out/chair_with_dummy.glb"
# An artist's mesh with texture coordinates and two materials, one with an image.
"$cli" fit "$src/samples/meshes/crate.obj" --scene "$out/crate.json" --attach
"$cli" export "$out/crate.json" --seconds 0.05 --out "$out/crate.glb"
NODE_PATH="$validator/node_modules" node "$src/tools/gltf-validator/validate.mjs" "$out"/*.glb
