#!/usr/bin/env bash
# Sets up, builds, and runs every test.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh build
cd build
# As many tests at a time as there are cores (tests that must run alone say so: RUN_SERIAL).
exec ctest --output-on-failure --timeout 600 -j"$(nproc)" "$@"
