"""certipose — certified camera deployment spaces for visual inspection (docs/python.md).

Given a triangle mesh of a part and a camera, certipose returns 6D pose boxes (a position box
and ZXZ Euler-angle intervals) such that every pose in a VALID box images a facet in focus, at a
usable angle, inside the image and without occlusion.

    import certipose
    mesh = certipose.Mesh.read("part.off")                  # or certipose.Mesh(V, F)
    camera = {"camera": {...}, "task": {...}}              # the camera JSON's shape (docs/io.md)
    r = certipose.solve_facet(mesh, camera, 0, position_eps=0.1, orientation_eps=0.38)
    r.positions[r.classes == "valid"]                      # (N, 3, 2) metres

The compiled core (certipose._core) holds the precompiled default pipelines; this file turns
dicts into the camera JSON, codes into strings and per-facet arrays into a part's arrays.
"""

from __future__ import annotations

import json as _json
import os as _os
import warnings as _warnings
from typing import Any, Callable, Iterator, NamedTuple, Optional, Sequence, Tuple, Union

import numpy as _np

from . import _core
from ._errors import Error, FileError, GeometryError, InvalidArgument, MeshError, OutOfRange

#: The package's version (the project's, as in pyproject.toml and CMakeLists.txt).
__version__: str = _core.version

__all__ = [
    "__version__", "Mesh", "Camera", "Solver", "Boxes", "FacetResult", "PartResult", "PartIterator", "Progress", "Coverage", "Plan",
    "solve_facet", "solve_part", "iter_part", "plan", "verify", "export", "camera", "read_part", "read_plan", "read_step",
    "sample_part", "example_camera", "available_formats",
    "Error", "InvalidArgument", "OutOfRange", "MeshError", "FileError", "GeometryError",
    "BOUNDARY_REASONS",
]

Mesh = _core.Mesh
Camera = _core.Camera
Mesh.__doc__ = """A triangle mesh of a part, in metres: ``Mesh(vertices, faces)`` from an (N, 3) float array and an
(M, 3) array of integer vertex indices, or ``Mesh.read(path, scale=1.0, weld_tolerance=None)`` from
OFF, OBJ, PLY, STL or STEP. Read-only ``vertices``, ``faces``, ``areas``, ``num_faces``,
``num_vertices``, ``digest`` (the fingerprint the programs record); ``facet(i)`` describes facet i."""
Camera.__doc__ = """A camera and its inspection task; make one with ``certipose.camera(spec)`` from a dict in the
camera JSON's shape, our camera JSON file or an OpenCV/ROS calibration file. ``to_dict()`` gives
the dict back; ``model`` and ``distance_range`` (metres) describe it."""
_mesh_read = _core.Mesh.read


def _read_mesh(path: Union[str, _os.PathLike], scale: float = 1.0, weld_tolerance: Optional[float] = None) -> "Mesh":
    """The mesh in ``path`` (OFF, OBJ, PLY, STL; STEP in metres at the default tessellation), its
    coordinates multiplied by ``scale``; ``weld_tolerance`` merges vertices closer than it (a
    triangle soup from STL). ``path`` is a str or any os.PathLike."""
    if not isinstance(path, (str, _os.PathLike)):
        raise InvalidArgument(f"path: expected a str or os.PathLike, got {type(path).__name__}", "path")
    return _mesh_read(_os.fspath(path), float(scale), weld_tolerance)


Mesh.read = staticmethod(_read_mesh)
Mesh.__repr__ = lambda self: (f"<certipose.Mesh {self.num_faces} facets, {self.num_vertices} vertices, "
                              f"digest {self.digest}>")
Camera.__repr__ = lambda self: (f"<certipose.Camera {self.model}, in focus from {self.distance_range[0]:.4g} m to "
                                f"{self.distance_range[1]:.4g} m>")


def _json_default(value: Any) -> Any:
    """numpy scalars and arrays in a camera dict, as the plain numbers json writes."""
    if isinstance(value, _np.generic):
        return value.item()
    if isinstance(value, _np.ndarray):
        return value.tolist()
    raise TypeError(f"a camera dict holds {type(value).__name__} {value!r}, which is not a number, string, list or dict")


