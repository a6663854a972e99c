#!/usr/bin/env bash
# A dirty mesh on the programs (CTest: program.dirty): overlapping bodies and a body buried in
# another, as CAD exports come.
#   dirty.sh SOLVE PART CAMERA WORK_DIR [PLAN]
# Checked: certipose-part reads it as a triangle soup by default, warns naming what it found
# (self-intersection, bodies, buried facets) and records "mesh_semantics" and "survey" in
# summary.json, where the buried body's facets are skipped with the reason; --mesh-semantics
# solid and --occlusion boolean refuse it naming what they need; certipose-solve warns that a
# buried facet cannot be inspected; summary.json records the paving and the options that change
# the answer; --keep-largest and --box-store are checked (bad values are usage errors); a plan
# reads the run's binary store and names the buried facets.
set -uo pipefail
solve=$1 part=$2 camera=$3 work=$4 plan=${5:-}
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 1
fail() { echo "FAIL: $*" >&2; exit 1; }
eps=(--position-eps 0.4 --orientation-eps 0.38)

# Three boxes: a slab, a box inside it (buried: all 12 faces) and a box through its side (the
# slab's side face 11 and the box's face 33 each have their centroid inside the other body:
# buried too, 14 in all).
python3 - <<'EOF2' > dirty.off || fail "could not write the mesh"
boxes = [((0, 0, 0), (0.2, 0.2, 0.1)), ((0.05, 0.05, 0.02), (0.15, 0.15, 0.06)), ((0.15, 0, 0), (0.3, 0.1, 0.15))]
faces = [(0, 2, 3), (0, 3, 1), (4, 5, 7), (4, 7, 6), (0, 1, 5), (0, 5, 4), (2, 6, 7), (2, 7, 3), (0, 4, 6), (0, 6, 2),
         (1, 3, 7), (1, 7, 5)]
V, F = [], []
for lo, hi in boxes:
    base = len(V)
    V += [(hi[0] if k & 1 else lo[0], hi[1] if k & 2 else lo[1], hi[2] if k & 4 else lo[2]) for k in range(8)]
    F += [tuple(base + i for i in f) for f in faces]
print("OFF")
print(len(V), len(F), 0)
for v in V: print(*v)
for f in F: print(3, *f)
EOF2

"$part" --mesh dirty.off --camera "$camera" "${eps[@]}" --out run --threads 2 --keep-largest 3 >out 2>err ||
    fail "certipose-part on the dirty mesh failed: $(cat err)"
grep -q "warning: occlusion reads the scene as a triangle soup" err || fail "no soup warning: $(cat err)"
grep -q "mesh self-intersects" err || fail "the warning does not say why: $(cat err)"
grep -q "3 bodies (3 closed), .* intersecting face pairs, 14 buried facets" err || fail "the survey line: $(cat err)"
grep -q "facet 11 is buried inside the body of face 24" err || fail "no buried example: $(cat err)"
[ -f run/boxes.cpbx ] && [ ! -e run/boxes.jsonl ] || fail "the default box store is boxes.cpbx alone"
python3 - run/summary.json <<'EOF2' || fail "summary.json does not record the soup, the survey or the settings"
import json, sys
s = json.load(open(sys.argv[1]))
st = s["settings"]
assert st["mesh_semantics"] == "soup", st
assert st["paving"] == "default" and st["corner_depth"] == 2 and st["keep_largest"] == 3 and st["facets"] == "all", st
assert st["grow"] is False and st["refine_seconds"] is None and st["max_boxes"] is None, st
sv = s["survey"]
assert sv["bodies"] == 3 and sv["closed_bodies"] == 3 and sv["buried"] == 14 and sv["intersecting_pairs"] > 0, sv
assert any("buried" in e for e in sv["examples"]), sv
facets = {f["index"]: f for f in s["facets"]}
for i in list(range(12, 24)) + [11, 33]:
    assert facets[i]["termination"] == "skipped" and "buried" in facets[i]["reason"], facets[i]
assert all(f["valid"] <= 3 for f in s["facets"])
assert sum(f["valid"] for f in s["facets"]) > 0
assert any(f.get("dropped", 0) > 0 for f in s["facets"]), "keep-largest dropped nothing"
EOF2

# What reads solids only refuses it, naming what it needs.
"$part" --mesh dirty.off --camera "$camera" "${eps[@]}" --out solid --mesh-semantics solid -q 2>err
[ $? -eq 1 ] || fail "--mesh-semantics solid: expected exit 1: $(cat err)"
grep -q "mesh self-intersects.*--mesh-semantics soup" err || fail "solid: the way out is not named: $(cat err)"
[ -e solid ] && fail "a failed run made its folder"
"$part" --mesh dirty.off --camera "$camera" "${eps[@]}" --out boolean --occlusion boolean -q 2>err
[ $? -eq 1 ] || fail "--occlusion boolean: expected exit 1: $(cat err)"
grep -q "needs closed, edge-manifold, self-intersection-free, outward-facing meshes" err || fail "boolean: $(cat err)"

# certipose-solve on a buried facet: a warning, no VALID box.
"$solve" --mesh dirty.off --camera "$camera" "${eps[@]}" --facet 14 --out buried.json >out 2>err ||
    fail "solve of a buried facet failed: $(cat err)"
grep -q "facet 14 is buried inside another closed body of the mesh: no camera can inspect it" err ||
    fail "solve does not say the facet is buried: $(cat err)"
python3 -c 'import json,sys; assert json.load(open(sys.argv[1]))["stats"]["valid"] == 0' buried.json ||
    fail "a buried facet got VALID boxes"

# Bad values of the new options are usage errors.
for bad in "--keep-largest 0" "--keep-largest x" "--box-store xml" "--mesh-semantics clean"; do
    # shellcheck disable=SC2086
    "$part" --mesh dirty.off --camera "$camera" "${eps[@]}" --out bad $bad -q 2>err
    [ $? -eq 2 ] || fail "$bad: expected exit 2: $(cat err)"
done
"$part" --mesh dirty.off --camera "$camera" "${eps[@]}" --out bin --box-store binary -q 2>err || fail "binary only: $(cat err)"
[ -f bin/boxes.cpbx ] && [ ! -e bin/boxes.jsonl ] || fail "--box-store binary wrote boxes.jsonl or no store"

# A plan reads the binary store (no boxes.jsonl there).
if [ -n "$plan" ]; then
    "$plan" --mesh dirty.off --camera "$camera" --part-results bin --coverage 0.9 --out PLAN.json -q 2>err ||
        fail "plan from a binary store failed: $(cat err)"
    python3 -c 'import json,sys; p=json.load(open(sys.argv[1])); assert p["cameras"], p' PLAN.json || fail "an empty plan"
    # The 14 buried facets are named so in the plan (the survey's word), not "never visible".
    python3 - PLAN.json <<'EOF2' || fail "the plan does not name the buried facets"
import json, sys
why = {u["facet"]: u["reason"] for u in json.load(open(sys.argv[1]))["uncovered"]}
buried = list(range(12, 24)) + [11, 33]
assert all(why.get(f) == "buried in another body" for f in buried), {f: why.get(f) for f in buried}
assert sum(r == "buried in another body" for r in why.values()) == 14, why
EOF2
fi
echo "dirty mesh: all checks passed"
