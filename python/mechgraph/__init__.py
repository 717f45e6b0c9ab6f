"""mechgraph from Python: scenes of cam, spring and joint calculations, evaluated in process.

    import mechgraph
    scene = mechgraph.Scene.load("scenes/valvetrain_cams.yaml")
    r = scene.run(set={"rpm": "6500 rpm", "kurz.max_lift": (9, "mm")})
    r["v_arc.max_acceleration"]                      # float, SI
    r.table("kurz.svaj", units="display")            # DataFrame in the scene's units
    scene.sweep({"rpm [rpm]": [5000, 6000, 7000]})   # DataFrame, rows of `mechgraph sweep`

Every number for a parameter with a dimension says its unit: text ("9 mm"), a pair (9, "mm"), a
pint quantity, a column header ("lift [mm]"), or SI said so (mechgraph.si(0.009), si=True); a bare
number is refused (SceneError), except for counts and ratios.

Plugins are found as the command line finds them: folders given to :func:`load_plugins`, then
``MECHGRAPH_PLUGIN_PATH``, then the built-in folder beside libmechgraph.
"""
from __future__ import annotations

import json
from typing import Any, Dict, List, Sequence

from ._errors import EvaluationError, MechgraphError, PluginError, SceneError, SceneFileNotFoundError, UnitError
from . import _core
from ._result import Quantity, Result
from ._scene import Scene
from ._study import Study
from ._units import SI, si

__version__: str = _core.__version__

__all__ = ["Scene", "Study", "Result", "Quantity", "si", "SI", "MechgraphError", "SceneError", "SceneFileNotFoundError",
           "UnitError", "EvaluationError", "PluginError",
           "describe", "node_types", "plugins", "load_plugins", "set_log_level", "Description"]


class Description(dict):
    """A node type as ``mechgraph describe TYPE --json`` gives it; ``str()`` is the text form."""

    def __init__(self, data: Dict[str, Any], text: str):
        super().__init__(data)
        self.text = text

    def __str__(self) -> str:
        return self.text

    def _repr_pretty_(self, printer, cycle) -> None:  # IPython shows the text
        printer.text(self.text)


def describe(type: str) -> Description:
    """One node type in full: parameters (dimension, default, range), ports, effects, knobs."""
    json_text, text = _core.describe(type)
    return Description(json.loads(json_text), text)


def node_types() -> List[str]:
    """The node types the loaded plugins provide."""
    return list(_core.node_types())


def plugins() -> List[Dict[str, Any]]:
    """The loaded plugins: id, version, sdk_version, fingerprint, file, node_types."""
    return list(_core.plugins())


def load_plugins(plugin_dirs: Sequence[str] = (), only: bool = False) -> List[Dict[str, Any]]:
    """Loads the plugins again: `plugin_dirs` first (as ``--plugin-dir``), then
    ``MECHGRAPH_PLUGIN_PATH`` and the built-in folder, or only `plugin_dirs` with ``only=True``
    (``--only-plugin-dir``). Scenes made later use them; scenes made before keep theirs."""
    return list(_core.load_plugins([str(d) for d in plugin_dirs], bool(only)))


def set_log_level(level: str) -> None:
    """spdlog's level for mechgraph's messages on stderr: trace, debug, info, warn (default), error, off."""
    _core.set_log_level(level)
