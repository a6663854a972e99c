"""The Python module certipose (docs/python.md): the same boxes as the programs, bit for bit;
VALID boxes checked by sampling poses in numpy (independently of the C++ checker); progress,
cancellation and KeyboardInterrupt; the GIL released; bad input raising typed errors."""
import json
import os
import pathlib
import signal
import subprocess
import sys
import threading
import time

import numpy as np
import pytest

import certipose

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "scripts"))
import box_store  # noqa: E402

SOLVE = os.environ.get("CERTIPOSE_SOLVE", "certipose-solve")
PART = os.environ.get("CERTIPOSE_PART", "certipose-part")
SHARED = pathlib.Path(os.environ.get("CERTIPOSE_SHARED", ROOT.parent / "shared"))
MESH = str(SHARED / "meshes" / "angle_block.off")
CAMERA = str(SHARED / "cases" / "camera.json")
FACETS = list(range(0, 704, 7))  # a sample of the part: open faces, hidden ones, skipped ones
EPS = dict(position_eps=0.1, orientation_eps=0.38)


@pytest.fixture(scope="module")
def solver():
    return certipose.Solver(MESH, CAMERA)


@pytest.fixture(scope="module")
def part(solver):
    return solver.solve_part(facets=FACETS, threads=2, boundary=True, **EPS)


@pytest.fixture(scope="module")
def program_part(tmp_path_factory):
    out = tmp_path_factory.mktemp("part") / "run"
    subprocess.run([PART, "--mesh", MESH, "--camera", CAMERA, "--position-eps", "0.1", "--orientation-eps", "0.38",
                    "--facets", ",".join(map(str, FACETS)), "--boundary", "--threads", "2", "--box-store", "binary",
                    "--out", str(out), "-q"], check=True)
    return out


# ---- the same boxes as the programs --------------------------------------------------------

def test_solve_facet_is_certipose_solve_bit_for_bit(tmp_path):
    out = tmp_path / "r.json"
    subprocess.run([SOLVE, "--mesh", MESH, "--facet", "21", "--camera", CAMERA, "--position-eps", "0.1",
                    "--orientation-eps", "0.38", "--out", str(out), "-q"], check=True)
    doc = json.loads(out.read_text())
    r = certipose.solve_facet(MESH, json.loads(pathlib.Path(CAMERA).read_text()), 21, **EPS)
    assert len(r) == len(doc["boxes"]) > 0
    want = np.array([b["position"] + b["orientation"] for b in doc["boxes"]])
    assert want.shape == r.bounds.shape == (len(r), 6, 2)
    assert np.array_equal(want.view(np.uint64), np.ascontiguousarray(r.bounds).view(np.uint64))  # bit for bit
    assert list(r.classes) == [b["class"] for b in doc["boxes"]]
    assert list(r.reasons) == [b.get("undecided", "") for b in doc["boxes"]]
    assert r.stats["valid"] == doc["stats"]["valid"] and r.stats["boundary"] == doc["stats"]["boundary"]
    assert r.positions.shape == r.orientations.shape == (len(r), 3, 2)
    assert np.shares_memory(r.positions, r.bounds)  # views, not copies


def test_solve_part_is_certipose_part_bit_for_bit(part, program_part):
    boxes, checked = box_store.read(program_part / "boxes.cpbx")
    summary = json.loads((program_part / "summary.json").read_text())
    assert checked
    assert len(part) == len(boxes) > 1000
    assert np.array_equal(part.facets, boxes["facet"].astype(np.int64))
    mine = np.ascontiguousarray(part.bounds)
    theirs = np.concatenate([boxes["position"], boxes["orientation"]], axis=1)
    assert np.array_equal(mine.view(np.uint64), np.ascontiguousarray(theirs).view(np.uint64))
    assert np.array_equal(part.class_codes, boxes["cls"])
    assert np.array_equal(np.where(part.reason_codes < 0, box_store.NO_REASON, part.reason_codes), boxes["reason"])
    assert [(r["index"], r["valid"], r["boundary"], r["termination"]) for r in part.records] == \
        [(r["index"], r["valid"], r["boundary"], r["termination"]) for r in summary["facets"]]


def test_mesh_from_arrays_is_the_mesh_read(solver):
    m = certipose.Mesh(np.array(solver.mesh.vertices), np.array(solver.mesh.faces, dtype=np.int64))
    assert m.digest == solver.mesh.digest
    assert not solver.mesh.vertices.flags.writeable  # a view of the library's mesh, read-only

    class Trimeshish:  # what trimesh.Trimesh offers
        vertices = np.array(solver.mesh.vertices)
        faces = np.array(solver.mesh.faces)
    a = certipose.solve_facet(Trimeshish(), CAMERA, 21, **EPS)
    b = solver.solve_facet(21, **EPS)
    assert np.array_equal(a.bounds, b.bounds) and len(a) > 0


