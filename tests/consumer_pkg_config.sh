#!/usr/bin/env bash
# Builds tests/consumer/hanging_box.cpp against the Tandem installed in PREFIX with one compiler
# line and pkg-config, as the README shows, and runs it.
# Usage: consumer_pkg_config.sh CXX PREFIX LIBDIR WORK_DIR
set -euo pipefail
cxx=$1 prefix=$2 libdir=$3 work=$4
source_file=$(cd "$(dirname "$0")/consumer" && pwd)/hanging_box.cpp

rm -rf "$work" && mkdir -p "$work"
export PKG_CONFIG_PATH="$prefix/$libdir/pkgconfig"
flags=$(pkg-config --cflags --libs tandem)
echo "pkg-config --cflags --libs tandem: $flags"
# The rpath lets a shared libtandem be found where it was installed.
"$cxx" -std=c++20 -O2 "$source_file" -o "$work/hanging_box" $flags -Wl,-rpath,"$(pkg-config --variable=libdir tandem)"
"$work/hanging_box"
