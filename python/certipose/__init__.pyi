# Type stubs of the module certipose (docs/python.md), for IDEs and type checkers.
import os
from typing import Any, Callable, Iterator, NamedTuple, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

_Path = Union[str, os.PathLike]
_CameraSpec = Union["Camera", dict, _Path]
_MeshSpec = Union["Mesh", _Path, Any]  # a Mesh, a file, or anything with .vertices and .faces (trimesh, Open3D)

BOUNDARY_REASONS: Tuple[str, ...]
__version__: str

class Error(Exception): ...
class InvalidArgument(Error, ValueError):
    field: str
    def __init__(self, message: str, field: str = "") -> None: ...
class OutOfRange(Error, IndexError, ValueError):
    field: str
    index: int
    size: int
class MeshError(Error, ValueError): ...
class FileError(Error, OSError): ...
class GeometryError(Error, ValueError): ...

class Mesh:
    """A triangle mesh, validated (finite coordinates, indices in range, no degenerate face)."""
    def __init__(self, vertices: npt.ArrayLike, faces: npt.ArrayLike) -> None: ...
    @staticmethod
    def read(path: Union[str, os.PathLike], scale: float = 1.0, weld_tolerance: Optional[float] = None) -> "Mesh": ...
    @property
    def num_faces(self) -> int: ...
    @property
    def num_vertices(self) -> int: ...
    @property
    def vertices(self) -> npt.NDArray[np.float64]: ...  # (N, 3), a read-only view
    @property
    def faces(self) -> npt.NDArray[np.uint32]: ...      # (M, 3), a read-only view
    @property
    def areas(self) -> npt.NDArray[np.float64]: ...
    @property
    def digest(self) -> str: ...
    def facet(self, index: int) -> dict: ...

class Camera:
    """A camera and inspection task, as the camera JSON gives them (docs/io.md)."""
    @staticmethod
    def from_dict(spec: dict) -> "Camera": ...
    @staticmethod
    def from_json(text: str, source: str = "", base_dir: str = "") -> "Camera": ...
    @staticmethod
    def read(path: str, working_distance: Optional[Tuple[float, float]] = None,
             min_view_angle: Optional[float] = None) -> "Camera": ...
    def to_json(self) -> str: ...
    def to_dict(self) -> dict: ...
    @property
    def model(self) -> str: ...
    @property
    def distance_range(self) -> Tuple[float, float]: ...

def camera(spec: _CameraSpec, *, working_distance: Optional[Sequence[float]] = None,
           min_view_angle: Optional[float] = None) -> Camera: ...

class Boxes:
    bounds: npt.NDArray[np.float64]        # (N, 6, 2)
    class_codes: npt.NDArray[np.uint8]     # 0 VALID, 1 BOUNDARY
    reason_codes: npt.NDArray[np.int8]     # index into BOUNDARY_REASONS; -1 for VALID
    @property
    def positions(self) -> npt.NDArray[np.float64]: ...     # (N, 3, 2)
    @property
    def orientations(self) -> npt.NDArray[np.float64]: ...  # (N, 3, 2)
    @property
    def classes(self) -> npt.NDArray[np.str_]: ...          # "valid" / "boundary"
    @property
    def reasons(self) -> npt.NDArray[np.str_]: ...
    @property
    def valid(self) -> npt.NDArray[np.bool_]: ...
    def __len__(self) -> int: ...
    def to_records(self) -> npt.NDArray[np.void]: ...       # facet, cls, reason, x_lo, x_hi, ... beta_hi
    def box_lines(self, which: Union[str, npt.NDArray[np.bool_]] = "valid") -> Tuple[npt.NDArray[np.float64], npt.NDArray[np.int64]]: ...
    def to_open3d(self, which: Union[str, npt.NDArray[np.bool_]] = "valid",
                  colour: Sequence[float] = (0.1, 0.55, 0.2)) -> Any: ...  # open3d.geometry.LineSet
    def _repr_html_(self) -> str: ...

class FacetResult(Boxes):
    facet: int
    stats: dict
    record: dict
    @property
    def termination(self) -> str: ...

class PartResult(Boxes):
    facets: npt.NDArray[np.int64]          # each box's facet
    summary: dict
    records: list
    folder: Optional[str]
    @property
    def termination(self) -> str: ...

class Progress(NamedTuple):
    facets_done: int
    facets_total: int
    valid: int
    boundary: int
    seconds: float
    seconds_left: float
    boundary_found: int = 0

class Coverage(NamedTuple):
    certified: npt.NDArray[np.int64]
    possible: npt.NDArray[np.int64]
    certified_area: float
    possible_area: float

class PartIterator(Iterator[FacetResult]):
    summary: Optional[dict]
    def __iter__(self) -> "PartIterator": ...
    def __next__(self) -> FacetResult: ...
    def cancel(self) -> None: ...

