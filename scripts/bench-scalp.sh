#!/usr/bin/env bash
# Times `groom scalp` (read + repair + signed distance + write) against `vdb_tool -mesh2ls` on the
# same mesh and voxel size. The two alternate, ROUNDS times (default 5), and the best of each is
# compared: on a shared machine a burst of load then hits both alike.
# Usage: scripts/bench-scalp.sh MESH VOXEL [GROOM_BINARY]
set -euo pipefail
mesh=$1
voxel=$2
groom=${3:-$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)/build/groom}
rounds=${ROUNDS:-5}
command -v vdb_tool >/dev/null || { echo "vdb_tool not found (apt-get install libopenvdb-tools)" >&2; exit 1; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
seconds() {  # wall-clock seconds of one run
  local s e
  s=$(date +%s.%N); "$@" >/dev/null 2>&1; e=$(date +%s.%N)
  echo "$e - $s" | bc -l
}
g=1e9 v=1e9
for _ in $(seq "$rounds"); do
  t=$(seconds "$groom" scalp "$mesh" -o "$tmp/g.vdb" --voxel "$voxel" --band 3 -q --force)
  g=$(awk -v a="$t" -v b="$g" 'BEGIN { print (a < b) ? a : b }')
  t=$(seconds vdb_tool -read "$mesh" -mesh2ls voxel="$voxel" width=3 -write "$tmp/v.vdb")
  v=$(awk -v a="$t" -v b="$v" 'BEGIN { print (a < b) ? a : b }')
done
printf "%s voxel %s: groom scalp %.3f s, vdb_tool -mesh2ls %.3f s, ratio %.2f (best of %d, alternating)\n" \
  "$(basename "$mesh")" "$voxel" "$g" "$v" "$(echo "$g / $v" | bc -l)" "$rounds"
