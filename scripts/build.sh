#!/usr/bin/env bash
# Configures and builds mechgraph into ./build (Release-with-debug-info, Ninja, ccache when present).
set -euo pipefail
cd "$(dirname "$0")/.."
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo >&2
cmake --build build --parallel "$(nproc)" >&2
