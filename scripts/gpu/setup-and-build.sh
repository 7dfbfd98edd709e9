#!/usr/bin/env bash
# On the lent GPU host (see docs/PERFORMANCE.md): unpack the GL libraries and headers carried in .gl/
# (filled here by ../shared/gpu-host/fetch-debs.sh nlohmann-json3-dev), point GLVND's EGL at the
# NVIDIA driver, and build the headless Release configuration into build/gpu (tests included).
set -euo pipefail
cd "$(dirname "$0")/../.."
for f in .gl/*.deb; do dpkg -x "$f" /; done
ldconfig
export __EGL_VENDOR_LIBRARY_FILENAMES=/usr/local/nvidia/share/glvnd/egl_vendor.d/10_nvidia.json
cmake -S . -B build/gpu -G Ninja -DCMAKE_BUILD_TYPE=Release -DRANRYU_WINDOW=OFF >/dev/null
cmake --build build/gpu -j 16 --target "${1:-all}"
nvidia-smi --query-gpu=name,driver_version,clocks.sm,clocks.mem --format=csv,noheader || true
