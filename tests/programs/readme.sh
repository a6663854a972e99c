#!/usr/bin/env bash
# Runs the README's walkthrough (the ```sh block between the readme-walkthrough markers) line
# for line, as a user would after README command (1) (CTest: program.readme).
#   readme.sh SOURCE_DIR BINARY_DIR WORK_DIR NODE
# The work directory mirrors a checkout: examples/ is the source's, build/release is this build
# tree, so the README's paths run unchanged. Then it checks what the README promises: every file
# exists, no camera of the plan is below the fixture plate's top, the verify report certifies the
# plan's facets, the underside on the plate is named as resting on it, and the HTML page and the
# installation sheet pass their browser tests (their screenshots are docs/viewer.png and
# docs/sheet.png: copy them from WORK_DIR after a change that shows).
set -uo pipefail
src=$1 bin=$2 work=$3 node=$4
fail() { echo "FAIL: $*" >&2; exit 1; }
rm -rf "$work" && mkdir -p "$work/build" && cd "$work" || exit 1
ln -s "$src/examples" examples
ln -s "$bin" build/release
awk '/<!-- readme-walkthrough: begin -->/{on=1; next} /<!-- readme-walkthrough: end -->/{on=0} on' "$src/README.md" \
    | sed '/^```/d' > walkthrough.sh
[ "$(grep -c 'certipose-' walkthrough.sh)" -ge 9 ] || fail "the README's walkthrough block was not found"
bash -euo pipefail walkthrough.sh > out 2> err || fail "the README's walkthrough failed: $(tail -5 err)"

for f in facet900.json facet900.ply part-run/summary.json part-run/boxes.cpbx plan.json verify.json \
         plan.csv plan.yaml plan.urdf plan.glb plan.html sheet.html; do
    [ -s "$f" ] || fail "the walkthrough did not write $f"
done
grep -q '"occluders"' plan.json || fail "plan.json does not record the occluder"
grep -q 'fixture_plate' plan.json || fail "plan.json does not name the fixture plate"
# No camera box reaches below the plate's top (z = 0): the keep-out box held.
python3 - <<'PY' || exit 1
import json, sys
plan = json.load(open("plan.json"))
low = [c["position"][2][0] for c in plan["cameras"]]
if not plan["cameras"]: sys.exit("FAIL: the plan has no camera")
if min(low) <= 0: sys.exit("FAIL: a camera box reaches the keep-out below the plate's top: z from %g" % min(low))
print("readme: %d cameras, lowest box z %.3f m" % (len(low), min(low)))
PY
"$node" "$src/tests/web/validate_glb.mjs" plan.glb >/dev/null || fail "plan.glb does not validate"
"$node" "$src/tests/web/viewer_test.mjs" plan.html viewer.png > viewer.log 2>&1 || fail "viewer: $(tail -5 viewer.log)"
# The plan's occluder is an input of the export too: never written over. (A copy of the plan
# naming a copy of the plate, so that a failure cannot touch the checkout.)
cp "$src/examples/data/fixture_plate.off" plate_copy.off
sed 's|examples/data/fixture_plate.off|plate_copy.off|' plan.json > plan_copy.json
build/release/examples/certipose-export plan_copy.json --format csv --out plate_copy.off 2>err
[ $? -eq 1 ] || fail "export over the plan's occluder: expected exit 1"
grep -q "is the plan's occluder" err || fail "the occluder as --out is not named: $(cat err)"
cmp -s plate_copy.off "$src/examples/data/fixture_plate.off" || fail "export wrote over the plan's occluder"
# The underside resting on the plate is named for what it is, not left to a finer eps.
python3 - <<'PY' || exit 1
import json, sys
plan = json.load(open("plan.json"))
resting = [u["facet"] for u in plan["uncovered"] if u["reason"] == "rests on an occluder"]
if len(resting) < 100: sys.exit("FAIL: only %d facets rest on the plate" % len(resting))
print("readme: %d facets rest on the plate" % len(resting))
PY
grep -q 'rests on an occluder' plan.html || fail "the viewer does not carry the uncovered facets' reasons"
"$node" "$src/tests/web/sheet_test.mjs" sheet.html plan.csv sheet.png > sheet.log 2>&1 || fail "sheet: $(tail -8 sheet.log)"
echo "readme: the walkthrough ran; screenshots: $work/viewer.png, $work/sheet.png"
