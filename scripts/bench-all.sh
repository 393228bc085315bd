#!/usr/bin/env bash
# npm run bench: builds native, WASM and the CGAL planar VSA peer, then runs bench/run.mjs
# (about ten minutes on two cores) which writes bench/RESULTS.md and its charts.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/ensure-deps.sh --wasm --cgal --browser
cmake -S . -B build/native -DCMAKE_BUILD_TYPE=Release > /dev/null
cmake --build build/native -j "$(nproc)" > /dev/null
scripts/build.sh > /dev/null
cmake -S . -B build/bench -DCMAKE_BUILD_TYPE=Release -DVQSA_CGAL_PEER=ON > /dev/null
cmake --build build/bench -j "$(nproc)" --target planar_vsa > /dev/null
node bench/run.mjs