def test_strict_inputs_get_our_errors(solver, tmp_path):
    V, F = np.array(solver.mesh.vertices), np.array(solver.mesh.faces, dtype=np.int64)
    # float face indices are refused, not truncated
    with pytest.raises(certipose.InvalidArgument, match="faces must be integer vertex indices, got an array of dtype float64"):
        certipose.Mesh(V, F + 0.7)
    with pytest.raises(certipose.InvalidArgument, match="vertices must be numbers"):
        certipose.Mesh(np.array([["a", "b", "c"]]), F[:0])
    assert certipose.Mesh(V.tolist(), F.tolist()).digest == solver.mesh.digest  # plain lists are fine
    # float32 vertices: a warning saying what it costs
    with pytest.warns(UserWarning, match="float32"):
        m32 = certipose.Mesh(V.astype(np.float32), F)
    assert m32.num_faces == solver.mesh.num_faces
    # os.PathLike wherever a path is taken
    assert certipose.Mesh.read(pathlib.Path(MESH)).digest == certipose.Mesh.read(MESH).digest
    with pytest.raises(certipose.InvalidArgument, match="path: expected a str or os.PathLike, got int"):
        certipose.Mesh.read(3)
    # numpy scalars and arrays in a camera dict
    spec = json.loads(pathlib.Path(CAMERA).read_text())
    numpyish = json.loads(json.dumps(spec), parse_float=np.float64, parse_int=np.int64)
    assert certipose.camera(numpyish).to_dict() == certipose.camera(spec).to_dict()
    with pytest.raises(certipose.InvalidArgument, match="camera: a camera dict holds object"):
        certipose.camera({**spec, "task": object()})
    # regions: one string, a tuple, or a list of either
    one = certipose.Solver(MESH, CAMERA, keep_out="box:-10,-10,-10,10,10,0.3")
    tup = certipose.Solver(MESH, CAMERA, keep_out=("box", -10, -10, -10, 10, 10, 0.3))
    lst = certipose.Solver(MESH, CAMERA, keep_out=["box:-10,-10,-10,10,10,0.3"])
    a, b, c = (s.solve_facet(21, **EPS) for s in (one, tup, lst))
    assert np.array_equal(a.bounds, b.bounds) and np.array_equal(a.bounds, c.bounds)
    full = solver.solve_facet(21, **EPS)
    assert a.bounds.shape != full.bounds.shape or not np.array_equal(a.bounds, full.bounds)  # the region cut
    with pytest.raises(certipose.InvalidArgument, match=r"keep_out\[0\]"):
        certipose.Solver(MESH, CAMERA, keep_out=[3.0])
    # a tuple of region strings is several regions, not one ("box:..." is not a number)
    two = ("box:-10,-10,-10,10,10,0.3", "sphere:0,0,0.6,0.01")
    d = certipose.Solver(MESH, CAMERA, keep_out=two).solve_facet(21, **EPS)
    e = certipose.Solver(MESH, CAMERA, keep_out=list(two)).solve_facet(21, **EPS)
    assert np.array_equal(d.bounds, e.bounds)


def test_the_examples_part_and_camera_come_with_the_package():
    assert certipose.sample_part().digest == certipose.Mesh.read(SAMPLE).digest  # the programs' part
    assert certipose.example_camera() == json.loads((ROOT / "examples" / "data" / "camera.json").read_text())
    assert certipose.camera(certipose.example_camera()).model == "thin_lens"
    formats = certipose.available_formats()
    assert {"csv", "moveit", "urdf", "ply", "glb", "sheet"} <= set(formats)
    assert ("html" in formats) == certipose._core.has_viewer


def test_objects_say_what_they_are(solver):
    assert certipose.__version__ == "0.1.0"
    assert repr(solver.mesh).startswith(f"<certipose.Mesh {solver.mesh.num_faces} facets")
    assert "in focus from" in repr(solver.camera)
    assert repr(solver).startswith("<certipose.Solver ")
    assert "integer vertex indices" in certipose.Mesh.__doc__
    assert certipose.Camera.__doc__


def _members(cls):
    for name, value in vars(cls).items():
        if not name.startswith("_"):
            yield name, value.__func__ if isinstance(value, staticmethod) else value


def test_every_public_name_explains_itself():
    """help() shows a docstring for every public function, class, method and property (pybind11's
    bare signature line does not count), and the module's functions show their options by name."""
    import inspect
    bare = []
    for name in certipose.__all__:
        obj = getattr(certipose, name)
        if isinstance(obj, (str, tuple)):
            continue
        doc = inspect.getdoc(obj) or ""
        if not doc.strip():
            bare.append(name)
        if inspect.isclass(obj) and not issubclass(obj, BaseException):
            for member, value in _members(obj):
                if not callable(value) and not isinstance(value, property):
                    continue
                doc = (value.__doc__ or "").strip()
                if not doc or (doc.startswith(member + "(") and "\n" not in doc):
                    bare.append(f"{name}.{member}")
    assert not bare, bare
    # solve_facet(mesh, camera_spec, facet, **options) shows the scene's and the solve's keywords
    for function, some in [(certipose.solve_facet, {"occlusion", "keep_out", "position_eps", "grow"}),
                           (certipose.solve_part, {"occluders", "threads", "progress"}),
                           (certipose.plan, {"scale", "cameras", "tolerance"}),
                           (certipose.verify, {"mesh_semantics", "tolerance"}),
                           (certipose.export, {"mesh", "link_prefix", "snippet"})]:
        names = set(inspect.signature(function).parameters)
        assert some <= names and "options" not in names, (function.__name__, names)
    import pydoc
    text = pydoc.render_doc(certipose.solve_facet, renderer=pydoc.plaintext)
    assert "position_eps: 'float' = 0.1" in text and "keep_out:" in text, text


