#!/usr/bin/env bash
# Builds the library, the command and the tests with AddressSanitizer and UndefinedBehaviorSanitizer
# (TANDEM_SANITIZE=ON: any report aborts the program, so the test that saw it fails) and runs the
# suite, with the slow paper-scene runs shortened (TANDEM_SHORT_TESTS=1). docs/reliability.md,
# "Sanitizers". Run scripts/setup.sh first (packages).
# Usage: scripts/sanitize.sh [build-dir] [ctest options]     (default: build-asan)
set -euo pipefail
cd "$(dirname "$0")/.."
build_dir=${1:-build-asan}
shift $(( $# > 0 ? 1 : 0 ))

# Only what the C++ suite runs: the library, the `tandem` command and the test executables; no
# Python module (it would need the sanitizer runtime preloaded into python3), benchmarks or
# renderer (the viewer and render tests need Mesa, whose dlopen'd drivers LeakSanitizer cannot
# attribute). -O1 -g1: ASan's reports still name file and line. 19.0 CPU-min for the 94 targets
# (22 at -O2 -g with everything); docs/reliability.md, "CI time".
cmake -S . -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" \
      -DTANDEM_WARNINGS_AS_ERRORS=ON -DTANDEM_SANITIZE=ON -DTANDEM_BUILD_BENCHMARKS=OFF -DTANDEM_BUILD_PYTHON=OFF \
      -DTANDEM_BUILD_RENDER=OFF -DPython3_EXECUTABLE=/usr/bin/python3 >/dev/null
cmake --build "$build_dir" --parallel "$(nproc)"

export TANDEM_SHORT_TESTS=1
# halt_on_error: the first report fails the test; leaks are reported too, but not those inside
# Mesa, LLVM (llvmpipe) and GLFW, which keep their allocations until exit by design.
export ASAN_OPTIONS=halt_on_error=1:detect_leaks=1:abort_on_error=0:strict_string_checks=1:detect_stack_use_after_return=1
export UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1
export LSAN_OPTIONS=suppressions=$PWD/tests/sanitizer_leaks.supp:print_suppressions=0
cd "$build_dir"
# The paper scenes' 10 s checks take 5+ minutes each under the sanitizers: the soak test runs the
# same scenes for 2 s instead (TANDEM_SHORT_TESTS), and the determinism test 60 to 150 steps.
# Packaging (install_*, shared_library_exports: installing and building consumer projects) is the
# Release suite's; here it would only compile consumers again.
exec ctest --output-on-failure --timeout 900 -j"$(nproc)" -E '^PaperScenes\.|^install_|^shared_library_' "$@"
