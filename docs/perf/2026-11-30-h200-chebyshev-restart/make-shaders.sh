#!/usr/bin/env bash
# Run in the repository's root before a call of this folder (scratch/ travels with the tree): the shader
# folders its calls read, from glsl/, this folder's patches and the wall-drag folder's drag-out shaders.
#   scratch/glsl-restart, -overshoot                   glsl/ with restart.patch, overshoot.patch
#   scratch/glsl-dragout-restart, -dragout-overshoot   the drag implicit and out of (D8)'s force
#                                                      condition (docs/perf/2026-11-30-h200-wall-drag/) with the same
#   scratch/glsl-rows-restart, -fluid-restart, -big-restart, -wall-restart   the drag out with that patch
set -eu
here=docs/perf/2026-11-30-h200-chebyshev-restart
bash docs/perf/2026-11-30-h200-wall-drag/make-shaders.sh
put() {   # put FOLDER BASE PATCH
  rm -rf "scratch/$1" && cp -r "$2" "scratch/$1"
  patch -s -d "scratch/$1" -p2 < "$here/$3"
}
put glsl-restart glsl restart.patch
put glsl-overshoot glsl overshoot.patch
put glsl-dragout-restart scratch/glsl-dragout restart.patch
put glsl-dragout-overshoot scratch/glsl-dragout overshoot.patch
for v in rows-restart fluid-restart big-restart wall-restart; do put glsl-$v scratch/glsl-dragout $v.patch; done
