#!/usr/bin/python3
"""Every citation of the design or of a docs file resolves (run by .ci/run).

In every tracked source, script and document:
  - `docs/<name>.md` names a file that exists;
  - `docs/<name>.md "Section"` names a heading of that file that contains Section as whole words;
  - `docs/design.md §N` / `§N.M` names a numbered section of docs/design.md;
  - the design card's old names (`DESIGN.md`, `DESIGN §`) are not cited: the design in the
    repository is docs/design.md (`../shared/DESIGN.md`, its history, may be named as such).
Prints each unresolved citation as file:line: what; exits 1 if there is one, 0 otherwise.
Usage: tools/check_citations.py [REPO_ROOT]
"""
import os
import re
import subprocess
import sys

SUFFIXES = (".cpp", ".h", ".md", ".py", ".sh", ".txt", ".yaml", ".proto", ".cmake", ".in")
DOC = re.compile(r"docs/([A-Za-z0-9_.-]+?\.md)(?:\s+\"([^\"]+)\")?")
SECTION = re.compile(r"docs/design\.md,?\s+§\s*([0-9]+(?:\.[0-9]+)?)")
OLD = re.compile(r"(?<![/A-Za-z])DESIGN(?:\.md| §)")


def headings(path):
    """The heading lines of a markdown file, lower-cased."""
    out = []
    with open(path, encoding="utf-8") as f:
        for line in f:
            if line.startswith("#"):
                out.append(line.strip("# \n").lower())
    return out


def design_sections(root):
    """The section numbers of docs/design.md ("1", "2.7", ...)."""
    out = set()
    for h in headings(os.path.join(root, "docs", "design.md")):
        m = re.match(r"([0-9]+(?:\.[0-9]+)?)\.?\s", h)
        if m:
            out.add(m.group(1))
    return out


def main():
    root = sys.argv[1] if len(sys.argv) > 1 else os.path.dirname(os.path.dirname(
        os.path.abspath(__file__)))
    files = subprocess.run(["git", "-C", root, "ls-files"], check=True, capture_output=True,
                           text=True).stdout.split()
    sections = design_sections(root)
    cache = {}
    bad = []
    for rel in files:
        if not rel.endswith(SUFFIXES) and os.path.basename(rel) != "CMakeLists.txt":
            continue
        if os.path.basename(rel).startswith("check_citations"):  # the checker and its test
            continue
        try:
            with open(os.path.join(root, rel), encoding="utf-8") as f:
                lines = f.readlines()
        except (UnicodeDecodeError, FileNotFoundError):
            continue
        for n, line in enumerate(lines, 1):
            for m in DOC.finditer(line):
                name, title = m.group(1), m.group(2)
                path = os.path.join(root, "docs", name)
                if not os.path.isfile(path):
                    bad.append(f"{rel}:{n}: docs/{name} does not exist")
                    continue
                if title:
                    hs = cache.setdefault(path, headings(path))
                    # the title as whole words of a heading ("Lanes" names "Lanes: the layer
                    # vectors daemon to daemon"; "Handshake" does not name "... handshakes ...")
                    word = re.compile(r"(?<!\w)" + re.escape(title.lower()) + r"(?!\w)")
                    if not any(word.search(h) for h in hs):
                        bad.append(f"{rel}:{n}: docs/{name} has no heading \"{title}\"")
            for m in SECTION.finditer(line):
                if m.group(1) not in sections:
                    bad.append(f"{rel}:{n}: docs/design.md has no section {m.group(1)}")
            if OLD.search(line) and "shared/DESIGN.md" not in line:
                bad.append(f"{rel}:{n}: cites the design card by its old name; cite "
                           "docs/design.md §N")
    for b in bad:
        print(b)
    print(f"check_citations: {len(bad)} unresolved citation(s)", file=sys.stderr)
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
