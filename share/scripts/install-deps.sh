#!/usr/bin/env bash
# Installs every Debian bookworm package roislam needs to build, test and run.
# Idempotent: apt-get skips what is already installed, so re-running is safe.
set -euo pipefail
if [ "$(id -u)" -ne 0 ]; then
  echo "install-deps.sh: must run as root (apt-get install)" >&2
  exit 1
fi
export DEBIAN_FRONTEND=noninteractive
PKGS=(
  build-essential cmake pkg-config git ca-certificates
  libmrpt-dev mrpt-apps
  libopencv-dev libeigen3-dev liboctomap-dev libopenni2-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  libcli11-dev nlohmann-json3-dev
  gnuplot-nox clang-format
  clang-14 libclang-rt-14-dev
  libegl1 libegl-mesa0 libgl1-mesa-dri
  # The live view (--gui): X11 client, wx headers (canvas-only repaints),
  # and for its tests and screenshots a virtual display and key presses.
  libx11-dev libwxgtk3.2-dev xvfb xdotool
)
missing=()
for p in "${PKGS[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ "${#missing[@]}" -eq 0 ]; then
  echo "install-deps.sh: all ${#PKGS[@]} packages already installed"
  exit 0
fi
apt-get update
apt-get install -y --no-install-recommends "${missing[@]}"
