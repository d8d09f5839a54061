#!/usr/bin/env bash
# Submits the frames of a shot to Slurm as one job array and waits for it. Each array task runs the
# groom command line for its frames (--frames A:B; `####` in file names is the frame number), so any
# frame can be re-run alone, and the same line goes to any farm (README: Animated grooms).
#
#   scripts/slurm-frames.sh [options] FIRST:LAST -- groom generate guides.####.usda --scalp head.vdb ... -o hair.####.usda
#
# Options:
#   --chunk K        frames per array task (default 1); a task pays groom's start and the scalp's
#                    load once for its K frames
#   --shards N       split every frame into N array tasks (--shard I/N; `groom merge` joins them; the
#                    command's -o must then name the shard, e.g. -o hair.####.s@SHARD@.usda)
#   --logs DIR       where task logs go (default: slurm-logs/ in the current folder)
#   --timeout SEC    give up (scancel) after SEC seconds (default 3600)
#   --sbatch "ARGS"  more sbatch options (partition, account, memory, ...)
# Exit status: 0 when every task succeeded; 1 when one failed (its log is printed); 2 usage; 124 timeout
# (the job is cancelled).
set -euo pipefail

chunk=1 shards=1 logs=slurm-logs timeout_s=3600 extra=""
while [[ $# -gt 0 && "$1" == --* ]]; do
  case "$1" in
    --chunk) chunk=$2; shift 2 ;;
    --shards) shards=$2; shift 2 ;;
    --logs) logs=$2; shift 2 ;;
    --timeout) timeout_s=$2; shift 2 ;;
    --sbatch) extra=$2; shift 2 ;;
    --) break ;;
    *) echo "slurm-frames: unknown option $1" >&2; exit 2 ;;
  esac
done
range=${1:-}
shift || true
[[ "${1:-}" == "--" ]] && shift
if [[ ! "$range" =~ ^([0-9]+):([0-9]+)$ || $# -eq 0 ]]; then
  echo "usage: $0 [--chunk K] [--shards N] [--logs DIR] [--timeout SEC] FIRST:LAST -- groom COMMAND ..." >&2
  exit 2
fi
first=${BASH_REMATCH[1]} last=${BASH_REMATCH[2]}
(( last >= first && chunk >= 1 && shards >= 1 )) || { echo "slurm-frames: need FIRST <= LAST, --chunk >= 1, --shards >= 1" >&2; exit 2; }
command -v sbatch >/dev/null || { echo "slurm-frames: sbatch not found (scripts/install-deps.sh --with-slurm; scripts/slurm-local.sh start)" >&2; exit 2; }

chunks=$(( (last - first) / chunk + 1 ))
tasks=$(( chunks * shards ))
mkdir -p "$logs"
logs=$(cd "$logs" && pwd)
job="$logs/frames-job.sh"
status=$(mktemp -d "$logs/status.XXXXXX")
# The task's command line, each word quoted for the shell; @SHARD@ in it becomes the shard index.
cmdline=$(printf '%q ' "$@")
{
  echo '#!/usr/bin/env bash'
  echo 'set -euo pipefail'
  printf 'first=%d last=%d chunk=%d shards=%d\n' "$first" "$last" "$chunk" "$shards"
  printf 'line=%q\n' "$cmdline"
  printf 'status=%q\n' "$status"
  cat <<'JOB'
t=$SLURM_ARRAY_TASK_ID
c=$(( t / shards )) s=$(( t % shards ))
a=$(( first + c * chunk )) b=$(( first + c * chunk + chunk - 1 ))
if (( b > last )); then b=$last; fi
shard=""
if (( shards > 1 )); then shard="--shard $s/$shards"; fi
echo "task $t: frames $a:$b ${shard} start $(date +%s.%N)"
set +e
eval "${line//@SHARD@/$s} --frames $a:$b $shard"
rc=$?
echo "task $t: exit $rc end $(date +%s.%N)"
echo "$rc" > "$status/task_$t.rc"
exit "$rc"
JOB
} > "$job"
chmod +x "$job"

start=$(date +%s.%N)
# Submit, then watch the queue every half second: `sbatch --wait` polls at growing intervals (up to
# 10 s here), which would add seconds to every short shot. Each task leaves its exit status in
# $status, so success needs no accounting database.
# shellcheck disable=SC2086
jobid=$(sbatch --parsable --array=0-$((tasks - 1)) --job-name=groom-frames \
  --output="$logs/%A_%a.log" --chdir="$PWD" --cpus-per-task=1 $extra "$job" | cut -d';' -f1)
[[ -n "$jobid" ]] || { echo "slurm-frames: sbatch gave no job id" >&2; exit 1; }
deadline=$(( $(date +%s) + timeout_s ))
while squeue -h -j "$jobid" 2>/dev/null | grep -q .; do
  if (( $(date +%s) > deadline )); then
    scancel "$jobid" || true
    echo "slurm-frames: job $jobid timed out after $timeout_s s; cancelled (logs in $logs)" >&2
    exit 124
  fi
  sleep 0.5
done
end=$(date +%s.%N)
secs=$(echo "$end - $start" | bc -l)
failed=()
for ((t = 0; t < tasks; t++)); do
  rc=$(cat "$status/task_$t.rc" 2>/dev/null || echo "none")
  [[ "$rc" == 0 ]] || failed+=("$t:$rc")
done
if ((${#failed[@]})); then
  echo "slurm-frames: job $jobid: ${#failed[@]} of $tasks tasks failed (task:exit ${failed[*]}); logs in $logs" >&2
  for f in "${failed[@]}"; do
    log="$logs/${jobid}_${f%%:*}.log"
    [[ -f "$log" ]] && { echo "--- $log" >&2; tail -n 20 "$log" >&2; }
  done
  exit 1
fi
printf 'slurm-frames: job %s: frames %d-%d (%d tasks) done in %.1f s, %.1f frames per minute\n' \
  "$jobid" "$first" "$last" "$tasks" "$secs" "$(echo "($last - $first + 1) * 60 / $secs" | bc -l)"
