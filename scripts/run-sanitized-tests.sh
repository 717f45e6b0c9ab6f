#!/usr/bin/env bash
# The whole test suite once more, built by clang with AddressSanitizer and UndefinedBehaviorSanitizer
# (Debug, -O1) in build-asan/ (or the folder given): a memory error, a leak or undefined behaviour
# fails the run. clang, not the README's gcc: it compiles the instrumented files in about half the
# time (this is CI's largest build), and the suite then also runs as a clang build (the C++
# shortcut between plugins is off there, detail/cxx_abi_key.hpp; the README's gcc build tests it).
#   scripts/run-sanitized-tests.sh [BUILD_DIR]
# CI runs it after the README's test command (.ci/run); it takes a few minutes more than that.
# The folder is configured by scripts/configure-asan.sh, shared with the fuzzers (CI builds the
# instrumented library once; this builds the fuzz targets too, the fuzzers only run them).
# The SDK packaging test (label sdk) is left out: it builds an uninstrumented plugin project against
# this instrumented library, which ASan cannot run; the README test command runs it. So is the one
# slow docs test (label docs-slow): it replays the README's 1000-sample study listing through the
# CLI, a minute uninstrumented, paths the instrumented study tests run on fewer samples. So are the
# two walks of the simulating nodes' parameter limits (dynamics, float speed): six minutes of ODE
# integration instrumented, a third of this suite's time, on code the other walks and the dynamics
# tests run instrumented at fewer points; the README command runs them. The Python
# module is not built here (an instrumented extension cannot load into Debian's uninstrumented
# python3); its C++ is the library the C++ tests run instrumented, and the README command runs its tests.
set -euo pipefail
dir=$(realpath -m "${1:-$(dirname "$0")/../build-asan}")
cd "$(dirname "$0")/.."
scripts/install-deps.sh
scripts/configure-asan.sh "$dir"
cmake --build "$dir" --parallel "$(nproc)" >&2
cd "$dir"
# LeakSanitizer does not walk threads' TLS for roots (use_tls=0): its tracer (gcc 12's runtime, when
# this suite was built by gcc) crashed walking TLS at the exit of `report --pdf` run by the test binary ("Tracer caught signal
# 11"; it began when the SDK 1.x bridge's thread_local sets came into the plugins; the same
# command run by hand passes). Without TLS roots a block held only from TLS would be reported as a
# leak: the check can only report more, never fewer.
ASAN_OPTIONS=detect_leaks=1:abort_on_error=1:allocator_may_return_null=1 LSAN_OPTIONS=use_tls=0 \
  UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
  ctest --output-on-failure --parallel "$(nproc)" --timeout 900 --label-exclude 'sdk|docs-slow' \
    --exclude-regex 'of the simulating nodes \(dynamics, float speed\)'
