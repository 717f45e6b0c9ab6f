"""The result of one run: values in SI by their ``node.port`` label."""
from __future__ import annotations

from typing import Any, Dict, Iterator, List, NamedTuple, Optional, Tuple

import numpy as np

from . import _core


class Quantity(NamedTuple):
    """A scalar output: ``value`` in SI with its SI ``unit``, and the same in the unit a report
    shows it in (the port's or the scene's display unit; the SI unit when it has none)."""

    value: float
    unit: str
    display_value: float
    display_unit: str

    def __str__(self) -> str:
        return f"{self.display_value:.6g} {self.display_unit}".rstrip()


def _column_label(column: Dict[str, Any]) -> str:
    return f"{column['name']} [{column['unit']}]" if column["unit"] else column["name"]


class Result:
    """What ``Scene.run`` returns. ``r["node.port"]`` is a float for a scalar (SI), a numpy array
    for a series (its values; ``r.axis(name)`` gives the axis), a numpy structured array for a table
    (axis and channels as fields; ``r.table(name)`` as a pandas DataFrame). ``keys()`` are the
    outputs asked for, then the cells of the scene's report."""

    __slots__ = ("_outcome", "_labels", "_asked")

    def __init__(self, outcome: "_core.RunOutcome"):
        self._outcome = outcome
        self._labels, self._asked = outcome.labels()

    # mapping protocol over the outputs asked for
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
        return [(k, self[k]) for k in self.keys()]

    def __getitem__(self, label: str) -> Any:
        value = self._outcome.value(label)
        if isinstance(value, dict):
            return _structured(value)
        return value

    def kind(self, label: str) -> str:
        """'scalar', 'series', 'table' or 'handle'."""
        return self._outcome.kind(label)

    def unit(self, label: str) -> str:
        """The SI unit of an output ('' when dimensionless)."""
        return self._outcome.unit(label)

    def quantity(self, label: str, unit: Optional[str] = None) -> Quantity:
        """A scalar with its SI unit and display unit (or ``unit`` when given, e.g. 'mm')."""
        si = self._outcome.value(label)
        if not isinstance(si, float):
            raise TypeError(f"output '{label}' is a {self.kind(label)}, not a scalar")
        si_unit = self._outcome.unit(label)
        shown = unit if unit is not None else self._outcome.display_unit(label)
        if not shown:
            return Quantity(si, si_unit, si, si_unit)
        return Quantity(si, si_unit, self._outcome.in_unit(label, shown), shown)

    def axis(self, label: str) -> Tuple[np.ndarray, str, List[str]]:
        """A series' axis (SI), the axis' SI unit and the element labels (may be empty)."""
        return self._outcome.series_axis(label)

    def table(self, label: str):
        """A table (or a series) as a pandas DataFrame in SI, columns labelled ``name [unit]``."""
        import pandas as pd

        if self.kind(label) == "series":
            axis, axis_unit, names = self.axis(label)
            unit = self.unit(label)
            frame = pd.DataFrame({f"axis [{axis_unit}]" if axis_unit else "axis": axis,
                                  f"{label} [{unit}]" if unit else label: self[label]})
            if names:
                frame.index = names
            return frame
        value = self._outcome.value(label)
        if not isinstance(value, dict):
            raise TypeError(f"output '{label}' is a {self.kind(label)}, not a table")
        columns = [value["axis"]] + value["channels"]
        frame = pd.DataFrame({_column_label(c): c["values"] for c in columns})
        frame.attrs["histogram"] = value["histogram"]
        frame.attrs["marks"] = list(value["marks"])
        return frame

    def table_marks(self, label: str) -> List[Tuple[str, float]]:
        """Reference values on a table's axis (a specification's limits), SI."""
        return list(self._outcome.value(label)["marks"])

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

    def to_dict(self) -> Dict[str, Any]:
        return dict(self.items())

    def __repr__(self) -> str:
        parts = []
        for k in self.keys():
            kind = self.kind(k)
            parts.append(f"{k}={self.quantity(k)}" if kind == "scalar" else f"{k}=<{kind}>")
        return "Result(" + ", ".join(parts) + ")"


def _structured(value: Dict[str, Any]) -> np.ndarray:
    columns = [value["axis"]] + value["channels"]
    dtype = [(c["name"], np.float64) for c in columns]
    out = np.empty(len(value["axis"]["values"]), dtype=dtype)
    for c in columns:
        out[c["name"]] = c["values"]
    return out
