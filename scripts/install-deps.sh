#!/usr/bin/env bash
# Installs the Debian 12 packages touchcloud builds and tests with (with
# --fuzz, also those scripts/fuzz.sh needs). Does nothing when they are all
# present; needs root (or sudo) otherwise.
set -euo pipefail
packages=(
  cmake ninja-build g++ lld pkg-config python3
  libeigen3-dev libpcl-dev libopencv-dev libboost-dev libboost-filesystem-dev
  libyaml-cpp-dev libceres-dev libflann-dev libcli11-dev nlohmann-json3-dev libnanoflann-dev libopenblas-dev libsleef-dev
  libgtest-dev libbenchmark-dev
  python3-matplotlib python3-numpy python3-dev pybind11-dev python3-pytest
  python3-open3d pcl-tools
  libopenmpi-dev openmpi-bin
  libfftw3-dev
  libjpeg-dev libpng-dev libavutil-dev zlib1g-dev libdeflate-dev
  libtorch-dev
  chromium
  libcpp-httplib-dev python3-opencv
  mkdocs doxygen
)
# The report's JavaScript comes through npm: Debian's package, unless an npm
# is there already (NodeSource's nodejs bundles one and conflicts with it).
command -v npm >/dev/null 2>&1 || packages+=(npm)
# scripts/fuzz.sh: Debian's clang with its libFuzzer and sanitizer runtimes.
if [ "${1:-}" = "--fuzz" ]; then packages+=(clang libclang-rt-14-dev); fi
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0
echo "installing: ${missing[*]}" >&2
sudo=""
[ "$(id -u)" -ne 0 ] && sudo="sudo"
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq
$sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
