#!/usr/bin/env bash
# Installs what certipose needs on Debian 12, and nothing when it is all there (idempotent):
# the C++ toolchain and libraries, and for the Python module (docs/python.md) pybind11, the
# Python headers, venv and pip (its build backend needs nothing else) and matplotlib (its
# example's plot); OpenCASCADE's data-exchange and modelling toolkits read STEP files
# (io/read_step.hpp; LGPL-2.1 with the OCCT exception); ROS's check_urdf (liburdfdom-tools),
# Chromium and Open3D (python3-open3d: a mesh tool that is not ours) only test what the exports,
# the viewer and the Python helpers write.
set -euo pipefail
packages=(g++ cmake ninja-build ccache libeigen3-dev libboost-dev libcgal-dev libgmp-dev libmpfr-dev
          libtbb-dev doctest-dev libbenchmark-dev nlohmann-json3-dev libcli11-dev
          libopenmpi-dev openmpi-bin libglpk-dev clang-14 libclang-rt-14-dev libyaml-cpp-dev libtinygltf-dev
          libocct-data-exchange-dev libocct-modeling-algorithms-dev
          chromium liburdfdom-tools python3-numpy python3-pytest
          pybind11-dev python3-dev python3-venv python3-pip python3-matplotlib python3-open3d)
# Node.js bundles the web viewer (certipose-export --format html) and runs its tests; a machine
# that has no `node` gets Debian's (18 on Debian 12). The lockfile is pinned to versions whose
# `engines` Debian's Node.js meets; the check after the install refuses an older `node`.
web="$(dirname "$0")/../web"
command -v node >/dev/null || packages+=(nodejs npm)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]} == 0)); then
  echo "install-deps: all ${#packages[@]} packages present"
else
  echo "install-deps: installing ${missing[*]}"
  sudo=""
  [ "$(id -u)" -eq 0 ] || sudo="sudo"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
# The oldest Node.js every locked package accepts: the largest "node": ">=N" in the lockfile.
need_node=$(grep -o '"node": *">= *[0-9]*' "$web/package-lock.json" | grep -o '[0-9]*$' | sort -n | tail -1)
have_node=$(node -p 'process.versions.node' 2>/dev/null || echo none)
if [ "${have_node%%.*}" = none ] || [ "${have_node%%.*}" -lt "${need_node:-0}" ]; then
  echo "install-deps: web/package-lock.json needs Node.js >= ${need_node}, but \`node\` is ${have_node}" \
       "($(command -v node || echo 'not on PATH')). Remove that node so that Debian's nodejs is installed," \
       "or put Node.js >= ${need_node} first on PATH, then run this again." >&2
  exit 1
fi
command -v npm >/dev/null || {
  echo "install-deps: Node.js ${have_node} has no \`npm\`: install the npm of that Node.js" \
       "(Debian's nodejs needs the package npm), then run this again." >&2
  exit 1
}
# The web viewer's JavaScript (three.js, esbuild, gltf-validator, playwright-core), exactly as the
# lockfile pins it; again only when web/node_modules is missing or older than the lockfile.
if [ ! -f "$web/node_modules/.package-lock.json" ] || [ "$web/package-lock.json" -nt "$web/node_modules/.package-lock.json" ]; then
  echo "install-deps: npm ci in web/"
  (cd "$web" && npm ci --no-audit --no-fund --loglevel=error)
fi
