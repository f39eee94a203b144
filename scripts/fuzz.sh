#!/usr/bin/env bash
# Builds the scene fuzzers with clang (TANDEM_FUZZ=ON: libFuzzer, ASan, UBSan) and runs their
# tests: every seed once, then each fuzzer for a bounded time (the two side by side). Any
# finding (crash, sanitizer report, round-trip mismatch, timeout, out of memory) fails.
# docs/reliability.md, "Fuzzing". The tree is scripts/configure_checked.sh's, shared with
# scripts/sanitize.sh: given its folder, only the two fuzzers are compiled.
# Usage: scripts/fuzz.sh [build-dir] [seconds per fuzzer]      (default: build-fuzz 30)
set -euo pipefail
cd "$(dirname "$0")/.."
build_dir=${1:-build-fuzz}
seconds=${2:-30}

scripts/configure_checked.sh "$build_dir" -DTANDEM_FUZZ_SECONDS="$seconds"
cmake --build "$build_dir" --parallel "$(nproc)" --target tandem_fuzz_scene tandem_fuzz_scene_structured
cd "$build_dir"
exec ctest --output-on-failure --timeout 900 -j"$(nproc)" -R '^tandem_fuzz_'
