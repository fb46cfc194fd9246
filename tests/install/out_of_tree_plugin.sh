#!/usr/bin/env bash
# Installs the toolkit into a temporary prefix, builds examples/custom_plugin
# against it with find_package(touchcloud), loads the plugin through
# TOUCHCLOUD_PLUGIN_PATH and runs it in a pipeline with the installed CLI;
# builds and runs a program on the installed imaging and calibration
# libraries, and one against the installed gp library (touchcloud::gp,
# tests/install/gp_consumer).
# Usage: out_of_tree_plugin.sh SOURCE_DIR BUILD_DIR
set -euo pipefail
src=$1 build=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

cmake --install "$build" --prefix "$work/prefix" > "$work/install.log"
cmake -S "$src/examples/custom_plugin" -B "$work/plugin" -G Ninja \
      -DCMAKE_PREFIX_PATH="$work/prefix" -DCMAKE_BUILD_TYPE=Release > "$work/configure.log"
cmake --build "$work/plugin" > "$work/build.log"
test -f "$work/plugin/touchcloud_contact_disc.so"

export TOUCHCLOUD_PLUGIN_PATH="$work/plugin"
tc="$work/prefix/bin/touchcloud"
"$tc" plugins contact_disc | grep -q "radius_mm"
"$tc" run "$src/examples/custom_plugin/contact_disc.yaml" --out "$work/out" --quiet > "$work/run.log"
grep -q '"disc.points_kept"' "$work/out/summary.json"
kept=$(python3 -c "import json,sys; print(int(json.load(open(sys.argv[1]))['metrics']['disc.points_kept']['value']))" "$work/out/summary.json")
# The dome's 2000 points are spread evenly by area over a 32.5 mm hemisphere.
# A 10 mm disc around the axis is a cap of height h = 32.5 - sqrt(32.5^2 - 10^2)
# = 1.576 mm, area 2 pi R h, which is h / R = 4.85 % of the hemisphere: ~97 points.
if [ "$kept" -lt 90 ] || [ "$kept" -gt 105 ]; then
  echo "contact_disc kept $kept points, expected about 97" >&2; exit 1
fi
# A program built against the installed libraries alone (no plugin, no runtime).
mkdir -p "$work/libs_consumer"
cat > "$work/libs_consumer/CMakeLists.txt" <<'CMAKE'
cmake_minimum_required(VERSION 3.22)
project(touchcloud_consumer LANGUAGES C CXX)
set(CMAKE_CXX_STANDARD 20)
find_package(touchcloud 0.1 REQUIRED)
add_executable(consumer consumer.cpp)
target_link_libraries(consumer PRIVATE touchcloud::imaging touchcloud::calibration)
CMAKE
cat > "$work/libs_consumer/consumer.cpp" <<'CXX'
#include <touchcloud/calibration/normal_chart.hpp>
#include <touchcloud/imaging/contact_region.hpp>
int main() {
  const cv::Mat rest(16, 16, CV_8UC1, cv::Scalar(0)), pressed(16, 16, CV_8UC1, cv::Scalar(60));
  const cv::Mat contact = touchcloud::imaging::contact_region(pressed, rest, {});
  const touchcloud::calibration::NormalChart chart(Eigen::Vector3d::UnitZ());
  return cv::countNonZero(contact) == 256 && chart.normal(0, 0).isApprox(Eigen::Vector3d::UnitZ()) ? 0 : 1;
}
CXX
cmake -S "$work/libs_consumer" -B "$work/libs_consumer/build" -G Ninja -DCMAKE_PREFIX_PATH="$work/prefix" \
      -DCMAKE_BUILD_TYPE=Release > "$work/libs_consumer.log"
cmake --build "$work/libs_consumer/build" >> "$work/libs_consumer.log"
"$work/libs_consumer/build/consumer"
# The installed CLI finds the installed built-in plugins (not the build tree's).
"$tc" plugins --json | python3 -c "import json,sys; libs=[p['library'] for p in json.load(sys.stdin)]; assert all(l.startswith('$work/prefix') or l.startswith('$work/plugin') for l in libs), libs"
echo "out-of-tree plugin: built, loaded and run; kept $kept points; a program on the installed imaging and calibration libraries ran"

cmake -S "$src/tests/install/gp_consumer" -B "$work/consumer" -G Ninja \
      -DCMAKE_PREFIX_PATH="$work/prefix" -DCMAKE_BUILD_TYPE=Release > "$work/consumer_configure.log"
cmake --build "$work/consumer" > "$work/consumer_build.log"
fitted=$("$work/consumer/fit_touches")
# Three touches of 9 points: selections at 9, 18 (>= 13.5) and 27 (>= 27)
# points; between its touches the mean of a plane is the plane (6.1 mm).
python3 - "$fitted" <<'PY'
import sys
words = sys.argv[1].split()
assert words[0] == "selections" and words[1] == "3" and abs(float(words[3]) - 6.1) < 0.01, sys.argv[1]
PY
echo "gp library: built against and run ($fitted)"
