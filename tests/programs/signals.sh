#!/usr/bin/env bash
# SIGINT and SIGTERM sent to the programs while they run (CTest: program.signals).
#   signals.sh SOLVE PART MESH CAMERA WORK_DIR [PLAN]
# certipose-solve must stop, write nothing (no result, no PLY, no temporary) and exit 130/143;
# certipose-part must stop, leave a readable summary.json marked interrupted with the facets it
# finished, boxes.jsonl and boxes.cpbx (the same boxes, counted in its header), no temporary, and exit 130/143; certipose-plan (one-shot mode, given as
# PLAN) must stop, write neither PLAN.json nor its PLY, say so in one line and exit 130/143.
set -uo pipefail
solve=$1 part=$2 mesh=$3 camera=$4 work=$5 plan=${6:-}
rm -rf "$work" && mkdir -p "$work"
fail() { echo "FAIL: $*" >&2; exit 1; }

# Starts "$@" in the background, waits until it has run for a while (the mesh is read and the
# solve has started), sends the signal and returns the exit code.
signal_after() {
  local sig=$1 delay=$2; shift 2
  "$@" &
  local pid=$!
  sleep "$delay"
  kill -0 "$pid" 2>/dev/null || { wait "$pid"; fail "$1 finished before the signal (rc $?): make its job longer"; }
  kill "-$sig" "$pid"
  wait "$pid"
}

for sig in INT TERM; do
  expected=$([ $sig = INT ] && echo 130 || echo 143)

  dir=$work/solve-$sig && mkdir -p "$dir"
  # ε_p = 0.004 m on the case-study facet: tens of seconds of paving, stopped after 2 s.
  signal_after $sig 2 "$solve" --mesh "$mesh" --facet 900 --camera "$camera" --position-eps 0.004 \
      --orientation-eps 0.38 --out "$dir/result.json" --ply "$dir/boxes.ply" --quiet 2>"$dir/stderr"
  rc=$?
  [ $rc -eq "$expected" ] || fail "certipose-solve on SIG$sig exited $rc, expected $expected: $(cat "$dir/stderr")"
  [ -z "$(ls -A "$dir" | grep -v '^stderr$')" ] || fail "certipose-solve on SIG$sig left files: $(ls -A "$dir")"
  grep -q "interrupted by SIG$sig" "$dir/stderr" || fail "certipose-solve on SIG$sig said: $(cat "$dir/stderr")"
  [ "$(wc -l < "$dir/stderr")" -eq 1 ] || fail "certipose-solve on SIG$sig printed more than one line: $(cat "$dir/stderr")"

  out=$work/part-$sig
  signal_after $sig 3 "$part" --mesh "$mesh" --camera "$camera" --position-eps 0.1 --orientation-eps 0.38 \
      --threads 2 --box-store both --out "$out" --quiet 2>"$work/part-$sig.stderr"
  rc=$?
  [ $rc -eq "$expected" ] || fail "certipose-part on SIG$sig exited $rc, expected $expected: $(cat "$work/part-$sig.stderr")"
  [ -f "$out/summary.json" ] && [ -f "$out/boxes.jsonl" ] && [ -f "$out/boxes.cpbx" ] ||
    fail "certipose-part on SIG$sig wrote: $(ls -A "$out" 2>&1)"
  [ "$(ls -A "$out" | wc -l)" -eq 3 ] || fail "certipose-part on SIG$sig left extra files: $(ls -A "$out")"
  # The binary store holds the same boxes, and its header counts them (a whole store).
  python3 - "$out" <<'EOF2' || fail "certipose-part on SIG$sig: boxes.cpbx does not match boxes.jsonl"
import os, struct, sys
d = sys.argv[1]
lines = sum(1 for l in open(os.path.join(d, "boxes.jsonl")) if l.strip())
head = open(os.path.join(d, "boxes.cpbx"), "rb").read(32)
count = struct.unpack_from("<Q", head, 24)[0]
assert head[:8] == b"CPBOXES\0" and count == lines == (os.path.getsize(os.path.join(d, "boxes.cpbx")) - 32) // 104, (count, lines)
EOF2
  grep -q '"interrupted": *true' "$out/summary.json" || fail "certipose-part's summary is not marked interrupted"
  # Every facet with boxes in boxes.jsonl is one the summary lists as finished, and fewer than all.
  finished=$(grep -o '"index": *[0-9]*' "$out/summary.json" | grep -o '[0-9]*$' | sort -n | uniq)
  count=$(echo "$finished" | grep -c .)
  faces=$(grep -o '"faces": *[0-9]*' "$out/summary.json" | grep -o '[0-9]*$')
  [ "$count" -gt 0 ] && [ "$count" -lt "$faces" ] || fail "certipose-part on SIG$sig finished $count of $faces facets"
  in_boxes=$(grep -o '"facet": *[0-9]*' "$out/boxes.jsonl" | grep -o '[0-9]*$' | sort -n | uniq)
  [ -z "$(comm -13 <(echo "$finished") <(echo "$in_boxes"))" ] || fail "boxes.jsonl has facets the summary does not list"

  if [ -n "$plan" ]; then
    dir=$work/plan-$sig && mkdir -p "$dir"
    # One shot: the whole part is solved first (minutes), stopped after 3 s.
    signal_after $sig 3 "$plan" --mesh "$mesh" --camera "$camera" --position-eps 0.1 --orientation-eps 0.38 \
        --out "$dir/plan.json" --ply "$dir/plan.ply" --quiet 2>"$dir/stderr"
    rc=$?
    [ $rc -eq "$expected" ] || fail "certipose-plan on SIG$sig exited $rc, expected $expected: $(cat "$dir/stderr")"
    [ -z "$(ls -A "$dir" | grep -v '^stderr$')" ] || fail "certipose-plan on SIG$sig left files: $(ls -A "$dir")"
    grep -q "interrupted by SIG$sig" "$dir/stderr" || fail "certipose-plan on SIG$sig said: $(cat "$dir/stderr")"
    [ "$(wc -l < "$dir/stderr")" -eq 1 ] || fail "certipose-plan on SIG$sig printed more than one line: $(cat "$dir/stderr")"
  fi
done
echo "signals: the programs stop cleanly on SIGINT and SIGTERM"
