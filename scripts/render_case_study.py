#!/usr/bin/env python3
"""Renders a certipose result (the result JSON of docs/io.md) with its part mesh to a PNG: the part in grey,
the facet of interest in red, VALID position boxes in green and BOUNDARY ones as faint yellow
outlines; the title gives the counts, the paving, the certified volume and the solve time, all
from the result JSON.

Needs Debian's python3-matplotlib (a documentation tool only; the library does not use it):
    /usr/bin/python3 scripts/render_case_study.py PART.off RESULT.json OUT.png
"""
import json
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from mpl_toolkits.mplot3d.art3d import Line3DCollection, Poly3DCollection  # noqa: E402


def read_off(path):
    with open(path) as f:
        words = [w for line in f for w in line.split("#", 1)[0].split()]
    assert words[0] == "OFF", "not an OFF file"
    nv, nf = int(words[1]), int(words[2])
    it = 4
    verts = []
    for _ in range(nv):
        verts.append(tuple(float(w) for w in words[it:it + 3]))
        it += 3
    faces = []
    for _ in range(nf):
        n = int(words[it])
        faces.append(tuple(int(w) for w in words[it + 1:it + 1 + n]))
        it += 1 + n
    return verts, faces


def box_faces(b):
    (x0, x1), (y0, y1), (z0, z1) = b
    c = [(x, y, z) for z in (z0, z1) for y in (y0, y1) for x in (x0, x1)]
    quads = [(0, 1, 3, 2), (4, 5, 7, 6), (0, 1, 5, 4), (2, 3, 7, 6), (0, 2, 6, 4), (1, 3, 7, 5)]
    return [[c[i] for i in q] for q in quads]


def box_edges(b):
    (x0, x1), (y0, y1), (z0, z1) = b
    c = [(x, y, z) for z in (z0, z1) for y in (y0, y1) for x in (x0, x1)]
    pairs = [(0, 1), (1, 3), (3, 2), (2, 0), (4, 5), (5, 7), (7, 6), (6, 4), (0, 4), (1, 5), (2, 6), (3, 7)]
    return [(c[i], c[j]) for i, j in pairs]


def main(off_path, result_path, png_path):
    verts, faces = read_off(off_path)
    result = json.load(open(result_path))
    fi = result["facet"]["index"]
    fig = plt.figure(figsize=(11, 8), dpi=110)
    ax = fig.add_subplot(111, projection="3d")
    part = [[verts[i] for i in f] for k, f in enumerate(faces) if k != fi]
    ax.add_collection3d(Poly3DCollection(part, facecolor=(0.7, 0.7, 0.72), edgecolor=(0.45, 0.45, 0.5),
                                         linewidths=0.1, alpha=1.0))
    ax.add_collection3d(Poly3DCollection([result["facet"]["vertices"]], facecolor="red", edgecolor="darkred"))
    valid = [b for b in result["boxes"] if b["class"] == "valid"]
    boundary = [b for b in result["boxes"] if b["class"] == "boundary"]
    quads = [q for b in valid for q in box_faces(b["position"])]
    ax.add_collection3d(Poly3DCollection(quads, facecolor=(0.1, 0.75, 0.2, 0.25), edgecolor=(0.0, 0.45, 0.1, 0.6),
                                         linewidths=0.4))
    edges = [e for b in boundary for e in box_edges(b["position"])]
    ax.add_collection3d(Line3DCollection(edges, colors=[(0.85, 0.7, 0.0, 0.08)], linewidths=0.3))
    pts = [c for b in result["boxes"] for c in ([p[0] for p in b["position"]], [p[1] for p in b["position"]])]
    lo = [min(min(p[k] for p in pts), min(v[k] for v in verts)) for k in range(3)]
    hi = [max(max(p[k] for p in pts), max(v[k] for v in verts)) for k in range(3)]
    span = max(h - l for l, h in zip(lo, hi))
    mid = [(l + h) / 2 for l, h in zip(lo, hi)]
    for setter, m in zip((ax.set_xlim, ax.set_ylim, ax.set_zlim), mid):
        setter(m - span / 2, m + span / 2)
    ax.set_box_aspect((1, 1, 1))
    ax.view_init(elev=24, azim=-58)
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.set_zlabel("z (m)")
    s = result["stats"]
    settings = result.get("settings", {})
    steps = [settings.get(k) for k in ("inner_contraction", "occlusion_cuts", "leaf_corner_boxes")]
    if None in steps:
        paving = None  # an older file that does not say
    elif not any(steps):
        paving = "the paper's paving"
    elif all(steps):
        paving = "default paving (corner depth %d)" % settings.get("corner_depth", 1)
    else:
        paving = "paving: " + " + ".join(n for n, on in zip(("inner contraction", "occlusion cuts", "corner boxes"), steps)
                                         if on)
    volume = s.get("valid_volume")
    details = [paving, None if volume is None else "%.3f m\N{SUPERSCRIPT THREE} of positions certified" % volume,
               "%.3f s" % s["seconds"]]
    ax.set_title("certipose case study: facet %d, %d VALID (green) and %d BOUNDARY (yellow) pose boxes\n%s"
                 % (fi, s["valid"], s["boundary"], ", ".join(d for d in details if d)))
    fig.tight_layout()
    fig.savefig(png_path)


if __name__ == "__main__":
    if len(sys.argv) != 4:
        sys.exit("usage: render_case_study.py PART.off RESULT.json OUT.png")
    main(*sys.argv[1:])
