#!/usr/bin/env bash
# The demo's grooms on a real head scan instead of the synthetic head: Lee Perry-Smith's bust
# (../shared/datasets/lee_perry_smith: "Infinite, 3D Head Scan by Lee Perry-Smith", CC BY 3.0, based on a work at triplegangers.com;
# +Y up, face +Z, about 5.7 cm per unit). Skipped, saying so, when ../shared/datasets is absent (a
# fresh clone has no ../shared; the scan is never copied into this repository).
# Usage: datasets/demo-scan.sh [OUT_DIR]   (expects `groom` on PATH; build first: bash scripts/build.sh)
# Every length is in the scan's units: a curl radius of 0.04 is about 2.3 mm; --units-per-cm 0.175
# tells each command so (default hair widths, the scale check).
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
out=${1:-out/demo-scan}
scan=${GROOM_SCAN:-$root/../shared/datasets/lee_perry_smith/LeePerrySmith.obj}
if [[ ! -f $scan ]]; then
    echo "demo-scan: skipped: $scan is absent (it comes with ../shared/datasets, not with this repository)"
    exit 0
fi
mkdir -p "$out"
run() {
    echo "\$ $*"
    "$@"
}

echo "1. scalp and hairline"
run groom scalp "$scan" -o "$out/scan.vdb"
run groom hairline --scalp "$out/scan.vdb" -o "$out/hairline.usda"

echo "2. Izzy on the scan: two puffs, the rest gathered into them along a centre parting"
for side in left right; do
    x=$([[ $side == left ]] && echo -1.0 || echo 1.0)
    sx=$([[ $side == left ]] && echo -1.7 || echo 1.7)
    seed=$([[ $side == left ]] && echo 1 || echo 2)
    run groom puff --scalp "$out/scan.vdb" -o "$out/izzy_puff_$side.usda" --center "$x,3.6,-0.3" --radius 0.5 \
        --sphere-center "$sx,4.45,-0.3" --sphere-radius 1.0 --rows 6 --cols 6 --cap-angle 160 \
        --hairs 5000 --type 4a --amplitude 0.03,0.045 --seed "$seed" --units-per-cm 0.175
done
run groom parting --scalp "$out/scan.vdb" -o "$out/parting.usda" --through 0,3.3,5/0,6,0/0,1.5,-5 --step 0.04
run groom gather "$out/izzy_puff_left.usda" "$out/izzy_puff_right.usda" --scalp "$out/scan.vdb" \
    --hairline "$out/hairline.usda" --parting "$out/parting.usda" --parting-gap 0.05 -o "$out/izzy_gathered.usda" \
    --hairs 12000 --lift 0.014 --step 0.045 --band-width 0.14 --band-thickness 0.02 --type 4a --amplitude 0.03,0.045 --seed 3 \
    --units-per-cm 0.175

run groom edges --scalp "$out/scan.vdb" --hairline "$out/hairline.usda" --parting "$out/parting.usda" --parting-gap 0.05 \
    -o "$out/izzy_baby_hairs.usda" --direction alternate --units-per-cm 0.175 --seed 2

echo "2b. Alisha's cornrows on the scan: 12 straight-back rows from the hairline to the nape, edge hairs between them"
knot=0.385  # 2.2 cm per knot, as the demo head's
run groom cornrow-guides --scalp "$out/scan.vdb" --hairline "$out/hairline.usda" --center 0,2.3,0 --radius 1.7 --count 12 \
    -o "$out/alisha_guides.usda" --tails-out "$out/alisha_tails.usda" --tail-length 2.4
run groom braid "$out/alisha_guides.usda" --scalp "$out/scan.vdb" -o "$out/alisha_braids.usda" --orient scalp --strands 3 \
    --knot-length "$knot" --rest --clearance 0.009 --fibers 40 --feed-in 0.8 --width 0.1
run groom partition "$out/alisha_guides.usda" --scalp "$out/scan.vdb" -o "$out/alisha_edges.usda" --centroids knots \
    --knot-length "$knot" --samples 6 --max-height 0.175 --hairline "$out/hairline.usda" --units-per-cm 0.175

echo "3. box braids on the scan: sections about 3.4 cm square, a plait each"
run groom sections --scalp "$out/scan.vdb" --hairline "$out/hairline.usda" --layout grid --cols 8 --length 4.2 \
    --parting-gap 0.05 --step 0.045 --bend 0.175 --clearance 0.05 --layer 0.026 \
    -o "$out/box_guides.usda" --partings-out "$out/box_partings.usda" --roots-out "$out/box_roots.usda" --roots 30000 \
    --units-per-cm 0.175
run groom braid "$out/box_guides.usda" --scalp "$out/scan.vdb" -o "$out/box_braids.usda" --pattern plait --strands 3 \
    --knot-length 0.21 --width 0.079 --taper 0.55,1,1,1,1,1,1,1,1,1,1,1 --fibers 16 --clearance 0.009 --loose-length 0.35

echo "4. pictures"
run groom render "$out/izzy_puff_left.usda" "$out/izzy_puff_right.usda" "$out/izzy_gathered.usda" "$out/izzy_baby_hairs.usda" --scalp "$scan" \
    -o "$out/izzy_scan.png" --views front,left,back --size 420x420
run groom render "$out/alisha_braids.usda" "$out/alisha_edges.usda" --scalp "$scan" \
    -o "$out/alisha_scan.png" --views front,left,back --size 420x420
run groom render "$out/alisha_braids.usda" "$out/alisha_edges.usda" --scalp "$scan" \
    -o "$out/alisha_scan_back.png" --camera 0,-3,-12,0,1.2,0 --fov 25 --size 600x600
run groom render "$out/box_braids.usda" "$out/box_roots.usda" "$out/box_partings.usda" --scalp "$scan" \
    -o "$out/box_braids_scan.png" --views front,left,back --size 420x420
echo "demo-scan: done -> $out"