def test_the_stub_spells_out_what_the_module_takes():
    """Each function's parameters in __init__.pyi are the module's own, by name and kind."""
    import ast
    import inspect
    stub = ast.parse((pathlib.Path(certipose.__file__).parent / "__init__.pyi").read_text())
    for node in stub.body:
        if isinstance(node, ast.FunctionDef) and node.name in certipose.__all__:
            a = node.args
            stubbed = [x.arg for x in a.posonlyargs + a.args] + [x.arg for x in a.kwonlyargs]
            runtime = [p.name for p in inspect.signature(getattr(certipose, node.name)).parameters.values()]
            assert stubbed == runtime, (node.name, stubbed, runtime)


def test_progress_counts_what_the_result_holds(solver):
    facets = list(range(0, 704, 50))
    for keep in (False, True):
        seen = []
        r = solver.solve_part(facets=facets, threads=1, boundary=keep, progress=lambda p: seen.append(p), **EPS)
        assert seen and all(p.boundary_found >= p.boundary for p in seen)
        held = int((~r.valid).sum())
        if keep:
            assert all(p.boundary == p.boundary_found for p in seen) and seen[-1].boundary <= held
        else:
            assert held == 0 and all(p.boundary == 0 for p in seen)
        assert max(p.boundary_found for p in seen) > 0  # the paving did leave boxes undecided


# ---- soundness: sampled poses of VALID boxes, checked in numpy -------------------------------

def rotation(phi, gamma, beta):
    """R = Rz(phi) Rx(gamma) Rz(beta), for arrays of angles: (..., 3, 3)."""
    def rz(a):
        c, s, z, o = np.cos(a), np.sin(a), np.zeros_like(a), np.ones_like(a)
        return np.stack([np.stack([c, -s, z], -1), np.stack([s, c, z], -1), np.stack([z, z, o], -1)], -2)

    def rx(a):
        c, s, z, o = np.cos(a), np.sin(a), np.zeros_like(a), np.ones_like(a)
        return np.stack([np.stack([o, z, z], -1), np.stack([z, c, -s], -1), np.stack([z, s, c], -1)], -2)
    return rz(phi) @ rx(gamma) @ rz(beta)


def segment_blocked(p, q, tri, skip):
    """For segments p[i] -> q[i] (open at both ends), whether one meets a triangle of `tri`
    (T, 3, 3) other than index `skip` (Moller-Trumbore; a hit must be strictly inside)."""
    keep = np.ones(len(tri), bool)
    keep[skip] = False
    t0, e1, e2 = tri[keep, 0], tri[keep, 1] - tri[keep, 0], tri[keep, 2] - tri[keep, 0]
    d = q - p                                                  # (S, 3)
    h = np.cross(d[:, None, :], e2[None])                      # (S, T, 3)
    a = np.einsum("tk,stk->st", e1, h)
    with np.errstate(divide="ignore", invalid="ignore"):
        f = 1.0 / a
        s = p[:, None, :] - t0[None]
        u = f * np.einsum("stk,stk->st", s, h)
        qv = np.cross(s, e1[None])
        v = f * np.einsum("sk,stk->st", d, qv)
        t = f * np.einsum("tk,stk->st", e2, qv)
    tiny = 1e-9
    hit = (np.abs(a) > 1e-300) & (u > tiny) & (v > tiny) & (u + v < 1 - tiny) & (t > tiny) & (t < 1 - tiny)
    return hit.any(axis=1)


class Checker:
    """The six constraints of docs/conventions.md ("What a VALID box certifies") at sampled poses
    of a box (its 64 corners and 8 random inner poses) and points of a facet (its vertices, its
    centroid and 6 random inner points), in plain numpy."""

    def __init__(self, summary, mesh):
        cam = summary["camera"]
        self.theta = summary["task"]["min_view_angle"]
        self.K, self.W, self.H = np.array(cam["K"]), cam["width_px"], cam["height_px"]
        self.dmin, self.dmax = cam["d_min"], cam["d_max"]
        self.tri = np.asarray(mesh.vertices)[np.asarray(mesh.faces)]
        self.rng = np.random.default_rng(7)
        self.corners = np.array(np.meshgrid(*[[0, 1]] * 6, indexing="ij")).reshape(6, -1).T.astype(float)

    def violations(self, f, b):
        """The constraints (numbers 2-6) some sampled pose of box b (6, 2) breaks for facet f."""
        v = self.tri[f]
        n = np.cross(v[1] - v[0], v[2] - v[0])
        n /= np.linalg.norm(n)
        c = v.mean(axis=0)
        w = self.rng.dirichlet([1, 1, 1], size=6) * (1 - 3e-3) + 1e-3
        pts = np.concatenate([v * (1 - 3e-6) + c * 3e-6, [c], w @ v])  # just inside the facet
        frac = np.concatenate([self.corners, self.rng.random((8, 6))])
        pose = b[:, 0] + frac * (b[:, 1] - b[:, 0])
        p, R = pose[:, :3], rotation(pose[:, 3], pose[:, 4], pose[:, 5])
        broken = set()
        dist = np.linalg.norm(p[:, None, :] - pts[None], axis=2)
        if not ((dist >= self.dmin * (1 - 1e-12)).all() and (dist <= self.dmax * (1 + 1e-12)).all()):
            broken.add(2)
        if not ((p - v[0]) @ n > 0).all():
            broken.add(3)
        pc = p - c
        if not (pc @ n >= np.sin(self.theta) * np.linalg.norm(pc, axis=1) * (1 - 1e-12)).all():
            broken.add(4)
        qc = np.einsum("sji,svj->svi", R, v[None] - p[:, None, :])  # R^T (q - p) for each vertex
        pix = qc @ self.K.T
        with np.errstate(divide="ignore", invalid="ignore"):
            u, vv = pix[..., 0] / pix[..., 2], pix[..., 1] / pix[..., 2]
        slack = 1e-6
        if not ((qc[..., 2] > 0).all() and ((u >= -slack) & (u <= self.W + slack) & (vv >= -slack)
                                            & (vv <= self.H + slack)).all()):
            broken.add(5)
        ps, qs = np.repeat(p, len(pts), axis=0), np.tile(pts, (len(p), 1))
        if segment_blocked(ps, qs, self.tri, f).any():
            broken.add(6)
        return broken, len(p)


