#!/usr/bin/env bash
# certipose-part --resume (CTest: program.resume): a run killed part-way (SIGKILL, then also with
# its journal's last line torn and junk after its stores' last checkpoint, as a power loss may
# leave them), one stopped by SIGINT, one by its box budget, and one whose disk filled (a small
# tmpfs; root only, else that part is skipped) are each continued with --resume, and the folder then holds the very
# boxes.cpbx of an uninterrupted run, byte for byte, and the same facet records. A resume with
# another setting or mesh is refused, naming it, and leaves the unfinished run as it was. The
# same for a --patches run killed and budget-stopped.
#   resume.sh PART MESH CAMERA WORK_DIR
set -uo pipefail
part=$1 mesh=$2 camera=$3 work=$4
fail() { echo "FAIL: $*" >&2; exit 1; }
umount "$work/disk" 2>/dev/null
rm -rf "$work" && mkdir -p "$work" && cd "$work" || fail "cannot make $work"
base=(--mesh "$mesh" --camera "$camera" --position-eps 0.1 --orientation-eps 0.38 --facets 0-399 --threads 2)
run=("${base[@]}" -q)

# The same facet records (all but their times) and the same summary settings.
same_records() {
    python3 - "$1/summary.json" "$2/summary.json" <<'EOF' || fail "$2/summary.json differs from $1/summary.json"
import json, sys
a, b = (json.load(open(p)) for p in sys.argv[1:3])
strip = lambda s: [{k: v for k, v in f.items() if k != "seconds"} for f in s["facets"]]
assert strip(a) == strip(b), "facet records differ"
assert a["settings"] == b["settings"], "settings differ"
for k in ("facets_selected", "facets", "valid", "boundary", "skipped", "termination"):
    assert a["totals"][k] == b["totals"][k], k
assert b["totals"]["termination"] == "completed"
EOF
}
# Starts a run into $1 in the background and waits until its journal holds a checkpoint with
# facets (a second line: the first holds the stores' headers).
start_and_wait() {
    "$part" "${run[@]}" --out "$1" & pid=$!
    for _ in $(seq 1 400); do
        [ -f "$1/run-in-progress/journal" ] && [ "$(wc -l < "$1/run-in-progress/journal")" -ge 2 ] && return 0
        kill -0 $pid 2>/dev/null || fail "the run into $1 ended before its first checkpoint"
        sleep 0.05
    done
    fail "no checkpoint in $1 after 20 s"
}

"$part" "${run[@]}" --out full || fail "the uninterrupted run failed"
[ -f full/boxes.cpbx ] && [ ! -e full/run-in-progress ] || fail "the uninterrupted run left $(ls -A full)"

# ---- SIGKILL ----------------------------------------------------------------------------------
start_and_wait killed
kill -KILL $pid; wait $pid 2>/dev/null
[ -e killed/summary.json ] && fail "the run finished before SIGKILL; the test needs a longer run"
[ -d killed/run-in-progress ] || fail "a killed run left no run-in-progress/"
# Refused: another setting, another mesh (its scale), another store; the run stays resumable.
"$part" "${run[@]/0.1/0.2}" --out killed --resume 2>err && fail "--resume with another --position-eps was accepted"
grep -q 'settings.position_eps: 0.1 in the run, 0.2 here' err || fail "the differing setting is not named: $(cat err)"
"$part" "${run[@]}" --scale 1.5 --out killed --resume 2>err && fail "--resume with another --scale was accepted"
grep -q 'mesh\.\(digest\|scale\)' err || fail "the differing mesh is not named: $(cat err)"
"$part" "${run[@]}" --box-store both --out killed --resume 2>err && fail "--resume with another --box-store was accepted"
grep -q 'settings.box_store' err || fail "the differing store is not named: $(cat err)"
[ -d killed/run-in-progress ] && [ ! -e killed/summary.json ] || fail "a refused --resume changed the folder"
# What a power loss may leave: a journal line cut short, bytes after the last checkpoint.
printf '0123abcd {"facets":[{"index":' >> killed/run-in-progress/journal
head -c 1000 /dev/urandom >> killed/run-in-progress/boxes.cpbx
"$part" "${run[@]}" --out killed --resume || fail "--resume after SIGKILL failed"
cmp -s full/boxes.cpbx killed/boxes.cpbx || fail "after SIGKILL and --resume, boxes.cpbx differs from the uninterrupted run's"
same_records full killed
[ ! -e killed/run-in-progress ] || fail "a finished resume left run-in-progress/"
"$part" "${base[@]}" --out killed --resume >out || fail "--resume of a complete run failed"
grep -q 'complete; nothing to resume' out || fail "--resume of a complete run says: $(cat out)"

