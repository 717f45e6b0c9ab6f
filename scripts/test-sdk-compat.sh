#!/usr/bin/env bash
# The SDK 1.x promise, checked against the sdk-1.0 release (docs/writing-plugins.md,
# "Compatibility"; the reference commit is named in sdk/ABI_REFERENCE):
#  1. the reference's sources (git archive of its commit) are built and installed into a cache
#     folder: its libmechgraph_sdk.so.1 and host library, its SDK headers, its CMake package, its
#     real plugin named below (not its program or its other plugins: the check runs the current
#     host; a stand-in for the program, which refuses to run, is what the package's config finds);
#  2. from them: examples/plugin (out of tree, against the reference's installed package), the
#     reference's C test plugins (tests/test_plugins/c_*.c, against its C headers alone) and one
#     real plugin (sdk/ABI_REFERENCE `real_plugin`, as the reference built it);
#  3. the CURRENT host (BUILD_DIR/bin/mechgraph) loads them, with the current libmechgraph_sdk.so.1,
#     runs `mechgraph plugin-test` on each, the example's scene beside the built-in plugins and the
#     real plugin's scene (`real_scene`) with the reference's plugin in place of the built-in one;
#  4. scripts/sdk-abi-compare.sh: abidiff between the reference's libmechgraph_sdk.so.1 and the
#     current one (new functions and fields appended to growable structs allowed, any other change
#     fails), and the reference's tests/sdk/c_layout_test.cpp compiled against the current headers;
#  5. the pre-1.0 C++ ABI version (abi_version.hpp) is the reference's: a plugin of
#     MECHGRAPH_PLUGIN_1 built against the reference (1.0 to 1.2 did not compile the C++ layer into
#     the plugin, mechgraph::sdk_cxx) calls C++ helpers of libmechgraph_sdk.so.1 with the class
#     layouts it was compiled with.
# The reference's build is kept in BUILD_DIR/sdk-reference/<commit> (MECHGRAPH_SDK_REFERENCE_CACHE
# to put it elsewhere), so later runs only check it is up to date; its compiler cache entries are
# the main build's (same relative layout, CCACHE_BASEDIR).
#   scripts/test-sdk-compat.sh [BUILD_DIR]      (BUILD_DIR built; default: build)
#   MECHGRAPH_SDK_REFERENCE=<commit> scripts/test-sdk-compat.sh   compares with another commit
set -euo pipefail
src=$(cd "$(dirname "$0")/.." && pwd)
build=$(cd "${1:-$src/build}" && pwd)
start=$SECONDS
say() { echo "test-sdk-compat: $*" >&2; }
fail() { say "FAIL: $*"; exit 1; }
step() { say "$1 ($((SECONDS - start)) s)"; }
unset MECHGRAPH_PLUGIN_PATH
mechgraph=$build/bin/mechgraph
[ -x "$mechgraph" ] || fail "no $mechgraph: build the current tree first (scripts/build.sh)"
command -v abidiff >/dev/null || fail "abidiff not found (apt-get install abigail-tools; scripts/install-deps.sh)"

# 1. Which commit is the reference.
reference_file=$src/sdk/ABI_REFERENCE
field() { sed -n "s/^$1:[[:space:]]*//p" "$reference_file" | head -n 1; }
tag=$(field tag)
recorded=$(field commit)
real_plugin=$(field real_plugin)
real_scene=$(field real_scene)
git -C "$src" rev-parse --git-dir >/dev/null 2>&1 || fail "$src is not a git clone: the check builds the reference from the history"
tagged=$(git -C "$src" rev-parse -q --verify "refs/tags/$tag^{commit}" || true)
if [ -n "${MECHGRAPH_SDK_REFERENCE:-}" ]; then
  ref=$(git -C "$src" rev-parse --verify "$MECHGRAPH_SDK_REFERENCE^{commit}") || fail "MECHGRAPH_SDK_REFERENCE=$MECHGRAPH_SDK_REFERENCE is no commit"
  how="MECHGRAPH_SDK_REFERENCE=$MECHGRAPH_SDK_REFERENCE"
elif [[ $recorded =~ ^[0-9a-f]{40}$ ]]; then
  git -C "$src" cat-file -e "$recorded^{commit}" 2>/dev/null ||
    fail "commit $recorded (sdk/ABI_REFERENCE) is not in this clone (a shallow clone? git fetch --unshallow)"
  [ -z "$tagged" ] || [ "$tagged" = "$recorded" ] || fail "tag $tag is commit $tagged, but sdk/ABI_REFERENCE records $recorded"
  ref=$recorded how="recorded in sdk/ABI_REFERENCE"