class Plan:
    @staticmethod
    def read(path: _Path) -> "Plan": ...
    def to_dict(self) -> dict: ...
    @property
    def cameras(self) -> list: ...
    @property
    def coverage(self) -> dict: ...
    @property
    def uncovered(self) -> list: ...
    @property
    def seconds(self) -> dict: ...
    def save(self, path: _Path) -> None: ...
    def to_records(self) -> npt.NDArray[np.void]: ...       # camera, x ... beta, x_lo ... beta_hi, aim_*, facets, certified_area
    def to_open3d(self, colour: Sequence[float] = (0.85, 0.3, 0.1)) -> Any: ...  # open3d.geometry.LineSet
    def _repr_html_(self) -> str: ...
    def export(self, format: str, path: Optional[_Path] = None, *, mesh: Optional[_MeshSpec] = None,
               scale: Optional[float] = None, parent_frame: str = "world", link: str = "optical",
               title: str = "certipose plan", link_prefix: str = "camera_", robot_name: str = "certipose_cameras",
               snippet: bool = False) -> Optional[bytes]: ...

class Solver:
    mesh: Mesh
    camera: Camera
    mesh_path: str
    scale: float
    survey: Optional[dict]
    def __init__(self, mesh: _MeshSpec, camera_spec: _CameraSpec, *, occlusion: str = "aabb",
                 mesh_semantics: str = "auto", scale: float = 1.0,
                 working_distance: Optional[Sequence[float]] = None, min_view_angle: Optional[float] = None,
                 occluders: Sequence[Any] = (), keep_in: Union[str, Tuple[Any, ...], Sequence[Any]] = (),
                 keep_out: Union[str, Tuple[Any, ...], Sequence[Any]] = ()) -> None: ...
    @property
    def occlusion(self) -> str: ...
    def solve_facet(self, facet: int, *, position_eps: float = 0.1, orientation_eps: float = 0.38,
                    max_boxes: Optional[int] = None, time_limit: Optional[float] = None, paper_paving: bool = False,
                    corner_depth: Optional[int] = None, corner_rest: Optional[float] = None,
                    refine: Optional[float] = None, grow: bool = False) -> FacetResult: ...
    def iter_part(self, *, position_eps: float = 0.1, orientation_eps: float = 0.38,
                  facets: Union[None, str, Sequence[int]] = None, threads: int = 0, boundary: bool = False,
                  keep_largest: Optional[int] = None, max_boxes_per_facet: Optional[int] = None,
                  facet_time_limit: Optional[float] = None, max_boxes: Optional[int] = None,
                  time_limit: Optional[float] = None, paper_paving: bool = False, corner_depth: Optional[int] = None,
                  corner_rest: Optional[float] = None, refine: Optional[float] = None, grow: bool = False,
                  reuse: bool = True,
                  progress: Optional[Callable[[Progress], Optional[bool]]] = None) -> PartIterator: ...
    def solve_part(self, *, position_eps: float = 0.1, orientation_eps: float = 0.38,
                   facets: Union[None, str, Sequence[int]] = None, threads: int = 0, boundary: bool = False,
                   keep_largest: Optional[int] = None, max_boxes_per_facet: Optional[int] = None,
                   facet_time_limit: Optional[float] = None, max_boxes: Optional[int] = None,
                   time_limit: Optional[float] = None, paper_paving: bool = False, corner_depth: Optional[int] = None,
                   corner_rest: Optional[float] = None, refine: Optional[float] = None, grow: bool = False,
                   reuse: bool = True,
                   progress: Optional[Callable[[Progress], Optional[bool]]] = None) -> PartResult: ...
    def inspect(self, bounds: npt.ArrayLike, *, threads: int = 0, possible: bool = True) -> list[Coverage]: ...
    def plan(self, part: Union[PartResult, _Path], *, cameras: Optional[int] = None, coverage: Optional[float] = None,
             candidates_per_facet: int = 1, tolerance: Optional[Sequence[float]] = (0.005, 0.02),
             lp_seconds: float = 60, exact: Optional[float] = None, threads: int = 0, all_candidates: bool = False,
             progress: Optional[Callable[[int, int], Optional[bool]]] = None) -> Plan: ...
    def verify(self, poses: Union[npt.ArrayLike, _Path], *, tolerance: bool = True,
               progress: Optional[Callable[[int, int], Optional[bool]]] = None) -> dict: ...

# The functions take the Solver's keywords (the scene) and the options of the Solver method of
# their name.
def solve_facet(
    mesh: _MeshSpec, camera_spec: _CameraSpec, facet: int, *, occlusion: str = "aabb", mesh_semantics: str = "auto", scale: float = 1.0,
    working_distance: Optional[Sequence[float]] = None, min_view_angle: Optional[float] = None,
    occluders: Sequence[Any] = (), keep_in: Union[str, Tuple[Any, ...], Sequence[Any]] = (),
    keep_out: Union[str, Tuple[Any, ...], Sequence[Any]] = (),
    position_eps: float = 0.1, orientation_eps: float = 0.38,
    max_boxes: Optional[int] = None, time_limit: Optional[float] = None, paper_paving: bool = False,
    corner_depth: Optional[int] = None, corner_rest: Optional[float] = None,
    refine: Optional[float] = None, grow: bool = False) -> FacetResult: ...
