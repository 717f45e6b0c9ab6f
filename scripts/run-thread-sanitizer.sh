#!/usr/bin/env bash
# The tests whose code runs on threads, built with ThreadSanitizer (-O1, in build-tsan/): the
# evaluator's pool with a shared memo cache, sweeps on several workers (in process and through the
# `mechgraph sweep` command, itself instrumented), the Monte Carlo sampler, the conformance kit's
# thread-safety check. A data race or a lock-order inversion fails the run. CI runs it (.ci/run).
# The Python sweeps run the same library code (SceneSession over run_sweep) and are not
# instrumented here: an instrumented extension cannot load into Debian's python3.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
flags="-fsanitize=thread -fno-omit-frame-pointer"
cmake -S . -B build-tsan -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DMECHGRAPH_PYTHON=OFF \
  -DCMAKE_CXX_FLAGS="$flags" -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g" \
  -DCMAKE_EXE_LINKER_FLAGS="$flags" -DCMAKE_SHARED_LINKER_FLAGS="$flags" -DCMAKE_MODULE_LINKER_FLAGS="$flags" >&2
cmake --build build-tsan --parallel "$(nproc)" --target mechgraph_thread_tests >&2
cd build-tsan
# halt_on_error: the first race ends the test program with TSan's exit code (66), failing the run;
# the instrumented `mechgraph` the CLI tests start reports its races the same way.
TSAN_OPTIONS="halt_on_error=1 second_deadlock_stack=1 history_size=4" tests/mechgraph_thread_tests "~[slow]"
