#!/usr/bin/env bash
# npm run build: the WASM module (emcmake, -O3) and the static site in dist/.
set -euo pipefail
cd "$(dirname "$0")/.."

scripts/ensure-deps.sh --wasm
[ -d node_modules/three ] || npm ci --no-audit --no-fund
# Debian's emcc keeps its cache under /usr/share; use our own where that is read-only.
[ -w /usr/share/emscripten/cache ] || export EM_CACHE="$PWD/build/emcache"
emcmake cmake -S . -B build/wasm -DCMAKE_BUILD_TYPE=Release > /dev/null
cmake --build build/wasm -j "$(nproc)"

# The site: our pages and modules, the WASM module, and the few Three.js files the
# viewer imports (no CDN: meshes and code never leave the user's machine).
rm -rf dist
mkdir -p dist/vendor/three/addons/controls
cp -r web/. dist/
cp build/wasm/wasm/vqsa.mjs build/wasm/wasm/vqsa.wasm dist/
cp node_modules/three/build/three.module.js node_modules/three/build/three.core.js dist/vendor/three/
# OrbitControls imports the bare specifier 'three': point it at the file, so that the
# viewer works from any folder of any static host without an import map.
sed "s#from 'three'#from '../../three.module.js'#" node_modules/three/examples/jsm/controls/OrbitControls.js \
  > dist/vendor/three/addons/controls/OrbitControls.js
node scripts/example-assets.mjs dist/examples
node scripts/write-schema.mjs dist/vqsa-schema.js
echo "built dist/"
