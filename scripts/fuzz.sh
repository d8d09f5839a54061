#!/usr/bin/env bash
# Builds groom's libFuzzer targets (clang -fsanitize=fuzzer,address,undefined; see fuzz/) and runs
# each for a bounded time on the generated seed corpus plus every regression input ever found.
#
#   bash scripts/fuzz.sh                     # every target, 5 s each
#   bash scripts/fuzz.sh --seconds 600 usda  # one target for ten minutes
#
# The working corpus grows in $GROOM_SANITIZE_BUILD_DIR/fuzz-corpus/<target> across runs; a crash
# leaves its input in .../fuzz-artifacts/ and the script exits 1. Make every crash a test in
# tests/kernel/regression_test.cpp (input under tests/data/regressions/<target>/).
set -euo pipefail
seconds=5
targets=()
while (($#)); do
  case "$1" in
    --seconds) seconds=$2; shift 2 ;;
    --seconds=*) seconds=${1#*=}; shift ;;
    -h|--help) sed -n '2,11p' "$0"; exit 0 ;;
    *) targets+=("$1"); shift ;;
  esac
done
all=(usda obj_curves ply_curves hair obj_mesh ply_mesh off stl cli_args parse_floats)
((${#targets[@]})) || targets=("${all[@]}")

source "$(dirname "${BASH_SOURCE[0]}")/sanitize-env.sh"
configure_sanitize_build
build_targets=(make_fuzz_corpus)
for t in "${targets[@]}"; do build_targets+=("${t}_fuzz"); done
cmake --build "$sbuild" -j "$jobs" --target "${build_targets[@]}" 2>&1 | grep -E 'error|warning: unused' || true
cmake --build "$sbuild" -j "$jobs" --target "${build_targets[@]}" >/dev/null

seeds=$sbuild/fuzz-seeds
rm -rf "$seeds"
# Fuzzing must not leak: LeakSanitizer would stop the run at exit; the readers hold no globals.
"$sbuild/fuzz/make_fuzz_corpus" "$seeds" 2>/dev/null
mkdir -p "$sbuild/fuzz-artifacts"

printf '%-13s %10s %8s %8s  %s\n' target executions exec/s corpus result
failed=0
for t in "${targets[@]}"; do
  work=$sbuild/fuzz-corpus/$t
  mkdir -p "$work" "$seeds/$t"
  dirs=("$work" "$seeds/$t")
  [[ -d $root/tests/data/regressions/$t ]] && dirs+=("$root/tests/data/regressions/$t")
  extra=()
  [[ -f $seeds/$t.dict ]] && extra+=(-dict="$seeds/$t.dict")
  log=$sbuild/fuzz-artifacts/$t.log
  # -timeout: one input taking over 10 s is a hang; -rss_limit_mb / -malloc_limit_mb: a reader that
  # believes a header's absurd count and allocates for it is a crash, not a slow run.
  set +e
  "$sbuild/fuzz/${t}_fuzz" "${dirs[@]}" "${extra[@]}" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
    -malloc_limit_mb=1024 -max_len=65536 -print_final_stats=1 -artifact_prefix="$sbuild/fuzz-artifacts/$t-" >"$log" 2>&1
  rc=$?
  set -e
  execs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$' || echo 0)
  rate=$(grep -o 'stat::average_exec_per_sec: *[0-9]*' "$log" | grep -o '[0-9]*$' || echo 0)
  corpus=$(find "$work" -type f | wc -l)
  if ((rc == 0)); then result=ok; else result="CRASH (see $log)"; failed=1; fi
  printf '%-13s %10s %8s %8s  %s\n' "$t" "${execs:-0}" "${rate:-0}" "$corpus" "$result"
done
exit $failed
