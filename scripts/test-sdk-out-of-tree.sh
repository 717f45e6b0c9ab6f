#!/usr/bin/env bash
# A plugin from outside mechgraph is a first-class citizen of every host (issue 30, item 4): the
# loom plugin of tests/out_of_tree/loom (a new lift law, loom.heddle_law, and a new joint type,
# loom.lever_pivot, with angle frames, units, roles and codes of their own, through the SDK 1.x
# entry) is copied out of the source tree and built against mechgraph installed to a temporary
# prefix (find_package(mechgraph)). With no change to any host it gets:
#   plugin-test (the conformance kit, the law's CamLaw contract included), describe, run (units
#   and the frame tag of each angle, codes by name), report (its figures and tables with their
#   labels, units, frames and codes), sweep (CSV headers with units and frames), Python (values
#   and tables in display units) and bench (its accuracy knob).
# tests/cli/foreign_presentation_test.cpp checks the finer points of declared presentation (derived
# frames, marks, points, notes) on an in-tree plugin; this script checks the whole path from an
# installed package.
#   scripts/test-sdk-out-of-tree.sh [BUILD_DIR]        (CTest runs it as "sdk: ...")
set -euo pipefail
src=$(cd "$(dirname "$0")/.." && pwd)
build=$(cd "${1:-$src/build}" && pwd)
work=$(mktemp -d "${TMPDIR:-/tmp}/mechgraph-oot.XXXXXX")
trap 'rm -rf "$work"' EXIT
unset MECHGRAPH_PLUGIN_PATH PYTHONPATH
fail() { echo "test-sdk-out-of-tree: FAIL: $*" >&2; exit 1; }
expect() {  # expect FILE TEXT WHAT: FILE contains TEXT (fixed string)
  grep -qF -- "$2" "$1" || { cat "$1" >&2; fail "$3: no '$2' in $(basename "$1")"; }
}

prefix=$work/prefix
cmake --install "$build" --prefix "$prefix" > "$work/install.log" 2>&1 || { cat "$work/install.log" >&2; fail "install failed"; }
cp -r "$src/tests/out_of_tree/loom" "$work/loom"
launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
{ cmake -S "$work/loom" -B "$work/loom/build" -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_BUILD_TYPE=Release "${launcher[@]}" &&
  cmake --build "$work/loom/build"; } > "$work/build.log" 2>&1 || { cat "$work/build.log" >&2; fail "the loom plugin did not build against the installed package"; }
plugin_dir=$work/loom/build/mechgraph-plugins
plugin=$plugin_dir/mechgraph_loom.so
nm -D --defined-only "$plugin" | grep -q ' mechgraph_plugin_entry_1$' || fail "the plugin does not export the SDK 1.x entry"
# Built by this compiler from the installed headers, its C++ layer has the host's key (c/object_cxx.h):
# its laws reach the host and the built-in plugins as their C++ objects. A host built by clang has
# no key (detail/cxx_abi_key.hpp), and neither then has the plugin.
host_key=$(grep -m1 '^mechgraph-sdk-.*/headers-' <<< "$(strings "$prefix/lib/libmechgraph.so")" || true)
if [[ -n $host_key ]]; then
  grep -qxF -- "$host_key" <<< "$(strings "$plugin")" || fail "the plugin's C++ layer key is not the host's ($host_key)"
else
  readelf -p .comment "$prefix/lib/libmechgraph.so" 2>/dev/null | grep -q clang ||
    fail "no C++ layer key in the installed libmechgraph, which is not a clang build"
  ! grep -q '^mechgraph-sdk-.*/headers-' <<< "$(strings "$plugin")" || fail "the plugin has a C++ layer key, the clang-built host none"
fi
mg() { "$prefix/bin/mechgraph" -q --plugin-dir "$plugin_dir" "$@"; }
scene=$work/loom/loom.yaml

# The conformance kit, the law's contract included.
mg plugin-test --strict --continuity loom.heddle_law=2 "$plugin" > "$work/kit.txt" 2>&1 || { cat "$work/kit.txt" >&2; fail "plugin-test failed"; }
expect "$work/kit.txt" "loom.heddle_law: " "plugin-test"
grep -q "loom.heddle_law: .* 0 failed" "$work/kit.txt" || fail "plugin-test did not pass loom.heddle_law"
grep -q "loom.lever_pivot: .* 0 failed" "$work/kit.txt" || fail "plugin-test did not pass loom.lever_pivot"
expect "$work/kit.txt" "PASS  cam_law loom.heddle_law.law: output max_acceleration is the law's extremum" "plugin-test"
expect "$work/kit.txt" "presentation: frames declared and acyclic" "plugin-test"

# describe: its frames and presentation.
mg describe loom.heddle_law > "$work/describe.txt"
expect "$work/describe.txt" "drum: drum angle from the top" "describe"
expect "$work/describe.txt" "presented as derivative_family" "describe"
expect "$work/describe.txt" "codes 1 rise_start, 2 top, 3 return_end" "describe"

# run: display units with the frame's tag, codes by name.
mg run "$scene" > "$work/run.txt" || { cat "$work/run.txt" >&2; fail "the scene did not run"; }
expect "$work/run.txt" "mm/deg (drum)" "run: a rate per drum degree"
expect "$work/run.txt" "mm/deg^2 (drum)" "run"
expect "$work/run.txt" "deg (drum)" "run"
expect "$work/run.txt" "deg (swing)" "run"
expect "$work/run.txt" "um" "run: the play in micrometres"
expect "$work/run.txt" "rise_start" "run: the station codes by name"
expect "$work/run.txt" "return_end" "run"
# The numbers in those units: rise_begins = -80 deg (drum); play_max = 6 x 40 um = 240 um;
# max_velocity = 1.875 H / beta = 1.875 x 60 mm / 80 deg = 1.40625 mm/deg.
grep -qE "heddle.rise_begins.* -80(\.0+)? deg \(drum\)" "$work/run.txt" || { cat "$work/run.txt" >&2; fail "run: rise_begins is not -80 deg (drum)"; }
grep -qE "pivot.play_max.* 240(\.0+)? um" "$work/run.txt" || { cat "$work/run.txt" >&2; fail "run: play_max is not 240 um"; }
grep -qE "heddle.max_velocity.* 1\.406[0-9]* mm/deg \(drum\)" "$work/run.txt" || { cat "$work/run.txt" >&2; fail "run: max_velocity is not 1.406 mm/deg (drum)"; }

