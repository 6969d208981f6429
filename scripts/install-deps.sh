#!/usr/bin/env bash
# Installs the Debian 12 packages cloudmath needs, idempotently and quietly.
# Usage: scripts/install-deps.sh            (build + tests)
# Packages already installed are not touched; apt-get runs only when something is missing.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config   # toolchain
  libglm-dev                                     # vector types (the library's only dependency)
  doctest-dev                                    # unit tests
  libbenchmark-dev                               # bench/
  libstb-dev                                     # tools/: stb_image_write for PNG output
  libegl-dev libgl-dev libopengl-dev             # GLSL tests: EGL + GL headers, libOpenGL
  libegl-mesa0 libgl1-mesa-dri                   # GLSL tests: Mesa EGL, llvmpipe (no GPU)
  glslang-tools spirv-tools                      # GLSL tests: glslangValidator, spirv-val
  libglfw3-dev                                   # examples/cloud_renderer: the window mode
  xvfb xauth                                     # its test: the window on a virtual X server
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed'; then
    missing+=("$p")
  fi
done
[ ${#missing[@]} -eq 0 ] && exit 0

sudo=""
if [ "$(id -u)" -ne 0 ]; then
  command -v sudo >/dev/null 2>&1 || { echo "install-deps: need root or sudo to install: ${missing[*]}" >&2; exit 1; }
  sudo="sudo"
fi
echo "install-deps: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq >/dev/null
$sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
