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

import html as _html
import inspect as _inspect
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
        if isinstance(r, (tuple, list)) and r and r[0] in ("box", "sphere"):
            return r[0] + ":" + ",".join(repr(float(x)) for x in r[1:])
        raise InvalidArgument(f"{where}: expected \"box:XMIN,YMIN,ZMIN,XMAX,YMAX,ZMAX\", \"sphere:X,Y,Z,R\" or a tuple "
                              f"(\"box\", ...) / (\"sphere\", ...), got {r!r}", where)
    # One region as a tuple starts with its kind; a tuple of region strings is several regions.
    if isinstance(regions, str) or (isinstance(regions, tuple) and regions and regions[0] in ("box", "sphere")):
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


def _camera_to_dict(self) -> dict:
    """The camera and task as a dict in the camera JSON's shape (certipose.camera() takes it back)."""
    return _json.loads(self.to_json())


Camera.to_dict = _camera_to_dict


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


_BOUND_NAMES = ("x", "y", "z", "phi", "gamma", "beta")
#: The 12 edges of a box whose 8 corners are numbered by bits (x: 1, y: 2, z: 4).
_BOX_EDGES = _np.array([[0, 1], [2, 3], [4, 5], [6, 7], [0, 2], [1, 3], [4, 6], [5, 7], [0, 4], [1, 5], [2, 6], [3, 7]])
_STYLE = ("<style>.certipose table{border-collapse:collapse;font:12px sans-serif}"
          ".certipose td,.certipose th{border:1px solid #ccc;padding:2px 6px;text-align:right}"
          ".certipose caption{text-align:left;font-weight:bold;padding:4px 0}</style>")


def _table(caption: str, head: Sequence[str], rows: Sequence[Sequence[Any]], more: int = 0) -> str:
    """An HTML table (every cell escaped); `more` rows left out are counted in a last row."""
    e = _html.escape
    out = [f"<table><caption>{e(caption)}</caption><tr>" + "".join(f"<th>{e(h)}</th>" for h in head) + "</tr>"]
    out += ["<tr>" + "".join(f"<td>{e(str(c))}</td>" for c in r) + "</tr>" for r in rows]
    if more:
        out.append(f'<tr><td colspan="{len(head)}">… {more} more</td></tr>')
    return "".join(out) + "</table>"


def _line_set(points: _np.ndarray, lines: _np.ndarray, colour: Sequence[float]) -> Any:
    """An Open3D LineSet (Open3D is imported here, only when asked for)."""
    try:
        import open3d as o3d
    except ImportError:
        raise ImportError("certipose: to_open3d needs Open3D (Debian: apt-get install python3-open3d; "
                          "or pip install open3d); box_lines() gives the same geometry as arrays") from None
    ls = o3d.geometry.LineSet(o3d.utility.Vector3dVector(_np.asarray(points, dtype=float)),
                              o3d.utility.Vector2iVector(_np.asarray(lines, dtype=_np.int32)))
    ls.paint_uniform_color(list(colour))
    return ls


