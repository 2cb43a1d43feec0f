#!/usr/bin/env bash
# tools/check_citations.py fails on each kind of broken citation and passes on sound ones: a
# throw-away repository with docs/design.md and a source citing a missing file, a missing heading,
# a heading named by part of a word only, a missing design section and the design card's old
# name; then the same source fixed.
set -euo pipefail
check="$1/tools/check_citations.py"
here=$(cd "$(dirname "$0")" && pwd)
# shellcheck source=expect_findings.sh
. "$here/expect_findings.sh"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cd "$tmp"
git init -q .
mkdir docs src
printf '# design\n## 1. Processes\n## 2. The method\n### 2.7 Layer\n' > docs/design.md
printf '# Checkpoints\n## When\n## Soak: 10 handshakes\n' > docs/checkpoints.md
cat > src/a.cpp <<'SRC'
// docs/missing.md
// docs/checkpoints.md "Where and how"
// docs/design.md §2.9
// DESIGN.md §2.7
// docs/checkpoints.md "Handshake"
SRC
git add -A
expect_findings "$check" "$tmp" "src/a.cpp:1: docs/missing.md does not exist" \
            "src/a.cpp:2: docs/checkpoints.md has no heading \"Where and how\"" \
            "src/a.cpp:3: docs/design.md has no section 2.9" \
            "src/a.cpp:4: cites the design card by its old name" \
            "src/a.cpp:5: docs/checkpoints.md has no heading \"Handshake\""
cat > src/a.cpp <<'SRC'
// docs/checkpoints.md "When", docs/design.md §2.7 and §1 (docs/design.md §1)
// docs/checkpoints.md "Soak", docs/checkpoints.md "10 handshakes"
SRC
/usr/bin/python3 "$check" "$tmp" || { echo "FAIL: sound citations refused"; exit 1; }
echo "PASS"