def check_sampled_poses(check, run, per_facet):
    """Checks `per_facet` random VALID boxes of each facet of `run`; returns (facets, poses) checked."""
    facets, poses = 0, 0
    for f in np.unique(run.facets[run.valid]):
        sel = np.flatnonzero(run.valid & (run.facets == f))
        for i in check.rng.choice(sel, size=min(len(sel), per_facet), replace=False):
            broken, k = check.violations(f, run.bounds[i])
            assert not broken, (f, i, broken)
            poses += k
        facets += 1
    return facets, poses


def test_valid_boxes_hold_at_sampled_poses(part, program_part):
    check = Checker(json.loads((program_part / "summary.json").read_text()), part_solver_mesh())
    facets, poses = check_sampled_poses(check, part, 8)
    # the sample holds facets occlusion refused: the ray casting is not idle
    assert any(r["valid"] == 0 and r["boundary_reasons"].get("occlusion", 0) > 0 for r in part.records)
    assert facets >= 30 and poses > 20000


@pytest.mark.parametrize("mode", [
    dict(max_boxes_per_facet=300),                        # every facet stopped by its box budget
    dict(paper_paving=True),                              # the paper's paving
    dict(refine=0.02, grow=True, keep_largest=50),        # refinement (budget-stopped) with growth, kept largest
])
def test_valid_boxes_hold_in_every_mode(solver, program_part, mode):
    run = solver.solve_part(facets=FACETS[::2], threads=2, **EPS, **mode)
    check = Checker(json.loads((program_part / "summary.json").read_text()), part_solver_mesh())
    facets, poses = check_sampled_poses(check, run, 3)
    assert facets >= 15 and poses > 3000
    if "max_boxes_per_facet" in mode:
        assert any(r["termination"] == "box_budget" for r in run.records)


def test_reused_facets_say_where_from_and_hold():
    # Bottom facets of the sample part, one shape (docs/part.md#reuse-between-translates): the
    # first is paved, the others take its boxes, each proven again; reuse=False paves each alone.
    sample = certipose.Solver(SAMPLE, str(ROOT / "examples" / "data" / "camera.json"))
    facets = [2, 6, 10, 14]
    run = sample.solve_part(facets=facets, threads=2, **EPS)
    alone = sample.solve_part(facets=facets, threads=2, reuse=False, **EPS)
    assert [r["reused_from"] for r in run.records] == [None, 2, 2, 2]
    assert [r["reused_from"] for r in alone.records] == [None] * 4
    assert run.summary["reused"] == 3 and alone.summary["reused"] == 0
    assert all(r["valid"] > 0 for r in run.records)
    check = Checker(run.summary["run"], sample.mesh)
    checked, poses = check_sampled_poses(check, run, 40)
    assert checked == 4 and poses > 4 * 40 * 64


def test_the_sampling_check_catches_wrong_boxes(part, program_part):
    check = Checker(json.loads((program_part / "summary.json").read_text()), part_solver_mesh())
    f = int(part.facets[part.valid][0])
    b = part.bounds[np.flatnonzero(part.valid & (part.facets == f))[0]].copy()
    v = check.tri[f]
    n = np.cross(v[1] - v[0], v[2] - v[0])
    n /= np.linalg.norm(n)
    far = b.copy()
    far[:3] += (2 * check.dmax * n)[:, None]  # out of focus
    assert 2 in check.violations(f, far)[0]
    behind = b.copy()
    behind[:3] -= (2 * ((b[:3].mean(axis=1) - v.mean(axis=0)) @ n) * n)[:, None]  # mirrored through the plane
    assert 3 in check.violations(f, behind)[0]
    aside = b.copy()
    aside[3:] = [[0, 0], [0, 0], [0, 0]]  # looking straight up
    assert 5 in check.violations(f, aside)[0] or np.allclose(n, [0, 0, -1])
    # a segment through a triangle is blocked; one that ends on a neighbouring facet's edge is not
    tri = np.array([[[0, 0, 0], [1, 0, 0], [0, 1, 0]], [[0, 0, 1], [1, 0, 1], [0, 1, 1]]], float)
    p = np.array([[0.2, 0.2, 2.0], [0.2, 0.2, 2.0]])
    q = np.array([[0.2, 0.2, 0.0], [0.2, 0.2, 1.0]])
    assert list(segment_blocked(p, q, tri, 0)) == [True, False]


_MESH = {}


def part_solver_mesh():
    if "m" not in _MESH:
        _MESH["m"] = certipose.Mesh.read(MESH)
    return _MESH["m"]


# ---- progress, cancellation, interruption, the GIL -----------------------------------------

