#!/usr/bin/env bash
# Configures and builds mechgraph into ./build (Release-with-debug-info, Ninja, ccache when present).
set -euo pipefail
cd "$(dirname "$0")/.."
# Compiler cache entries shared by every build folder one level below the source (build/,
# build-pip/ of pip install) and by copies of the tree elsewhere: paths relative to the source.
export CCACHE_BASEDIR="${CCACHE_BASEDIR:-$PWD}" CCACHE_NOHASHDIR="${CCACHE_NOHASHDIR:-1}"
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo >&2
cmake --build build --parallel "$(nproc)" >&2
