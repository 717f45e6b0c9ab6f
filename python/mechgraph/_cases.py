"""A sweep's cases from a pandas DataFrame or a dict of arrays, named as on the command line."""
from __future__ import annotations

import re
from typing import Any, List, Tuple

import numpy as np

from . import _core
from ._units import column_entry

_HEADER = re.compile(r"^\s*(?P<name>[^\[\]]*?)\s*(\[\s*(?P<unit>[^\[\]]*?)\s*\])?\s*$")


def split_header(column: str) -> Tuple[str, str]:
    """'cam.max_lift [mm]' -> ('cam.max_lift', 'mm'); 'rpm' -> ('rpm', ''). A unit of degrees with
    the angle it counts, as mechgraph's labels write it ('deg (crank)'), is read without it: the
    reference names the angle, not a scale (as a cases file's header)."""
    m = _HEADER.match(str(column))
    if not m or not m["name"]:
        from ._errors import SceneError

        raise SceneError(f"cases: column {column!r}: expected 'name' or 'name [unit]'")
    return m["name"], _core.unit_without_reference(m["unit"] or "")


def case_columns(cases: Any, si: bool = False) -> Tuple[List[str], List[str], List[bool], list]:
    """Names, units, SI marks and columns of `cases`: a DataFrame, a dict of arrays or lists, or
    anything with ``items()``. A column's unit is in its header (``lift [mm]``), or comes with its
    values (``(values, "mm")``, a pint quantity); ``mechgraph.si(values)`` or `si` marks numbers
    without a unit as SI (_units.py). The columns go to the C++ side, where one conversion
    (python_values.cpp) reads every kind of value the same way as ``set=`` does: numbers in the
    column's unit; numbers without one only for a dimensionless parameter or when marked SI; text
    cells read as a cases file's ('6500 rpm', 'roller'). Refused there, naming the column:
    True/False, complex numbers, dates, times and durations (numpy datetime64/timedelta64, pandas),
    bytes, None and NA."""
    if hasattr(cases, "columns") and hasattr(cases, "__getitem__"):  # a DataFrame
        items = [(c, cases[c]) for c in cases.columns]
    elif hasattr(cases, "items"):
        items = list(cases.items())
    else:
        raise TypeError("cases: expected a pandas DataFrame or a dict of arrays, got " + type(cases).__name__)
    names, units, marks, columns = [], [], [], []
    seen = set()  # a set, not the list: a frame may have hundreds of thousands of columns
    for header, values in items:
        name, unit = split_header(header)
        if name in seen:
            from ._errors import SceneError

            raise SceneError(f"cases: column '{name}' appears twice")
        values, unit, marked = column_entry(str(header), unit, values, si)
        columns.append(_as_column(values))
        names.append(name)
        seen.add(name)
        units.append(unit)
        marks.append(marked)
    return names, units, marks, columns


def _as_column(values: Any) -> Any:
    """A column that can be sliced (dask's chunks) with its cells' kinds kept: a list, a tuple or a
    numpy array as it is (a list mixing True and 1.0 must not become floats); a pandas Series as its
    numpy values (datetime64 stays datetime64, to be refused); anything else through numpy."""
    if isinstance(values, (list, tuple, np.ndarray)):
        return values
    if hasattr(values, "to_numpy"):
        return values.to_numpy()
    return np.asarray(values)
