#!/usr/bin/env bash
# Installs the build tree into PREFIX (emptied first) as a user would, and checks what is there:
# headers, libtandem, the CMake package and pkg-config files, the command (its version, and the
# scene files it finds beside itself).
# Usage: install_tree.sh CMAKE BUILD_DIR PREFIX VERSION LIBDIR
set -euo pipefail
cmake=$1 build=$2 prefix=$3 version=$4 libdir=$5

rm -rf "$prefix"
"$cmake" --install "$build" --prefix "$prefix" >/dev/null

status=0
for file in include/tandem/world.h include/tandem/version.h include/tandem/export.h \
            "$libdir/cmake/Tandem/TandemConfig.cmake" "$libdir/cmake/Tandem/TandemConfigVersion.cmake" \
            "$libdir/cmake/Tandem/TandemTargets.cmake" "$libdir/pkgconfig/tandem.pc" \
            share/tandem/scenes/rope_wheel.json share/doc/tandem/LICENSE bin/tandem; do
  [[ -e "$prefix/$file" ]] || { echo "install_tree: $file was not installed"; status=1; }
done
if ! compgen -G "$prefix/$libdir/libtandem.*" >/dev/null; then
  echo "install_tree: no libtandem in $prefix/$libdir"
  status=1
fi
# Every public header is installed (version.h is generated, so it is not in the source tree's list).
for header in "$(dirname "$0")"/../include/tandem/*.h; do
  [[ -e "$prefix/include/tandem/$(basename "$header")" ]] || { echo "install_tree: $(basename "$header") missing"; status=1; }
done

printed=$("$prefix/bin/tandem" --version)
[[ "$printed" == "tandem $version" ]] || { echo "install_tree: tandem --version printed '$printed', not 'tandem $version'"; status=1; }
listed=$("$prefix/bin/tandem" list)
grep -q "Scene files in $prefix/share/tandem/scenes" <<<"$listed" ||
  { echo "install_tree: the installed tandem does not find its scenes:"; echo "$listed"; status=1; }
"$prefix/bin/tandem" run "$prefix/share/tandem/scenes/rope_wheel.json" --steps 5 --quiet >/dev/null ||
  { echo "install_tree: the installed tandem does not run an installed scene"; status=1; }

((status == 0)) && echo "install_tree: Tandem $version installed into $prefix"
exit $status
