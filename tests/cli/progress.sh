#!/usr/bin/env bash
# Progress on stderr: one line per stage once a run has taken longer than
# SCAFFOLD_PROGRESS_AFTER seconds (2 by default, so a short run shows none),
# and none at all with -q, however long the run.
set -euo pipefail
build="$1"; src="$2"
tmp="$(mktemp -d)"; trap 'rm -rf "$tmp"' EXIT
fail=0
in="$src/golden/two-level-pillars/input.gcode"

SCAFFOLD_PROGRESS_AFTER=0 "$build/scaffold" "$in" -o "$tmp/a.gcode" 2> "$tmp/a.err"
for stage in "finding overhangs" "planning" "writing the support" "s so far)"; do
  grep -q "$stage" "$tmp/a.err" || { echo "FAIL: no progress line with '$stage'"; cat "$tmp/a.err"; fail=1; }
done

SCAFFOLD_PROGRESS_AFTER=0 "$build/scaffold" -q "$in" -o "$tmp/q.gcode" 2> "$tmp/q.err"
[ ! -s "$tmp/q.err" ] || { echo "FAIL: -q printed:"; cat "$tmp/q.err"; fail=1; }

"$build/scaffold" "$in" -o "$tmp/d.gcode" 2> "$tmp/d.err"
! grep -q "s so far)" "$tmp/d.err" || { echo "FAIL: a short run printed progress:"; cat "$tmp/d.err"; fail=1; }

# Progress changes nothing in the output.
cmp -s "$tmp/a.gcode" "$tmp/q.gcode" || { echo "FAIL: output differs with progress on"; fail=1; }
cmp -s "$tmp/a.gcode" "$tmp/d.gcode" || { echo "FAIL: output differs with progress off"; fail=1; }
exit $fail
