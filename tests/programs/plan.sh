#!/usr/bin/env bash
# certipose-part -> certipose-plan -> certipose-verify on facets of the sample part (CTest:
# program.plan_and_verify).
#   plan.sh PART PLAN VERIFY MESH CAMERA WORK_DIR
# The plan is written with its PLY, refuses to overwrite an input or to plan from a run of
# another scale, mesh or camera (d_min one bit off), rejects contradictory options with exit 2,
# has a one-shot mode honouring --cameras, skips candidates by default and inspects all with
# --all-candidates, and certipose-verify certifies the plan's boxes and
# the tolerance of an exact pose, and the same facets from the pose given as a quaternion or a 4x4
# matrix; every JSON written leads with its format and version; another mount offset is refused.
# certipose-part's reuse between translates is on by default and off with --no-reuse.
set -uo pipefail
part=$1 plan=$2 verify=$3 mesh=$4 camera=$5 work=$6
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 1
fail() { echo "FAIL: $*" >&2; exit 1; }

"$part" --mesh "$mesh" --camera "$camera" --position-eps 0.1 --orientation-eps 0.38 --facets 880-920 \
    --box-store both --out run --quiet || fail "certipose-part failed"

# Reuse between translates (docs/part.md#reuse-between-translates): bottom facets of one shape
# take the first one's boxes, recorded in summary.json; --no-reuse paves each on its own.
"$part" --mesh "$mesh" --camera "$camera" --position-eps 0.1 --orientation-eps 0.38 --facets 2,6,10,14 \
    --out reuse --quiet || fail "certipose-part on bottom facets failed"
[ "$(grep -o '"reused_from": *2' reuse/summary.json | wc -l)" -eq 3 ] || fail "facets 6, 10, 14 did not reuse facet 2's boxes"
grep -q '"reuse": *true' reuse/summary.json || fail "settings.reuse is not true"
"$part" --mesh "$mesh" --camera "$camera" --position-eps 0.1 --orientation-eps 0.38 --facets 2,6,10,14 \
    --out alone --quiet --no-reuse || fail "certipose-part --no-reuse failed"
grep -q '"reused_from"' alone/summary.json && fail "--no-reuse reused boxes"
grep -q '"reuse": *false' alone/summary.json || fail "settings.reuse is not false with --no-reuse"

"$plan" --mesh "$mesh" --camera "$camera" --part-results run --coverage 0.9 --out plan.json --ply plan.ply >out 2>err \
    || fail "certipose-plan failed: $(cat err)"
grep -q '"cameras": *\[' plan.json || fail "plan.json has no cameras"
grep -q '"lower_bound_cameras": *[1-9]' plan.json || fail "plan.json has no positive lower bound"
grep -q '"uncovered"' plan.json || fail "plan.json has no uncovered list"
head -c 3 plan.ply | grep -q ply || fail "plan.ply is not a PLY"
grep -q 'camera box(es) certify' out || fail "no summary line: $(cat out)"
[ -s err ] && fail "stderr not empty: $(cat err)"
cameras=$(grep -c '"from_facet"' plan.json)
[ "$cameras" -ge 1 ] || fail "no camera in the plan"

# Thinning: of three candidates per facet (more than one round of 64), fewer are inspected than
# offered (neighbouring facets certify each other); --all-candidates inspects every one. Both
# plans reach the target.
count() { python3 -c "import json,sys; s=json.load(open(sys.argv[1]))['settings']; print(s[sys.argv[2]])" "$1" "$2"; }
"$plan" --mesh "$mesh" --camera "$camera" --part-results run --coverage 0.9 --candidates-per-facet 3 --out thin.json -q 2>err \
    || fail "certipose-plan --candidates-per-facet 3 failed: $(cat err)"
[ "$(count thin.json candidates)" -gt 64 ] || fail "only $(count thin.json candidates) candidates"
[ "$(count thin.json inspected)" -lt "$(count thin.json candidates)" ] \
    || fail "thinning inspected $(count thin.json inspected) of $(count thin.json candidates) candidates"
"$plan" --mesh "$mesh" --camera "$camera" --part-results run --coverage 0.9 --candidates-per-facet 3 --all-candidates \
    --out all.json -q 2>err \
    || fail "certipose-plan --all-candidates failed: $(cat err)"
[ "$(count all.json inspected)" -eq "$(count all.json candidates)" ] || fail "--all-candidates skipped candidates"
for p in thin.json all.json; do
    python3 -c "import json,sys; c=json.load(open(sys.argv[1]))['coverage']; sys.exit(c['certified_area'] < 0.9 * c['coverable_area'] * (1 - 1e-9))" "$p" \
        || fail "$p does not certify 90 % of its coverable area"
done

