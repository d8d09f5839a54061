#!/usr/bin/env bash
# The animated demo: Alisha (cornrows, edge hairs, loose curly ends, baby hairs) turning her head over
# 24 frames, every frame made by the same `groom ... --frames 0:23` command lines a farm would run
# one frame at a time (scripts/slurm-frames.sh), and drawn as a contact sheet.
# Usage: datasets/animate.sh [OUT_DIR] [FRAMES]   (expects `groom` on PATH; /usr/bin/python3)
#
#   1. the head, its scalp field (built once: the head moves rigidly), its hairline;
#   2. Alisha's guides in the head's rest pose: cornrow rows and their tails;
#   3. the shot (datasets/animate_shot.py): the head's pose per frame (poses.txt, for --scalp-xform)
#      and her tails swayed by the turn, posed, per frame (tails.####.obj: what a simulation hands over);
#   4. per frame: braids, edge hairs and baby hairs from the rest-pose guides moved by the pose; the
#      curly ends populated and curled from that frame's tails;
#   5. a picture per frame from one fixed camera, and the contact sheet of all frames.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
out=${1:-out/animate}
frames=${2:-24}
last=$((frames - 1))
py=${PYTHON:-/usr/bin/python3}
mkdir -p "$out"
log="$out/animate.log"
: >"$log"
threads=${GROOM_THREADS:-0}

step() {
    local name=$1
    shift
    local t0 t1
    t0=$(date +%s.%N)
    if ! "$@" >>"$log" 2>&1; then
        tail -n 20 "$log" >&2
        echo "animate: step '$name' failed: $*" >&2
        exit 1
    fi
    t1=$(date +%s.%N)
    printf '  %-26s %7.2fs\n' "$name" "$(echo "$t1 - $t0" | bc -l)"
    echo "$name $(echo "$t1 - $t0" | bc -l)" >>"$out/times.txt"
}
: >"$out/times.txt"

echo "1. head, scalp, hairline (once)"
step "head" groom head -o "$out/head.obj" --resolution 96 --threads "$threads"
step "scalp" groom scalp "$out/head.obj" -o "$out/head.vdb" --threads "$threads"
step "hairline" groom hairline --scalp "$out/head.vdb" -o "$out/hairline.usda" --threads "$threads"

echo "2. Alisha's guides, rest pose (once)"
knot=2.2
step "cornrow guides" groom cornrow-guides --scalp "$out/head.vdb" -o "$out/guides.usda" --count 12 \
    --tails-out "$out/tails_rest.usda" --tail-length 14 --hairline "$out/hairline.usda" --threads "$threads"
step "tails to obj" groom convert "$out/tails_rest.usda" -o "$out/tails_rest.obj"

echo "3. the shot: $frames frames of a head turn and the ends' sway"
step "poses and tails" "$py" "$here/animate_shot.py" "$out" "$frames" "$out/head.obj" "$out/tails_rest.obj"

echo "4. the groom, frame by frame (--frames 0:$last --scalp-xform poses.txt)"
anim=(--frames "0:$last" --scalp-xform "$out/poses.txt" --threads "$threads" --quiet)
step "braid x$frames" groom braid "$out/guides.usda" --scalp "$out/head.vdb" -o "$out/braids.####.usda" \
    --orient scalp --strands 3 --knot-length "$knot" --rest --clearance 0.05 --fibers 40 --feed-in 0.3 "${anim[@]}"
step "partition x$frames" groom partition "$out/guides.usda" --scalp "$out/head.vdb" -o "$out/edges.####.usda" \
    --centroids knots --knot-length "$knot" --count 60 --samples 6 --max-height 1 "${anim[@]}"
step "populate tails x$frames" groom populate "$out/tails.####.obj" -o "$out/tail_hairs.####.usda" --count 60 --radius 0.45 "${anim[@]}"
step "curl tails x$frames" groom curl "$out/tail_hairs.####.usda" -o "$out/curls.####.usda" --type 3c --root-ease 1 --seed 1 "${anim[@]}"
step "edges x$frames" groom edges --scalp "$out/head.vdb" --hairline "$out/hairline.usda" -o "$out/baby.####.usda" --seed 1 "${anim[@]}"

echo "5. pictures"
# One camera for every frame (a framed-to-fit view would follow the head): three-quarter back, above.
step "render x$frames" groom render "$out/braids.####.usda" "$out/edges.####.usda" "$out/curls.####.usda" "$out/baby.####.usda" \
    --scalp "$out/head.####.obj" --camera -50,18,-55,0,-4,-3 --fov 30 --size 240 --supersample 2 --color-by file \
    -o "$out/frame.####.png" --frames "0:$last" --threads "$threads" --quiet
pngs=()
for ((f = 0; f <= last; f++)); do pngs+=("$(printf '%s/frame.%04d.png' "$out" "$f")"); done
step "contact sheet" "$py" "$here/contact_sheet.py" "$out/contact_sheet.png" 6 "${pngs[@]}"
groom_secs=$(awk '/x'"$frames"'/ && !/render/ {s += $NF} END {print s}' "$out/times.txt")
printf 'animate: %d frames of the groom in %.1f s: %.1f frames per minute (pictures not counted) -> %s\n' \
    "$frames" "$groom_secs" "$(echo "$frames * 60 / $groom_secs" | bc -l)" "$out/contact_sheet.png"
