#!/usr/bin/env bash
# Installs the Debian packages the build needs, and only the missing ones (checked with dpkg -s).
# `apt-get update` runs only when something is missing. Works as root, or through sudo.
# Extra package names as arguments are checked the same way (the sanitizer and fuzz builds add clang).
set -euo pipefail

packages=(
  cmake ninja-build g++ pkg-config
  nlohmann-json3-dev   # scene files
  libcli11-dev         # the supermodal command line
  libeigen3-dev        # modal dynamics: sparse assembly, dense eigen solves
  libspectra-dev       # modal dynamics: shift-invert eigen solves for large lattices
  libsuitesparse-dev   # modal dynamics: CHOLMOD's ordering and supernodes for their sparse Cholesky
  libccd-dev           # contact: MPR penetration depth of convex pairs
  libassimp-dev        # io: mesh import (OBJ, PLY, STL, glTF/GLB, FBX)
  libgtest-dev         # tests
  python3 python3-jsonschema   # tests/schema: the scene schema against the loader
  pybind11-dev python3-dev    # python/: the module supermodal (SUPERMODAL_PYTHON)
  python3-numpy python3-pytest  # python/: its arrays, and tests/python
  python3-distributed  # python/: supermodal.sweep runs its grid on a Dask cluster (tests/python)
  libbenchmark-dev     # bench/
  gnuplot-nox          # `supermodal bench --out`: the speed/accuracy plot (PREFIX.png; skipped without it)
  libimgui-dev         # editor/: Dear ImGui (core library and backend sources)
  libglfw3-dev         # editor/: the window of the interactive editor
  libegl-dev libgles-dev libstb-dev   # render/: EGL + OpenGL ES 3.0 headers, stb_image (reading PNG)
  libspng-dev          # render/: PNG encoding (frame capture, screenshots)
  xvfb xauth           # tests/editor: the editor's window under a virtual X server (xvfb-run)
  libegl1 libegl-mesa0 libgles2 libgl1-mesa-dri  # at run time: Mesa's EGL (surfaceless) and llvmpipe
  blender              # tests/blender: the Blender add-on's test runs inside Blender 3.4 (Python 3.11)
  "$@"
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg -s "$p" >/dev/null 2>&1 || ! dpkg -s "$p" 2>/dev/null | grep -q '^Status: install ok installed'; then
    missing+=("$p")
  fi
done
# node and npm run the Khronos glTF validator (tests/gltf). Debian's packages only when no node is on
# the PATH: a node from elsewhere brings its own npm, and Debian's npm would conflict with it.
if ! command -v node >/dev/null 2>&1 || ! command -v npm >/dev/null 2>&1; then
  for p in nodejs npm; do
    dpkg -s "$p" 2>/dev/null | grep -q '^Status: install ok installed' || missing+=("$p")
  done
fi
[ ${#missing[@]} -eq 0 ] && exit 0

echo "deps: installing ${missing[*]}"
if [ "$(id -u)" -eq 0 ]; then
  as_root=()
elif command -v sudo >/dev/null 2>&1; then
  as_root=(sudo)
else
  echo "deps: missing ${missing[*]} and not root (no sudo): install them and rerun" >&2
  exit 1
fi
export DEBIAN_FRONTEND=noninteractive
"${as_root[@]}" apt-get update -qq
"${as_root[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
