#!/usr/bin/env python3
"""What a part placement tolerance and a distorted lens cost, measured on the bundled sample part
(docs/placement.md#what-it-costs). For each case it runs, with the programs of a release build:

  * bench_completeness on the case study (facet 900): the certified share of the sampled true
    inspection space of the NOMINAL placement (docs/completeness.md), so the share shows what
    the tolerance costs;
  * certipose-part on the whole part, 2 threads: time, VALID boxes; alone, and (two rows) standing
    on the fixture plate with camera positions kept above it, the README's scene;
  * certipose-plan --coverage 0.95 from that run: cameras, coverage, time.

Cases: part tolerances 0, ±1 mm/0.5°, ±3 mm/1°, ±5 mm/2° with the pinhole-twin of
examples/data/camera.json, and the same camera with a strongly distorted lens
(k1 = +0.3, k2 = 0.1 and k1 = -0.3) at no tolerance.

    python3 bench/placement_cost.py PROGRAMS_DIR BENCH_DIR OUT_DIR
    # e.g. build/release/examples build/bench/bench /tmp/placement (a release build's programs,
    # the bench preset's bench_completeness)
It writes OUT_DIR/placement_cost.json, prints a Markdown table, and with python3-matplotlib
draws OUT_DIR/placement_cost.png (`--plot OUT_DIR/placement_cost.json` draws it again).
"""
import json
import math
import os
import re
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)


def run(cmd, **kw):
    t0 = time.monotonic()
    p = subprocess.run(cmd, capture_output=True, text=True, **kw)
    if p.returncode != 0:
        sys.exit(f"failed ({p.returncode}): {' '.join(cmd)}\n{p.stdout}\n{p.stderr}")
    return p, time.monotonic() - t0


def main():
    if len(sys.argv) == 3 and sys.argv[1] == "--plot":  # the figure again, from a saved run
        with open(sys.argv[2]) as f:
            plot(json.load(f), os.path.dirname(os.path.abspath(sys.argv[2])))
        return
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    bins, bench, out = sys.argv[1], sys.argv[2], sys.argv[3]
    os.makedirs(out, exist_ok=True)
    part = os.path.join(bins, "sample_part.off")
    if not os.path.exists(part):
        run([os.path.join(bins, "make_sample_part"), part])
    plate = os.path.join(ROOT, "examples/data/fixture_plate.off")
    with open(os.path.join(ROOT, "examples/data/camera.json")) as f:
        base = json.load(f)
    cameras = {"pinhole lens": dict(base)}
    for name, k in (("k1 = +0.3, k2 = 0.1", [0.3, 0.1, 0.0, 0.0, 0.0]), ("k1 = -0.3", [-0.3, 0.0, 0.0, 0.0, 0.0])):
        c = json.loads(json.dumps(base))
        c["camera"]["distortion_coefficients"] = k
        cameras[name] = c
    for name, c in cameras.items():
        with open(os.path.join(out, re.sub(r"[^a-z0-9]+", "_", name.lower()) + ".json"), "w") as f:
            json.dump(c, f)

    deg = math.pi / 180
    cases = [("pinhole lens", None, False), ("pinhole lens", (0.001, 0.5 * deg), False),
             ("pinhole lens", (0.003, 1.0 * deg), False), ("pinhole lens", (0.005, 2.0 * deg), False),
             ("k1 = +0.3, k2 = 0.1", None, False), ("k1 = -0.3", None, False),
             ("pinhole lens", None, True), ("pinhole lens", (0.003, 1.0 * deg), True)]
    rows = []
    for lens, tol, on_plate in cases:
        cam = os.path.join(out, re.sub(r"[^a-z0-9]+", "_", lens.lower()) + ".json")
        label = f"{lens}, " + ("no tolerance" if tol is None else f"±{tol[0] * 1000:g} mm / {tol[1] / deg:g}°")
        if on_plate:
            label += ", on the plate"
        tag = re.sub(r"[^a-z0-9]+", "_", label.lower()).strip("_")
        scene = ["--occluder", plate, "--keep-out", "box:-10,-10,-10,10,10,0"] if on_plate else []
        if tol is not None:
            scene += ["--part-tolerance", f"{tol[0]},{tol[0]},{tol[0]},{tol[1]!r}"]
        # The case study's certified share (the nominal truth), default paving.
        env = dict(os.environ, CERTIPOSE_BENCH_CAMERA=cam)
        mode = "full" if tol is None else f"full@{tol[0]}/{tol[1]!r}"
        p, _ = run([os.path.join(bench, "bench_completeness"), "4000", mode], env=env)
        share = None
        for line in p.stdout.splitlines():
            if line.startswith("| sample_part.off"):
                share = float(line.split("|")[4].split("%")[0])
        run_dir = os.path.join(out, "run_" + tag)
        subprocess.run(["rm", "-rf", run_dir])
        _, part_s = run([os.path.join(bins, "certipose-part"), "--mesh", part, "--camera", cam, *scene, "--position-eps", "0.1",
                         "--orientation-eps", "0.38", "--threads", "2", "--out", run_dir, "--quiet"])
        with open(os.path.join(run_dir, "summary.json")) as f:
            totals = json.load(f)["totals"]
        plan = os.path.join(out, "plan_" + tag + ".json")
        p, plan_s = run([os.path.join(bins, "certipose-plan"), "--mesh", part, "--camera", cam, *scene, "--part-results", run_dir,
                         "--coverage", "0.95", "--out", plan])
        with open(plan) as f:
            doc = json.load(f)
        m = re.search(r"certify ([0-9.]+) % of the coverable area \(([0-9.]+) % of the part\)", p.stdout)
        rows.append({"case": label, "lens": lens, "on_plate": on_plate, "translation_m": 0 if tol is None else tol[0],
                     "rotation_rad": 0 if tol is None else tol[1], "case_study_share_percent": share,
                     "part_seconds": round(part_s, 1), "valid_boxes": totals["valid"], "boundary_boxes": totals["boundary"],
                     "cameras": len(doc["cameras"]), "plan_seconds": round(plan_s, 1),
                     "coverable_percent": float(m.group(1)) if m else None, "part_percent": float(m.group(2)) if m else None})
        subprocess.run(["rm", "-rf", run_dir])
        print(json.dumps(rows[-1]), flush=True)
    with open(os.path.join(out, "placement_cost.json"), "w") as f:
        json.dump(rows, f, indent=1)
    print("| case | case study: certified share | whole part: time | VALID boxes | cameras for 95 % | of the part | plan time |")
    print("| --- | --- | --- | --- | --- | --- | --- |")
    for r in rows:
        print(f"| {r['case']} | {r['case_study_share_percent']:.1f} % | {r['part_seconds']:.1f} s | "
              f"{r['valid_boxes']:_} | {r['cameras']} | {r['part_percent']} % | {r['plan_seconds']:.1f} s |".replace("_", " "))
    plot(rows, out)


