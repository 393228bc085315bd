#!/usr/bin/env bash
# Installs the Debian packages vqsa builds with, when some are missing.
# Non-interactive, so it runs the same in CI and on a fresh machine.
#   --wasm      also Emscripten (the WASM build)
#   --browser   also Chromium (the browser tests)
#   --fuzz      also clang and its sanitizer/libFuzzer runtimes
#   --cgal      also CGAL (the planar VSA peer of the benchmark; never needed by the app or the tests)
set -euo pipefail

packages=(cmake g++ make libgtest-dev libeigen3-dev libtinygltf-dev nlohmann-json3-dev libfast-float-dev libboost-graph-dev)
for flag in "$@"; do
  case "$flag" in
    --wasm) packages+=(emscripten) ;;
    --browser) packages+=(chromium) ;;
    --cgal) packages+=(libcgal-dev) ;;
    --fuzz) packages+=(clang libclang-rt-14-dev) ;;
    *) echo "ensure-deps: unknown flag $flag" >&2; exit 2 ;;
  esac
done
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0

echo "Installing missing Debian packages: ${missing[*]}"
sudo=""
[ "$(id -u)" -ne 0 ] && sudo="sudo"
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq
$sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
