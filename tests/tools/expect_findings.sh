# Sourced by the tests of tools/check_*.py: expect_findings CHECK ROOT WANT... runs the checker on
# ROOT, prints what it said, and fails unless it exits 1 and says every WANT (a fixed string).
expect_findings() {
  local check="$1" root="$2" out status want
  shift 2
  set +e
  out=$(/usr/bin/python3 "$check" "$root" 2>&1)
  status=$?
  set -e
  echo "$out"
  [ "$status" -eq 1 ] || { echo "FAIL: exit $status, want 1"; exit 1; }
  for want in "$@"; do
    grep -qF "$want" <<<"$out" || { echo "FAIL: missing '$want'"; exit 1; }
  done
}