def _regions(field: str, regions: Any) -> list:
    """Camera regions as the programs' text: a "box:..." / "sphere:..." string, a ("box", xmin, ...)
    tuple, or a sequence of these."""
    def one(r: Any, where: str) -> str:
        if isinstance(r, str):
            return r
        if isinstance(r, (tuple, list)) and r and isinstance(r[0], str):
            return r[0] + ":" + ",".join(repr(float(x)) for x in r[1:])
        raise InvalidArgument(f"{where}: expected \"box:XMIN,YMIN,ZMIN,XMAX,YMAX,ZMAX\", \"sphere:X,Y,Z,R\" or a tuple "
                              f"(\"box\", ...) / (\"sphere\", ...), got {r!r}", where)
    if isinstance(regions, str) or (isinstance(regions, tuple) and regions and isinstance(regions[0], str)):
        regions = [regions]
    return [one(r, f"{field}[{i}]") for i, r in enumerate(regions)]

#: The reasons a BOUNDARY box was left undecided, in the order of their codes.
BOUNDARY_REASONS: tuple = tuple(_core.boundary_reasons)
_CLASS_NAMES = _np.array(["valid", "boundary"])
_REASON_NAMES = _np.array(list(BOUNDARY_REASONS) + [""])  # code -1 (VALID) indexes the last


def _camera_from_dict(spec: dict) -> "Camera":
    """A camera from a dict in the camera JSON's shape (docs/io.md)."""
    try:
        text = _json.dumps(spec, allow_nan=False, default=_json_default)
    except TypeError as e:
        raise InvalidArgument(f"camera: {e}", "camera") from None
    return _core.Camera.from_json(text, "camera")


Camera.from_dict = staticmethod(_camera_from_dict)
Camera.to_dict = lambda self: _json.loads(self.to_json())


def camera(spec: Union["Camera", dict, str, _os.PathLike], *, working_distance: Optional[Sequence[float]] = None,
           min_view_angle: Optional[float] = None) -> "Camera":
    """A Camera from a Camera, a dict in the camera JSON's shape, or a file: our camera JSON, or an
    OpenCV/ROS calibration file (then ``working_distance=(d_min, d_max)`` in metres and
    ``min_view_angle`` in radians are required, as the programs' options of those names)."""
    if isinstance(spec, _core.Camera):
        if working_distance is not None or min_view_angle is not None:
            raise InvalidArgument("working_distance and min_view_angle apply to a calibration file only, "
                                  "not to a certipose.Camera", "working_distance")
        return spec
    if isinstance(spec, dict):
        if working_distance is not None or min_view_angle is not None:
            raise InvalidArgument("working_distance and min_view_angle apply to a calibration file only; "
                                  "a camera dict has its own d_min, d_max and task.min_view_angle", "working_distance")
        return _camera_from_dict(spec)
    if isinstance(spec, (str, _os.PathLike)):
        wd = None if working_distance is None else (float(working_distance[0]), float(working_distance[1]))
        return _core.Camera.read(_os.fspath(spec), wd, min_view_angle)
    raise InvalidArgument(f"camera: expected a dict, a file path or a certipose.Camera, got {type(spec).__name__}", "camera")


def _mesh(m: Union["Mesh", str, _os.PathLike, Any], scale: float = 1.0) -> "Mesh":
    if isinstance(m, _core.Mesh):
        if scale != 1.0:
            raise InvalidArgument(f"scale {scale!r} applies to a mesh read from a file or arrays; this certipose.Mesh "
                                  f"is already in metres (read it with certipose.Mesh.read(path, scale))", "scale")
        return m
    if isinstance(m, (str, _os.PathLike)):
        return _core.Mesh.read(_os.fspath(m), scale)
    if hasattr(m, "vertices") and hasattr(m, "faces"):  # trimesh.Trimesh, or anything shaped like it
        return _core.Mesh(_np.asarray(m.vertices) * scale, _np.asarray(m.faces))
    if hasattr(m, "vertices") and hasattr(m, "triangles"):  # open3d.geometry.TriangleMesh (float64)
        return _core.Mesh(_np.asarray(m.vertices) * scale, _np.asarray(m.triangles))
    if hasattr(m, "vertex") and hasattr(m, "triangle"):  # open3d.t.geometry.TriangleMesh (float32 by default)
        v = m.vertex.positions.numpy()
        return _core.Mesh(v if scale == 1.0 else v * v.dtype.type(scale), m.triangle.indices.numpy())
    raise InvalidArgument(f"mesh: expected a certipose.Mesh, a file path or a mesh with vertices and faces, "
                          f"got {type(m).__name__}", "mesh")


