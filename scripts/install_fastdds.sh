#!/usr/bin/env bash
# Install the Fast DDS toolchain the cross-vendor interop test builds its C++ node with
# (tests/interop/fastdds): Debian's Fast DDS 2.9 (the DDS under ROS 2 Humble's default
# rmw_fastrtps_cpp), Fast CDR, the fastddsgen IDL compiler, cmake and g++.
# Idempotent: does nothing when everything is already there; one apt-get update otherwise.
set -euo pipefail
PKGS=(libfastrtps-dev libfastcdr-dev fastddsgen cmake g++ make)
missing=()
for p in "${PKGS[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
    echo "== fastdds toolchain: already installed"
    exit 0
fi
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
echo "== fastdds toolchain: installing ${missing[*]}"
$SUDO apt-get update -qq
DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
echo "== fastdds toolchain: installed"
