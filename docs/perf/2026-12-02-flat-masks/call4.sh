#!/usr/bin/env bash
# Call 4 (by hand, the same session): nvdisasm of the programs call 3 cut from the driver's cache on the
# development machine (zstd is not on the GPU host): scratch/sass-blobs/{current,flat2}-{24,25}.sass,
# program 24 the density solve's accelerate pass, 25 its residual pass.
cd scratch/sass-blobs && for f in current-24 flat2-24 current-25 flat2-25; do /usr/local/cuda/bin/nvdisasm -b SM90 $f.sass > $OUT/$f.txt 2>&1; echo "$f $(wc -l < $OUT/$f.txt)"; done