# ---- SIGINT: committed as interrupted, then continued ----------------------------------------
start_and_wait interrupted
kill -INT $pid; wait $pid; rc=$?
[ $rc -eq 130 ] || fail "SIGINT: exit $rc, expected 130"
grep -q '"interrupted": *true' interrupted/summary.json || fail "SIGINT: the summary is not marked interrupted"
[ -e interrupted/run-in-progress ] && fail "SIGINT left run-in-progress/ beside the committed run"
"$part" "${run[@]}" --out interrupted --resume || fail "--resume after SIGINT failed"
cmp -s full/boxes.cpbx interrupted/boxes.cpbx || fail "after SIGINT and --resume, boxes.cpbx differs from the uninterrupted run's"
same_records full interrupted

# ---- a box budget, then a run without one --------------------------------------------------
"$part" "${run[@]}" --max-boxes 100000 --out budget || fail "the run with a box budget failed"
grep -q '"termination": *"box_budget"' budget/summary.json || fail "--max-boxes 100000 did not stop the run"
"$part" "${run[@]}" --max-boxes 100000 --out budget --resume || fail "--resume with the spent budget failed"
grep -q '"termination": *"box_budget"' budget/summary.json || fail "--resume with the spent budget went past it"
"$part" "${run[@]}" --out budget --resume || fail "--resume without the budget failed"
cmp -s full/boxes.cpbx budget/boxes.cpbx || fail "a budget-stopped run resumed without it differs from the uninterrupted run"
same_records full budget

# ---- --patches: a run killed or budget-stopped between work items resumes to the same boxes ----
# (the journal checkpoints only between items, and the rest is grouped as the run grouped it)
patches_resumed() {
    run=("${base[@]}" --patches -q)
    "$part" "${run[@]}" --out pfull || fail "the uninterrupted --patches run failed"
    grep -q '"patch":' pfull/summary.json || fail "the --patches run patched nothing"
    start_and_wait pkilled
    kill -KILL $pid; wait $pid 2>/dev/null
    [ -e pkilled/summary.json ] && fail "the --patches run finished before SIGKILL; the test needs a longer run"
    "$part" "${run[@]}" --out pkilled --resume || fail "--resume of a killed --patches run failed"
    cmp -s pfull/boxes.cpbx pkilled/boxes.cpbx || fail "after SIGKILL and --resume, the --patches boxes.cpbx differs"
    same_records pfull pkilled
    "$part" "${run[@]}" --max-boxes 100000 --out pbudget || fail "the --patches run with a box budget failed"
    grep -q '"termination": *"box_budget"' pbudget/summary.json || fail "--max-boxes 100000 did not stop the --patches run"
    "$part" "${base[@]}" -q --out pbudget --resume 2>err && fail "--resume without --patches of a --patches run was accepted"
    grep -q 'settings.patches' err || fail "the differing patches setting is not named: $(cat err)"
    "$part" "${run[@]}" --out pbudget --resume || fail "--resume of a budget-stopped --patches run failed"
    cmp -s pfull/boxes.cpbx pbudget/boxes.cpbx || fail "a budget-stopped --patches run resumed differs"
    same_records pfull pbudget
}

# ---- a full disk ------------------------------------------------------------------------------
mkdir -p disk
if ! mount -t tmpfs -o size=8m tmpfs disk 2>/dev/null; then
    echo "SIGKILL and SIGINT resumed; the full-disk part skipped (mounting a tmpfs needs root)"
    patches_resumed
    exit 0
fi
trap 'umount "$work/disk" 2>/dev/null' EXIT
"$part" "${run[@]}" --out disk/run 2>err && fail "a run that filled its disk exited 0"
grep -q 'disk full' err || fail "the full disk is not named: $(cat err)"
grep -q 'run the same command with --resume' err || fail "the error does not say the run is resumable: $(cat err)"
[ "$(wc -l < err)" -eq 1 ] || fail "more than one line: $(cat err)"
[ -e disk/run/summary.json ] && fail "a run that filled its disk wrote summary.json"
mount -o remount,size=96m disk || fail "cannot grow the tmpfs"
"$part" "${run[@]}" --out disk/run --resume || fail "--resume after a full disk failed"
cmp -s full/boxes.cpbx disk/run/boxes.cpbx || fail "after a full disk and --resume, boxes.cpbx differs from the uninterrupted run's"
same_records full disk/run
umount "$work/disk" 2>/dev/null; trap - EXIT
patches_resumed
echo "SIGKILL (with a torn journal), SIGINT, a box budget and a full disk: each resumed to the uninterrupted run's boxes; with --patches too"
exit 0
