#!/usr/bin/python3
"""Compares two crashlink result.h5 files value by value (tests/docker/compose_test.sh).

    compare_results.py REFERENCE.h5 RUN.h5 [--rtol R]

Every dataset under /history (glstat, probes, contacts), /states and /coupling is compared;
/timing (wall and CPU times) is not. A value matches when |a - b| <= rtol * max|reference of that
dataset| (rtol 0 by default: bit-identical). Prints one line per group of datasets with the number
of values that differ and the largest difference, then `[measured]` lines; exit 1 on a mismatch or
a dataset present in only one file, 0 otherwise.
"""
import argparse
import sys

import h5py
import numpy as np

COMPARED = ("history", "states", "coupling")


def datasets(f):
    out = {}

    def visit(name, obj):
        if isinstance(obj, h5py.Dataset) and name.split("/")[0] in COMPARED:
            out[name] = obj

    f.visititems(visit)
    return out


def group_of(name):
    # /history/probes/head/acceleration -> history/probes/head ; /states/12/x -> states
    parts = name.split("/")
    if parts[0] == "states":
        return "states"
    return "/".join(parts[:-1])


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("reference")
    ap.add_argument("run")
    ap.add_argument("--rtol", type=float, default=0.0)
    a = ap.parse_args()
    ok = True
    with h5py.File(a.reference, "r") as fr, h5py.File(a.run, "r") as fu:
        dr, du = datasets(fr), datasets(fu)
        for name in sorted(set(dr) ^ set(du)):
            print(f"only in {'reference' if name in dr else 'run'}: /{name}")
            ok = False
        groups = {}
        for name in sorted(set(dr) & set(du)):
            r, u = dr[name], du[name]
            g = groups.setdefault(group_of(name), {"values": 0, "differ": 0, "max_abs": 0.0,
                                                   "max_rel": 0.0, "worst": ""})
            if r.shape != u.shape:
                print(f"shape differs: /{name}: {r.shape} vs {u.shape}")
                ok = False
                continue
            x, y = r[()], u[()]
            if x.dtype.kind not in "fiu":  # strings: must be equal
                if not np.array_equal(x, y):
                    print(f"differs: /{name}")
                    ok = False
                continue
            x = np.asarray(x, dtype=np.float64)
            y = np.asarray(y, dtype=np.float64)
            same = (x == y) | (np.isnan(x) & np.isnan(y))
            g["values"] += x.size
            g["differ"] += int(np.count_nonzero(~same))
            if x.size == 0:
                continue
            d = np.where(same, 0.0, np.abs(x - y))
            scale = float(np.nanmax(np.abs(x))) if np.any(np.isfinite(x)) else 0.0
            dmax = float(np.nanmax(d)) if np.any(~same) else 0.0
            rel = dmax / scale if scale > 0 else (np.inf if dmax > 0 else 0.0)
            if dmax > g["max_abs"]:
                g["max_abs"] = dmax
            if rel > g["max_rel"]:
                g["max_rel"], g["worst"] = rel, name
            if rel > a.rtol or np.any(np.isnan(x) != np.isnan(y)):
                ok = False
        total = differ = 0
        worst_rel = 0.0
        for gname, g in groups.items():
            if gname.startswith("states") or gname.startswith("history") or gname.startswith("coupling"):
                print(f"/{gname}: {g['values']} values, {g['differ']} differ, max |diff| "
                      f"{g['max_abs']:.3g}, max relative {g['max_rel']:.3g}"
                      + (f" (/{g['worst']})" if g['differ'] else ""))
            total += g["values"]
            differ += g["differ"]
            worst_rel = max(worst_rel, g["max_rel"])
        print(f"[measured] compared values: {total}, differing: {differ}, "
              f"max relative difference: {worst_rel:.3g} (tolerance {a.rtol:g})")
    print("MATCH" if ok else "MISMATCH")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
