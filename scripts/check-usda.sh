#!/usr/bin/env bash
# Independent syntax check of .usda files with tinyusdz (npm, a WebAssembly build of an
# independent USD parser). Each FILE must load as a stage; then tinyusdz's own re-serialisation of
# the layer is read back by `groom info` and its curve and point counts must equal the original's.
#
#   scripts/check-usda.sh [--no-install] FILE.usda...
#
# tinyusdz is installed (npm) into a cache folder outside the repository, by default
# ~/.cache/groom-tinyusdz (override with GROOM_TINYUSDZ_DIR). --no-install never touches the network.
# Exit: 0 all files pass, 1 a file fails, 77 the checker is unavailable (no node/npm, or --no-install
# and no cached tinyusdz): callers such as the test suite treat 77 as "skipped".
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
install=1
if [[ ${1:-} == --no-install ]]; then install=0; shift; fi
if [[ $# -eq 0 ]]; then echo "usage: $0 [--no-install] FILE.usda..." >&2; exit 2; fi
cache=${GROOM_TINYUSDZ_DIR:-${XDG_CACHE_HOME:-$HOME/.cache}/groom-tinyusdz}
groom=${GROOM:-$root/build/groom}

if ! command -v node >/dev/null 2>&1; then echo "check-usda: node not found; skipped" >&2; exit 77; fi
if [[ ! -f $cache/node_modules/tinyusdz/tinyusdz.wasm ]]; then
  if [[ $install -eq 0 ]]; then echo "check-usda: tinyusdz not installed in $cache; skipped" >&2; exit 77; fi
  if ! command -v npm >/dev/null 2>&1; then echo "check-usda: npm not found; skipped" >&2; exit 77; fi
  mkdir -p "$cache"
  (cd "$cache" && npm install --no-audit --no-fund --silent tinyusdz >/dev/null) || { echo "check-usda: npm install tinyusdz failed" >&2; exit 77; }
fi

cat > "$cache/check.mjs" <<'JS'
// The npm build of tinyusdz targets browsers only: present this process as a renderer window
// and hand it the wasm bytes directly.
import { readFileSync, writeFileSync } from 'fs';
import { fileURLToPath } from 'url';
process.type = 'renderer';
globalThis.window = globalThis;
const dir = fileURLToPath(new URL('./node_modules/tinyusdz/', import.meta.url));
const { default: init } = await import(dir + 'tinyusdz.js');
const m = await init({ wasmBinary: readFileSync(dir + 'tinyusdz.wasm'), print: () => {}, printErr: () => {} });
const [file, out] = process.argv.slice(2);
const bytes = new Uint8Array(readFileSync(file));
const stage = new m.TinyUSDZLoaderNative();
if (!stage.loadFromBinary(bytes, file)) { console.error(`tinyusdz: ${file}: failed to load as a stage`); process.exit(1); }
const layer = new m.TinyUSDZLoaderNative();
if (!layer.loadAsLayerFromBinary(bytes, file)) { console.error(`tinyusdz: ${file}: failed to load as a layer`); process.exit(1); }
writeFileSync(out, layer.layerToString());
JS

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
status=0
counts() { "$groom" info --json "$1" | grep -E '^  "(curves|points)"' | tr -d ' ,\n'; }
for f in "$@"; do
  if ! node "$cache/check.mjs" "$f" "$tmp/reserialised.usda"; then status=1; continue; fi
  if [[ -x $groom ]]; then
    a=$(counts "$f") b=$(counts "$tmp/reserialised.usda") || { echo "check-usda: $f: groom cannot read tinyusdz's re-serialisation" >&2; status=1; continue; }
    if [[ $a != "$b" ]]; then echo "check-usda: $f: counts differ after tinyusdz ($a vs $b)" >&2; status=1; continue; fi
    echo "check-usda: $f: OK (tinyusdz loads it; its re-serialisation reads back with $a)"
  else
    echo "check-usda: $f: OK (tinyusdz loads it)"
  fi
done
exit $status
