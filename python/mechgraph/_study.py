"""The answers of an uncertainty study (``Scene.study``) as pandas DataFrames.

Every number is the one ``mechgraph study --json`` prints (SI); ``samples`` holds each case of the
design as the rows of ``mechgraph sweep SCENE --study`` show it (parameters and outputs in the
units of their column headers), ``exit`` (0, or the failure class: 2 scene, 3 evaluation).
"""
import json
from typing import Any, Dict


class Study:
    """The answers of one uncertainty study (``Scene.study``, ``mechgraph.dask.study``): the JSON
    document ``mechgraph study --json`` prints, as ``json``, and its tables as DataFrames (numbers in
    SI, as in that document; ``samples`` excepted, see there)."""

    def __init__(self, json_text: str, cases: Dict[str, Any]):
        self.json: Dict[str, Any] = json.loads(json_text)
        self._cases = cases

    @property
    def samples(self):
        """One row per case of the design, in the columns of ``mechgraph sweep SCENE --study``'s
        rows: the uncertain parameters and the outputs in the units of their headers
        (``lash [mm]``, ``name [unit]``), NaN where the case failed, ``exit`` (0, or
        the failure class: 2 scene, 3 evaluation) and ``role``: ``"A"`` or ``"B"`` for the rows
        the statistics are made of, ``"AB name"`` for Saltelli's rows that move one parameter
        (with sensitivity; without, every row is ``"A"``). Statistics of a sensitivity study's
        samples: ``samples[samples.role.isin(["A", "B"])]``, as ``summary`` takes them."""
        import pandas as pd

        frame = pd.DataFrame(self._cases)
        frame["role"] = self._roles(len(frame))
        return frame

    def _roles(self, cases: int):
        import numpy as np

        names = [p["name"] for p in self.json["parameters"]] if self.json.get("sensitivity") else []
        pattern = np.array(["A", "B"] + [f"AB {name}" for name in names] if names else ["A"], dtype=object)
        return pattern[np.arange(cases) % len(pattern)]  # Python strings, as a list of them gave

    @property
    def summary(self):
        """One row per output: n, failed, mean (with its interval), standard deviation, min, max,
        and against spec limits Cp, Cpk, the counted ppm (Wilson interval), the normal model's, and
        the ppm with the failed cases counted out of spec (``ppm_or_failed``, Wilson interval)."""
        import pandas as pd

        rows = []
        for name, o in self.json["outputs"].items():
            row = {"output": name, "unit": o["unit"], "n": o["n"], "failed": o["failed"]}
            for key in ("mean", "standard_deviation", "min", "max", "cp", "cpk", "ppm", "ppm_normal"):
                row[key] = o.get(key)
            row["mean_lower"], row["mean_upper"] = o.get("mean_interval", [None, None])
            if "out_of_spec" in o:
                row["below"], row["above"] = o["out_of_spec"].get("below"), o["out_of_spec"].get("above")
                lo, hi = o["out_of_spec"]["wilson"]
                row["ppm_lower"], row["ppm_upper"] = 1e6 * lo, 1e6 * hi
            if "out_of_spec_or_failed" in o:
                row["ppm_or_failed"] = o["ppm_or_failed"]
                lo, hi = o["out_of_spec_or_failed"]["wilson"]
                row["ppm_or_failed_lower"], row["ppm_or_failed_upper"] = 1e6 * lo, 1e6 * hi
            rows.append(row)
        return pd.DataFrame(rows).set_index("output")

    @property
    def quantiles(self):
        """One row per output and level: the quantile (type 7) and its distribution-free
        confidence interval from exact binomial ranks (``lower``, ``upper``), in SI (``unit``)."""
        import pandas as pd

        rows = [{"output": name, "unit": o["unit"], "level": q["level"], "value": q["value"], "lower": q["interval"][0],
                 "upper": q["interval"][1]}
                for name, o in self.json["outputs"].items() for q in o["quantiles"]]
        return pd.DataFrame(rows)

    @property
    def histograms(self):
        """One row per output and bin: the bin's edges (``low``, ``high``, in SI: ``unit``) and its count."""
        import pandas as pd

        rows = []
        for name, o in self.json["outputs"].items():
            h = o["histogram"]
            for k, count in enumerate(h["counts"]):
                rows.append({"output": name, "unit": o["unit"], "low": h["low"] + k * h["width"], "high": h["low"] + (k + 1) * h["width"],
                             "count": count})
        return pd.DataFrame(rows)

    @property
    def sobol(self):
        """One row per output and parameter: first-order (Saltelli 2010) and total (Jansen) indices
        with their bootstrap intervals."""
        import pandas as pd

        rows = []
        for name, o in self.json["outputs"].items():
            for parameter, s in o.get("sobol", {}).get("indices", {}).items():
                rows.append({"output": name, "parameter": parameter, "first": s["first"], "first_lower": s["first_interval"][0],
                             "first_upper": s["first_interval"][1], "total": s["total"], "total_lower": s["total_interval"][0],
                             "total_upper": s["total_interval"][1]})
        return pd.DataFrame(rows)

    @property
    def events(self):
        """One row per declared event: how many cases had it of how many (``undecided``: the
        cases without a value, left out of the trials), the estimated probability, and its Wilson
        and Clopper-Pearson intervals."""
        import pandas as pd

        rows = [{"event": name, "events": e["events"], "trials": e["trials"], "undecided": e.get("undecided", 0),
                 "probability": e["estimate"],
                 "wilson_lower": e["wilson"][0], "wilson_upper": e["wilson"][1],
                 "clopper_pearson_lower": e["clopper_pearson"][0], "clopper_pearson_upper": e["clopper_pearson"][1]}
                for name, e in self.json["events"].items()]
        return pd.DataFrame(rows)

    def __repr__(self) -> str:
        j = self.json
        return f"Study({j['method']}, {j['samples']} samples, {j['cases']} cases, {j['failed']} failed)"
