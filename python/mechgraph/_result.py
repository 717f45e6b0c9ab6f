"""The result of one run: values by their ``node.port`` label, in SI or in the scene's units."""
from __future__ import annotations

import html
from typing import Any, Dict, Iterator, List, NamedTuple, Optional, Tuple

import numpy as np

from . import _core
from ._errors import SceneError, UnitError

#: ``units=`` of :meth:`Result.value` and :meth:`Result.table`: SI (the default), or the units the
#: scene shows values in (its ``units:``, else each port's own display unit, else SI).
SI_UNITS, DISPLAY_UNITS = "si", "display"


class Quantity(NamedTuple):
    """A scalar output: ``value`` in SI with its SI ``unit``, and the same in the unit a report
    shows it in (the scene's display unit or the port's; the SI unit when it has none), or in the
    unit asked of :meth:`Result.quantity`. ``frame`` is the angle it counts as its port declares
    it ('crank', 'cam'; '' when none), shown after degrees as the terminal and the report show it:
    ``54.4 deg (crank)``."""

    value: float
    unit: str
    display_value: float
    display_unit: str
    frame: str = ""

    def __str__(self) -> str:
        # six significant digits; rounding noise (an angle below 1e-9 of a turn) reads 0
        unit = _core.unit_with_reference(self.display_unit, self.frame)
        return f"{_core.shown_number(self.display_value, self.value, self.unit)} {unit}".rstrip()


def _column_label(name: str, unit: str, frame: str = "") -> str:
    """``name [unit]``; a unit of degrees carries the angle its column counts, as declared:
    ``opening [deg (cam)]`` (the CLI's CSV and the sweep's header write the same)."""
    unit = _core.unit_with_reference(unit, frame) if unit else unit
    return f"{name} [{unit}]" if unit else name


def _in_unit(values: Any, si_unit: str, unit: str, what: str) -> Any:
    """`values` (SI, of SI unit `si_unit`) in `unit`; UnitError for a unit of another dimension."""
    if not unit or unit == si_unit:
        return values
    scale, offset, unit_si = _core.unit_scale(unit)
    if unit_si != si_unit:
        raise UnitError(f"{what}: unit '{unit}' is {unit_si or 'dimensionless'} in SI, the value is {si_unit or 'dimensionless'}")
    return np.asarray(values) / scale - offset if not isinstance(values, float) else values / scale - offset


