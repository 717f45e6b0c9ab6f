#!/usr/bin/env bash
# A plugin built by another compiler: installs this (gcc-built) build to a temporary prefix, builds
# examples/plugin with clang++ against the installed package (SDK 1.x entry, no build fingerprint),
# and checks that the gcc-built host loads it, that `mechgraph plugin-test` passes both of its
# node types and that its scene runs beside the built-in plugins.
#   scripts/test-sdk-clang.sh [BUILD_DIR]        (CTest runs it as "sdk: ..." when clang++ exists)
set -euo pipefail
src=$(cd "$(dirname "$0")/.." && pwd)
build=$(cd "${1:-$src/build}" && pwd)
clangxx=${CLANGXX:-}
[ -n "$clangxx" ] && [ "$clangxx" != MECHGRAPH_CLANGXX-NOTFOUND ] || clangxx=$(command -v clang++ || true)
[ -n "$clangxx" ] || { echo "test-sdk-clang: no clang++ (apt-get install clang; scripts/install-deps.sh installs it)" >&2; exit 1; }
work=$(mktemp -d "${TMPDIR:-/tmp}/mechgraph-sdk-clang.XXXXXX")
trap 'rm -rf "$work"' EXIT
unset MECHGRAPH_PLUGIN_PATH
fail() { echo "test-sdk-clang: $*" >&2; exit 1; }

cmake --install "$build" --prefix "$work/prefix" > "$work/install.log" 2>&1 || { cat "$work/install.log" >&2; fail "install failed"; }
cmake -S "$src/examples/plugin" -B "$work/example" -DCMAKE_CXX_COMPILER="$clangxx" -DCMAKE_PREFIX_PATH="$work/prefix" \
  -DCMAKE_BUILD_TYPE=Release -DBUILD_TESTING=OFF > "$work/configure.log" 2>&1 || { cat "$work/configure.log" >&2; fail "configure failed"; }
grep -q "The CXX compiler identification is Clang" "$work/configure.log" || fail "CMake did not pick clang++ ($clangxx)"
cmake --build "$work/example" > "$work/build.log" 2>&1 || { cat "$work/build.log" >&2; fail "clang++ could not build the example"; }
plugin=$work/example/mechgraph-plugins/mechgraph_example.so
[ -f "$plugin" ] || fail "no plugin at $plugin"
readelf -p .comment "$plugin" | grep -q clang || fail "the plugin was not built by clang ($(readelf -p .comment "$plugin"))"
mechgraph=$work/prefix/bin/mechgraph

"$mechgraph" --plugin-dir "$work/example/mechgraph-plugins" plugins > "$work/plugins.txt" 2>&1 || true
grep -q "^example 1.0.0" "$work/plugins.txt" || { cat "$work/plugins.txt" >&2; fail "the gcc-built host did not load the clang-built plugin"; }

set +e
"$mechgraph" plugin-test --strict --continuity example.parabolic_cam=1 "$plugin" > "$work/kit.txt" 2>&1
code=$?
set -e
[ "$code" = 0 ] || { cat "$work/kit.txt" >&2; fail "plugin-test failed (exit $code)"; }
grep -q "example.parabolic_cam: .* 0 failed" "$work/kit.txt" || fail "plugin-test did not pass the cam"
grep -q "example.slot_joint: .* 0 failed" "$work/kit.txt" || fail "plugin-test did not pass the joint"

"$mechgraph" --plugin-dir "$work/example/mechgraph-plugins" run "$src/examples/plugin/example.yaml" > "$work/run.txt" 2>&1 ||
  { cat "$work/run.txt" >&2; fail "the example scene did not run"; }
for out in parabolic.max_acceleration valve.max_acceleration slot.play_max; do
  grep -q "$out" "$work/run.txt" || fail "the example scene did not print $out"
done
echo "test-sdk-clang: PASS (clang++ plugin loaded by the gcc host, plugin-test, scene)" >&2
