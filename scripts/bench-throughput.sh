#!/usr/bin/env bash
# Issue 17's throughput table: `groom generate --count HAIRS` on Sintel's head (its 228 guides, the
# `.vdb` `groom scalp` writes), `groom curl` of those hairs and `curl --scalp`, each a whole process
# at 1 and 2 threads, beside the I/O floor (`groom convert` of the same output, same format), all as
# `.hair`. Runs alternate ROUNDS times (default 3), so a burst of load on a shared machine hits every
# command; each line prints the range of wall seconds and peak RSS over the rounds. The ratios the
# issue asks for (1 -> 2 threads, command / floor, curl --scalp / curl) are printed from the
# per-round walls, as ranges.
# Usage: [ROUNDS=3] [TMPDIR=/dev/shm] scripts/bench-throughput.sh [HAIRS] [BUILD_DIR]   (needs ../shared/datasets,
# /usr/bin/time; files go to mktemp -d, so TMPDIR on a RAM disk takes the disk out of every figure)
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
hairs=${1:-100000}
build=${2:-$root/build}
groom=$build/groom
data=$root/../shared/datasets/sintel_tressfx_opengl
rounds=${ROUNDS:-3}
[ -f "$data/sintel.obj" ] || { echo "bench-throughput: $data/sintel.obj not found (needs ../shared/datasets)" >&2; exit 2; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

"$groom" scalp "$data/sintel.obj" -o "$tmp/sintel.vdb" -q
"$groom" generate "$data/sintel_guides.obj" --scalp "$tmp/sintel.vdb" --count "$hairs" -o "$tmp/gen.hair" -q
"$groom" curl "$tmp/gen.hair" -o "$tmp/curl.hair" -q

run() {  # name command...: appends "wall rss_mb" of one run to $tmp/name
  # Wall from bash's microsecond clock (time's %e has 10 ms steps, a tenth of the 0.1 s floors);
  # peak RSS from /usr/bin/time.
  local name=$1 start end; shift
  start=$EPOCHREALTIME
  /usr/bin/time -f "%M" -o "$tmp/t" "$@" -q --force >/dev/null 2>&1
  end=$EPOCHREALTIME
  awk -v s="$start" -v e="$end" '{ printf "%.3f %.0f\n", e - s, $1 / 1024 }' "$tmp/t" >>"$tmp/$name"
}
for _ in $(seq "$rounds"); do
  for t in 1 2; do
    run "floor-gen-t$t" "$groom" convert "$tmp/gen.hair" -o "$tmp/x.hair" --threads "$t"
    run "generate-t$t" "$groom" generate "$data/sintel_guides.obj" --scalp "$tmp/sintel.vdb" --count "$hairs" -o "$tmp/x.hair" --threads "$t"
    run "floor-curl-t$t" "$groom" convert "$tmp/curl.hair" -o "$tmp/x.hair" --threads "$t"
    run "curl-t$t" "$groom" curl "$tmp/gen.hair" -o "$tmp/x.hair" --threads "$t"
    run "curl-scalp-t$t" "$groom" curl "$tmp/gen.hair" --scalp "$tmp/sintel.vdb" -o "$tmp/x.hair" --threads "$t"
  done
done

range() { sort -g | awk 'NR == 1 { lo = $1 } { hi = $1 } END { printf (lo == hi ? "%s" : "%s-%s"), lo, hi }'; }
ratios() { paste -d' ' "$tmp/$1" "$tmp/$2" | awk '{ printf "%.2f\n", $1 / $3 }' | range; }  # per-round wall a / wall b
echo "$(nproc) cores, load $(cut -d' ' -f1-3 /proc/loadavg), $hairs hairs, $rounds rounds alternating"
for name in floor-gen generate floor-curl curl curl-scalp; do
  for t in 1 2; do
    printf "%-14s %s thread(s): wall %-12s s  RSS %s MB\n" "$name" "$t" "$(cut -d' ' -f1 "$tmp/$name-t$t" | range)" \
      "$(cut -d' ' -f2 "$tmp/$name-t$t" | range)"
  done
done
echo "1 -> 2 threads:   generate $(ratios generate-t1 generate-t2)x  curl $(ratios curl-t1 curl-t2)x  curl --scalp $(ratios curl-scalp-t1 curl-scalp-t2)x"
for t in 1 2; do
  echo "against the floor, $t thread(s): generate $(ratios generate-t$t floor-gen-t$t)x  curl $(ratios curl-t$t floor-curl-t$t)x;" \
    "curl --scalp / curl $(ratios curl-scalp-t$t curl-t$t)x"
done
