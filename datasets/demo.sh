#!/usr/bin/env bash
# The demo groom, as a chain of `groom` commands: copy it to start your own scripts.
# Usage: datasets/demo.sh [OUT_DIR]   (expects `groom` on PATH; scripts/demo.sh builds and runs it)
#
# With no input from you it
#   1. makes the default head (`groom head`) and converts it to a scalp field (`groom scalp`);
#   2. builds an Alisha-style groom: cornrow guides front to back over the scalp, braided lying on the
#      scalp (`--orient scalp`), edge hairs between the rows pulled into each knot, loose curly ends
#      past the nape;
#   3. builds an Izzy-style groom: two afro puffs of curls with mixed cross-sections, the rest of the
#      scalp's hair gathered into them flat on the scalp (default hairline, centre parting, bands);
#   4. builds box braids: the scalp inside the hairline parted into square sections, a plait each;
#   5. writes each groom as .usda and renders front, side and top pictures;
#   6. prints what it made (curves, points, seconds per step) and where the files are.
# Every length is in centimetres (the head's units).
set -euo pipefail
out=${1:-out/demo}
mkdir -p "$out"
log="$out/demo.log"
: >"$log"
threads=${GROOM_THREADS:-0}

# --- helpers ------------------------------------------------------------------------------------------
# `step NAME groom ARGS...` runs one command, times it, keeps its messages in demo.log and prints the
# command's own summary line (each groom command ends with one: what it made and where).
summary=()
step() {
    local name=$1
    shift
    local t0 t1 secs msg
    t0=$(date +%s.%N)
    if ! "$@" --threads "$threads" 2>"$out/.step.err"; then
        cat "$out/.step.err" >&2
        echo "demo: step '$name' failed: $*" >&2
        exit 1
    fi
    t1=$(date +%s.%N)
    secs=$(awk -v a="$t0" -v b="$t1" 'BEGIN { printf "%.2f", b - a }')
    # The line naming the output file says what was made; else the last line.
    msg=$(grep -- '->' "$out/.step.err" | tail -n 1 || true)
    [[ -n $msg ]] || msg=$(grep -v '^\s*$' "$out/.step.err" | tail -n 1 || true)
    { echo "\$ $*"; cat "$out/.step.err"; } >>"$log"
    printf '  %-22s %7ss  %s\n' "$name" "$secs" "$msg"
    summary+=("$(printf '%-22s %7ss  %s' "$name" "$secs" "$msg")")
}
# True when this build of groom has the command (ops land one by one; the demo runs what exists).
have() { groom --help 2>/dev/null | grep -qE "^  $1 "; }
skipped=()
skip() {
    skipped+=("$1")
    echo "  (skipped: $1)"
}

groom --version
echo "demo: writing to $out"

# --- 1. the head and its scalp field ------------------------------------------------------------------
echo "1. head and scalp"
step "head" groom head -o "$out/head.obj" --resolution 96
scalp="$out/head.obj"  # every --scalp accepts a mesh (converted on the fly) or the .vdb below
if have scalp; then
    step "scalp" groom scalp "$out/head.obj" -o "$out/head.vdb"
    scalp="$out/head.vdb"
else
    skip "groom scalp (scalp field conversion) is not in this build"
fi
hairline=""
if have hairline; then
    # The head's default hairline (forehead, temples, sideburns, over the ears, nape): where hair grows.
    step "hairline" groom hairline --scalp "$scalp" -o "$out/hairline.usda"
    hairline="$out/hairline.usda"
fi

# --- 2. Alisha: cornrows, edge hairs, loose curly ends -----------------------------------------------
echo "2. Alisha: cornrows"
alisha=()
knot=2.2  # cm per knot (a strand's full cycle: 6 crossings), shared by braid and partition so edge hairs meet the braids' knots
if have cornrow-guides; then
    # Rows from the hairline at the front to the hairline at the nape (without one, the outer rows
    # would start on the forehead below it).
    step "cornrow guides" groom cornrow-guides --scalp "$scalp" -o "$out/alisha_guides.usda" \
        --count 12 --tails-out "$out/alisha_tails.usda" --tail-length 14 ${hairline:+--hairline "$hairline"}
    if have braid; then
        step "braid" groom braid "$out/alisha_guides.usda" --scalp "$scalp" -o "$out/alisha_braids.usda" \
            --orient scalp --strands 3 --knot-length "$knot" --rest --clearance 0.05 --fibers 40 --feed-in 0.8 \
            --loose-length 1.1 --flare 0.6
        alisha+=("$out/alisha_braids.usda")
    else
        skip "groom braid is not in this build"
        alisha+=("$out/alisha_guides.usda")
    fi
    if have partition; then
        step "partition" groom partition "$out/alisha_guides.usda" --scalp "$scalp" -o "$out/alisha_edges.usda" \
            --centroids knots --knot-length "$knot" --samples 6 --max-height 1 ${hairline:+--hairline "$hairline"}
        alisha+=("$out/alisha_edges.usda")
    else
        skip "groom partition (edge hairs) is not in this build"
    fi
    tails="$out/alisha_tails.usda"
    if have populate; then
        # As many hairs as the braid's fibers, as wide as its unbraided end: the braids had stopped
        # in a blunt wad above a bundle half their width (a trial: "a rope glued to a stick").
        step "populate tails" groom populate "$tails" -o "$out/alisha_tail_hairs.usda" --count 120 --radius 0.6
        tails="$out/alisha_tail_hairs.usda"
    else
        skip "groom populate (hairs around each tail) is not in this build"
    fi
    # With the scalp: the tails hang down the back of the neck, and 12% of their curled points were
    # inside it without (a trial).
    step "curl tails" groom curl "$tails" --scalp "$scalp" -o "$out/alisha_curls.usda" --type 3c --root-ease 1 --seed 1
    alisha+=("$out/alisha_curls.usda")
    if have edges && [[ -n $hairline ]]; then
        # Her edges: baby hairs laid flat along the front of the hairline, swept away from the face.
        step "edges" groom edges --scalp "$scalp" --hairline "$hairline" -o "$out/alisha_baby_hairs.usda" --seed 1
        alisha+=("$out/alisha_baby_hairs.usda")
    fi
