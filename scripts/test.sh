#!/usr/bin/env bash
# npm test: install what is missing, build natively, run the C++ tests, then the node tests.
set -euo pipefail
cd "$(dirname "$0")/.."

scripts/ensure-deps.sh
[ -d node_modules/three ] && [ -d node_modules/gltf-validator ] || npm ci --no-audit --no-fund
cmake -S . -B build/native -DCMAKE_BUILD_TYPE=Release
cmake --build build/native -j "$(nproc)"
rm -rf build/native/test-output
ctest --test-dir build/native --output-on-failure -j "$(nproc)"
node --test tests/node/
