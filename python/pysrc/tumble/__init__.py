"""tumble from Python: high-accuracy rigid-body dynamics.

The functions here call the same library code as the ``tumble`` command line, so a run gives
the same numbers, to the last bit, and a refused input the same reason:

* :func:`simulate` runs a built-in scene, a TOML scene file or a model (a file, its text, or a
  dict laid out like one, with SymPy expressions where the file has text) and returns a
  :class:`Simulation` whose columns are NumPy arrays (``.to_pandas()``, ``.to_polars()``);
  :func:`model_text` writes such a dict as a model file;
* :func:`sweep` runs a parameter sweep (a sweep file or a dict laid out like one) and returns
  its results as a DataFrame (pandas, or polars, or a dict of arrays);
* :func:`inertia` computes the mass properties of a closed triangle mesh (a file, or vertex and
  face arrays);
* :func:`scenes`, :func:`integrators` list what there is; :func:`work_precision` measures error
  against cost;
* :meth:`Simulation.plot` draws a run and :func:`plot` redraws a saved result (a run's CSV, a
  sweep, work–precision, long-run or hard-case atlas folder) with the figure code of the
  command line: the same result gives the same file, byte for byte.

Long runs release the GIL; Ctrl-C stops them at the next step and raises
``KeyboardInterrupt``. Inputs refused before any work raise ``ValueError`` (``TypeError`` for a
value of the wrong type), naming the argument or key; a run that fails raises
:class:`SimulationError` with the time and state it carries.
"""

from __future__ import annotations

import json
import os
import sys
from typing import Any, Callable, Dict, List, Mapping, Optional, Sequence, Union

import numpy as np

from . import _tumble
from ._tumble import SimulationError

__version__: str = _tumble.__version__

__all__ = [
    "Simulation",
    "SimulationError",
    "__version__",
    "inertia",
    "integrators",
    "model_text",
    "plot",
    "scenes",
    "simulate",
    "sweep",
    "work_precision",
]

PathLike = Union[str, "os.PathLike[str]"]


def _f64(raw: bytes) -> np.ndarray:
    return np.frombuffer(raw, dtype=np.float64).copy()


