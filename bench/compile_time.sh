#!/usr/bin/env bash
# Compile cost of a downstream translation unit that includes <certipose/cgal.hpp> and runs the
# default pipeline (tests/consumer/main_cgal.cpp), at -O2: wall time and peak compiler memory,
# header-only (certipose::cgal) and with certipose::precompiled (the library itself is built
# first and not counted: it is compiled once per project).
#
#   bash bench/compile_time.sh                 # this tree
#   bash bench/compile_time.sh --ref 0e11dd8   # also an older commit's consumer TU, for before/after
#
# With --ref, the older tree's examples/docs/cgal_solver.cpp (the default pipeline through the
# headers it offered then) is compiled the same way. Needs /usr/bin/time (Debian package `time`).
# ccache is bypassed, so every figure is a cold compile.
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
ref=""
while (($#)); do
  case "$1" in
    --ref) ref="$2"; shift 2 ;;
    *) echo "usage: $0 [--ref GIT_REF]" >&2; exit 2 ;;
  esac
done
if [ ! -x /usr/bin/time ]; then
  echo "compile_time: /usr/bin/time is missing (apt-get install time)" >&2
  exit 1
fi
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
export CCACHE_DISABLE=1

# measure <label> <source tree> <consumer source> <cmake target to link>
measure() {
  local label="$1" tree="$2" source="$3" link="$4" dir="$work/$1"
  mkdir -p "$dir"
  cat > "$dir/CMakeLists.txt" <<EOF
cmake_minimum_required(VERSION 3.22)
project(certipose_compile_time CXX)
add_subdirectory("$tree" certipose)
add_executable(consumer "$source")
target_link_libraries(consumer PRIVATE $link)
EOF
  cmake -S "$dir" -B "$dir/build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_FLAGS_RELEASE="-O2 -DNDEBUG" \
        -DCMAKE_CXX_COMPILER_LAUNCHER="/usr/bin/time;-f;%e %M;-a;-o;$dir/time.log" >/dev/null
  if [ "$link" = certipose::precompiled ]; then
    cmake --build "$dir/build" --target certipose_precompiled >/dev/null
  fi
  : > "$dir/time.log"
  cmake --build "$dir/build" --target consumer >/dev/null  # the launcher times compiles only
  read -r seconds kb < <(tail -n 1 "$dir/time.log")
  printf '%-40s %7.1f s %7.0f MB\n' "$label" "$seconds" "$((kb / 1024))"
}

printf '%-40s %9s %10s\n' "consumer TU (-O2, cold)" "wall" "peak"
if [ -n "$ref" ]; then
  git -C "$here" worktree add -q --detach "$work/ref" "$ref"
  measure "before ($ref, header-only)" "$work/ref" "$work/ref/examples/docs/cgal_solver.cpp" certipose::cgal
  git -C "$here" worktree remove --force "$work/ref"
fi
measure "header-only (certipose::cgal)" "$here" "$here/tests/consumer/main_cgal.cpp" certipose::cgal
measure "precompiled (certipose::precompiled)" "$here" "$here/tests/consumer/main_cgal.cpp" certipose::precompiled
