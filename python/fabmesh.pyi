"""Type stub of the fabmesh module (docs/python.md). tests/python/test_stub.py
holds it to the module: every name, class member and parameter here is the
module's, and the module has no public name that is not here."""

import enum
from os import PathLike
from typing import Any, Iterator, Optional, Union

import numpy as np
import numpy.typing as npt

__version__: str

StrPath = Union[str, PathLike[str]]
ArrayLike = npt.ArrayLike

class Error(Exception):
    """Any failure of a fabmesh call; exit_code is the command line's code for it."""
    exit_code: int

class InputError(Error, ValueError):
    """Bad input (exit code 2), with where it is."""
    key: Optional[str]
    file: Optional[str]
    line: Optional[int]
    column: Optional[int]
    override: Optional[str]
    is_default: bool
    point: Optional[tuple[float, ...]]

class MissingFileError(InputError, FileNotFoundError):
    """A file that does not exist."""

class ValidationFailed(Error):
    """A mesh that is not valid for what it is asked for (exit code 1)."""

class MachineError(Error, OSError):
    """A fault of the machine, not of the input (exit code 5)."""

class Unit(str, enum.Enum):
    """A unit of length; each member is its text too (Unit.mm == "mm")."""
    mm = "mm"
    cm = "cm"
    m = "m"
    inch = "in"

class DefectKind(str, enum.Enum):
    """A kind of defect a mesh can have, named as the JSON reports name it."""
    empty = "empty"
    non_finite_vertex = "non_finite_vertex"
    boundary_edge = "boundary_edge"
    non_manifold_edge = "non_manifold_edge"
    non_manifold_vertex = "non_manifold_vertex"
    inconsistent_orientation = "inconsistent_orientation"
    inside_out = "inside_out"
    inverted_component = "inverted_component"
    nested_same_orientation = "nested_same_orientation"
    degenerate_face = "degenerate_face"
    duplicate_face = "duplicate_face"
    self_intersection = "self_intersection"

class PartRole(str, enum.Enum):
    """What a part of a Result is."""
    product = "product"
    mould_side = "mould_side"
    mould_base = "mould_base"
    piece = "piece"
    master = "master"
    case = "case"

class Parameter:
    """One of a design's named parameters (`parameters:`), with the value used."""
    @property
    def name(self) -> str: ...
    @property
    def value(self) -> float: ...
    @property
    def min(self) -> Optional[float]: ...
    @property
    def max(self) -> Optional[float]: ...
    @property
    def step(self) -> Optional[float]: ...
    @property
    def kind(self) -> str: ...
    @property
    def text(self) -> str: ...
    @property
    def choices(self) -> list[str]: ...
    @property
    def description(self) -> str: ...

class Design:
    """A design, read and checked; immutable, safe to share between threads."""
    @property
    def kind(self) -> str: ...
    @property
    def name(self) -> str: ...
    @property
    def units(self) -> Unit: ...
    @property
    def tolerance(self) -> float: ...
    @property
    def path(self) -> str: ...
    @property
    def outputs(self) -> list[str]: ...
    @property
    def parameters(self) -> list[Parameter]: ...
    @property
    def parameter_set(self) -> str: ...
    @property
    def parameter_sets(self) -> list[str]: ...

def read_design(path: StrPath, overrides: Optional[dict[str, Any]] = None) -> Design:
    """Reads a design file with -D style overrides (numbers, texts, lists; numpy values too)."""

def parse_design(design: Union[str, dict[str, Any]], overrides: Optional[dict[str, Any]] = None,
                 source: StrPath = "design.yaml") -> Design:
    """Reads a design from YAML text or a dict of its keys, with overrides."""

def load_design(path: Optional[StrPath] = None, *, text: Optional[str] = None,
                overrides: Optional[dict[str, Any]] = None) -> Design:
    """Deprecated since 0.4: read_design(path) or parse_design(text)."""

class Defect:
    """One kind of defect found: its kind, how many, and a few places."""
    @property
    def kind(self) -> DefectKind: ...
    @property
    def count(self) -> int: ...
    @property
    def examples(self) -> npt.NDArray[np.float64]: ...

