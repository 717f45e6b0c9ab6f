"""The errors mechgraph raises: the command line's message, its exit class and, for a scene, where."""
from __future__ import annotations

import re

_LOCATION = re.compile(r"^(?P<file>[^\n]*?):(?P<line>\d+):(?P<column>\d+): ")
_NODE = re.compile(r"node '(?P<node>[^']+)'")


class MechgraphError(Exception):
    """Base class of mechgraph's errors. ``exit_code`` is the command line's exit code for the same
    failure (2 scene or usage, 3 evaluation, 4 plugin load, 5 writing results)."""

    exit_code = 1

    def __init__(self, message: str):
        super().__init__(message)
        self.message = message


class SceneError(MechgraphError, ValueError):
    """The scene (or a value given to it) is wrong: ``location`` is ``(file, line, column)`` when
    the message starts with one, else None."""

    exit_code = 2

    def __init__(self, message: str):
        super().__init__(message)
        m = _LOCATION.match(message)
        self.location = (m["file"], int(m["line"]), int(m["column"])) if m else None


class EvaluationError(MechgraphError, ArithmeticError):
    """A node failed (an infeasible design, a non-finite result): ``node`` names it when the message does."""

    exit_code = 3

    def __init__(self, message: str):
        super().__init__(message)
        m = _NODE.search(message)
        self.node = m["node"] if m else None


class PluginError(MechgraphError, ImportError):
    """A plugin could not be loaded (refused file, ABI mismatch, none found)."""

    exit_code = 4
