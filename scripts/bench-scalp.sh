#!/usr/bin/env bash
# Times `groom scalp` (repair + signed distance + write) against `vdb_tool -mesh2ls` on the same mesh
# and voxel size. Usage: scripts/bench-scalp.sh MESH.obj VOXEL [GROOM_BINARY]
set -euo pipefail
mesh=$1
voxel=$2
groom=${3:-$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)/build/groom}
command -v vdb_tool >/dev/null || { echo "vdb_tool not found (apt-get install libopenvdb-tools)" >&2; exit 1; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
best() {  # best of 3 wall-clock seconds
  local b=1e9
  for _ in 1 2 3; do
    local s e
    s=$(date +%s.%N); "$@" >/dev/null 2>&1; e=$(date +%s.%N)
    b=$(echo "$e - $s" | bc -l | awk -v b="$b" '{print ($1 < b) ? $1 : b}')
  done
  echo "$b"
}
g=$(best "$groom" scalp "$mesh" -o "$tmp/g.vdb" --voxel "$voxel" --band 3 -q --force)
v=$(best vdb_tool -read "$mesh" -mesh2ls voxel="$voxel" width=3 -write "$tmp/v.vdb")
printf "%s voxel %s: groom scalp %.3f s, vdb_tool -mesh2ls %.3f s, ratio %.2f\n" "$(basename "$mesh")" "$voxel" "$g" "$v" "$(echo "$g / $v" | bc -l)"
