"""The errors mechgraph raises: the command line's message, its exit class, and what the error is
about as data (never parsed from the message): ``location``, ``node``, ``parameter``."""
from __future__ import annotations

import errno
from typing import Optional, Tuple


class MechgraphError(Exception):
    """Base class of mechgraph's errors. ``message`` is the command line's message for the same
    failure, ``exit_code`` its exit code (2 scene or usage, 3 evaluation, 4 plugin load, 5 writing
    results). What the error is about, as data carried from the C++ error (None when it names none):

    - ``location``: ``(file, line, column)`` in the scene file (or the name given to
      ``Scene.from_text``), 1-based;
    - ``node``: the node's name;
    - ``parameter``: the parameter's name (a node's own, or the name given to ``set=``).
    """

    exit_code = 1
    location: Optional[Tuple[str, int, int]] = None
    node: Optional[str] = None
    parameter: Optional[str] = None

    def __init__(self, message: str):
        super().__init__(message)
        self.message = message


class SceneError(MechgraphError, ValueError):
    """The scene, or a value given to it, is wrong (exit code 2): a YAML or shape error, an unknown
    name (the message lists the valid ones), a value of the wrong dimension, out of range or
    without its unit, bad cases. ``location`` is set when the error stands at a place in the
    scene's text."""

    exit_code = 2


class SceneFileNotFoundError(SceneError, FileNotFoundError):
    """:meth:`Scene.load` of a file that does not exist: a SceneError (exit code 2, the command
    line's message) that is also a FileNotFoundError (``errno`` ENOENT, ``filename``)."""

    def __init__(self, message: str, filename: str = ""):
        FileNotFoundError.__init__(self, errno.ENOENT, message, filename)
        self.message = message

    def __str__(self) -> str:
        return self.message


class UnitError(MechgraphError, ValueError):
    """A unit that does not parse, or is of another dimension than the value it is asked for
    (``Result.quantity(label, "deg")`` of a length; ``Result.value``, ``Result.table`` with
    ``units=`` likewise). Exit code 2, as a wrong unit in a scene."""

    exit_code = 2


class EvaluationError(MechgraphError, ArithmeticError):
    """A node failed (exit code 3): an infeasible design, a non-finite result. ``node`` names it;
    ``parameter`` the parameter the node blamed, when it named one; ``location`` where that
    parameter (else the node) is written in the scene."""

    exit_code = 3


class PluginError(MechgraphError, ImportError):
    """A plugin could not be loaded (exit code 4): a refused file, an ABI mismatch, none found."""

    exit_code = 4
