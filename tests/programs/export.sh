#!/usr/bin/env bash
# certipose-part -> certipose-plan -> certipose-export in every format (CTest: program.export).
#   export.sh PART PLAN EXPORT MESH CAMERA WORK_DIR NODE SOURCE_DIR CHECK_URDF
# The CSV has a header naming each unit and a row per camera in millimetres and degrees; the
# MoveIt YAML and the URDF name every camera with the chosen link prefix, and check_urdf (Debian
# liburdfdom-tools) accepts the URDF as written; the .glb passes the Khronos glTF validator and
# three.js's GLTFLoader finds a camera object at each nominal pose; the HTML page loads in
# headless Chromium without console errors, draws, and its facet picker names the cameras that
# certify the picked facet.
# The output never replaces an input, a bad option writes nothing, and a mesh that is not the
# plan's is refused.
set -uo pipefail
part=$1 plan=$2 export=$3 mesh=$4 camera=$5 work=$6 node=$7 src=$8 check_urdf=${9:-}
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 1
fail() { echo "FAIL: $*" >&2; exit 1; }

"$part" --mesh "$mesh" --camera "$camera" --position-eps 0.1 --orientation-eps 0.38 --facets 880-920 \
    --out run --quiet || fail "certipose-part failed"
"$plan" --mesh "$mesh" --camera "$camera" --part-results run --coverage 0.9 --out plan.json --quiet \
    || fail "certipose-plan failed"
cameras=$(grep -c '"from_facet"' plan.json)
[ "$cameras" -ge 1 ] || fail "no camera in the plan"

"$export" plan.json --format csv --out plan.csv >out 2>err || fail "csv: $(cat err)"
head -1 plan.csv | grep -q '^camera,x_mm,y_mm,z_mm,qx,qy,qz,qw,r00,.*,axis_cone_half_angle_deg,roll_half_range_deg,.*,aim_distance_mm,' \
    || fail "csv header: $(head -1 plan.csv)"
[ "$(($(wc -l < plan.csv) - 1))" -eq "$cameras" ] || fail "csv: expected $cameras rows"
grep -q 'wrote plan.csv' out || fail "no summary line: $(cat out)"

"$export" plan.json --format moveit --out plan.yaml --quiet 2>err || fail "moveit: $(cat err)"
[ "$(grep -c 'parameterization: 1' plan.yaml)" -eq "$cameras" ] || fail "moveit: one orientation constraint per camera"
grep -q 'link_name: camera_0_optical_frame' plan.yaml || fail "moveit: no optical frame link"
"$export" plan.json --format moveit --link-prefix cell1_cam --out cell.yaml --quiet 2>err || fail "moveit: $(cat err)"
grep -q 'link_name: cell1_cam0_optical_frame' cell.yaml || fail "moveit: --link-prefix is not the link name"

"$export" plan.json --format urdf --parent-frame base_link --out plan.urdf --quiet 2>err || fail "urdf: $(cat err)"
[ "$(grep -c '<parent link="base_link"/>' plan.urdf)" -eq "$cameras" ] || fail "urdf: one joint per camera on base_link"
[ -x "$check_urdf" ] || fail "no check_urdf (apt-get install liburdfdom-tools; scripts/install-deps.sh does)"
"$check_urdf" plan.urdf >check.out 2>&1 || fail "check_urdf refuses the URDF: $(cat check.out)"
grep -q "root Link: base_link has $cameras child(ren)" check.out \
    || fail "check_urdf: base_link is not the root of the cameras: $(cat check.out)"
"$export" plan.json --format urdf --link-prefix cell1_cam --robot-name cell1 --out cell.urdf --quiet 2>err \
    || fail "urdf --link-prefix: $(cat err)"
"$check_urdf" cell.urdf >check.out 2>&1 || fail "check_urdf refuses the URDF with a prefix: $(cat check.out)"
grep -q 'robot name is: cell1' check.out || fail "check_urdf: not the robot name given: $(cat check.out)"
grep -q 'cell1_cam0_optical_frame' check.out || fail "check_urdf: no cell1_cam0_optical_frame: $(cat check.out)"
"$export" plan.json --format urdf --snippet --out snippet.urdf --quiet 2>err || fail "urdf --snippet: $(cat err)"
grep -q '<robot name' snippet.urdf && fail "urdf --snippet wrote a <robot>"
# The snippet is what a user pastes into their own robot: wrapped in one, check_urdf accepts it.
{ echo '<robot name="cell"><link name="world"/>'; cat snippet.urdf; echo '</robot>'; } > wrapped.urdf
"$check_urdf" wrapped.urdf >check.out 2>&1 || fail "check_urdf refuses the wrapped snippet: $(cat check.out)"
"$export" plan.json --format csv --snippet --out x.csv 2>err
[ $? -eq 2 ] || fail "--snippet with --format csv: expected exit 2"
"$export" plan.json --format urdf --parent-frame 'bad frame' --out bad.urdf --quiet 2>err
[ $? -eq 1 ] || fail "urdf: a frame name with a space: expected exit 1"
grep -q "bad frame" err || fail "the bad frame name is not named: $(cat err)"

"$export" plan.json --format glb --mesh "$mesh" --out plan.glb --quiet 2>err || fail "glb: $(cat err)"
"$node" "$src/tests/web/validate_glb.mjs" plan.glb || fail "plan.glb does not pass the glTF validator"
"$node" "$src/tests/web/load_glb.mjs" plan.glb plan.csv || fail "three.js does not see the plan's cameras in plan.glb"

"$export" plan.json --format html --mesh "$mesh" --out plan.html --quiet 2>err || fail "html: $(cat err)"
"$node" "$src/tests/web/viewer_test.mjs" plan.html viewer.png || fail "the HTML viewer test failed"

# Refusals: an output that is an input, bad options, a mesh that is not the plan's.
cp plan.json keep.json
"$export" plan.json --format csv --out plan.json --quiet 2>err && fail "overwrote its input"
cmp -s plan.json keep.json || fail "the plan was changed"
grep -q 'certipose-export: ' err || fail "no error line for an output that is an input"
"$export" plan.json --format pdf --out x.pdf 2>err
[ $? -eq 2 ] || fail "--format pdf: expected exit 2"
grep -q "'pdf'" err || fail "the bad format is not named: $(cat err)"
"$export" plan.json --format glb --out x.glb 2>err
[ $? -eq 2 ] || fail "--format glb without --mesh: expected exit 2"
"$export" plan.json --format csv --title T --out x.csv 2>err
[ $? -eq 2 ] || fail "--title with --format csv: expected exit 2"
grep -q -- "--title applies to --format html" err || fail "the unused option is not named: $(cat err)"
[ -e x.csv ] && fail "a refused run wrote its output"
printf 'OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n' > one.off
"$export" plan.json --format glb --mesh one.off --out x.glb 2>err
[ $? -eq 1 ] || fail "another mesh: expected exit 1"
grep -q 'mesh.faces' err || fail "the face count mismatch is not named: $(cat err)"
# The plan's own part at another scale: as many faces, another digest.
"$export" plan.json --format glb --mesh "$mesh" --scale 2 --out x.glb 2>err
[ $? -eq 1 ] || fail "the part at another scale: expected exit 1"
grep -q 'mesh.digest' err || fail "the digest mismatch is not named: $(cat err)"
[ -e x.pdf ] || [ -e x.glb ] && fail "a failed run wrote its output"
echo "export: $cameras cameras exported in 5 formats"
