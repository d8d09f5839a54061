#!/usr/bin/env bash
# The README's pictures of `groom edges`: close-ups of the baby hairs on the default head (`groom head`)
# with nothing else given (three-quarter view of the forehead, temple and sideburn), and the
# scalloped swoops of --direction alternate from the front. Needs build/groom.
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
echo "wrote $out/edges_closeup.png and $out/edges_alternate.png"
