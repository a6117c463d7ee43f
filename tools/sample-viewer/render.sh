#!/usr/bin/env bash
# Renders the Khronos Sample Viewer reference images into tests/data/sample-viewer/ (docs/SAMPLE_VIEWER.md).
# Usage: tools/sample-viewer/render.sh [--only Name,Name] [--keep-going] [--assets DIR] [--out DIR]
#        tools/sample-viewer/render.sh --views   (recompute views.json from the assets first)
set -euo pipefail
cd "$(dirname "$0")"
if [ ! -x /usr/bin/chromium ]; then
  echo "installing Debian's chromium" >&2
  apt-get update -qq && apt-get install -y -qq chromium
fi
if [ ! -d node_modules/@khronosgroup/gltf-viewer ] || [ ! -d node_modules/playwright-core ]; then
  PLAYWRIGHT_SKIP_BROWSER_DOWNLOAD=1 npm ci --no-audit --no-fund
fi
if [ "${1:-}" = "--views" ]; then
  shift
  node make-views.mjs
fi
exec node render-references.mjs "$@"
