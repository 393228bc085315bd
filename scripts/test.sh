#!/usr/bin/env bash
# npm test: install what is missing; native build + ctest; WASM build + site; node tests
# (export validation, WASM vs native); browser tests in headless Chromium.
set -euo pipefail
cd "$(dirname "$0")/.."

scripts/ensure-deps.sh --wasm --browser
[ -d node_modules/three ] && [ -d node_modules/gltf-validator ] && [ -d node_modules/playwright-core ] \
  || npm ci --no-audit --no-fund
cmake -S . -B build/native -DCMAKE_BUILD_TYPE=Release
cmake --build build/native -j "$(nproc)"
rm -rf build/native/test-output
ctest --test-dir build/native --output-on-failure -j "$(nproc)"
# The same tests but the heavy suites (tests/CMakeLists.txt) under AddressSanitizer and
# UndefinedBehaviorSanitizer. Line tables (-g1) are all a sanitizer's report needs; full
# debug info doubled the build (9 min of 24).
cmake -S . -B build/asan -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG=-g1 -DVQSA_HEAVY_TESTS=OFF \
  -DCMAKE_CXX_FLAGS="-O1 -fno-omit-frame-pointer -fsanitize=address,undefined -fno-sanitize-recover=undefined"
cmake --build build/asan -j "$(nproc)" --target vqsa_tests
ctest --test-dir build/asan --output-on-failure -j "$(nproc)"
scripts/build.sh
node --test tests/node/ tests/browser/