# report: figures and tables from the declarations.
mg report "$scene" --out "$work/report" > "$work/report.log" 2>&1 || { cat "$work/report.log" >&2; fail "report failed"; }
page=$work/report/report.html
expect "$page" "Heddle lift, lift rate and lift acceleration of heddle" "report: the derivative family's title"
expect "$page" "drum angle [deg (drum)]" "report: the family's axis in its frame"
expect "$page" "lift rate [mm/deg (drum)]" "report: a rate per drum degree"
expect "$page" "lift acceleration [mm/deg^2 (drum)]" "report"
expect "$page" "heddle lift [mm]" "report"
expect "$page" "swing angle [deg (swing)]" "report: the joint's axis in its frame"
expect "$page" "greatest tip play, least tip play [um]" "report: the play in micrometres"
expect "$page" "rise_start (1)" "report: the stations' codes by name"
expect "$page" "return_end (3)" "report"
expect "$work/report/heddle.stations.csv" "kind_name" "report: the code names in the CSV"
expect "$work/report/heddle.stations.csv" ",rise_start," "report: the code names in the CSV"
head -n 1 "$work"/report/plot_*_heddle_motion*.csv > "$work/motion-header.txt"
expect "$work/motion-header.txt" "heddle lift rate [mm/deg (drum)]" "report: the figure's CSV in display units with the frame"

# sweep: a grid over the lift; columns in display units with the frame an angle counts; max_velocity
# = 1.875 H / beta: 0.9375, 1.40625, 1.875 mm/deg for H = 40, 60, 80 mm.
mg sweep "$scene" --vary heddle.heddle_lift=40mm:80mm:3 --outputs heddle.max_velocity,pivot.play_max --out "$work/sweep.csv" \
  > "$work/sweep.log" 2>&1 || { cat "$work/sweep.log" >&2; fail "sweep failed"; }
expect "$work/sweep.csv" "case,heddle.heddle_lift [mm],heddle.max_velocity [mm/deg (drum)]" "sweep: the columns' units and frames"
expect "$work/sweep.csv" "pivot.play_max [um]" "sweep"
/usr/bin/python3 - "$work/sweep.csv" <<'PY' || fail "sweep: the rows are not 0.9375, 1.40625, 1.875 mm/deg"
import csv, sys
rows = list(csv.reader(open(sys.argv[1])))[1:]
assert [round(float(r[2]), 9) for r in rows] == [0.9375, 1.40625, 1.875], rows
PY

# bench: its knob measured.
mg bench "$scene" --node heddle > "$work/bench.txt" 2>&1 || { cat "$work/bench.txt" >&2; fail "bench failed"; }
expect "$work/bench.txt" "within 1e-09: samples = " "bench: the knob measured and a setting recommended"

# Python: the installed module, the plugin loaded from its folder; values and tables in display
# units, the frames angles count and the codes' names.
site=$(dirname "$(dirname "$(find "$prefix" -path '*dist-packages/mechgraph/__init__.py' -print -quit)")")
if [ -d "$site" ] && [ "$site" != . ]; then
  (cd "$work" && PYTHONPATH=$site /usr/bin/python3 - "$plugin_dir" "$scene" > "$work/python.txt" 2>&1) <<'PY' || { cat "$work/python.txt" >&2; fail "Python"; }
import sys
import mechgraph
mechgraph.load_plugins([sys.argv[1]])
r = mechgraph.Scene.load(sys.argv[2]).run()
assert r.display_unit("heddle.max_velocity").startswith("mm/deg"), r.display_unit("heddle.max_velocity")
assert abs(r.value("heddle.max_velocity", units="display") - 1.40625) < 1e-9
assert abs(r.value("pivot.play_max", units="display") - 240.0) < 1e-9
stations = r.table("heddle.stations")
assert list(stations["kind"]) == [1.0, 2.0, 3.0], stations
assert list(stations["kind_name"]) == ["rise_start", "top", "return_end"], stations
assert r.quantity("heddle.max_velocity").frame == "drum", r.quantity("heddle.max_velocity")
motion = r.table("heddle.heddle_motion", units="display")
assert list(motion.columns) == ["drum_angle [deg (drum)]", "heddle_lift [mm]", "lift_rate [mm/deg (drum)]", "lift_accel [mm/deg^2 (drum)]"], list(motion.columns)
assert len(motion) == 121
print("python ok")
PY
  expect "$work/python.txt" "python ok" "Python"
elif compgen -G "$build/lib/python3*/dist-packages/mechgraph/_core*.so" > /dev/null; then
  fail "the build has the Python module but the installed package has none"
else
  # A build without the module (-DMECHGRAPH_PYTHON=OFF, or pybind11 missing: then a CTest test
  # "python: the module is built" fails, python/CMakeLists.txt).
  echo "test-sdk-out-of-tree: this build has no Python module; Python not checked" >&2
fi
echo "test-sdk-out-of-tree: PASS (installed package, SDK 1.x entry, plugin-test, describe, run, report, sweep, bench, Python)" >&2