def plot(rows, out):
    """The figure of docs/placement.md from the rows (python3-matplotlib; nothing without it)."""
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("no matplotlib: no figure (Debian: python3-matplotlib)", file=sys.stderr)
        return
    tol_rows = [r for r in rows if r["lens"] == "pinhole lens" and not r["on_plate"]]
    x = [r["translation_m"] * 1000 for r in tol_rows]
    fig, ax = plt.subplots(1, 3, figsize=(12, 3.6))
    ax[0].plot(x, [r["case_study_share_percent"] for r in tol_rows], "o-")
    ax[0].set_ylabel("certified share, case study (%)")
    ax[1].plot(x, [r["part_percent"] for r in tol_rows], "o-", color="C0")
    ax[1].set_ylabel("part area the plan certifies (%)", color="C0")
    ax[1].set_ylim(0, 100)
    cams = ax[1].twinx()
    cams.plot(x, [r["cameras"] for r in tol_rows], "s--", color="C1")
    cams.set_ylabel("cameras for 95 % of the coverable area", color="C1")
    cams.set_ylim(0, max(r["cameras"] for r in tol_rows) + 2)
    ax[2].plot(x, [r["part_seconds"] for r in tol_rows], "o-", label="certipose-part")
    ax[2].plot(x, [r["plan_seconds"] for r in tol_rows], "s--", label="certipose-plan")
    ax[2].set_ylabel("seconds (2 cores)")
    ax[2].legend(fontsize=8)
    for a in ax:
        a.set_xlabel("part tolerance: ±mm (with 0, 0.5, 1, 2°)")
        a.set_xticks(x)
        a.grid(alpha=0.3)
    fig.suptitle("What a part placement tolerance costs on the sample part (default paving, ε_p 0.1 m, ε_o 0.38 rad)")
    fig.tight_layout()
    fig.savefig(os.path.join(out, "placement_cost.png"), dpi=110)


if __name__ == "__main__":
    main()