class Boxes:
    """Classified pose boxes as arrays. ``bounds`` is (N, 6, 2): rows x, y, z (metres), phi,
    gamma, beta (radians, ZXZ), columns lower, upper, exactly as certified (outward-rounded).
    ``positions`` and ``orientations`` are its two (N, 3, 2) halves (views, not copies).
    ``classes`` holds "valid" / "boundary", ``reasons`` why each BOUNDARY box stayed undecided
    ("" for VALID boxes); ``class_codes`` / ``reason_codes`` are the same as small integers."""

    def __init__(self, bounds: _np.ndarray, class_codes: _np.ndarray, reason_codes: _np.ndarray):
        self.bounds: _np.ndarray = bounds
        self.class_codes: _np.ndarray = class_codes    #: 0 VALID, 1 BOUNDARY
        self.reason_codes: _np.ndarray = reason_codes  #: index into BOUNDARY_REASONS; -1 for VALID

    @property
    def positions(self) -> _np.ndarray:
        return self.bounds[:, 0:3, :]

    @property
    def orientations(self) -> _np.ndarray:
        return self.bounds[:, 3:6, :]

    @property
    def classes(self) -> _np.ndarray:
        return _CLASS_NAMES[self.class_codes]

    @property
    def reasons(self) -> _np.ndarray:
        return _REASON_NAMES[self.reason_codes]

    @property
    def valid(self) -> _np.ndarray:
        """Mask of the VALID boxes."""
        return self.class_codes == 0

    def __len__(self) -> int:
        return int(self.bounds.shape[0])

    def _counts(self) -> str:
        v = int(self.valid.sum())
        return f"{v} valid, {len(self) - v} boundary boxes"


class FacetResult(Boxes):
    """One facet's boxes as arrays (see Boxes), and what the solve did."""

    def __init__(self, arrays: "_core.FacetArrays"):
        super().__init__(arrays.bounds, arrays.class_codes, arrays.reason_codes)
        self.facet: int = arrays.facet
        #: solve_facet: the solver's statistics (the result JSON's "stats"); iter_part: {}.
        self.stats: dict = dict(arrays.stats)
        #: iter_part: the facet's record (summary.json's "facets" entry); solve_facet: {}.
        self.record: dict = dict(arrays.record)

    @property
    def termination(self) -> str:
        return self.stats.get("termination") or self.record.get("termination", "")

    def __repr__(self) -> str:
        return f"<certipose.FacetResult facet {self.facet}: {self._counts()}>"


class PartResult(Boxes):
    """A whole-part run's boxes as arrays (see Boxes; ``facets`` names each box's facet) and its
    summary: ``records`` (one dict per facet solved, summary.json's "facets") and ``summary``."""

    def __init__(self, facets: _np.ndarray, bounds: _np.ndarray, class_codes: _np.ndarray, reason_codes: _np.ndarray,
                 summary: dict, folder: Optional[str] = None):
        super().__init__(bounds, class_codes, reason_codes)
        self.facets: _np.ndarray = facets
        self.summary: dict = summary
        self.records: list = summary.get("facets", [])
        #: The certipose-part folder it was read from (read_part), else None.
        self.folder: Optional[str] = folder

    @property
    def termination(self) -> str:
        return self.summary.get("termination", "")

    def __repr__(self) -> str:
        return f"<certipose.PartResult {len(self.records)} facets: {self._counts()} ({self.termination})>"


class Progress(NamedTuple):
    """A whole-part run's progress, as certipose-part's progress line shows it."""
    facets_done: int
    facets_total: int
    valid: int
    boundary: int
    seconds: float
    seconds_left: float  #: estimate (elapsed x work left / work done)


class Coverage(NamedTuple):
    """C(B) and P(B) of one box: the facets every pose of it certifiably inspects, and those it
    was not proven unable to (P is empty when not asked for), with their areas (m^2)."""
    certified: _np.ndarray
    possible: _np.ndarray
    certified_area: float
    possible_area: float


def _settings(position_eps: float, orientation_eps: float, max_boxes: Optional[int], time_limit: Optional[float],
              paper_paving: bool, corner_depth: Optional[int], corner_rest: Optional[float], refine: Optional[float],
              grow: bool) -> "_core.FacetSettings":
    s = _core.FacetSettings()
    s.position_eps = float(position_eps)
    s.orientation_eps = float(orientation_eps)
    s.max_boxes = None if max_boxes is None else _count("max_boxes", max_boxes)
    s.time_limit = time_limit
    s.paper_paving = bool(paper_paving)
    s.corner_depth = None if corner_depth is None else _count("corner_depth", corner_depth)
    s.corner_rest = corner_rest
    s.refine = refine
    s.grow = bool(grow)
    return s


