#!/usr/bin/env python3
"""Renders a deployment plan (certipose-plan's PLAN.json) for docs/coverage.md:
  OUT_PART.png  the part, each facet in the colour of the first camera box that certifies it
                (grey: none), and the camera position boxes in their colours;
  OUT_CURVE.png the certified share of the coverable area after k cameras, with the plan's
                lower bound on the cameras any plan needs.

Needs Debian's python3-matplotlib (a documentation tool only; the library does not use it):
    /usr/bin/python3 scripts/render_plan.py PART.off PLAN.json OUT_PART.png OUT_CURVE.png
"""
import colorsys
import json
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from mpl_toolkits.mplot3d.art3d import Poly3DCollection  # noqa: E402

from render_case_study import box_faces, read_off  # noqa: E402  (the OFF reader of the other docs picture)


def colour(k):
    # Golden-angle hue steps, as the PLY of certipose-plan (io/plan_files.hpp).
    r, g, b = colorsys.hsv_to_rgb((0.618033988749895 * k) % 1.0, 0.8, 0.9)
    return (r, g, b, 1.0)


def main(off_path, plan_path, out_part, out_curve):
    verts, faces = read_off(off_path)
    with open(plan_path) as f:
        plan = json.load(f)
    scale = plan["mesh"].get("scale", 1.0)
    verts = [tuple(scale * c for c in v) for v in verts]
    by = [None] * len(faces)
    for k in reversed(range(len(plan["cameras"]))):
        for f in plan["cameras"][k]["facets"]:
            by[f] = k
    face_colours = [(0.7, 0.7, 0.7, 1.0) if k is None else colour(k) for k in by]
    polys = [[verts[k] for k in f] for f in faces]
    fig = plt.figure(figsize=(13, 6.2), dpi=110)

    def fit(ax, pts):
        xs, ys, zs = zip(*pts)
        span = max(max(xs) - min(xs), max(ys) - min(ys), max(zs) - min(zs))
        mid = [(max(c) + min(c)) / 2 for c in (xs, ys, zs)]
        for setter, m in zip((ax.set_xlim, ax.set_ylim, ax.set_zlim), mid):
            setter(m - span / 2, m + span / 2)
        ax.set_axis_off()

    # Left: the part, each facet in the colour of its camera.
    ax = fig.add_subplot(1, 2, 1, projection="3d")
    ax.add_collection3d(Poly3DCollection(polys, facecolors=face_colours, edgecolors=(0, 0, 0, 0.12), linewidths=0.2))
    fit(ax, verts)
    ax.view_init(elev=35, azim=-60)
    ax.set_title("each facet in the colour of the camera box certifying it (grey: none)", fontsize=9)

    # Right: the camera boxes (drawn 20x larger to be seen) and their sight lines to what they certify.
    ax = fig.add_subplot(1, 2, 2, projection="3d")
    ax.add_collection3d(Poly3DCollection(polys, facecolors=face_colours, linewidths=0))
    pts = list(verts)
    for k, cam in enumerate(plan["cameras"]):
        c = colour(k)
        centre = [(lo + hi) / 2 for lo, hi in cam["position"]]
        grown = [[m - 20 * (hi - lo) / 2, m + 20 * (hi - lo) / 2] for m, (lo, hi) in zip(centre, cam["position"])]
        ax.add_collection3d(Poly3DCollection(box_faces(grown), facecolors=(c[0], c[1], c[2], 0.5),
                                             edgecolors=(c[0], c[1], c[2], 1.0), linewidths=0.6))
        fs = cam["facets"]
        target = [sum(verts[v][d] for f in fs for v in faces[f]) / (3 * len(fs)) for d in range(3)]
        ax.plot(*zip(centre, target), color=c, lw=0.8)
        pts.append(tuple(centre))
    fit(ax, pts)
    ax.view_init(elev=20, azim=-60)
    ax.set_title("camera position boxes (20x enlarged), lines to the centre of what each certifies", fontsize=9)
    cov = plan["coverage"]
    fig.suptitle(f"{len(plan['cameras'])} camera boxes certify {100 * cov['certified_area'] / cov['coverable_area']:.1f} % "
                 f"of the coverable area ({100 * cov['certified_area'] / cov['total_area']:.1f} % of the part); "
                 f"tolerance per box: {plan['settings'].get('tolerance')}")
    fig.savefig(out_part, bbox_inches="tight")

    curve = [a / cov["coverable_area"] * 100 for a in cov["curve"]]
    fig, ax = plt.subplots(figsize=(7, 4), dpi=110)
    ax.plot(range(1, len(curve) + 1), curve, marker="o", markersize=3)
    for share in (90, 95):
        k = next((i + 1 for i, c in enumerate(curve) if c >= share - 1e-9), None)
        if k:
            ax.axhline(share, color="grey", lw=0.6, ls="--")
            ax.annotate(f"{share} %: {k} cameras", (k, share), textcoords="offset points", xytext=(8, -12))
    ax.axvline(cov["lower_bound_cameras"], color="red", lw=0.8, ls=":",
               label=f"lower bound for {curve[-1]:.0f} %: {cov['lower_bound_cameras']} ({cov['lower_bound_method']})")
    ax.set_xlabel("cameras (greedy order)")
    ax.set_ylabel("certified share of the coverable area (%)")
    ax.set_ylim(0, 101)
    ax.legend(loc="lower right")
    ax.grid(alpha=0.3)
    fig.savefig(out_curve, bbox_inches="tight")


if __name__ == "__main__":
    if len(sys.argv) != 5:
        sys.exit(__doc__)
    main(*sys.argv[1:])
