#!/usr/bin/env bash
# npm run cli -- INPUT [flags]: builds the native CLI when needed and runs it.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
if [ ! -x "$root/build/native/wasm/vqsa" ]; then
  "$root/scripts/ensure-deps.sh" >&2
  cmake -S "$root" -B "$root/build/native" -DCMAKE_BUILD_TYPE=Release >&2
fi
cmake --build "$root/build/native" --target vqsa -j "$(nproc)" >&2
exec "$root/build/native/wasm/vqsa" "$@"
