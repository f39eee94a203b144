#!/usr/bin/env bash
# The paper's figures, made by Tandem: runs the paper's three scenes with --report-json and plots
# them with matplotlib (scripts/plot_figures.py says what each PNG shows).
#
# Usage: scripts/figures.sh OUT_DIR [--seconds S] [--data DATA_DIR] [--tandem PATH]
#   OUT_DIR     where the PNGs go (the docs' are made with docs/images)
#   --seconds   simulated seconds per scene (default: each scene file's duration, 10 s)
#   --data      keep the run reports and the plotted numbers (figures.json) here
#               (default: a temporary folder, removed afterwards)
#   --tandem    the tandem command (default: build/tandem)
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"

usage() { sed -n '5,11p' "$0" | sed 's/^# \{0,1\}//' >&2; exit 2; }
(($# >= 1)) || usage
out_dir=$1
shift
seconds=""
data_dir=""
tandem="$root/build/tandem"
while (($#)); do
  case $1 in
    --seconds) seconds=${2:?--seconds needs a number}; shift 2 ;;
    --data) data_dir=${2:?--data needs a folder}; shift 2 ;;
    --tandem) tandem=${2:?--tandem needs a path}; shift 2 ;;
    *) echo "figures.sh: unknown option '$1'" >&2; usage ;;
  esac
done
[[ -x $tandem ]] || { echo "figures.sh: no tandem command at '$tandem' (build first: scripts/setup.sh)" >&2; exit 1; }
python=/usr/bin/python3
"$python" -c "import numpy, matplotlib" 2>/dev/null ||
  { echo "figures.sh: $python needs numpy and matplotlib (apt-get install python3-numpy python3-matplotlib)" >&2; exit 1; }

if [[ -z $data_dir ]]; then
  data_dir=$(mktemp -d)
  trap 'rm -rf "$data_dir"' EXIT
fi
mkdir -p "$out_dir" "$data_dir"
run_length=()
[[ -n $seconds ]] && run_length=(--seconds "$seconds")

for scene in rope_wheel cloth_sphere jelly_dish; do
  echo "figures.sh: running $scene"
  "$tandem" run "$root/scenes/$scene.json" "${run_length[@]}" --quiet --report-json "$data_dir/$scene.json"
done
MPLBACKEND=Agg "$python" "$root/scripts/plot_figures.py" "$data_dir" "$out_dir" "$data_dir/figures.json"
