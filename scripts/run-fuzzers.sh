#!/usr/bin/env bash
# Fuzzes the scene boundary with libFuzzer (clang from Debian): the scene loader, the unit
# parser, --set overrides, cam.table's CSV reader, the sweep's --cases reader, the row checker of
# --resume and merge, csv_field and the other writers' escaping, each under AddressSanitizer + UBSan.
#   scripts/run-fuzzers.sh            every target for 60 s (what CI runs)
#   scripts/run-fuzzers.sh 3600       every target for an hour (a long run)
#   scripts/run-fuzzers.sh 600 fuzz_scene
# The seed corpus is tests/fuzz/corpus/<target> (and scenes/ for the loader); what the fuzzer
# adds goes to build-asan/corpus/<target>, never into the repository. A crash leaves its input in
# build-asan/artifacts/ and fails the run: turn it into a regression test (tests/core/...) and
# add the input to the seed corpus.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-60}
shift || true
targets=("$@")
((${#targets[@]})) || targets=(fuzz_scene fuzz_units fuzz_set fuzz_cam_table fuzz_cases fuzz_sweep_rows fuzz_csv_field fuzz_escape fuzz_gnuplot_data)

scripts/install-deps.sh

# The folder of the AddressSanitizer suite (scripts/configure-asan.sh): after scripts/run-sanitized-tests.sh,
# as in CI, the instrumented library is built and only what changed since is compiled.
dir=build-asan
scripts/configure-asan.sh "$dir"
cmake --build "$dir" --parallel "$(nproc)" --target "${targets[@]}" >&2

mkdir -p "$dir"/artifacts
# One target per core at a time (each fuzzer is one process on one core): the same seconds per
# target, in a fraction of the wall clock.
fuzz_one() {
  local t=$1 name=${1#fuzz_}
  local corpus="$dir"/corpus/$name
  mkdir -p "$corpus"
  local seeds=(tests/fuzz/corpus/$name)
  [ "$t" = fuzz_scene ] && seeds+=(scenes)
  # libFuzzer stops itself at -max_total_time and fails an input slower than -timeout; should the
  # process hang all the same (in its own exit, say), timeout ends it and the run fails with its
  # log, rather than CI waiting out its whole limit.
  ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
    timeout -k 30 $((seconds + 120)) "$dir"/fuzz/"$t" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -max_len=8192 \
    -print_final_stats=1 -artifact_prefix="$dir"/artifacts/"$name"- "$corpus" "${seeds[@]}" 2> "$dir"/"$t".log
}
status=0
jobs_at_once=$(nproc)
for t in "${targets[@]}"; do
  while (($(jobs -rp | wc -l) >= jobs_at_once)); do wait -n || true; done
  echo "== $t for ${seconds} s" >&2
  rm -f "$dir"/"$t".status
  (
    code=0
    fuzz_one "$t" || code=$?
    echo "$code" > "$dir"/"$t".status
  ) &
done
wait
for t in "${targets[@]}"; do
  code=$(cat "$dir"/"$t".status 2>/dev/null || echo none)
  if [ "$code" = 124 ] || [ "$code" = 137 ]; then
    echo "!! $t did not end within $((seconds + 120)) s (hung?); killed by timeout, the log in $dir/$t.log:" >&2
    tail -40 "$dir"/"$t".log >&2
    status=1
  elif [ "$code" != 0 ]; then
    echo "!! $t found a problem; its input is in $dir/artifacts/, the log in $dir/$t.log:" >&2
    tail -40 "$dir"/"$t".log >&2
    status=1
  else
    grep -E "stat::number_of_executed_units|stat::peak_rss_mb" "$dir"/"$t".log >&2 || true
  fi
done
exit $status
