#!/usr/bin/env bash
# Fixtures and keep-out zones on every program (CTest: program.scene): --occluder, --keep-in and
# --keep-out of certipose-solve, certipose-part, certipose-plan and certipose-verify.
#   scene.sh SOLVE PART MESH CAMERA PLATE WORK_DIR [PLAN VERIFY]
# PLATE is examples/data/fixture_plate.off, the plate the sample part stands on. Checked: bad
# region strings and occluder scales are usage errors (exit 2) naming the text; an open occluder
# is refused naming its file; with the plate and a keep-out box below it no VALID box (solve,
# part) enters the keep-out, and a keep-out that cuts the space the wall facet is seen from leaves
# fewer VALID boxes, none in it; the plate hides a bottom facet's only viewpoints (VALID boxes
# without it, none with it); the outputs record the occluders (path, scale, faces, digest) and
# the regions; a plan reusing a run made with other occluders or regions fails with the mismatch
# message; certipose-verify reports a pose in a keep-out as outside the allowed space, with no
# facets.
set -uo pipefail
solve=$1 part=$2 mesh=$3 camera=$4 plate=$5 work=$6 plan=${7:-} verify=${8:-}
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 1
fail() { echo "FAIL: $*" >&2; exit 1; }
eps=(--position-eps 0.1 --orientation-eps 0.38)

