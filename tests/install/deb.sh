#!/usr/bin/env bash
# Makes the Debian package with CPack, unpacks it into a temporary root
# (dpkg -x, as `apt install` would lay it out under /usr), and uses it from
# there alone: imports the Python module and runs a pipeline with it, runs a
# shipped pipeline and the shipped plugin example's pipeline with the
# unpacked CLI, and builds that example against the unpacked CMake package.
# The build tree must play no part: the unpacked files find each other
# relative to their own location.
# Usage: deb.sh BUILD_DIR PYTHON
set -euo pipefail
build=$1 python=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

cpack --config "$build/CPackConfig.cmake" -B "$work/package" > "$work/cpack.log" ||
  { cat "$work/cpack.log" >&2; exit 1; }
debs=("$work"/package/touchcloud_*.deb)
[ ${#debs[@]} -eq 1 ] && [ -f "${debs[0]}" ] || { echo "cpack made no single touchcloud_*.deb:" "${debs[@]}" >&2; exit 1; }
deb=${debs[0]}
[ "$(dpkg-deb --field "$deb" Package)" = touchcloud ]
# dpkg-shlibdeps found the libraries the package links (PCL, OpenCV, ...).
dpkg-deb --field "$deb" Depends | grep -q libpcl || { echo "Depends lacks PCL: $(dpkg-deb --field "$deb" Depends)" >&2; exit 1; }

root=$work/root
dpkg -x "$deb" "$root"
usr=$root/usr
share=$usr/share/touchcloud
for f in bin/touchcloud lib/cmake/touchcloud/touchcloudConfig.cmake include/touchcloud/stage.hpp \
         lib/touchcloud/plugins/touchcloud_downsample.so share/touchcloud/pipelines/fox_mask_active.yaml \
         share/touchcloud/sample_clouds/gel_dome.pcd share/touchcloud/models/gs_depthnet_w8.ckpt \
         share/touchcloud/examples/custom_plugin/CMakeLists.txt; do
  [ -e "$usr/$f" ] || { echo "the package lacks /usr/$f" >&2; exit 1; }
done
module=("$usr"/lib/python3/dist-packages/touchcloud*.so)
[ -f "${module[0]}" ] || { echo "the package lacks the Python module in /usr/lib/python3/dist-packages" >&2; exit 1; }

# Nothing from the build tree: no TOUCHCLOUD_PLUGIN_PATH, the work folder as
# the current directory.
unset TOUCHCLOUD_PLUGIN_PATH
cd "$work"
tc=$usr/bin/touchcloud
"$tc" plugins --json > plugins.json
"$python" - "$usr" plugins.json <<'PY'
import json, sys
usr, listing = sys.argv[1], json.load(open(sys.argv[2]))
outside = [p["library"] for p in listing if not p["library"].startswith(usr + "/lib/touchcloud/plugins/")]
assert len(listing) > 20 and not outside, f"{len(listing)} plugins, these from outside the package: {outside}"
PY

# A shipped pipeline, its data found relative to it under share/touchcloud.
"$tc" run "$share/pipelines/downsample_cloud.yaml" --out "$work/cli_run" --quiet > cli_run.log
test -s "$work/cli_run/gel_dome_thinned.ply"

# The Python module, from the unpacked dist-packages.
PYTHONPATH=$usr/lib/python3/dist-packages "$python" - "$usr" "$share/pipelines/downsample_cloud.yaml" <<'PY'
import sys
import touchcloud
usr, pipeline = sys.argv[1], sys.argv[2]
assert touchcloud.__file__.startswith(usr + "/lib/python3/dist-packages/"), touchcloud.__file__
r = touchcloud.run(pipeline, out=None, outputs=["thin.cloud"])
points = r.outputs["thin.cloud"]
assert points.shape[1] == 3 and 0 < points.shape[0] < len(touchcloud.read_cloud(usr + "/share/touchcloud/sample_clouds/gel_dome.pcd")), points.shape
PY

# The out-of-tree plugin example, as shipped, built against the unpacked
# CMake package and loaded by the unpacked CLI.
cmake -S "$share/examples/custom_plugin" -B "$work/plugin" -G Ninja \
      -DCMAKE_PREFIX_PATH="$usr" -DCMAKE_BUILD_TYPE=Release > plugin_configure.log ||
  { cat plugin_configure.log >&2; exit 1; }
grep -q "touchcloud_DIR:PATH=$usr/lib/cmake/touchcloud" "$work/plugin/CMakeCache.txt" ||
  { echo "the example did not find the unpacked package: $(grep touchcloud_DIR "$work/plugin/CMakeCache.txt")" >&2; exit 1; }
cmake --build "$work/plugin" > plugin_build.log || { cat plugin_build.log >&2; exit 1; }
TOUCHCLOUD_PLUGIN_PATH=$work/plugin "$tc" run "$share/examples/custom_plugin/contact_disc.yaml" \
  --out "$work/plugin_run" --quiet > plugin_run.log
grep -q '"disc.points_kept"' "$work/plugin_run/summary.json"
echo "deb: $(basename "$deb") ($(du -k "$deb" | cut -f1) KiB) unpacked; module imported and run, shipped pipeline run, plugin example built and run against it"
