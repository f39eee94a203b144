#!/usr/bin/env bash
# Builds tests/consumer against the Tandem installed in PREFIX with find_package(Tandem), as the
# README shows, and runs it. Checks that the package found is the one in PREFIX.
# Usage: consumer_cmake.sh CMAKE GENERATOR CXX PREFIX WORK_DIR VERSION [COMPILER_LAUNCHER]
set -euo pipefail
cmake=$1 generator=$2 cxx=$3 prefix=$4 work=$5 version=$6 launcher=${7:-}
source_dir=$(cd "$(dirname "$0")/consumer" && pwd)

rm -rf "$work"
"$cmake" -S "$source_dir" -B "$work" -G "$generator" -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_COMPILER="$cxx" \
  ${launcher:+-DCMAKE_CXX_COMPILER_LAUNCHER="$launcher"} -DCMAKE_PREFIX_PATH="$prefix" \
  -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF -DTANDEM_REQUIRED_VERSION="${version%.*}" >"$work.log" 2>&1 ||
  { cat "$work.log"; exit 1; }
found=$(sed -n 's/^Tandem_DIR:PATH=//p' "$work/CMakeCache.txt")
[[ "$found" == "$prefix"/* ]] || { echo "consumer_cmake: found Tandem in '$found', not in $prefix"; exit 1; }
"$cmake" --build "$work" >>"$work.log" 2>&1 || { cat "$work.log"; exit 1; }
"$work/hanging_box"