def test_progress_reports_and_cancels(solver):
    seen = []

    def progress(p):
        seen.append(p)
        return p.facets_done < 5  # cancel after five facets

    r = solver.solve_part(threads=1, progress=progress, **EPS)
    assert seen and all(isinstance(p, certipose.Progress) for p in seen)
    assert [p.facets_done for p in seen] == sorted(p.facets_done for p in seen)
    assert seen[0].facets_total == 704
    assert r.termination == "cancelled"
    assert 5 <= len(r.records) < 704


def test_progress_exception_stops_the_run(solver):
    def progress(p):
        raise RuntimeError("stop here")
    with pytest.raises(RuntimeError, match="stop here"):
        solver.solve_part(threads=2, progress=progress, **EPS)


def test_keyboard_interrupt_stops_a_part_run(solver):
    timer = threading.Timer(0.5, lambda: os.kill(os.getpid(), signal.SIGINT))
    start = time.monotonic()
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        solver.solve_part(threads=2, position_eps=0.02, orientation_eps=0.38)
    timer.join()
    assert time.monotonic() - start < 60  # stopped, not run to the end


def test_keyboard_interrupt_stops_a_facet_solve(solver):
    timer = threading.Timer(0.5, lambda: os.kill(os.getpid(), signal.SIGINT))
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        solver.solve_facet(21, position_eps=0.002, orientation_eps=0.38, max_boxes=10**9)
    timer.join()


def test_the_gil_is_released_while_solving(solver):
    ticks = []
    done = threading.Event()

    def solve():
        solver.solve_part(facets=FACETS[:40], threads=1, **EPS)
        done.set()
    t = threading.Thread(target=solve)
    t.start()
    while not done.is_set():
        ticks.append(1)
        time.sleep(0.001)
    t.join()
    assert len(ticks) > 10  # this thread ran while the other solved


def test_iterator_yields_in_facet_order_and_can_be_dropped(solver):
    it = solver.iter_part(facets=[21, 28, 35, 42], threads=2, **EPS)
    first = next(it)
    assert first.facet == 21 and first.record["index"] == 21
    del it  # stops the run, does not hang
    it = solver.iter_part(facets=[21, 28], threads=2, **EPS)
    assert [f.facet for f in it] == [21, 28]
    assert it.summary["facets_selected"] == 2


def test_inspect_gives_certified_and_possible_sets(solver, part):
    sel = np.flatnonzero(part.valid)[:20]
    cov = solver.inspect(part.bounds[sel], threads=2)
    areas = part_solver_mesh().areas
    assert len(cov) == 20
    for c in cov:
        assert set(c.certified) <= set(c.possible)
        assert c.certified_area == pytest.approx(areas[c.certified].sum(), rel=1e-9, abs=1e-15)
    assert any(len(c.certified) > 0 for c in cov)


# ---- bad input ------------------------------------------------------------------------------

def test_bad_input_raises_typed_errors_naming_the_value(solver, tmp_path):
    with pytest.raises(certipose.OutOfRange, match="facet 704 is out of range") as e:
        solver.solve_facet(704)
    assert e.value.index == 704 and isinstance(e.value, IndexError) and isinstance(e.value, ValueError)
    with pytest.raises(certipose.InvalidArgument, match="position_eps") as e:
        solver.solve_facet(21, position_eps=-1)
    assert isinstance(e.value, ValueError)
    with pytest.raises(certipose.InvalidArgument, match='"fast"'):
        certipose.Solver(MESH, CAMERA, occlusion="fast")
    with pytest.raises(certipose.InvalidArgument, match="corner_depth"):
        solver.solve_facet(21, corner_depth=9)
    with pytest.raises(certipose.InvalidArgument, match=r"\(N, 3\)"):
        certipose.Mesh(np.zeros((4, 2)), [[0, 1, 2]])
    with pytest.raises(certipose.MeshError, match="vertex 7"):
        certipose.Mesh(np.eye(3), [[0, 1, 7]])
    with pytest.raises(certipose.MeshError, match="vertex -1"):
        certipose.Mesh(np.eye(3), [[0, 1, -1]])
    with pytest.raises(certipose.MeshError, match="non-finite"):
        certipose.Mesh(np.array([[0, 0, 0], [1, 0, 0], [0, np.nan, 0]]), [[0, 1, 2]])
    with pytest.raises(certipose.FileError, match="nothing.off") as e:
        certipose.Mesh.read(str(tmp_path / "nothing.off"))
    assert isinstance(e.value, OSError) and e.value.filename.endswith("nothing.off")
    with pytest.raises(certipose.InvalidArgument, match="scale"):
        certipose.Mesh.read(MESH, scale=0)
    with pytest.raises(certipose.InvalidArgument, match="focal_length"):
        certipose.camera({"camera": {"model": "pinhole"}})
    with pytest.raises(certipose.InvalidArgument, match="facet selection \"5-2\""):
        solver.solve_part(facets="5-2", **EPS)
    with pytest.raises(certipose.InvalidArgument, match="threads"):
        solver.solve_part(threads=-1, **EPS)
    calib = ROOT / "tests" / "fuzz" / "seeds" / "calibration" / "opencv.yaml"
    with pytest.raises(certipose.InvalidArgument, match="working_distance"):
        certipose.camera(calib)
    cam = certipose.camera(calib, working_distance=(0.3, 0.8), min_view_angle=0.3)
    assert cam.distance_range == (0.3, 0.8)
    with pytest.raises(certipose.InvalidArgument, match="min_view_angle"):
        certipose.camera(CAMERA, min_view_angle=0.3)
    assert issubclass(certipose.FileError, certipose.Error) and issubclass(certipose.MeshError, certipose.Error)
    with pytest.raises(certipose.InvalidArgument, match="scale 0.001") as e:
        certipose.Solver(solver.mesh, CAMERA, scale=0.001)  # a Mesh is in metres already
    assert e.value.field == "scale"
    with pytest.raises(certipose.InvalidArgument) as e:
        solver.solve_part(threads=-1)
    assert e.value.field == "threads"
    with pytest.raises(certipose.InvalidArgument, match=r"got shape \(3,\)"):
        solver.inspect(np.zeros(3))
    blind = certipose.Solver(MESH, CAMERA, occlusion="none")
    with pytest.raises(certipose.InvalidArgument, match='occlusion "none"'):
        blind.verify(np.zeros((1, 6)))
    with pytest.raises(certipose.InvalidArgument, match='occlusion "none"'):
        blind.plan(tmp_path)
    bad_occluder = tmp_path / "open.off"
    bad_occluder.write_text("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n")
    with pytest.raises(certipose.Error, match="open.off"):
        certipose.Solver(MESH, CAMERA, occluders=[bad_occluder], mesh_semantics="solid")


