#!/usr/bin/python3
"""A kernel benchmark alone and with a copy on the other core: what one loses when both work.

    tools/bench_side_by_side.py BENCH FILTER [--rounds 3] [--min-time 1]

Runs the Google Benchmark binary BENCH (build/bench/bench_shell, build/bench/bench_hex8) on each
benchmark FILTER selects, one benchmark per invocation, in rounds: alone pinned to the first CPU,
alone pinned to the second, then on each CPU while another copy of the same benchmark runs
pinned to the other one from before the measured run starts until after it ends. The rounds
alternate the settings so that the machine's drift falls on all alike. Prints, per benchmark and
setting, the median over the rounds of ns per element (the `ns_per_element` counter; the real
time per iteration where a benchmark has none), every round's figure, and the ratio of the
loaded to the alone medians (both CPUs summed).

Two copies share nothing in software: separate processes, separate memory, no lock, no wait.
A loaded/alone ratio above 1 is what the hardware (caches, memory bandwidth) takes from each
core when both work; alone figures that differ between the CPUs, or from round to round, are
vCPUs whose speed the host moves (a host core shared with another guest). Either bounds every
two-core figure of the same work: a thread team waits at each pass for its slower member, and
two domains running at once against a mono run with the other core idle pay the ratio
(docs/threads.md "Measured", docs/benchmarks.md "Scale family").
"""

import argparse
import json
import os
import re
import statistics
import subprocess
import sys
import time


def figures(report):
    """{benchmark name: ns per element (or per iteration)} of one JSON report."""
    out = {}
    for b in json.loads(report)["benchmarks"]:
        if b.get("run_type") == "aggregate":
            continue
        ns = b.get("ns_per_element")  # an inverted rate scaled by 1e9: ns per element
        if ns is None:
            ns = b["real_time"] * {"ns": 1, "us": 1e3, "ms": 1e6, "s": 1e9}[b["time_unit"]]
        out.setdefault(b["name"], []).append(ns)
    return {k: statistics.median(v) for k, v in out.items()}


def pinned(cpu):
    return lambda: os.sched_setaffinity(0, {cpu})


def run_on(cmd, cpu, load_cmd=None, load_cpu=None):
    """cmd's report, pinned to `cpu`; with load_cmd, that runs pinned to load_cpu from before
    cmd starts until after it ends (so the whole measured run has the other core working)."""
    load = None
    if load_cmd is not None:
        load = subprocess.Popen(load_cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                                preexec_fn=pinned(load_cpu))
        time.sleep(1.0)  # past its set-up (the plate or box), into the kernel
    try:
        p = subprocess.run(cmd, capture_output=True, text=True, preexec_fn=pinned(cpu))
    finally:
        if load is not None:
            load.kill()
            load.wait()
    if p.returncode != 0:
        sys.exit(f"bench_side_by_side: {' '.join(cmd)} exited {p.returncode}: {p.stderr.strip()}")
    return figures(p.stdout)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("bench", help="a Google Benchmark binary, e.g. build/bench/bench_shell")
    ap.add_argument("filter", help="--benchmark_filter, e.g. 'Elastic5/'")
    ap.add_argument("--rounds", type=int, default=3, help="alternations of alone and loaded")
    ap.add_argument("--min-time", type=float, default=1.0, help="--benchmark_min_time, s")
    a = ap.parse_args()
    listed = subprocess.run([a.bench, f"--benchmark_filter={a.filter}", "--benchmark_list_tests"],
                            capture_output=True, text=True, check=True).stdout.split()
    cpus = sorted(os.sched_getaffinity(0))[:2]
    if len(cpus) < 2:
        sys.exit("bench_side_by_side: needs two CPUs")
    # [name][setting] -> figures; settings: alone on each CPU, and on each with the other loaded.
    got = {}
    # One benchmark per invocation, so that the load runs the same one as the measured copy.
    for r in range(a.rounds):
        for name in listed:
            cmd = [a.bench, f"--benchmark_filter=^{re.escape(name)}$", "--benchmark_format=json",
                   f"--benchmark_min_time={a.min_time}", "--benchmark_repetitions=3"]
            load_cmd = [a.bench, f"--benchmark_filter=^{re.escape(name)}$",
                        "--benchmark_min_time=5", "--benchmark_repetitions=1000"]
            g = got.setdefault(name, {})
            for c in cpus:
                g.setdefault(f"alone {c}", []).append(run_on(cmd, c)[name])
            for c, other in ((cpus[0], cpus[1]), (cpus[1], cpus[0])):
                g.setdefault(f"loaded {c}", []).append(run_on(cmd, c, load_cmd, other)[name])
        print(f"round {r + 1} of {a.rounds} done", file=sys.stderr, flush=True)
    if not got:
        sys.exit(f"bench_side_by_side: no benchmark matches {a.filter!r}")
    print(f"{a.bench}, {a.rounds} rounds, ns per element (medians; each round: alone on CPU "
          f"{cpus[0]}, alone on CPU {cpus[1]}, then on each with a copy running on the other)")
    heads = [f"alone {c}" for c in cpus] + [f"loaded {c}" for c in cpus]
    print(f"{'benchmark':<32}" + "".join(f"{h:>11}" for h in heads) + f"{'loaded/alone':>14}")
    for name, g in got.items():
        med = {h: statistics.median(g[h]) for h in heads}
        ratio = (med[heads[2]] + med[heads[3]]) / (med[heads[0]] + med[heads[1]])
        print(f"{name:<32}" + "".join(f"{med[h]:>11.1f}" for h in heads) + f"{ratio:>14.3f}")
        for h in heads:  # every round, for the spread
            print(f"{'':<4}{h:<10}" + " ".join(f"{x:.1f}" for x in g[h]))


if __name__ == "__main__":
    main()
