#!/usr/bin/env bash
# The tests whose code runs on threads, built with ThreadSanitizer (-O1, in build-tsan/): the
# evaluator's pool with a shared memo cache, sweeps on several workers (in process and through the
# `mechgraph sweep` command, itself instrumented), the Monte Carlo sampler, the conformance kit's
# thread-safety check. A data race or a lock-order inversion fails the run. CI runs it (.ci/run).
# Then the Python sweeps and runs (test_sweep.py, test_interrupt.py): the instrumented extension
# loads into Debian's python3 with TSan's runtime preloaded (Python itself is not instrumented, so
# only races in mechgraph's code are seen).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
flags="-fsanitize=thread -fno-omit-frame-pointer"
cmake -S . -B build-tsan -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DMECHGRAPH_PYTHON=ON \
  -DCMAKE_CXX_FLAGS="$flags" -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1" \
  -DCMAKE_EXE_LINKER_FLAGS="$flags" -DCMAKE_SHARED_LINKER_FLAGS="$flags" -DCMAKE_MODULE_LINKER_FLAGS="$flags" >&2
cmake --build build-tsan --parallel "$(nproc)" --target mechgraph_thread_tests mechgraph_python >&2
cd build-tsan
# halt_on_error: the first race ends the test program with TSan's exit code (66), failing the run;
# the instrumented `mechgraph` the CLI tests start reports its races the same way.
# A deadlock would hang the run: timeout ends it (exit 124), its output shown, rather than CI
# waiting out its whole limit with nothing said.
bounded() {
  local code=0
  timeout -k 30 1800 "$@" || code=$?
  if [ "$code" = 124 ] || [ "$code" = 137 ]; then echo "run-thread-sanitizer: $* did not end within 1800 s (hung?)" >&2; fi
  return "$code"
}
TSAN_OPTIONS="halt_on_error=1 second_deadlock_stack=1 history_size=4" bounded tests/mechgraph_thread_tests "~[slow]"
tsan_runtime=$(g++ -print-file-name=libtsan.so)
LD_PRELOAD="$tsan_runtime" TSAN_OPTIONS="halt_on_error=1 report_signal_unsafe=0" \
  PYTHONPATH="$PWD/lib/python3.11/dist-packages" MECHGRAPH_SOURCE_DIR="$PWD/.." MECHGRAPH_BINARY_DIR="$PWD" \
  MPLBACKEND=Agg PYTHONDONTWRITEBYTECODE=1 \
  bounded /usr/bin/python3 -m pytest -q -p no:cacheprovider ../python/tests/test_sweep.py ../python/tests/test_interrupt.py