def test_camera_round_trips_through_a_dict():
    cam = certipose.camera(CAMERA)
    again = certipose.camera(cam.to_dict())
    assert again.to_json() == cam.to_json()
    assert cam.model == "thin_lens"


# ---- plan, verify, export: the programs' answers -------------------------------------------

PLAN = os.environ.get("CERTIPOSE_PLAN", "certipose-plan")
VERIFY = os.environ.get("CERTIPOSE_VERIFY", "certipose-verify")
EXPORT = os.environ.get("CERTIPOSE_EXPORT", "certipose-export")


@pytest.fixture(scope="module")
def program_plan(program_part, tmp_path_factory):
    out = tmp_path_factory.mktemp("plan") / "PLAN.json"
    subprocess.run([PLAN, "--mesh", MESH, "--camera", CAMERA, "--part-results", str(program_part), "--coverage", "0.9",
                    "--threads", "2", "--out", str(out), "-q"], check=True)
    return out


def test_read_part_is_the_run(part, program_part):
    r = certipose.read_part(program_part)
    assert np.array_equal(r.bounds.view(np.uint64), np.ascontiguousarray(part.bounds).view(np.uint64))
    assert np.array_equal(r.facets, part.facets) and np.array_equal(r.reason_codes, part.reason_codes)
    assert r.records[0]["index"] == FACETS[0] and r.summary["format"] == "certipose-part-summary"


def test_plan_is_certipose_plan(solver, part, program_part, program_plan):
    theirs = json.loads(program_plan.read_text())
    from_folder = solver.plan(program_part, coverage=0.9, threads=2)
    assert from_folder.to_dict() == theirs
    from_run = solver.plan(part, coverage=0.9, threads=2)  # the same boxes, solved here
    assert from_run.to_dict() == theirs
    assert certipose.plan(MESH, CAMERA, program_part, coverage=0.9).to_dict() == theirs  # the function form
    assert certipose.export(program_plan, "csv") == from_run.export("csv")
    assert len(from_run.cameras) >= 2 and from_run.coverage["lower_bound_method"] in ("area", "greedy", "lp", "exact")


def test_plan_thinning_and_all_candidates(solver, program_part, tmp_path):
    out = tmp_path / "ALL.json"
    subprocess.run([PLAN, "--mesh", MESH, "--camera", CAMERA, "--part-results", str(program_part), "--coverage", "0.9",
                    "--candidates-per-facet", "3", "--threads", "2", "--all-candidates", "--out", str(out), "-q"], check=True)
    theirs = json.loads(out.read_text())
    every = solver.plan(program_part, coverage=0.9, candidates_per_facet=3, threads=2, all_candidates=True).to_dict()
    assert every == theirs and every["settings"]["inspected"] == every["settings"]["candidates"] > 64
    # More candidates than one round of 64: those whose facet an inspected one certifies are skipped.
    thinned = solver.plan(program_part, coverage=0.9, candidates_per_facet=3, threads=2).to_dict()["settings"]
    assert 1 <= thinned["inspected"] < thinned["candidates"]


def test_plan_reports_progress_and_cancels(solver, part):
    calls = []
    with pytest.raises(certipose.Error, match="cancelled"):
        # Every candidate: thinning would leave too few for a second progress call before the end.
        solver.plan(part, candidates_per_facet=100, threads=2, all_candidates=True,
                    progress=lambda done, all: calls.append((done, all)) or len(calls) < 2)
    assert len(calls) == 2 and 0 < calls[0][0] <= calls[1][0] < calls[1][1]


def test_plan_refuses_a_run_of_another_camera(part):
    wide = certipose.Solver(MESH, SHARED / "cases" / "camera_wide.json")
    with pytest.raises(certipose.InvalidArgument, match="camera"):
        wide.plan(part)