class ValidationReport:
    """The verdict on one mesh, as `fabmesh check` gives it."""
    @property
    def valid(self) -> bool: ...
    @property
    def watertight(self) -> bool: ...
    @property
    def manifold(self) -> bool: ...
    @property
    def oriented_outward(self) -> bool: ...
    @property
    def self_intersecting(self) -> bool: ...
    @property
    def vertices(self) -> int: ...
    @property
    def triangles(self) -> int: ...
    @property
    def components(self) -> int: ...
    @property
    def boundary_edges(self) -> int: ...
    @property
    def non_manifold_edges(self) -> int: ...
    @property
    def non_manifold_vertices(self) -> int: ...
    @property
    def degenerate_faces(self) -> int: ...
    @property
    def genus(self) -> Optional[int]: ...
    @property
    def volume(self) -> float: ...
    @property
    def area(self) -> float: ...
    @property
    def defects(self) -> list[Defect]: ...
    @property
    def error(self) -> Optional[str]: ...
    def to_json(self) -> str: ...
    def to_dict(self) -> dict[str, Any]: ...
    def __getitem__(self, key: str) -> Any:
        """Deprecated since 0.4: report.to_dict()[key]."""

class Mesh:
    """An indexed triangle mesh; unpacks as (vertices, triangles, units)."""
    @property
    def vertices(self) -> npt.NDArray[np.float64]: ...
    @property
    def triangles(self) -> npt.NDArray[np.int64]: ...
    @property
    def units(self) -> Optional[Unit]: ...
    def __len__(self) -> int: ...
    def __iter__(self) -> Iterator[Any]: ...

def check(vertices: ArrayLike, triangles: ArrayLike, *, weld_tolerance: float = 0.0,
          max_seconds: float = 600.0) -> ValidationReport:
    """Validates a mesh given as arrays, as `fabmesh check` validates a file."""

def check_file(path: StrPath, *, weld_tolerance: float = 0.0, max_seconds: float = 600.0) -> ValidationReport:
    """Validates a mesh file as `fabmesh check FILE --json`."""

def read_mesh(path: StrPath) -> Mesh:
    """Reads a mesh file: its vertices, triangles and units (None when it states none)."""

def write_mesh(path: StrPath, vertices: ArrayLike, triangles: ArrayLike, *, units: Optional[str] = None) -> None:
    """Writes a mesh in the format the extension names."""

class Curve:
    """A composite plane curve of n segments, parameter t in [0, n]."""
    @property
    def segments(self) -> int: ...
    @property
    def closed(self) -> bool: ...
    def evaluate(self, t: Union[float, ArrayLike]) -> npt.NDArray[np.float64]: ...
    def derivative(self, t: Union[float, ArrayLike], order: int = 1) -> npt.NDArray[np.float64]: ...
    def curvature(self, t: Union[float, ArrayLike]) -> Union[float, npt.NDArray[np.float64]]: ...
    def sample(self, tolerance: float) -> tuple[npt.NDArray[np.float64], float]: ...
    @property
    def joints(self) -> list[dict[str, Any]]:
        """Every joint, measured: before, after, closing, gap, tangent_angle,
        curvature_before, curvature_after, curvature_jump, declared, achieved."""
    @property
    def fairing(self) -> Optional[dict[str, Any]]:
        """{'energy', 'before', 'after'} for a faired curve, else None."""
    @property
    def through(self) -> Optional[dict[str, Any]]:
        """{'points', 'control_points', 'deviation'} for a curve made to pass through
        points, else None."""

def tbezier(points: ArrayLike, lam: float = 0.0, mu: float = 0.0) -> Curve: ...
def quasi_bspline(points: ArrayLike, lambdas: Optional[list[float]] = None) -> Curve: ...
def quasi_bspline_through(points: ArrayLike, lambdas: Optional[list[float]] = None) -> Curve:
    """The quasi-cubic B-spline through q0..qn at its joints, its control points solved
    exactly. Raises InputError (key 'through' or 'lambdas')."""
def hbezier(points: ArrayLike, alpha: float = 1.0, lam: float = 0.0, mu: float = 0.0) -> Curve: ...
def composite(segments: list[dict[str, Any]], closed: bool = False, closing: str = "G0") -> Curve:
    """T-Bezier, H-Bezier and line segments with a design file's keys (family, points,
    lambda, mu, alpha, join, continuity). Raises InputError naming the segment."""
def fair(curve: Curve, energy: str = "curvature_variation", keeps: Optional[str] = None) -> Curve:
    """The curve with the shape parameters minimising 'strain' or 'curvature_variation',
    control points kept; keeps: the least continuity a joint may fall to."""

