#!/usr/bin/env bash
# Installs the Debian 12 packages PriMo needs to build, test and run. Idempotent: only
# packages that are missing are installed, and apt is not touched when none are.
set -euo pipefail

packages=(
  # toolchain
  build-essential cmake ninja-build pkg-config ccache
  # core library
  libopenmesh-dev libeigen3-dev libsuitesparse-dev libopenblas0-pthread libtbb-dev
  # command line and file formats (Assimp reads glTF, FBX, COLLADA and 3MF; the checks before
  # it read COLLADA's and 3MF's XML with libxml2 and 3MF's zip with minizip)
  nlohmann-json3-dev libcli11-dev libassimp-dev libxml2-dev libminizip-dev
  # quality measurement: exact self-intersections and the ARAP peers (primo_quality only)
  libcgal-dev
  # editor
  libglfw3-dev libglm-dev libimgui-dev libstb-dev libgl-dev libgl1-mesa-dri
  # tests (GoogleTest; the editor's end-to-end tests under Xvfb) and the micro-benchmarks
  # (Google Benchmark: primo_microbench)
  libgtest-dev libbenchmark-dev xvfb xauth xdotool
  # the Python module and its tests
  python3-dev pybind11-dev python3-numpy python3-pytest python3-hypothesis
  # the Blender add-on's tests: Debian's Blender (3.4, on the same python3 as the module)
  blender
  # fuzzing (scripts/fuzz.sh): clang with libFuzzer and the sanitizer runtimes
  clang libclang-rt-14-dev
  # packaging (docs/packaging.md): the man page is `primo --help` through help2man
  # (cpack's dpkg-shlibdeps comes with build-essential's dpkg-dev)
  help2man
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed'; then
    missing+=("$p")
  fi
done

if ((${#missing[@]} == 0)); then
  echo "setup: all ${#packages[@]} packages are installed"
  exit 0
fi

echo "setup: installing ${missing[*]}"
sudo_cmd=()
if [[ $(id -u) -ne 0 ]]; then sudo_cmd=(sudo); fi
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
