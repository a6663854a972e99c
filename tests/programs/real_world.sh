#!/usr/bin/env bash
# Real-world inputs on the programs (CTest: program.real_world): part placement tolerance
# (--part-tolerance, --datum, and the fixture form --part-axis, --part-tilt), lens distortion in the camera JSON and calibration files given as
# --camera (OpenCV YAML, ROS camera_info) with --working-distance and --min-view-angle.
#   real_world.sh SOLVE PART MESH CAMERA WORK_DIR [PLAN VERIFY]
# Checked: the tolerance is recorded in task.placement_tolerance (datum: the part's centroid, or
# --datum) and leaves fewer VALID boxes, with "placement" boundary reasons; bad tolerances and a
# datum alone are usage errors (exit 2) naming the text; --compare-run puts a plan without the
# tolerance beside the plan with it; a plan from a run of another tolerance is
# refused naming task.placement_tolerance, with the same one it works and records it, and
# certipose-verify's REPORT.json records it; a distorted camera solves and records its
# coefficients, an impossible one is refused naming distortion_coefficients; a calibration file
# solves as the camera JSON's pinhole K (OpenCV's pixel centres are whole numbers, certipose's
# half-integers), and --working-distance / --min-view-angle are required with it and refused
# with a camera JSON.
set -uo pipefail
solve=$1 part=$2 mesh=$3 camera=$4 work=$5 plan=${6:-} verify=${7:-}
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 1
fail() { echo "FAIL: $*" >&2; exit 1; }
eps=(--position-eps 0.1 --orientation-eps 0.38)
tol=(--part-tolerance 0.003,0.003,0.003,0.0175)
facet=900

usage() {  # usage PROGRAM-NAME EXPECTED-TEXT COMMAND...
    local name=$1 text=$2; shift 2
    "$@" >out 2>err
    local rc=$?
    [ $rc -eq 2 ] || fail "$name ${*: -2}: expected exit 2, got $rc: $(cat err)"
    [ "$(wc -l < err)" -eq 1 ] || fail "$name: more than one error line: $(cat err)"
    grep -qF -- "$text" err || fail "$name: the error does not name '$text': $(cat err)"
    grep -q "^$name: error: " err || fail "$name: not the usage error line: $(cat err)"
}
valid_of() { python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["stats"]["valid"])' "$1"; }

# ---- placement tolerance: certipose-solve -------------------------------------------------------
solve_args=(--mesh "$mesh" --facet "$facet" --camera "$camera" "${eps[@]}" --quiet)
"$solve" "${solve_args[@]}" --out nominal.json 2>err || fail "solve (nominal) failed: $(cat err)"
"$solve" "${solve_args[@]}" --out tol.json "${tol[@]}" 2>err || fail "solve with --part-tolerance failed: $(cat err)"
python3 - nominal.json tol.json <<'EOF' || fail "solve: the placement tolerance is not recorded or changes nothing"
import json, sys
nominal, tol = (json.load(open(p)) for p in sys.argv[1:3])
assert "placement_tolerance" not in nominal["task"] or nominal["task"]["placement_tolerance"] is None, nominal["task"]
t = tol["task"]["placement_tolerance"]
assert t["translation"] == [0.003, 0.003, 0.003] and t["rotation"] == 0.0175, t
d = t["datum"]
assert len(d) == 3 and all(abs(a - b) < 5e-4 for a, b in zip(d, (0.0014, 0.0020, 0.0293))), d  # the part's centroid
assert 0 < tol["stats"]["valid"] < nominal["stats"]["valid"], (tol["stats"]["valid"], nominal["stats"]["valid"])
assert tol["stats"]["boundary_reasons"]["placement"] > 0, tol["stats"]["boundary_reasons"]
EOF
"$solve" "${solve_args[@]}" --out datum.json "${tol[@]}" --datum 0,0,0 2>err || fail "solve with --datum failed: $(cat err)"
python3 -c 'import json,sys; d=json.load(open(sys.argv[1]))["task"]["placement_tolerance"]["datum"]; assert d==[0,0,0], d' datum.json \
    || fail "solve: --datum 0,0,0 is not the datum recorded"

# The fixture form: ROT about the plate's normal, a small tilt; recorded, and it keeps more than
# the any-axis form of the same ROT (the part no longer tips by ROT).
"$solve" "${solve_args[@]}" --out plate.json "${tol[@]}" --part-axis 0,0,2 --part-tilt 0.001 2>err ||
    fail "solve with --part-axis failed: $(cat err)"
