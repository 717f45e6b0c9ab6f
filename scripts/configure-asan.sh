#!/usr/bin/env bash
# Configures the clang AddressSanitizer + UBSan build both heavy checks use, in the folder given
# (default build-asan/): the test suite (scripts/run-sanitized-tests.sh) and the libFuzzer targets
# (scripts/run-fuzzers.sh). One configuration for both, so that CI builds the instrumented library
# and plugins once: the fuzzers' coverage instrumentation (-fsanitize=fuzzer-no-link) is in the
# library the tests run too; it changes what is counted, not what runs (the callbacks are the
# sanitizer runtime's no-ops outside a fuzzer). The code no fuzz target reaches, the numerical
# nodes and the evaluator, is left out of the counters (MECHGRAPH_FUZZ_COVERAGE_IGNORE,
# tests/fuzz/coverage_ignore.txt): with them the suite ran a quarter slower.
#   scripts/configure-asan.sh [BUILD_DIR]
set -euo pipefail
dir=$(realpath -m "${1:-$(dirname "$0")/../build-asan}")
cd "$(dirname "$0")/.."
sanitizers="-fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined"
# Line tables only (-g1, the Debug type's -g replaced, not added to): a report still names file and
# line of every frame, and the build of a cold machine is about a quarter faster than with -g.
# The test programs' own files at -O0 and without the fuzzers' coverage (MECHGRAPH_TEST_COMPILE_OPTIONS;
# clang would then call the ignore list unused in every one): instrumented, they are the slowest
# part of CI's builds, and -O0 compiles them in about 40 % less time; the code they test stays at -O1.
cmake -S . -B "$dir" -G Ninja -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=Debug \
  -DMECHGRAPH_PYTHON=OFF -DMECHGRAPH_BENCH=OFF -DMECHGRAPH_FUZZ=ON -DMECHGRAPH_FUZZ_COVERAGE_IGNORE=ON \
  -DCMAKE_CXX_FLAGS="$sanitizers -fsanitize=fuzzer-no-link -O1" -DCMAKE_CXX_FLAGS_DEBUG="-g1" \
  -DMECHGRAPH_TEST_COMPILE_OPTIONS="-O0;-g1;-fno-sanitize=fuzzer-no-link;-Wno-unused-command-line-argument" \
  -DCMAKE_EXE_LINKER_FLAGS="$sanitizers" -DCMAKE_SHARED_LINKER_FLAGS="$sanitizers" -DCMAKE_MODULE_LINKER_FLAGS="$sanitizers" >&2