else
    skip "groom cornrow-guides is not in this build"
fi

# --- 3. Izzy: two afro puffs, the whole scalp gathered into them --------------------------------------
echo "3. Izzy: afro puffs"
izzy=()
if have puff; then
    # Left and right of the crown; each puff's sphere sits above and outside its root patch.
    step "puff left" groom puff --scalp "$scalp" -o "$out/izzy_puff_left.usda" \
        --center -4.8,9.5,-1.5 --radius 3 --sphere-center -7.5,14,-1.5 --sphere-radius 6 --rows 6 --cols 6 --cap-angle 160 \
        --hairs 5000 --type 4a --seed 1
    step "puff right" groom puff --scalp "$scalp" -o "$out/izzy_puff_right.usda" \
        --center 4.8,9.5,-1.5 --radius 3 --sphere-center 7.5,14,-1.5 --sphere-radius 6 --rows 6 --cols 6 --cap-angle 160 \
        --hairs 5000 --type 4a --seed 2
    izzy+=("$out/izzy_puff_left.usda" "$out/izzy_puff_right.usda")
    if have gather && [[ -n $hairline ]]; then
        # Every other hair of the scalp, inside the hairline, combed flat to the nearer puff on its side
        # of a centre parting (forehead, over the crown, down to the nape), under a band at each base.
        step "parting" groom parting --scalp "$scalp" -o "$out/izzy_parting.usda" --through 0,8,12/0,14,-1/0,-2,-14
        step "gather" groom gather "$out/izzy_puff_left.usda" "$out/izzy_puff_right.usda" --scalp "$scalp" \
            --hairline "$out/hairline.usda" --parting "$out/izzy_parting.usda" -o "$out/izzy_gathered.usda" \
            --hairs 24000 --type 4a --seed 3
        izzy+=("$out/izzy_gathered.usda")
        if have edges; then
            # Edges along the front, in swoops leaning alternately left and right, off the parting.
            step "edges" groom edges --scalp "$scalp" --hairline "$hairline" --parting "$out/izzy_parting.usda" \
                -o "$out/izzy_baby_hairs.usda" --direction alternate --seed 2
            izzy+=("$out/izzy_baby_hairs.usda")
        fi
    else
        skip "groom gather (the scalp's hair pulled into the puffs) is not in this build"
    fi
else
    skip "groom puff is not in this build"
fi

# --- 4. box braids from sections ---------------------------------------------------------------------
echo "4. box braids"
boxes=()
if have sections && [[ -n $hairline ]]; then
    # The scalp inside the hairline parted into a grid of square sections (about 3.4 cm), one hanging
    # guide each and every root of each section joined to it; a 3-strand plait per section.
    step "sections" groom sections --scalp "$scalp" --hairline "$hairline" --layout grid --cols 8 --length 24 \
        -o "$out/box_guides.usda" --partings-out "$out/box_partings.usda" --roots-out "$out/box_roots.usda" --roots 30000
    step "box braids" groom braid "$out/box_guides.usda" --scalp "$scalp" -o "$out/box_braids.usda" --pattern plait --strands 3 \
        --knot-length 1.2 --width 0.45 --taper 0.55,1,1,1,1,1,1,1,1,1,1,1 --fibers 16 --clearance 0.05 --loose-length 2
    boxes+=("$out/box_braids.usda" "$out/box_roots.usda" "$out/box_partings.usda")
else
    skip "groom sections (parted sections for box braids) is not in this build"
fi

# --- 5. pictures ----------------------------------------------------------------------------------------
echo "5. pictures"
render_groom() {  # NAME FILES...
    local name=$1
    shift
    step "render $name" groom render "$@" --scalp "$out/head.obj" -o "$out/$name.png" \
        --views front,left,top --size 480x480
    step "render $name 3/4" groom render "$@" --scalp "$out/head.obj" -o "$out/${name}_three_quarter.png" \
        --view three-quarter --size 720x720
}
step "render head" groom render --scalp "$out/head.obj" -o "$out/head.png" --views front,left,top --size 400x400
if ((${#alisha[@]})); then render_groom alisha "${alisha[@]}"; fi
if ((${#izzy[@]})); then render_groom izzy "${izzy[@]}"; fi
if ((${#boxes[@]})); then render_groom box_braids "${boxes[@]}"; fi

# --- 6. what was made ---------------------------------------------------------------------------------
echo
echo "demo: done. Steps (seconds, and what each made):"
printf '  %s\n' "${summary[@]}"
echo "Files in $out:"
(cd "$out" && ls -1 -- *.usda *.obj *.vdb *.png 2>/dev/null | sed 's/^/  /') || true
echo "  (every command's messages: $log)"
if ((${#skipped[@]})); then
    echo "not run, because this build lacks the command:"
    printf '  %s\n' "${skipped[@]}"
fi
rm -f "$out/.step.err"
