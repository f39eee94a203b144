#!/usr/bin/env bash
# Installs what Tandem needs on Debian 12 (only what is missing), then configures and builds it.
# Usage: scripts/setup.sh [build-dir]     (default: build)
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(build-essential cmake ninja-build pkg-config
          libbullet-dev libeigen3-dev libcli11-dev nlohmann-json3-dev libtinyobjloader-dev
          libgtest-dev libbenchmark-dev
          # export: `tandem export` writes glTF 2.0 with tinygltf (Debian ships it as a shared library)
          libtinygltf-dev
          # rendering: `tandem view` (GLFW, Dear ImGui), `tandem render` (EGL with no display,
          # Mesa's software rasteriser, ffmpeg for mp4); Xvfb and xdotool for the viewer's tests
          libopengl-dev libgl-dev libegl-dev libglfw3-dev libimgui-dev libstb-dev libegl-mesa0 libgl1-mesa-dri
          ffmpeg xvfb xauth xdotool
          # the paper's figures (scripts/figures.sh), the tests that read .npz records with NumPy,
          # the Python module (`import tandem`), its tests and examples, and `pip install .`
          python3 python3-dev pybind11-dev python3-numpy python3-pytest python3-matplotlib
          python3-pip python3-setuptools python3-wheel
          # the sanitizer suite and the scene fuzzers (scripts/sanitize.sh, scripts/fuzz.sh): clang,
          # its sanitizer and libFuzzer runtimes
          clang libclang-rt-14-dev
          # a compiler cache: the suite's `pip install .` test builds the library and the Python
          # module again, from the same sources with the same flags; ccache hands it this build's
          # objects (below)
          ccache)

missing=()
for package in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed" || missing+=("$package")
done
if ((${#missing[@]})); then
  echo "tandem: installing ${missing[*]}"
  if [[ $(id -u) -eq 0 ]]; then sudo=(); else sudo=(sudo); fi
  "${sudo[@]}" apt-get update -qq
  DEBIAN_FRONTEND=noninteractive "${sudo[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

build_dir=${1:-build}

# Compiled through ccache (when there), with paths under the build folder rewritten relative to
# the compiler's working folder (base_dir): the only thing that differs between this build's
# compiler calls and those of the package build python/tests/pip_install.cmake makes under
# build/python/pip_install/ is where the generated include/ folder is, and relative to each
# build's own folder it is `include` in both. Depend mode: no separate preprocessor run on a miss.
launcher=()
if command -v ccache >/dev/null; then
  launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
  mkdir -p "$build_dir"
  export CCACHE_BASEDIR=$(cd "$build_dir" && pwd) CCACHE_DEPEND=1
fi
cmake -S . -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE=Release -DTANDEM_WARNINGS_AS_ERRORS=ON \
      -DPython3_EXECUTABLE=/usr/bin/python3 "${launcher[@]}" >/dev/null
cmake --build "$build_dir" --parallel "$(nproc)"
