#!/usr/bin/env python3
"""Renders a deployment plan (certipose-plan's PLAN.json) for docs/coverage.md:
  OUT_PART.png  the part, each facet in the colour of the first camera box that certifies it
                (grey: none), and the camera position boxes in their colours; the plan's
                occluders (--occluder, recorded in PLAN.json) drawn in pale brown;
  OUT_CURVE.png the certified share of the coverable area after k cameras, with the plan's
                lower bound on the cameras any plan needs.

Needs Debian's python3-matplotlib (a documentation tool only; the library does not use it):
    /usr/bin/python3 scripts/render_plan.py PART.off PLAN.json OUT_PART.png OUT_CURVE.png

An occluder is read from its path as PLAN.json records it (as given to certipose-plan: relative
to the directory the plan was made in, so run this from there too), else relative to PLAN.json's
directory; OFF files only. One that cannot be found or read is left out, with a warning.
"""
import colorsys
import json
import os
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


OCCLUDER_COLOUR = (0.80, 0.72, 0.60, 1.0)


def read_occluders(plan, plan_path):
    """The triangles of the plan's occluders (scaled), and their names; missing ones warned about."""
    polys, names = [], []
    for o in plan.get("occluders") or []:
        path = o["path"]
        if not os.path.exists(path):
            path = os.path.join(os.path.dirname(os.path.abspath(plan_path)), o["path"])
        try:
            verts, faces = read_off(path)
        except (OSError, AssertionError, ValueError, IndexError) as e:
            print(f"render_plan.py: warning: occluder {o['path']} not drawn: {e}", file=sys.stderr)
            continue
        s = o.get("scale", 1.0)
        polys += [[tuple(s * c for c in verts[k]) for k in f] for f in faces]
        names.append(os.path.basename(o["path"]))
    return polys, names


def region_text(r):
    kind, numbers = next(iter(r.items()))
    return kind + ":" + ",".join(f"{v:g}" for v in numbers)


def main(off_path, plan_path, out_part, out_curve):
    verts, faces = read_off(off_path)
    with open(plan_path) as f:
        plan = json.load(f)
    scale = plan["mesh"].get("scale", 1.0)
    verts = [tuple(scale * c for c in v) for v in verts]
    occluders, occluder_names = read_occluders(plan, plan_path)
    occluder_pts = [p for poly in occluders for p in poly]
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

    def add_occluders(ax):
        # Drawn first, and the computed depth order turned off: mplot3d sorts whole collections by
        # their mean depth, so a large fixture below the part would otherwise be drawn over it.
        # The views look from above, where the fixtures of a part (a plate, a conveyor) lie below it.
        if not occluders:
            return
        ax.computed_zorder = False
        ax.add_collection3d(Poly3DCollection(occluders, facecolors=[OCCLUDER_COLOUR], edgecolors=(0.4, 0.35, 0.3, 0.5),
                                             linewidths=0.3, zorder=0))

    # Left: the part, each facet in the colour of its camera.
    ax = fig.add_subplot(1, 2, 1, projection="3d")
    add_occluders(ax)
    ax.add_collection3d(Poly3DCollection(polys, facecolors=face_colours, edgecolors=(0, 0, 0, 0.12), linewidths=0.2,
                                         zorder=1))
    fit(ax, verts + occluder_pts)
    ax.view_init(elev=35, azim=-60)
    ax.set_title("each facet in the colour of the camera box certifying it (grey: none)", fontsize=9)

    # Right: the camera boxes (drawn 20x larger to be seen) and their sight lines to what they certify.
    ax = fig.add_subplot(1, 2, 2, projection="3d")
    add_occluders(ax)
    ax.add_collection3d(Poly3DCollection(polys, facecolors=face_colours, linewidths=0, zorder=1))
    pts = list(verts) + occluder_pts
    for k, cam in enumerate(plan["cameras"]):
        c = colour(k)
        centre = [(lo + hi) / 2 for lo, hi in cam["position"]]
        grown = [[m - 20 * (hi - lo) / 2, m + 20 * (hi - lo) / 2] for m, (lo, hi) in zip(centre, cam["position"])]
        ax.add_collection3d(Poly3DCollection(box_faces(grown), facecolors=(c[0], c[1], c[2], 0.5),
                                             edgecolors=(c[0], c[1], c[2], 1.0), linewidths=0.6, zorder=2))
        fs = cam["facets"]
        target = [sum(verts[v][d] for f in fs for v in faces[f]) / (3 * len(fs)) for d in range(3)]
        ax.plot(*zip(centre, target), color=c, lw=0.8, zorder=3)
        pts.append(tuple(centre))
    fit(ax, pts)
    ax.view_init(elev=20, azim=-60)
    ax.set_title("camera position boxes (20x enlarged), lines to the centre of what each certifies", fontsize=9)
    cov = plan["coverage"]
    scene = []
    if occluder_names:
        scene.append("occluders (pale brown): " + ", ".join(occluder_names))
    for key, label in (("keep_in", "keep-in"), ("keep_out", "keep-out")):
        if plan.get(key):
            scene.append(label + " " + " ".join(region_text(r) for r in plan[key]))
    fig.suptitle(f"{len(plan['cameras'])} camera boxes certify {100 * cov['certified_area'] / cov['coverable_area']:.1f} % "
                 f"of the coverable area ({100 * cov['certified_area'] / cov['total_area']:.1f} % of the part); "
                 f"tolerance per box: {plan['settings'].get('tolerance')}" + ("\n" + "; ".join(scene) if scene else ""))
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
