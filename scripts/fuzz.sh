#!/usr/bin/env bash
# Builds the scene fuzzers with clang (TANDEM_FUZZ=ON: libFuzzer, ASan, UBSan) and runs their
# tests: every seed once, then each fuzzer for a bounded time. Any finding (crash, sanitizer
# report, round-trip mismatch, timeout, out of memory) fails. docs/reliability.md, "Fuzzing".
# Usage: scripts/fuzz.sh [build-dir] [seconds per fuzzer]      (default: build-fuzz 30)
set -euo pipefail
cd "$(dirname "$0")/.."
build_dir=${1:-build-fuzz}
seconds=${2:-30}

CC=clang CXX=clang++ cmake -S . -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
      -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ -DTANDEM_WARNINGS_AS_ERRORS=ON -DTANDEM_FUZZ=ON \
      -DTANDEM_BUILD_TESTS=OFF -DTANDEM_BUILD_BENCHMARKS=OFF -DTANDEM_BUILD_RENDER=OFF \
      -DTANDEM_FUZZ_SECONDS="$seconds" >/dev/null
cmake --build "$build_dir" --parallel "$(nproc)" --target tandem_fuzz_scene tandem_fuzz_scene_structured
cd "$build_dir"
exec ctest --output-on-failure --timeout 900
