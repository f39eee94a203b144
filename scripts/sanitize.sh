#!/usr/bin/env bash
# Builds the library, the command and the C++ tests with clang's AddressSanitizer and
# UndefinedBehaviorSanitizer (TANDEM_SANITIZE=ON: any report aborts the program, so the test that
# saw it fails) and runs the suite, with the slowest runs shortened (TANDEM_SHORT_TESTS=1).
# docs/reliability.md, "Sanitizers". Run scripts/setup.sh first (packages). The tree is
# scripts/configure_checked.sh's, which the fuzzers share: `scripts/fuzz.sh build-asan` after
# this builds only the two fuzzers.
# Usage: scripts/sanitize.sh [build-dir] [ctest options]     (default: build-asan)
set -euo pipefail
cd "$(dirname "$0")/.."
build_dir=${1:-build-asan}
shift $(( $# > 0 ? 1 : 0 ))

scripts/configure_checked.sh "$build_dir"
# Everything, the two fuzzers too (a few seconds more: scripts/fuzz.sh then only runs them).
cmake --build "$build_dir" --parallel "$(nproc)"

export TANDEM_SHORT_TESTS=1
# halt_on_error: the first report fails the test; leaks are reported too.
export ASAN_OPTIONS=halt_on_error=1:detect_leaks=1:abort_on_error=0:strict_string_checks=1:detect_stack_use_after_return=1
export UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1
export LSAN_OPTIONS=suppressions=$PWD/tests/sanitizer_leaks.supp:print_suppressions=0
cd "$build_dir"
# The paper scenes' 10 s checks take 5+ minutes each under the sanitizers: the soak test runs the
# same scenes for 2 s instead (TANDEM_SHORT_TESTS), and the determinism test fewer steps against
# golden values of their own. Packaging (install_*, shared_library_exports: installing and
# building consumer projects) is the Release suite's; here it would only compile consumers again.
# The fuzzers' tests are scripts/fuzz.sh's. The limit per test is generous: the jelly soak alone
# takes about 265 CPU-s here, and much more wall time on a shared machine (docs/reliability.md).
exec ctest --output-on-failure --timeout 1800 -j"$(nproc)" -E '^PaperScenes\.|^install_|^shared_library_|^tandem_fuzz_' "$@"
