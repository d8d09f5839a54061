#!/usr/bin/env bash
# Builds groom's libFuzzer targets (clang -fsanitize=fuzzer,address,undefined; see fuzz/) and runs
# each for a bounded time on the generated seed corpus plus every regression input ever found.
#
#   bash scripts/fuzz.sh                     # every target, 5 s each
#   bash scripts/fuzz.sh --seconds 600 usda  # one target for ten minutes
#   bash scripts/fuzz.sh --op-seconds 40     # target `ops` (every op command, drawn per input) 40 s
#   bash scripts/fuzz.sh --seconds 300 op_braid   # one op command for five minutes
#   bash scripts/fuzz.sh --write-op-seeds    # regenerate fuzz/seeds/ (the op targets' checked-in seeds)
#
# `ops` and op_<command> run fuzz/ops_fuzz.cpp (one binary for every op command); op_<command> sets
# GROOM_FUZZ_OP=<command> and keeps its own corpus. The default list has `ops` (one start-up for
# all commands, so CI pays it once); --op-seconds sets the time of `ops` and op_* targets.
# The op targets also start from fuzz/seeds/<target> (checked in; inputs that reach each command and
# exit 0, written by the harness itself: --write-op-seeds, to redo whenever ops_fuzz.cpp changes how
# it reads its bytes). The working corpus grows in $GROOM_SANITIZE_BUILD_DIR/fuzz-corpus/<target>
# across runs; a crash leaves its input in .../fuzz-artifacts/ and the script exits 1. Make every
# crash a test in tests/kernel/regression_test.cpp (input under tests/data/regressions/<target>/).
set -euo pipefail
seconds=5
op_seconds=
write_seeds=0
targets=()
while (($#)); do
  case "$1" in
    --seconds) seconds=$2; shift 2 ;;
    --seconds=*) seconds=${1#*=}; shift ;;
    --op-seconds) op_seconds=$2; shift 2 ;;
    --op-seconds=*) op_seconds=${1#*=}; shift ;;
    --write-op-seeds) write_seeds=1; shift ;;
    -h|--help) sed -n '2,19p' "$0"; exit 0 ;;
    *) targets+=("$1"); shift ;;
  esac
done
ops=(resample project cull hairline parting cornrow-guides braid partition populate curl generate puff gather edges
  sections render head)