class Result:
    """What :meth:`Scene.run` returns: the outputs by ``node.port`` label.

    ``r["node.port"]`` is a float for a scalar (SI), a numpy array for a series (``r.axis(label)``
    gives its axis), a numpy structured array for a table (``r.table(label)`` as a DataFrame).
    :meth:`value` and :meth:`table` take ``units="display"`` for the scene's units; :meth:`quantity`
    gives a scalar with its units. ``keys()`` are the outputs asked for, then the cells of the
    scene's report; another output of the scene (``r.table("kurz.svaj")`` when the scene did not
    ask for it) is evaluated on first use with the run's own values (the memo cache makes that the
    work of what it adds). :meth:`report_tables` gives the report's tables as DataFrames.
    """

    __slots__ = ("_outcome", "_labels", "_asked", "_scene", "_sets", "_extra")

    def __init__(self, outcome: "_core.RunOutcome", scene: Any = None, sets: Optional[list] = None):
        self._outcome = outcome
        self._labels, self._asked = outcome.labels()
        self._scene = scene          # the Scene's session: evaluates outputs asked for later
        self._sets = sets or []      # the run's own values, as the session takes them
        self._extra: Dict[str, Any] = {}

    def _source(self, label: str) -> "_core.RunOutcome":
        """The outcome that holds `label`: this run's, or a run of just that output with this run's
        values. A label the scene does not have is a KeyError naming the valid ones."""
        if label in self._labels or self._scene is None or not isinstance(label, str) or "." not in label:
            return self._outcome
        outcome = self._extra.get(label)
        if outcome is None:
            try:
                outcome = self._scene.run(self._sets, [label], 1, False)
            except SceneError as e:
                raise KeyError(str(e)) from None
            self._extra[label] = outcome
        return outcome

    # ---- the mapping protocol over the outputs asked for ------------------------------------
    def keys(self) -> List[str]:
        """The outputs asked for, then the report's cells (a scene with only a report has those)."""
        return list(dict.fromkeys(self._labels))

    def __iter__(self) -> Iterator[str]:
        return iter(self.keys())

    def __len__(self) -> int:
        return len(self.keys())

    def __contains__(self, label: object) -> bool:
        return label in self._labels

    def items(self) -> List[Tuple[str, Any]]:
        """(label, value) for each of :meth:`keys`, values as ``r[label]`` gives them (SI)."""
        return [(k, self[k]) for k in self.keys()]

    def __getitem__(self, label: str) -> Any:
        value = self._source(label).value(label)
        if isinstance(value, dict):
            return _structured(value)
        return value

    def to_dict(self) -> Dict[str, Any]:
        """``dict(r.items())``: every output asked for by label, in SI."""
        return dict(self.items())

    # ---- one output --------------------------------------------------------------------------
    def kind(self, label: str) -> str:
        """'scalar', 'series', 'table' or 'handle' (a domain object such as a cam law)."""
        return self._source(label).kind(label)

    def unit(self, label: str) -> str:
        """The SI unit of an output ('' when dimensionless)."""
        return self._source(label).unit(label)

    def display_unit(self, label: str) -> str:
        """The unit the scene shows an output in: its ``units:``, else the port's own display unit,
        else the SI unit ('' when dimensionless). For a series, of its values."""
        return self._source(label).display_unit(label) or self.unit(label)

    def value(self, label: str, units: str = SI_UNITS) -> Any:
        """A scalar (float) or a series' values (numpy array): in SI (``units="si"``, the default),
        in the scene's units (``units="display"``, see :meth:`display_unit`), or in a unit given by
        name (``units="mm"``). A unit of another dimension is a :class:`UnitError`."""
        source = self._source(label)
        kind = source.kind(label)
        if kind not in ("scalar", "series"):
            raise TypeError(f"output '{label}' is a {kind}; use table('{label}')")
        value = source.value(label)
        if units == SI_UNITS:
            return value
        unit = self.display_unit(label) if units == DISPLAY_UNITS else units
        return _in_unit(value, source.unit(label), unit, f"output '{label}'")

    def quantity(self, label: str, unit: Optional[str] = None) -> Quantity:
        """A scalar with its SI unit and its display unit (or ``unit`` when given, e.g. 'mm').
        A unit of another dimension, or one that does not parse, is a :class:`UnitError`."""
        source = self._source(label)
        si = source.value(label)
        if not isinstance(si, float):
            raise TypeError(f"output '{label}' is a {self.kind(label)}, not a scalar")
        si_unit = source.unit(label)
        shown = unit if unit is not None else source.display_unit(label)
        frame = self.frame(label)
        if not shown:
            return Quantity(si, si_unit, si, si_unit, frame)
        return Quantity(si, si_unit, _in_unit(si, si_unit, shown, f"output '{label}'"), shown, frame)

    def frame(self, label: str) -> str:
        """The angle a scalar's or a series' values count, as its port declares it ('crank',
        'cam'; '' when it declares none or the values are no angle): what the terminal and the
        report show after degrees (``deg (crank)``). A table's are in ``table(label).attrs["frames"]``."""
        return self._source(label).declarations(label)["frames"][0]

    def axis(self, label: str, units: str = SI_UNITS) -> Tuple[np.ndarray, str, List[str]]:
        """A series' axis, the axis' unit and the element labels (may be empty): in SI, or with
        ``units="display"`` in the scene's unit for the axis."""
        source = self._source(label)
        axis, axis_unit, names = source.series_axis(label)
        if units == DISPLAY_UNITS:
            shown = source.shown_units(label)[1] or axis_unit
            return _in_unit(axis, axis_unit, shown, f"the axis of '{label}'"), shown, names
        return axis, axis_unit, names

    def table(self, label: str, units: str = SI_UNITS):
        """A table (or a series) as a pandas DataFrame, columns labelled ``name [unit]``: in SI
        (``units="si"``, the default) or in the scene's units (``units="display"``: its
        ``units:``, else each column's own display unit, else SI). A unit of degrees names the
        angle its column counts, as declared: ``opening [deg (cam)]``, ``crank_opening [deg
        (crank)]`` (the CLI's CSV and terminal do the same; radians carry no tag). ``attrs`` hold ``histogram``
        (bool), ``marks`` (reference values on the axis, such as a specification's limits, in
        the axis' unit of the frame) and ``frames`` (column label -> the angle it counts as its
        port declares it, 'crank'; columns that declare none are left out). A column of declared
        codes (an events table's ``event``) is followed by ``<name>_name``, the codes' names as a
        pandas Categorical, as the CLI's CSV has it; ``attrs["codes"]`` maps the column to
        ``{value: name}``."""
        import pandas as pd

        if units not in (SI_UNITS, DISPLAY_UNITS):
            raise ValueError(f"units: 'si' or 'display', not {units!r}")
        source = self._source(label)
        kind = source.kind(label)
        if kind == "series":
            axis, axis_unit, names = self.axis(label, units)
            values = self.value(label, units)
            unit = self.display_unit(label) if units == DISPLAY_UNITS else self.unit(label)
            declared = source.declarations(label)["frames"]  # values, axis
            frame = pd.DataFrame({_column_label("axis", axis_unit, declared[1]): axis,
                                  _column_label(label, unit, declared[0]): values})
            if names:
                frame.index = names
            frame.attrs["frames"] = {c: f for c, f in zip(frame.columns, [declared[1], declared[0]]) if f}
            return frame
        if kind != "table":
            raise TypeError(f"output '{label}' is a {kind}, not a table")
        value = source.value(label)
        columns = [value["axis"]] + value["channels"]
        shown = source.shown_units(label) if units == DISPLAY_UNITS else [""] * len(columns)
        declared = source.declarations(label)
        data, axis_shown, frames, codes = {}, columns[0]["unit"], {}, {}
        for i, (c, unit, tag, named) in enumerate(zip(columns, shown, declared["frames"], declared["codes"])):
            unit = unit or c["unit"]
            name = _column_label(c["name"], unit, tag)
            data[name] = _in_unit(c["values"], c["unit"], unit, f"'{label}', column '{c['name']}'")
            if tag:
                frames[name] = tag
            if named:  # the codes' names beside the numbers, as the CLI's CSV has them
                codes[name] = {v: n for v, n, _ in named}
                data[f"{c['name']}_name"] = pd.Categorical([codes[name].get(v, "") for v in c["values"]],
                                                            categories=list(dict.fromkeys(n for _, n, _ in named)))
            if i == 0:
                axis_shown = unit
        frame = pd.DataFrame(data)
        frame.attrs["frames"] = frames
        frame.attrs["codes"] = codes
        frame.attrs["histogram"] = value["histogram"]
        frame.attrs["marks"] = [(name, float(_in_unit(x, columns[0]["unit"], axis_shown, "a mark")))
                                for name, x in value["marks"]]
        return frame

    def table_marks(self, label: str) -> List[Tuple[str, float]]:
        """Reference values on a table's axis (a specification's limits), SI."""
        return list(self._source(label).value(label)["marks"])

    def report_tables(self):
        """The scene's report tables (``report:``) as pandas DataFrames, one per table: a row per
        report row (the index holds its label), a ``unit`` column, then one column of numbers per
        report column (NaN for an empty cell). A row is in the unit the page and the terminal show
        it in: its own ``unit:``, else the unit the table already shows that dimension in, else
        the scene's ``units:`` or its port's unit, else the reader's unit (mm, deg, mm/deg^n,
        mm^2, mm^2*deg, mm^2*s), else SI. ``attrs["title"]`` is the table's title. Empty when the run asked for
        other ``outputs=`` (the report is then not evaluated)."""
        import pandas as pd

        frames = []
        for title, columns, rows in self._outcome.report_tables():
            frame = pd.DataFrame([[unit] + [np.nan if v is None else v for v in values] for _, unit, values in rows],
                                 index=pd.Index([label for label, _, _ in rows], name=title or None),
                                 columns=["unit"] + list(columns))
            frame.attrs["title"] = title
            frames.append(frame)
        return frames

    # ---- how the run went --------------------------------------------------------------------
    @property
    def notes(self) -> List[Tuple[str, str]]:
        """(node, note): how nodes made their results (Monte Carlo samples and seed, ...)."""
        return self._outcome.notes()

    @property
    def work(self) -> Dict[str, Dict[str, Any]]:
        """Per node run: type, whether reused from the memo cache, seconds, work counters."""
        return self._outcome.work()

    @property
    def evaluated(self) -> List[str]:
        """Nodes evaluated by this run (not taken from the memo cache)."""
        return [n for n, w in self.work.items() if not w["reused"]]

    @property
    def seconds(self) -> float:
        """Wall time of the evaluation."""
        return self._outcome.seconds

    @property
    def provenance(self) -> Dict[str, Any]:
        """What the result was made from: program, scene, overrides, each node's type, plugin and
        parameters as used (SI), the plugins. Computed when asked for."""
        return self._outcome.provenance()

    # ---- how it shows ------------------------------------------------------------------------
    def _summary(self) -> List[Tuple[str, str, str]]:
        """(label, value as shown, kind) for each output asked for."""
        out = []
        for k in self.keys():
            kind = self.kind(k)
            if kind == "scalar":
                out.append((k, str(self.quantity(k)), kind))
            elif kind == "series":
                out.append((k, f"{len(self[k])} values", kind))
            elif kind == "table":
                value = self._outcome.value(k)
                out.append((k, f"{len(value['axis']['values'])} rows x {1 + len(value['channels'])} columns", kind))
            else:
                out.append((k, "", kind))
        return out

    def __repr__(self) -> str:
        summary = self._summary()
        shown = [f"{k}={v}" if kind == "scalar" else f"{k}=<{kind}: {v}>" for k, v, kind in summary[:4]]
        more = f", ... {len(summary) - 4} more" if len(summary) > 4 else ""
        return f"<Result of {len(summary)} outputs in {self.seconds * 1e3:.3g} ms: " + ", ".join(shown) + more + ">"

    def _repr_html_(self) -> str:
        e = html.escape
        rows = "".join(f"<tr><td style='text-align:left'><code>{e(k)}</code></td><td style='text-align:right'>{e(v)}</td>"
                       f"<td>{e(kind)}</td></tr>" for k, v, kind in self._summary())
        return (f"<div><b>mechgraph result</b>: {len(self)} outputs, {self.seconds * 1e3:.3g} ms"
                f"<table><thead><tr><th>output</th><th>value (display units)</th><th>kind</th></tr></thead>"
                f"<tbody>{rows}</tbody></table></div>")


def _structured(value: Dict[str, Any]) -> np.ndarray:
    columns = [value["axis"]] + value["channels"]
    dtype = [(c["name"], np.float64) for c in columns]
    out = np.empty(len(value["axis"]["values"]), dtype=dtype)
    for c in columns:
        out[c["name"]] = c["values"]
    return out
