"""Units that cannot slip: how a value from Python says its unit.

A number for a parameter with a dimension must carry its unit or be marked as SI; the C++ side
(python/src/unit_rule.cpp) refuses a bare one with a message naming the dimension and the scene's
unit. This module turns what Python code may hand over into (value, unit, si):

- text: ``"9 mm"``, ``"6500 rpm"``, a word (``"roller"``);
- a number or array with its unit: ``(9, "mm")``, ``(angles_deg, "deg")``;
- a pint quantity (scalar or array), converted to its SI base units;
- a number or array marked SI: :func:`si` ``(0.009)``, or every bare number with ``si=True``;
- a bare number: taken as it is only for a dimensionless parameter (a count, a ratio).
"""
from __future__ import annotations

from typing import Any, List, Tuple

import numpy as np

from ._errors import SceneError

__all__ = ["si", "SI"]

# pint's SI base units (to_base_units) as mechgraph writes them; mechgraph has no other base.
_PINT_BASE = {"meter": "m", "kilogram": "kg", "second": "s", "radian": "rad", "kelvin": "K"}


class SI:
    """A number or an array marked as being in SI (m, rad, s, kg, N, Pa, rad/s ...): made by
    :func:`mechgraph.si`. ``value`` is what was marked."""

    __slots__ = ("value",)

    def __init__(self, value: Any):
        if isinstance(value, SI):
            value = value.value
        if is_pint(value):
            raise TypeError("mechgraph.si: a pint quantity carries its own unit; give it as it is")
        if isinstance(value, (str, bytes)):
            raise TypeError("mechgraph.si: text carries its own unit ('9 mm'); si() marks numbers")
        self.value = value

    def __repr__(self) -> str:
        return f"mechgraph.si({self.value!r})"


def si(value: Any) -> SI:
    """Marks a number (or a 1-D array, for a list parameter or a sweep column) as being in SI:
    ``scene.run(set={"kurz.max_lift": mechgraph.si(0.009)})`` is 9 mm. Without a mark, a bare number
    for a parameter with a dimension is refused, since 9 could mean mm as well as m."""
    return SI(value)


def is_pint(value: Any) -> bool:
    """Whether `value` is a pint Quantity (duck-typed: pint need not be imported)."""
    return hasattr(value, "to_base_units") and hasattr(value, "magnitude") and hasattr(value, "units")


def _pint_parts(q: Any, context: str) -> Tuple[Any, str]:
    """A pint quantity as (magnitude in SI base units, mechgraph's text of those units)."""
    base = q.to_base_units()
    items = base.unit_items() if hasattr(base, "unit_items") else base._units.items()
    parts = []
    for name, power in items:
        symbol = _PINT_BASE.get(name)
        if symbol is None:
            raise SceneError(f"{context}: the pint quantity {q!r} is in {name}, which mechgraph does not know "
                             f"(its units are of length, mass, time, angle and temperature)")
        p = float(power)
        if not p.is_integer():
            raise SceneError(f"{context}: the pint quantity {q!r} has a fractional power of {name}")
        parts.append(symbol if p == 1 else f"{symbol}^{int(p)}")
    magnitude = base.magnitude
    if isinstance(magnitude, (list, tuple)):
        magnitude = np.asarray(magnitude)
    return magnitude, "*".join(parts)


def _is_unit_pair(value: Any) -> bool:
    return isinstance(value, tuple) and len(value) == 2 and isinstance(value[1], str) and not isinstance(value[0], str)


def set_entry(name: str, value: Any, si_all: bool) -> Tuple[str, Any, str, bool]:
    """One ``set=`` entry as the C++ side takes it: (name, value, unit, si)."""
    context = f"set {name}"
    if isinstance(value, SI):
        return name, value.value, "", True
    if is_pint(value):
        magnitude, unit = _pint_parts(value, context)
        return name, magnitude, unit, False
    if _is_unit_pair(value):
        number, unit = value
        if isinstance(number, SI) or is_pint(number):
            raise SceneError(f"{context}: ({number!r}, {unit!r}) gives two units; give one")
        return name, number, unit.strip(), False
    return name, value, "", bool(si_all)


def set_entries(sets: Any, si_all: bool) -> List[Tuple[str, Any, str, bool]]:
    """``set=`` (a mapping) as a list of entries for the C++ side."""
    if sets is None:
        return []
    if not hasattr(sets, "items"):
        raise TypeError("set: expected a mapping of names to values, got " + type(sets).__name__)
    # text, the common case, without the checks below (a run's whole overhead is a few microseconds)
    return [(k, v, "", False) if type(v) is str and type(k) is str else set_entry(str(k), v, si_all)
            for k, v in sets.items()]


def column_entry(header: str, unit: str, values: Any, si_all: bool) -> Tuple[Any, str, bool]:
    """A sweep's column as (values, unit, si): the unit from the header, from a (values, unit) pair
    or a pint quantity; marked SI by :func:`si` or ``si=True``. Cells of a column of objects that are
    pint quantities or (number, unit) pairs become text ("9 mm")."""
    context = f"cases: column {header!r}"
    given = None
    if isinstance(values, SI):
        values, marked = values.value, True
    else:
        marked = False
    if is_pint(values):
        values, given = _pint_parts(values, context)
        values = np.atleast_1d(values)
    elif _is_unit_pair(values):
        values, given = values
    if given is not None:
        if unit:
            raise SceneError(f"{context}: the header names the unit [{unit}] and the values carry {given!r}; give one")
        unit = given.strip()
    elif isinstance(values, (list, tuple)) or (isinstance(values, np.ndarray) and values.dtype == object):
        values = [_cell(v, context) for v in values]
    return values, unit, marked or bool(si_all)


def _cell(value: Any, context: str) -> Any:
    if is_pint(value):
        magnitude, unit = _pint_parts(value, context)
        return f"{float(magnitude)!r} {unit}".strip()
    if _is_unit_pair(value):
        return f"{value[0]} {value[1]}"
    return value


def scene_value(value: Any) -> Any:
    """A value of a scene given as a dict (``Scene.from_dict``) as JSON writes it: a pint quantity
    as text in SI base units ("0.009 m"), numpy numbers and arrays as numbers and lists."""
    if is_pint(value):
        magnitude, unit = _pint_parts(value, "scene")
        if np.ndim(magnitude):
            return [f"{float(x)!r} {unit}".strip() for x in np.asarray(magnitude).ravel()]
        return f"{float(magnitude)!r} {unit}".strip()
    if isinstance(value, SI):
        raise TypeError("a scene's value is text with its unit ('9 mm') or a pint quantity; mechgraph.si() is for set=")
    if isinstance(value, np.generic):
        return value.item()
    if isinstance(value, np.ndarray):
        return value.tolist()
    raise TypeError(f"a scene's value cannot be a {type(value).__name__}")
