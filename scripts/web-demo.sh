#!/usr/bin/env bash
# Runs the WebGL2 demo page's browser test (web/test/browser.mjs: Playwright, Debian's
# Chromium, headless SwiftShader) and keeps its outputs in the docs: the screenshot
# docs/images/web_demo.png and the parity table docs/web_parity.md. Regenerates the npm
# package's generated files first (node web/build.mjs).
# Usage: bash scripts/web-demo.sh        (about 15 s)
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
bash scripts/install-deps.sh
node web/build.mjs
mkdir -p docs/images
node web/test/browser.mjs --screenshot docs/images/web_demo.png --markdown docs/web_parity.md
