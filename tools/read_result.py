#!/usr/bin/python3
"""Tiny reader of crashlink's result.h5 (layout: docs/result-format.md) for plot scripts.

    import read_result as rr
    r = rr.Result("out/result.h5")
    t, ek = r.glstat("time"), r.glstat("kinetic_energy")       # [k] arrays, s and J
    p = r.probe("head")                                          # dict time/displacement/...
    for k, time_s, state in r.states(): ...                      # h5py groups /states/<k>

Command line: `read_result.py FILE` prints a JSON summary (row counts, last glstat row, probes,
states, timing); `--units` adds every dataset's units. Needs python3-h5py (Debian).
"""
import json
import sys

import h5py
import numpy as np

GLSTAT = ("time", "kinetic_energy", "internal_energy", "hourglass_energy", "contact_energy",
          "external_work", "total_energy", "energy_balance_error")


def _text(v):
    return v.decode() if isinstance(v, bytes) else str(v)


class Result:
    def __init__(self, path):
        self.path = path
        self.f = h5py.File(path, "r")

    def close(self):
        self.f.close()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def glstat(self, name):
        """One /history/glstat column as a numpy array."""
        return np.asarray(self.f["history/glstat"][name][...])

    def probe_names(self):
        return list(self.f["history/probes"].keys())

    def probe(self, name):
        """/history/probes/<name> as a dict of arrays: time [k], displacement/velocity/acceleration [k,3]."""
        g = self.f["history/probes"][name]
        return {k: np.asarray(g[k][...]) for k in ("time", "displacement", "velocity", "acceleration")}

    def states(self):
        """Yields (k, time_s, group) for every field state in order."""
        s = self.f["states"]
        for k in range(int(s.attrs["count"])):
            g = s[str(k)]
            yield k, float(g.attrs["time"]), g

    def timing(self):
        """{'wall_seconds', 'coordinator_cpu_seconds', 'domains': {name: {...}}} or None."""
        if "timing" not in self.f:
            return None
        t = self.f["timing"]
        out = {k: float(t.attrs[k]) for k in ("wall_seconds", "coordinator_cpu_seconds")}
        out["domains"] = {}
        for name, g in t.items():
            out["domains"][_text(g.attrs.get("name", name))] = {
                "cpu_seconds": float(g.attrs["cpu_seconds"]),
                "cycles": int(g.attrs["cycles"]),
                "dt_min": float(g.attrs["dt_min"]),
                "elements": int(g.attrs["elements"]),
                "threads": int(g.attrs.get("threads", 1)),
            }
        return out

    def summary(self, units=False):
        out = {
            "format": _text(self.f.attrs.get("format", "")),
            "nodes": int(self.f["mesh/coordinates"].shape[0]),
            "parts": [_text(n) for n in self.f["mesh/part_names"][...]],
            "history_rows": int(self.f["history/glstat/time"].shape[0]),
            "glstat_last": {n: float(self.glstat(n)[-1]) for n in GLSTAT
                            if self.f["history/glstat/time"].shape[0] > 0},
            "probes": {n: int(self.f["history/probes"][n]["time"].shape[0])
                       for n in self.probe_names()},
            "states": [t for _, t, _ in self.states()],
            "timing": self.timing(),
        }
        if units:
            u = {}
            self.f.visititems(lambda name, obj: u.__setitem__(name, _text(obj.attrs["units"]))
                              if isinstance(obj, h5py.Dataset) and "units" in obj.attrs else None)
            out["units"] = u
        return out


def main(argv):
    args = [a for a in argv[1:] if not a.startswith("--")]
    if len(args) != 1:
        print(__doc__, file=sys.stderr)
        return 2
    with Result(args[0]) as r:
        print(json.dumps(r.summary(units="--units" in argv), indent=1, sort_keys=True))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
