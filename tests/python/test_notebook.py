"""certipose in a notebook: results and plans display themselves (_repr_html_, the plan's with
the 3-D viewer inline, rendered in Chromium), and boxes and cameras become record arrays and
Open3D geometry that hold the same numbers as the arrays."""
import os
import pathlib
import shutil
import subprocess

import numpy as np
import pytest

import certipose

ROOT = pathlib.Path(__file__).resolve().parents[2]
EPS = dict(position_eps=0.1, orientation_eps=0.38)
FACETS = list(range(0, 2300, 5))


@pytest.fixture(scope="module")
def solver():
    return certipose.Solver(certipose.sample_part(), certipose.example_camera())


@pytest.fixture(scope="module")
def part(solver):
    return solver.solve_part(facets=FACETS, threads=2, boundary=True, keep_largest=3, **EPS)


@pytest.fixture(scope="module")
def plan(solver, part):
    return solver.plan(part, coverage=0.9, threads=2)


def test_results_display_as_tables(solver, part):
    one = solver.solve_facet(900, max_boxes=3000, **EPS)
    html = one._repr_html_()
    assert "certipose.FacetResult</b> facet 900" in html and f"{int(one.valid.sum())} valid" in html
    assert html.count("<tr>") == 1 + 1 + len(set(one.reasons[~one.valid])) + 1 + 10 + 1  # counts, 10 boxes, "… more"
    assert f"… {len(one) - 10} more" in html
    html = part._repr_html_()
    assert f"{len(part.records)} facets solved" in html
    assert f"{len(np.unique(part.facets[part.valid]))} with a VALID box" in html


def test_records_hold_the_arrays(part, plan):
    rec = part.to_records()
    assert len(rec) == len(part) and list(rec.dtype.names[:3]) == ["facet", "cls", "reason"]
    assert np.array_equal(rec["facet"], part.facets) and np.array_equal(rec["cls"], part.classes)
    for i, n in enumerate(["x", "y", "z", "phi", "gamma", "beta"]):
        assert np.array_equal(rec[f"{n}_lo"], part.bounds[:, i, 0]) and np.array_equal(rec[f"{n}_hi"], part.bounds[:, i, 1])
    cams = plan.to_records()
    assert len(cams) == len(plan.cameras) > 0
    for k, c in enumerate(plan.cameras):
        assert cams["camera"][k] == k and cams["facets"][k] == len(c["facets"])
        assert [cams[n][k] for n in ("x", "y", "z", "phi", "gamma", "beta")] == c["nominal"]
        assert (cams["x_lo"][k], cams["x_hi"][k]) == tuple(c["position"][0])
        assert (cams["aim_x"][k], cams["aim_y"][k], cams["aim_z"][k]) == tuple(c["aim"])


def test_box_lines_are_the_boxes_edges(part):
    points, lines = part.box_lines("valid")
    boxes = part.positions[part.valid]
    assert points.shape == (8 * len(boxes), 3) and lines.shape == (12 * len(boxes), 2)
    corners = points.reshape(-1, 8, 3)
    assert np.array_equal(corners.min(axis=1), boxes[:, :, 0]) and np.array_equal(corners.max(axis=1), boxes[:, :, 1])
    edge = points[lines[:, 1]] - points[lines[:, 0]]
    assert ((edge != 0).sum(axis=1) == 1).all()  # each edge runs along one axis
    assert part.box_lines(np.zeros(len(part), bool))[0].shape == (0, 3)
    with pytest.raises(certipose.InvalidArgument, match="which: expected"):
        part.box_lines("largest")


def test_open3d_geometry(part, plan, solver):
    o3d = pytest.importorskip("open3d")  # Debian: python3-open3d (scripts/install-deps.sh)
    ls = part.to_open3d()
    assert isinstance(ls, o3d.geometry.LineSet)
    points, lines = part.box_lines()
    assert np.array_equal(np.asarray(ls.points), points) and np.array_equal(np.asarray(ls.lines), lines)
    cams = plan.to_open3d()
    assert len(cams.points) == 8 * len(plan.cameras) + 2 * len(plan.cameras)
    aims = np.asarray(cams.points)[8 * len(plan.cameras):].reshape(-1, 2, 3)
    assert np.array_equal(aims[:, 1], [c["aim"] for c in plan.cameras])
    # Open3D meshes: the legacy one in float64 is the part itself; a tensor one is accepted, float32
    # with the warning, float64 without.
    V, F = np.array(solver.mesh.vertices), np.array(solver.mesh.faces, dtype=np.int64)  # writeable copies
    legacy = o3d.geometry.TriangleMesh(o3d.utility.Vector3dVector(V), o3d.utility.Vector3iVector(F.astype(np.int32)))
    assert certipose.Solver(legacy, certipose.example_camera()).mesh.digest == solver.mesh.digest
    t64 = o3d.t.geometry.TriangleMesh()
    t64.vertex.positions = o3d.core.Tensor(V)
    t64.triangle.indices = o3d.core.Tensor(F)
    assert certipose.Solver(t64, certipose.example_camera()).mesh.digest == solver.mesh.digest
    t32 = o3d.t.geometry.TriangleMesh.from_legacy(legacy)
    with pytest.warns(UserWarning, match="float32"):
        assert certipose.Solver(t32, certipose.example_camera()).mesh.num_faces == solver.mesh.num_faces


def test_a_plan_displays_with_the_viewer_inline(plan, tmp_path):
    html = plan._repr_html_()
    assert f"<b>certipose.Plan</b> {len(plan.cameras)} cameras" in html
    if not certipose._core.has_viewer:
        assert "The 3-D view needs the part and a build with the web viewer" in html
        pytest.skip("this build has no web viewer (no Node.js when it was built)")
    assert 'iframe class="certipose-viewer"' in html and "<script" not in html.split("srcdoc=")[0]
    # What Jupyter does with it: the HTML in an output area of the page, rendered by Chromium.
    cell = tmp_path / "cell.html"
    cell.write_text('<!doctype html><html><head><meta charset="utf-8"><title>notebook cell</title></head>'
                    '<body style="font-family:sans-serif;margin:16px"><div class="input_area"><pre>In [3]: plan</pre>'
                    f'</div><div class="output_area"><div class="output_html">{html}</div></div></body></html>',
                    encoding="utf-8")
    node = os.environ.get("CERTIPOSE_NODE") or shutil.which("node")
    assert node and os.path.exists(node), "the build had the web viewer, so Node.js must be there to test it"
    shot = pathlib.Path(os.environ.get("CERTIPOSE_NOTEBOOK_SCREENSHOT", tmp_path / "notebook.png"))
    out = subprocess.run([node, str(ROOT / "tests" / "web" / "notebook_test.mjs"), str(cell), str(len(plan.cameras)),
                          str(shot)], capture_output=True, text=True, timeout=300)
    assert out.returncode == 0, out.stdout + out.stderr
    assert shot.stat().st_size > 10000


def test_a_plan_read_from_a_file_finds_its_part(plan, tmp_path):
    """A plan made from arrays records "<arrays>": read back, it shows the table and says why
    there is no view; the viewer needs the part at hand."""
    path = tmp_path / "PLAN.json"
    plan.save(path)
    again = certipose.read_plan(path)
    html = again._repr_html_()
    assert f"{len(plan.cameras)} cameras" in html and "iframe" not in html and "needs the part" in html
