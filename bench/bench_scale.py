#!/usr/bin/python3
"""The head-impact scene's scale family (issue 24 item 4; docs/benchmarks.md "Scale family").

The scene of scenarios/head_impact.yaml with the hood and cowl refined by 1, 2 and 4 (hood 10, 5
and 2.5 mm; cowl 12, 6 and 3 mm, whose grid keeps holding the mounts' corner nodes) and the
wiper's hexes refined alike (4, 2 and 1 mm), so that the step ratio between the domains stays
the same. Each size runs in `--mode mono` (one thread) and `--mode multi` (one thread per
domain), interleaved run by run (mono L1, multi L1, mono L2, ...) so that the machine's load
falls on all alike; the figures are medians over the runs, with their range:

  elements        of the model
  ns/el-cyc       CPU of the cycles / (elements x cycles): mono, and each domain of multi (the
                  CPU before the first cycle, /timing setup_cpu_seconds, left out)
  mem B/el        peak resident memory / elements: mono's process; multi's daemons summed
  contact ns      contact wall time per slave node-cycle (mono)
  checkpoint      mono's checkpoint at mid-run: state MB, ms, folder MB
  result.h5 MB    mono's and multi's
  CPU gain        mono CPU / multi CPU: of the whole run (daemons + coordinator, set-up
                  included), and of the cycles alone (the daemons' CPU after their first cycle;
                  the coordinator's CPU, mostly its own set-up, is a row of its own); the ideal
                  gain (mono's element-cycles / the domains' summed); the cycles' gain / ideal

    bench/bench_scale.py [-b BUILD] [--levels 1,2,4] [--end-time 0.008] [--runs 3]
                         [--keep DIR [--resume]] [--check]

--resume takes the finished runs already in DIR (a benchmark stopped part-way goes on where it
stopped; the scenes in DIR are rewritten, so keep the same --levels and --end-time).

--check (the short variant in CI): every figure must be present, finite and positive and the
runs must have finished; exit 1 otherwise. Needs /usr/bin/python3 with python3-yaml and
python3-h5py.
"""

import argparse
import math
import os
import shutil
import statistics
import subprocess
import sys
import tempfile

import h5py
import yaml

RESUME = False  # --resume
HERE = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def scaled_scene(base, level, end_time_s):
    """The base head-impact scene with its deformable meshes refined by `level` (1, 2, 4)."""
    s = yaml.safe_load(open(base))
    h_mm = 10.0 / level
    s["name"] = f"head_impact_scale_{h_mm:g}mm"
    s["controls"]["end_time"] = end_time_s
    parts = s["parts"]

    def scale(mesh, key):
        mesh[key] = [int(d) * level for d in mesh[key]] if isinstance(mesh[key], list) \
            else int(mesh[key]) * level

    scale(parts["hood"]["mesh"], "divisions")          # 10 mm -> 10 / level
    scale(parts["cowl"]["mesh"], "divisions")          # 12 mm: the mounts' corners stay on it
    for name in ("mount_left", "mount_centre", "mount_right"):
        scale(parts[name]["mesh"], "divisions")        # 4 mm hexes, refined alike
    scale(parts["wiper_bar"]["mesh"], "cross_divisions")
    scale(parts["wiper_bar"]["mesh"], "divisions")
    return s


DONE = "bench_scale.done"  # written in a run folder once its run has exited 0


def finished(out):
    """A run folder whose run exited 0 (--resume keeps it; a run stopped part-way has /timing too,
    up to where it stopped, but no mark)."""
    return os.path.exists(os.path.join(out, DONE))


def run(cmd, log):
    out = cmd[cmd.index("--out") + 1]
    if RESUME and finished(out):
        return
    with open(log, "w") as f:
        r = subprocess.run(cmd, stdout=f, stderr=subprocess.STDOUT)
    if r.returncode != 0:
        sys.stderr.write(f"bench_scale: {' '.join(cmd)} failed ({r.returncode}):\n")
        sys.stderr.write("".join(open(log).readlines()[-8:]))
        sys.exit(1)
    open(os.path.join(out, DONE), "w").close()


