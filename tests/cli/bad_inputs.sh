#!/usr/bin/env bash
# The catalogue of bad inputs: each must give exactly this one-line error,
# exit non-zero, and leave the input untouched (never a half-written file).
set -uo pipefail
build="$1"; src="$2"
tmp="$(mktemp -d)"; trap 'chmod -R u+w "$tmp"; rm -rf "$tmp"' EXIT
fail=0; n=0
# expect NAME EXPECTED-STDERR-SUBSTRING [scaffold args...] < input in $tmp/in.gcode
expect() {
  local name="$1" want="$2"; shift 2
  n=$((n+1))
  cp "$tmp/in.gcode" "$tmp/orig.gcode" 2>/dev/null || true
  if "$build/scaffold" "$@" 2>"$tmp/err" >/dev/null; then
    echo "FAIL $name: exit 0"; fail=1; return
  fi
  if ! grep -qF -- "$want" "$tmp/err"; then
    echo "FAIL $name: expected '$want', got: $(cat "$tmp/err")"; fail=1; return
  fi
  if [ "$(wc -l < "$tmp/err")" -ne 1 ]; then echo "FAIL $name: more than one line: $(cat "$tmp/err")"; fail=1; fi
  if [ -f "$tmp/orig.gcode" ] && ! cmp -s "$tmp/in.gcode" "$tmp/orig.gcode"; then echo "FAIL $name: input changed"; fail=1; fi
  if ls -a "$tmp" | grep -q '\.scaffold-'; then echo "FAIL $name: temp file left behind"; fail=1; fi
}
body() { printf 'G90\nM82\nG92 E0\nG1 Z0.2 F7800\nG1 X10 Y10\nG1 X20 Y10 E1 F1800\n'; }

: > "$tmp/in.gcode"
expect empty "in.gcode: the file is empty" "$tmp/in.gcode"
printf 'G28\nG1 X10 Y10 F3000\n' > "$tmp/in.gcode"
expect no-extrusions "no extrusions found" --method pillars "$tmp/in.gcode"
printf 'G90\nM83\nG1 Z0.2 F7800\nG1 X10 Y10\nG1 X20 Y10 A1 F1800\n; gcode_flavor = mach3\n' > "$tmp/in.gcode"
expect mach3-axis "the mach3 flavour extrudes on the A axis" "$tmp/in.gcode"
printf 'GCDE\001\000\000\000binary' > "$tmp/in.gcode"
expect binary-checksum "in.gcode: binary G-code: unknown checksum type 26978 at byte 8" "$tmp/in.gcode"
printf 'GCDE\001\000\000\000\001\000\001\000' > "$tmp/in.gcode"
expect binary-cut "in.gcode: binary G-code block 0 at byte 10: the file ends inside the block header" "$tmp/in.gcode"
printf 'GCDE\001\000\000\000\000\000\001\000\000\000\004\000\000\000\000\000G1\n' > "$tmp/in.gcode"
expect binary-lying-size "in.gcode: binary G-code block 0 (G-code) at byte 10: the block says it holds 14 bytes but only 13 remain" "$tmp/in.gcode"
{ body; printf 'G20\nG1 X1 Y1\n'; } > "$tmp/in.gcode"
expect inch-mix "in.gcode:7: G20 (inches) after moves in millimetres" "$tmp/in.gcode"
{ body; printf '; spiral_vase = 1\n'; } > "$tmp/in.gcode"
expect vase "spiral vase mode is not supported" "$tmp/in.gcode"
{ body; printf '; complete_objects = 1\n'; } > "$tmp/in.gcode"
expect sequential "sequential printing (complete objects) is not supported" "$tmp/in.gcode"
{ body; printf 'G1 X1e99 Y10 E2\n'; } > "$tmp/in.gcode"
expect huge "in.gcode:7: coordinate out of range" "$tmp/in.gcode"
{ body; printf 'G1 Xnan Y10 E2\n'; } > "$tmp/in.gcode"
expect nan "in.gcode:7: parameter without a number" "$tmp/in.gcode"
{ body; printf 'G1 X1.2.3 Y10 E2\n'; } > "$tmp/in.gcode"
expect malformed "in.gcode:7: malformed number: 'G1 X1.2.3 Y10 E2'" "$tmp/in.gcode"
{ body; printf 'G1 X0 Y{machine_depth} ;Present print\n'; } > "$tmp/in.gcode"
expect placeholder "in.gcode:7: a slicer placeholder left unfilled ({...}: the slicer's custom G-code was not expanded): 'G1 X0 Y{machine_depth} ;Present print'" "$tmp/in.gcode"
{ body; printf 'G2 X30 Y10 E2\n'; } > "$tmp/in.gcode"
expect arc "in.gcode:7: G2/G3 arc with neither I/J nor R" "$tmp/in.gcode"
expect missing "cannot open for reading: No such file or directory" "$tmp/nope.gcode"
body > "$tmp/in.gcode"
expect bad-option "unrecognised option '--frobnicate'" --frobnicate "$tmp/in.gcode"
expect bad-value "setting '--xy-gap' from the command line is not a number: 'wide'" --xy-gap wide "$tmp/in.gcode"
expect bad-threads "--threads must be at least 1, got 0" --threads 0 "$tmp/in.gcode"
mkdir -p "$tmp/ro"; body > "$tmp/ro/in.gcode"; chmod a-w "$tmp/ro"
if [ "$(id -u)" -ne 0 ]; then
  expect read-only-dir "cannot create the output file: Permission denied" --method none "$tmp/ro/in.gcode"
elif [ -d /sys/kernel ] && ! touch /sys/scaffold-probe 2>/dev/null; then
  # root writes into a read-only directory anyway; sysfs refuses even root.
  expect read-only-dir "cannot create the output file: Permission denied" --method none "$tmp/in.gcode" -o /sys/out.gcode
fi
chmod u+w "$tmp/ro"
n=$((n+1))
if "$build/scaffold" --method none "$tmp/in.gcode" -o - > /dev/full 2>"$tmp/err"; then echo "FAIL disk-full: exit 0"; fail=1
elif ! grep -q "<stdout>: write failed: No space left on device" "$tmp/err"; then echo "FAIL disk-full: $(cat "$tmp/err")"; fail=1; fi
SCAFFOLD_TEST_FAIL_WRITE=1 expect injected-failure "the original file is unchanged" --method none "$tmp/in.gcode"

# Inputs that must pass through unchanged with --method none.
ok() {
  local name="$1"; n=$((n+1))
  "$build/scaffold" -q --method none "$tmp/in.gcode" -o "$tmp/out.gcode" 2>"$tmp/err" && cmp -s "$tmp/in.gcode" "$tmp/out.gcode" \
    || { echo "FAIL $name: $(cat "$tmp/err")"; fail=1; }
}
{ body; printf 'M900 K0.05\nG29.1 Z0.1\nM486 S1\nM117 Hello; world\nT?\nG4 P100\n'; } > "$tmp/in.gcode"; ok unknown-codes
{ body; printf '; '; head -c 70000 /dev/zero | tr '\0' 'x'; printf '\n'; } > "$tmp/in.gcode"; ok long-comment
{ body; printf '; caf\xe9 \xff\xfe\n'; } > "$tmp/in.gcode"; ok non-utf8
{ body; printf 'G1 X30 Y10 E2'; } > "$tmp/in.gcode"; ok truncated-last-line
{ body; printf 'G92 E9999990\nG1 X30 Y10 E9999991\nG1 X40 Y10 E9999992\n'; } > "$tmp/in.gcode"; ok huge-e
[ "$fail" -eq 0 ] || exit 1
echo "$n bad-input cases behave"
