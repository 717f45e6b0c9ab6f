#!/usr/bin/env bash
# The main job: install dependencies, build, and run the valve-train cam comparison.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
scripts/build.sh
./build/bin/mechgraph run scenes/valvetrain_cams.yaml "$@"
