#!/usr/bin/env bash
# A plugin built by another compiler and another C++ standard library: installs this (gcc-built,
# libstdc++) build to a temporary prefix and builds examples/plugin against the installed package
# with clang++ twice, with its default standard library (libstdc++) and with -stdlib=libc++ (LLVM's,
# which shares nothing with the host's). For each, the gcc-built host must load it, `mechgraph
# plugin-test` must pass both of its node types and its scene must run beside the built-in plugins.
# The libc++ build also runs the example's own conformance test program, and its plugin must need
# libc++ and not libstdc++ (readelf -d), import from libmechgraph_sdk.so.1 only C functions (mg_*)
# and no C++ symbol of namespace mechgraph (the SDK's C++ layer is compiled into it), and export
# only its entry: the proof that no C++ type crosses the boundary.
#   scripts/test-sdk-clang.sh [BUILD_DIR]        (CTest runs it as "sdk: ...")
# Needs clang++ and libc++ (Debian: clang libc++-dev libc++abi-dev; scripts/install-deps.sh).
set -euo pipefail
src=$(cd "$(dirname "$0")/.." && pwd)
build=$(cd "${1:-$src/build}" && pwd)
say() { echo "test-sdk-clang: $*" >&2; }
fail() { say "$*"; exit 1; }
clangxx=${CLANGXX:-}
[ -n "$clangxx" ] && [ "$clangxx" != MECHGRAPH_CLANGXX-NOTFOUND ] || clangxx=$(command -v clang++ || true)
[ -n "$clangxx" ] || fail "no clang++ (apt-get install clang; scripts/install-deps.sh installs it)"
work=$(mktemp -d "${TMPDIR:-/tmp}/mechgraph-sdk-clang.XXXXXX")
trap 'rm -rf "$work"' EXIT
unset MECHGRAPH_PLUGIN_PATH
# libc++ is there when clang++ can link a program against it.
printf '#include <string>\nint main() { return std::string("x").size() == 1 ? 0 : 1; }\n' > "$work/probe.cpp"
"$clangxx" -std=c++20 -stdlib=libc++ "$work/probe.cpp" -o "$work/probe" > "$work/probe.log" 2>&1 ||
  { cat "$work/probe.log" >&2; fail "clang++ cannot build with -stdlib=libc++ (apt-get install libc++-dev libc++abi-dev; scripts/install-deps.sh installs them)"; }

cmake --install "$build" --prefix "$work/prefix" > "$work/install.log" 2>&1 || { cat "$work/install.log" >&2; fail "install failed"; }
mechgraph=$work/prefix/bin/mechgraph
launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)

