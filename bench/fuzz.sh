#!/usr/bin/env bash
# Builds the libFuzzer targets (CMake preset "fuzz": Clang 14, -fsanitize=fuzzer,address,undefined over
# every tumble library) and runs each for SECONDS, starting from its seed corpus (fuzz/corpus/TARGET)
# with its dictionary (fuzz/TARGET.dict). Prints per target: inputs run, execs/s, coverage (edges) and
# features, corpus size, findings. A finding (crash, sanitizer report, leak, timeout, out-of-memory,
# an exception other than tumble::Error, a broken contract) is saved under build/fuzz/findings/TARGET/
# and makes the exit status 1. New inputs go to build/fuzz/corpus/TARGET (never into the repository).
#
#   bash bench/fuzz.sh SECONDS [TARGET...]       e.g. bash bench/fuzz.sh 300 fuzz_ply
#
# Reproduce a finding: build/fuzz/bin/TARGET build/fuzz/findings/TARGET/crash-...; minimise it:
# build/fuzz/bin/TARGET -minimize_crash=1 -runs=10000 FILE. scripts/test.sh runs this for 5 s each.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:?usage: bench/fuzz.sh SECONDS [TARGET...]}
shift
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(fuzz_scene fuzz_obj fuzz_off fuzz_ply fuzz_stl fuzz_mass fuzz_robot)

bash scripts/install-deps.sh >/dev/null
command -v clang++ >/dev/null || ln -sf /usr/bin/clang++-14 /usr/local/bin/clang++
cmake --preset fuzz >/dev/null
build_targets=()
for t in "${targets[@]}"; do build_targets+=(--target "$t"); done
nice cmake --build --preset fuzz -j "$(nproc)" "${build_targets[@]}"

bin=$PWD/build/fuzz/bin
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:allocator_may_return_null=0}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
status=0
printf '%-11s %9s %8s %6s %6s %7s  %s\n' target runs execs/s cov ft corpus findings
for t in "${targets[@]}"; do
  case "$t" in
    fuzz_scene | fuzz_robot) max_len=8192 ;;
    fuzz_mass) max_len=2048 ;;
    *) max_len=4096 ;;
  esac
  corpus=$PWD/build/fuzz/corpus/$t
  findings=$PWD/build/fuzz/findings/$t
  log=build/fuzz/logs/$t.log
  mkdir -p "$corpus" "$findings" build/fuzz/logs
  before=$(find "$findings" -type f | wc -l)
  # -timeout: one input taking longer is a hang; -rss_limit_mb/-malloc_limit_mb: memory a file of
  # max_len bytes can never justify. Crashes stop the run (libFuzzer's default) and are kept.
  run_status=0
  nice "$bin/$t" -max_total_time="$seconds" -max_len=$max_len -timeout=10 -rss_limit_mb=2048 \
    -malloc_limit_mb=1024 -dict="$PWD/fuzz/$t.dict" -artifact_prefix="$findings/" -print_final_stats=1 \
    "$corpus" "$PWD/fuzz/corpus/$t" >"$log" 2>&1 || run_status=$?
  after=$(find "$findings" -type f | wc -l)
  runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  rate=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log" | tail -1)
  last=$(grep -E '^#[0-9]+' "$log" | tail -1 || true)
  cov=$(sed -nE 's/.* cov: ([0-9]+).*/\1/p' <<<"$last")
  ft=$(sed -nE 's/.* ft: ([0-9]+).*/\1/p' <<<"$last")
  size=$(find "$corpus" -type f | wc -l)
  new=$((after - before))
  if [ "$run_status" -ne 0 ] || [ "$new" -gt 0 ]; then
    status=1
    what=$(grep -m1 -E '^(==[0-9]+==ERROR|SUMMARY|.*runtime error|fuzz: contract|terminate called)' "$log" || true)
    printf '%-11s %9s %8s %6s %6s %7s  %s\n' "$t" "${runs:-?}" "${rate:-?}" "${cov:-?}" "${ft:-?}" "$size" \
      "$new new in $findings (exit $run_status): ${what:-see $log}"
  else
    printf '%-11s %9s %8s %6s %6s %7s  %s\n' "$t" "${runs:-?}" "${rate:-?}" "${cov:-?}" "${ft:-?}" "$size" none
  fi
done
exit $status
