#!/usr/bin/env bash
# On the GPU host, after setup-and-build.sh: the README's hero picture and clip in the water shading
# (docs/RENDERING.md) at 1920x1080, and a profile of that frame with its per-pass timings. Writes to
# $OUT (or ./hero-out):
#   dam-break-1m.png          frame 33 (0.55 s: the surge has climbed the far wall and folds back)
#   dam-break-1m.mp4          the first 1.5 s (90 frames, 60 fps, H.264), a few MB
#   turbulent-jet.png, .mp4   the jet at spacing 0.004 (~420k particles), frame 60 and 2 s
#   profile-dam-break-1m.txt, .json   `profile` of the 1M dam break at 1920x1080 (per-pass ms)
#   *.log                     each command's output
# The dam break at spacing 0.002 has 1.0M particles (0.2 x 0.4 x 0.1 m of water). Without ffmpeg on
# the host the clips are skipped (say so) and only the pictures are made. `hero.sh smoke` runs the
# same commands at the scenes' own spacings, 320x180 and a few frames (a check of the script on llvmpipe).
set -uo pipefail
cd "$(dirname "$0")/../.."
out=${OUT:-hero-out}
mkdir -p "$out"
B=${RANRYU_BIN:-build/gpu/app/ranryu}
size=1920x1080 dam=0.002 jet=0.004 scale=1
if [ "${1:-}" = smoke ]; then size=320x180 dam=0.0125 jet=0.025 scale=10; fi
tmp=$(mktemp -d)
have_ffmpeg=1
command -v ffmpeg >/dev/null || { have_ffmpeg=0; echo "hero.sh: no ffmpeg on this host: pictures only, no clips"; }

# record SCENE SPACING FRAMES HERO_FRAME NAME
record() {
  local scene=$1 spacing=$2 frames=$(( $3 / scale )) hero=$(( $4 / scale )) name=$5
  local video=()
  [ $have_ffmpeg = 1 ] && video=(--video "$out/$name.mp4")
  $B record --scene "$scene" --spacing "$spacing" --shading water --size $size --frames "$frames" \
     --out "$tmp/$name" --force "${video[@]}" --quiet > "$out/$name.log" 2>&1
  echo "== record $name: rc $?"
  cp "$tmp/$name/$(printf 'frame_%05d.png' "$hero")" "$out/$name.png" && echo "   $out/$name.png"
  cp "$tmp/$name/run.json" "$out/$name.run.json" 2>/dev/null
  [ $have_ffmpeg = 1 ] && ls -l "$out/$name.mp4"
  rm -rf "${tmp:?}/$name"
}

record dam-break $dam 90 33 dam-break-1m
record turbulent-jet $jet 120 60 turbulent-jet

$B profile --scene dam-break --spacing $dam --shading water --size $size --frames $(( 60 / scale )) --warmup $(( 10 / scale )) \
   --json "$out/profile-dam-break-1m.json" > "$out/profile-dam-break-1m.txt" 2>&1
echo "== profile dam-break 1M $size: rc $?"
grep -E "^(shadow-map|clear|draw-|liquid-thickness|compose|level-set|mc\.|surface\.|frame|total)" "$out/profile-dam-break-1m.txt"
rm -rf "$tmp"
