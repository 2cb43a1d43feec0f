#!/usr/bin/env python3
"""Keeps a fuzz corpus small (tools/fuzz.sh --merge, docs/fuzzing.md).

usage: fuzz_trim.py CONTROL_FILE DEST MAX

CONTROL_FILE is the -merge_control_file of a libFuzzer -merge=1 run over the checked-in corpus
and the run's finds. It lists the inputs (smallest first) and, per input, the coverage edges it
added to those before it ("COV i e1 e2 ..."). Into DEST (emptied) go every named input (seeds
and regression inputs: names that are not libFuzzer's 40-hex hashes) and at most MAX found
inputs, those that added the most edges, so the corpus stays tens of small files while keeping
the bulk of the coverage. Prints what it kept.
"""
import os
import re
import sys


def main():
    control, dest, most = sys.argv[1], sys.argv[2], int(sys.argv[3])
    with open(control) as f:
        lines = f.read().splitlines()
    count = int(lines[0])
    paths = lines[2:2 + count]
    added = {}
    for line in lines[2 + count:]:
        if line.startswith("COV "):
            fields = line.split()
            added[int(fields[1])] = len(fields) - 2
    named = [i for i, p in enumerate(paths) if not re.fullmatch(r"[0-9a-f]{40}", os.path.basename(p))]
    found = sorted((i for i in added if i not in named and added[i] > 0), key=lambda i: -added[i])
    keep = named + found[:most]
    data = {}  # read first: DEST is usually one of the merged folders
    for i in keep:
        with open(paths[i], "rb") as f:
            data[os.path.basename(paths[i])] = f.read()
    for old in os.listdir(dest):
        os.remove(os.path.join(dest, old))
    for name, content in data.items():
        with open(os.path.join(dest, name), "wb") as f:
            f.write(content)
    edges = sum(added.get(i, 0) for i in keep)
    print(f"fuzz_trim: kept {len(named)} named + {min(most, len(found))} found inputs of "
          f"{len(paths)}; they added {edges} of {sum(added.values())} edges in merge order")


if __name__ == "__main__":
    main()
