#!/usr/bin/env bash
# PrusaSlicer 2.7+ hands post-processing scripts a *binary* G-code file under
# a temporary name (not ending in .bgcode) and says the final name in
# SLIC3R_PP_OUTPUT_NAME. scaffold must recognise the file by its content,
# rewrite it in place as binary G-code with supports, and keep it checkable.
# Input: the bundled PrusaSlicer-settings .bgcode (heatshrink 12/4, MeatPack).
set -euo pipefail
build="$1"; src="$2"
tmp="$(mktemp -d)"; trap 'rm -rf "$tmp"' EXIT
orig="$src/tests/data/bgcode/overhang_test.prusaslicer25.nosup.prusaslicer.bgcode"
work="$tmp/.overhang_test.gcode.tmp.12345"   # PrusaSlicer's temporary file
cp "$orig" "$work"
SLIC3R_PP_OUTPUT_NAME="$tmp/overhang_test_0.4n_0.2mm_PLA_MK4_1h32m.bgcode" SLIC3R_BINARY_GCODE=1 \
  "$build/scaffold" "$work" > "$tmp/log" 2>&1 || { echo "FAIL: the hook failed:"; cat "$tmp/log"; exit 1; }
[ "$(head -c 4 "$work")" = "GCDE" ] || { echo "FAIL: the result is not binary G-code"; exit 1; }
cmp -s "$orig" "$work" && { echo "FAIL: the file was not changed"; exit 1; }
"$build/scaffold" "$work" --method none --output-format ascii -o "$tmp/decoded.gcode" -q
grep -q "^; scaffold " "$tmp/decoded.gcode" || { echo "FAIL: the hook did not run"; exit 1; }
grep -q "^;TYPE:Support material" "$tmp/decoded.gcode" || { echo "FAIL: no support written"; exit 1; }
# The metadata the printer shows carries the new filament total.
was="$(grep -m1 '^; filament used \[mm\] = ' <("$build/scaffold" "$orig" --method none --output-format ascii -o - -q))"
now="$(grep -m1 '^; filament used \[mm\] = ' "$tmp/decoded.gcode")"
[ "$was" != "$now" ] || { echo "FAIL: filament used not updated ($now)"; exit 1; }
"$build/scaffold-check" --min-stiffness 0 "$work" --original "$orig" > "$tmp/check.txt" || {
  echo "FAIL: the binary output fails scaffold-check"; cat "$tmp/check.txt"; exit 1; }
# --method none: byte for byte; --output-format must be ascii or binary.
"$build/scaffold" "$orig" --method none -o "$tmp/same.bgcode" -q
cmp -s "$orig" "$tmp/same.bgcode" || { echo "FAIL: --method none changed a binary file"; exit 1; }
if "$build/scaffold" "$orig" --output-format text -o "$tmp/x" 2>/dev/null; then echo "FAIL: --output-format text accepted"; exit 1; fi
# A damaged binary file (cut short): one line naming the block, exit 1, the file untouched.
head -c 100000 "$orig" > "$tmp/.cut.gcode.tmp"
cp "$tmp/.cut.gcode.tmp" "$tmp/cut.before"
if "$build/scaffold" "$tmp/.cut.gcode.tmp" 2> "$tmp/err.txt"; then echo "FAIL: a cut binary file was accepted"; exit 1; fi
[ "$(wc -l < "$tmp/err.txt")" -eq 1 ] || { echo "FAIL: not a one-line error:"; cat "$tmp/err.txt"; exit 1; }
grep -q "binary G-code block [0-9]* (G-code) at byte [0-9]*: " "$tmp/err.txt" || { echo "FAIL: error does not name the block:"; cat "$tmp/err.txt"; exit 1; }
cmp -s "$tmp/.cut.gcode.tmp" "$tmp/cut.before" || { echo "FAIL: the damaged input was changed"; exit 1; }
echo "binary G-code hook: in place, still binary, supported ($was -> $now), passes scaffold-check"
