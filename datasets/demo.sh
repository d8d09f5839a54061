#!/usr/bin/env bash
# The demo groom, as a chain of `groom` commands (copy it to start your own scripts).
# Usage: datasets/demo.sh [OUT_DIR]   (expects `groom` on PATH)
set -euo pipefail
out=${1:-out/demo}
mkdir -p "$out"
groom --version