class Simulation:
    """The trajectory of one run and how it was made.

    ``result["t"]`` (or ``result.columns["t"]``) is a NumPy array of the column ``t``;
    ``result.names`` lists the columns in order (``t``, the coordinates, the rates, the
    diagnostics); ``coordinates`` and ``rates`` are the scene's coordinate and rate columns.

    ``record`` is the run's record, the dict ``tumble simulate -o FILE.csv`` writes as
    ``FILE.csv.json`` (the same type, the same keys; ``csv`` is empty and ``provenance`` is
    this process's). Each of its keys is also an attribute: ``scene``, ``origin``, ``frame``,
    ``parameters``, ``integrator``, ``dt`` or ``tol``, ``t_end``, ``every``, ``at``, ``rows``,
    ``steps``, ``evaluations``, ``reached_t``, ``max_energy_rel_err`` (the largest relative
    energy error over every step), ``energy_warning``, ``error_estimate``, ``wall_time_s``,
    ``provenance`` — except ``columns``, whose names are ``names`` here. ``version`` is
    ``provenance["tumble_version"]``.

    ``error_estimate`` is a dict: ``status`` (``'estimated'``, ``'off'`` with
    ``check=False``, or ``'failed'`` with the ``reason``); when estimated, ``final``, the
    estimated error of the final state, and ``max``, the largest over the compared rows (at
    ``max_t``), in the work–precision norm (``max |Δᵢ| / (1 + |yᵢ|)`` over the coordinates and
    rates); ``trust`` (``'trustworthy'``, ``'round-off'``, ``'within-tolerance'``,
    ``'not-trustworthy'`` or ``'unchecked'``) and ``trust_reason``; the ``companion`` and
    ``check`` settings that measured it and their cost.
    """

    scene: str
    origin: str
    frame: str
    parameters: Dict[str, float]
    integrator: str
    dt: Optional[float]
    tol: Optional[float]
    t_end: float
    every: int
    at: Optional[List[float]]
    rows: int
    steps: int
    evaluations: int
    reached_t: float
    max_energy_rel_err: float
    energy_warning: bool
    error_estimate: Dict[str, Any]
    wall_time_s: float
    provenance: Dict[str, Any]

    def __init__(self, raw: Dict[str, Any]) -> None:
        self.record: Dict[str, Any] = json.loads(raw["record"])
        for key, value in self.record.items():
            if key != "columns":
                setattr(self, key, value)
        # In the scene's declared order (the record's map is sorted by name).
        given = self.record["parameters"]
        self.parameters = {name: given[name] for name in raw["parameter_order"] if name in given}
        names: List[str] = list(self.record["columns"])
        rows: int = self.record["rows"]
        self._data: bytes = raw["data"]
        data = _f64(self._data)
        self.names: List[str] = names
        self.columns: Dict[str, np.ndarray] = {
            name: data[k * rows : (k + 1) * rows] for k, name in enumerate(names)
        }
        self.coordinates: List[str] = list(raw["coordinates"])
        self.rates: List[str] = list(raw["rates"])
        self.version: str = self.record["provenance"]["tumble_version"]

    def __getitem__(self, name: str) -> np.ndarray:
        try:
            return self.columns[name]
        except KeyError:
            raise KeyError(
                f"{name!r}: no such column; the columns are {', '.join(self.names)}"
            ) from None

    def __len__(self) -> int:
        return self.rows

    def __repr__(self) -> str:
        step = f"dt={self.dt}" if self.dt is not None else f"tol={self.tol}"
        return (
            f"<Simulation {self.scene}: {self.integrator}, {step}, t in [0, {self.t_end}], "
            f"{self.rows} rows x {len(self.names)} columns>"
        )

    def plot(
        self,
        path: PathLike,
        *,
        figure_size: Optional[str] = None,
        font_size: Optional[float] = None,
        dpi: Optional[float] = None,
        svg_text: str = "font",
    ) -> None:
        """Draw the run as ``tumble simulate --plot PATH`` does (PNG, SVG or PDF by the
        extension): the coordinates, rates and energy error against time, with the display
        symbols, units and log axes of the command line. The options are ``tumble``'s figure
        options: ``figure_size`` (``'single'``, ``'double'`` or ``'WxH'`` in in, cm or mm),
        ``font_size`` (pt), ``dpi``, ``svg_text`` (``'font'`` or ``'paths'``). The same run
        gives the same file as the command line, byte for byte."""
        _tumble.plot_run(
            self.scene,
            self.coordinates,
            self.rates,
            self.integrator,
            self.dt,
            self.tol,
            list(self.parameters.items()),
            self.names,
            self._data,
            self.rows,
            os.fspath(path),
            figure_size=figure_size,
            font_size=font_size,
            dpi=dpi,
            svg_text=svg_text,
        )

    def to_pandas(self) -> Any:
        """The columns as a ``pandas.DataFrame`` (needs pandas)."""
        import pandas as pd

        return pd.DataFrame({name: self.columns[name] for name in self.names})

    def to_polars(self) -> Any:
        """The columns as a ``polars.DataFrame`` (needs polars)."""
        import polars as pl

        return pl.DataFrame({name: self.columns[name] for name in self.names})


def _sympy_text(expr: Any) -> str:
    """A SymPy expression in the model language: ``^`` for powers, ``abs``, ``exp(1)`` for
    ``E``, floats to the last bit."""
    from sympy import S
    from sympy.printing.str import StrPrinter

    class _Printer(StrPrinter):  # type: ignore[misc]
        def _print_Pow(self, e: Any, rational: bool = False) -> str:
            if e.exp == S.Half:
                return f"sqrt({self._print(e.base)})"
            if e.exp == -1:
                return f"(1/({self._print(e.base)}))"
            return f"(({self._print(e.base)})^({self._print(e.exp)}))"

        def _print_Abs(self, e: Any) -> str:
            return f"abs({self._print(e.args[0])})"

        def _print_Exp1(self, e: Any) -> str:
            return "exp(1)"

        def _print_Rational(self, e: Any) -> str:
            return f"({e.p}/{e.q})"

        def _print_Float(self, e: Any) -> str:
            return repr(float(e))

    return str(_Printer().doprint(expr))


def _is_sympy(value: Any) -> bool:
    return type(value).__module__.split(".")[0] == "sympy"


def _plain(value: Any, key: str) -> Any:
    """A model dict's values as dicts, lists, numbers and text: SymPy numbers as floats, other
    SymPy expressions as text in the model language."""
    if isinstance(value, Mapping):
        return {k: _plain(v, f"{key}.{k}" if key else str(k)) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_plain(v, f"{key}[{i}]") for i, v in enumerate(value)]
    if _is_sympy(value):
        if getattr(value, "is_Number", False):
            return float(value)
        if getattr(value, "is_Symbol", False) or hasattr(value, "free_symbols"):
            return _sympy_text(value)
        raise TypeError(f"{key}: a SymPy {type(value).__name__} is not an expression")
    return value


