"""A scene held in memory: built once, evaluated many times."""
from __future__ import annotations

import json
import os
from typing import Any, Dict, Iterable, Mapping, Optional, Sequence, Union

import numpy as np

from . import _core
from ._cases import case_columns
from ._errors import SceneError, SceneFileNotFoundError
from ._result import Result
from ._progress import _Bar, progress_bar
from ._units import SI, _is_unit_pair, is_pint, scene_value, set_entries

SetValue = Union[str, float, int, Sequence[float]]

# A run slower than this is run on a worker thread the next time, so Ctrl-C interrupts it; faster
# runs stay on the calling thread (a thread start would cost more than the 50 us overhead budget).
_INTERRUPTIBLE_AFTER_S = 0.01


class Scene:
    """A mechgraph scene. Make one with :meth:`load`, :meth:`from_text` or :meth:`from_dict`.

    The scene is parsed once; each choice of outputs and of the names given to ``set=`` builds its
    graph once, and a memo cache is kept across runs, so a run that changes one parameter evaluates
    only what depends on it."""

    def __init__(self, session: "_core.Session", source: tuple):
        self._session = session
        self._source = source  # ("file", path) or ("text", yaml, label): enough to rebuild it elsewhere
        self._interruptible = True

    # ---- making one --------------------------------------------------------------------------
    @classmethod
    def load(cls, path: Union[str, os.PathLike]) -> "Scene":
        """Reads a scene file (YAML, units in strings). Errors are SceneError naming
        file:line:column (``location``); a file that does not exist is a
        :class:`SceneFileNotFoundError`, which is also a FileNotFoundError."""
        path = os.fspath(path)
        try:
            return cls(_core.Session.load(path), ("file", path))
        except SceneError as e:
            if not os.path.exists(path):
                raise SceneFileNotFoundError(e.message, path) from None
            raise

    @classmethod
    def from_text(cls, yaml: str, name: str = "<text>") -> "Scene":
        """A scene from YAML text; `name` stands for the file in messages (relative files a node
        names are taken from the working directory). Bounded as a scene file is: more than 1 MiB
        of text (UTF-8) is refused with SceneError before any of it is read."""
        return cls(_core.Session.from_text(yaml, name), ("text", yaml, name))

    @classmethod
    def from_dict(cls, scene: Mapping[str, Any], name: str = "<dict>") -> "Scene":
        """A scene from a dict shaped like the YAML (``{"params": ..., "nodes": ..., "outputs": [...]}``),
        bounded as :meth:`from_text` is (the dict written as indented JSON, at most 1 MiB). Values
        are text with their units (``"8 mm"``) or pint quantities (written in SI base units); a
        bare number for a parameter with a dimension is refused as in a scene file."""
        return cls.from_text(json.dumps(scene, indent=1, default=scene_value), name)

    # pickling (dask): the scene travels as its text and is built again where it lands
    def __reduce__(self):
        if self._source[0] == "file":
            return (_rebuild, ("file", self._source[1]))
        return (_rebuild, self._source)

    # ---- what it is --------------------------------------------------------------------------
    @property
    def title(self) -> str:
        """The scene's ``title:`` ("" when it has none)."""
        return self._session.title

    @property
    def file(self) -> str:
        """The scene's file as given to :meth:`load`, or the `name` given to :meth:`from_text`."""
        return self._session.file

    @property
    def params(self) -> list:
        """The scene's parameters (names ``set=`` takes, besides ``node.param``)."""
        return self._session.params

    @property
    def outputs(self) -> list:
        """The outputs the scene asks for (``node.port``)."""
        return self._session.outputs

    def validate(self, *, max_work: Optional[float] = None, max_memory: Optional[float] = None) -> None:
        """Builds the scene against the loaded plugins and checks it, evaluating nothing
        (``mechgraph validate``), its work estimate within `max_work` and `max_memory` as
        :meth:`run` takes them. Raises SceneError."""
        self._session.validate(*_budget(max_work, max_memory))

    # ---- evaluating --------------------------------------------------------------------------
    def run(self, set: Optional[Mapping[str, SetValue]] = None, outputs: Optional[Iterable[str]] = None,
            threads: int = 1, si: bool = False, *, max_work: Optional[float] = None,
            max_memory: Optional[float] = None) -> Result:
        """Evaluates the scene and returns its :class:`Result`.

        set: values by name (a scene parameter ``rpm`` or a node's ``kurz.max_lift``), each with its
            unit: text as ``--set`` takes it (``"6500 rpm"``, a word such as ``"roller"``), a pair
            ``(9, "mm")``, a pint quantity, or a number marked SI with ``mechgraph.si(0.009)``. A
            1-D array goes to a list parameter (``table.angles``) the same ways:
            ``(angles_deg, "deg")``, a pint array, ``mechgraph.si(radians)``. A bare number is
            taken only for a dimensionless parameter (a count, a ratio); for one with a dimension
            it is refused (SceneError naming the dimension and the scene's unit), unless `si` is
            True. Refused as values: True/False and bool arrays, complex numbers, dates, times and
            durations (datetime, numpy datetime64/timedelta64, pandas), bytes, None.
        outputs: ``node.port`` labels instead of the scene's outputs and report; each one is then
            readable in the result (``r.table("kurz.svaj")``, which the scene may not ask for).
        threads: independent nodes evaluated at once.
        si: every bare number in `set` is in SI (m, rad, rad/s ...).
        max_work, max_memory: the work budget, as ``mechgraph run``'s ``--max-work`` (work items,
            default 1e9) and ``--max-memory`` (bytes, default 4 GiB): the run's estimate with the
            `set` values is checked first, and one beyond either is refused (SceneError naming the
            biggest term and the value to pass).
        """
        entries = set_entries(set, si)
        outcome = self._session.run(entries, list(outputs or []), threads, self._interruptible,
                                    *_budget(max_work, max_memory))
        result = Result(outcome, self._session, entries)
        self._interruptible = outcome.seconds > _INTERRUPTIBLE_AFTER_S
        return result

    def sweep(self, cases: Any, set: Optional[Mapping[str, SetValue]] = None, outputs: Optional[Iterable[str]] = None,
              threads: int = 0, si: bool = False, progress: Any = True, *, max_work: Optional[float] = None,
              max_memory: Optional[float] = None, _column_units: Optional[list] = None):
        """Runs one case per row of `cases` (a DataFrame, or a dict of arrays) on `threads` worker
        threads (0: one per core) with the GIL released, and returns the rows of
        ``mechgraph sweep --cases`` as a DataFrame: ``case``, the inputs, the outputs (columns
        ``name [unit]``, values in that unit), ``exit`` and ``error``; a failed case is a row with
        its exit class (2 scene, 3 evaluation) and message.

        Units: a column's header names the unit of its numbers as on the command line
        (``cam.max_lift [mm]``), or the values carry it (``(values, "mm")``, a pint quantity);
        numbers without a unit are taken only for a dimensionless parameter, or when marked SI
        (``mechgraph.si(values)``, or `si` True for every column); else SceneError. Text cells are
        read as a cases file's ("6500 rpm", "roller"): a column without a unit in its name is shown
        in the unit of its first number written with one (``rpm [rpm]``). Columns of dates or
        durations are refused.

        set: fixed values for every case, as :meth:`run` takes them (``{"rpm": "6000 rpm"}``);
            a text is taken as it is, never read as YAML.
        si: every number without a unit (in `cases` and `set`) is in SI.
        progress: a tqdm bar on stderr (or a Jupyter widget) once the sweep has run for a second
            (True, the default); False for none; or a callable ``progress(done, total)`` called
            about every 20 ms while cases run, and once more with the final count when they end.
        max_work, max_memory: the work budget of all the cases together, as ``mechgraph sweep``'s
            (default 1e12 work items, 4 GiB held by the threads at once).
        """
        # _column_units (mechgraph.dask.sweep): each column's unit as the whole sweep shows it, so
        # that a chunk names and shows its columns alike whatever its own first cells are.
        import pandas as pd

        names, units, marks, columns = case_columns(cases, si)
        total = len(columns[0]) if columns else 0
        bar = progress_bar(progress, total, "sweep " + (os.path.basename(self.file) if self.file else "scene"))
        try:
            (header, values), summary = self._session.sweep(names, units, marks, columns, set_entries(set, si),
                                                            list(outputs or []), int(threads), bar,
                                                            *_budget(max_work, max_memory), list(_column_units or []))
        except BaseException:
            if isinstance(bar, _Bar):
                bar.close()
            raise
        if isinstance(bar, _Bar):
            bar.close(summary["cases"])
        frame = pd.DataFrame(values, columns=header)
        frame.attrs["summary"] = summary
        return frame

    def study(self, parameters: Optional[Mapping[str, Any]] = None, *, samples: Optional[int] = None,
              method: Optional[str] = None, seed: Optional[int] = None, sensitivity: Optional[bool] = None,
              limits: Optional[Mapping[str, Any]] = None, events: Optional[Mapping[str, Any]] = None,
              set: Optional[Mapping[str, SetValue]] = None, outputs: Optional[Iterable[str]] = None,
              threads: int = 0, si: bool = False, settings: Optional[Mapping[str, Any]] = None,
              max_work: Optional[float] = None, max_memory: Optional[float] = None) -> "Study":
        """An uncertainty study of the scene, as ``mechgraph study`` runs it (docs/python.md).

        parameters: distributions by parameter name, as the scene's ``uncertainty: parameters:``
            writes them, e.g. ``{"lash": {"normal": {"mean": "0.25 mm", "sigma": "0.01 mm"}}}``;
            merged over the scene's block by name. limits, events, samples, method, seed and
            sensitivity replace the block's. Returns a Study (DataFrames: summary, quantiles,
            histograms, sobol, events, samples). The answers do not depend on `threads`.
        set: fixed values for every case, as :meth:`run` takes them (a bare number only for a
            dimensionless parameter, or with `si` True); not on a parameter given a distribution.
        settings: any other key of the block (confidence, bootstrap, quantiles, bins,
            correlations), replacing the block's.
        A value with a unit is text ("0.25 mm"), a pint quantity or a (number, unit) pair; a bare
        number only where the quantity is dimensionless (limits and thresholds included).
        max_work, max_memory: the work budget, as ``mechgraph study``'s (its cases and its
            bootstrap: default 1e12 work items; what it holds: default 4 GiB).
        """
        from ._study import Study

        args = _study_arguments(parameters, samples, method, seed, sensitivity, limits, events, set, outputs, si, settings)
        json_text, cases = self._session.study(args[0], args[1], args[2], args[3], args[4], args[5], int(threads),
                                               *_budget(max_work, max_memory))
        return Study(json_text, cases)

    def cache_info(self) -> Dict[str, int]:
        """Memo cache lookups of this scene's runs: hits and misses."""
        hits, misses = self._session.cache_counters()
        return {"hits": hits, "misses": misses}

    def clear_cache(self) -> None:
        """Empties this scene's memo cache: the next run evaluates every node it needs."""
        self._session.clear_cache()

    def __repr__(self) -> str:
        return f"Scene({self.title or self.file!r})"


