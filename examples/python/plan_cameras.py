"""Load a part, certify camera poses for every facet, plan cameras and plot the coverage
(docs/python.md). Runs after `pip install` alone: without --mesh and --camera it takes the sample
part and the example camera that come with the module.

    python3 examples/python/plan_cameras.py coverage.png [--mesh PART] [--camera CAMERA.json]
                                            [--scale S] [--threads N] [--plan PLAN.json]
"""
import argparse
import sys

import matplotlib
import numpy as np

import certipose

matplotlib.use("Agg")  # draw to a file, with or without a display
import matplotlib.pyplot as plt  # noqa: E402
from mpl_toolkits.mplot3d.art3d import Poly3DCollection  # noqa: E402


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("picture", help="the coverage plot to write (PNG)")
    ap.add_argument("--mesh", help="the part: a mesh or STEP file (default: certipose.sample_part())")
    ap.add_argument("--camera", help="the camera JSON (default: certipose.example_camera())")
    ap.add_argument("--plan", help="also write the plan here (PLAN.json)")
    ap.add_argument("--scale", type=float, default=1.0)
    ap.add_argument("--threads", type=int, default=0)
    args = ap.parse_args()

    # The part and the camera: a mesh file (or certipose.Mesh(V, F) from numpy arrays, a
    # trimesh.Trimesh, an Open3D mesh) and the camera JSON (or a dict of the same shape).
    mesh = args.mesh or certipose.sample_part()
    camera = args.camera or certipose.example_camera()
    solver = certipose.Solver(mesh, camera, scale=args.scale)

    # Every facet, on every core; the progress callback runs on this thread.
    def progress(p):
        if sys.stderr.isatty():
            print(f"\r{p.facets_done} / {p.facets_total} facets, ETA {p.seconds_left:.0f} s", end="", file=sys.stderr)

    part = solver.solve_part(position_eps=0.1, orientation_eps=0.38, threads=args.threads, progress=progress)
    if sys.stderr.isatty():
        print(file=sys.stderr)
    valid = part.valid
    print(f"{len(part.records)} facets: {valid.sum()} VALID boxes, "
          f"{np.unique(part.facets[valid]).size} facets certified from somewhere")

    # The fewest cameras certifying 95 % of what can be certified, each a box of +-5 mm, +-0.02 rad.
    plan = solver.plan(part, coverage=0.95)
    c = plan.coverage
    print(f"{len(plan.cameras)} cameras certify {100 * c['certified_area'] / c['coverable_area']:.1f} % "
          f"of the coverable area; at least {c['lower_bound_cameras']} are needed ({c['lower_bound_method']} bound)")
    if args.plan:
        plan.save(args.plan)

    # Each facet in the colour of the first camera that certifies it (grey: none), and the
    # certified area after 1, 2, ... cameras.
    V, F = solver.mesh.vertices, solver.mesh.faces
    first = np.full(solver.mesh.num_faces, -1)
    for k, camera in reversed(list(enumerate(plan.cameras))):
        first[camera["facets"]] = k
    colours = plt.cm.tab10(first % 10)
    colours[first < 0] = (0.8, 0.8, 0.8, 1.0)
    fig = plt.figure(figsize=(11, 5))
    ax = fig.add_subplot(1, 2, 1, projection="3d")
    ax.add_collection3d(Poly3DCollection(V[F], facecolors=colours, edgecolor="none"))
    centres = np.array([camera["nominal"][:3] for camera in plan.cameras])
    ax.scatter(*centres.T, c=plt.cm.tab10(np.arange(len(centres)) % 10), marker="^", s=60, depthshade=False)
    everything = np.vstack([V, centres])
    middle, half = everything.mean(axis=0), np.ptp(everything, axis=0).max() / 2
    ax.set(xlim=(middle[0] - half, middle[0] + half), ylim=(middle[1] - half, middle[1] + half),
           zlim=(middle[2] - half, middle[2] + half), xlabel="x (m)", ylabel="y (m)", zlabel="z (m)")
    ax.set_title("facets by the camera that certifies them")
    curve = np.array(c["curve"]) / c["coverable_area"]
    ax2 = fig.add_subplot(1, 2, 2)
    ax2.plot(np.arange(1, len(curve) + 1), 100 * curve, "o-")
    ax2.set(xlabel="cameras", ylabel="% of the coverable area certified", ylim=(0, 100))
    ax2.grid(True)
    fig.tight_layout()
    fig.savefig(args.picture, dpi=90)
    print(f"wrote {args.picture}" + (f" and {args.plan}" if args.plan else ""))


if __name__ == "__main__":
    main()
