#!/usr/bin/env bash
# meadow.sh — all set-up on a fresh Debian 12 machine, then one job.
#   ./meadow.sh demo   install what is missing, build, run the main job on the bundled sample
#   ./meadow.sh test   install what is missing, build, run the whole test suite (CTest)
#   ./meadow.sh asan   the same suite under AddressSanitizer + UBSan
#   ./meadow.sh measure  regenerate every table in docs/measurements (--quick: a smoke run)
#   ./meadow.sh fuzz [SECONDS]  build the libFuzzer targets (clang) and run each for SECONDS
#   ./meadow.sh build  install what is missing and build only
#   ./meadow.sh deps   install what is missing, nothing else
# Idempotent: packages already present are not touched; builds are incremental.
set -euo pipefail
cd "$(dirname "$0")"
root=$PWD

# Debian 12 packages meadow builds and tests with (README, "Dependencies").
packages=(
  build-essential cmake ninja-build pkg-config git
  libopencv-dev libopenni2-dev libpcl-dev libeigen3-dev libglm-dev libtinygltf-dev
  nlohmann-json3-dev libcli11-dev
  libegl-dev libgl-dev libopengl-dev libegl-mesa0 libgl1-mesa-dri
  libgtest-dev libgmock-dev libbenchmark-dev
  gnuplot-nox
  libglfw3-dev xvfb xauth ffmpeg
)
# Only `fuzz` needs clang and libFuzzer.
fuzz_packages=(clang libclang-rt-14-dev)

install_missing() {
  local missing=()
  for p in "${packages[@]}" "$@"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "ok installed" || missing+=("$p")
  done
  # node and npm run the glTF validator. Checked as commands, not packages: a machine may have
  # them from another source (nodesource's nodejs bundles npm and conflicts with Debian's npm).
  command -v node >/dev/null 2>&1 || missing+=(nodejs)
  command -v npm >/dev/null 2>&1 || missing+=(npm)
  if ((${#missing[@]})); then
    echo "meadow.sh: installing ${#missing[@]} missing package(s): ${missing[*]}"
    local sudo=""
    [ "$(id -u)" -eq 0 ] || sudo=sudo
    $sudo apt-get update -qq
    DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
  fi
  # The Khronos glTF validator (npm) checks the .glb export in the tests.
  if [ ! -x "$root/tools/node_modules/.bin/gltf_validator" ] && [ ! -f "$root/tools/node_modules/gltf-validator/package.json" ]; then
    echo "meadow.sh: installing the Khronos glTF validator (npm gltf-validator) into tools/"
    (cd "$root/tools" && npm install --silent --no-audit --no-fund >/dev/null)
  fi
}

jobs=$(nproc)
build() {
  local preset=$1
  [ -f "build/$preset/build.ninja" ] || cmake --preset "$preset" >/dev/null
  # Ninja's progress lines and its "no work to do" are noise; errors and warnings stay.
  # The build's own status decides (PIPESTATUS is read before anything else can reset it).
  local status
  set +e
  cmake --build --preset "$preset" -j "$jobs" | grep -vE '^\[[0-9]+/[0-9]+\] |^ninja: no work to do'
  status=${PIPESTATUS[0]}
  set -e
  return "$status"
}

export XDG_RUNTIME_DIR=${XDG_RUNTIME_DIR:-/tmp}
cmd=${1:-help}
case "$cmd" in
  deps)  install_missing ;;
  build) install_missing; build default ;;
  test)  install_missing; build default; ctest --preset default -j "$jobs" ;;
  asan)  install_missing; build asan; ctest --preset asan -j "$jobs" ;;
  demo)  install_missing; build default; shift; exec "$root/samples/demo.sh" "$root/build/default/cli/meadow" "$@" ;;
  measure) install_missing; build default; shift; exec "$root/tools/measure.sh" "$@" ;;
  fuzz)  install_missing "${fuzz_packages[@]}"; build fuzz; shift; exec "$root/tools/fuzz.sh" "$@" ;;
  *) sed -n '2,10p' "$0"; [ "$cmd" = help ] || exit 2 ;;
esac