def _count(field: str, v: Any, least: int = 1) -> int:
    if isinstance(v, bool) or not isinstance(v, (int, _np.integer)) or v < least:
        raise InvalidArgument(f"{field} must be an integer >= {least}, got {v!r}", field)
    return int(v)


def _facet_selection(facets: Union[None, str, Sequence[int]]) -> Optional[str]:
    if facets is None or isinstance(facets, str):
        return facets
    return ",".join(str(_count("facets", f, 0)) for f in facets)


class Solver:
    """A part, a camera and an occlusion test: the occlusion scene is built once (seconds for a
    large part) and reused by every solve, inspection and part run.

    ``occlusion``: "aabb" (default; any triangle soup), "boolean" (the paper's test; closed
    solids only) or "none" (VALID boxes then hold for every constraint but occlusion).
    ``mesh_semantics``: "auto", "solid" or "soup" (docs/occlusion.md). A mesh read as a triangle
    soup gives a warning naming what was found; ``survey`` holds it. ``occluders``: extra meshes
    in the occlusion scene (fixtures, conveyors, the cell): Mesh objects, files, or (file, scale)
    pairs. ``keep_in`` / ``keep_out``: camera regions, "box:XMIN,YMIN,ZMIN,XMAX,YMAX,ZMAX" or
    "sphere:X,Y,Z,R" (metres): VALID boxes are restricted to where a camera may stand, as the
    programs' --occluder, --keep-in and --keep-out do."""

    def __init__(self, mesh, camera_spec, *, occlusion: str = "aabb", mesh_semantics: str = "auto", scale: float = 1.0,
                 working_distance: Optional[Sequence[float]] = None, min_view_angle: Optional[float] = None,
                 occluders: Sequence[Any] = (), keep_in: Sequence[str] = (), keep_out: Sequence[str] = ()):
        self.mesh = _mesh(mesh, scale)
        #: The mesh's file and scale as the documents record them ("<arrays>" for a mesh given as arrays).
        self.mesh_path = _os.fspath(mesh) if isinstance(mesh, (str, _os.PathLike)) else "<arrays>"
        self.scale = float(scale) if isinstance(mesh, (str, _os.PathLike)) else 1.0
        self.camera = camera(camera_spec, working_distance=working_distance, min_view_angle=min_view_angle)
        scene = []
        for i, o in enumerate(occluders):
            if isinstance(o, tuple):
                path, factor = o
                scene.append((_core.Mesh.read(_os.fspath(path), float(factor)), _os.fspath(path), float(factor)))
            elif isinstance(o, (str, _os.PathLike)):
                scene.append((_core.Mesh.read(_os.fspath(o), 1.0), _os.fspath(o), 1.0))
            else:
                scene.append((_mesh(o), f"<occluder {i}>", 1.0))
        try:
            self._core = _core.Solver(self.mesh, self.camera, occlusion, mesh_semantics, scene, _regions("keep_in", keep_in),
                                      _regions("keep_out", keep_out))
        except Error as e:  # the occlusion names extra meshes "occluder 0", ...: say which file each is
            if scene and "occluder" in str(e):
                e.args = (str(e) + " (" + ", ".join(f"occluder {i}: {o[1]}" for i, o in enumerate(scene)) + ")",)
            raise
        #: What the survey found when the scene is read as a triangle soup; None otherwise.
        self.survey: Optional[dict] = self._core.survey
        if self.survey is not None:
            s = self.survey
            found = ", ".join(f"{s[k]} {k.replace('_', ' ')}" for k in
                              ("intersecting_pairs", "duplicate_faces", "open_edges", "nonmanifold_edges",
                               "inward_bodies", "buried", "covered") if s[k])
            _warnings.warn(f"certipose: occlusion reads the scene as a triangle soup ({s['why_not_solid'] or 'as asked'}): "
                           f"{s['bodies']} bodies ({s['closed_bodies']} closed){', ' + found if found else ''}",
                           stacklevel=2)

    def __repr__(self) -> str:
        return (f"<certipose.Solver {self.mesh.num_faces} facets, {self.camera.model} camera, "
                f"{self.occlusion} occlusion>")

    @property
    def occlusion(self) -> str:
        return self._core.occlusion

    def solve_facet(self, facet: int, *, position_eps: float = 0.1, orientation_eps: float = 0.38,
                    max_boxes: Optional[int] = None, time_limit: Optional[float] = None, paper_paving: bool = False,
                    corner_depth: Optional[int] = None, corner_rest: Optional[float] = None,
                    refine: Optional[float] = None, grow: bool = False) -> FacetResult:
        """Certified pose boxes of one facet: what certipose-solve computes with the same options."""
        s = _settings(position_eps, orientation_eps, max_boxes, time_limit, paper_paving, corner_depth, corner_rest,
                      refine, grow)
        return FacetResult(self._core.solve_facet(_count("facet", facet, 0), s))

    def iter_part(self, *, position_eps: float = 0.1, orientation_eps: float = 0.38,
                  facets: Union[None, str, Sequence[int]] = None, threads: int = 0, boundary: bool = False,
                  keep_largest: Optional[int] = None, max_boxes_per_facet: Optional[int] = None,
                  facet_time_limit: Optional[float] = None, max_boxes: Optional[int] = None,
                  time_limit: Optional[float] = None, paper_paving: bool = False, corner_depth: Optional[int] = None,
                  corner_rest: Optional[float] = None, refine: Optional[float] = None, grow: bool = False,
                  reuse: bool = True,
                  progress: Optional[Callable[[Progress], Optional[bool]]] = None) -> "PartIterator":
        """The facets of a whole-part run, each as it finishes, in facet order (what certipose-part
        computes with the same options). See solve_part for the options."""
        return PartIterator(self._start(False, position_eps, orientation_eps, facets, threads, boundary, keep_largest,
                                        max_boxes_per_facet, facet_time_limit, max_boxes, time_limit, paper_paving,
                                        corner_depth, corner_rest, refine, grow, reuse, progress))

    def _start(self, collect, position_eps, orientation_eps, facets, threads, boundary, keep_largest, max_boxes_per_facet,
               facet_time_limit, max_boxes, time_limit, paper_paving, corner_depth, corner_rest, refine, grow, reuse,
               progress):
        s = _settings(position_eps, orientation_eps, max_boxes_per_facet, facet_time_limit, paper_paving, corner_depth,
                      corner_rest, refine, grow)
        cb = None if progress is None else (lambda d: progress(Progress(**d)))
        return self._core.start_part(s, _facet_selection(facets), _count("threads", threads, 0), bool(boundary),
                                     None if keep_largest is None else _count("keep_largest", keep_largest),
                                     None if max_boxes is None else _count("max_boxes", max_boxes), time_limit,
                                     bool(reuse), cb, collect)

    def solve_part(self, *, position_eps: float = 0.1, orientation_eps: float = 0.38,
                   facets: Union[None, str, Sequence[int]] = None, threads: int = 0, boundary: bool = False,
                   keep_largest: Optional[int] = None, max_boxes_per_facet: Optional[int] = None,
                   facet_time_limit: Optional[float] = None, max_boxes: Optional[int] = None,
                   time_limit: Optional[float] = None, paper_paving: bool = False, corner_depth: Optional[int] = None,
                   corner_rest: Optional[float] = None, refine: Optional[float] = None, grow: bool = False,
                   reuse: bool = True,
                   progress: Optional[Callable[[Progress], Optional[bool]]] = None) -> PartResult:
        """Certified pose boxes of every facet (or of ``facets``: a list or "0,5,17-30"), on
        ``threads`` threads (0: every core), as certipose-part computes them with the same
        options; ``boundary`` keeps BOUNDARY boxes too, ``keep_largest`` the K largest VALID
        boxes per facet; ``max_boxes_per_facet`` / ``facet_time_limit`` budget each facet,
        ``max_boxes`` / ``time_limit`` the whole run; ``reuse=False`` paves every facet on its own
        (by default a facet nothing can occlude takes a translate's boxes, each proven again, and
        its record's ``reused_from`` names that facet). ``progress(Progress)`` is called after
        facets finish, on the calling thread; returning False cancels the run (the facets
        finished are returned, ``termination`` "cancelled"). Ctrl-C (KeyboardInterrupt) stops
        the run and is raised."""
        run = self._start(True, position_eps, orientation_eps, facets, threads, boundary, keep_largest,
                          max_boxes_per_facet, facet_time_limit, max_boxes, time_limit, paper_paving, corner_depth,
                          corner_rest, refine, grow, reuse, progress)
        facets_of_boxes, bounds, classes, reasons = run.collect()
        summary = run.summary
        summary["run"] = _json.loads(_core.run_record(self._core))  # what plan() compares with
        return PartResult(facets_of_boxes, bounds, classes, reasons, summary)

    def inspect(self, bounds, *, threads: int = 0, possible: bool = True) -> list:
        """C(B) and P(B) of each box of an (N, 6, 2) bounds array (docs/coverage.md), in order."""
        return [Coverage(**c) for c in self._core.inspect(_np.asarray(bounds, dtype=_np.float64), _count("threads", threads, 0),
                                                          bool(possible))]