# An output that is an input: refused, the input untouched.
before=$(md5sum < "$camera")
cp "$camera" cam.json
"$plan" --mesh "$mesh" --camera cam.json --part-results run --out ./cam.json --quiet 2>err && fail "overwrote its input"
cmp -s "$camera" cam.json || fail "the camera file was changed"
[ "$(md5sum < "$camera")" = "$before" ] || fail "the camera file was changed"
grep -q 'certipose-plan: ' err || fail "no error line for an output that is an input"

# Contradictory options: exit 2, one line.
"$plan" --mesh "$mesh" --camera "$camera" --part-results run --position-eps 0.1 --orientation-eps 0.38 \
    --out x.json 2>err
[ $? -eq 2 ] || fail "--part-results with --position-eps: expected exit 2"
[ "$(wc -l < err)" -eq 1 ] || fail "more than one error line: $(cat err)"
"$plan" --mesh "$mesh" --camera "$camera" --part-results run --cameras 2 --coverage 0.9 --out x.json 2>err
[ $? -eq 2 ] || fail "--cameras with --coverage: expected exit 2"
[ -e x.json ] && fail "a failed run wrote its output"

# A run of another scale certifies another part.
"$plan" --mesh "$mesh" --scale 2 --camera "$camera" --part-results run --out y.json 2>err
[ $? -eq 1 ] || fail "planning from a run of another scale: expected exit 1"
grep -q 'mesh.scale' err || fail "the scale mismatch is not named: $(cat err)"
[ -e y.json ] && fail "a failed run wrote its output"

# A run of another mesh with as many faces: its digest differs.
mkdir -p other && cp run/boxes.jsonl other/ && sed 's/"digest": *"[0-9a-f]*"/"digest":"0123456789abcdef"/' run/summary.json > other/summary.json
grep -q '0123456789abcdef' other/summary.json || fail "summary.json has no mesh digest"
"$plan" --mesh "$mesh" --camera "$camera" --part-results other --out z.json 2>err
[ $? -eq 1 ] || fail "planning from a run of another mesh: expected exit 1"
grep -q 'mesh.digest' err || fail "the mesh mismatch is not named: $(cat err)"

# A run whose d_min differs in the last bit: its boxes were carved for another focus range, so
# nothing of it is trusted (the run above, of this very camera, compared equal bit for bit).
mkdir -p nudged && cp run/boxes.jsonl nudged/
python3 -c 'import json, math, sys
s = json.load(open(sys.argv[1]))
s["camera"]["d_min"] = math.nextafter(s["camera"]["d_min"], math.inf)
json.dump(s, open(sys.argv[2], "w"))' run/summary.json nudged/summary.json || fail "could not edit summary.json"
"$plan" --mesh "$mesh" --camera "$camera" --part-results nudged --out n.json 2>err
[ $? -eq 1 ] || fail "planning from a run whose d_min differs in the last bit: expected exit 1"
grep -q 'camera distance range' err || fail "the d_min mismatch is not named: $(cat err)"
[ -e n.json ] && fail "a failed run wrote its output"

# One shot, at most 2 cameras.
"$plan" --mesh "$mesh" --camera "$camera" --position-eps 0.1 --orientation-eps 0.38 --facets 895-905 --cameras 2 \
    --out oneshot.json --quiet || fail "one-shot certipose-plan failed"
n=$(grep -c '"from_facet"' oneshot.json)
[ "$n" -ge 1 ] && [ "$n" -le 2 ] || fail "one-shot plan with --cameras 2 has $n cameras"

# certipose-verify: the plan's boxes certify facets; an exact pose gets a tolerance box.
"$verify" --mesh "$mesh" --camera "$camera" --poses plan.json --out report.json >vout 2>err || fail "certipose-verify failed: $(cat err)"
grep -q '"poses"' report.json || fail "report.json has no poses"
grep -Eq 'pose 0 \(box\): [1-9][0-9]* facets certified' vout || fail "the plan's first box certifies nothing: $(cat vout)"
nominal=$(grep -o '"nominal": *\[[^]]*\]' plan.json | head -1 | sed 's/"nominal": *//')
echo "{\"poses\": [$nominal]}" > poses.json
"$verify" --mesh "$mesh" --camera "$camera" --poses poses.json >vout 2>err || fail "certipose-verify (exact pose) failed: $(cat err)"
grep -q 'tolerance +-' vout || fail "no tolerance box for an exact pose: $(cat vout)"
"$verify" --mesh "$mesh" --camera "$camera" --poses poses.json --out poses.json 2>err && fail "verify overwrote its input"

# Every JSON document written leads with its format and version.
for f in plan.json:certipose-plan run/summary.json:certipose-part-summary report.json:certipose-verify-report; do
    head -3 "${f%%:*}" | tr -d '\n' | grep -Eq '^\{ *"format": "'"${f#*:}"'", *"version": 1,' \
        || fail "${f%%:*} does not start with \"format\": \"${f#*:}\", \"version\": 1"
done

