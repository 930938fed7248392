"""Type stubs of the native module ``tumble._tumble`` (the raw results the ``tumble``
package turns into NumPy arrays and DataFrames)."""

from typing import Any, Callable, Dict, List, Optional, Tuple, Union

__version__: str

class SimulationError(RuntimeError):
    """A run that failed: a model or integration error, with the time and state it carries."""

def simulate(
    scene: str,
    params: Optional[Dict[str, float]] = None,
    integrator: Optional[str] = None,
    dt: Optional[float] = None,
    tol: Optional[float] = None,
    t_end: Optional[float] = None,
    at: Optional[List[float]] = None,
    every: Optional[int] = None,
    output_dt: Optional[float] = None,
    max_steps: int = ...,
    allow_coarse_step: bool = False,
    check: bool = True,
) -> Dict[str, Any]:
    """``record``: the run's record as JSON text (the ``FILE.csv.json`` of ``tumble simulate``,
    its ``columns`` and ``rows`` included); ``data``: the columns one after the other,
    native-endian float64 bytes, ``rows`` values each; the scene's ``coordinates`` and
    ``rates``; ``parameter_order``: the parameters' names in the scene's order."""

def plot(
    input: str,
    output: str,
    *,
    columns: Optional[List[str]] = None,
    t_range: Optional[Tuple[float, float]] = None,
    metric: Optional[str] = None,
    figure: str = "map",
    slices: int = 5,
    log_colour: bool = False,
    colour_map: str = "viridis",
    figure_size: Optional[str] = None,
    font_size: Optional[float] = None,
    dpi: Optional[float] = None,
    svg_text: str = "font",
) -> None:
    """``tumble plot INPUT -o OUTPUT``: a saved result redrawn."""

def plot_run(
    scene: str,
    coordinates: List[str],
    rates: List[str],
    integrator: str,
    dt: Optional[float],
    tol: Optional[float],
    parameters: List[Tuple[str, float]],
    columns: List[str],
    data: bytes,
    rows: int,
    output: str,
    *,
    figure_size: Optional[str] = None,
    font_size: Optional[float] = None,
    dpi: Optional[float] = None,
    svg_text: str = "font",
) -> None:
    """The ``simulate --plot`` figure of a run held in memory (``data`` as :func:`simulate`
    returns it)."""

def work_precision(
    scene: str,
    params: Optional[Dict[str, float]] = None,
    integrators: Optional[List[str]] = None,
    t_end: Optional[float] = None,
    max_seconds: float = ...,
) -> Dict[str, Any]:
    """The reference; ``rungs``, JSON text of a list of rows (a dict per run, keyed as the
    columns of ``work-precision.csv``); ``columns``, those keys in order; ``stopped`` (why each
    ladder stopped)."""

def scenes_json() -> str:
    """``tumble scenes --json``."""

def integrators_json() -> str:
    """``tumble integrators --json``."""

def toml_text(table: Dict[str, Any]) -> str:
    """A dict laid out like a TOML file (a model file), as TOML text."""

def sweep(
    spec: Union[str, Dict[str, Any]],
    threads: Optional[int] = None,
    output: Optional[str] = None,
    resume: bool = False,
    allow_coarse_step: bool = False,
    progress: Optional[Callable[[int, int, int], None]] = None,
) -> Dict[str, Any]:
    """The run's record and ``columns``: ``(name, kind, payload)`` with kind ``f64``/``i64``
    (native-endian bytes) or ``str`` (a list)."""

def inertia(
    path: Optional[str] = None,
    vertices: Optional[bytes] = None,
    faces: Optional[bytes] = None,
    density: Optional[float] = None,
    mass: Optional[float] = None,
) -> Dict[str, Union[float, List[float], List[List[float]]]]:
    """Mass properties; ``vertices`` (float64) and ``faces`` (int64) as native-endian bytes of
    ``(N, 3)`` and ``(M, 3)`` arrays."""
