#!/usr/bin/env bash
# The add-on's pictures for the README: docs/images/blender_render.png (Cycles, headless: cornrows
# braided by bpy.ops.groom.braid on the demo's head) and docs/images/blender_panel.png (a real
# Blender window under Xvfb showing the Groom panel beside that groom). Needs the demo's output
# (scripts/demo.sh), Blender, Xvfb and xdotool (scripts/install-deps.sh --with-tools).
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
export GROOM_DEMO=${GROOM_DEMO:-$root/out/demo} GROOM_OUT=${GROOM_OUT:-$root/docs/images}
export GROOM_BLENDER_ADDON_DIR=$root/blender PYTHONPATH=${GROOM_BUILD_DIR:-$root/build}/python
export GROOM_TMP=$(mktemp -d)
trap 'rm -rf "$GROOM_TMP"' EXIT
timeout 600 blender -b --factory-startup --python-exit-code 1 --python "$root/scripts/blender_pictures.py"
# The window: Blender opens the saved scene; after it settles, a click on the sidebar's Groom tab
# (at the sidebar's right edge in a 1600x1000 window); the script's timer takes the screenshot.
timeout 300 xvfb-run -a -s "-screen 0 1600x1000x24" bash -c '
  blender --factory-startup -noaudio --window-geometry 0 0 1600 1000 "$GROOM_TMP/groom_pictures.blend" \
    --python "$0" >"$GROOM_TMP/ui.log" 2>&1 &
  pid=$!
  sleep 6
  xdotool mousemove 1307 245 click 1
  wait $pid' "$root/scripts/blender_pictures.py"
ls -l "$GROOM_OUT/blender_panel.png" "$GROOM_OUT/blender_render.png"
