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
          # the scene fuzzers (scripts/fuzz.sh): clang and its libFuzzer runtime
          clang libclang-rt-14-dev)

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

cmake -S . -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE=Release -DTANDEM_WARNINGS_AS_ERRORS=ON \
      -DPython3_EXECUTABLE=/usr/bin/python3 >/dev/null
cmake --build "$build_dir" --parallel "$(nproc)"