def _plan(self, part, *, cameras: Optional[int] = None, coverage: Optional[float] = None,
          candidates_per_facet: int = 1, tolerance: Optional[Sequence[float]] = (0.005, 0.02), lp_seconds: float = 60,
          exact: Optional[float] = None, threads: int = 0, all_candidates: bool = False,
          progress: Optional[Callable[[int, int], Optional[bool]]] = None) -> Plan:
    """The fewest camera boxes that certify the part (certipose-plan; docs/coverage.md), from a
    whole-part run: a PartResult of this solver, a certipose-part folder, or a PartResult read
    from one. ``cameras`` (at most K) or ``coverage`` (a share of the coverable area, default
    0.95); candidates are the ``candidates_per_facet`` largest VALID boxes of each facet, cut
    to ``tolerance`` = (metres, radians) half-widths around their centres (None: whole boxes);
    GLPK's LP lower bound gets ``lp_seconds``, its exact answer ``exact`` seconds if given.
    A candidate whose facet an already inspected one certifies is skipped, largest estimated view
    first (docs/coverage.md#thinning), unless ``all_candidates``. ``progress(done, all)`` follows the candidates' certified facet
    sets; False cancels."""
    opt = _core.plan_options(None if cameras is None else _count("cameras", cameras), coverage,
                             None if tolerance is None else (float(tolerance[0]), float(tolerance[1])),
                             float(lp_seconds), exact, _count("threads", threads, 0), bool(all_candidates))
    per = _count("candidates_per_facet", candidates_per_facet)
    if isinstance(part, PartResult) and part.folder is not None:
        part = part.folder
    if isinstance(part, (str, _os.PathLike)):
        doc = _core.make_plan(self._core, _os.fspath(part), per, False, self.mesh_path, self.scale, opt, progress)
        return Plan(doc)
    if not isinstance(part, PartResult):
        raise InvalidArgument(f"plan: expected a PartResult or a certipose-part folder, got {type(part).__name__}", "part")
    mine, theirs = _json.loads(_core.run_record(self._core)), part.summary.get("run")
    if theirs is None:
        raise InvalidArgument("plan: this PartResult records no run (make it with Solver.solve_part, or read a "
                              "certipose-part folder with certipose.read_part)", "part")
    for key in mine:
        if theirs.get(key) != mine[key]:
            raise InvalidArgument(f"plan: the run's {key} ({_json.dumps(theirs.get(key))}) is not this solver's "
                                  f"({_json.dumps(mine[key])}): plan with the mesh, camera and scene the run used", key)
    if not mine["occlusion_checked"]:
        raise InvalidArgument("plan: the run did not check occlusion (occlusion=\"none\"); its boxes certify no facet",
                              "occlusion")
    doc = _core.make_plan(self._core, (part.facets, part.bounds, part.class_codes, part.records), per, True,
                          self.mesh_path, self.scale, opt, progress)
    return Plan(doc)


