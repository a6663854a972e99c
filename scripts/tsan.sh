#!/usr/bin/env bash
# The whole-part solver's threaded run under ThreadSanitizer (tests/tsan/part_solver.cpp).
# Not in CI (a CGAL translation unit under TSan takes ~100 s to build); run it after changing
# part/ or anything a worker shares (the solver, the occlusion scene). Exit 0: no race reported.
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-build/tsan}
mkdir -p "$out"
g++ -std=c++20 -O1 -g -fsanitize=thread -Iinclude -I/usr/include/eigen3 tests/tsan/part_solver.cpp \
    -o "$out/part_solver_tsan" -lgmp -lmpfr -ltbb
TSAN_OPTIONS="halt_on_error=1 exitcode=66" "$out/part_solver_tsan"
