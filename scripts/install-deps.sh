#!/usr/bin/env bash
# Installs the Debian 12 packages ranryu needs to build, run headless (Mesa llvmpipe when there is
# no GPU) and test (Xvfb for the window test; ffmpeg and ffprobe for the video tests;
# python3-jsonschema for the scene schema's test; python3-matplotlib for scripts/sweep-charts.py). ffmpeg
# is a runtime option for users: only `ranryu record --video` runs it, and says so when it is missing.
# Only missing packages are installed; through sudo when not run as root.
set -euo pipefail
pkgs=(g++ cmake ninja-build pkg-config
      libegl-dev libopengl-dev libgl-dev libegl-mesa0 libgl1-mesa-dri libglx-mesa0
      libglm-dev libstb-dev nlohmann-json3-dev catch2 libglfw3-dev libimgui-dev
      xvfb xauth ffmpeg python3-matplotlib python3-jsonschema)
missing=()
for p in "${pkgs[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0
echo "install-deps: installing ${missing[*]}"
sudo=""
if [ "$(id -u)" -ne 0 ]; then
  command -v sudo >/dev/null || { echo "install-deps: need root or sudo to install: ${missing[*]}" >&2; exit 1; }
  sudo="sudo"
fi
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq
$sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
