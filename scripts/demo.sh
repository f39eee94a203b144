#!/usr/bin/env bash
# Sets up, builds, and runs one of the paper's scenes headless (the rope over a wheel, Fig. 4),
# printing what it simulated, how fast, and the step report.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh build
exec build/tandem run scenes/rope_wheel.json --report "$@"