elif [ -n "$tagged" ]; then
  ref=$tagged how="tag $tag"
else
  [ "$(git -C "$src" rev-parse --is-shallow-repository)" = false ] ||
    fail "a shallow clone without tag $tag: fetch the history (git fetch --unshallow --tags)"
  ref=$(git -C "$src" log -1 --format=%H -G'^commit:' -- sdk/ABI_REFERENCE)
  [ -n "$ref" ] || fail "sdk/ABI_REFERENCE is not committed, and there is no tag $tag"
  how="the commit that last changed the commit: line of sdk/ABI_REFERENCE (no tag $tag in this clone)"
fi
say "reference: $(git -C "$src" log -1 --format='%h %s' "$ref") ($how)"

# 2. The reference's tree, built and installed (cached by commit).
cache_root=${MECHGRAPH_SDK_REFERENCE_CACHE:-$build/sdk-reference}
cache=$cache_root/${ref:0:12}
ref_src=$cache/src
# One reference kept (a build is about 1 GB): the others go, unless a run names its own.
if [ -z "${MECHGRAPH_SDK_REFERENCE:-}" ] && [ -d "$cache_root" ]; then
  find "$cache_root" -mindepth 1 -maxdepth 1 -type d ! -name "${ref:0:12}" -exec rm -rf {} +
fi
prefix=$cache/prefix
if [ ! -f "$cache/.unpacked" ]; then
  rm -rf "$cache"
  mkdir -p "$ref_src"
  git -C "$src" archive --format=tar "$ref" | tar -x -C "$ref_src"
  touch "$cache/.unpacked"
fi
# The build folder one below the source, as build/ is in the main tree: the same relative paths on
# every compiler command line, so ccache answers from the main build's entries.
export CCACHE_BASEDIR=$ref_src CCACHE_NOHASHDIR=1
log=$cache/build.log
# Only what the check uses is built (the libraries, the real plugin: about a third of the tree) and
# installed: the reference's own install() is wrapped, after its project(), to skip the rules of
# the targets not built (its program, its other plugins). Everything else it installs as it did.
# (CMake keeps an overridden command as _install; a rule naming targets of both kinds fails
# loudly, for a reference laid out otherwise than sdk-1.0.)
used_targets="mechgraph mechgraph_sdk_library mechgraph_sdk mechgraph_host $real_plugin"
cat > "$cache/install-used.cmake" <<EOF
# Written by scripts/test-sdk-compat.sh: install the targets the SDK check builds, nothing else.
include_guard(GLOBAL)
function(install)
  if(ARGV0 STREQUAL "TARGETS")
    set(used 0)
    set(unused 0)
    list(SUBLIST ARGV 1 -1 names)
    foreach(name IN LISTS names)
      if(name MATCHES "^[A-Z_]+\$")
        break()  # the first keyword (EXPORT, LIBRARY, DESTINATION, ...) ends the targets
      elseif(name IN_LIST mechgraph_compat_used_targets)
        math(EXPR used "\${used} + 1")
      else()
        math(EXPR unused "\${unused} + 1")
      endif()
    endforeach()
    if(used AND unused)
      message(FATAL_ERROR "test-sdk-compat: install(\${ARGV}) names targets the check builds and others")
    elseif(unused)
      return()
    endif()
  endif()
  _install(\${ARGV})
endfunction()
set(mechgraph_compat_used_targets $used_targets)
EOF
{ cmake -S "$ref_src" -B "$ref_src/build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DMECHGRAPH_BUILD_TESTS=OFF \
    -DMECHGRAPH_PYTHON=OFF -DCMAKE_DISABLE_FIND_PACKAGE_benchmark=ON -DCMAKE_PROJECT_INCLUDE="$cache/install-used.cmake" &&
  cmake --build "$ref_src/build" --parallel "$(nproc)" --target mechgraph mechgraph_sdk_library "$real_plugin" &&
  cmake --install "$ref_src/build" --prefix "$prefix"; } > "$log" 2>&1 || { tail -n 40 "$log" >&2; fail "the reference did not build (log: $log)"; }
