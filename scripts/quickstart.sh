#!/usr/bin/env bash
# README command (1): install what is missing, build the programs the README shows (Release,
# -O2: certipose-solve, -part, -plan, -verify, -export, the sample part and the Python module
# in build/release/python, docs/python.md) and run the
# main example — the paper's case study (§8) — on the bundled sample part: facet 900, a
# top-surface facet next to a protrusion, ε_p = 0.1 m, ε_o = 0.38 rad, the camera of examples/data/camera.json.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
cmake --preset release -DCERTIPOSE_BUILD_TESTS=OFF
cmake --build --preset release --target certipose-solve certipose-part certipose-plan certipose-verify \
  certipose-export certipose_sample_part certipose_python
out=build/release/case-study
mkdir -p "$out"
build/release/examples/certipose-solve --mesh build/release/examples/sample_part.off --facet 900 \
  --camera examples/data/camera.json --position-eps 0.1 --orientation-eps 0.38 \
  --out "$out/result.json" --ply "$out/boxes.ply" "$@"