def test_verify_is_certipose_verify(solver, program_plan, tmp_path):
    out = tmp_path / "REPORT.json"
    subprocess.run([VERIFY, "--mesh", MESH, "--camera", CAMERA, "--poses", str(program_plan), "--out", str(out), "-q"], check=True)
    theirs = json.loads(out.read_text())
    mine = solver.verify(program_plan)
    assert len(mine["poses"]) == len(theirs["poses"]) > 0
    for a, b in zip(mine["poses"], theirs["poses"]):
        assert list(a["facets"]) == b["facets"] and list(a["possible"]) == b["possible"]
        assert a["certified_area"] == b["certified_area"] and a["kind"] == b["kind"]
    assert mine["union"] == theirs["union"]
    # exact poses: the nominal poses, each with its tolerance box
    nominal = np.array([c["nominal"] for c in certipose.read_plan(program_plan).cameras])
    exact = solver.verify(nominal)
    assert all(p["kind"] == "pose" for p in exact["poses"])
    assert any(p.get("tolerance") for p in exact["poses"])


@pytest.mark.parametrize("fmt", ["csv", "urdf", "moveit", "glb", "html", "sheet"])
def test_export_is_certipose_export(fmt, program_plan, tmp_path):
    out = tmp_path / f"plan.{fmt}"
    args = [EXPORT, str(program_plan), "--format", fmt, "--out", str(out), "-q"]
    if fmt in ("glb", "html", "sheet"):
        args += ["--mesh", MESH] + (["--title", "t"] if fmt in ("html", "sheet") else [])
    subprocess.run(args, check=True)
    plan = certipose.read_plan(program_plan)
    mine = plan.export(fmt, mesh=MESH if fmt in ("glb", "html", "sheet") else None, title="t")
    assert mine == out.read_bytes()
    plan.export(fmt, tmp_path / "again", mesh=MESH, title="t")
    assert (tmp_path / "again").read_bytes() == mine


@pytest.mark.parametrize("fmt,options,flags", [
    ("urdf", {"link_prefix": "cell1_cam", "robot_name": "cell1"}, ["--link-prefix", "cell1_cam", "--robot-name", "cell1"]),
    ("urdf", {"snippet": True}, ["--snippet"]),
    ("moveit", {"link_prefix": "cell1_cam"}, ["--link-prefix", "cell1_cam"]),
])
def test_export_options_are_certipose_export_flags(fmt, options, flags, program_plan, tmp_path):
    out = tmp_path / "out"
    subprocess.run([EXPORT, str(program_plan), "--format", fmt, "--out", str(out), "-q"] + flags, check=True)
    mine = certipose.read_plan(program_plan).export(fmt, **options)
    assert mine == out.read_bytes()
    assert mine != certipose.read_plan(program_plan).export(fmt)  # the option changed something


def test_plan_and_export_bad_input(solver, part, program_plan, tmp_path):
    with pytest.raises(certipose.InvalidArgument, match="coverage"):
        solver.plan(part, coverage=1.5)
    with pytest.raises(certipose.InvalidArgument, match="cameras or coverage"):
        solver.plan(part, cameras=2, coverage=0.5)
    with pytest.raises(certipose.FileError, match="summary.json"):
        solver.plan(str(tmp_path))
    with pytest.raises(certipose.InvalidArgument, match='"pdf"'):
        certipose.read_plan(program_plan).export("pdf")
    with pytest.raises(certipose.InvalidArgument, match="mesh"):
        certipose.read_plan(program_plan).export("glb")
    with pytest.raises(certipose.InvalidArgument, match="poses"):
        solver.verify(np.zeros((2, 5)))
    with pytest.raises(certipose.InvalidArgument, match="lower > upper"):
        solver.verify(np.array([[[0, 1], [0, 1], [2, 1], [0, 0], [0, 0], [0, 0]]], float))


# ---- the scene: occluders and camera regions, as the programs take them ----------------------

SAMPLE = os.environ.get("CERTIPOSE_SAMPLE_PART", str(ROOT / "build" / "release" / "examples" / "sample_part.off"))
PLATE = str(ROOT / "examples" / "data" / "fixture_plate.off")
KEEP_OUT = "box:-10,-10,-10,10,10,0.3"  # cuts through the boxes above the part (it is ~0.05 m high)
SAMPLE_FACETS = list(range(0, 2300, 23))


@pytest.fixture(scope="module")
def scene_run(tmp_path_factory):
    out = tmp_path_factory.mktemp("scene") / "run"
    subprocess.run([PART, "--mesh", SAMPLE, "--camera", str(ROOT / "examples" / "data" / "camera.json"),
                    "--occluder", PLATE, "--keep-out", KEEP_OUT, "--position-eps", "0.1", "--orientation-eps", "0.38",
                    "--facets", ",".join(map(str, SAMPLE_FACETS)), "--threads", "2", "--box-store", "binary",
                    "--out", str(out), "-q"], check=True)
    return out


