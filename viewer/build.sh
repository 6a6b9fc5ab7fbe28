#!/usr/bin/env bash
# Builds the browser viewer: curvenet compiled to WebAssembly (viewer/pkg/curvenet.wasm) and
# the npm packages of the page (three.js; playwright-core for the browser test).
set -euo pipefail
cd "$(dirname "$0")/.."
if ! rustup target list --installed 2>/dev/null | grep -q '^wasm32-unknown-unknown$'; then
    rustup target add wasm32-unknown-unknown
fi
cargo build --profile wasm --target wasm32-unknown-unknown -p curvenet-wasm
mkdir -p viewer/pkg
cp target/wasm32-unknown-unknown/wasm/curvenet_wasm.wasm viewer/pkg/curvenet.wasm
cd viewer
if [ ! -d node_modules/three ] || [ ! -d node_modules/playwright-core ]; then
    npm ci --no-audit --no-fund
fi
echo "viewer built: viewer/pkg/curvenet.wasm ($(du -h pkg/curvenet.wasm | cut -f1))"
