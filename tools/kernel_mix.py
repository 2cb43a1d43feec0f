#!/usr/bin/python3
"""Executed instructions and flops per element of one element-kernel call, counted exactly.

Runs a kernel benchmark (bench_hex8, bench_shell) under valgrind's callgrind with per-instruction
counts, keeps the last kernel call (the benchmark's timed one; the first calls of bench_hex8 and
the warm-up calls of bench_shell differ), reads each executed instruction's mnemonic from
objdump and prints, per element: instructions, flops (an FMA lane counts 2, add, sub, mul, div
and sqrt lanes 1; a ymm instruction has 4 double lanes, an xmm one 2, a scalar one 1) and the
most frequent mnemonics. With --ns (a measured ns per element-cycle) and --peak-gflops (what
bench_fma_peak measures) it also prints the rate and its fraction of the peak.

The host's hardware counters are not needed (this VM has none), and the count does not depend
on the machine's load. docs/benchmarks.md "The arithmetic bound" quotes it.

  tools/kernel_mix.py build/bench/bench_shell BM_ShellPlastic5/316 99856 [--ns 160 --peak-gflops 40.7]
  tools/kernel_mix.py build/bench/bench_hex8 BM_Hex8Elastic/100/100/10 100000
"""
import argparse
import collections
import glob
import os
import re
import subprocess
import sys
import tempfile


def executed_counts(bench, filt):
    """Per-address executed counts of the last kernel call, in the bench binary's own object."""
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, 'cg')
        cmd = ['valgrind', '--tool=callgrind', '--dump-instr=yes', '--compress-strings=no',
               '--compress-pos=no', f'--callgrind-out-file={out}', '--toggle-collect=*_forces<*',
               '--dump-after=crashlink::elements::*_internal_forces*', bench,
               f'--benchmark_filter={filt}$', '--benchmark_min_time=0.01']
        try:
            r = subprocess.run(cmd, capture_output=True, text=True)
        except FileNotFoundError:
            sys.exit('kernel_mix: valgrind is not installed (apt-get install valgrind)')
        dumps = sorted(glob.glob(out + '.*'), key=lambda p: int(p.rsplit('.', 1)[1]))
        if r.returncode != 0 or not dumps:
            sys.exit(f'kernel_mix: callgrind found no kernel call of {filt} in {bench} '
                     f'(exit {r.returncode}); is valgrind installed and the filter a benchmark?\n'
                     + r.stderr[-2000:])
        counts = collections.Counter()
        ob, skip = None, False
        name = os.path.basename(bench)
        with open(dumps[-1]) as f:
            for line in f:
                if line.startswith('ob='):
                    ob = line[3:].strip()
                elif line.startswith('calls='):
                    skip = True  # the next line is the call's inclusive cost, not an instruction
                elif skip:
                    skip = False
                else:
                    m = re.match(r'^(0x[0-9a-f]+) \S+ (\d+)$', line.strip())
                    if m and ob is not None and os.path.basename(ob) == name:
                        counts[int(m.group(1), 16)] += int(m.group(2))
        return counts


def mnemonics(bench):
    dis = subprocess.run(['objdump', '-d', '--no-show-raw-insn', bench], capture_output=True,
                         text=True, check=True).stdout
    ins = {}
    for line in dis.splitlines():
        m = re.match(r'^\s*([0-9a-f]+):\s+(\S+)\s*(.*)$', line)
        if m:
            ins[int(m.group(1), 16)] = (m.group(2), m.group(3))
    return ins


def main():
    ap = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    ap.add_argument('bench')
    ap.add_argument('benchmark',
                    help='the benchmark with its size, e.g. BM_ShellPlastic5/316')
    ap.add_argument('elements', type=float, help="the benchmark's element count")
    ap.add_argument('--ns', type=float, help='measured ns per element-cycle')
    ap.add_argument('--peak-gflops', type=float, help="bench_fma_peak's GFLOP/s")
    ap.add_argument('--top', type=int, default=12)
    a = ap.parse_args()
    counts, ins = executed_counts(a.bench, a.benchmark), mnemonics(a.bench)
    if not any(addr in ins for addr in counts):
        sys.exit(f'kernel_mix: no executed instruction of {a.bench} itself was recorded (a '
                 'symlink, or VALGRIND_OPTS adding events?); run the bench binary by its path')
    total, flops = 0, 0.0
    mix, kinds = collections.Counter(), collections.Counter()
    for addr, c in counts.items():
        if addr not in ins:
            continue
        mn, ops = ins[addr]
        if not mn.startswith('v') and re.match(r'^(add|sub|mul|div|sqrt)(pd|sd)$', mn):
            mn = 'v' + mn  # SSE2 forms (a build without x86-64-v3): count them alike
        total += c
        mix[mn] += c
        lanes = 1 if mn.endswith('sd') else 4 if '%ymm' in ops else 2 if '%xmm' in ops else 0
        if re.match(r'^vf(n)?m(add|sub)\d*(pd|sd)$', mn):
            flops += 2 * lanes * c
            kinds['fma'] += lanes * c
        elif re.match(r'^v(add|sub|mul|div|sqrt)(pd|sd)$', mn):
            flops += lanes * c
            kinds[mn[1:-2]] += lanes * c
    ne = a.elements
    print(f'{a.benchmark}: {total / ne:.0f} instructions and {flops / ne:.0f} flops per element '
          '(lanes per element: ' +
          ', '.join(f'{k} {v / ne:.0f}' for k, v in sorted(kinds.items())) + ')')
    if a.ns:
        rate = flops / ne / a.ns
        line = f'at {a.ns:g} ns per element: {rate:.1f} GFLOP/s'
        if a.peak_gflops:
            line += f', {100 * rate / a.peak_gflops:.0f} % of the peak {a.peak_gflops:g}'
        print(line)
    for mn, c in mix.most_common(a.top):
        print(f'  {mn:14s} {c / ne:8.1f}')


if __name__ == '__main__':
    main()
