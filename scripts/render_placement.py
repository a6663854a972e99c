#!/usr/bin/env python3
"""Renders two certipose results of one facet side by side (docs/placement.md): the VALID position
boxes certified for the nominal placement of the part, and those certified for every placement a
tolerance admits. Same view and scale in both; the titles give counts and certified volumes from
the result JSON, and the tolerance from its task.

Needs Debian's python3-matplotlib (a documentation tool only):
    /usr/bin/python3 scripts/render_placement.py PART.off NOMINAL.json TOLERANT.json OUT.png
"""
import json
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from render_case_study import box_faces, plt, Poly3DCollection, read_off  # noqa: E402


def main(off_path, nominal_path, tolerant_path, png_path):
    verts, faces = read_off(off_path)
    results = [json.load(open(p)) for p in (nominal_path, tolerant_path)]
    fig = plt.figure(figsize=(14, 6.5), dpi=100)
    pts = [c for r in results for b in r["boxes"] if b["class"] == "valid"
           for c in ([p[0] for p in b["position"]], [p[1] for p in b["position"]])]
    lo = [min(min(p[k] for p in pts), min(v[k] for v in verts)) for k in range(3)]
    hi = [max(max(p[k] for p in pts), max(v[k] for v in verts)) for k in range(3)]
    span = max(h - l for l, h in zip(lo, hi))
    mid = [(l + h) / 2 for l, h in zip(lo, hi)]
    for n, r in enumerate(results):
        ax = fig.add_subplot(1, 2, n + 1, projection="3d")
        fi = r["facet"]["index"]
        ax.add_collection3d(Poly3DCollection([[verts[i] for i in f] for k, f in enumerate(faces) if k != fi],
                                             facecolor=(0.7, 0.7, 0.72), edgecolor=(0.45, 0.45, 0.5), linewidths=0.1))
        ax.add_collection3d(Poly3DCollection([r["facet"]["vertices"]], facecolor="red", edgecolor="darkred"))
        quads = [q for b in r["boxes"] if b["class"] == "valid" for q in box_faces(b["position"])]
        ax.add_collection3d(Poly3DCollection(quads, facecolor=(0.1, 0.75, 0.2, 0.22), edgecolor=(0.0, 0.45, 0.1, 0.5),
                                             linewidths=0.3))
        for setter, m in zip((ax.set_xlim, ax.set_ylim, ax.set_zlim), mid):
            setter(m - span / 2, m + span / 2)
        ax.set_box_aspect((1, 1, 1))
        ax.view_init(elev=24, azim=-58)
        ax.set_xlabel("x (m)")
        ax.set_ylabel("y (m)")
        ax.set_zlabel("z (m)")
        t = r["task"].get("placement_tolerance")
        what = "the nominal placement" if not t else "every placement within ±%g mm, ±%.2g°" % (
            t["translation"][0] * 1000, t["rotation"] * 180 / 3.141592653589793)
        s = r["stats"]
        ax.set_title("facet %d, certified for %s:\n%d VALID boxes, %.3f m\N{SUPERSCRIPT THREE} of positions"
                     % (fi, what, s["valid"], s["valid_volume"]), fontsize=10)
    fig.tight_layout()
    fig.savefig(png_path)


if __name__ == "__main__":
    if len(sys.argv) != 5:
        sys.exit("usage: render_placement.py PART.off NOMINAL.json TOLERANT.json OUT.png")
    main(*sys.argv[1:])
