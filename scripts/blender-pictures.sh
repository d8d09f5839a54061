#!/usr/bin/env bash
# The add-on's pictures for the README: docs/images/blender_panel.png (a real Blender window under
# Xvfb: the Groom panel beside cornrows braided by the add-on on the demo's head) and
# docs/images/blender_render.png (Cycles). Needs the demo's output (scripts/demo.sh), Blender and
# Xvfb (scripts/install-deps.sh --with-tools).
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
export GROOM_DEMO=${GROOM_DEMO:-$root/out/demo} GROOM_OUT=${GROOM_OUT:-$root/docs/images}
export GROOM_BLENDER_ADDON_DIR=$root/blender PYTHONPATH=${GROOM_BUILD_DIR:-$root/build}/python
timeout 600 blender -b --factory-startup --python-exit-code 1 --python "$root/scripts/blender_pictures.py"
timeout 600 xvfb-run -a -s "-screen 0 1600x1000x24" blender --factory-startup -noaudio --window-geometry 0 0 1600 1000 \
  --python "$root/scripts/blender_pictures.py"
ls -l "$GROOM_OUT/blender_panel.png" "$GROOM_OUT/blender_render.png"
