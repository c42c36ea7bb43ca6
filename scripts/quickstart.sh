#!/usr/bin/env bash
# Set up, build and run rtsim on a Debian 12 machine.
#   scripts/quickstart.sh run   install what is missing, build the rtsim program (Release), run
#                               the default machine (Ullner's peripheral) on the default scene
#   scripts/quickstart.sh test  install what is missing, build everything (Release: the tests and
#                               benchmarks too), run the test suite
# Installs only Debian packages (needs root, or sudo). Nothing is downloaded from elsewhere.
set -euo pipefail

cd "$(dirname "$0")/.."
mode="${1:-run}"
build_dir="${RTSIM_BUILD_DIR:-build}"
jobs="$(nproc 2>/dev/null || echo 2)"

# Every Debian package the build, the tests and analysis/ need (OpenMPI: `rtsim sweep --mpi`).
packages=(
  cmake g++ make pkg-config
  libsystemc-dev libglm-dev libopenimageio-dev openimageio-tools libboost-dev
  libtomlplusplus-dev nlohmann-json3-dev libcli11-dev
  libgtest-dev libgmock-dev googletest libbenchmark-dev
  libopenmpi-dev openmpi-bin
  python3 python3-matplotlib python3-numpy python3-pandas
  graphviz
)
# Only the tests need these: headless Chromium opens report.html (tests/report_test.cpp).
test_packages=(chromium)
if [ "$mode" = test ]; then packages+=("${test_packages[@]}"); fi

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "quickstart: installing Debian packages: ${missing[*]}"
  sudo_cmd=()
  if [ "$(id -u)" -ne 0 ]; then sudo_cmd=(sudo); fi
  "${sudo_cmd[@]}" apt-get update -qq
  DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends \
    "${missing[@]}"
fi

cmake -S . -B "$build_dir" -DCMAKE_BUILD_TYPE=Release
# `run` needs the rtsim program only (it builds the modules it loads); `test` builds everything:
# the test programs and the benchmarks too.
targets=()
if [ "$mode" = run ]; then targets=(--target rtsim); fi
cmake --build "$build_dir" -j "$jobs" "${targets[@]}"

case "$mode" in
  run)
    shift || true
    "$build_dir/rtsim" run --width 256 --height 256 --out out/default "$@"
    ;;
  test)
    ctest --test-dir "$build_dir" --output-on-failure -j "$jobs"
    ;;
  *)
    echo "usage: scripts/quickstart.sh run|test" >&2
    exit 2
    ;;
esac
