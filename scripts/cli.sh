#!/usr/bin/env bash
# npm run cli -- INPUT [flags]: builds the native CLI when needed and runs it.
# npm run cli:wasm -- INPUT [flags]: the same CLI compiled to WebAssembly, under node.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
if [ "${1:-}" = "--wasm" ]; then
  shift
  [ -f "$root/build/wasm/wasm/vqsa-cli.js" ] || "$root/scripts/build.sh" >&2
  exec node "$root/build/wasm/wasm/vqsa-cli.js" "$@"
fi
if [ ! -x "$root/build/native/wasm/vqsa" ]; then
  "$root/scripts/ensure-deps.sh" >&2
  cmake -S "$root" -B "$root/build/native" -DCMAKE_BUILD_TYPE=Release >&2
fi
cmake --build "$root/build/native" --target vqsa -j "$(nproc)" >&2
exec "$root/build/native/wasm/vqsa" "$@"