def _budget(max_work: Any, max_memory: Any) -> tuple:
    """max_work and max_memory as the module takes them: 0.0 for the default, else a positive
    finite number (ValueError otherwise; TypeError for a bool or a non-number)."""
    values = []
    for name, value in (("max_work", max_work), ("max_memory", max_memory)):
        if value is None:
            values.append(0.0)
            continue
        if isinstance(value, bool) or not isinstance(value, (int, float, np.integer, np.floating)):
            raise TypeError(f"{name}: a number, not {type(value).__name__}")
        try:
            number = float(value)
        except OverflowError:
            number = float("inf")
        if not (number > 0.0 and np.isfinite(number)):
            raise ValueError(f"{name}: a positive finite number, not {value!r}")
        values.append(number)
    return tuple(values)


def _study_arguments(parameters, samples, method, seed, sensitivity, limits, events, set, outputs, si=False,
                     settings=None) -> tuple:
    """Scene.study's settings as the module takes them: the block as JSON text ("" for none), the
    fixed overrides (entries by the unit rule of ``set=``), samples, method and seed as text ("": the scene's), the outputs."""
    block: Dict[str, Any] = {}
    if settings is not None:
        if not hasattr(settings, "items"):
            raise TypeError("settings: expected a mapping of the uncertainty block's keys, got " + type(settings).__name__)
        for key, value in settings.items():
            if key in ("parameters", "limits", "events", "sensitivity", "samples", "method", "seed"):
                raise TypeError(f"settings: {key!r} has an argument of its own: study({key}=...)")
            block[str(key)] = _study_value(value, f"settings: {key}")
    if parameters:
        block["parameters"] = _study_value(dict(parameters), "parameters")
    for key, value in (("limits", limits), ("events", events), ("sensitivity", sensitivity)):
        if value is not None:
            block[key] = _study_value(value, key)
    if method is not None and method not in _STUDY_METHODS:
        raise ValueError(f"method: {method!r} is not a sampling method; valid: {', '.join(_STUDY_METHODS)}")
    return (json.dumps(block) if block else "", set_entries(set, si), _whole_text(samples, "samples", 2, 250_000_000),
            method or "", _whole_text(seed, "seed", 0, 2 ** 62), list(outputs or []))


