#!/usr/bin/env bash
# Cross-checks groom's USD reader against tinyusdz (an independent USD implementation, npm build):
#
#   scripts/check-usd-tinyusdz.sh xforms            # xform ops: tinyusdz's world matrices vs groom's points
#   scripts/check-usd-tinyusdz.sh compose FILE...   # composition: tinyusdz flattens the file (inherits,
#                                                   # variants, references, payloads); groom must read the
#                                                   # same curves from the flattened file as from the original
#
# `xforms` writes a file of Xform prims covering every op (translate, scale, rotateX/Y/Z, the six
# rotate orders, orient, transform, !invert!, !resetXformStack!, nesting); each holds a Mesh (whose
# world matrix tinyusdz reports) and a BasisCurves probe with points at the origin and the unit axes
# (whose transformed points groom reports): the probe's points give groom's matrix column by column.
# Curves are compared as multisets (tinyusdz reorders prims), to 1e-4 relative.
# Uses the tinyusdz cached by scripts/check-usda.sh (never installs). Exit 0 pass, 1 fail, 77 unavailable.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cache=${GROOM_TINYUSDZ_DIR:-${XDG_CACHE_HOME:-$HOME/.cache}/groom-tinyusdz}
groom=${GROOM:-$root/build/groom}
py=/usr/bin/python3
if ! command -v node >/dev/null 2>&1 || [[ ! -f $cache/node_modules/tinyusdz/tinyusdz.wasm ]]; then
  echo "check-usd-tinyusdz: node or a cached tinyusdz ($cache) missing; skipped" >&2
  exit 77
fi
mode=${1:-}
shift || true
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

cat > "$cache/groom-usd-check.mjs" <<'JS'
// node groom-usd-check.mjs nodes FILE      -> one line per mesh node: absPath and its global matrix (row vectors)
// node groom-usd-check.mjs flatten IN OUT  -> the layer with inherits, variants, references, payloads composed
import { readFileSync, writeFileSync } from 'fs';
import { fileURLToPath } from 'url';
process.type = 'renderer';
globalThis.window = globalThis;
const dir = fileURLToPath(new URL('./node_modules/tinyusdz/', import.meta.url));
const { default: init } = await import(dir + 'tinyusdz.js');
const m = await init({ wasmBinary: readFileSync(dir + 'tinyusdz.wasm'), print: () => {}, printErr: () => {} });
const [mode, file, out] = process.argv.slice(2);
const bytes = new Uint8Array(readFileSync(file));
const t = new m.TinyUSDZLoaderNative();
if (mode === 'nodes') {
  if (!t.loadFromBinary(bytes, file)) { console.error(`tinyusdz: ${file}: failed to load`); process.exit(1); }
  const walk = (n) => {
    if (n.nodeType === 'mesh') console.log(n.absPath + ' ' + Array.from(n.globalMatrix).join(' '));
    for (const c of n.children || []) walk(c);
  };
  for (let i = 0; i < t.numRootNodes(); ++i) walk(t.getRootNode(i));
} else {
  if (!t.loadAsLayerFromBinary(bytes, file)) { console.error(`tinyusdz: ${file}: failed to load as a layer`); process.exit(1); }
  // Twice: an arc's target may itself bring arcs.
  for (let pass = 0; pass < 2; ++pass)
    for (const step of ['composeInherits', 'composeVariants', 'composeReferences', 'composePayload'])
      if (!t[step]()) { console.error(`tinyusdz: ${file}: ${step} failed`); process.exit(1); }
  writeFileSync(out, t.layerToString());
}
JS

status=0
case $mode in
xforms)
  "$py" - "$tmp/x.usda" <<'PY'
import sys
cases = [
    ('t', ['double3 xformOp:translate = (1, -2, 3)'], ['xformOp:translate']),
    ('s', ['float3 xformOp:scale = (2, 3, 0.5)'], ['xformOp:scale']),
    ('rx', ['double xformOp:rotateX = 30'], ['xformOp:rotateX']),
    ('ry', ['float xformOp:rotateY = -75'], ['xformOp:rotateY']),
    ('rz', ['float xformOp:rotateZ = 120'], ['xformOp:rotateZ']),
    ('o', ['quatf xformOp:orient = (0.9238795, 0.2209424, 0.2209424, 0.2209424)'], ['xformOp:orient']),
    ('m', ['matrix4d xformOp:transform = ( (0.5, 0.1, 0, 0), (-0.2, 1, 0.3, 0), (0, 0.4, 2, 0), (7, 8, 9, 1) )'], ['xformOp:transform']),
    ('trs', ['double3 xformOp:translate = (1, 2, 3)', 'float3 xformOp:rotateXYZ = (30, 45, 60)', 'float3 xformOp:scale = (2, 3, 4)'],
     ['xformOp:translate', 'xformOp:rotateXYZ', 'xformOp:scale']),
    ('pivot', ['double3 xformOp:translate:pivot = (1, 0, 2)', 'float3 xformOp:rotateXYZ = (10, 20, 30)'],
     ['xformOp:translate:pivot', 'xformOp:rotateXYZ', '!invert!xformOp:translate:pivot']),
]
for order in ['XYZ', 'XZY', 'YXZ', 'YZX', 'ZXY', 'ZYX']:
    cases.append(('r' + order, [f'float3 xformOp:rotate{order} = (20, 50, 70)'], [f'xformOp:rotate{order}']))