def _verify(self, poses, *, tolerance: bool = True,
            progress: Optional[Callable[[int, int], Optional[bool]]] = None) -> dict:
    """certipose-verify: for each pose (an (N, 6) array of exact poses [x, y, z, phi, gamma,
    beta], an (N, 6, 2) array of pose boxes, or a POSES.json / PLAN.json path) the facets
    certified from every pose of it (``facets``, C(B)), those not proven impossible
    (``possible``), their areas and shares, and for an exact pose the largest box around it
    keeping C(B) certified (``tolerance``). Returns {"poses": [...], "union": {...}}."""
    if isinstance(poses, (str, _os.PathLike)):
        return _core.verify(self._core, _os.fspath(poses), bool(tolerance), progress)
    return _core.verify(self._core, _np.asarray(poses, dtype=_np.float64), bool(tolerance), progress)


Solver.plan = _plan
Solver.verify = _verify


class PartIterator:
    """Iterates a whole-part run's facets as they finish (FacetResult, in facet order). ``summary``
    is set once it is exhausted; ``cancel()`` ends the run early (the facets already finished are
    still yielded). Dropping the iterator stops the run."""

    def __init__(self, run: "_core.PartRun"):
        self._run = run
        self.summary: Optional[dict] = None

    def __iter__(self) -> "PartIterator":
        return self

    def __next__(self) -> FacetResult:
        try:
            return FacetResult(next(self._run))
        except StopIteration:
            if self.summary is None:
                self.summary = self._run.summary
            raise

    def cancel(self) -> None:
        self._run.cancel()


