#!/usr/bin/env python3
"""Renders a whole-part run (certipose-part's folder) on its mesh to a PNG: each facet coloured by
the certified position volume of its VALID boxes (sum over boxes, litres, log scale); facets with
no VALID box in grey, skipped ones in dark grey.

Needs Debian's python3-matplotlib (a documentation tool only; the library does not use it):
    /usr/bin/python3 scripts/render_part.py PART.off RUN_DIR OUT.png
"""
import json
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib import cm, colors  # noqa: E402
from mpl_toolkits.mplot3d.art3d import Poly3DCollection  # noqa: E402

import box_store  # noqa: E402  (boxes.cpbx with numpy, beside this script)
from render_case_study import read_off  # noqa: E402  (the OFF reader of the other docs picture)


def valid_volumes(run_dir, faces):
    """Litres of certified camera positions per facet: the sum over its VALID boxes, read from
    the store the run wrote (summary.json settings.box_store; boxes.cpbx by default)."""
    volume = [0.0] * faces
    if os.path.exists(os.path.join(run_dir, "boxes.cpbx")):
        boxes, _ = box_store.read(os.path.join(run_dir, "boxes.cpbx"))
        valid = boxes[boxes["cls"] == box_store.VALID]
        widths = valid["position"][:, :, 1] - valid["position"][:, :, 0]
        for facet, v in zip(valid["facet"], widths.prod(axis=1) * 1e3):
            volume[facet] += float(v)
        return volume
    with open(os.path.join(run_dir, "boxes.jsonl")) as f:
        for line in f:
            b = json.loads(line)
            if b["class"] != "valid":
                continue
            (x0, x1), (y0, y1), (z0, z1) = b["position"]
            volume[b["facet"]] += (x1 - x0) * (y1 - y0) * (z1 - z0) * 1e3
    return volume


def main(off_path, run_dir, out_path):
    verts, faces = read_off(off_path)
    with open(f"{run_dir}/summary.json") as f:
        summary = json.load(f)
    scale = summary["mesh"].get("scale", 1.0)
    verts = [tuple(scale * c for c in v) for v in verts]
    volume = valid_volumes(run_dir, len(faces))
    skipped = {r["index"] for r in summary["facets"] if r["termination"] == "skipped"}
    solved = {r["index"] for r in summary["facets"]}
    positive = [v for v in volume if v > 0]
    norm = colors.LogNorm(vmin=max(min(positive), max(positive) * 1e-4), vmax=max(positive))
    cmap = cm.viridis
    face_colours = []
    for i in range(len(faces)):
        if i in skipped:
            face_colours.append((0.25, 0.25, 0.25, 1.0))
        elif i not in solved or volume[i] == 0:
            face_colours.append((0.75, 0.75, 0.75, 1.0))
        else:
            face_colours.append(cmap(norm(volume[i])))
    fig = plt.figure(figsize=(9, 6.5), dpi=110)
    ax = fig.add_subplot(projection="3d")
    ax.add_collection3d(Poly3DCollection([[verts[k] for k in f] for f in faces], facecolors=face_colours,
                                         edgecolors=(0, 0, 0, 0.15), linewidths=0.2))
    xs, ys, zs = zip(*verts)
    span = max(max(xs) - min(xs), max(ys) - min(ys), max(zs) - min(zs))
    mid = [(max(c) + min(c)) / 2 for c in (xs, ys, zs)]
    for setter, m in zip((ax.set_xlim, ax.set_ylim, ax.set_zlim), mid):
        setter(m - span / 2, m + span / 2)
    ax.view_init(elev=35, azim=-60)
    ax.set_axis_off()
    sm = cm.ScalarMappable(norm=norm, cmap=cmap)
    sm.set_array([])
    fig.colorbar(sm, ax=ax, shrink=0.6, label="certified position volume of the facet's VALID boxes (litres)")
    t = summary["totals"]
    ax.set_title(f"{t['facets']} facets: {t['valid']} VALID boxes, {t['skipped']} skipped "
                 f"({sum(1 for v in volume if v > 0)} facets with a certified pose)")
    fig.savefig(out_path, bbox_inches="tight")


if __name__ == "__main__":
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    main(*sys.argv[1:])
