#!/usr/bin/env bash
# Inputs the fuzzers once crashed on: both methods must end with success or
# a clean error (exit 0 or 1), never a signal.
set -uo pipefail
build="$1"; src="$2"
tmp="$(mktemp -d)"; trap 'rm -rf "$tmp"' EXIT
fail=0; n=0
for f in "$src"/tests/data/fuzz/*; do
  for m in pillars scaffold; do
    "$build/scaffold" -q --method "$m" "$f" -o "$tmp/out.gcode" 2>/dev/null
    rc=$?
    n=$((n+1))
    if [ "$rc" -gt 1 ]; then echo "FAIL $(basename "$f") --method $m: exit $rc"; fail=1; fi
  done
done
[ "$n" -gt 0 ] || { echo "FAIL: no inputs"; exit 1; }
[ "$fail" -eq 0 ] || exit 1
echo "$n fuzz regressions end cleanly"