python3 - tol.json plate.json <<'EOF' || fail "solve: the fixture form is not recorded, or keeps no more than any axis"
import json, sys
anyaxis, plate = (json.load(open(p)) for p in sys.argv[1:3])
t = plate["task"]["placement_tolerance"]
assert t["axis"] == [0, 0, 2] and t["tilt"] == 0.001 and t["rotation"] == 0.0175, t
assert plate["stats"]["valid"] >= anyaxis["stats"]["valid"] > 0, (plate["stats"]["valid"], anyaxis["stats"]["valid"])
EOF
# Millimetres typed as metres: a warning naming the unit (the run still goes: nothing survives it).
loud_args=(--mesh "$mesh" --facet "$facet" --camera "$camera" "${eps[@]}")
"$solve" "${loud_args[@]}" --out mm.json --part-tolerance 2,2,2,0.01 --max-boxes 50 >out 2>err
grep -q "warning: --part-tolerance lets the part slide by 2 m, .*is it in millimetres? It is read as metres: 0.002 for 2 mm" err ||
    fail "no unit warning for --part-tolerance 2,2,2: $(cat err)"
"$solve" "${loud_args[@]}" --out ok.json "${tol[@]}" >out 2>err
grep -q "warning: --part-tolerance" err && fail "a tolerance warning for a plausible tolerance: $(cat err)"
rm -f bad.json
usage certipose-solve "--part-axis 0,0,1: needs --part-tolerance" "$solve" "${solve_args[@]}" --out bad.json --part-axis 0,0,1
usage certipose-solve "--part-tilt 0.001: needs --part-axis" "$solve" "${solve_args[@]}" --out bad.json "${tol[@]}" --part-tilt 0.001
usage certipose-solve "must not be 0,0,0" "$solve" "${solve_args[@]}" --out bad.json "${tol[@]}" --part-axis 0,0,0
usage certipose-solve "degrees?" "$solve" "${solve_args[@]}" --out bad.json "${tol[@]}" --part-axis 0,0,1 --part-tilt 5
usage certipose-solve "--part-tolerance 0.003,0.003,-1,0.02" "$solve" "${solve_args[@]}" --out bad.json --part-tolerance 0.003,0.003,-1,0.02
usage certipose-solve "--part-tolerance 1,2,3" "$solve" "${solve_args[@]}" --out bad.json --part-tolerance 1,2,3
usage certipose-solve "degrees?" "$solve" "${solve_args[@]}" --out bad.json --part-tolerance 0,0,0,20
usage certipose-solve "--datum 0,0,0: needs --part-tolerance" "$solve" "${solve_args[@]}" --out bad.json --datum 0,0,0
usage certipose-solve "'a' is not a finite number" "$solve" "${solve_args[@]}" --out bad.json "${tol[@]}" --datum a,b,c
[ -e bad.json ] && fail "a usage error wrote its output"

# ---- lens distortion in the camera JSON --------------------------------------------------------
with_distortion() {  # with_distortion OUT.json COEFFICIENTS-JSON
    python3 - "$camera" "$1" "$2" <<'EOF'
import json, sys
d = json.load(open(sys.argv[1]))
d["camera"]["distortion_coefficients"] = json.loads(sys.argv[3])
json.dump(d, open(sys.argv[2], "w"))
EOF
}
# k1 = -1e9: the image folds a pixel from the principal point, no image region can be certified.
# (k1 = +1e9 is accepted: a region of a few pixels is certified, and the solve finds no VALID box.)
with_distortion distorted.json '[0.3, 0.1, 0, 0, 0]' && with_distortion impossible.json '[-1e9, 0, 0, 0]' || fail "could not write the cameras"
"$solve" --mesh "$mesh" --facet "$facet" --camera distorted.json "${eps[@]}" --out distorted_result.json --quiet 2>err \
    || fail "solve with a distorted camera failed: $(cat err)"
python3 -c 'import json,sys; c=json.load(open(sys.argv[1]))["camera"]; assert c["distortion_coefficients"]==[0.3,0.1,0,0,0], c' \
    distorted_result.json || fail "solve: the result does not record the distortion coefficients"