def _box_lines(position_bounds: _np.ndarray) -> Tuple[_np.ndarray, _np.ndarray]:
    """(points (8K, 3), lines (12K, 2)) of K position boxes given as (K, 3, 2) bounds."""
    k = position_bounds.shape[0]
    corner = (_np.arange(8)[:, None] >> _np.arange(3)[None, :]) & 1  # (8, 3): 0 lower, 1 upper
    points = position_bounds[:, _np.arange(3)[None, :], corner].reshape(-1, 3)  # corner c's axis a: bound corner[c, a]
    lines = (_BOX_EDGES[None, :, :] + 8 * _np.arange(k)[:, None, None]).reshape(-1, 2)
    return points, lines


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
        """(N, 3, 2) position intervals [x, y, z] x [lower, upper], metres (a view of ``bounds``)."""
        return self.bounds[:, 0:3, :]

    @property
    def orientations(self) -> _np.ndarray:
        """(N, 3, 2) ZXZ Euler-angle intervals [phi, gamma, beta] x [lower, upper], radians (a view)."""
        return self.bounds[:, 3:6, :]

    @property
    def classes(self) -> _np.ndarray:
        """(N,) "valid" or "boundary" for each box."""
        return _CLASS_NAMES[self.class_codes]

    @property
    def reasons(self) -> _np.ndarray:
        """(N,) why each BOUNDARY box stayed undecided (one of BOUNDARY_REASONS); "" for VALID boxes."""
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

    def _facet_column(self) -> _np.ndarray:
        raise NotImplementedError

    def to_records(self) -> _np.ndarray:
        """One record per box, as a numpy structured array that ``pandas.DataFrame(r.to_records())``
        turns into a table: ``facet``, ``cls`` ("valid" / "boundary"), ``reason``, then ``x_lo``,
        ``x_hi``, ``y_lo``, ... ``beta_hi`` (metres, radians; the certified bounds as they are)."""
        fields = [("facet", _np.int64), ("cls", "U8"), ("reason", f"U{max(map(len, BOUNDARY_REASONS))}")] + [
            (f"{n}_{end}", _np.float64) for n in _BOUND_NAMES for end in ("lo", "hi")]
        out = _np.empty(len(self), dtype=fields)
        out["facet"] = self._facet_column()
        out["cls"] = self.classes
        out["reason"] = self.reasons
        for i, n in enumerate(_BOUND_NAMES):
            out[f"{n}_lo"] = self.bounds[:, i, 0]
            out[f"{n}_hi"] = self.bounds[:, i, 1]
        return out

    def _select(self, which: Union[str, _np.ndarray]) -> _np.ndarray:
        if isinstance(which, str):
            masks = {"valid": self.valid, "boundary": ~self.valid, "all": _np.ones(len(self), bool)}
            if which not in masks:
                raise InvalidArgument(f"which: expected \"valid\", \"boundary\", \"all\" or a mask, got {which!r}", "which")
            return masks[which]
        mask = _np.asarray(which)
        if mask.dtype != bool or mask.shape != (len(self),):
            raise InvalidArgument(f"which: a mask must be a bool array of shape ({len(self)},), got {mask.dtype} "
                                  f"{mask.shape}", "which")
        return mask

    def box_lines(self, which: Union[str, _np.ndarray] = "valid") -> Tuple[_np.ndarray, _np.ndarray]:
        """The position boxes that ``which`` selects ("valid", "boundary", "all" or a bool mask) as
        line geometry: (points (8K, 3) in metres, lines (12K, 2) index pairs into points). Open3D
        draws it (to_open3d), trimesh with ``trimesh.load_path(points[lines])``."""
        return _box_lines(self.positions[self._select(which)])

    def to_open3d(self, which: Union[str, _np.ndarray] = "valid", colour: Sequence[float] = (0.1, 0.55, 0.2)) -> Any:
        """The position boxes ``which`` selects as an ``open3d.geometry.LineSet`` (see box_lines)."""
        return _line_set(*self.box_lines(which), colour)

    def _html_boxes(self, limit: int = 10) -> str:
        rows = [[self._facet_column()[i], self.classes[i], self.reasons[i] or "—"] +
                [f"{self.bounds[i, k, 0]:.4g} … {self.bounds[i, k, 1]:.4g}" for k in range(6)]
                for i in range(min(limit, len(self)))]
        return _table("boxes (metres, radians)", ["facet", "class", "reason", *_BOUND_NAMES], rows,
                      max(0, len(self) - limit))

    def _html_counts(self) -> str:
        reasons, counts = _np.unique(self.reasons[~self.valid], return_counts=True)
        rows = [["valid", int(self.valid.sum())]] + [[f"boundary: {r}", int(c)] for r, c in zip(reasons, counts)]
        return _table("boxes by class", ["class", "boxes"], rows)


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
        """How the facet's solve ended: "complete", or the budget or cancellation that stopped it."""
        return self.stats.get("termination") or self.record.get("termination", "")

    def __repr__(self) -> str:
        return f"<certipose.FacetResult facet {self.facet}: {self._counts()}>"

    def _facet_column(self) -> _np.ndarray:
        return _np.full(len(self), self.facet, dtype=_np.int64)

    def _repr_html_(self) -> str:
        """A notebook shows the result as its counts and its first boxes."""
        return (f'{_STYLE}<div class="certipose"><p><b>certipose.FacetResult</b> facet {self.facet}: '
                f"{_html.escape(self._counts())} ({_html.escape(self.termination or 'no budget stop')})</p>"
                f"{self._html_counts()}{self._html_boxes()}</div>")


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
        """How the run ended: "complete", or the budget or cancellation that stopped it."""
        return self.summary.get("termination", "")

    def __repr__(self) -> str:
        return f"<certipose.PartResult {len(self.records)} facets: {self._counts()} ({self.termination})>"

    def _facet_column(self) -> _np.ndarray:
        return _np.asarray(self.facets, dtype=_np.int64)

    def _repr_html_(self) -> str:
        """A notebook shows the run as its counts, per facet and per box."""
        with_valid = len(_np.unique(self.facets[self.valid]))
        return (f'{_STYLE}<div class="certipose"><p><b>certipose.PartResult</b> {len(self.records)} facets solved, '
                f"{with_valid} with a VALID box: {_html.escape(self._counts())} ({_html.escape(self.termination)})</p>"
                f"{self._html_counts()}{self._html_boxes()}</div>")