def timing(h5_path):
    with h5py.File(h5_path, "r") as f:
        t = f["timing"]
        out = {"wall": float(t.attrs["wall_seconds"]),
               "coordinator_cpu": float(t.attrs["coordinator_cpu_seconds"]), "domains": {}}
        for link in t:
            a = t[link].attrs
            name = a["name"].decode() if isinstance(a["name"], bytes) else str(a["name"])
            out["domains"][name] = {k: float(a[k]) for k in (
                "cpu_seconds", "cycles", "elements", "contact_seconds", "contact_node_cycles",
                "peak_rss_bytes", "setup_cpu_seconds")}
    return out


def folder_bytes(path):
    total = 0
    for root, _, files in os.walk(path):
        for name in files:
            total += os.path.getsize(os.path.join(root, name))
    return total


def checkpoint_line(log):
    """(state MB, ms) from "...: checkpoint at t = ... s (cycle ...), X MB of state, Y ms"."""
    for line in open(log):
        if ": checkpoint at t = " in line and "MB of state" in line:
            tail = line.rsplit("),", 1)[1].split(",")
            return float(tail[0].split()[0]), float(tail[1].split()[0])
    return math.nan, math.nan


def measure_mono(exe, scene, out, end_time_s, log):
    if not (RESUME and finished(out)):
        shutil.rmtree(out, ignore_errors=True)
    run([exe, "run", scene, "--mode", "mono", "--quiet", "--out", out,
         "--checkpoint-interval", repr(end_time_s / 2)], log)
    t = timing(os.path.join(out, "result.h5"))
    (d,) = t["domains"].values()
    state_mb, ms = checkpoint_line(log)
    return {
        "elements": d["elements"],
        "cpu": d["cpu_seconds"],
        "cycle_cpu": d["cpu_seconds"] - d["setup_cpu_seconds"],
        "element_cycles": d["elements"] * d["cycles"],
        "ns": 1e9 * (d["cpu_seconds"] - d["setup_cpu_seconds"]) / (d["elements"] * d["cycles"]),
        "mem": d["peak_rss_bytes"] / d["elements"],
        "rss": d["peak_rss_bytes"],
        "contact_ns": 1e9 * d["contact_seconds"] / max(d["contact_node_cycles"], 1),
        "ckpt_state_mb": state_mb,
        "ckpt_ms": ms,
        "ckpt_dir_mb": folder_bytes(os.path.join(out, "checkpoints")) / 1e6,
        "h5_mb": os.path.getsize(os.path.join(out, "result.h5")) / 1e6,
    }


def measure_multi(exe, scene, out, log):
    if not (RESUME and finished(out)):
        shutil.rmtree(out, ignore_errors=True)
    run([exe, "run", scene, "--mode", "multi", "--quiet", "--out", out], log)
    t = timing(os.path.join(out, "result.h5"))
    doms = t["domains"]
    elements = sum(d["elements"] for d in doms.values())
    r = {
        "cpu": sum(d["cpu_seconds"] for d in doms.values()) + t["coordinator_cpu"],
        "cycle_cpu": sum(d["cpu_seconds"] - d["setup_cpu_seconds"] for d in doms.values()),
        "coordinator_cpu": t["coordinator_cpu"],
        "element_cycles": sum(d["elements"] * d["cycles"] for d in doms.values()),
        "mem": sum(d["peak_rss_bytes"] for d in doms.values()) / elements,
        "rss": sum(d["peak_rss_bytes"] for d in doms.values()),
        "h5_mb": os.path.getsize(os.path.join(out, "result.h5")) / 1e6,
        "contact_ns": 1e9 * sum(d["contact_seconds"] for d in doms.values()) /
        max(sum(d["contact_node_cycles"] for d in doms.values()), 1),
    }
    for name, d in doms.items():
        r[f"ns_{name}"] = 1e9 * (d["cpu_seconds"] - d["setup_cpu_seconds"]) / (
            d["elements"] * d["cycles"])
        r[f"el_{name}"] = d["elements"]
    return r