def model_text(model: Mapping[str, Any]) -> str:
    """The text of a model file from a dict laid out like one.

    ``{"model": {"name": ...}, "parameters": {...}, "coordinates": {...}, "points": {...},
    "lagrangian": {...}, ...}``: the tables of a model file as dicts, its expressions as text
    or as SymPy expressions (printed in the model language: ``x**2`` as ``x^2``), numbers as
    numbers. ``simulate`` takes such a dict directly.
    """
    if not isinstance(model, Mapping):
        raise TypeError(f"model: expected a dict laid out like a model file, got {type(model).__name__}")
    return str(_tumble.toml_text(_plain(model, "")))


def simulate(
    scene: Union[PathLike, Mapping[str, Any]],
    params: Optional[Mapping[str, float]] = None,
    integrator: Optional[str] = None,
    dt: Optional[float] = None,
    tol: Optional[float] = None,
    t_end: Optional[float] = None,
    at: Optional[Sequence[float]] = None,
    *,
    every: Optional[int] = None,
    output_dt: Optional[float] = None,
    max_steps: Optional[int] = None,
    allow_coarse_step: bool = False,
    check: bool = True,
) -> Simulation:
    """Run a scene and return its trajectory, as ``tumble simulate`` does.

    ``scene`` is a built-in scene (:func:`scenes`), a TOML scene file or model file (a path
    ending in ``.toml`` or naming an existing file; ``tumble models`` lists the shipped models),
    the text of a model file itself, or a dict laid out like a model file (see
    :func:`model_text`; SymPy expressions accepted where the file has text). ``params`` sets parameters over the scene's (or the
    file's) values. ``integrator``, ``dt`` (fixed step) or ``tol`` (adaptive tolerance),
    ``t_end`` (horizon) override the file's ``[run]`` options and the scene's defaults. Rows:
    every step (or every ``every``-th), or at the times ``at`` or every ``output_dt`` seconds
    from dense output, and always the final state. ``max_steps`` caps the steps (default: the
    command line's ``--max-steps``, 10⁹).

    A fixed step that turns the initial rotation by more than 0.5 rad a step is refused unless
    ``allow_coarse_step=True``. The run's error is estimated (``Simulation.error_estimate``)
    by running it again at half the step (or a tolerance 100 times tighter) and at twice the
    step (or 100 times looser): about 2–3 times the run's cost; ``check=False`` skips it. Raises ``ValueError``/``TypeError`` for a refused input,
    :class:`SimulationError` when the run fails, ``KeyboardInterrupt`` on Ctrl-C.
    """
    text = model_text(scene) if isinstance(scene, Mapping) else os.fspath(scene)
    raw = _tumble.simulate(
        text,
        params=None if params is None else dict(params),
        integrator=integrator,
        dt=dt,
        tol=tol,
        t_end=t_end,
        at=None if at is None else [float(x) for x in at],
        every=every,
        output_dt=output_dt,
        allow_coarse_step=allow_coarse_step,
        check=check,
        **({} if max_steps is None else {"max_steps": max_steps}),
    )
    return Simulation(raw)


def _progress_bar(total_hint: Optional[int] = None) -> Callable[[int, int, int], None]:
    """A progress callback: a tqdm bar (notebook or terminal) if tqdm is installed, else a line
    on stderr rewritten in place."""
    try:
        from tqdm.auto import tqdm
    except ImportError:
        tqdm = None
    state: Dict[str, Any] = {}

    def update(finished: int, total: int, failed: int) -> None:
        if tqdm is not None:
            bar = state.get("bar")
            if bar is None:
                bar = state["bar"] = tqdm(total=total, unit="point", desc="sweep")
            bar.update(finished - bar.n)
            bar.set_postfix(failed=failed, refresh=False)
            if finished >= total:
                bar.close()
        else:
            end = "\n" if finished >= total else ""
            sys.stderr.write(f"\rsweep: {finished}/{total} points, {failed} failed{end}")
            sys.stderr.flush()

    return update


