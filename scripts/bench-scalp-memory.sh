#!/usr/bin/env bash
# Peak memory (/usr/bin/time %M) of the scalp field against groom's own estimate (shown by
# --verbose in the step's label), on every head of ../shared/datasets at its default voxel and at
# that voxel / DIV (default 4), for: `groom scalp`; `groom probe` converting the mesh (field + query
# bricks); `groom probe` loading the .vdb `groom scalp` wrote (it carries the repaired mesh); and,
# when OLD_GROOM names an older groom binary, loading the .vdb that one wrote (no stored mesh: the
# zero crossing is extracted). The probe reads every 97th vertex of the mesh. Prints a TSV row per
# head and voxel: name voxel, then estimate and peak (bytes) per command, then peak/estimate.
# Usage: scripts/bench-scalp-memory.sh [GROOM_BINARY]   (env: DIV, OLD_GROOM, DATASETS)
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
G=${1:-$root/build/groom}
D=${DATASETS:-$root/../shared/datasets}
div=${DIV:-4}
[ -d "$D" ] || { echo "$D not found" >&2; exit 1; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
heads=(
  "sintel_tressfx_opengl/sintel.obj|" "sintel_frostbitten/sintel-collider.obj|"
  "amd_tressfx_ponytail/ponytail_head.obj|" "amd_tressfx_ponytail/ponytail_head.obj|Mesh_head"
  "demosthenes_scan/demosthenes-low-res.obj|" "ict_facekit/generic_neutral_mesh.obj|"
  "lee_perry_smith/LeePerrySmith.obj|" "makehuman/base.obj|" "makehuman/base.obj|body"
  "nefertiti_scan/nefertiti-lowres.obj|" "ratboy_mohawk_tressfx/Ratboy_body.obj|"
)
# peak LABEL CMD...: runs CMD with --verbose; prints "estimate peak" in bytes.
peak() {
  local label=$1; shift
  /usr/bin/time -f "%M" -o "$tmp/t" "$@" -v >/dev/null 2>"$tmp/err"
  local est
  est=$(grep -o "$label (estimated [^)]*)" "$tmp/err" | head -1 | sed 's/.*estimated \([0-9.]*\) \([GMK]i*B\|bytes\).*/\1 \2/')
  awk -v e="$est" -v k="$(tail -1 "$tmp/t")" 'BEGIN { split(e, a, " "); m = a[2] == "GiB" ? 2^30 : a[2] == "MiB" ? 2^20 : 1;
    printf "%.0f %.0f", a[1] * m, k * 1024 }'
}
printf "head\tvoxel\tscalp_est\tscalp_peak\tmesh_est\tmesh_peak\tvdb_est\tvdb_peak\told_est\told_peak\n"
for hg in "${heads[@]}"; do
  mesh=$D/${hg%%|*} group=${hg##*|}
  [ -f "$mesh" ] || continue
  g=() sg=()
  [ -n "$group" ] && g=(--group "$group") sg=(--scalp-group "$group")
  grep '^v ' "$mesh" | awk 'NR % 97 == 1 { print $2, $3, $4 }' >"$tmp/pts.txt"
  h0=$("$G" scalp "$mesh" "${g[@]}" -o "$tmp/d.vdb" --force 2>&1 | sed -n 's/.*voxel \([0-9.e+-]*\),.*/\1/p')
  for h in "$h0" "$(awk -v h="$h0" -v d="$div" 'BEGIN { printf "%.6g", h / d }')"; do
    s=$(peak "signed distance" "$G" scalp "$mesh" "${g[@]}" --voxel "$h" -o "$tmp/s.vdb" --force)
    m=$(peak "signed distance" "$G" probe "$tmp/pts.txt" --scalp "$mesh" "${sg[@]}" --scalp-voxel "$h" -o "$tmp/p.csv" --force)
    v=$(peak "load scalp" "$G" probe "$tmp/pts.txt" --scalp "$tmp/s.vdb" -o "$tmp/p.csv" --force)
    o="- -"
    if [ -n "${OLD_GROOM:-}" ]; then
      "$OLD_GROOM" scalp "$mesh" "${g[@]}" --voxel "$h" -o "$tmp/o.vdb" -q --force
      o=$(peak "load scalp" "$G" probe "$tmp/pts.txt" --scalp "$tmp/o.vdb" -o "$tmp/p.csv" --force)
    fi
    printf "%s\t%s\t%s\t%s\t%s\t%s\n" "$(basename "$mesh" .obj)${group:+:$group}" "$h" "${s/ /	}" "${m/ /	}" "${v/ /	}" "${o/ /	}"
  done
done
