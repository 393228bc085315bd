#!/usr/bin/env bash
# npm test: install what is missing, build natively, run the C++ tests.
set -euo pipefail
cd "$(dirname "$0")/.."

scripts/ensure-deps.sh
cmake -S . -B build/native -DCMAKE_BUILD_TYPE=Release
cmake --build build/native -j "$(nproc)"
ctest --test-dir build/native --output-on-failure -j "$(nproc)"