all=(usda obj_curves ply_curves hair obj_mesh ply_mesh off stl cli_args parse_floats ops)
((${#targets[@]})) || targets=("${all[@]}")

source "$(dirname "${BASH_SOURCE[0]}")/sanitize-env.sh"
configure_sanitize_build
build_targets=(make_fuzz_corpus)
binary_of() { if [[ $1 == op_* || $1 == ops ]]; then echo ops_fuzz; else echo "${1}_fuzz"; fi; }
for t in "${targets[@]}"; do
  if [[ $t == op_* && " ${ops[*]} " != *" ${t#op_} "* ]]; then
    echo "fuzz.sh: no op command '${t#op_}' (op targets: ${ops[*]/#/op_})" >&2
    exit 2
  fi
done
((write_seeds)) && targets=(ops)
for t in "${targets[@]}"; do build_targets+=("$(binary_of "$t")"); done
mapfile -t build_targets < <(printf '%s\n' "${build_targets[@]}" | sort -u)
cmake --build "$sbuild" -j "$jobs" --target "${build_targets[@]}" 2>&1 | grep -E 'error|warning: unused' || true
cmake --build "$sbuild" -j "$jobs" --target "${build_targets[@]}" >/dev/null

if ((write_seeds)); then
  rm -rf "$root/fuzz/seeds"
  GROOM_FUZZ_WRITE_SEEDS=$root/fuzz/seeds "$sbuild/fuzz/ops_fuzz"
  exit 0
fi

seeds=$sbuild/fuzz-seeds
rm -rf "$seeds"
# Fuzzing must not leak: LeakSanitizer would stop the run at exit; the readers hold no globals.
"$sbuild/fuzz/make_fuzz_corpus" "$seeds" 2>/dev/null
mkdir -p "$sbuild/fuzz-artifacts"

printf '%-18s %10s %8s %8s  %s\n' target executions exec/s corpus result
failed=0
for t in "${targets[@]}"; do
  work=$sbuild/fuzz-corpus/$t
  mkdir -p "$work" "$seeds/$t"
  dirs=("$work" "$seeds/$t")
  [[ -d $root/tests/data/regressions/$t ]] && dirs+=("$root/tests/data/regressions/$t")
  [[ -d $root/fuzz/seeds/$t ]] && dirs+=("$root/fuzz/seeds/$t")
  extra=()
  [[ -f $seeds/$t.dict ]] && extra+=(-dict="$seeds/$t.dict")
  log=$sbuild/fuzz-artifacts/$t.log
  run_seconds=$seconds
  op_env=()
  if [[ $t == op_* || $t == ops ]]; then
    [[ $t == op_* ]] && op_env=(GROOM_FUZZ_OP="${t#op_}")
    [[ -n $op_seconds ]] && run_seconds=$op_seconds
  fi
  # -timeout: one input taking over 60 s is a hang. 10 s flagged a sound input on the 2-core VM (an
  # op-target seed whose fuzzed mesh converts to a field in about 11 s under ASan and coverage,
  # perf: OpenVDB's narrow-band expansion and the exact closest faces), and 30 s failed CI once: an
  # op input is run twice when it leaves memory allocated (libFuzzer's leak check), and CI's cores
  # are slower than the VM's. The slow inputs found were made faster (sections' march, the
  # harness's scalp budget); a large but valid input still takes its time under ASan.
  timeout=60
  # -rss_limit_mb / -malloc_limit_mb: a reader that believes a header's absurd count and allocates
  # for it is a crash, not a slow run.
  started=$(mktemp)
  set +e
  env "${op_env[@]}" "$sbuild/fuzz/$(binary_of "$t")" "${dirs[@]}" "${extra[@]}" -max_total_time="$run_seconds" -timeout=$timeout -rss_limit_mb=2048 \
    -malloc_limit_mb=1024 -max_len=65536 -print_final_stats=1 -artifact_prefix="$sbuild/fuzz-artifacts/$t-" >"$log" 2>&1
  rc=$?
  set -e
  execs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$' || echo 0)
  rate=$(grep -o 'stat::average_exec_per_sec: *[0-9]*' "$log" | grep -o '[0-9]*$' || echo 0)
  corpus=$(find "$work" -type f | wc -l)
  if ((rc == 0)); then result=ok; else result="CRASH (see $log)"; failed=1; fi
  printf '%-18s %10s %8s %8s  %s\n' "$t" "${execs:-0}" "${rate:-0}" "$corpus" "$result"
  # CI keeps only this script's output, not the log or the input: print why, and the input's bytes,
  # so a crash seen once on CI's machine can be made a regression test here.
  # (Each in braces with `|| true`: under pipefail a head that stops reading, or a grep that finds
  # nothing, would end the script before the other targets run.)
  if ((rc != 0)); then
    { grep -E '^ops_fuzz: |ERROR|SUMMARY|^    #[0-9]+ .* in |deadly signal|Test unit written|out-of-memory|timeout' "$log" |
      grep -v -E ' (NEW|REDUCE|pulse) ' | head -60 | sed 's/^/  | /' >&2; } || true
    for a in "$sbuild/fuzz-artifacts/$t-"*; do
      [[ -f $a && $a -nt $started ]] || continue
      echo "  | $a (base64, whole: at most 64 KiB of input):" >&2
      { base64 -w 100 "$a" | sed 's/^/  | /' >&2; } || true
    done
  fi
  rm -f "$started"
done
exit $failed