def med(values):
    v = [x for x in values if not math.isnan(x)]
    return statistics.median(v) if v else math.nan


def span(values, fmt):
    v = [x for x in values if not math.isnan(x)]
    if len(v) < 2 or min(v) == max(v):
        return ""
    return f" ({fmt.format(min(v))}-{fmt.format(max(v))})"


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("-b", "--build", default=os.path.join(HERE, "build"))
    ap.add_argument("--scenario", default=os.path.join(HERE, "scenarios", "head_impact.yaml"))
    ap.add_argument("--levels", default="1,2,4", help="refinements of the 10 mm hood (1, 2, 4)")
    ap.add_argument("--end-time", type=float, default=0.008, help="simulated time, s")
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--keep", help="keep the scenes and run folders here")
    ap.add_argument("--check", action="store_true", help="exit 1 if a figure is missing")
    ap.add_argument("--resume", action="store_true",
                    help="with --keep: take the finished runs already in DIR, run the rest")
    a = ap.parse_args()
    global RESUME
    RESUME = a.resume
    if a.resume and not a.keep:
        sys.exit("bench_scale: --resume needs --keep DIR (the folder of the runs to take)")
    exe = os.path.join(a.build, "apps", "crashlink")
    if not os.access(exe, os.X_OK):
        sys.exit(f"bench_scale: {exe} not found (build first, or -b DIR)")
    levels = [int(x) for x in a.levels.split(",")]
    work = a.keep or tempfile.mkdtemp(prefix="bench_scale.")
    os.makedirs(work, exist_ok=True)
    print(f"bench_scale: {os.path.basename(a.scenario)} at levels {levels}, end time "
          f"{a.end_time:g} s, {a.runs} run(s) of mono and multi each; {os.cpu_count()} core(s), "
          f"load {open('/proc/loadavg').read().split()[0]}", flush=True)
    scenes = {}
    for L in levels:
        scenes[L] = os.path.join(work, f"scale_{L}.yaml")
        with open(scenes[L], "w") as f:
            f.write(f"# {a.scenario} refined {L}x by bench/bench_scale.py\n")
            yaml.safe_dump(scaled_scene(a.scenario, L, a.end_time), f, sort_keys=False)
    mono = {L: [] for L in levels}
    multi = {L: [] for L in levels}
    for i in range(1, a.runs + 1):
        for L in levels:
            base = os.path.join(work, f"L{L}-{i}")
            mono[L].append(measure_mono(exe, scenes[L], base + "-mono", a.end_time,
                                        base + "-mono.log"))
            multi[L].append(measure_multi(exe, scenes[L], base + "-multi", base + "-multi.log"))
            m, c = mono[L][-1], multi[L][-1]
            print(f"  run {i} level {L}: {m['elements']:.0f} elements, mono CPU {m['cpu']:.1f} s, "
                  f"multi CPU {c['cpu']:.1f} s, gain {m['cpu'] / c['cpu']:.3f} (ideal "
                  f"{m['element_cycles'] / c['element_cycles']:.3f})", flush=True)

    def row(label, fn, fmt="{:.4g}"):
        cells = []
        for L in levels:
            v = [fn(L, k) for k in range(a.runs)]
            cells.append(fmt.format(med(v)) + span(v, fmt))
        print(f"{label:<28}" + "".join(f"{c:>24}" for c in cells))
        return [med([fn(L, k) for k in range(a.runs)]) for L in levels]

    print()
    print(f"{'hood mesh':<28}" + "".join(f"{f'{10.0 / L:g} mm':>24}" for L in levels))
    figures = {}
    figures["elements"] = row("elements", lambda L, k: mono[L][k]["elements"], "{:.0f}")
    domains = sorted(k[3:] for k in multi[levels[0]][0] if k.startswith("ns_"))
    for d in domains:
        row(f"  of which {d}", lambda L, k, d=d: multi[L][k][f"el_{d}"], "{:.0f}")
    figures["ns_mono"] = row("mono ns/element-cycle", lambda L, k: mono[L][k]["ns"], "{:.1f}")
    for d in domains:
        figures[f"ns_{d}"] = row(f"multi {d} ns/element-cycle",
                                 lambda L, k, d=d: multi[L][k][f"ns_{d}"], "{:.1f}")
    figures["mem_mono"] = row("mono memory B/element", lambda L, k: mono[L][k]["mem"], "{:.0f}")
    figures["mem_multi"] = row("multi memory B/element", lambda L, k: multi[L][k]["mem"],
                               "{:.0f}")
    figures["contact_mono"] = row("mono contact ns/node-cycle",
                                  lambda L, k: mono[L][k]["contact_ns"], "{:.1f}")
    figures["contact_multi"] = row("multi contact ns/node-cyc",
                                   lambda L, k: multi[L][k]["contact_ns"], "{:.1f}")
    figures["ckpt_state"] = row("checkpoint state MB", lambda L, k: mono[L][k]["ckpt_state_mb"],
                                "{:.1f}")
    figures["ckpt_ms"] = row("checkpoint ms", lambda L, k: mono[L][k]["ckpt_ms"], "{:.0f}")
    figures["ckpt_dir"] = row("checkpoint folder MB", lambda L, k: mono[L][k]["ckpt_dir_mb"],
                              "{:.1f}")
    figures["h5_mono"] = row("mono result.h5 MB", lambda L, k: mono[L][k]["h5_mb"], "{:.1f}")
    figures["h5_multi"] = row("multi result.h5 MB", lambda L, k: multi[L][k]["h5_mb"], "{:.1f}")
    row("multi coordinator CPU s", lambda L, k: multi[L][k]["coordinator_cpu"], "{:.2f}")
    row("CPU gain, whole run", lambda L, k: mono[L][k]["cpu"] / multi[L][k]["cpu"], "{:.3f}")
    figures["gain"] = row("CPU gain, the cycles",
                          lambda L, k: mono[L][k]["cycle_cpu"] / multi[L][k]["cycle_cpu"], "{:.3f}")
    figures["ideal"] = row("ideal gain (element-cycles)",
                           lambda L, k: mono[L][k]["element_cycles"] / multi[L][k]["element_cycles"],
                           "{:.3f}")
    figures["of_ideal"] = row("gain of the cycles / ideal",
                              lambda L, k: (mono[L][k]["cycle_cpu"] / multi[L][k]["cycle_cpu"])
                              / (mono[L][k]["element_cycles"] / multi[L][k]["element_cycles"]),
                              "{:.3f}")
    # Marginal memory: what one more element costs, between consecutive sizes (the fixed part of
    # a process, libraries and buffers, drops out).
    for j in range(1, len(levels)):
        lo, hi = levels[j - 1], levels[j]
        de = figures["elements"][j] - figures["elements"][j - 1]
        for mode, runs_of in (("mono", mono), ("multi", multi)):
            rss = [med([r["rss"] for r in runs_of[L]]) for L in (lo, hi)]
            print(f"marginal memory {mode} {10.0 / lo:g} -> {10.0 / hi:g} mm: "
                  f"{(rss[1] - rss[0]) / de:.0f} B/element")
    if len(levels) > 1:
        first = levels[0]
        print(f"\nagainst the {10.0 / first:g} mm size (issue 24: within 15 %; gain >= 0.95 of ideal):")
        for key in ["ns_mono"] + [f"ns_{d}" for d in domains] + ["mem_mono", "mem_multi"]:
            rel = [v / figures[key][0] for v in figures[key]]
            print(f"  {key:<12}" + "".join(f"{r:>10.3f}" for r in rel))
    if a.check:
        bad = [k for k, vals in figures.items() for v in vals if not (v > 0 and math.isfinite(v))]
        if bad:
            sys.exit(f"bench_scale: figures missing or not positive: {sorted(set(bad))}")
        print("bench_scale: every figure present and positive")
    if not a.keep:
        shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    main()