# The plan's nominal pose given as a quaternion and as a 4x4 camera-to-world matrix (converted to
# ZXZ angles, boxes of +-1e-8 rad) certifies the same facets as its exact ZXZ angles.
python3 -c 'import json, math, sys
x, y, z, phi, gamma, beta = json.loads(sys.argv[1])
sp, cp, sg, cg, sb, cb = math.sin(phi), math.cos(phi), math.sin(gamma), math.cos(gamma), math.sin(beta), math.cos(beta)
r = [[cp * cb - sp * cg * sb, -cp * sb - sp * cg * cb, sp * sg],
     [sp * cb + cp * cg * sb, cp * cg * cb - sp * sb, -cp * sg],
     [sg * sb, sg * cb, cg]]
h = math.sin(gamma / 2), math.cos(gamma / 2)
q = [h[0] * math.cos((phi - beta) / 2), h[0] * math.sin((phi - beta) / 2), h[1] * math.sin((phi + beta) / 2),
     h[1] * math.cos((phi + beta) / 2)]
m = [r[0] + [x], r[1] + [y], r[2] + [z], [0, 0, 0, 1]]
# the same matrix, orthonormal only within about 4e-7: its box is widened, per angle
n = [row[:] for row in m]
n[0][1] += 2e-7; n[2][0] -= 2e-7
json.dump({"poses": [[x, y, z, phi, gamma, beta], {"position": [x, y, z], "quaternion": q}, {"matrix": m},
                     {"matrix": n}]},
          open("forms.json", "w"))' "$nominal" || fail "could not write forms.json"
"$verify" --mesh "$mesh" --camera "$camera" --poses forms.json --out forms_report.json >vout 2>err \
    || fail "certipose-verify (quaternion, matrix) failed: $(cat err)"
grep -q 'pose 1 (quaternion): [1-9][0-9]* facets certified' vout || fail "the quaternion pose certifies nothing: $(cat vout)"
grep -q 'pose 2 (matrix): [1-9][0-9]* facets certified' vout || fail "the matrix pose certifies nothing: $(cat vout)"
grep -q 'pose 1 (quaternion).*tolerance +-' vout || fail "no tolerance box for a quaternion pose: $(cat vout)"
python3 -c 'import json, sys
p = json.load(open("forms_report.json"))["poses"]
assert [e["kind"] for e in p] == ["pose", "quaternion", "matrix", "matrix"], [e["kind"] for e in p]
assert p[0]["facets"] and p[1]["facets"] == p[0]["facets"] and p[2]["facets"] == p[0]["facets"], [e["facets"] for e in p]
# A converted pose stands for every angle of its box: the half-widths reported hold from each
# edge of it, so each is the tolerance box less the half-width of that angle (for the widened
# matrix, 4 off / sin(gamma) in phi and beta, far more than 1e-8).
for e in p[1:]:
    t = e["tolerance"]
    assert t, e
    for k in range(3):
        lo, hi = e["orientation"][k]
        c, h = (lo + hi) / 2, (hi - lo) / 2
        room = min(c - t["orientation"][k][0], t["orientation"][k][1] - c) - h
        assert t["half_widths"][k + 3] <= room + 1e-15, (e["index"], k, t["half_widths"][k + 3], room, h)
w = [(b - a) / 2 for a, b in p[3]["orientation"]]
assert w[0] > 1e-7 and w[2] > 1e-7 and w[1] > 1e-8, w  # the widened box' \
    || fail "quaternion / matrix poses certify other facets than the ZXZ pose, or their tolerances ignore the pose's own box"
# At the gimbal lock (optical axis along world -Z) a quaternion is refused: give ZXZ angles.
echo '{"poses": [{"position": [0, 0, 1], "quaternion": [1, 0, 0, 0]}]}' > lock.json
"$verify" --mesh "$mesh" --camera "$camera" --poses lock.json 2>err
[ $? -eq 1 ] || fail "a quaternion at the gimbal lock: expected exit 1"
grep -q 'poses\[0\].quaternion: the orientation is at the ZXZ gimbal lock' err || fail "the gimbal lock is not named: $(cat err)"

# A camera of another mount offset is another installation: a run of the camera without one is refused.
python3 -c 'import json, sys
c = json.load(open(sys.argv[1]))
c["camera"]["mount_offset"] = [0.0, 0.02, -0.05]
json.dump(c, open("mounted.json", "w"))' "$camera" || fail "could not write mounted.json"
"$plan" --mesh "$mesh" --camera mounted.json --part-results run --out m.json 2>err
[ $? -eq 1 ] || fail "planning with another mount offset: expected exit 1"
grep -q 'camera.mount_offset (\[0, 0, 0\]) is not this plan.s (\[0, 0.02, -0.05\])' err || fail "the mount offset mismatch is not named: $(cat err)"
[ -e m.json ] && fail "a failed run wrote its output"
exit 0
