#!/usr/bin/env bash
# Installs what certipose needs on Debian 12, and nothing when it is all there (idempotent).
set -euo pipefail
packages=(g++ cmake ninja-build ccache libeigen3-dev libboost-dev libcgal-dev libgmp-dev libmpfr-dev
          libtbb-dev doctest-dev libbenchmark-dev nlohmann-json3-dev libcli11-dev
          libopenmpi-dev openmpi-bin libglpk-dev clang-14 libclang-rt-14-dev)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]} == 0)); then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi
echo "install-deps: installing ${missing[*]}"
sudo=""
[ "$(id -u)" -eq 0 ] || sudo="sudo"
$sudo apt-get update -qq
DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
