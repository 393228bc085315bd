#!/usr/bin/env bash
# npm run bench:core: Lloyd-stage timing on fandisk/22 and bunny_closed/28 (median of runs).
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
"$root/scripts/ensure-deps.sh"
cmake -S "$root" -B "$root/build/native" -DCMAKE_BUILD_TYPE=Release > /dev/null
cmake --build "$root/build/native" --target vqsa_bench -j "$(nproc)" > /dev/null
exec "$root/build/native/bench/vqsa_bench" "${VQSA_MESHES:-$root/../shared/meshes}" "${1:-5}"
