# Sourced by the scripts of scripts/gpu/ that run the built binary on the GPU host (after
# setup-and-build.sh): the repository root as the working folder, $out (from $OUT, else the default
# given) made, $B the binary ($RANRYU_BIN, else build/gpu/app/ranryu), and GLVND's EGL on the NVIDIA
# driver, as setup-and-build.sh sets it, where that driver's file is.
#     . "$(dirname "$0")/env.sh" bench-out
set -uo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/../.."
out=${OUT:-$1}
mkdir -p "$out"
B=${RANRYU_BIN:-build/gpu/app/ranryu}
nvidia_egl=/usr/local/nvidia/share/glvnd/egl_vendor.d/10_nvidia.json
[ -e "$nvidia_egl" ] && export __EGL_VENDOR_LIBRARY_FILENAMES=${__EGL_VENDOR_LIBRARY_FILENAMES:-$nvidia_egl}
