"""Sweeps beyond one machine from Python: chunks of cases mapped over a dask.distributed cluster.

Each worker builds the scene once (the first chunk it gets) and keeps it, with its memo cache, for
the chunks after; the rows come back in case order and equal ``Scene.sweep`` row for row (``case``
numbers count over all the cases). From the command line, the same job is a Slurm job array
(``mechgraph sweep --shard``)."""
from __future__ import annotations

from typing import Any, Dict, Iterable, Mapping, Optional, Tuple

from ._cases import case_columns
from ._scene import Scene
from ._progress import _Bar, progress_bar
from ._units import SI, set_entries

# Scenes built on this worker process, by their source (the scene travels as its text or path).
_worker_scenes: Dict[Tuple[str, ...], Scene] = {}


def _worker_scene(source: Tuple[str, ...]) -> Scene:
    scene = _worker_scenes.get(source)
    if scene is None:
        scene = Scene.load(source[1]) if source[0] == "file" else Scene.from_text(source[1], source[2])
        _worker_scenes[source] = scene
    return scene


def _run_chunk(source: Tuple[str, ...], first: int, chunk: Dict[str, Any], sets: Optional[Mapping[str, str]],
               outputs: Optional[list], threads: int, budget: Tuple[Optional[float], Optional[float]] = (None, None),
               column_units: Optional[list] = None):
    frame = _worker_scene(source).sweep(chunk, set=sets, outputs=outputs, threads=threads, progress=False,
                                        max_work=budget[0], max_memory=budget[1], _column_units=column_units)
    frame["case"] = frame["case"] + first
    return frame


def sweep(client: Any, scene: Scene, cases: Any, chunk: int = 1000, set: Optional[Mapping[str, Any]] = None,
          outputs: Optional[Iterable[str]] = None, threads: int = 1, si: bool = False, progress: Any = True, *,
          max_work: Optional[float] = None, max_memory: Optional[float] = None):
    """Runs `cases` (a DataFrame or dict of arrays, as :meth:`Scene.sweep` takes) on the workers of
    `client` (a ``dask.distributed.Client``) in chunks of `chunk` cases, `threads` threads per
    chunk, and returns one DataFrame in case order. Units as :meth:`Scene.sweep` takes them (`si`
    marks every number without a unit as SI). `progress`: a tqdm bar of the cases done, chunk by
    chunk, once the sweep has run for a second (False: none; a callable ``progress(done, total)``). The columns of a series output are fixed per
    chunk; a chunk whose cases all fail has only the scalar columns (its rows are aligned to the
    others by name). `max_work`: the work budget of all the cases together, as :meth:`Scene.sweep`
    takes it (default 1e12 work items), checked here before any chunk is sent, case by case with its
    own values (SceneError naming the case); `max_memory`: what one chunk's `threads` hold at once
    (default 4 GiB), checked here for the whole sweep's largest case (`threads` 0 counts this
    machine's cores, the workers' own check theirs). Each worker checks its chunk
    again."""
    import pandas as pd

    from ._scene import _budget

    if chunk < 1:
        raise ValueError("chunk must be at least 1")
    budget = _budget(max_work, max_memory)  # refused here, not on the workers
    names, units, marks, columns = case_columns(cases, si)
    headers = [f"{n} [{u}]" if u else n for n, u in zip(names, units)]
    total = len(columns[0]) if columns else 0
    outs = list(outputs or [])
    # The whole sweep within its budget before anything runs: the chunks alone would each pass. Its
    # columns' units go with each chunk: a column without one shows the unit of its first number
    # written with one, which a chunk's own first cells need not have.
    column_units = scene._session.check_sweep(names, units, marks, columns, set_entries(set, si), outs, int(threads), *budget)
    source = scene._source
    sets = {k: (v if isinstance(v, SI) or not si else SI(v)) for k, v in dict(set or {}).items()}
    futures = []
    for first in range(0, total, chunk):
        part = {h: SI(c[first:first + chunk]) if m else c[first:first + chunk] for h, m, c in zip(headers, marks, columns)}
        futures.append(client.submit(_run_chunk, source, first, part, sets, outs, threads, (max_work, max_memory), column_units,
                                     pure=False))
    bar = progress_bar(progress, total, "dask sweep")
    if bar is not None and futures:
        from distributed import as_completed

        sizes = {f.key: min(chunk, total - first) for f, first in zip(futures, range(0, total, chunk))}
        done = 0
        for future in as_completed(futures):
            done += sizes[future.key]
            bar(done, total)
        if isinstance(bar, _Bar):
            bar.close(done)
    frames = client.gather(futures)
    if not frames:
        return scene.sweep(cases, set=set, outputs=outputs, threads=threads, si=si, max_work=max_work, max_memory=max_memory)
    result = pd.concat(frames, ignore_index=True)
    widest = max(frames, key=lambda f: len(f.columns))
    ordered = list(widest.columns) + [c for c in result.columns if c not in widest.columns]
    return result[ordered]


def study(client: Any, scene: Scene, parameters: Optional[Mapping[str, Any]] = None, *, samples: Optional[int] = None,
          method: Optional[str] = None, seed: Optional[int] = None, sensitivity: Optional[bool] = None,
          limits: Optional[Mapping[str, Any]] = None, events: Optional[Mapping[str, Any]] = None,
          set: Optional[Mapping[str, Any]] = None, outputs: Optional[Iterable[str]] = None, chunk: int = 1000, threads: int = 1,
          si: bool = False, settings: Optional[Mapping[str, Any]] = None, max_work: Optional[float] = None,
          max_memory: Optional[float] = None):
    """An uncertainty study (as :meth:`Scene.study` takes its settings) whose cases run on the
    workers of `client` by :func:`sweep`: the design is made here, its cases (parameters in SI)
    go out in chunks, the rows come back exact, and the answers are made from them: the same
    numbers as ``scene.study(...)`` in one process. `max_work`, `max_memory`: the study's budget
    (what it holds beside its cases, its bootstrap) as :meth:`Scene.study` takes it: checked here
    for the whole study before its cases go out, and again for each chunk on its worker."""
    from ._scene import _budget, _study_arguments
    from ._study import Study

    args = _study_arguments(parameters, samples, method, seed, sensitivity, limits, events, set, outputs, si, settings)
    budget = _budget(max_work, max_memory)
    design, shown = scene._session.study_design(*args, *budget)
    # The design's parameters are in SI: marked so, for the unit rule of sweep columns.
    rows = sweep(client, scene, {name: SI(values) for name, values in design.items()}, chunk=chunk, set=set,
                 outputs=outputs, threads=threads, si=si, max_work=max_work, max_memory=max_memory)
    columns = {name: [float("nan") if v is None else float(v) for v in rows[name]] for name in rows.columns
               if name not in design and name not in ("case", "exit", "error")}
    exits = [int(e) for e in rows["exit"]]
    json_text = scene._session.study_rows(*args, columns, exits, *budget)
    cases = dict(shown)
    cases.update(columns)
    cases["exit"] = exits
    return Study(json_text, cases)
