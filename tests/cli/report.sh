#!/usr/bin/env bash
# --report: the JSON says what the output's header says (points, pillars,
# filament), lists every dropped point with its position, and the time of
# each stage; --buildplate-only drops the points over the model.
set -euo pipefail
build="$1"; src="$2"
tmp="$(mktemp -d)"; trap 'rm -rf "$tmp"' EXIT
fail=0
val() { sed -n "s/^  \"$1\": \\([-0-9.]*\\),\$/\\1/p" "$2"; }
check() { if [ "$2" != "$3" ]; then echo "FAIL $1: '$2' != '$3'"; fail=1; fi; }

in="$src/golden/two-level-pillars/input.gcode"
"$build/scaffold" -q --method pillars "$in" -o "$tmp/out.gcode" --report "$tmp/r.json"
head_line="$(grep '^; scaffold: points = ' "$tmp/out.gcode")"
check points "$(val points "$tmp/r.json")" "$(echo "$head_line" | sed 's/.*points = \([0-9]*\),.*/\1/')"
check pillars "$(val pillars "$tmp/r.json")" "$(echo "$head_line" | sed 's/.*pillars = \([0-9]*\),.*/\1/')"
check filament "$(val support_filament_mm "$tmp/r.json")" \
  "$(sed -n 's/^; scaffold: support filament used \[mm\] = //p' "$tmp/out.gcode")"
check dropped_points "$(val dropped_points "$tmp/r.json")" 0
[ "$(val points "$tmp/r.json")" -gt 0 ] || { echo "FAIL: no points"; fail=1; }
[ "$(val layers_touched "$tmp/r.json")" -gt 0 ] || { echo "FAIL: no layers touched"; fail=1; }
for stage in read layers overhangs plan toolpath splice write; do
  grep -q "\"$stage\": [0-9.]*" "$tmp/r.json" || { echo "FAIL: no time for stage $stage"; fail=1; }
done
grep -q '^  "unheld_bridge_ends": \[\],$' "$tmp/r.json" || { echo "FAIL: unheld_bridge_ends missing or not empty"; fail=1; }

# The upper shelf stands over the lower one: with --buildplate-only every
# one of its points is dropped, and each is listed with x, y, z, layer.
"$build/scaffold" -q --method pillars --buildplate-only "$in" -o "$tmp/bp.gcode" --report "$tmp/bp.json"
n="$(val dropped_points "$tmp/bp.json")"
check dropped_all "$n" "$(val points "$tmp/bp.json")"
check pillars_bp "$(val pillars "$tmp/bp.json")" 0
check listed "$(grep -o '{"x": [-0-9.]*, "y": [-0-9.]*, "z": [-0-9.]*, "layer": [0-9]*}' "$tmp/bp.json" | wc -l)" "$n"
[ "$fail" -eq 0 ] || { cat "$tmp/r.json" "$tmp/bp.json"; exit 1; }
echo "report matches the output ($n points dropped with --buildplate-only, all listed)"
