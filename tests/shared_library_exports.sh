#!/usr/bin/env bash
# Checks a shared libtandem: its SONAME carries the version (libtandem.so.MAJOR.MINOR), and it
# exports nothing but the public API of include/tandem/: every exported function is in
# namespace tandem and named in a public header (internals such as the solver or Bullet's
# wrapper stay hidden).
# Usage: shared_library_exports.sh LIBRARY MAJOR.MINOR HEADER_DIR
set -euo pipefail
library=$1 abi=$2 headers=$3

status=0
soname=$(readelf -d "$library" | sed -n 's/.*(SONAME).*\[\(.*\)\]/\1/p')
echo "SONAME: $soname"
[[ "$soname" == "libtandem.so.$abi" ]] || { echo "shared_library_exports: SONAME is '$soname', not libtandem.so.$abi"; status=1; }

exported=$(nm -D --defined-only "$library" | awk '{ $1 = ""; $2 = ""; sub(/^ +/, ""); print }' | c++filt)
count=$(wc -l <<<"$exported")
echo "exported symbols: $count"
outside=$(grep -v -E '^((typeinfo|typeinfo name|vtable) for )?tandem::' <<<"$exported" || true)
if [[ -n "$outside" ]]; then
  echo "shared_library_exports: exported outside namespace tandem:"
  echo "$outside" | head -20
  status=1
fi
private=$(grep -E '::(Impl|detail)\b' <<<"$exported" || true)
if [[ -n "$private" ]]; then
  echo "shared_library_exports: exports private parts:"
  echo "$private"
  status=1
fi
# The name each exported function or class is known by (tandem::World::step(double) -> World, step).
names=$(grep -E '^tandem::' <<<"$exported" | sed -E 's/\[abi:[a-z0-9]+\]//g; s/\(.*//; s/<.*//' | tr ':' '\n' | grep -v -E '^$|^tandem$|^operator|^~' | sort -u)
for name in $names; do
  grep -q -w -r -F -- "$name" "$headers" || { echo "shared_library_exports: exports $name, which no public header declares"; status=1; }
done
((status == 0)) && echo "shared_library_exports: $count symbols, all tandem's public API"
exit $status
