#!/usr/bin/env bash
# npm start: install what is missing, build the WASM module and the site, serve it on
# http://localhost:8080 (PORT overrides).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh
exec node scripts/serve.mjs