class Progress(NamedTuple):
    """A whole-part run's progress, as certipose-part's progress line shows it. ``valid``: VALID
    boxes found so far (keep_largest keeps at most K of each facet's); ``boundary``: BOUNDARY boxes
    the result will hold (0 unless the run keeps them, ``boundary=True``); ``boundary_found``: those
    the paving left undecided, kept or not."""
    facets_done: int
    facets_total: int
    valid: int
    boundary: int
    seconds: float
    seconds_left: float  #: estimate (elapsed x work left / work done)
    boundary_found: int = 0


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
        """The occlusion test in use: "aabb", "boolean" or "none"."""
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
        kept = bool(boundary)
        cb = None if progress is None else (
            lambda d: progress(Progress(**{**d, "boundary": d["boundary"] if kept else 0, "boundary_found": d["boundary"]})))
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
        return Plan(doc, self.mesh)
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
    return Plan(doc, self.mesh)


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
        """Ends the run early: facets already finished are still yielded, then iteration stops."""
        self._run.cancel()


class Plan:
    """A camera plan: PLAN.json's content (docs/coverage.md). ``cameras`` (each with its
    position and orientation bounds, nominal pose, certified facets and area), ``coverage``
    (certified, coverable and total area, the lower bound on the number of cameras and its
    method) and ``uncovered`` (facets no chosen camera certifies, with the reason) are the
    document's fields as dicts; ``to_dict()`` is the whole document."""

    def __init__(self, doc: "_core.PlanDocument", mesh: Optional["Mesh"] = None):
        self._doc = doc
        self._dict = _json.loads(doc.to_json())
        self._mesh = mesh  # the part, when the plan was made here (the 3-D view draws it)

    @staticmethod
    def read(path: Union[str, _os.PathLike]) -> "Plan":
        """Reads a PLAN.json (certipose-plan's, or one Plan.save wrote)."""
        return Plan(_core.PlanDocument.read(_os.fspath(path)))

    def to_dict(self) -> dict:
        """The whole PLAN.json document as a dict (a fresh copy)."""
        return _json.loads(self._doc.to_json())

    @property
    def cameras(self) -> list:
        """One dict per camera: "position" and "orientation" bounds, the "nominal" pose [x, y, z, phi,
        gamma, beta], "facets" it certifies, "certified_area" (m^2), "aim" (the point it looks at)."""
        return self._dict["cameras"]

    @property
    def coverage(self) -> dict:
        """"certified_area", "coverable_area" and "total_area" (m^2), "lower_bound_cameras" and its
        "lower_bound_method", and "curve" (the certified area after each camera)."""
        return self._dict["coverage"]

    @property
    def uncovered(self) -> list:
        """The facets no chosen camera certifies, each {"facet": i, "reason": why}."""
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

    def to_records(self) -> _np.ndarray:
        """One record per camera, as a numpy structured array (``pandas.DataFrame(plan.to_records())``):
        ``camera``, the nominal pose ``x``, ``y``, ``z``, ``phi``, ``gamma``, ``beta`` (metres,
        radians, ZXZ), the certified bounds ``x_lo`` ... ``beta_hi``, ``aim_x``, ``aim_y``, ``aim_z``
        (the point on the part it looks at), ``facets`` (how many it certifies) and
        ``certified_area`` (m^2)."""
        fields = ([("camera", _np.int64)] + [(n, _np.float64) for n in _BOUND_NAMES] +
                  [(f"{n}_{end}", _np.float64) for n in _BOUND_NAMES for end in ("lo", "hi")] +
                  [("aim_x", _np.float64), ("aim_y", _np.float64), ("aim_z", _np.float64), ("facets", _np.int64),
                   ("certified_area", _np.float64)])
        out = _np.empty(len(self.cameras), dtype=fields)
        for k, c in enumerate(self.cameras):
            bounds = list(c["position"]) + list(c["orientation"])
            out[k] = ((k, *c["nominal"], *[b for lo_hi in bounds for b in lo_hi], *c["aim"], len(c["facets"]),
                       c["certified_area"]))
        return out

    def to_open3d(self, colour: Sequence[float] = (0.85, 0.3, 0.1)) -> Any:
        """The cameras as one ``open3d.geometry.LineSet``: each camera's certified position box and a
        line from its nominal position to its aim point on the part."""
        points, lines = _box_lines(_np.array([c["position"] for c in self.cameras], dtype=float).reshape(-1, 3, 2))
        sight = _np.array([p for c in self.cameras for p in (c["nominal"][:3], c["aim"])], dtype=float).reshape(-1, 3)
        sight_lines = len(points) + _np.arange(len(sight)).reshape(-1, 2)
        return _line_set(_np.vstack([points, sight]), _np.vstack([lines, sight_lines]), colour)

    def _viewer_html(self) -> Optional[str]:
        """The 3-D viewer's page, or None when this build has no viewer or the part is not at hand."""
        if not _core.has_viewer:
            return None
        mesh = self._mesh
        if mesh is None:
            path = self._dict["mesh"].get("path", "")
            if not path or not _os.path.isfile(path):
                return None
            try:
                mesh = _mesh(path, self._dict["mesh"]["scale"])
            except Error:
                return None
        try:
            return self._doc.export("html", mesh, "world", "optical", "certipose plan", "camera_", "certipose_cameras",
                                    False).decode()
        except Error:  # e.g. a different part under the recorded path: the table still shows
            return None

    def _repr_html_(self) -> str:
        """A notebook shows the plan as its cameras' table and, when the part is at hand and the build
        has the web viewer, the 3-D viewer inline."""
        c = self.coverage
        share = c["certified_area"] / c["coverable_area"] if c["coverable_area"] else 0.0
        of_part = c["certified_area"] / c["total_area"] if c["total_area"] else 0.0
        rows = [[k, *(f"{1000 * v:.1f}" for v in cam["nominal"][:3]), len(cam["facets"]),
                 f"{1e4 * cam['certified_area']:.1f}", *(f"{1000 * v:.1f}" for v in cam["aim"])]
                for k, cam in enumerate(self.cameras)]
        table = _table("cameras", ["camera", "x mm", "y mm", "z mm", "facets", "area cm²", "aim x mm", "aim y mm",
                                   "aim z mm"], rows)
        page = self._viewer_html()
        view = ("<p><i>The 3-D view needs the part and a build with the web viewer: "
                "plan.export(\"html\", \"plan.html\", mesh=...).</i></p>" if page is None else
                f'<iframe class="certipose-viewer" srcdoc="{_html.escape(page, quote=True)}" '
                f'style="width:100%;height:480px;border:1px solid #ccc" sandbox="allow-scripts"></iframe>')
        return (f'{_STYLE}<div class="certipose"><p><b>certipose.Plan</b> {len(self.cameras)} cameras certify '
                f"{100 * share:.1f} % of the coverable area, {100 * of_part:.1f} % of the part; at least "
                f"{c['lower_bound_cameras']} ({_html.escape(str(c['lower_bound_method']))}); "
                f"{len(self.uncovered)} facets uncovered</p>{table}{view}</div>")


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


def _spell_out(function: Callable, *methods: Callable) -> None:
    """Gives `function` (mesh, camera_spec, ..., **options) the signature help() and IDEs show: its
    own parameters, then the Solver's keywords and those of `methods` by name, keyword-only."""
    own = _inspect.signature(function)
    params = [p for p in own.parameters.values() if p.kind is not p.VAR_KEYWORD]
    names = {p.name for p in params}
    for m in methods:
        for p in _inspect.signature(m).parameters.values():
            if p.kind is p.KEYWORD_ONLY and p.name not in names:
                params.append(p)
                names.add(p.name)
    function.__signature__ = own.replace(parameters=params)


_spell_out(solve_facet, Solver.__init__, Solver.solve_facet)
_spell_out(solve_part, Solver.__init__, Solver.solve_part)
_spell_out(iter_part, Solver.__init__, Solver.iter_part)
_spell_out(plan, Solver.__init__, Solver.plan)
_spell_out(verify, Solver.__init__, Solver.verify)
_spell_out(export, Plan.export)


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
    (Node.js on the machine when the module was built; see docs/python.md#install)."""
    return ("csv", "moveit", "urdf", "ply", "glb", "sheet") + (("html",) if _core.has_viewer else ())
