"""Progress of long sweeps: a tqdm bar (python3-tqdm) in notebooks and terminals.

A bar appears only once a sweep has run for ``delay`` seconds (1 s), so short sweeps print
nothing; in a Jupyter kernel with ipywidgets it is a widget, else text on stderr (which Jupyter
shows in place as well). Without tqdm there is no bar and no error.
"""
from __future__ import annotations

import sys
import time
from typing import Any, Callable, Optional, Union

#: Seconds a sweep runs before its bar appears.
DELAY_S = 1.0


def _bar_class() -> Any:
    try:
        from tqdm import std
    except ImportError:
        return None
    try:
        shell = sys.modules["IPython"].get_ipython()
        if shell is not None and "IPKernelApp" in shell.config:
            import ipywidgets  # noqa: F401  (tqdm.notebook's widget)
            from tqdm import notebook

            return notebook.tqdm
    except Exception:
        pass
    return std.tqdm


class _Bar:
    """progress(done, total) for the C++ sweep: makes the bar on first call, updates it after."""

    def __init__(self, total: int, description: str, make: Any):
        self._started = time.monotonic()  # the delay counts from the sweep's start, not the first call
        self._bar = None
        self._total = total
        self._description = description
        self._make = make

    def __call__(self, done: int, total: int) -> None:
        if self._bar is None:
            delay = max(0.0, DELAY_S - (time.monotonic() - self._started))
            self._bar = self._make(total=total, desc=self._description, unit="case", delay=delay,
                                   file=sys.stderr, leave=True, dynamic_ncols=True)
        if done > self._bar.n:
            self._bar.update(done - self._bar.n)  # update() keeps to tqdm's delay and refresh interval

    def close(self, done: Optional[int] = None) -> None:
        if self._bar is not None:
            if done is not None and done > self._bar.n:
                self._bar.update(done - self._bar.n)
            self._bar.close()


def progress_bar(progress: Union[bool, Callable[[int, int], None], None], total: int, description: str) -> Any:
    """What Scene.sweep hands the C++ side: None (no bar), the caller's own callable
    ``progress(done, total)``, or a tqdm bar (``progress=True``, the default)."""
    if progress is None or progress is False or total == 0:
        return None
    if callable(progress) and progress is not True:
        return progress
    make = _bar_class()
    return _Bar(total, description, make) if make is not None else None
