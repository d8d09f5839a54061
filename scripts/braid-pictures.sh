#!/usr/bin/env bash
# The README's braid pictures: every pattern of `groom braid` seen from above (the braid's normal
# toward the camera) and from the side, strands coloured, and close-ups of the demo's cornrows, alone
# and with their edge hairs. Needs build/groom and, for the close-up, out/demo from scripts/demo.sh.
# Usage: bash scripts/braid-pictures.sh [OUT_DIR]   (default docs/images)
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
groom=${GROOM:-$root/build/groom}
out=${1:-$root/docs/images}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
layers=()
col=0
# A fishtail crosses a piece at every step (16 a knot for 8 pieces), so its knots are longer.
for spec in "plait 3 2.4" "plait 5 2.4" "fishtail 8 9" "twist 2 2.4" "rope 3 2.4" "round 4 2.4" "lissajous 3 2.4"; do
    set -- $spec
    x=$((col * 3))
    # Top row: normal toward the camera (+z); bottom row: normal sideways (+x), so the front view
    # shows each braid from above and from the side.
    for row in top side; do
        if [ $row = top ]; then y0=0; normal=0,0,1; else y0=-13; normal=1,0,0; fi
        printf 'v %s %s 0\nv %s %s 0\nl 1 2\n' "$x" "$y0" "$x" "$((y0 - 11))" > "$tmp/g.obj"
        "$groom" braid "$tmp/g.obj" -o "$tmp/$1_$2_$row.usda" --pattern "$1" --strands "$2" --knot-length "$3" \
            --initial-normal "$normal" --fibers 24 --quiet
        layers+=("$tmp/$1_$2_$row.usda")
    done
    col=$((col + 1))
done
"$groom" render "${layers[@]}" -o "$out/braid_patterns.png" --view front --color-by strand --size 1400x900 --quiet
if [ -f "$root/out/demo/alisha_braids.usda" ]; then
    "$groom" render "$root/out/demo/alisha_braids.usda" --scalp "$root/out/demo/head.obj" -o "$out/cornrow_closeup.png" \
        --camera 1.2,24,1,1.2,12,1 --up 0,0,-1 --fov 22 --color-by strand --size 700 --quiet
fi
if [ -f "$root/out/demo/alisha_edges.usda" ]; then
    # The same place with the edge hairs between the rows (`groom partition`, the demo's options).
    "$groom" render "$root/out/demo/alisha_braids.usda" "$root/out/demo/alisha_edges.usda" --scalp "$root/out/demo/head.obj" \
        -o "$out/partition_edges.png" --camera 1.2,24,1,1.2,12,1 --up 0,0,-1 --fov 22 --size 700 --quiet
fi
echo "wrote $out/braid_patterns.png, $out/cornrow_closeup.png and $out/partition_edges.png"
