#!/usr/bin/env bash
# Configures one clang build tree for both checked runs (docs/reliability.md, "Sanitizers",
# "Fuzzing"): the library, the `tandem` command and the C++ tests with AddressSanitizer and
# UndefinedBehaviorSanitizer (TANDEM_SANITIZE: any report aborts), and the scene fuzzers
# (TANDEM_FUZZ: the library also carries libFuzzer's coverage instrumentation, which the tests,
# linked without libFuzzer, do not use). scripts/sanitize.sh and scripts/fuzz.sh both call it, so
# that given the same folder the second builds on the first's objects instead of compiling the
# library again.
# Usage: scripts/configure_checked.sh build-dir [more cmake options]
set -euo pipefail
cd "$(dirname "$0")/.."
build_dir=$1
shift

# No Python module (it would need the sanitizer runtime preloaded into python3), benchmarks or
# renderer (the viewer and render tests need Mesa, whose dlopen'd drivers LeakSanitizer cannot
# attribute). -O1 -g1: ASan's reports still name file and line (-g1 is clang's line tables).
cmake -S . -B "$build_dir" -G Ninja -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
      -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" \
      -DTANDEM_WARNINGS_AS_ERRORS=ON -DTANDEM_SANITIZE=ON -DTANDEM_FUZZ=ON \
      -DTANDEM_BUILD_BENCHMARKS=OFF -DTANDEM_BUILD_PYTHON=OFF -DTANDEM_BUILD_RENDER=OFF \
      -DPython3_EXECUTABLE=/usr/bin/python3 "$@" >/dev/null