"$solve" --mesh "$mesh" --facet "$facet" --camera impossible.json "${eps[@]}" --out bad.json --quiet 2>err
[ $? -eq 1 ] || fail "an impossible distortion: expected exit 1: $(cat err)"
grep -q "distortion_coefficients" err || fail "an impossible distortion is not named: $(cat err)"
grep -qF "impossible.json" err || fail "the error does not name the camera file: $(cat err)"
[ -e bad.json ] && fail "a failed run wrote its output"

# ---- calibration files as --camera ---------------------------------------------------------------
# examples/data/camera.json's camera as OpenCV and ROS calibrations: f = 0.012 m / 3.45e-6 m px⁻¹,
# the principal point (1224, 1024) in certipose's pixels is (1223.5, 1023.5) in OpenCV's.
f=$(python3 -c 'print(repr(0.012 / 3.45e-6))')
cat > opencv.yaml <<EOF
%YAML:1.0
---
image_width: 2448
image_height: 2048
camera_matrix: !!opencv-matrix
   rows: 3
   cols: 3
   dt: d
   data: [ $f, 0., 1223.5, 0., $f, 1023.5, 0., 0., 1. ]
distortion_coefficients: !!opencv-matrix
   rows: 1
   cols: 5
   dt: d
   data: [ 0.05, -0.01, 0., 0., 0. ]
EOF
cat > ros.yaml <<EOF
image_width: 2448
image_height: 2048
camera_name: inspection_cam
camera_matrix:
  rows: 3
  cols: 3
  data: [$f, 0, 1223.5, 0, $f, 1023.5, 0, 0, 1]
distortion_model: plumb_bob
distortion_coefficients:
  rows: 1
  cols: 5
  data: [0, 0, 0, 0, 0]
rectification_matrix:
  rows: 3
  cols: 3
  data: [1, 0, 0, 0, 1, 0, 0, 0, 1]
projection_matrix:
  rows: 3
  cols: 4
  data: [$f, 0, 1223.5, 0, 0, $f, 1023.5, 0, 0, 0, 1, 0]
EOF
working=(--working-distance 0.49,0.77 --min-view-angle 0.35)
for cal in opencv ros; do
    "$solve" --mesh "$mesh" --facet "$facet" --camera $cal.yaml "${working[@]}" "${eps[@]}" --out $cal.json --quiet 2>err \
        || fail "solve with the $cal calibration failed: $(cat err)"
    python3 - $cal.json nominal.json $cal <<'EOF' || fail "solve: the $cal calibration is not the camera JSON's K"
import json, sys
r, nominal, cal = json.load(open(sys.argv[1])), json.load(open(sys.argv[2])), sys.argv[3]
c, n = r["camera"], nominal["camera"]
assert (c["width_px"], c["height_px"]) == (2448, 2048), c
for i in range(3):
    for j in range(3):
        assert abs(c["K"][i][j] - n["K"][i][j]) <= 1e-9 * max(1.0, abs(n["K"][i][j])), (c["K"], n["K"])
assert (c["d_min"], c["d_max"]) == (0.49, 0.77), c
assert r["task"]["min_view_angle"] == 0.35, r["task"]
if cal == "opencv": assert c["distortion_coefficients"] == [0.05, -0.01, 0, 0, 0], c
else: assert not c.get("distortion_coefficients"), c
assert r["stats"]["valid"] > 0, r["stats"]
EOF
done
# The options and the file go together.
usage certipose-solve "--working-distance" "$solve" --mesh "$mesh" --facet "$facet" --camera opencv.yaml --min-view-angle 0.35 \
    "${eps[@]}" --out bad.json
usage certipose-solve "--min-view-angle" "$solve" --mesh "$mesh" --facet "$facet" --camera ros.yaml --working-distance 0.49,0.77 \
    "${eps[@]}" --out bad.json
usage certipose-solve "--working-distance" "$solve" "${solve_args[@]}" --out bad.json --working-distance 0.49,0.77
usage certipose-solve "--min-view-angle" "$solve" "${solve_args[@]}" --out bad.json --min-view-angle 0.35
usage certipose-solve "--working-distance 0.77,0.49" "$solve" --mesh "$mesh" --facet "$facet" --camera opencv.yaml \
    --working-distance 0.77,0.49 --min-view-angle 0.35 "${eps[@]}" --out bad.json
