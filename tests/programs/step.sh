#!/usr/bin/env bash
# A STEP part on the programs (CTest: program.step): the real SolidWorks part of ../shared/cad
# (inches) as --mesh.
#   step.sh PART PLAN SOLVE STEP_FILE OFF_FILE CAMERA WORK_DIR
# Checked: certipose-part reads it in metres, tessellated at the default deflection (1/1000 of
# the diagonal), says so, and writes the triangles it certified (mesh.off, metres) and the CAD
# faces in summary.json ("cad": unit, deflections, and per face its id, surface, area, deviation
# and facets, a partition of the facets); mesh.off is the part's own STL export (OFF_FILE, inches)
# to within the deflection; certipose-plan plans from the run with --mesh the STEP file (the same
# tessellation, the same digest) and with --mesh mesh.off; --resume with another --deflection is
# refused; --scale with STEP, --deflection with a mesh and bad deflections are usage errors; a
# file named .step that is not STEP is an input error naming it.
set -uo pipefail
part=$1 plan=$2 solve=$3 step=$4 off=$5 camera=$6 work=$7
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 1
fail() { echo "FAIL: $*" >&2; exit 1; }
eps=(--position-eps 0.1 --orientation-eps 0.38)

"$part" --mesh "$step" --camera "$camera" "${eps[@]}" --facets 0-59 --threads 2 --out run >out 2>err ||
    fail "certipose-part on the STEP file failed: $(cat err)"
grep -q "CAD: 96 faces (file unit INCH), tessellated at" out || fail "no CAD line: $(cat out)"
grep -q "mesh.off" out || fail "the report does not name mesh.off: $(cat out)"
[ -f run/mesh.off ] || fail "no run/mesh.off"
python3 - run/summary.json run/mesh.off "$off" <<'EOF2' || fail "summary.json's cad or mesh.off is wrong"
import json, math, sys
s = json.load(open(sys.argv[1]))
def read_off(path, scale=1.0):
    words = open(path).read().split()
    assert words[0] == "OFF"
    nv, nf = int(words[1]), int(words[2])
    v = [tuple(float(x) * scale for x in words[4 + 3 * i: 7 + 3 * i]) for i in range(nv)]
    at = 4 + 3 * nv
    f = [tuple(int(x) for x in words[at + 4 * i + 1: at + 4 * i + 4]) for i in range(nf)]
    return v, f
v, f = read_off(sys.argv[2])
assert s["mesh"]["faces"] == len(f) and s["mesh"]["scale"] == 1, s["mesh"]
assert s["mesh"]["path"].endswith("featuretype.STEP"), s["mesh"]
c = s["cad"]
assert c["unit"] == "INCH", c["unit"]
assert c["angular_deflection"] == 0.5, c
lo = [min(p[k] for p in v) for k in range(3)]
hi = [max(p[k] for p in v) for k in range(3)]
diag = math.dist(lo, hi)
# OpenCASCADE's bounding box (which the default is taken from) holds the B-rep with its tolerances:
# a little larger than the triangles'
assert abs(c["deflection"] - diag / 1000) < 1e-2 * c["deflection"], (c["deflection"], diag)
faces = c["faces"]
assert len(faces) == 96
kinds = {}
for i, face in enumerate(faces):
    assert face["id"] == i and face["area"] > 0 and 0 <= face["deviation"] <= 1.01 * c["deflection"], face
    kinds[face["surface"]] = kinds.get(face["surface"], 0) + 1
assert kinds == {"plane": 49, "cylinder": 46, "bspline": 1}, kinds
listed = sorted(x for face in faces for x in face["facets"])
assert listed == list(range(len(f))), "the faces' facets are not a partition of the facets"
# the part's own STL export, in inches: the same bounding box to within the deflection
w, _ = read_off(sys.argv[3], 0.0254)
for k in range(3):
    assert abs(min(p[k] for p in w) - lo[k]) < 2 * c["deflection"], (k, lo)
    assert abs(max(p[k] for p in w) - hi[k]) < 2 * c["deflection"], (k, hi)
assert s["totals"]["facets"] == 60 and s["totals"]["valid"] > 0, s["totals"]
EOF2

# The other programs read the same STEP file into the same triangles (the run's digest), or the run's mesh.off.
"$plan" --mesh "$step" --camera "$camera" --part-results run --out plan.json --quiet 2>err ||
    fail "certipose-plan with the STEP file failed: $(cat err)"
"$plan" --mesh run/mesh.off --camera "$camera" --part-results run --out plan_off.json --quiet 2>err ||
    fail "certipose-plan with mesh.off failed: $(cat err)"
"$solve" --mesh "$step" --camera "$camera" "${eps[@]}" --facet 3 --out facet3.json >/dev/null 2>err ||
    fail "certipose-solve on the STEP file failed: $(cat err)"

# Another tessellation is another run.
"$part" --mesh "$step" --camera "$camera" "${eps[@]}" --facets 0-59 --deflection 0.0005 --out run --resume --quiet \
    >/dev/null 2>err && fail "--resume accepted another --deflection"
grep -q "resume" err || fail "the refusal does not say why: $(cat err)"

# Usage errors (exit 2) and input errors (exit 1), each naming what is wrong.
expect() {  # expect CODE PATTERN command...
    local code=$1 pattern=$2
    shift 2
    "$@" >/dev/null 2>err
    local got=$?
    [ "$got" -eq "$code" ] || fail "exit $got, not $code: $* : $(cat err)"
    grep -q -- "$pattern" err || fail "no '$pattern' in: $(cat err)"
}
expect 2 "--scale: .* is a STEP file" "$part" --mesh "$step" --camera "$camera" "${eps[@]}" --scale 0.0254 --out bad
expect 2 "--deflection: .* is a mesh" "$part" --mesh "$off" --camera "$camera" "${eps[@]}" --deflection 0.001 --out bad
expect 2 "--deflection: must be a positive" "$part" --mesh "$step" --camera "$camera" "${eps[@]}" --deflection 0 --out bad
expect 2 "--deflection: the angular deflection must be in (0, pi)" "$part" --mesh "$step" --camera "$camera" "${eps[@]}" \
    --deflection 0.001,4 --out bad
echo "solid nothing" > fake.step
expect 1 "fake.step: not a STEP file" "$part" --mesh fake.step --camera "$camera" "${eps[@]}" --out bad
[ ! -e bad ] || fail "a refused run left an output folder"
echo "step.sh: all checks passed"
