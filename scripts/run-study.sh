#!/usr/bin/env bash
# The main job: install what building needs, build the program and its plugins only (the test
# suite, the Python module and the benchmarks are left to scripts/run-tests.sh), and run the
# valve-train cam comparison.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh --study
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo >&2
cmake --build build --parallel "$(nproc)" --target mechgraph_cli followers cams springs valvetrain fits joints backlash >&2
./build/bin/mechgraph run scenes/valvetrain_cams.yaml "$@"
