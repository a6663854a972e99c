#!/usr/bin/env bash
# --part-pose on the programs (CTest: program.part_pose): the part placed by a pose is the very
# mesh a user would get by moving the file by hand, recorded, and carried from run to plan to
# verify and export.
#   part_pose.sh PART PLAN VERIFY EXPORT MESH CAMERA WORK_DIR
# Checked: with a pose whose rotation is exact (90° about z, entries 0 and ±1) the moved vertices
# are exact roundings, so certipose-part on MESH --part-pose and on a copy of MESH moved in Python
# give the same digest and byte-identical boxes.cpbx, in the 12- and 16-number and the
# X,Y,Z,ROLL,PITCH,YAW forms alike; summary.json, PLAN.json and REPORT.json record mesh.pose; a
# plan refuses a run made with another pose, naming mesh.pose; certipose-export draws the part at
# the plan's pose; a reflection, a matrix that is not a rotation, a last row that is not 0 0 0 1
# and a wrong count of numbers are usage errors (exit 2) naming --part-pose.
set -uo pipefail
part=$1 plan=$2 verify=$3 export=$4 mesh=$5 camera=$6 work=$7
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 1
fail() { echo "FAIL: $*" >&2; exit 1; }
eps=(--position-eps 0.1 --orientation-eps 0.38)
facets=(--facets 880-895)
pose12=0,-1,0,0.5,1,0,0,0,0,0,1,0.25
pose16=$pose12,0,0,0,1

# The mesh moved by hand: v -> (-y + 0.5, x, z + 0.25), written with every digit.
python3 - "$mesh" moved.off <<'EOF' || fail "could not write moved.off"
import sys
lines = [l for l in open(sys.argv[1]).read().split("\n") if l.strip() and not l.startswith("#")]
assert lines[0].strip() == "OFF"
nv, nf = map(int, lines[1].split()[:2])
out = ["OFF", f"{nv} {nf} 0"]
for l in lines[2:2 + nv]:
    x, y, z = map(float, l.split()[:3])
    out.append(f"{repr(-y + 0.5)} {repr(x)} {repr(z + 0.25)}")
out += lines[2 + nv:2 + nv + nf]
open(sys.argv[2], "w").write("\n".join(out) + "\n")
EOF

"$part" --mesh moved.off --camera "$camera" "${eps[@]}" "${facets[@]}" --out by_hand --quiet 2>err ||
    fail "certipose-part on moved.off: $(cat err)"
"$part" --mesh "$mesh" --part-pose "$pose12" --camera "$camera" "${eps[@]}" "${facets[@]}" --out posed --quiet 2>err ||
    fail "certipose-part --part-pose (12 numbers): $(cat err)"
"$part" --mesh "$mesh" --part-pose "$pose16" --camera "$camera" "${eps[@]}" "${facets[@]}" --out posed16 --quiet 2>err ||
    fail "certipose-part --part-pose (16 numbers): $(cat err)"
cmp -s by_hand/boxes.cpbx posed/boxes.cpbx || fail "--part-pose does not give the boxes of the mesh moved by hand"
cmp -s posed/boxes.cpbx posed16/boxes.cpbx || fail "the 12- and 16-number forms differ"
python3 - <<'EOF' || fail "summary.json does not record the pose as given"
import json
hand = json.load(open("by_hand/summary.json"))["mesh"]
posed = json.load(open("posed/summary.json"))["mesh"]
assert hand["digest"] == posed["digest"], (hand, posed)
assert "pose" not in hand, hand
assert posed["pose"] == [[0, -1, 0, 0.5], [1, 0, 0, 0], [0, 0, 1, 0.25], [0, 0, 0, 1]], posed
EOF
# The X,Y,Z,ROLL,PITCH,YAW form: yaw pi/2 is the same turn up to the rounding of cos(pi/2).
"$part" --mesh "$mesh" --part-pose 0.5,0,0.25,0,0,1.5707963267948966 --camera "$camera" "${eps[@]}" "${facets[@]}" \
    --out rpy --quiet 2>err || fail "certipose-part --part-pose X,Y,Z,R,P,Y: $(cat err)"
python3 - <<'EOF' || fail "the X,Y,Z,ROLL,PITCH,YAW pose is not recorded as its matrix"
import json
m = json.load(open("rpy/summary.json"))["mesh"]["pose"]
want = [[0, -1, 0, 0.5], [1, 0, 0, 0], [0, 0, 1, 0.25], [0, 0, 0, 1]]
assert all(abs(m[r][c] - want[r][c]) < 1e-15 for r in range(4) for c in range(4)), m
EOF

# Run -> plan -> verify -> export, each with the pose; a plan without it is refused.
"$plan" --mesh "$mesh" --camera "$camera" --part-results posed --coverage 0.9 --out plan.json --quiet 2>err
[ $? -eq 1 ] || fail "a plan without the run's --part-pose: expected exit 1: $(cat err)"
grep -q "mesh.pose" err || fail "the refusal does not name mesh.pose: $(cat err)"
"$plan" --mesh "$mesh" --part-pose "$pose12" --camera "$camera" --part-results posed --coverage 0.9 --out plan.json \
    --quiet 2>err || fail "certipose-plan --part-pose: $(cat err)"
"$verify" --mesh "$mesh" --part-pose "$pose12" --camera "$camera" --poses plan.json --out report.json --quiet 2>err ||
    fail "certipose-verify --part-pose: $(cat err)"
python3 - <<'EOF' || fail "PLAN.json or REPORT.json does not record the pose, or verify disagrees with the plan"
import json
plan, report = json.load(open("plan.json")), json.load(open("report.json"))
want = [[0, -1, 0, 0.5], [1, 0, 0, 0], [0, 0, 1, 0.25], [0, 0, 0, 1]]
assert plan["mesh"]["pose"] == want and report["mesh"]["pose"] == want
assert plan["cameras"], "no camera"
for cam, pose in zip(plan["cameras"], report["poses"]):
    assert set(cam["facets"]) <= set(pose["facets"]), (cam["facets"], pose["facets"])
EOF
"$export" plan.json --format glb --mesh "$mesh" --out plan.glb --quiet 2>err || fail "export at the plan's pose: $(cat err)"
"$export" plan.json --format glb --mesh "$mesh" --part-pose 0,0,0,0,0,0 --out x.glb --quiet 2>err
[ $? -eq 1 ] || fail "export at another pose than the plan's: expected exit 1"
grep -q "mesh.digest" err || fail "the other pose is not refused by digest: $(cat err)"

# Bad poses: usage errors naming --part-pose, nothing written.
for bad in 1,0,0,0,0,1,0,0,0,0,-1,0 1,0,0,0,0,1,0.001,0,0,0,1,0 1,2,3 "$pose12,1,1,1,1" 0,0,0,0,0,nan; do
    "$part" --mesh "$mesh" --part-pose "$bad" --camera "$camera" "${eps[@]}" --out bad --quiet 2>err
    rc=$?
    [ $rc -eq 2 ] || fail "--part-pose $bad: expected exit 2, got $rc: $(cat err)"
    grep -q -- "--part-pose" err || fail "--part-pose $bad: the error does not name the option: $(cat err)"
    [ -e bad ] && fail "--part-pose $bad: a refused run wrote its folder"
done
grep -q "reflection" <("$part" --mesh "$mesh" --part-pose 1,0,0,0,0,1,0,0,0,0,-1,0 --camera "$camera" "${eps[@]}" \
    --out bad 2>&1) || fail "a reflection is not called one"
exit 0