def test_occluders_and_regions_are_the_programs(scene_run, tmp_path):
    camera_file = str(ROOT / "examples" / "data" / "camera.json")
    s = certipose.Solver(SAMPLE, camera_file, occluders=[PLATE], keep_out=[KEEP_OUT])
    r = s.solve_part(facets=SAMPLE_FACETS, threads=2)
    boxes, _ = box_store.read(scene_run / "boxes.cpbx")
    theirs = np.concatenate([boxes["position"], boxes["orientation"]], axis=1)
    assert len(r) == len(boxes) > 0
    assert np.array_equal(np.ascontiguousarray(r.bounds).view(np.uint64), np.ascontiguousarray(theirs).view(np.uint64))
    assert (r.positions[:, 2, 0] >= 0.3).all()  # nothing below the keep-out's top
    unrestricted = certipose.Solver(SAMPLE, camera_file, occluders=[PLATE]).solve_part(facets=SAMPLE_FACETS, threads=2)
    assert (unrestricted.positions[unrestricted.valid][:, 2, 0] < 0.3).any()  # the region did cut something
    f = int(SAMPLE_FACETS[np.argmax(np.bincount(r.facets[r.valid], minlength=2300)[SAMPLE_FACETS])])
    one = s.solve_facet(f)  # certipose-solve restricts to the regions too
    assert (one.positions[one.valid][:, 2, 0] >= 0.3).all() and one.valid.any()
    plan_file = tmp_path / "PLAN.json"
    subprocess.run([PLAN, "--mesh", SAMPLE, "--camera", camera_file, "--occluder", PLATE, "--keep-out", KEEP_OUT,
                    "--part-results", str(scene_run), "--coverage", "0.95", "--threads", "2", "--out", str(plan_file), "-q"],
                   check=True)
    assert s.plan(scene_run, coverage=0.95, threads=2).to_dict() == json.loads(plan_file.read_text())
    assert s.plan(r, coverage=0.95, threads=2).to_dict() == json.loads(plan_file.read_text())
    bare = certipose.Solver(SAMPLE, camera_file)
    with pytest.raises(certipose.InvalidArgument, match="occluders"):
        bare.plan(scene_run)
    with pytest.raises(certipose.InvalidArgument, match="occluders"):
        bare.plan(r)
    with pytest.raises(certipose.InvalidArgument, match="keep_out"):
        certipose.Solver(SAMPLE, camera_file, keep_out=["cube:1,2"])
    # a pose below the keep-out's top certifies nothing
    below = np.array([[0.0, 0.0, 0.1, 0.0, 0.0, 0.0]])
    v = s.verify(below)["poses"][0]
    assert v["camera_region"] == "forbidden" and len(v["facets"]) == 0


def test_the_stub_names_the_api():
    import ast
    stub = ast.parse((pathlib.Path(certipose.__file__).parent / "__init__.pyi").read_text())
    names = {n.name for n in stub.body if isinstance(n, (ast.ClassDef, ast.FunctionDef))} | \
        {t.id for n in stub.body if isinstance(n, ast.AnnAssign) for t in [n.target]}
    assert set(certipose.__all__) <= names, set(certipose.__all__) - names
    solver_stub = next(n for n in stub.body if isinstance(n, ast.ClassDef) and n.name == "Solver")
    methods = {n.name for n in solver_stub.body if isinstance(n, ast.FunctionDef)}
    public = {m for m in dir(certipose.Solver) if not m.startswith("_")}
    assert public <= methods | {"occlusion"}, public - methods


STEP = SHARED / "cad" / "featuretype.STEP"


def test_read_step_is_the_programs_tessellation_with_its_faces(tmp_path):
    mesh, cad = certipose.read_step(STEP)
    assert cad["unit"] == "INCH" and cad["angular_deflection"] == 0.5 and cad["dropped_triangles"] >= 0
    assert len(cad["faces"]) == 96
    kinds = {}
    for f in cad["faces"]:
        kinds[f["surface"]] = kinds.get(f["surface"], 0) + 1
    assert kinds == {"plane": 49, "cylinder": 46, "bspline": 1}
    # the faces' facets are a partition of the facets, and face_of the same map read the other way
    facets = np.sort(np.concatenate([f["facets"] for f in cad["faces"]]))
    assert np.array_equal(facets, np.arange(mesh.num_faces))
    for f in cad["faces"]:
        assert np.all(cad["face_of"][f["facets"]] == f["id"])
        assert f["area"] > 0 and 0 <= f["deviation"] <= 1.01 * cad["deflection"]
    # the programs' tessellation: certipose-part's mesh.off is the same mesh, bit for bit
    subprocess.run([PART, "--mesh", str(STEP), "--camera", CAMERA, "--position-eps", "0.1", "--orientation-eps", "0.38",
                    "--facets", "0", "--out", str(tmp_path / "run"), "--quiet"], check=True)
    off = certipose.Mesh.read(str(tmp_path / "run" / "mesh.off"))
    assert np.array_equal(off.vertices, mesh.vertices) and np.array_equal(off.faces, mesh.faces)
    assert off.digest == mesh.digest
    # Mesh.read reads it too, in metres; a scale is refused (the file has its unit)
    assert certipose.Mesh.read(str(STEP)).digest == mesh.digest
    with pytest.raises(certipose.InvalidArgument, match="carries its length unit") as e:
        certipose.Mesh.read(str(STEP), 0.0254)
    assert e.value.field == "scale"
    # a finer tessellation has more facets, each face within the finer deflection (the sampled
    # maximum of one face need not shrink: OpenCASCADE places the new vertices)
    finer, fine = certipose.read_step(STEP, deflection=cad["deflection"] / 2, angular_deflection=0.25)
    assert finer.num_faces > mesh.num_faces and fine["deflection"] == cad["deflection"] / 2
    assert max(f["deviation"] for f in fine["faces"]) <= 1.01 * fine["deflection"]
    with pytest.raises(certipose.InvalidArgument, match="deflection"):
        certipose.read_step(STEP, deflection=0.0)
    with pytest.raises(certipose.FileError, match="missing.step"):
        certipose.read_step(tmp_path / "missing.step")
