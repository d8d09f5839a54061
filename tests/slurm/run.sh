#!/usr/bin/env bash
# A 4-frame shot as a Slurm job array (scripts/slurm-frames.sh): a head turning (--scalp-xform), its
# edge hairs made frame by frame by Slurm tasks, each frame's file byte for byte the one a local
# `--frames 0:3` run writes. Exit 77 (CTest: skipped), saying why, where Slurm is not installed or
# cannot start here; every step runs under a time limit so a stuck daemon cannot hang CI.
set -uo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
groom=${GROOM_BINARY:?GROOM_BINARY must name the groom executable}
skip() { echo "SKIPPED: $*"; exit 77; }

for b in sbatch sinfo slurmctld slurmd munged; do
  command -v "$b" >/dev/null || skip "$b not installed (scripts/install-deps.sh --with-slurm)"
done
started=0
if ! timeout 10 bash "$root/scripts/slurm-local.sh" status; then
  [[ $(id -u) -eq 0 ]] || skip "no Slurm node answers and starting one needs root"
  timeout 60 bash "$root/scripts/slurm-local.sh" start || skip "Slurm did not start here (scripts/slurm-local.sh start failed; see /var/log/slurm)"
  started=1
fi
work=$(mktemp -d /tmp/groom-slurm-test.XXXXXX)
cleanup() {
  rm -rf "$work"
  if [[ $started -eq 1 ]]; then bash "$root/scripts/slurm-local.sh" stop; fi
}
trap cleanup EXIT
cd "$work"

timeout 120 "$groom" head -o head.obj --resolution 24 --quiet || { echo "FAIL: groom head"; exit 1; }
# Frame f: a turn of 6f degrees about Y and a shift of 0.1f along X.
for f in 0 1 2 3; do echo "$f $(echo "$f * 0.1" | bc -l) 0 0 0 $((6 * f)) 0"; done > poses.txt
args=(edges --scalp head.obj --scalp-xform poses.txt --direction random --from -90 --to 90 --seed 3 --quiet)

timeout 120 "$groom" "${args[@]}" --frames 0:3 -o local.####.usda || { echo "FAIL: local run"; exit 1; }
timeout 200 bash "$root/scripts/slurm-frames.sh" --logs "$work/logs" --timeout 180 0:3 -- "$groom" "${args[@]}" -o farm.####.usda
rc=$?
if [[ $rc -ne 0 ]]; then echo "FAIL: slurm-frames.sh exit $rc"; cat "$work"/logs/*.log 2>/dev/null | tail -n 40; exit 1; fi
for f in 0000 0001 0002 0003; do
  [[ -s farm.$f.usda ]] || { echo "FAIL: farm.$f.usda not written"; exit 1; }
  cmp -s local.$f.usda farm.$f.usda || { echo "FAIL: frame $f from Slurm differs from the local run"; exit 1; }
done
cmp -s local.0000.usda local.0001.usda && { echo "FAIL: frames 0 and 1 are the same: the pose was not applied"; exit 1; }
echo "PASS: 4 frames from a Slurm job array, each equal to the local run's"