# The package's config checks that its program is there (MECHGRAPH_EXECUTABLE); nothing here runs it.
mkdir -p "$prefix/bin"
printf '#!/bin/sh\necho "the sdk-1.0 reference of scripts/test-sdk-compat.sh: its program is not built" >&2\nexit 1\n' > "$prefix/bin/mechgraph"
chmod +x "$prefix/bin/mechgraph"
step "reference built and installed in $cache"

# 3. Plugins from the reference's sources, against the reference's SDK.
plugins=$cache/plugins
mkdir -p "$plugins/example" "$plugins/c" "$plugins/real"
launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
{ cmake -S "$ref_src/examples/plugin" -B "$cache/example-build" -G Ninja -DCMAKE_PREFIX_PATH="$prefix" \
    -DCMAKE_BUILD_TYPE=Release -DBUILD_TESTING=OFF "${launcher[@]}" &&
  cmake --build "$cache/example-build" &&
  cp "$cache/example-build/mechgraph-plugins/mechgraph_example.so" "$plugins/example/"; } > "$cache/example.log" 2>&1 ||
  { cat "$cache/example.log" >&2; fail "the reference's examples/plugin did not build against the reference's package"; }
c_sources=()
for c in "$ref_src"/tests/test_plugins/c_*.c; do
  [ -f "$c" ] || continue
  name=$(basename "$c" .c)
  c_sources+=("$name")
  # As tests/CMakeLists.txt builds them: C11, the C headers alone, no mechgraph library linked.
  if [ ! -f "$plugins/c/mechgraph_test_$name.so" ] || [ "$c" -nt "$plugins/c/mechgraph_test_$name.so" ]; then
    cc -std=c11 -O1 -fPIC -shared -fvisibility=hidden -Wl,--no-undefined -I"$ref_src/sdk/include" "$c" \
      -o "$plugins/c/mechgraph_test_$name.so" -lm || fail "the reference's $name.c did not compile"
  fi