usage certipose-solve "degrees?" "$solve" --mesh "$mesh" --facet "$facet" --camera opencv.yaml \
    --working-distance 0.49,0.77 --min-view-angle 20 "${eps[@]}" --out bad.json
usage certipose-part "--working-distance" "$part" --mesh "$mesh" --camera opencv.yaml "${eps[@]}" --out p
# A broken calibration: exit 1, the reader's error naming the file and the field.
sed 's/1023.5, 0., 0., 1\./1023.5, 0., 0., 2./' opencv.yaml > broken.yaml
"$solve" --mesh "$mesh" --facet "$facet" --camera broken.yaml "${working[@]}" "${eps[@]}" --out bad.json --quiet 2>err
[ $? -eq 1 ] || fail "a broken calibration: expected exit 1: $(cat err)"
grep -qF "broken.yaml" err && grep -qF "camera_matrix" err || fail "a broken calibration is not named: $(cat err)"
[ -e bad.json ] && fail "a usage error or failed run wrote its output"
[ -e p ] && fail "a usage error made its folder"

# ---- certipose-part, certipose-plan, certipose-verify -------------------------------------------
facets=(--facets 898-902)
"$part" --mesh "$mesh" --camera "$camera" "${eps[@]}" "${facets[@]}" --out run --quiet "${tol[@]}" 2>err \
    || fail "part with --part-tolerance failed: $(cat err)"
python3 -c 'import json,sys; t=json.load(open(sys.argv[1]))["task"]["placement_tolerance"]; assert t["rotation"]==0.0175 and len(t["datum"])==3, t' \
    run/summary.json || fail "part: summary.json does not record the tolerance"
# The calibration form on certipose-part too.
"$part" --mesh "$mesh" --camera ros.yaml "${working[@]}" "${eps[@]}" --facets 900 --out run_ros --quiet 2>err \
    || fail "part with a ROS calibration failed: $(cat err)"
[ -n "$plan" ] || exit 0
"$plan" --mesh "$mesh" --camera "$camera" --part-results run --coverage 0.9 --out bad.json --quiet 2>err
[ $? -eq 1 ] || fail "plan from a run with another tolerance: expected exit 1: $(cat err)"
grep -q "task.placement_tolerance" err || fail "the tolerance mismatch is not named: $(cat err)"
[ -e bad.json ] && fail "a failed plan wrote its output"
"$plan" --mesh "$mesh" --camera "$camera" --part-results run --coverage 0.9 --out plan.json "${tol[@]}" >out 2>err \
    || fail "plan with the run's tolerance failed: $(cat err)"
# The shares it prints hold for every placement the tolerance admits: the summary says which.
grep -q "certified for every placement of the part within ±3.0, 3.0, 3.0 mm and 1.00° about any axis" out \
    || fail "the plan's summary does not name the placement tolerance: $(cat out)"
python3 - plan.json <<'EOF' || fail "PLAN.json does not record the tolerance"
import json, sys
t = json.load(open(sys.argv[1]))["task"]["placement_tolerance"]
assert t["translation"] == [0.003, 0.003, 0.003] and t["rotation"] == 0.0175 and len(t["datum"]) == 3, t
EOF
# With and without the tolerance side by side: --compare-run plans a run of the same facets made
# without it, as certipose-plan plans that run on its own; PLAN.json stays this plan's.
"$part" --mesh "$mesh" --camera "$camera" "${eps[@]}" "${facets[@]}" --out run_free --quiet 2>err \
    || fail "part without a tolerance failed: $(cat err)"
"$plan" --mesh "$mesh" --camera "$camera" --part-results run_free --coverage 0.9 --out free.json >free.out 2>err \
    || fail "plan without a tolerance failed: $(cat err)"
"$plan" --mesh "$mesh" --camera "$camera" --part-results run --compare-run run_free --coverage 0.9 --out compared.json \
    "${tol[@]}" >out 2>err || fail "plan with --compare-run failed: $(cat err)"
free_shares=$(grep -o "[0-9]* camera box(es) certify .* of the part)" free.out) || fail "no shares in: $(cat free.out)"
grep -qF "  without a placement tolerance (--compare-run run_free): $free_shares" out \
    || fail "--compare-run does not give the run's own plan ($free_shares): $(cat out)"