def leaf():
    return ('def Mesh "mesh" {\n int[] faceVertexCounts = [3]\n int[] faceVertexIndices = [0, 1, 2]\n point3f[] points = [(1,0,0), (0,1,0), (0,0,1)]\n}\n'
            'def BasisCurves "probe" {\n uniform token type = "linear"\n int[] curveVertexCounts = [4]\n'
            ' point3f[] points = [(0,0,0), (1,0,0), (0,1,0), (0,0,1)]\n}\n')
def xform(name, props, order, body):
    text = f'def Xform "{name}" {{\n' + ''.join(p + '\n' for p in props)
    text += 'uniform token[] xformOpOrder = [' + ', '.join(f'"{o}"' for o in order) + ']\n'
    return text + body + '}\n'
out = '#usda 1.0\n'
for name, props, order in cases:
    out += xform(name, props, order, leaf())
# Nesting, and a reset under a transformed parent.
out += xform('outer', ['double3 xformOp:translate = (5, 0, 0)', 'float3 xformOp:rotateZYX = (15, 25, 35)'], ['xformOp:translate', 'xformOp:rotateZYX'],
             xform('inner', ['float3 xformOp:scale = (1, 2, 3)', 'double xformOp:rotateY = 40'], ['xformOp:rotateY', 'xformOp:scale'], leaf()) +
             xform('reset', ['double3 xformOp:translate = (0, 1, 0)'], ['!resetXformStack!', 'xformOp:translate'], leaf()))
open(sys.argv[1], 'w').write(out)
PY
  node "$cache/groom-usd-check.mjs" nodes "$tmp/x.usda" > "$tmp/tiny.txt"
  "$groom" convert "$tmp/x.usda" -o "$tmp/groom.ply" --ascii -q
  # Probe order in groom's output is traversal order: the same as the file's, as is tinyusdz's node walk.
  "$py" - "$tmp/tiny.txt" "$tmp/groom.ply" <<'PY' || status=1
import sys
tiny = [l.split() for l in open(sys.argv[1]) if l.strip()]
lines = open(sys.argv[2]).read().split('\n')
n = int([l for l in lines if l.startswith('element vertex')][0].split()[2])
start = lines.index('end_header') + 1
pts = [list(map(float, l.split()[:3])) for l in lines[start:start + n]]
if len(pts) != 4 * len(tiny):
    sys.exit(f'check-usd-tinyusdz: {len(tiny)} meshes from tinyusdz but {len(pts)} probe points from groom')
worst = 0.0
for i, row in enumerate(tiny):
    path, M = row[0], list(map(float, row[1:]))
    o, x, y, z = pts[4 * i:4 * i + 4]
    # Row-vector matrix: origin -> row 3; axis k -> row k + row 3.
    want = [M[12:15]] + [[M[4 * k + j] + M[12 + j] for j in range(3)] for k in range(3)]
    got = [o, x, y, z]
    err = max(abs(a - b) / max(1.0, abs(a)) for w, g in zip(want, got) for a, b in zip(w, g))
    worst = max(worst, err)
    print(f'{path}: max relative difference {err:.2e}')
    if err > 1e-4:
        print(f'  tinyusdz {want}\n  groom    {got}')
print(f'check-usd-tinyusdz xforms: {len(tiny)} transforms, worst difference {worst:.2e}')
sys.exit(0 if worst <= 1e-4 else 1)
PY
  ;;
compose)
  for f in "$@"; do
    node "$cache/groom-usd-check.mjs" flatten "$f" "$tmp/flat.usda" || { status=1; continue; }
    "$groom" convert "$f" -o "$tmp/a.ply" --ascii -q
    "$groom" convert "$tmp/flat.usda" -o "$tmp/b.ply" --ascii -q
    "$py" - "$tmp/a.ply" "$tmp/b.ply" "$f" <<'PY' || status=1
import sys
def curves(path):
    lines = open(path).read().split('\n')
    el = {l.split()[1]: int(l.split()[2]) for l in lines if l.startswith('element ')}
    start = lines.index('end_header') + 1
    pts = [tuple(round(float(v), 4) for v in l.split()[:3]) for l in lines[start:start + el['vertex']]]
    counts = [int(l.split()[0]) for l in lines[start + el['vertex'] + el.get('edge', 0):][:el.get('curve', 0)]]
    out, i = [], 0
    for c in counts:
        out.append(tuple(pts[i:i + c]))
        i += c
    return sorted(out)
a, b = curves(sys.argv[1]), curves(sys.argv[2])
same = a == b
print(f'check-usd-tinyusdz compose: {sys.argv[3]}: {len(a)} curves from the file, {len(b)} from tinyusdz\'s flattening: ' + ('same' if same else 'DIFFERENT'))
sys.exit(0 if same else 1)
PY
  done
  ;;
*)
  echo "usage: $0 xforms | compose FILE.usda..." >&2
  exit 2
  ;;
esac
exit $status
