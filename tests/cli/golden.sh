#!/usr/bin/env bash
# Golden tests: each golden/<case>/ holds input.gcode, args and
# expected.gcode; the output must match byte for byte, and be deterministic.
set -euo pipefail
build="$1"; src="$2"
tmp="$(mktemp -d)"; trap 'rm -rf "$tmp"' EXIT
n=0; fail=0
for dir in "$src"/golden/*/; do
  name="$(basename "$dir")"
  read -r -a args < "$dir/args"
  "$build/scaffold" -q "${args[@]}" "$dir/input.gcode" -o "$tmp/$name.gcode"
  "$build/scaffold" -q "${args[@]}" - < "$dir/input.gcode" > "$tmp/$name.again.gcode"
  if ! cmp -s "$tmp/$name.gcode" "$tmp/$name.again.gcode"; then echo "FAIL $name: not deterministic"; fail=1; fi
  if ! cmp -s "$tmp/$name.gcode" "$dir/expected.gcode"; then
    echo "FAIL $name: differs from golden (tools/golden-update regenerates on purpose)"
    diff "$dir/expected.gcode" "$tmp/$name.gcode" | head -20
    fail=1
  fi
  n=$((n+1))
done
[ "$n" -gt 0 ] || { echo "FAIL: no golden cases"; exit 1; }
[ "$fail" -eq 0 ] || exit 1
echo "$n golden cases identical"
