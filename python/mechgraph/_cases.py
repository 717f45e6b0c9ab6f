"""A sweep's cases from a pandas DataFrame or a dict of arrays, named as on the command line."""
from __future__ import annotations

import re
from typing import Any, List, Tuple

import numpy as np

_HEADER = re.compile(r"^\s*(?P<name>[^\[\]]*?)\s*(\[\s*(?P<unit>[^\[\]]*?)\s*\])?\s*$")


def split_header(column: str) -> Tuple[str, str]:
    """'cam.max_lift [mm]' -> ('cam.max_lift', 'mm'); 'rpm' -> ('rpm', '')."""
    m = _HEADER.match(str(column))
    if not m or not m["name"]:
        from ._errors import SceneError

        raise SceneError(f"cases: column {column!r}: expected 'name' or 'name [unit]'")
    return m["name"], m["unit"] or ""


def case_columns(cases: Any) -> Tuple[List[str], List[str], list]:
    """Names, units and columns (float64 arrays, or lists of text) of `cases`: a DataFrame, a dict
    of arrays or lists, or anything with ``items()``. Numbers are in the column's unit, or SI
    when the column names none; text cells are read as a cases file's ('6500 rpm', 'roller')."""
    if hasattr(cases, "columns") and hasattr(cases, "__getitem__"):  # a DataFrame
        items = [(c, cases[c].to_numpy()) for c in cases.columns]
    elif hasattr(cases, "items"):
        items = list(cases.items())
    else:
        raise TypeError("cases: expected a pandas DataFrame or a dict of arrays, got " + type(cases).__name__)
    names, units, columns = [], [], []
    seen = set()  # a set, not the list: a frame may have hundreds of thousands of columns
    for header, values in items:
        name, unit = split_header(header)
        if name in seen:
            from ._errors import SceneError

            raise SceneError(f"cases: column '{name}' appears twice")
        array = np.asarray(values)
        if array.ndim != 1:
            raise TypeError(f"cases: column '{header}' is not one-dimensional")
        if array.dtype.kind in "iuf":
            columns.append(np.ascontiguousarray(array, dtype=np.float64))
        elif array.dtype.kind == "b":
            raise TypeError(f"cases: column '{header}' holds True/False, not values")
        else:
            columns.append([str(v) for v in array.tolist()])
        names.append(name)
        seen.add(name)
        units.append(unit)
    if names and len({len(c) for c in columns}) != 1:
        from ._errors import SceneError

        raise SceneError("cases: the columns are not all as long")
    return names, units, columns