# The facets: a bottom facet (normal -z, on the plate) and a wall facet at x = -0.15 (normal -x)
# whose lower edge is on the plate.
read -r bottom wall < <(python3 - "$mesh" <<'EOF'
import math, sys
lines = [l for l in open(sys.argv[1]).read().split("\n") if l.strip()]
nv, nf = map(int, lines[1].split()[:2])
V = [tuple(map(float, lines[2 + i].split())) for i in range(nv)]
F = [tuple(map(int, lines[2 + nv + i].split()[1:4])) for i in range(nf)]
def normal(f):
    a, b, c = (V[i] for i in f)
    u = [b[k] - a[k] for k in range(3)]; v = [c[k] - a[k] for k in range(3)]
    n = [u[1]*v[2] - u[2]*v[1], u[2]*v[0] - u[0]*v[2], u[0]*v[1] - u[1]*v[0]]
    l = math.sqrt(sum(x * x for x in n)); return [x / l for x in n]
bottom = [i for i, f in enumerate(F) if normal(f)[2] < -0.99]
wall = [i for i, f in enumerate(F) if normal(f)[0] < -0.99 and all(abs(V[j][0] + 0.15) < 1e-12 for j in f)
        and abs(sum(V[j][1] for j in f) / 3) < 0.05]
print(bottom[len(bottom) // 2], wall[0])
EOF
)
[ -n "$bottom" ] && [ -n "$wall" ] || fail "could not find the bottom and wall facets"

below='box:-2,-2,-2,2,2,-0.01'          # everything under the plate
side='box:-2,-2,-0.01,-0.5,2,2'          # a slab of the space in front of the wall facet

# ---- usage errors: exit 2, one line, naming the text ---------------------------------------------
usage() {  # usage PROGRAM-NAME EXPECTED-TEXT COMMAND...
    local name=$1 text=$2; shift 2
    "$@" >out 2>err
    local rc=$?
    [ $rc -eq 2 ] || fail "$name ${*: -2}: expected exit 2, got $rc: $(cat err)"
    [ "$(wc -l < err)" -eq 1 ] || fail "$name: more than one error line: $(cat err)"
    grep -qF -- "$text" err || fail "$name: the error does not name '$text': $(cat err)"
    grep -q "^$name: error: " err || fail "$name: not the usage error line: $(cat err)"
}
solve_args=(--mesh "$mesh" --facet "$wall" --camera "$camera" "${eps[@]}" --out r.json --quiet)
usage certipose-solve "'cube:0,0,0,1,1,1'" "$solve" "${solve_args[@]}" --keep-out cube:0,0,0,1,1,1
usage certipose-solve "'box:0,0,0,1,1'" "$solve" "${solve_args[@]}" --keep-out box:0,0,0,1,1
usage certipose-solve "xmin 1 is not below xmax 0" "$solve" "${solve_args[@]}" --keep-out box:1,0,0,0,1,1
usage certipose-solve "'box:1,0,0,0,1,1'" "$solve" "${solve_args[@]}" --keep-out box:1,0,0,0,1,1
usage certipose-solve "radius must be positive" "$solve" "${solve_args[@]}" --keep-in sphere:0,0,0,-0.5
usage certipose-solve "'1x' is not a number" "$solve" "${solve_args[@]}" --keep-in sphere:0,0,0,1x
usage certipose-solve "got '-1'" "$solve" "${solve_args[@]}" --occluder "$plate:-1"
usage certipose-solve "got 'nan'" "$solve" "${solve_args[@]}" --occluder "$plate:nan"
usage certipose-solve "File does not exist: missing.off" "$solve" "${solve_args[@]}" --occluder missing.off
usage certipose-part "'sphere:0,0'" "$part" --mesh "$mesh" --camera "$camera" "${eps[@]}" --out p --keep-out sphere:0,0
usage certipose-part "got '0'" "$part" --mesh "$mesh" --camera "$camera" "${eps[@]}" --out p --occluder "$plate:0"
[ -e r.json ] && fail "a usage error wrote its output"
[ -e p ] && fail "a usage error made its folder"

# An occluder path with a colon whose tail is not a number is a path (here: a missing file).
usage certipose-solve "File does not exist: odd:name.off" "$solve" "${solve_args[@]}" --occluder odd:name.off
# MESH:SCALE: the plate at scale 1 spelled out is read.
"$solve" "${solve_args[@]}" --max-boxes 20 --occluder "$plate:1" 2>err || fail "--occluder PLATE:1 failed: $(cat err)"

# An occluder that is not a closed solid: read as a triangle soup by default, with a warning;
# with --mesh-semantics solid, exit 1 and the policy's error naming the file.
head -n 21 "$plate" | sed '2s/.*/8 11 0/' > open.off
rm -f r.json
"$solve" "${solve_args[@]:0:${#solve_args[@]}-1}" --max-boxes 20 --occluder open.off >out 2>err || fail "an open occluder (soup): $(cat err)"
grep -q "triangle soup .*occluder 0: mesh is not a closed manifold" err || fail "no soup warning for the open occluder: $(cat err)"
grep -q "open edges" err || fail "the warning does not count the open edges: $(cat err)"
rm -f r.json
"$solve" "${solve_args[@]}" --occluder open.off --mesh-semantics solid 2>err
[ $? -eq 1 ] || fail "an open occluder, solid: expected exit 1: $(cat err)"
grep -q -- "--occluder open.off: .*occluder 0" err || fail "the open occluder is not named: $(cat err)"
[ -e r.json ] && fail "a failed run wrote its output"

# ---- certipose-solve ---------------------------------------------------------------------------
# JSON helpers: the VALID boxes entering a box region; the VALID count.
entering() {  # entering FILE.json|FILE.jsonl XMIN YMIN ZMIN XMAX YMAX ZMAX [FACET]
    python3 - "$@" <<'EOF'
import json, sys
path, r = sys.argv[1], list(map(float, sys.argv[2:8]))
facet = int(sys.argv[8]) if len(sys.argv) > 8 else None
if path.endswith(".jsonl"):
    boxes = [json.loads(l) for l in open(path) if l.strip()]
    boxes = [b for b in boxes if facet is None or b["facet"] == facet]
else:
    boxes = json.load(open(path))["boxes"]
n = 0
for b in boxes:
    if b["class"] != "valid": continue
    p = b["position"]
    # closed boxes: disjoint iff separated on some axis
    if all(p[k][1] >= r[k] and p[k][0] <= r[k + 3] for k in range(3)): n += 1
print(n)
EOF
}
valid_of() { python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["stats"]["valid"])' "$1"; }

"$solve" --mesh "$mesh" --facet "$wall" --camera "$camera" "${eps[@]}" --out wall.json --quiet \
    || fail "solve (wall, no scene) failed"
"$solve" --mesh "$mesh" --facet "$wall" --camera "$camera" "${eps[@]}" --out wall_plate.json --quiet \
    --occluder "$plate" --keep-out "$below" 2>err || fail "solve (wall, plate, keep-out below) failed: $(cat err)"
[ "$(entering wall_plate.json -2 -2 -2 2 2 -0.01)" -eq 0 ] || fail "solve: a VALID box enters the keep-out below the plate"
[ "$(valid_of wall_plate.json)" -gt 0 ] || fail "solve: the wall facet has no VALID box on the plate"
"$solve" --mesh "$mesh" --facet "$wall" --camera "$camera" "${eps[@]}" --out wall_side.json --quiet \
    --occluder "$plate" --keep-out "$below" --keep-out "$side" || fail "solve (wall, two keep-outs) failed"
[ "$(entering wall_plate.json -2 -2 -0.01 -0.5 2 2)" -gt 0 ] || fail "solve: the side keep-out would not cut anything (test is vacuous)"
[ "$(entering wall_side.json -2 -2 -0.01 -0.5 2 2)" -eq 0 ] || fail "solve: a VALID box enters the side keep-out"
[ "$(entering wall_side.json -2 -2 -2 2 2 -0.01)" -eq 0 ] || fail "solve: a VALID box enters the keep-out below the plate"
[ "$(valid_of wall_side.json)" -gt 0 ] || fail "solve: the side keep-out left no VALID box"
python3 - wall_side.json "$plate" <<'EOF' || fail "solve: the result JSON does not record the scene"
import json, sys
d = json.load(open(sys.argv[1]))
assert len(d["occluders"]) == 1, d["occluders"]
o = d["occluders"][0]
assert o["path"] == sys.argv[2] and o["scale"] == 1 and o["faces"] == 12 and len(o["digest"]) == 16, o
assert d["keep_in"] == [], d["keep_in"]
assert d["keep_out"] == [{"box": [-2, -2, -2, 2, 2, -0.01]}, {"box": [-2, -2, -0.01, -0.5, 2, 2]}], d["keep_out"]
assert "camera_region" in d["stats"]["boundary_reasons"]
for b in d["boxes"]:
    if b.get("undecided") == "camera_region": assert b["class"] == "boundary"
EOF
python3 - wall.json <<'EOF' || fail "solve: a run without a scene does not record empty lists"
import json, sys
d = json.load(open(sys.argv[1]))
assert d["occluders"] == [] and d["keep_in"] == [] and d["keep_out"] == []
EOF

# The plate hides the bottom facet's only viewpoints.
"$solve" --mesh "$mesh" --facet "$bottom" --camera "$camera" "${eps[@]}" --out bottom.json --quiet \
    || fail "solve (bottom facet) failed"
"$solve" --mesh "$mesh" --facet "$bottom" --camera "$camera" "${eps[@]}" --out bottom_plate.json --quiet \
    --occluder "$plate" || fail "solve (bottom facet, plate) failed"
[ "$(valid_of bottom.json)" -gt 0 ] || fail "solve: the bottom facet has no VALID box without the plate"
[ "$(valid_of bottom_plate.json)" -eq 0 ] || fail "solve: the plate does not hide the bottom facet"

# ---- certipose-part ----------------------------------------------------------------------------
"$part" --mesh "$mesh" --camera "$camera" "${eps[@]}" --facets "$bottom,$wall" --out run_free --quiet --box-store both \
    || fail "part (no scene) failed"
"$part" --mesh "$mesh" --camera "$camera" "${eps[@]}" --facets "$bottom,$wall" --out run --quiet --boundary --box-store both \
    --occluder "$plate" --keep-out "$below" --keep-out "$side" 2>err || fail "part (plate, keep-outs) failed: $(cat err)"
[ "$(entering run/boxes.jsonl -2 -2 -2 2 2 -0.01)" -eq 0 ] || fail "part: a VALID box enters the keep-out below the plate"
[ "$(entering run/boxes.jsonl -2 -2 -0.01 -0.5 2 2)" -eq 0 ] || fail "part: a VALID box enters the side keep-out"
[ "$(entering run_free/boxes.jsonl -2 -2 -0.01 -0.5 2 2 "$wall")" -gt 0 ] || fail "part: the side keep-out would cut nothing"
python3 - run/summary.json run_free/summary.json "$bottom" "$wall" run/boxes.jsonl <<'EOF' || fail "part: summary.json is wrong"
import json, sys
s, free, bottom, wall = json.load(open(sys.argv[1])), json.load(open(sys.argv[2])), int(sys.argv[3]), int(sys.argv[4])
rec = {f["index"]: f for f in s["facets"]}
rec_free = {f["index"]: f for f in free["facets"]}
assert rec_free[bottom]["valid"] > 0, "no VALID box for the bottom facet without the plate"
assert rec[bottom]["valid"] == 0, "the plate does not hide the bottom facet in the part run"
assert rec[wall]["valid"] > 0, "no VALID box for the wall facet"
assert [o["faces"] for o in s["occluders"]] == [12] and len(s["occluders"][0]["digest"]) == 16
assert s["keep_out"] == [{"box": [-2, -2, -2, 2, 2, -0.01]}, {"box": [-2, -2, -0.01, -0.5, 2, 2]}] and s["keep_in"] == []
lines = [json.loads(l) for l in open(sys.argv[5]) if l.strip()]
valid = sum(1 for b in lines if b["facet"] == wall and b["class"] == "valid")
assert valid == rec[wall]["valid"], (valid, rec[wall]["valid"])
assert free["occluders"] == [] and free["keep_out"] == []
EOF

# ---- certipose-plan and certipose-verify ------------------------------------------------------
[ -n "$plan" ] || exit 0
scene=(--occluder "$plate" --keep-out "$below" --keep-out "$side")
"$part" --mesh "$mesh" --camera "$camera" "${eps[@]}" --facets 880-920 --out plan_run --quiet "${scene[@]}" \
    || fail "part (plan run) failed"
"$plan" --mesh "$mesh" --camera "$camera" --part-results plan_run --coverage 0.9 --out plan.json --quiet "${scene[@]}" \
    2>err || fail "plan with the run's scene failed: $(cat err)"
# The keep-outs given in the other order are the same regions.
"$plan" --mesh "$mesh" --camera "$camera" --part-results plan_run --coverage 0.9 --out plan2.json --quiet \
    --keep-out "$side" --occluder "$plate" --keep-out "$below" 2>err || fail "plan with the regions reordered failed: $(cat err)"
python3 - plan.json <<'EOF' || fail "PLAN.json does not record the scene, or a camera box enters a keep-out"
import json, sys
p = json.load(open(sys.argv[1]))
assert [o["faces"] for o in p["occluders"]] == [12]
assert len(p["keep_out"]) == 2 and p["keep_in"] == []
assert p["cameras"], "no camera"
for c in p["cameras"]:
    pos = c["position"]
    for r in p["keep_out"]:
        b = r["box"]
        assert not all(pos[k][1] >= b[k] and pos[k][0] <= b[k + 3] for k in range(3)), (pos, b)
EOF
mismatch() {  # mismatch WHAT-NAMED OPTIONS...
    local what=$1; shift
    "$plan" --mesh "$mesh" --camera "$camera" --part-results plan_run --coverage 0.9 --out bad.json --quiet "$@" 2>err
    [ $? -eq 1 ] || fail "plan from a run of another scene ($*): expected exit 1: $(cat err)"
    grep -q "the run's $what (.*) is not this plan's" err || fail "the $what mismatch is not named: $(cat err)"
    [ -e bad.json ] && fail "a failed plan wrote its output"
    return 0
}
mismatch occluders --keep-out "$below" --keep-out "$side"                         # no occluder
cp "$plate" plate_copy.off
mismatch occluders --occluder "$plate:1.001" --keep-out "$below" --keep-out "$side"  # another scale
mismatch keep_out --occluder "$plate" --keep-out "$below"                          # a region less
mismatch keep_out --occluder "$plate" --keep-out "$below" --keep-out 'box:-2,-2,-0.01,-0.5,2,2.0000000001'
mismatch keep_in --occluder "$plate" --keep-out "$below" --keep-out "$side" --keep-in 'sphere:0,0,0,5'
# The same occluder under another name is the same scene.
"$plan" --mesh "$mesh" --camera "$camera" --part-results plan_run --coverage 0.9 --out plan3.json --quiet \
    --occluder plate_copy.off --keep-out "$below" --keep-out "$side" 2>err || fail "plan with a copy of the plate failed: $(cat err)"
# A summary.json written before the scene was recorded (no "occluders", "keep_in", "keep_out")
# reads as a run without any: it plans without --occluder and --keep-out, and not with them.
mkdir -p old && cp run_free/boxes.jsonl old/
python3 - run_free/summary.json old/summary.json <<'EOF' || fail "could not edit summary.json"
import json, sys
s = json.load(open(sys.argv[1]))
for k in ("occluders", "keep_in", "keep_out"): del s[k]
json.dump(s, open(sys.argv[2], "w"))
EOF
"$plan" --mesh "$mesh" --camera "$camera" --part-results old --coverage 0.9 --out old.json --quiet 2>err \
    || fail "plan from a summary.json without the scene failed: $(cat err)"
python3 -c 'import json,sys; p=json.load(open(sys.argv[1])); assert p["occluders"]==[] and p["keep_in"]==[] and p["keep_out"]==[]' old.json \
    || fail "PLAN.json of a run without a scene does not record empty lists"
"$plan" --mesh "$mesh" --camera "$camera" --part-results old --coverage 0.9 --out old2.json --quiet --occluder "$plate" 2>err
[ $? -eq 1 ] && grep -q "the run's occluders (none) is not this plan's" err || fail "a run without occluders planned with one: $(cat err)"
# One shot: the regions cut the candidates there too.
"$plan" --mesh "$mesh" --camera "$camera" "${eps[@]}" --facets 895-905 --cameras 2 --out oneshot.json --quiet \
    "${scene[@]}" || fail "one-shot plan with the scene failed"

# certipose-verify: the plan's boxes are allowed; a pose under the plate is outside the allowed space.
"$verify" --mesh "$mesh" --camera "$camera" --poses plan.json --out report.json --quiet "${scene[@]}" 2>err \
    || fail "verify of the plan failed: $(cat err)"
python3 - report.json <<'EOF' || fail "verify: the plan's boxes are not all allowed"
import json, sys
r = json.load(open(sys.argv[1]))
assert r["poses"] and all(p["camera_region"] == "allowed" for p in r["poses"]), [p["camera_region"] for p in r["poses"]]
assert len(r["occluders"]) == 1 and len(r["keep_out"]) == 2
EOF
echo '{"poses": [[-0.6, 0, -0.3, 0, 2.5, 0], [0, 0, 0.6, 0, 0, 0]]}' > poses.json
"$verify" --mesh "$mesh" --camera "$camera" --poses poses.json --out pose_report.json "${scene[@]}" >vout 2>err \
    || fail "verify of a pose in the keep-out failed: $(cat err)"
grep -q "pose 0 (exact): OUTSIDE the allowed camera space" vout || fail "the pose in the keep-out is not reported: $(cat vout)"
grep -q "pose 1 (exact): OUTSIDE" vout && fail "the allowed pose is reported outside: $(cat vout)"
python3 - pose_report.json <<'EOF' || fail "verify: the report of the pose in the keep-out is wrong"
import json, sys
p = json.load(open(sys.argv[1]))["poses"]
assert p[0]["camera_region"] == "forbidden" and p[0]["facets"] == [] and p[0]["possible"] == [], p[0]
assert p[1]["camera_region"] == "allowed", p[1]
EOF
usage certipose-verify "'sphere:1,2,3'" "$verify" --mesh "$mesh" --camera "$camera" --poses poses.json --keep-in sphere:1,2,3
usage certipose-plan "'box:a,0,0,1,1,1'" "$plan" --mesh "$mesh" --camera "$camera" --part-results plan_run --out x.json \
    --keep-out box:a,0,0,1,1,1
exit 0
