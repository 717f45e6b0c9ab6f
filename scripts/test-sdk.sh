#!/usr/bin/env bash
# The SDK as a plugin author meets it: runs the tutorial of docs/writing-plugins.md line by line
# (every ```sh block between <!-- tutorial:begin --> and <!-- tutorial:end -->), so the tutorial
# cannot drift from what works: install this build to a temporary prefix, build examples/plugin out
# of tree against the installed package, run its own tests, `mechgraph plugin-test` it, run its
# scene beside the built-in plugins, install it. Then checks what the tutorial only shows.
#   scripts/test-sdk.sh [BUILD_DIR]        (CTest runs it as "sdk: ...")
set -euo pipefail
export MECHGRAPH_SRC
MECHGRAPH_SRC=$(cd "$(dirname "$0")/.." && pwd)
export MECHGRAPH_BUILD
MECHGRAPH_BUILD=$(cd "${1:-$MECHGRAPH_SRC/build}" && pwd)
export WORK
WORK=$(mktemp -d "${TMPDIR:-/tmp}/mechgraph-sdk.XXXXXX")
export PREFIX=$WORK/prefix
trap 'rm -rf "$WORK"' EXIT
# The installed program must find its plugins relative to itself, not in the build tree.
unset MECHGRAPH_PLUGIN_PATH

tutorial=$WORK/tutorial.sh
awk '/<!-- tutorial:begin -->/{on=1} /<!-- tutorial:end -->/{on=0}
     on && /^```sh$/{block=1; next} block && /^```$/{block=0; next} block{print}' \
  "$MECHGRAPH_SRC/docs/writing-plugins.md" > "$tutorial"
steps=$(grep -c . "$tutorial" || true)
if [ "$steps" -lt 6 ]; then
  echo "test-sdk: found only $steps tutorial lines in docs/writing-plugins.md" >&2
  exit 1
fi
echo "test-sdk: running the $steps lines of the tutorial in $WORK" >&2
(cd "$WORK" && bash -euxo pipefail "$tutorial") > "$WORK/tutorial.out" 2> "$WORK/tutorial.err" || {
  cat "$WORK/tutorial.out" "$WORK/tutorial.err" >&2
  echo "test-sdk: the tutorial failed" >&2
  exit 1
}

fail() { echo "test-sdk: $*" >&2; cat "$WORK/tutorial.out" >&2; exit 1; }
plugin=$WORK/my-plugin/build/mechgraph-plugins/mechgraph_example.so
[ -f "$plugin" ] || fail "the example plugin was not built at $plugin"
# Hidden visibility: the plugin exports its entry and nothing of its own (weak symbols of standard
# library templates, which libstdc++ declares visible, may come along: RTTI, make_shared's tag,
# member templates such as `void std::deque<...>::_M_push_back_aux<>()`; mechgraph's interfaces
# have their RTTI in libmechgraph_sdk).
exported=$(nm -DC --defined-only "$plugin" | cut -d' ' -f3- |
  grep -v -E '^((typeinfo|typeinfo name|vtable) for )?([A-Za-z_:<>*&]+ )?std::' || true)
[ "$exported" = "mechgraph_plugin_entry_1" ] || fail "the plugin exports more than its entry: $exported"
# No build path in what was installed: package files, headers, and the data the library, program
# and plugins read at run time (debug information may name the sources; it is not read).
if grep -rlF "$MECHGRAPH_BUILD" "$PREFIX/lib/cmake" "$PREFIX/include" >/dev/null 2>&1; then
  fail "the installed package names the build folder $MECHGRAPH_BUILD"
fi
for f in "$PREFIX"/lib/libmechgraph.so.* "$PREFIX/bin/mechgraph" "$PREFIX"/lib/mechgraph/plugins/*.so; do
  strings_of_f=$(readelf -p .rodata -p .dynstr "$f" 2>/dev/null || true)
  if grep -qF "$MECHGRAPH_BUILD" <<< "$strings_of_f"; then
    fail "$f carries the build folder $MECHGRAPH_BUILD"
  fi
done
# The scene's four outputs, the example's beside the built-ins'.
for out in parabolic.max_acceleration cycloidal.max_acceleration valve.max_acceleration slot.play_max; do
  grep -q "$out" "$WORK/tutorial.out" || fail "the example scene did not print $out"
done
grep -q "example.parabolic_cam: .* 0 failed" "$WORK/tutorial.out" || fail "plugin-test did not pass the cam"
grep -q "example.slot_joint: .* 0 failed" "$WORK/tutorial.out" || fail "plugin-test did not pass the joint"
for t in example.parabolic_cam example.slot_joint; do
  grep -q "PASS  node $t: evaluates with its defaults" "$WORK/tutorial.out" || fail "plugin-test did not evaluate $t"
done
grep -q "PASS  cam_law example.parabolic_cam.law: output max_acceleration is the law's extremum" "$WORK/tutorial.out" ||
  fail "plugin-test did not check the cam's peaks"
# Installed into mechgraph's prefix it is a built-in plugin: listed without --plugin-dir.
# (Into a file first: `grep -q` in a pipe under pipefail would stop the writer with SIGPIPE.)
"$PREFIX/bin/mechgraph" plugins > "$WORK/plugins.txt"
grep -q "^example 1.0.0" "$WORK/plugins.txt" || fail "the installed example is not among the built-in plugins"
# A scene asking for a newer example than installed is refused at load (exit 2), naming both.
sed 's/example: ">=1.0, <2"/example: ">=1.1"/' "$MECHGRAPH_SRC/examples/plugin/example.yaml" > "$WORK/newer.yaml"
set +e
"$PREFIX/bin/mechgraph" run "$WORK/newer.yaml" 2> "$WORK/newer.err"
code=$?
set -e
[ "$code" = 2 ] && grep -q "requires plugin 'example' >=1.1, but the loaded one is 1.0.0" "$WORK/newer.err" ||
  fail "a scene requiring example >=1.1 was not refused as expected (exit $code): $(cat "$WORK/newer.err")"
echo "test-sdk: PASS (tutorial, exported symbols, installed paths, scene, plugin-test, requires)" >&2
