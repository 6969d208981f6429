#!/usr/bin/env bash
# Installs the Debian 12 packages cloudmath needs, idempotently and quietly.
# Usage: scripts/install-deps.sh            (build + tests)
# Packages already installed are not touched; apt-get runs only when something is missing.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config   # toolchain
  clang                                          # tests: compilers.clang, -Weverything header checks
  libglm-dev                                     # vector types (the library's only dependency)
  doctest-dev                                    # unit tests
  libbenchmark-dev                               # bench/
  libstb-dev                                     # tools/: stb_image_write for PNG output
  zlib1g-dev                                     # tools/: the gzip-stored truth data (docs/data)
  libegl-dev libgl-dev libopengl-dev             # GLSL tests: EGL + GL headers, libOpenGL
  libegl-mesa0 libgl1-mesa-dri                   # GLSL tests: Mesa EGL, llvmpipe (no GPU)
  glslang-tools spirv-tools spirv-cross          # GLSL and HLSL tests: glslangValidator, spirv-val, spirv-cross
  libglfw3-dev                                   # examples/cloud_renderer: the window mode
  xvfb xauth                                     # its test: the window on a virtual X server
  chromium                                       # web/: the WebGL2 page's browser test
  node-typescript                                # web/: tsc checks the npm package's .d.ts
)
# web/ needs Node.js and npm; a machine that has them (Debian's or another build) keeps them.
if ! command -v node >/dev/null 2>&1 || ! command -v npm >/dev/null 2>&1; then
  packages+=(nodejs npm)
fi

# The npm packages of web/ (playwright-core and three, pinned by web/package-lock.json):
# npm ci when node_modules was not installed from the current lock file.
install_npm_packages() {
  local web
  web="$(cd "$(dirname "${BASH_SOURCE[0]}")/../web" && pwd)"
  if ! cmp -s "$web/package-lock.json" "$web/node_modules/.cloudmath-installed-lock.json"; then
    echo "install-deps: npm ci in web/"
    (cd "$web" && npm ci --no-audit --no-fund --loglevel=error >/dev/null)
    cp "$web/package-lock.json" "$web/node_modules/.cloudmath-installed-lock.json"
  fi
}

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed'; then
    missing+=("$p")
  fi
done
if [ ${#missing[@]} -eq 0 ]; then
  install_npm_packages
  exit 0
fi

sudo=""
if [ "$(id -u)" -ne 0 ]; then
  command -v sudo >/dev/null 2>&1 || { echo "install-deps: need root or sudo to install: ${missing[*]}" >&2; exit 1; }
  sudo="sudo"
fi
echo "install-deps: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq >/dev/null
$sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
install_npm_packages
