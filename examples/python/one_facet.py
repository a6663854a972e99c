"""One facet of a part given as numpy arrays, with a camera given as a dict: the certified pose
boxes, a check of one pose, and an error (docs/python.md).

    python3 examples/python/one_facet.py
"""
import numpy as np

import certipose

# A 20 cm cube standing on the origin: vertices (V) and counter-clockwise faces (F), as
# trimesh.Trimesh.vertices / .faces or Open3D's vertices / triangles give them.
V = 0.2 * np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [0, 0, 1], [1, 0, 1], [1, 1, 1], [0, 1, 1]], float)
F = np.array([[0, 2, 1], [0, 3, 2], [4, 5, 6], [4, 6, 7], [0, 1, 5], [0, 5, 4],
              [1, 2, 6], [1, 6, 5], [2, 3, 7], [2, 7, 6], [3, 0, 4], [3, 4, 7]])

# The camera JSON's shape (docs/conventions.md): a 12 mm lens at f/8 focused at 0.6 m.
camera = {"camera": {"model": "thin_lens", "focal_length": 0.012, "f_stop": 8, "focus_distance": 0.6,
                     "max_blur_circle": 6.9e-6, "pixel_pitch": 3.45e-6, "width_px": 2448, "height_px": 2048},
          "task": {"min_view_angle": 0.35}}

r = certipose.solve_facet(certipose.Mesh(V, F), camera, 2, position_eps=0.1, orientation_eps=0.38)
print(r)                                  # <certipose.FacetResult facet 2: ... valid, ... boundary boxes>
valid = r.classes == "valid"
positions = r.positions[valid]            # (N, 3, 2): [x, y, z] x [lower, upper], metres
orientations = r.orientations[valid]      # (N, 3, 2): [phi, gamma, beta] x [lower, upper], radians
print(f"{valid.sum()} VALID boxes in {r.stats['seconds']:.3f} s; widest x interval "
      f"{np.max(positions[:, 0, 1] - positions[:, 0, 0]):.3f} m")

# Any pose inside a VALID box inspects the facet: take a box's centre and verify it.
solver = certipose.Solver(certipose.Mesh(V, F), camera)
centre = r.bounds[valid][0].mean(axis=1)  # [x, y, z, phi, gamma, beta]
report = solver.verify(centre[None, :])["poses"][0]
assert 2 in report["facets"]
print(f"the centre of the first VALID box certifies facets {list(report['facets'])}; it may move by "
      f"+-{1000 * min(report['tolerance']['half_widths'][:3]):.1f} mm and still certify them all")

# Bad input is a Python exception naming the value.
try:
    certipose.solve_facet(certipose.Mesh(V, F), camera, 12)
except IndexError as e:                   # certipose.OutOfRange, also a ValueError
    print("error:", e)