# check LABEL STDLIB_FLAG BUILD_TESTING: builds examples/plugin from the installed package, loads it
# into the gcc-built host, plugin-test, its scene; prints the plugin's path.
check() {
  local label=$1 flag=$2 testing=$3 dir=$work/example-$1
  cmake -S "$src/examples/plugin" -B "$dir" -G Ninja -DCMAKE_CXX_COMPILER="$clangxx" -DCMAKE_CXX_FLAGS="$flag" \
    -DCMAKE_PREFIX_PATH="$work/prefix" -DCMAKE_BUILD_TYPE=Release -DBUILD_TESTING="$testing" "${launcher[@]}" \
    > "$work/configure-$label.log" 2>&1 || { cat "$work/configure-$label.log" >&2; fail "$label: configure failed"; }
  grep -q "The CXX compiler identification is Clang" "$work/configure-$label.log" || fail "$label: CMake did not pick clang++ ($clangxx)"
  cmake --build "$dir" > "$work/build-$label.log" 2>&1 || { cat "$work/build-$label.log" >&2; fail "$label: clang++ could not build the example"; }
  local plugin=$dir/mechgraph-plugins/mechgraph_example.so
  [ -f "$plugin" ] || fail "$label: no plugin at $plugin"
  readelf -p .comment "$plugin" | grep -q clang || fail "$label: the plugin was not built by clang ($(readelf -p .comment "$plugin"))"
  if [ "$testing" = ON ]; then
    ctest --test-dir "$dir" --output-on-failure > "$work/ctest-$label.log" 2>&1 ||
      { cat "$work/ctest-$label.log" >&2; fail "$label: the example's own conformance test failed"; }
  fi

  "$mechgraph" --plugin-dir "$dir/mechgraph-plugins" plugins > "$work/plugins-$label.txt" 2>&1 || true
  grep -q "^example 1.0.0" "$work/plugins-$label.txt" || { cat "$work/plugins-$label.txt" >&2; fail "$label: the gcc-built host did not load the clang-built plugin"; }
  set +e
  "$mechgraph" plugin-test --strict --continuity example.parabolic_cam=1 "$plugin" > "$work/kit-$label.txt" 2>&1
  local code=$?
  set -e
  [ "$code" = 0 ] || { cat "$work/kit-$label.txt" >&2; fail "$label: plugin-test failed (exit $code)"; }
  grep -q "example.parabolic_cam: .* 0 failed" "$work/kit-$label.txt" || fail "$label: plugin-test did not pass the cam"
  grep -q "example.slot_joint: .* 0 failed" "$work/kit-$label.txt" || fail "$label: plugin-test did not pass the joint"
  "$mechgraph" --plugin-dir "$dir/mechgraph-plugins" run "$src/examples/plugin/example.yaml" > "$work/run-$label.txt" 2>&1 ||
    { cat "$work/run-$label.txt" >&2; fail "$label: the example scene did not run"; }
  for out in parabolic.max_acceleration valve.max_acceleration slot.play_max; do
    grep -q "$out" "$work/run-$label.txt" || fail "$label: the example scene did not print $out"
  done
  say "$label: loaded by the gcc host, plugin-test passed ($(grep -c '^PASS' "$work/kit-$label.txt") checks), scene ran"
}

check libstdcxx "" OFF
check libcxx "-stdlib=libc++" ON
plugin=$work/example-libcxx/mechgraph-plugins/mechgraph_example.so
needed=$(readelf -d "$plugin" | sed -n 's/.*(NEEDED).*\[\(.*\)\]/\1/p')
grep -q '^libc++\.so' <<< "$needed" || fail "libcxx: the plugin does not need libc++: $(echo $needed)"
! grep -q '^libstdc++' <<< "$needed" || fail "libcxx: the plugin needs libstdc++: $(echo $needed)"
# What it imports from libmechgraph_sdk.so.1: C functions only.
from_sdk=$(nm -D --undefined-only "$plugin" | sed -n 's/.* \([^ ]*\)@MECHGRAPH_SDK_.*/\1/p')
[ -n "$from_sdk" ] || fail "libcxx: the plugin imports nothing from libmechgraph_sdk.so.1 (is it linked?)"
not_c=$(grep -v '^mg_[A-Za-z0-9_]*$' <<< "$from_sdk" || true)
[ -z "$not_c" ] || fail "libcxx: the plugin imports from libmechgraph_sdk.so.1 more than mg_* functions: $(echo $not_c)"
cxx_mechgraph=$(nm -D --undefined-only "$plugin" | c++filt | grep -E '(^|[ :<(])mechgraph::' || true)
[ -z "$cxx_mechgraph" ] || fail "libcxx: the plugin imports C++ symbols of namespace mechgraph: $cxx_mechgraph"
exported=$(nm -D --defined-only "$plugin" | awk '{print $3}')
[ "$exported" = mechgraph_plugin_entry_1 ] || fail "libcxx: the plugin exports more than its entry: $(echo $exported)"
say "libcxx: needs $(grep '^libc++' <<< "$needed" | tr '\n' ' ')and no libstdc++; imports from libmechgraph_sdk.so.1 only $(echo $from_sdk); exports only its entry"
say "PASS (examples/plugin by clang++ with libstdc++ and with libc++ in the gcc host: plugin-test, scene)"
