#!/usr/bin/env bash
# The whole test suite under AddressSanitizer + UndefinedBehaviorSanitizer (+ LeakSanitizer): a
# clang build with GROOM_SANITIZE=ON in ./build-sanitize (shared with scripts/fuzz.sh), then CTest.
#   bash scripts/test-sanitize.sh            # every suite
#   bash scripts/test-sanitize.sh -R Usda    # extra arguments go to ctest
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/sanitize-env.sh"
configure_sanitize_build
start=$(date +%s)
cmake --build "$sbuild" -j "$jobs" 2>&1 | grep -vE '^\[ *[0-9]+%\]|^Consolidate|^-- ' || true
cmake --build "$sbuild" -j "$jobs" >/dev/null
built=$(date +%s)
cd "$sbuild"
ctest --output-on-failure -j "$jobs" "$@"
echo "test-sanitize: build $((built - start)) s, tests $(($(date +%s) - built)) s"
