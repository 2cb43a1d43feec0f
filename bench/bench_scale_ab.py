#!/usr/bin/python3
"""Two crashlink builds on one size of the scale family (bench/bench_scale.py), mono, alternated.

    bench/bench_scale_ab.py OLD_EXE NEW_EXE [--level 4] [--end-time 0.0002] [--rounds 2]

Runs OLD, NEW, OLD, NEW, ... (`crashlink run SCENE --mode mono`) on the head impact with its hood
and cowl refined `--level` times, and prints for each run and as medians the cycles' CPU per
element-cycle and bench_scale's breakdown of it: the hex and shell kernels per element of their
kind, the global step and the rest (nodal passes, rigid bodies, output) per element-cycle. On a
host whose cores change speed (docs/threads.md "Measured"), alternating is what makes the two
builds' figures comparable; the kernels' figures show which speed a run had.
"""

import argparse
import os
import statistics
import subprocess
import sys
import tempfile

import yaml

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import bench_scale  # noqa: E402  (the scene and the breakdown)


def one_run(exe, scene, out):
    subprocess.run([exe, "run", scene, "--mode", "mono", "--quiet", "--out", out], check=True,
                   stdout=subprocess.DEVNULL)
    (d,) = bench_scale.timing(os.path.join(out, "result.h5"))["domains"].values()
    figures = bench_scale.breakdown(d)
    figures["ns_per_element_cycle"] = (1e9 * (d["cpu_seconds"] - d["setup_cpu_seconds"]) /
                                       (d["elements"] * d["cycles"]))
    return figures


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("old")
    ap.add_argument("new")
    ap.add_argument("--scenario", default=os.path.join(os.path.dirname(HERE), "scenarios",
                                                       "head_impact.yaml"))
    ap.add_argument("--level", type=int, default=4, help="refinement of the 10 mm hood (1, 2, 4)")
    ap.add_argument("--end-time", type=float, default=0.0002, help="s")
    ap.add_argument("--rounds", type=int, default=2)
    a = ap.parse_args()
    keys = ("ns_per_element_cycle", "ns_hex", "ns_shell", "ns_global_step", "ns_rest")
    with tempfile.TemporaryDirectory(prefix="bench_scale_ab_") as work:
        scene = os.path.join(work, f"scale_{a.level}.yaml")
        with open(scene, "w") as f:
            yaml.safe_dump(bench_scale.scaled_scene(a.scenario, a.level, a.end_time), f,
                           sort_keys=False)
        runs = {"old": [], "new": []}
        print(f"bench_scale_ab: level {a.level} ({10.0 / a.level:g} mm hood), end time "
              f"{a.end_time:g} s, {a.rounds} rounds; ns: " + ", ".join(keys))
        for r in range(a.rounds):
            for name in ("old", "new"):
                exe = getattr(a, name)
                fig = one_run(exe, scene, os.path.join(work, name))
                runs[name].append(fig)
                print(f"  round {r} {name}: " + "  ".join(f"{fig[k]:7.1f}" for k in keys),
                      flush=True)
        for name in ("old", "new"):
            print(f"median {name}:  " + "  ".join(
                f"{statistics.median(f[k] for f in runs[name]):7.1f}" for k in keys))


if __name__ == "__main__":
    main()
