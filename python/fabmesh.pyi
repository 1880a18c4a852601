"""Type stub of the fabmesh module (docs/python.md)."""

from os import PathLike
from typing import Any, Optional, Union

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

class ValidationFailed(Error):
    """A mesh that is not valid for what it is asked for (exit code 1)."""

class EnvironmentError(Error, OSError):
    """Writing failed for a reason of the machine (exit code 5)."""

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
    def description(self) -> str: ...

class Design:
    """A design, read and checked; immutable, safe to share between threads."""
    @property
    def kind(self) -> str: ...
    @property
    def name(self) -> str: ...
    @property
    def units(self) -> str: ...
    @property
    def tolerance(self) -> float: ...
    @property
    def path(self) -> str: ...
    @property
    def outputs(self) -> list[str]: ...
    @property
    def parameters(self) -> list[Parameter]: ...

def load_design(path: Optional[StrPath] = None, *, text: Optional[str] = None,
                overrides: Optional[dict[str, Any]] = None) -> Design:
    """Reads a design from a file or from YAML text, with -D style overrides."""

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

class BuiltCurve:
    """One of a design's curves as built."""
    key: str
    points: npt.NDArray[np.float64]
    closed: bool
    max_deviation: float
    curve: Curve

class Result:
    """A design built and validated as `fabmesh run` builds it."""
    @property
    def valid(self) -> bool: ...
    @property
    def vertices(self) -> npt.NDArray[np.float64]: ...
    @property
    def triangles(self) -> npt.NDArray[np.int64]: ...
    @property
    def units(self) -> str: ...
    @property
    def tolerance(self) -> float: ...
    @property
    def max_deviation(self) -> float: ...
    @property
    def error(self) -> str: ...
    @property
    def curves(self) -> list[BuiltCurve]: ...
    @property
    def report(self) -> dict[str, Any]: ...
    @property
    def validation(self) -> dict[str, Any]: ...
    def write(self, path: StrPath) -> None: ...
    def outputs(self, folder: StrPath) -> list[str]: ...

def build(design: Design) -> Result:
    """Builds and validates a design as `fabmesh run` does."""

def check(vertices: ArrayLike, triangles: ArrayLike, *, weld_tolerance: float = 0.0,
          max_seconds: float = 600.0) -> dict[str, Any]:
    """Validates a mesh given as arrays; returns one `check --json` item."""

def check_file(path: StrPath, *, weld_tolerance: float = 0.0, max_seconds: float = 600.0) -> dict[str, Any]:
    """Validates a mesh file as `fabmesh check FILE --json`."""

def repair(vertices: ArrayLike, triangles: ArrayLike, *, max_deviation: float = 0.0, wrap: bool = False,
           weld_distance: Optional[float] = None, fill_holes: bool = True,
           max_seconds: float = 600.0) -> dict[str, Any]:
    """Repairs a mesh given as arrays (docs/repair.md): the report, with the result's "vertices" and "triangles"."""

def repair_file(path: StrPath, output: StrPath, *, max_deviation: float = 0.0, wrap: bool = False,
                weld_distance: Optional[float] = None, fill_holes: bool = True,
                max_seconds: float = 600.0) -> dict[str, Any]:
    """Repairs a mesh file into `output` as `fabmesh repair PATH -o OUTPUT --json`."""

def read_mesh(path: StrPath) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.int64], Optional[str]]:
    """Reads a mesh file: (vertices, triangles, units or None)."""

def write_mesh(path: StrPath, vertices: ArrayLike, triangles: ArrayLike, *, units: Optional[str] = None) -> None:
    """Writes a mesh in the format the extension names."""

def tbezier(points: ArrayLike, lam: float = 0.0, mu: float = 0.0) -> Curve: ...
def quasi_bspline(points: ArrayLike, lambdas: Optional[list[float]] = None) -> Curve: ...
def hbezier(points: ArrayLike, alpha: float = 1.0, lam: float = 0.0, mu: float = 0.0) -> Curve: ...
def composite(segments: list[dict[str, Any]], closed: bool = False, closing: str = "G0") -> Curve:
    """T-Bezier, H-Bezier and line segments with a design file's keys (family, points,
    lambda, mu, alpha, join, continuity). Raises InputError naming the segment."""
def fair(curve: Curve, energy: str = "curvature_variation", keeps: Optional[str] = None) -> Curve:
    """The curve with the shape parameters minimising 'strain' or 'curvature_variation',
    control points kept; keeps: the least continuity a joint may fall to."""
def optimize(design: Design) -> list[dict[str, Any]]:
    """The fairest shape parameters of the design's curves, as `fabmesh optimize --json`."""