def solve_part(
    mesh: _MeshSpec, camera_spec: _CameraSpec, *, occlusion: str = "aabb", mesh_semantics: str = "auto", scale: float = 1.0,
    working_distance: Optional[Sequence[float]] = None, min_view_angle: Optional[float] = None,
    occluders: Sequence[Any] = (), keep_in: Union[str, Tuple[Any, ...], Sequence[Any]] = (),
    keep_out: Union[str, Tuple[Any, ...], Sequence[Any]] = (),
    position_eps: float = 0.1, orientation_eps: float = 0.38,
    facets: Union[None, str, Sequence[int]] = None, threads: int = 0, boundary: bool = False,
    keep_largest: Optional[int] = None, max_boxes_per_facet: Optional[int] = None,
    facet_time_limit: Optional[float] = None, max_boxes: Optional[int] = None,
    time_limit: Optional[float] = None, paper_paving: bool = False, corner_depth: Optional[int] = None,
    corner_rest: Optional[float] = None, refine: Optional[float] = None, grow: bool = False,
    reuse: bool = True, progress: Optional[Callable[[Progress], Optional[bool]]] = None) -> PartResult: ...
def iter_part(
    mesh: _MeshSpec, camera_spec: _CameraSpec, *, occlusion: str = "aabb", mesh_semantics: str = "auto", scale: float = 1.0,
    working_distance: Optional[Sequence[float]] = None, min_view_angle: Optional[float] = None,
    occluders: Sequence[Any] = (), keep_in: Union[str, Tuple[Any, ...], Sequence[Any]] = (),
    keep_out: Union[str, Tuple[Any, ...], Sequence[Any]] = (),
    position_eps: float = 0.1, orientation_eps: float = 0.38,
    facets: Union[None, str, Sequence[int]] = None, threads: int = 0, boundary: bool = False,
    keep_largest: Optional[int] = None, max_boxes_per_facet: Optional[int] = None,
    facet_time_limit: Optional[float] = None, max_boxes: Optional[int] = None,
    time_limit: Optional[float] = None, paper_paving: bool = False, corner_depth: Optional[int] = None,
    corner_rest: Optional[float] = None, refine: Optional[float] = None, grow: bool = False,
    reuse: bool = True, progress: Optional[Callable[[Progress], Optional[bool]]] = None) -> PartIterator: ...
def plan(
    mesh: _MeshSpec, camera_spec: _CameraSpec, part: Union[PartResult, _Path], *, occlusion: str = "aabb", mesh_semantics: str = "auto", scale: float = 1.0,
    working_distance: Optional[Sequence[float]] = None, min_view_angle: Optional[float] = None,
    occluders: Sequence[Any] = (), keep_in: Union[str, Tuple[Any, ...], Sequence[Any]] = (),
    keep_out: Union[str, Tuple[Any, ...], Sequence[Any]] = (),
    cameras: Optional[int] = None, coverage: Optional[float] = None,
    candidates_per_facet: int = 1, tolerance: Optional[Sequence[float]] = (0.005, 0.02),
    lp_seconds: float = 60, exact: Optional[float] = None, threads: int = 0, all_candidates: bool = False,
    progress: Optional[Callable[[int, int], Optional[bool]]] = None) -> Plan: ...
def verify(
    mesh: _MeshSpec, camera_spec: _CameraSpec, poses: Union[npt.ArrayLike, _Path], *, occlusion: str = "aabb", mesh_semantics: str = "auto", scale: float = 1.0,
    working_distance: Optional[Sequence[float]] = None, min_view_angle: Optional[float] = None,
    occluders: Sequence[Any] = (), keep_in: Union[str, Tuple[Any, ...], Sequence[Any]] = (),
    keep_out: Union[str, Tuple[Any, ...], Sequence[Any]] = (),
    tolerance: bool = True, progress: Optional[Callable[[int, int], Optional[bool]]] = None) -> dict: ...
def read_part(folder: _Path) -> PartResult: ...
def read_plan(path: _Path) -> Plan: ...
def read_step(path: _Path, deflection: Optional[float] = None,
              angular_deflection: Optional[float] = None) -> Tuple[Mesh, dict]: ...
def export(plan_or_path: Union[Plan, _Path], format: str, path: Optional[_Path] = None, *,
           mesh: Optional[_MeshSpec] = None, scale: Optional[float] = None, parent_frame: str = "world",
           link: str = "optical", title: str = "certipose plan", link_prefix: str = "camera_",
           robot_name: str = "certipose_cameras", snippet: bool = False) -> Optional[bytes]: ...
def sample_part() -> Mesh: ...
def example_camera() -> dict: ...
def available_formats() -> Tuple[str, ...]: ...
