"""Sweeps beyond one machine from Python: chunks of cases mapped over a dask.distributed cluster.

Each worker builds the scene once (the first chunk it gets) and keeps it, with its memo cache, for
the chunks after; the rows come back in case order and equal ``Scene.sweep`` row for row (``case``
numbers count over all the cases). From the command line, the same job is a Slurm job array
(``mechgraph sweep --shard``)."""
from __future__ import annotations

from typing import Any, Dict, Iterable, Mapping, Optional, Tuple

from ._cases import case_columns
from ._scene import Scene

# Scenes built on this worker process, by their source (the scene travels as its text or path).
_worker_scenes: Dict[Tuple[str, ...], Scene] = {}


def _worker_scene(source: Tuple[str, ...]) -> Scene:
    scene = _worker_scenes.get(source)
    if scene is None:
        scene = Scene.load(source[1]) if source[0] == "file" else Scene.from_text(source[1], source[2])
        _worker_scenes[source] = scene
    return scene


def _run_chunk(source: Tuple[str, ...], first: int, chunk: Dict[str, Any], sets: Optional[Mapping[str, str]],
               outputs: Optional[list], threads: int):
    frame = _worker_scene(source).sweep(chunk, set=sets, outputs=outputs, threads=threads)
    frame["case"] = frame["case"] + first
    return frame


def sweep(client: Any, scene: Scene, cases: Any, chunk: int = 1000, set: Optional[Mapping[str, str]] = None,
          outputs: Optional[Iterable[str]] = None, threads: int = 1):
    """Runs `cases` (a DataFrame or dict of arrays, as :meth:`Scene.sweep` takes) on the workers of
    `client` (a ``dask.distributed.Client``) in chunks of `chunk` cases, `threads` threads per
    chunk, and returns one DataFrame in case order. The columns of a series output are fixed per
    chunk; a chunk whose cases all fail has only the scalar columns (its rows are aligned to the
    others by name)."""
    import pandas as pd

    if chunk < 1:
        raise ValueError("chunk must be at least 1")
    names, units, columns = case_columns(cases)
    headers = [f"{n} [{u}]" if u else n for n, u in zip(names, units)]
    total = len(columns[0]) if columns else 0
    source = scene._source
    sets = dict(set or {})
    outs = list(outputs or [])
    futures = []
    for first in range(0, total, chunk):
        part = {h: c[first:first + chunk] for h, c in zip(headers, columns)}
        futures.append(client.submit(_run_chunk, source, first, part, sets, outs, threads, pure=False))
    frames = client.gather(futures)
    if not frames:
        return scene.sweep(cases, set=set, outputs=outputs, threads=threads)
    result = pd.concat(frames, ignore_index=True)
    widest = max(frames, key=lambda f: len(f.columns))
    ordered = list(widest.columns) + [c for c in result.columns if c not in widest.columns]
    return result[ordered]


def study(client: Any, scene: Scene, parameters: Optional[Mapping[str, Any]] = None, *, samples: Optional[int] = None,
          method: Optional[str] = None, seed: Optional[int] = None, sensitivity: Optional[bool] = None,
          limits: Optional[Mapping[str, Any]] = None, events: Optional[Mapping[str, Any]] = None,
          set: Optional[Mapping[str, str]] = None, outputs: Optional[Iterable[str]] = None, chunk: int = 1000, threads: int = 1):
    """An uncertainty study (as :meth:`Scene.study` takes its settings) whose cases run on the
    workers of `client` by :func:`sweep`: the design is made here, its cases (parameters in SI)
    go out in chunks, the rows come back exact, and the answers are made from them: the same
    numbers as ``scene.study(...)`` in one process."""
    from ._scene import _study_arguments
    from ._study import Study

    args = _study_arguments(parameters, samples, method, seed, sensitivity, limits, events, set, outputs)
    design = scene._session.study_design(*args)
    rows = sweep(client, scene, design, chunk=chunk, set=set, outputs=outputs, threads=threads)
    columns = {name: [float("nan") if v is None else float(v) for v in rows[name]] for name in rows.columns
               if name not in design and name not in ("case", "exit", "error")}
    exits = [int(e) for e in rows["exit"]]
    json_text = scene._session.study_rows(*args, columns, exits)
    cases = dict(design)
    cases.update(columns)
    cases["exit"] = exits
    return Study(json_text, cases)
