#!/usr/bin/env bash
# A full head (issue 17): HAIRS hairs x 32 points grown from Sintel's 228 guides on her scalp, curled,
# written as .hair, each step a whole process timed by /usr/bin/time (wall, CPU, peak memory) next to
# its I/O floor (`groom convert` of the same file) and the memory aim: peak <= 2 x the output's bytes
# + the field (the field's own process peak, `groom scalp`, stands for it: an upper bound).
# Usage: scripts/full-head.sh [HAIRS] [OUT_DIR]   (default 1000000, /tmp/groom-full-head; needs
# ../shared/datasets and a build: scripts/build.sh). Takes about a minute and 2 GB of disk at 1M.
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
hairs=${1:-1000000}
out=${2:-/tmp/groom-full-head}
groom=${GROOM:-$here/build/groom}
data=$here/../shared/datasets/sintel_tressfx_opengl
[ -f "$data/sintel.obj" ] || { echo "full-head: $data/sintel.obj not found (needs ../shared/datasets)" >&2; exit 2; }
mkdir -p "$out"
threads=${GROOM_THREADS:-0}
step() {  # step NAME command...: prints NAME wall CPU peak
    local name=$1; shift
    /usr/bin/time -f "%e %U %S %M" -o "$out/time.txt" "$@" --threads "$threads" --force --quiet
    read -r wall user sys kb < "$out/time.txt"
    awk -v n="$name" -v w="$wall" -v u="$user" -v s="$sys" -v k="$kb" \
        'BEGIN { printf "%-10s wall %6.2f s  CPU %6.2f s  peak %5d MiB\n", n, w, u + s, k / 1024 }' 
    echo "$kb" > "$out/$name.kb"
}
step scalp "$groom" scalp "$data/sintel.obj" -o "$out/sintel.vdb"
step generate "$groom" generate "$data/sintel_guides.obj" --scalp "$out/sintel.vdb" --count "$hairs" -o "$out/hair.hair"
step curl "$groom" curl "$out/hair.hair" -o "$out/curled.hair"
step floor "$groom" convert "$out/curled.hair" -o "$out/floor.hair"
bytes=$(stat -c %s "$out/curled.hair")
field_kb=$(cat "$out/scalp.kb")
aim_kb=$((2 * bytes / 1024 + field_kb))
worst=0
for s in generate curl floor; do k=$(cat "$out/$s.kb"); [ "$k" -gt "$worst" ] && worst=$k; done
echo "output $((bytes / 1048576)) MiB; aim 2 x output + field = $((aim_kb / 1024)) MiB; worst step $((worst / 1024)) MiB"
[ "$worst" -le "$aim_kb" ] && echo "full-head: within the memory aim" || echo "full-head: OVER the memory aim"
