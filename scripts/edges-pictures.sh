#!/usr/bin/env bash
# The README's pictures of `groom edges`: close-ups of the baby hairs on the default head (`groom head`)
# with nothing else given (three-quarter view of the forehead, temple and sideburn), the scalloped
# swoops of --direction alternate from the front, and, when ../shared/datasets is there, the defaults
# on Lee Perry-Smith's scan (about 5.7 cm per unit: --units-per-cm 0.175). Needs build/groom.
# Usage: bash scripts/edges-pictures.sh [OUT_DIR]   (default docs/images)
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
groom=${GROOM:-$root/build/groom}
out=${1:-$root/docs/images}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
"$groom" head -o "$tmp/head.obj" --quiet
"$groom" scalp "$tmp/head.obj" -o "$tmp/head.vdb" --quiet
"$groom" edges --scalp "$tmp/head.vdb" -o "$tmp/edges.usda" --quiet
"$groom" render "$tmp/edges.usda" --scalp "$tmp/head.obj" -o "$out/edges_closeup.png" \
    --camera 10,9,20,2.5,5.5,6 --fov 32 --size 900x600 --quiet
"$groom" edges --scalp "$tmp/head.vdb" -o "$tmp/alternate.usda" --direction alternate --quiet
"$groom" render "$tmp/alternate.usda" --scalp "$tmp/head.obj" -o "$out/edges_alternate.png" \
    --camera 0,8,26,0,6.3,7 --fov 22 --size 900x450 --quiet
scan=${GROOM_SCAN:-$root/../shared/datasets/lee_perry_smith/LeePerrySmith.obj}
if [[ -f $scan ]]; then
    "$groom" scalp "$scan" -o "$tmp/scan.vdb" --quiet
    "$groom" edges --scalp "$tmp/scan.vdb" -o "$tmp/scan_edges.usda" --units-per-cm 0.175 --quiet
    "$groom" render "$tmp/scan_edges.usda" --scalp "$scan" -o "$out/edges_scan.png" \
        --camera 1.2,3.2,7,0,2.5,1.8 --fov 26 --size 900x600 --quiet
    echo "wrote $out/edges_scan.png"
else
    echo "edges_scan.png: skipped ($scan is absent)"
fi
echo "wrote $out/edges_closeup.png and $out/edges_alternate.png"