class Plan:
    """A camera plan: PLAN.json's content (docs/coverage.md). ``cameras`` (each with its
    position and orientation bounds, nominal pose, certified facets and area), ``coverage``
    (certified, coverable and total area, the lower bound on the number of cameras and its
    method) and ``uncovered`` (facets no chosen camera certifies, with the reason) are the
    document's fields as dicts; ``to_dict()`` is the whole document."""

    def __init__(self, doc: "_core.PlanDocument"):
        self._doc = doc
        self._dict = _json.loads(doc.to_json())

    @staticmethod
    def read(path: Union[str, _os.PathLike]) -> "Plan":
        """Reads a PLAN.json (certipose-plan's, or one Plan.save wrote)."""
        return Plan(_core.PlanDocument.read(_os.fspath(path)))

    def to_dict(self) -> dict:
        return _json.loads(self._doc.to_json())

    @property
    def cameras(self) -> list:
        return self._dict["cameras"]

    @property
    def coverage(self) -> dict:
        return self._dict["coverage"]

    @property
    def uncovered(self) -> list:
        return self._dict.get("uncovered", [])

    @property
    def seconds(self) -> dict:
        """Time spent on the candidates' certified facet sets and on the choice (0 for a plan read)."""
        return {"inspection": self._doc.seconds_inspection, "choice": self._doc.seconds_choice}

    def save(self, path: Union[str, _os.PathLike]) -> None:
        """Writes PLAN.json atomically (a complete file or none)."""
        self._doc.write(_os.fspath(path))

    def export(self, format: str, path: Union[None, str, _os.PathLike] = None, *, mesh=None, scale: Optional[float] = None,
               parent_frame: str = "world", link: str = "optical", title: str = "certipose plan",
               link_prefix: str = "camera_", robot_name: str = "certipose_cameras",
               snippet: bool = False) -> Optional[bytes]:
        """The plan in certipose-export's formats (docs/conventions.md#exports): "csv", "moveit",
        "urdf", "ply", "glb", "html" or "sheet" (the last four draw the part: give ``mesh``, the
        plan's part, or its file with the plan's scale by default). ``link_prefix`` names the
        cameras' links in "urdf" and "moveit"; ``robot_name`` and ``snippet`` are "urdf"'s, as
        certipose-export's --link-prefix, --robot-name and --snippet. Returns the bytes, or writes
        them atomically to ``path`` and returns None."""
        m = None
        if mesh is not None:
            m = _mesh(mesh, self._dict["mesh"]["scale"] if scale is None else scale)
        data = self._doc.export(format, m, parent_frame, link, title, link_prefix, robot_name, snippet)
        if path is None:
            return data
        _core.write_atomically(_os.fspath(path), data)
        return None

    def __repr__(self) -> str:
        c = self.coverage
        share = c["certified_area"] / c["coverable_area"] if c["coverable_area"] else 0.0
        return f"<certipose.Plan {len(self.cameras)} cameras, {100 * share:.1f} % of the coverable area>"


def read_part(folder: Union[str, _os.PathLike]) -> PartResult:
    """A certipose-part folder (summary.json, and boxes.cpbx or boxes.jsonl) as a PartResult."""
    facets, bounds, classes, reasons, summary = _core.read_part(_os.fspath(folder))
    return PartResult(facets, bounds, classes, reasons, _json.loads(summary), folder=_os.fspath(folder))