grep -q "certified for every placement of the part within ±3.0, 3.0, 3.0 mm and 1.00° about any axis (--part-tolerance)$" out \
    || fail "--compare-run: the tolerance line: $(cat out)"
python3 - plan.json compared.json <<'EOF' || fail "--compare-run changed PLAN.json"
import json, sys
a, b = (json.load(open(p)) for p in sys.argv[1:])
assert a["cameras"] == b["cameras"] and a["coverage"] == b["coverage"] and a["task"] == b["task"], (a["coverage"], b["coverage"])
EOF
"$plan" --mesh "$mesh" --camera "$camera" --part-results run --compare-run run --coverage 0.9 --out same.json \
    "${tol[@]}" --quiet 2>err
[ $? -eq 1 ] || fail "--compare-run of the same tolerance: expected exit 1: $(cat err)"
grep -q "run/summary.json: the run has this plan's placement tolerance" err || fail "--compare-run same: $(cat err)"
[ -e same.json ] && fail "a refused --compare-run wrote its output"
"$verify" --mesh "$mesh" --camera "$camera" --poses plan.json --out report.json --quiet "${tol[@]}" 2>err \
    || fail "verify with --part-tolerance failed: $(cat err)"
python3 - report.json <<'EOF' || fail "REPORT.json does not record the tolerance"
import json, sys
t = json.load(open(sys.argv[1]))["placement_tolerance"]
assert t["translation"] == [0.003, 0.003, 0.003] and t["rotation"] == 0.0175 and len(t["datum"]) == 3, t
EOF
usage certipose-verify "--min-view-angle" "$verify" --mesh "$mesh" --camera opencv.yaml --poses plan.json \
    --working-distance 0.49,0.77 --out r.json
usage certipose-plan "--working-distance" "$plan" --mesh "$mesh" --camera "$camera" --part-results run --out x.json \
    --working-distance 0.49,0.77

# Units a person cannot get wrong: the sample part (metres) as if it were millimetres read as
# metres (x1000: ~300 m seen from under a metre) and as if it were metres scaled as millimetres
# (x0.001: a third of a millimetre) each solve, with a warning naming the likely unit and --scale;
# at its true size, no warning.
"$solve" --mesh "$mesh" --scale 1000 --camera "$camera" "${eps[@]}" --facet "$facet" --out big.json >out 2>err ||
    fail "certipose-solve on the mesh x1000 failed: $(cat err)"
grep -q "certipose-solve: warning: the part is .* m across after --scale 1000, .*is the mesh in millimetres.*--scale 0.001" err ||
    fail "no unit warning for a part x1000: $(cat err)"
"$part" --mesh "$mesh" --scale 0.001 --camera "$camera" "${eps[@]}" --facets 0-3 --out tiny --quiet >out 2>err ||
    fail "certipose-part on the mesh x0.001 failed: $(cat err)"
[ ! -s err ] || fail "--quiet printed: $(cat err)"
"$part" --mesh "$mesh" --scale 0.001 --camera "$camera" "${eps[@]}" --facets 0-3 --out tiny >out 2>err ||
    fail "certipose-part on the mesh x0.001 failed: $(cat err)"
grep -q "certipose-part: warning: the part is .* m across after --scale 0.001, fewer than 4 pixels.*Drop --scale" err ||
    fail "no unit warning for a part x0.001: $(cat err)"
# A plan that certifies nothing (the part x1000: nothing is in focus) is written, with each facet's
# reason, but exits 1 and says why, naming the likely cause: not "0.0 %" and exit 0.
if [ -n "$plan" ]; then
    "$plan" --mesh "$mesh" --scale 1000 --camera "$camera" "${eps[@]}" --facets 0-3 --out empty.json >out 2>err
    rc=$?
    [ $rc -eq 1 ] || fail "a plan with no camera: expected exit 1, got $rc: $(cat err)"
    grep -q "certipose-plan: no camera certifies any facet of .*(4 never visible, 2296 not solved): .*--scale" err ||
        fail "a plan with no camera does not say why: $(cat err)"
    [ -s empty.json ] || fail "the empty plan (with its reasons) was not written"
fi
"$solve" --mesh "$mesh" --camera "$camera" "${eps[@]}" --facet "$facet" --out true.json >out 2>err ||
    fail "certipose-solve at true size failed: $(cat err)"
grep -q "warning: the part is" err && fail "a unit warning at the part's true size: $(cat err)"
exit 0
