#!/usr/bin/env bash
# Box braids from sections, as a chain of `groom` commands: the default head, its scalp field and
# hairline, the scalp parted into a grid of square sections (one hanging guide each, and every root of
# each section joined to its guide), a 3-strand plait per section, and pictures.
# Usage: datasets/box-braids.sh [OUT_DIR]   (expects `groom` on PATH; build first with scripts/build.sh)
# Every length is in centimetres (the head's units).
set -euo pipefail
out=${1:-out/box-braids}
mkdir -p "$out"
threads=${GROOM_THREADS:-0}
g() { groom "$@" --threads "$threads"; }

g head -o "$out/head.obj" --resolution 96
g scalp "$out/head.obj" -o "$out/head.vdb"
g hairline --scalp "$out/head.vdb" -o "$out/hairline.usda"
# 8 bands ear to ear, cells as long as wide (about 3.4 cm): 46 sections. Guides 24 cm long hang
# under gravity along the scalp, combed back where they would fall over the face.
g sections --scalp "$out/head.vdb" --hairline "$out/hairline.usda" --layout grid --cols 8 --length 24 \
    -o "$out/guides.usda" --partings-out "$out/partings.usda" --roots-out "$out/roots.usda" --roots 30000
# One plait per guide, hanging (rotation-minimising frames, not --orient scalp), 16 fibers a strand,
# thinner where it leaves the scalp, a short loose end.
g braid "$out/guides.usda" --scalp "$out/head.vdb" -o "$out/braids.usda" --pattern plait --strands 3 \
    --knot-length 1.2 --width 0.45 --taper 0.55,1,1,1,1,1,1,1,1,1,1,1 --fibers 16 --clearance 0.05 --loose-length 2
g render "$out/braids.usda" "$out/roots.usda" "$out/partings.usda" --scalp "$out/head.obj" -o "$out/box_braids.png" \
    --views front,left,back --size 480x480
g render "$out/braids.usda" "$out/roots.usda" "$out/partings.usda" --scalp "$out/head.obj" -o "$out/box_braids_crown.png" \
    --camera 13,24,-12,0,9,-2 --fov 32 --size 600x600
echo "box-braids: wrote $out/{guides,partings,roots,braids}.usda and $out/box_braids{,_crown}.png"