done
real_so=$prefix/lib/mechgraph/plugins/mechgraph_$real_plugin.so
[ -f "$real_so" ] || real_so=$(find "$prefix" -name "mechgraph_$real_plugin.so" -print -quit)
[ -f "$real_so" ] || fail "the reference installed no plugin '$real_plugin' (sdk/ABI_REFERENCE real_plugin)"
cp "$real_so" "$plugins/real/"
real_so=$plugins/real/mechgraph_$real_plugin.so
for p in "$plugins/example/mechgraph_example.so" "$plugins"/c/*.so; do
  nm -D --defined-only "$p" | grep -q ' mechgraph_plugin_entry_1$' || fail "$p does not export the SDK 1.x entry mechgraph_plugin_entry_1"
done
if nm -D --defined-only "$real_so" | grep -q ' mechgraph_plugin_entry_1$'; then
  real_entry="SDK 1.x entry"
else
  real_entry="pre-1.0 C++ entry (ABI $(sed -n 's/^#define MECHGRAPH_PLUGIN_ABI_VERSION //p' "$ref_src/sdk/include/mechgraph/abi_version.hpp"))"
fi
step "built from the reference: examples/plugin, ${#c_sources[@]} C plugins (${c_sources[*]}), $real_plugin ($real_entry)"

# 4. The current host loads them and runs their conformance kit and a scene.
work=$(mktemp -d "${TMPDIR:-/tmp}/mechgraph-sdk-compat.XXXXXX")
trap 'rm -rf "$work"' EXIT
# Which libmechgraph_sdk.so.1 the plugins get: the host's (one per process, by its soname), never
# the reference's that the plugins were linked against.
LD_DEBUG=files "$mechgraph" --plugin-dir "$plugins/example" --plugin-dir "$plugins/c" --plugin-dir "$plugins/real" plugins > "$work/plugins.txt" 2> "$work/ld.txt" ||
  { cat "$work/plugins.txt" "$work/ld.txt" >&2; fail "mechgraph plugins failed with the reference's plugins"; }
if grep -q "file=$cache.*libmechgraph_sdk" "$work/ld.txt"; then
  fail "the reference's libmechgraph_sdk.so.1 was loaded instead of the current one: $(grep "file=$cache" "$work/ld.txt" | head -n 1)"
fi
grep -q "^example 1\." "$work/plugins.txt" || { cat "$work/plugins.txt" >&2; fail "the current host did not load the reference's example plugin"; }
kit() {  # kit NAME ARGS...: plugin-test in the current host, must pass
  local name=$1
  shift
  set +e
  "$mechgraph" plugin-test "$@" > "$work/kit-$name.txt" 2>&1
  local code=$?
  set -e
  [ "$code" = 0 ] || { cat "$work/kit-$name.txt" >&2; fail "plugin-test failed on the reference's $name (exit $code)"; }
  grep -q " 0 failed" "$work/kit-$name.txt" || { cat "$work/kit-$name.txt" >&2; fail "plugin-test printed no summary for $name"; }
  say "plugin-test $name: $(grep -c '^PASS' "$work/kit-$name.txt") checks passed"
}
kit example --strict --continuity example.parabolic_cam=1 "$plugins/example/mechgraph_example.so"
for p in "$plugins"/c/*.so; do
  kit "$(basename "$p" .so)" --strict "$p"
done
# Not --strict: a real plugin's types may have required parameters without examples (the kit then
# skips their evaluation); its scene evaluates them.
kit "$real_plugin" "$real_so"
"$mechgraph" --plugin-dir "$plugins/example" run "$ref_src/examples/plugin/example.yaml" > "$work/run.txt" 2>&1 ||
  { cat "$work/run.txt" >&2; fail "the reference's example scene did not run in the current host"; }
for out in parabolic.max_acceleration cycloidal.max_acceleration valve.max_acceleration slot.play_max; do
  grep -q "$out" "$work/run.txt" || { cat "$work/run.txt" >&2; fail "the example scene did not print $out"; }
done
# The real plugin's scene, beside the current built-in plugins (the folder given first wins: the
# built-in plugin of the same id is skipped); provenance says which file ran.
if [ -n "$real_scene" ]; then
  "$mechgraph" -q --plugin-dir "$plugins/real" run --json "$ref_src/$real_scene" > "$work/real.json" 2> "$work/real.err" ||
    { cat "$work/real.err" >&2; fail "the reference's $real_scene did not run in the current host with its $real_plugin"; }
  ran=$(/usr/bin/python3 -c 'import json, sys; print(json.load(open(sys.argv[1]))["provenance"]["plugins"][sys.argv[2]]["file"])' \
        "$work/real.json" "$real_plugin") || fail "$real_scene: no provenance of plugin $real_plugin"
  [ "$ran" = "$real_so" ] || fail "$real_scene ran $real_plugin from $ran, not the reference's $real_so"
fi
step "current host: the reference's plugins pass plugin-test, its example scene${real_scene:+ and $real_scene} run"

# 5. The SDK library's ABI against the reference's.
if [ ! -s "$cache/reference.abi" ] || [ "$ref_src/build/lib/libmechgraph_sdk.so.1" -nt "$cache/reference.abi" ]; then
  "$ref_src/scripts/abi-dump.sh" "$ref_src/build" "$cache/reference.abi" 2> "$work/abidw-ref.txt" ||
    { rm -f "$cache/reference.abi"; cat "$work/abidw-ref.txt" >&2; fail "abidw failed on the reference's library"; }
fi
"$src/scripts/abi-dump.sh" "$build" "$work/current.abi" 2> "$work/abidw-cur.txt" ||
  { cat "$work/abidw-cur.txt" >&2; fail "abidw failed on the current library"; }
"$src/scripts/sdk-abi-compare.sh" "$cache/reference.abi" "$work/current.abi" "$ref_src/tests/sdk/c_layout_test.cpp" \
  "$src/sdk/include" "$build/sdk/include" || fail "the SDK's C boundary changed incompatibly since the reference (above)"
step "abidiff: libmechgraph_sdk.so.1 compatible with the reference's"

# 6. The C++ helpers' class layouts (see 5. at the top).
abi_of() { sed -n 's/^#define MECHGRAPH_PLUGIN_ABI_VERSION //p' "$1/sdk/include/mechgraph/abi_version.hpp"; }
[ "$(abi_of "$ref_src")" = "$(abi_of "$src")" ] ||
  fail "the pre-1.0 C++ ABI changed since the reference ($(abi_of "$ref_src") -> $(abi_of "$src")): plugins built with MECHGRAPH_PLUGIN_1 at the reference call C++ helpers of libmechgraph_sdk.so.1 with the old class layouts. Keep the layouts: they are part of SDK 1.x (docs/writing-plugins.md, 'Not covered')"
say "PASS in $((SECONDS - start)) s (reference ${ref:0:12}: examples/plugin, C plugins, $real_plugin in the current host; abidiff clean; C++ ABI $(abi_of "$src"))"