def read_step(path: Union[str, _os.PathLike], deflection: Optional[float] = None,
              angular_deflection: Optional[float] = None) -> Tuple["Mesh", dict]:
    """A STEP file (AP203, AP214, AP242) read in metres from its unit and tessellated, as
    certipose-part reads one (docs/step.md): returns (mesh, cad). `deflection`: the chordal
    deflection in metres (None: 1/1000 of the part's diagonal); `angular_deflection` in radians
    (None: 0.5). What is certified is the tessellation, `mesh`. `cad` holds "unit" (the file's),
    "deflection", "angular_deflection", "dropped_triangles", "face_of" (the CAD face of each
    facet, an int64 array) and "faces": per CAD face a dict of "id", "name" ("" when the file
    gives none), "surface" ("plane", "cylinder", ...), "area" (m²), "deviation" (the largest
    sampled distance between the face and its triangles, m) and "facets" (an int64 array).
    Mesh.read(path) reads the same mesh without the faces."""
    return _core.read_step(_os.fspath(path), deflection, angular_deflection)


def read_plan(path: Union[str, _os.PathLike]) -> Plan:
    """Reads a PLAN.json."""
    return Plan.read(path)


_SOLVER_KEYWORDS = ("occlusion", "mesh_semantics", "scale", "working_distance", "min_view_angle", "occluders",
                    "keep_in", "keep_out")


def _solver_and_options(mesh, camera_spec, options: dict):
    """A Solver from the keywords it takes (see Solver), and the rest of `options`."""
    scene = {k: options.pop(k) for k in _SOLVER_KEYWORDS if k in options}
    return Solver(mesh, camera_spec, **scene), options


def solve_facet(mesh, camera_spec, facet: int, **options) -> FacetResult:
    """Certified pose boxes of one facet (certipose-solve): the Solver's keywords (the scene:
    occlusion, mesh_semantics, scale, working_distance, min_view_angle, occluders, keep_in,
    keep_out) and Solver.solve_facet's options. Builds the occlusion scene on each call: for many
    facets of one part, use a Solver."""
    solver, rest = _solver_and_options(mesh, camera_spec, options)
    return solver.solve_facet(facet, **rest)


def solve_part(mesh, camera_spec, **options) -> PartResult:
    """Certified pose boxes of every facet of a part (certipose-part): the Solver's keywords and
    Solver.solve_part's options."""
    solver, rest = _solver_and_options(mesh, camera_spec, options)
    return solver.solve_part(**rest)


def iter_part(mesh, camera_spec, **options) -> PartIterator:
    """A whole-part run's facets as they finish: the Solver's keywords and Solver.iter_part's options."""
    solver, rest = _solver_and_options(mesh, camera_spec, options)
    return solver.iter_part(**rest)


def plan(mesh, camera_spec, part, **options) -> Plan:
    """A camera plan from a whole-part run (certipose-plan): the Solver's keywords and Solver.plan's options."""
    solver, rest = _solver_and_options(mesh, camera_spec, options)
    return solver.plan(part, **rest)


def verify(mesh, camera_spec, poses, **options) -> dict:
    """The facets anyone's poses certifiably inspect (certipose-verify): the Solver's keywords and
    Solver.verify's options."""
    solver, rest = _solver_and_options(mesh, camera_spec, options)
    return solver.verify(poses, **rest)


def export(plan_or_path: Union[Plan, str, _os.PathLike], format: str, path: Union[None, str, _os.PathLike] = None,
           **options) -> Optional[bytes]:
    """A plan (or a PLAN.json) in certipose-export's formats; see Plan.export."""
    p = plan_or_path if isinstance(plan_or_path, Plan) else Plan.read(plan_or_path)
    return p.export(format, path, **options)


def sample_part() -> "Mesh":
    """The procedural sample part the programs' examples use (2300 facets, metres; the same mesh,
    digest for digest, as the build's examples/sample_part.off), so that examples run after
    ``pip install`` alone."""
    return _core.sample_part()


def example_camera() -> dict:
    """The examples' camera (examples/data/camera.json: a 2448 x 2048 px thin-lens camera with a
    12 mm lens at f/8, focused at 0.6 m) as a dict in the camera JSON's shape (docs/io.md)."""
    return _json.loads(_core.example_camera)


def available_formats() -> Tuple[str, ...]:
    """The formats Plan.export offers in this build: "html" only when the build had the web viewer
    (Node.js and ``npm ci`` in web/ when the module was built)."""
    return ("csv", "moveit", "urdf", "ply", "glb", "sheet") + (("html",) if _core.has_viewer else ())