_STUDY_METHODS = ("monte_carlo", "latin_hypercube", "sobol")


def _study_value(value: Any, context: str) -> Any:
    """A value of the study's block as its JSON takes it: a pint quantity or a (number, unit) pair
    as text with its unit ("50 g"; a Celsius temperature in degC), numpy numbers as numbers, numpy
    arrays as lists, mappings and lists value by value."""
    if isinstance(value, SI):
        raise TypeError(f"{context}: a study's value carries its unit ('50 g', a pint quantity or (50, 'g')); "
                        "mechgraph.si() is for set=")
    if hasattr(value, "items"):
        return {str(k): _study_value(v, f"{context}: {k}") for k, v in value.items()}
    if is_pint(value) and not getattr(value, "_is_multiplicative", True):
        # A temperature on an offset scale: a level (a mean, a limit) or a width (a sigma, a
        # tolerance), which only the study's reader tells apart; so it goes as written, not
        # converted to kelvin as a level (5 degC of sigma is 5 K, not 278.15 K).
        if str(value.units) != "degree_Celsius" or np.ndim(value.magnitude):
            raise TypeError(f"{context}: {value!r} is on an offset temperature scale mechgraph reads only as one "
                            "number in degC: give it in degC or K")
        return f"{float(value.magnitude)!r} degC"
    if is_pint(value) or _is_unit_pair(value):
        return scene_value(value) if is_pint(value) else f"{value[0]!r} {value[1]}".strip()
    if isinstance(value, np.ndarray):
        return [_study_value(v, context) for v in value.tolist()]
    if isinstance(value, (list, tuple)):
        return [_study_value(v, context) for v in value]
    if isinstance(value, np.generic):
        return value.item()
    return value


def _whole_text(value: Any, name: str, low: int, high: int) -> str:
    """samples= or seed= as the module's text ("" for the scene's): a whole number in [low, high],
    never rounded."""
    if value is None:
        return ""
    if isinstance(value, bool) or not isinstance(value, (int, np.integer, float, np.floating)) or \
            not float(value).is_integer():
        raise TypeError(f"{name}: expected a whole number, got {value!r}")
    if not low <= int(value) <= high:
        raise ValueError(f"{name}: {int(value)} is not from {low} to {high}")
    return str(int(value))


def _rebuild(kind: str, *args: str) -> Scene:
    if kind == "file":
        return Scene.load(args[0])
    return Scene.from_text(*args)
