#!/usr/bin/env bash
# On the GPU host, after setup-and-build.sh: the frames of the README's clips, for a host without
# ffmpeg. Records each clip with `ranryu record --shading water`, converts its PNG frames to JPEG
# (quality 85, Pillow in the host's python3) and packs them into $OUT/clip-NAME.tar, split into parts
# of 15 MB (clip-NAME.tar.aa, .ab, ...: the device tool returns files of up to 16 MB); join them with
# cat and encode them where ffmpeg is (scripts/encode-clip.sh). Usage:
#     scripts/gpu/clip.sh NAME SCENE SOLVER SPACING FRAMES SIZE [NAME SCENE SOLVER SPACING FRAMES SIZE ...]
# e.g. scripts/gpu/clip.sh dam-break-pbf-246k dam-break pbf 0.00317 150 1280x720
set -uo pipefail
cd "$(dirname "$0")/../.."
out=${OUT:-clip-out}
mkdir -p "$out"
B=${RANRYU_BIN:-build/gpu/app/ranryu}
PY=${PYTHON:-python3}
tmp=$(mktemp -d)
while [ $# -ge 6 ]; do
  name=$1 scene=$2 solver=$3 spacing=$4 frames=$5 size=$6
  shift 6
  start=$(date +%s.%N)
  $B record --scene "$scene" --solver "$solver" --spacing "$spacing" --shading water --size "$size" --frames "$frames" \
     --out "$tmp/$name" --force --quiet > "$out/clip-$name.log" 2>&1
  rc=$?
  echo "== record $name ($scene, $solver, spacing $spacing, $frames frames at $size): rc $rc, $(echo "$(date +%s.%N) - $start" | bc) s"
  tail -3 "$out/clip-$name.log"
  "$PY" - "$tmp/$name" <<'PY'
import pathlib, sys
from PIL import Image
d = pathlib.Path(sys.argv[1])
for png in sorted(d.glob("frame_*.png")):
    Image.open(png).convert("RGB").save(png.with_suffix(".jpg"), quality=85)
    png.unlink()
PY
  cp "$tmp/$name/run.json" "$tmp/$name/run-$name.json" 2>/dev/null
  tar cf - -C "$tmp" "$name" | split -b 15M - "$out/clip-$name.tar."
  ls -l "$out/clip-$name.tar."*
  rm -rf "${tmp:?}/$name"
done
rm -rf "$tmp"
