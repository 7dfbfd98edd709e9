#!/usr/bin/env bash
# Call 2 (2026-12-02, evening): issue 11's side-by-side table on the tree of 04b48c5 (the dam break as
# each solver ships it, frames 20-40, the whole pipeline at 1920x1080, 64k-1M: bench-dfsph.sh), and the
# DFSPH dam break's ten seconds with the whole pipeline at 246,078.
set -u
[ -x build/gpu/app/ranryu ] || scripts/gpu/setup-and-build.sh ranryu > /tmp/b.txt 2>&1 || { tail -30 /tmp/b.txt; exit 1; }
. scripts/gpu/env.sh x
root=$OUT
mkdir -p "$root/bench"
OUT=$root/bench scripts/gpu/bench-dfsph.sh "dfsph wcsph pbf" "0.005 0.004 0.00317 0.0025 0.002" 20 20 > "$root/side-by-side.txt" 2>&1
tail -16 "$root/side-by-side.txt"
timeout 120 "$B" profile --scene dam-break --spacing 0.00317 --size 1920x1080 --frames 600 --warmup 0 \
  --json "$root/db-246k-10s.json" --records "$root/db-246k-10s.csv" > "$root/db-246k-10s.txt" 2>&1
echo "== ten seconds rc $?"; grep -E "fps and real-time|substeps/frame" "$root/db-246k-10s.txt"
