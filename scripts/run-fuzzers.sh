#!/usr/bin/env bash
# Fuzzes the scene boundary with libFuzzer (clang from Debian): the scene loader, the unit
# parser, --set overrides, cam.table's CSV reader, the sweep's --cases reader, the row checker of
# --resume and merge, csv_field and the other writers' escaping, each under AddressSanitizer + UBSan.
#   scripts/run-fuzzers.sh            every target for 60 s (what CI runs)
#   scripts/run-fuzzers.sh 3600       every target for an hour (a long run)
#   scripts/run-fuzzers.sh 600 fuzz_scene
# The seed corpus is tests/fuzz/corpus/<target> (and scenes/ for the loader); what the fuzzer
# adds goes to build-fuzz/corpus/<target>, never into the repository. A crash leaves its input in
# build-fuzz/artifacts/ and fails the run: turn it into a regression test (tests/core/...) and
# add the input to the seed corpus.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-60}
shift || true
targets=("$@")
((${#targets[@]})) || targets=(fuzz_scene fuzz_units fuzz_set fuzz_cam_table fuzz_cases fuzz_sweep_rows fuzz_csv_field fuzz_escape fuzz_gnuplot_data)

scripts/install-deps.sh

flags="-fsanitize=address,undefined,fuzzer-no-link -fno-omit-frame-pointer -fno-sanitize-recover=undefined -O1"
link="-fsanitize=address,undefined"
# Line tables only: the Debug type's own -g comes after CMAKE_CXX_FLAGS, so it is replaced, not added to.
cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_COMPILER=clang++ \
  -DMECHGRAPH_FUZZ=ON -DMECHGRAPH_BUILD_TESTS=OFF -DCMAKE_CXX_FLAGS="$flags" -DCMAKE_CXX_FLAGS_DEBUG="-g1" \
  -DCMAKE_EXE_LINKER_FLAGS="$link" -DCMAKE_SHARED_LINKER_FLAGS="$link" -DCMAKE_MODULE_LINKER_FLAGS="$link" >&2
cmake --build build-fuzz --parallel "$(nproc)" --target "${targets[@]}" >&2

mkdir -p build-fuzz/artifacts
# One target per core at a time (each fuzzer is one process on one core): the same seconds per
# target, in a fraction of the wall clock.
fuzz_one() {
  local t=$1 name=${1#fuzz_}
  local corpus=build-fuzz/corpus/$name
  mkdir -p "$corpus"
  local seeds=(tests/fuzz/corpus/$name)
  [ "$t" = fuzz_scene ] && seeds+=(scenes)
  # libFuzzer stops itself at -max_total_time and fails an input slower than -timeout; should the
  # process hang all the same (in its own exit, say), timeout ends it and the run fails with its
  # log, rather than CI waiting out its whole limit.
  ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
    timeout -k 30 $((seconds + 120)) build-fuzz/fuzz/"$t" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -max_len=8192 \
    -print_final_stats=1 -artifact_prefix=build-fuzz/artifacts/"$name"- "$corpus" "${seeds[@]}" 2> build-fuzz/"$t".log
}
status=0
jobs_at_once=$(nproc)
for t in "${targets[@]}"; do
  while (($(jobs -rp | wc -l) >= jobs_at_once)); do wait -n || true; done
  echo "== $t for ${seconds} s" >&2
  rm -f build-fuzz/"$t".status
  (
    code=0
    fuzz_one "$t" || code=$?
    echo "$code" > build-fuzz/"$t".status
  ) &
done
wait
for t in "${targets[@]}"; do
  code=$(cat build-fuzz/"$t".status 2>/dev/null || echo none)
  if [ "$code" = 124 ] || [ "$code" = 137 ]; then
    echo "!! $t did not end within $((seconds + 120)) s (hung?); killed by timeout, the log in build-fuzz/$t.log:" >&2
    tail -40 build-fuzz/"$t".log >&2
    status=1
  elif [ "$code" != 0 ]; then
    echo "!! $t found a problem; its input is in build-fuzz/artifacts/, the log in build-fuzz/$t.log:" >&2
    tail -40 build-fuzz/"$t".log >&2
    status=1
  else
    grep -E "stat::number_of_executed_units|stat::peak_rss_mb" build-fuzz/"$t".log >&2 || true
  fi
done
exit $status
