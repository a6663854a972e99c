#!/usr/bin/env bash
# certipose-part-mpi when one rank fails mid-run: rank 0's output fills its disk (a 256 KiB tmpfs),
# its sink throws, and the job must end with a message naming the rank, a non-zero exit code,
# and no std::terminate, while rank 1 is still waiting for work (ctest's TIMEOUT catches a hang).
# The unfinished run is kept: with the disk grown, --resume on both ranks finishes it, and its
# boxes are those of an uninterrupted run.
# The tmpfs needs root (CI runs as root); without it the test is skipped (exit 77).
#   part_mpi_error.sh MPIEXEC PART_MPI MESH CAMERA WORK_DIR
set -uo pipefail
mpiexec=$1 part=$2 mesh=$3 camera=$4 work=$5
fail() { echo "FAIL: $*" >&2; exit 1; }
umount "$work/disk" 2>/dev/null
rm -rf "$work" && mkdir -p "$work/disk" || fail "cannot make $work"
cd "$work"
if ! mount -t tmpfs -o size=256k tmpfs disk 2>/dev/null; then
    echo "SKIP: cannot mount a tmpfs here (needs root)"
    exit 77
fi
trap 'umount "$work/disk" 2>/dev/null' EXIT
flags=(--oversubscribe)
[ "$(id -u)" = 0 ] && flags+=(--allow-run-as-root)
"$mpiexec" "${flags[@]}" -np 2 "$part" --mesh "$mesh" --camera "$camera" --position-eps 0.1 --orientation-eps 0.38 \
    --facets 0-59,900,2000-2029 --threads 1 --box-store jsonl --out disk/run -q >out 2>err
rc=$?
[ $rc -ne 0 ] || fail "a run that filled its disk exited 0: $(cat err)"
grep -q 'certipose-part: rank 0 of 2: .*write failed' err || fail "the failing rank is not named: $(cat err)"
grep -qi 'terminate called' err && fail "std::terminate: $(cat err)"
grep -q 'run the same command with --resume' err || fail "the error does not say the run is resumable: $(cat err)"
# Nothing half written is left under the output's name; the unfinished run is beside it.
[ -e disk/run/boxes.jsonl ] && fail "a failed run left disk/run/boxes.jsonl"
[ -e disk/run/summary.json ] && fail "a failed run left disk/run/summary.json"
[ "$(ls -A disk/run 2>/dev/null)" = run-in-progress ] || fail "a failed run left other files: $(ls -A disk/run)"
echo "rank 0's disk full: exit $rc, $(grep -o 'rank 0 of 2: [^;]*' err)"
mount -o remount,size=96m disk || fail "cannot grow the tmpfs"
args=(--mesh "$mesh" --camera "$camera" --position-eps 0.1 --orientation-eps 0.38 --facets 0-59,900,2000-2029 --threads 1
      --box-store jsonl -q)
"$mpiexec" "${flags[@]}" -np 2 "$part" "${args[@]}" --out disk/run --resume 2>err || fail "--resume on 2 ranks failed: $(cat err)"
"$mpiexec" "${flags[@]}" -np 2 "$part" "${args[@]}" --out disk/fresh 2>err || fail "the uninterrupted run failed: $(cat err)"
cmp -s disk/run/boxes.jsonl disk/fresh/boxes.jsonl || fail "the resumed run's boxes differ from an uninterrupted run's"
[ -e disk/run/run-in-progress ] && fail "the finished resume left run-in-progress/"
echo "resumed on 2 ranks: the boxes of an uninterrupted run"
exit 0
