#!/usr/bin/env bash
# `groom probe` end to end (whole processes: read the points, load the scalp, query, write the CSV)
# against bench/probe_reference.cpp, the plain CGAL program a user would write (CGAL's OBJ reader,
# AABB tree with accelerate_distance_queries, iostream in, printf out), on 2M points around Sintel's
# head (`../shared/datasets/sintel_tressfx_opengl`).
#
# Two sets of 2,000,000 points:
#   hair: every point of 62,500 hairs x 32 points grown by `groom generate` from Sintel's 228 real
#         guides: what a TD probes (hair against the scalp), mostly 0-10 voxels (0-2.3 cm) out;
#   box:  uniform in the mesh's bounding box grown by 10%: far points and points inside, where
#         the narrow band helps nothing.
# Each is given as text (`x y z` lines, 67 MB) and as .npy (float32, 24 MB); the scalp as the OBJ
# mesh and as a .vdb from `groom scalp`. Runs alternate (reference, then groom), ROUNDS times
# (default 3), so a burst of load on the shared machine hits both; each line prints the range of
# wall seconds, CPU seconds and peak RSS over the rounds and the range of the per-round ratios
# (reference wall / groom wall).
# Usage: [ROUNDS=3] [SETS="hair box"] [KEEP=DIR] scripts/bench-probe.sh [BUILD_DIR]   (needs /usr/bin/time and python3)
# KEEP=DIR makes the inputs in DIR once and reuses them (for profiling the same files, or comparing
# builds); by default they go to a temporary folder, removed at the end.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${1:-$root/build}
groom=$build/groom
ref=$build/probe_reference
data=${DATA:-$root/../shared/datasets/sintel_tressfx_opengl}
rounds=${ROUNDS:-3}
[ -x "$ref" ] || { echo "$ref not built (GROOM_BUILD_BENCHMARKS=ON)" >&2; exit 1; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
inputs=${KEEP:-$tmp}
mkdir -p "$inputs"

if [ ! -s "$inputs/box.npy" ]; then
"$groom" generate "$data/sintel_guides.obj" --scalp "$data/sintel.obj" --count 62500 -o "$tmp/hair.ply" -q
"$groom" convert "$tmp/hair.ply" -o "$tmp/hair.obj" -q
grep '^v ' "$tmp/hair.obj" | cut -c3- >"$tmp/hair.txt"
"$groom" scalp "$data/sintel.obj" -o "$tmp/sintel.vdb" -q
python3 - "$data/sintel.obj" "$tmp" <<'EOF'
import random, struct, sys
mesh, tmp = sys.argv[1], sys.argv[2]
vs = [tuple(map(float, l.split()[1:4])) for l in open(mesh) if l.startswith('v ')]
lo = [min(v[k] for v in vs) for k in range(3)]
hi = [max(v[k] for v in vs) for k in range(3)]
pad = [0.05 * (h - l) for l, h in zip(lo, hi)]
rng = random.Random(17)
with open(f'{tmp}/box.txt', 'w') as f:
    for _ in range(2_000_000):
        f.write(' '.join(repr(struct.unpack('f', struct.pack('f', rng.uniform(l - p, h + p)))[0]) for l, h, p in zip(lo, hi, pad)) + '\n')
def npy(name):  # the text's float32 values as a (N, 3) '<f4' array
    vals = [float(t) for line in open(f'{tmp}/{name}.txt') for t in line.split()]
    head = "{'descr': '<f4', 'fortran_order': False, 'shape': (%d, 3), }" % (len(vals) // 3)
    head += ' ' * ((64 - (10 + len(head) + 1) % 64) % 64) + '\n'
    with open(f'{tmp}/{name}.npy', 'wb') as f:
        f.write(b'\x93NUMPY\x01\x00' + struct.pack('<H', len(head)) + head.encode())
        f.write(struct.pack('<%df' % len(vals), *vals))
npy('hair'); npy('box')
EOF
[ "$inputs" = "$tmp" ] || cp "$tmp"/hair.txt "$tmp"/box.txt "$tmp"/hair.npy "$tmp"/box.npy "$tmp"/sintel.vdb "$inputs"/
fi

measure() {  # prints "wall cpu rss_mb" of one run
  /usr/bin/time -f "%e %U %S %M" -o "$tmp/t" "$@" >/dev/null 2>&1
  awk '{ printf "%.2f %.2f %.0f\n", $1, $2 + $3, $4 / 1024 }' "$tmp/t"
}
range() {  # "lo-hi" of a column of numbers
  sort -g | awk 'NR == 1 { lo = $1 } { hi = $1 } END { printf (lo == hi ? "%s" : "%s-%s"), lo, hi }'
}
report() {  # name file-of-"wall cpu rss ratio" lines
  printf "%-44s wall %-11s s  CPU %-11s s  RSS %-9s MB" "$1" "$(cut -d' ' -f1 "$2" | range)" "$(cut -d' ' -f2 "$2" | range)" \
    "$(cut -d' ' -f3 "$2" | range)"
  if [ "$(awk 'NF > 3' "$2" | wc -l)" -gt 0 ]; then printf "  reference/groom %sx" "$(cut -d' ' -f4 "$2" | range)"; fi
  printf "\n"
}

echo "$(nproc) cores, load $(cut -d' ' -f1-3 /proc/loadavg), $rounds rounds alternating; 2,000,000 points each"
for set in ${SETS:-hair box}; do
  : >"$tmp/ref1" >"$tmp/ref2"
  for v in mesh-t1 mesh-t2 npy-t2 npyout-t2 vdb-t2; do : >"$tmp/$v"; done
  for _ in $(seq "$rounds"); do
    r1=$(measure "$ref" "$data/sintel.obj" "$inputs/$set.txt" "$tmp/ref.csv" 1); echo "$r1" >>"$tmp/ref1"
    r2=$(measure "$ref" "$data/sintel.obj" "$inputs/$set.txt" "$tmp/ref.csv" 2); echo "$r2" >>"$tmp/ref2"
    run() {  # variant ref-line groom-args...
      local v=$1 against=$2; shift 2
      local g; g=$(measure "$groom" probe "$@" -q --force)
      echo "$g $(echo "${against%% *} ${g%% *}" | awk '{ printf "%.2f", $1 / $2 }')" >>"$tmp/$v"
    }
    run mesh-t1 "$r1" --scalp "$data/sintel.obj" "$inputs/$set.txt" -o "$tmp/g.csv" --threads 1
    run mesh-t2 "$r2" --scalp "$data/sintel.obj" "$inputs/$set.txt" -o "$tmp/g.csv" --threads 2
    run npy-t2 "$r2" --scalp "$data/sintel.obj" "$inputs/$set.npy" -o "$tmp/g.csv" --threads 2
    run npyout-t2 "$r2" --scalp "$data/sintel.obj" "$inputs/$set.npy" -o "$tmp/g.npy" --threads 2
    run vdb-t2 "$r2" --scalp "$inputs/sintel.vdb" "$inputs/$set.txt" -o "$tmp/g.csv" --threads 2
  done
  report "$set: reference, 1 thread" "$tmp/ref1"
  report "$set: reference, queries on 2 threads" "$tmp/ref2"
  report "$set: groom, mesh, text, 1 thread (vs ref 1)" "$tmp/mesh-t1"
  report "$set: groom, mesh, text, 2 threads (vs ref 2)" "$tmp/mesh-t2"
  report "$set: groom, mesh, .npy in, 2 threads (vs ref 2)" "$tmp/npy-t2"
  report "$set: groom, mesh, .npy in and out (vs ref 2)" "$tmp/npyout-t2"
  report "$set: groom, .vdb, text, 2 threads (vs ref 2)" "$tmp/vdb-t2"
done
