#!/usr/bin/env bash
# npm run fuzz -- [SECONDS] [TARGET...]: builds the libFuzzer targets with clang
# (address and undefined-behaviour sanitizers) and runs each for SECONDS (default 60),
# starting from the seeds in tests/fuzz/seeds. Findings land in build/fuzz/findings/.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-60}"
shift || true
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(off obj ply stl gltf glb pipeline)

scripts/ensure-deps.sh --fuzz
CC=clang CXX=clang++ cmake -S . -B build/fuzz -DVQSA_FUZZ=ON -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS="-fsanitize=address,undefined,fuzzer-no-link -fno-sanitize-recover=undefined" > /dev/null
cmake --build build/fuzz -j "$(nproc)" --target $(printf 'fuzz_%s ' "${targets[@]}")

mkdir -p build/fuzz/findings
for t in "${targets[@]}"; do
  corpus="build/fuzz/corpus/$t"
  mkdir -p "$corpus"
  seeds="tests/fuzz/seeds/$t"
  [ -d "$seeds" ] || seeds="tests/fuzz/seeds/$( [ "$t" = glb ] && echo gltf || echo "$t")"
  echo "== fuzz_$t for ${seconds}s"
  build/fuzz/tests/fuzz/fuzz_"$t" "$corpus" "$seeds" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
    -max_len=65536 -artifact_prefix=build/fuzz/findings/"$t"- -print_final_stats=1 2>&1 \
    | grep -E "^(stat::number_of_executed_units|stat::peak_rss_mb|==.*ERROR|SUMMARY)|Done [0-9]+ runs|artifact_prefix" || true
done
echo "findings (if any):"
ls build/fuzz/findings/ 2>/dev/null || true
