#!/usr/bin/env bash
# Call 2 (2026-12-02): the GL suite on the H200 with the tree of both of the day's DFSPH changes (the wall's
# gradient sum, the Kappa block's positions): the GPU passes against their CPU references on the driver
# the benchmarks run on (the rows' kappa_b read through the vec4 view's component index, among others).
set -u
scripts/gpu/setup-and-build.sh all > /tmp/b.txt 2>&1 || { tail -30 /tmp/b.txt; exit 1; }
export __EGL_VENDOR_LIBRARY_FILENAMES=/usr/local/nvidia/share/glvnd/egl_vendor.d/10_nvidia.json
{ nvidia-smi --query-gpu=name,driver_version --format=csv,noheader; date -u; } > "$OUT/device.txt"
timeout 400 build/gpu/tests/ranryu_gl_tests > "$OUT/gl-tests.txt" 2>&1
echo "gl tests rc $?"
tail -4 "$OUT/gl-tests.txt"
grep -B2 -A12 "FAILED" "$OUT/gl-tests.txt" | head -60
