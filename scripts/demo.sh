#!/usr/bin/env bash
# Sets up, builds, and runs the flagship scene headless, printing what it simulated and how fast.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh build
exec build/tandem run curtain --report "$@"
