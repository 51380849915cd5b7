#!/usr/bin/env bash
# Installs the Khronos glTF validator that tests/gltf runs: `npm ci` of tools/gltf-validator's
# package-lock.json into BUILD/gltf-validator/ (BUILD: the first argument, else $SUPERMODAL_BUILD_DIR,
# else build). Nothing is fetched when that lock file is already installed there.
set -euo pipefail
cd "$(dirname "$0")/.."

build=${1:-${SUPERMODAL_BUILD_DIR:-build}}
dest="$build/gltf-validator"
if ! command -v node >/dev/null 2>&1 || ! command -v npm >/dev/null 2>&1; then
  echo "gltf_validator: node and npm are needed (scripts/deps.sh installs them)" >&2
  exit 1
fi
if cmp -s tools/gltf-validator/package-lock.json "$dest/package-lock.json" &&
  [ -f "$dest/node_modules/gltf-validator/package.json" ]; then
  exit 0
fi
mkdir -p "$dest"
cp tools/gltf-validator/package.json tools/gltf-validator/package-lock.json "$dest/"
echo "gltf_validator: npm ci in $dest"
(cd "$dest" && npm ci --ignore-scripts --no-audit --no-fund --loglevel=error)