class BuiltCurve:
    """One of a design's curves as built."""
    @property
    def key(self) -> str: ...
    @property
    def points(self) -> npt.NDArray[np.float64]: ...
    @property
    def closed(self) -> bool: ...
    @property
    def max_deviation(self) -> float: ...
    @property
    def curve(self) -> Curve: ...

class Part:
    """One mesh of a Result: the design's own (its product) or a mould part."""
    @property
    def name(self) -> str: ...
    @property
    def role(self) -> PartRole: ...
    @property
    def vertices(self) -> npt.NDArray[np.float64]: ...
    @property
    def triangles(self) -> npt.NDArray[np.int64]: ...
    @property
    def validation(self) -> ValidationReport: ...
    @property
    def valid(self) -> bool: ...

class OutputFile:
    """One file `fabmesh run` writes for the design."""
    @property
    def path(self) -> str: ...
    @property
    def format(self) -> str: ...
    @property
    def units(self) -> Unit: ...
    @property
    def max_added_error(self) -> float: ...
    @property
    def valid_as_written(self) -> Optional[bool]: ...
    @property
    def parts(self) -> list[str]: ...

class Result:
    """A design built and validated as `fabmesh run` builds it."""
    @property
    def valid(self) -> bool: ...
    @property
    def error(self) -> str: ...
    @property
    def name(self) -> str: ...
    @property
    def kind(self) -> str: ...
    @property
    def units(self) -> Unit: ...
    @property
    def tolerance(self) -> float: ...
    @property
    def max_deviation(self) -> float: ...
    @property
    def parts(self) -> list[Part]: ...
    @property
    def curves(self) -> list[BuiltCurve]: ...
    @property
    def files(self) -> list[OutputFile]: ...
    @property
    def skipped(self) -> list[str]: ...
    @property
    def warnings(self) -> list[str]: ...
    @property
    def vertices(self) -> npt.NDArray[np.float64]: ...
    @property
    def triangles(self) -> npt.NDArray[np.int64]: ...
    @property
    def validation(self) -> ValidationReport: ...
    def to_json(self) -> str: ...
    def to_dict(self) -> dict[str, Any]: ...
    @property
    def report(self) -> dict[str, Any]:
        """Deprecated since 0.4: Result.to_dict()."""
    def write(self, path: StrPath) -> None: ...
    def outputs(self, folder: StrPath) -> list[str]: ...

def build(design: Design) -> Result:
    """Builds and validates a design as `fabmesh run` does."""

def optimize(design: Design) -> list[dict[str, Any]]:
    """The fairest shape parameters of the design's curves, as `fabmesh optimize --json`."""

def __getattr__(name: str) -> Any:
    """EnvironmentError, deprecated since 0.4: MachineError."""

class RepairReport:
    """What a repair did and got (docs/repair.md)."""
    @property
    def valid(self) -> bool: ...
    @property
    def changed(self) -> bool: ...
    @property
    def vertices(self) -> npt.NDArray[np.float64]: ...
    @property
    def triangles(self) -> npt.NDArray[np.int64]: ...
    @property
    def distance(self) -> float: ...
    @property
    def weld_distance(self) -> float: ...
    @property
    def components_before(self) -> int: ...
    @property
    def components_after(self) -> int: ...
    @property
    def volume_before(self) -> float: ...
    @property
    def volume_after(self) -> float: ...
    @property
    def area_before(self) -> float: ...
    @property
    def area_after(self) -> float: ...
    @property
    def unresolved(self) -> list[str]: ...
    @property
    def after(self) -> ValidationReport: ...
    def to_json(self) -> str: ...
    def to_dict(self) -> dict[str, Any]: ...

def repair(vertices: ArrayLike, triangles: ArrayLike, *, max_deviation: float = 0.0, wrap: bool = False,
           weld_distance: Optional[float] = None, fill_holes: bool = True,
           max_seconds: float = 600.0) -> RepairReport:
    """Repairs a mesh given as arrays (docs/repair.md)."""

def repair_file(path: StrPath, output: StrPath, *, max_deviation: float = 0.0, wrap: bool = False,
                weld_distance: Optional[float] = None, fill_holes: bool = True,
                max_seconds: float = 600.0) -> dict[str, Any]:
    """Repairs a mesh file into output, as `fabmesh repair PATH -o OUTPUT --json`: its item."""
