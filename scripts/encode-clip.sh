#!/usr/bin/env bash
# Encodes a clip's frames (a folder or a tar of frame_NNNNN.jpg or .png, as scripts/gpu/clip.sh or
# `ranryu record` write them) into an H.264 mp4 at 60 fps, and a GIF preview at 30 fps and half size.
# Usage: scripts/encode-clip.sh FRAMES OUT.mp4 [OUT.gif]
set -euo pipefail
src=$1 mp4=$2 gif=${3:-}
command -v ffmpeg >/dev/null || { echo "encode-clip.sh: ffmpeg is not installed" >&2; exit 1; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
if [ -f "$src" ]; then tar xf "$src" -C "$tmp"; src=$(dirname "$(find "$tmp" -name 'frame_00000.*' | head -1)"); fi
ext=$(ls "$src" | grep -m1 -oE '\.(jpg|png)$')
ffmpeg -loglevel error -y -framerate 60 -i "$src/frame_%05d$ext" -c:v libx264 -pix_fmt yuv420p -crf 24 -preset slow \
  -movflags +faststart "$mp4"
ls -l "$mp4"
if [ -n "$gif" ]; then
  ffmpeg -loglevel error -y -framerate 60 -i "$src/frame_%05d$ext" \
    -vf "fps=30,scale=iw/2:-1:flags=lanczos,split[a][b];[a]palettegen=max_colors=128[p];[b][p]paletteuse=dither=bayer" "$gif"
  ls -l "$gif"
fi