def plot(
    result: PathLike,
    path: PathLike,
    *,
    columns: Optional[Sequence[str]] = None,
    t_range: Optional[Sequence[float]] = None,
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
    """Redraw a saved result into ``path`` (PNG, SVG or PDF by the extension), as
    ``tumble plot RESULT -o PATH`` does and with the same code: the same result gives the same
    file, byte for byte.

    ``result`` is a run's CSV (``simulate -o FILE.csv``, its ``FILE.csv.json`` beside it), or a
    folder: a sweep (``sweep(..., output=DIR)`` or ``tumble sweep -o DIR``), a work–precision
    study, a long run (``work-precision --long``) or a hard-case atlas. A run: ``columns`` to
    draw and ``t_range=(t0, t1)``. A sweep: ``metric`` (by its name in ``results.csv``),
    ``figure`` (``'map'`` or ``'slices'``), ``slices``, ``log_colour``, ``colour_map``
    (``'viridis'``, ``'cividis'``, ``'magma'``, ``'grey'``). Figure options as for
    :meth:`Simulation.plot`.
    """
    _tumble.plot(
        os.fspath(result),
        os.fspath(path),
        columns=None if columns is None else list(columns),
        t_range=None if t_range is None else (float(t_range[0]), float(t_range[1])),
        metric=metric,
        figure=figure,
        slices=slices,
        log_colour=log_colour,
        colour_map=colour_map,
        figure_size=figure_size,
        font_size=font_size,
        dpi=dpi,
        svg_text=svg_text,
    )


def _frame(columns: Dict[str, np.ndarray], kind: str) -> Any:
    if kind == "pandas":
        import pandas as pd

        return pd.DataFrame(columns)
    if kind == "polars":
        import polars as pl

        return pl.DataFrame(columns)
    if kind == "dict":
        return columns
    raise ValueError(f"frame={kind!r}: give 'pandas', 'polars', 'dict' or None")


def _default_frame() -> str:
    for kind, module in (("pandas", "pandas"), ("polars", "polars")):
        try:
            __import__(module)
            return kind
        except ImportError:
            continue
    return "dict"


def sweep(
    file_or_dict: Union[PathLike, Mapping[str, Any]],
    threads: Optional[int] = None,
    output: Optional[PathLike] = None,
    resume: bool = False,
    *,
    allow_coarse_step: bool = False,
    progress: Union[bool, Callable[[int, int, int], None]] = True,
    frame: Optional[str] = None,
) -> Any:
    """Run a parameter sweep and return its results, one row per point, as ``tumble sweep``
    writes ``results.csv``: ``index`` (``level`` for a refined sweep), the axes, the metrics
    (NaN where undefined), ``status``, ``reason``.

    ``file_or_dict`` is a sweep file (TOML) or a dict laid out like one (``{"scene": ...,
    "axes": {...}, "run": {...}, "metrics": {...}}``). ``threads``: worker threads (default: the
    cores). ``output``: a folder for the journal and ``results.csv`` (default: a temporary
    folder, removed after); ``resume=True`` continues the sweep in ``output``. ``progress``:
    ``True`` shows a bar (tqdm in Jupyter or a terminal when installed, else a line on stderr),
    ``False`` nothing, or a callable ``f(finished, total, failed)``. ``frame``: ``'pandas'``,
    ``'polars'`` or ``'dict'`` (default: pandas if installed, else polars, else a dict of
    arrays). The result's ``attrs`` (pandas) hold the run's record.

    Ctrl-C stops the sweep (finished points stay in ``output``'s journal for ``resume=True``)
    and raises ``KeyboardInterrupt``.
    """
    spec: Any = dict(file_or_dict) if isinstance(file_or_dict, Mapping) else os.fspath(file_or_dict)
    callback = _progress_bar() if progress is True else (progress or None)
    raw = _tumble.sweep(
        spec,
        threads=threads,
        output=None if output is None else os.fspath(output),
        resume=resume,
        allow_coarse_step=allow_coarse_step,
        progress=callback,
    )
    columns: Dict[str, np.ndarray] = {}
    for name, kind, payload in raw.pop("columns"):
        if kind == "f64":
            columns[name] = _f64(payload)
        elif kind == "i64":
            columns[name] = np.frombuffer(payload, dtype=np.int64).copy()
        else:
            columns[name] = np.array(payload, dtype=object)
    result = _frame(columns, frame or _default_frame())
    if hasattr(result, "attrs"):
        result.attrs.update(raw)
    return result


def inertia(
    path_or_arrays: Union[PathLike, Sequence[Any]],
    density: Optional[float] = None,
    mass: Optional[float] = None,
) -> Dict[str, Any]:
    """Mass properties of a closed triangle mesh, as ``tumble inertia --json`` prints them.

    ``path_or_arrays`` is a mesh file (OBJ or STL) or a pair ``(vertices, faces)``: vertices an
    array of shape ``(N, 3)`` of floats (metres), faces an array of shape ``(M, 3)`` of integer
    vertex indices, counter-clockwise seen from outside. ``density`` (kg/m³) or ``mass`` (kg)
    sets the mass (default: density 1).

    Returns a dict: ``mass``, ``volume``, ``center_of_mass`` (3,), ``inertia`` (3, 3) about the
    centre of mass, ``principal_moments`` (3,) ascending, ``principal_axes`` (3, 3) whose
    columns are the axes, ``principal_euler_zyz`` (3,).
    """
    if isinstance(path_or_arrays, (str, os.PathLike)):
        raw = _tumble.inertia(path=os.fspath(path_or_arrays), density=density, mass=mass)
    else:
        if not isinstance(path_or_arrays, (tuple, list)) or len(path_or_arrays) != 2:
            raise TypeError(
                "path_or_arrays: expected a mesh file's path or a pair (vertices, faces)"
            )
        vertices = _mesh_array("vertices", path_or_arrays[0], "N", floating=True)
        faces = _mesh_array("faces", path_or_arrays[1], "M", floating=False)
        raw = _tumble.inertia(
            vertices=vertices.astype(np.float64).tobytes(),
            faces=faces.astype(np.int64).tobytes(),
            density=density,
            mass=mass,
        )
    return {
        key: np.array(value) if isinstance(value, (list, tuple)) else value
        for key, value in raw.items()
    }


def _mesh_array(name: str, value: Any, rows: str, floating: bool) -> np.ndarray:
    array = np.asarray(value)
    kind = "floats (float32 or float64)" if floating else "integers"
    if array.ndim != 2 or array.shape[1] != 3:
        raise ValueError(
            f"{name}: expected an array of shape ({rows}, 3) of {kind}, got shape {array.shape}"
        )
    ok = array.dtype.kind == "f" if floating else array.dtype.kind in "iu"
    if not ok:
        raise ValueError(
            f"{name}: expected an array of shape ({rows}, 3) of {kind}, got dtype {array.dtype}"
        )
    if array.dtype.kind == "u" and array.size and array.max() > np.iinfo(np.int64).max:
        raise ValueError(f"{name}: an index does not fit in 64 bits")
    return np.ascontiguousarray(array)


def scenes() -> List[Dict[str, Any]]:
    """The built-in scenes, as ``tumble scenes --json`` lists them: name, summary, coordinates,
    columns, parameters (name, default, unit, domain, description), conserved quantities,
    oracle, applicable integrators, the default run and ``recommended``: the methods for each
    purpose (an error band, a long horizon) with the measurement behind them."""
    return json.loads(_tumble.scenes_json())


def integrators() -> List[Dict[str, Any]]:
    """Every integrator, as ``tumble integrators --json`` lists them: name, order, family,
    properties, stages, problem, problems, summary, and the built-in scenes it runs."""
    return json.loads(_tumble.integrators_json())


def work_precision(
    scene: PathLike,
    params: Optional[Mapping[str, float]] = None,
    integrators: Optional[Sequence[str]] = None,
    t_end: Optional[float] = None,
    max_seconds: Optional[float] = None,
    *,
    frame: Optional[str] = None,
) -> Any:
    """Error at the final time against cost, per integrator, as ``tumble work-precision``
    measures it: a reference solution (cross-checked), then for each integrator a ladder of
    steps or tolerances until a run takes ``max_seconds`` (default: the command line's
    ``--max-seconds``, 0.5 s) or the error reaches round-off.

    Returns one row per run, with the columns of ``work-precision.csv`` (the same record
    type): ``integrator``, ``order`` (a number, ``'exact'`` or ``'variable'``), ``dt`` or
    ``tol`` (NaN for the other), ``steps``, ``evaluations``, ``error``, ``max_energy_rel_err``,
    ``wall_time_s``, ``repeats`` (timed runs), as a DataFrame (``frame`` as for :func:`sweep`);
    ``attrs`` (pandas) hold the reference and why each ladder stopped. Times depend on the
    machine and its load.
    """
    raw = _tumble.work_precision(
        os.fspath(scene),
        params=None if params is None else dict(params),
        integrators=None if integrators is None else list(integrators),
        t_end=t_end,
        **({} if max_seconds is None else {"max_seconds": max_seconds}),
    )
    rungs: List[Dict[str, Any]] = json.loads(raw.pop("rungs"))
    columns: Dict[str, np.ndarray] = {}
    for key in raw.pop("columns"):
        values = [r[key] for r in rungs]
        if any(isinstance(v, str) for v in values):
            columns[key] = np.array(values, dtype=object)
        elif all(isinstance(v, int) for v in values):
            columns[key] = np.array(values, dtype=np.int64)
        else:
            columns[key] = np.array([np.nan if v is None else v for v in values], dtype=np.float64)
    result = _frame(columns, frame or _default_frame())
    if hasattr(result, "attrs"):
        result.attrs.update(raw)
    return result
