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
  mem B/el        peak resident memory (VmHWM) / elements: mono's process; multi's daemons
                  summed; and the marginal memory between consecutive sizes
                  mono's broken down: the hex and the shell kernels' CPU per element-cycle
                  of their kind (sampled by the solver on every 16th cycle: /timing
                  *_kernel_seconds, *_element_cycles, kernel_sampled_cycles; nan from older
                  result files, which --check refuses), the global step's refreshes (probes
                  and Lanczos, /timing global_step_seconds) and the rest of the cycles' CPU
                  but the contacts (nodal passes, rigid bodies, output) per element-cycle; the
                  element mix changes with the size (the
                  wiper's hexes refine in 3-D, the shells in 2-D), so mono's single figure
                  grows where neither kernel does
  contact ns      contact CPU time per slave node-cycle
  checkpoint      a mono run of its own per size (to 0.2 ms at most), one checkpoint at half of
                  it: state MB, ms, folder MB (the runs above take none: a checkpoint's state
                  buffer would be their peak memory)
  result.h5 MB    mono's and multi's
  CPU gain        mono / multi: of the whole process tree (launcher, daemons, coordinator,
                  reading, cutting and gathering: getrusage of the children), and of the cycles
                  alone (/timing cpu_seconds - setup_cpu_seconds; the coordinator's CPU, mostly
                  its own set-up, is a row of its own); the ideal gain (mono's element-cycles /
                  the domains' summed); the cycles' gain / ideal

    bench/bench_scale.py [-b BUILD] [--levels 1,2,4] [--end-time 0.008] [--runs 3]
                         [--keep DIR [--resume]] [--check]

--resume takes the finished runs already in DIR whose command and scene match (a benchmark stopped
part-way goes on where it stopped).

--check (the short variant in CI): every figure must be present, finite and positive and the
runs must have finished; exit 1 otherwise. Needs /usr/bin/python3 with python3-yaml and
python3-h5py.
"""

import argparse
import hashlib
import json
import math
import os
import resource
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


def run_key(cmd, scene):
    """What a finished run must match to be taken again by --resume: the command and the scene."""
    with open(scene, "rb") as f:
        digest = hashlib.sha256(f.read()).hexdigest()
    return json.dumps({"cmd": cmd, "scene_sha256": digest}, sort_keys=True)


def finished(out, key):
    """A run folder whose run exited 0 with this command and scene (--resume takes it; a run
    stopped part-way has /timing too, up to where it stopped, but no mark)."""
    mark = os.path.join(out, DONE)
    if not (os.path.exists(mark) and os.path.exists(os.path.join(out, "result.h5"))):
        return False
    with open(mark) as f:
        return f.read() == key


def children_cpu_s():
    """CPU seconds (user + system) of this script's children that have ended, grandchildren
    included: a run's launcher with its daemons, coordinator and gather."""
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def run(cmd, scene, log):
    """Runs `cmd` (a `crashlink run ... --out DIR`); returns the process tree's CPU seconds, or
    None for a run taken from an earlier benchmark (--resume)."""
    out = cmd[cmd.index("--out") + 1]
    key = run_key(cmd, scene)
    if RESUME and finished(out, key):
        return None
    shutil.rmtree(out, ignore_errors=True)
    cpu0_s = children_cpu_s()
    with open(log, "w") as f:
        r = subprocess.run(cmd, stdout=f, stderr=subprocess.STDOUT)
    tree_cpu_s = children_cpu_s() - cpu0_s
    if r.returncode != 0:
        sys.stderr.write(f"bench_scale: {' '.join(cmd)} failed ({r.returncode}):\n")
        sys.stderr.write("".join(open(log).readlines()[-8:]))
        sys.exit(1)
    with open(os.path.join(out, DONE), "w") as f:
        f.write(key)
    with open(os.path.join(out, "bench_scale.cpu"), "w") as f:
        f.write(repr(tree_cpu_s))
    return tree_cpu_s


def tree_cpu(out):
    """The process tree's CPU seconds of the run in `out` (kept beside it by run()); NaN for a run
    of an older benchmark that did not keep it."""
    try:
        with open(os.path.join(out, "bench_scale.cpu")) as f:
            return float(f.read())
    except OSError:
        return math.nan


def timing(h5_path):
    with h5py.File(h5_path, "r") as f:
        t = f["timing"]
        out = {"wall_s": float(t.attrs["wall_seconds"]),
               "coordinator_cpu_s": float(t.attrs["coordinator_cpu_seconds"]), "domains": {}}
        for link in t:
            a = t[link].attrs
            name = a["name"].decode() if isinstance(a["name"], bytes) else str(a["name"])
            out["domains"][name] = {k: float(a[k]) for k in (
                "cpu_seconds", "cycles", "elements", "contact_seconds", "contact_node_cycles",
                "peak_rss_bytes", "setup_cpu_seconds")}
            for k in ("kernel_sampled_cycles", "hex_kernel_seconds", "hex_element_cycles",
                      "shell_kernel_seconds", "shell_element_cycles",
                      "global_step_seconds"):  # absent before 2026-11-29: nan
                out["domains"][name][k] = float(a[k]) if k in a else math.nan
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


def breakdown(d):
    """One domain's cycles, broken down per element-cycle (elements: the model's, rigid ones
    too, as in ns/element-cycle): the kernels' CPU per element-cycle of each kind (from the
    cycles the solver samples; nan for a kind the domain has not), the global step's refreshes,
    and the rest (nodal passes, rigid bodies, output, the coupling's exchanges) less the
    contacts, with the kernels' CPU of the sampled cycles taken to all cycles. Result files
    from before these figures give nan."""
    cycle_cpu_s = d["cpu_seconds"] - d["setup_cpu_seconds"]
    element_cycles = d["elements"] * d["cycles"]
    out = {}
    for kind in ("hex", "shell"):
        n = d[f"{kind}_element_cycles"]
        out[f"ns_{kind}"] = 1e9 * d[f"{kind}_kernel_seconds"] / n if n > 0 else math.nan
    sampled = d["kernel_sampled_cycles"]
    kernels_s = ((d["hex_kernel_seconds"] + d["shell_kernel_seconds"]) * d["cycles"] / sampled
                 if sampled > 0 else math.nan)
    rest_s = cycle_cpu_s - kernels_s - d["contact_seconds"] - d["global_step_seconds"]
    counted = d["hex_element_cycles"] + d["shell_element_cycles"]
    out["hex_fraction"] = d["hex_element_cycles"] / counted if counted > 0 else math.nan
    out["ns_global_step"] = 1e9 * d["global_step_seconds"] / element_cycles
    out["ns_rest"] = 1e9 * rest_s / element_cycles
    return out


def measure_mono(exe, scene, out, log):
    run([exe, "run", scene, "--mode", "mono", "--quiet", "--out", out], scene, log)
    t = timing(os.path.join(out, "result.h5"))
    (d,) = t["domains"].values()
    cycle_cpu_s = d["cpu_seconds"] - d["setup_cpu_seconds"]
    return {
        **breakdown(d),
        "elements": d["elements"],
        "tree_cpu_s": tree_cpu(out),
        "cycle_cpu_s": cycle_cpu_s,
        "element_cycles": d["elements"] * d["cycles"],
        "ns_per_element_cycle": 1e9 * cycle_cpu_s / (d["elements"] * d["cycles"]),
        "rss_bytes": d["peak_rss_bytes"],
        "contact_ns_per_node_cycle": 1e9 * d["contact_seconds"] / max(d["contact_node_cycles"], 1),
        "h5_MB": os.path.getsize(os.path.join(out, "result.h5")) / 1e6,
    }


def measure_checkpoint(exe, scene, out, end_time_s, log):
    """A mono run of its own with one checkpoint at end_time_s / 2: its state MB, ms and folder
    MB (not in the runs that measure CPU and memory: the checkpoint's state buffer would be their
    peak)."""
    run([exe, "run", scene, "--mode", "mono", "--quiet", "--out", out,
         "--checkpoint-interval", repr(end_time_s / 2)], scene, log)
    state_MB, ms = checkpoint_line(log)
    return {"state_MB": state_MB, "ms": ms,
            "folder_MB": folder_bytes(os.path.join(out, "checkpoints")) / 1e6}


def measure_multi(exe, scene, out, log):
    run([exe, "run", scene, "--mode", "multi", "--quiet", "--out", out], scene, log)
    t = timing(os.path.join(out, "result.h5"))
    doms = t["domains"]
    r = {
        "tree_cpu_s": tree_cpu(out),
        "cycle_cpu_s": sum(d["cpu_seconds"] - d["setup_cpu_seconds"] for d in doms.values()),
        "coordinator_cpu_s": t["coordinator_cpu_s"],
        "element_cycles": sum(d["elements"] * d["cycles"] for d in doms.values()),
        "rss_bytes": sum(d["peak_rss_bytes"] for d in doms.values()),
        "h5_MB": os.path.getsize(os.path.join(out, "result.h5")) / 1e6,
        "contact_ns_per_node_cycle": 1e9 * sum(d["contact_seconds"] for d in doms.values()) /
        max(sum(d["contact_node_cycles"] for d in doms.values()), 1),
    }
    for name, d in doms.items():
        r[f"ns_{name}"] = 1e9 * (d["cpu_seconds"] - d["setup_cpu_seconds"]) / (
            d["elements"] * d["cycles"])
        r[f"el_{name}"] = d["elements"]
        r[f"parts_{name}"] = breakdown(d)
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
    try:
        measure_family(a, exe, levels, work)
    finally:
        if not a.keep:
            shutil.rmtree(work, ignore_errors=True)


def measure_family(a, exe, levels, work):
    print(f"bench_scale: {os.path.basename(a.scenario)} at levels {levels}, end time "
          f"{a.end_time:g} s, {a.runs} run(s) of mono and multi each; {os.cpu_count()} core(s), "
          f"load {open('/proc/loadavg').read().split()[0]}", flush=True)
    # The checkpoint's own runs: to at most 0.2 ms (the state's size does not depend on the time).
    ckpt_end_s = min(a.end_time, 2e-4)
    scenes, ckpt_scenes = {}, {}
    for L in levels:
        for table, end_s, stem in ((scenes, a.end_time, "scale"), (ckpt_scenes, ckpt_end_s, "ckpt")):
            table[L] = os.path.join(work, f"{stem}_{L}.yaml")
            with open(table[L], "w") as f:
                f.write(f"# {a.scenario} refined {L}x, to {end_s:g} s, by bench/bench_scale.py\n")
                yaml.safe_dump(scaled_scene(a.scenario, L, end_s), f, sort_keys=False)
    mono = {L: [] for L in levels}
    multi = {L: [] for L in levels}
    ckpt = {}
    for i in range(1, a.runs + 1):
        for L in levels:
            base = os.path.join(work, f"L{L}-{i}")
            mono[L].append(measure_mono(exe, scenes[L], base + "-mono", base + "-mono.log"))
            multi[L].append(measure_multi(exe, scenes[L], base + "-multi", base + "-multi.log"))
            if i == 1:
                ckpt[L] = measure_checkpoint(exe, ckpt_scenes[L], base + "-ckpt", ckpt_end_s,
                                             base + "-ckpt.log")
            m, c = mono[L][-1], multi[L][-1]
            print(f"  run {i} level {L}: {m['elements']:.0f} elements, CPU of the cycles: mono "
                  f"{m['cycle_cpu_s']:.1f} s, multi {c['cycle_cpu_s']:.1f} s, gain "
                  f"{m['cycle_cpu_s'] / c['cycle_cpu_s']:.3f} (ideal "
                  f"{m['element_cycles'] / c['element_cycles']:.3f})", flush=True)

    def row(label, fn, fmt="{:.4g}"):
        cells, medians = [], []
        for L in levels:
            v = [fn(L, k) for k in range(a.runs)]
            cells.append(fmt.format(med(v)) + span(v, fmt))
            medians.append(med(v))
        print(f"{label:<30}" + "".join(f"{c:>24}" for c in cells))
        return medians

    print()
    print(f"{'hood mesh':<30}" + "".join(f"{f'{10.0 / L:g} mm':>24}" for L in levels))
    figures = {}
    elements = {L: mono[L][0]["elements"] for L in levels}
    figures["elements"] = row("elements", lambda L, k: elements[L], "{:.0f}")
    domains = sorted(k[3:] for k in multi[levels[0]][0] if k.startswith("ns_"))
    for d in domains:
        row(f"  of which {d}", lambda L, k, d=d: multi[L][k][f"el_{d}"], "{:.0f}")
    figures["ns_mono"] = row("mono ns/element-cycle",
                             lambda L, k: mono[L][k]["ns_per_element_cycle"], "{:.1f}")
    row("  hexes of the deformable elements", lambda L, k: mono[L][k]["hex_fraction"], "{:.3f}")
    figures["ns_hex"] = row("  hex kernel ns/hex-cycle", lambda L, k: mono[L][k]["ns_hex"],
                            "{:.1f}")
    figures["ns_shell"] = row("  shell kernel ns/shell-cycle",
                              lambda L, k: mono[L][k]["ns_shell"], "{:.1f}")
    row("  global step ns/element-cycle", lambda L, k: mono[L][k]["ns_global_step"], "{:.1f}")
    figures["ns_rest"] = row("  rest ns/element-cycle", lambda L, k: mono[L][k]["ns_rest"],
                             "{:.1f}")
    for d in domains:
        figures[f"ns_{d}"] = row(f"multi {d} ns/element-cycle",
                                 lambda L, k, d=d: multi[L][k][f"ns_{d}"], "{:.1f}")
        for part, label in (("hex", "hex kernel ns/hex-cycle"),
                            ("shell", "shell kernel ns/shell-cycle"),
                            ("global_step", "global step ns/element-cycle"),
                            ("rest", "rest ns/element-cycle")):
            if part != "rest" and all(math.isnan(multi[L][k][f"parts_{d}"][f"ns_{part}"])
                                      for L in levels for k in range(a.runs)):
                continue  # a kind this domain has not
            medians = row(f"  {label}",
                          lambda L, k, d=d, part=part: multi[L][k][f"parts_{d}"][f"ns_{part}"],
                          "{:.1f}")
            if part == "rest":  # nan if a daemon did not write its kernels' figures
                figures[f"ns_rest_{d}"] = medians
    figures["mem_mono"] = row("mono peak memory B/element",
                              lambda L, k: mono[L][k]["rss_bytes"] / elements[L], "{:.0f}")
    figures["mem_multi"] = row("multi peak memory B/element",
                               lambda L, k: multi[L][k]["rss_bytes"] / elements[L], "{:.0f}")
    figures["contact_mono"] = row("mono contact ns/node-cycle",
                                  lambda L, k: mono[L][k]["contact_ns_per_node_cycle"], "{:.1f}")
    figures["contact_multi"] = row("multi contact ns/node-cycle",
                                   lambda L, k: multi[L][k]["contact_ns_per_node_cycle"], "{:.1f}")
    figures["ckpt_state"] = row("checkpoint state MB", lambda L, k: ckpt[L]["state_MB"], "{:.1f}")
    figures["ckpt_ms"] = row("checkpoint ms", lambda L, k: ckpt[L]["ms"], "{:.0f}")
    figures["ckpt_dir"] = row(f"checkpoint folder MB ({ckpt_end_s / 2:g} s)",
                              lambda L, k: ckpt[L]["folder_MB"], "{:.1f}")
    figures["h5_mono"] = row("mono result.h5 MB", lambda L, k: mono[L][k]["h5_MB"], "{:.1f}")
    figures["h5_multi"] = row("multi result.h5 MB", lambda L, k: multi[L][k]["h5_MB"], "{:.1f}")
    row("multi coordinator CPU s", lambda L, k: multi[L][k]["coordinator_cpu_s"], "{:.2f}")
    row("CPU gain, whole process tree",
        lambda L, k: mono[L][k]["tree_cpu_s"] / multi[L][k]["tree_cpu_s"], "{:.3f}")
    figures["gain"] = row("CPU gain, the cycles",
                          lambda L, k: mono[L][k]["cycle_cpu_s"] / multi[L][k]["cycle_cpu_s"],
                          "{:.3f}")
    figures["ideal"] = row("ideal gain (element-cycles)",
                           lambda L, k: mono[L][k]["element_cycles"] / multi[L][k]["element_cycles"],
                           "{:.3f}")
    figures["of_ideal"] = row("gain of the cycles / ideal",
                              lambda L, k: (mono[L][k]["cycle_cpu_s"] / multi[L][k]["cycle_cpu_s"])
                              / (mono[L][k]["element_cycles"] / multi[L][k]["element_cycles"]),
                              "{:.3f}")
    # Marginal memory: what one more element costs, between consecutive sizes (the fixed part of
    # a process, libraries and buffers, drops out).
    for j in range(1, len(levels)):
        lo, hi = levels[j - 1], levels[j]
        de = elements[hi] - elements[lo]
        for mode, runs_of in (("mono", mono), ("multi", multi)):
            rss = [med([r["rss_bytes"] for r in runs_of[L]]) for L in (lo, hi)]
            print(f"marginal memory {mode} {10.0 / lo:g} -> {10.0 / hi:g} mm: "
                  f"{(rss[1] - rss[0]) / de:.0f} B/element")
    if len(levels) > 1:
        print(f"\nagainst the {10.0 / levels[0]:g} mm size (issue 24: within 15 %; gain >= 0.95 "
              f"of ideal):")
        for key in (["ns_mono", "ns_hex", "ns_shell", "ns_rest"] + [f"ns_{d}" for d in domains]
                    + ["mem_mono", "mem_multi"]):
            rel = [v / figures[key][0] for v in figures[key]]
            print(f"  {key:<12}" + "".join(f"{r:>10.3f}" for r in rel))
    if a.check:
        bad = [k for k, vals in figures.items() for v in vals if not (v > 0 and math.isfinite(v))]
        if bad:
            sys.exit(f"bench_scale: figures missing or not positive: {sorted(set(bad))}")
        print("bench_scale: every figure present and positive")


if __name__ == "__main__":
    main()
