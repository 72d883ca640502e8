#!/usr/bin/env bash
# Pass-through must be byte-identical on real slicer files (PrusaSlicer with
# absolute/relative E, firmware retraction and z-hop; Slic3r; Cura), through
# a file, stdin/stdout, and in place.
set -euo pipefail
build="$1"; src="$2"
tmp="$(mktemp -d)"; trap 'rm -rf "$tmp"' EXIT
n=0
for gz in "$src"/tests/data/corpus/*.gcode.gz; do
  f="$tmp/in.gcode"
  gzip -dc "$gz" > "$f"
  "$build/scaffold" -q --method none "$f" -o "$tmp/out.gcode"
  cmp "$f" "$tmp/out.gcode" || { echo "FAIL file: $gz"; exit 1; }
  "$build/scaffold" -q --method none - < "$f" > "$tmp/out2.gcode"
  cmp "$f" "$tmp/out2.gcode" || { echo "FAIL stdin/stdout: $gz"; exit 1; }
  cp "$f" "$tmp/inplace.gcode"
  "$build/scaffold" -q --method none "$tmp/inplace.gcode"
  cmp "$f" "$tmp/inplace.gcode" || { echo "FAIL in place: $gz"; exit 1; }
  n=$((n+1))
done
[ "$n" -ge 3 ] || { echo "FAIL: only $n corpus files found"; exit 1; }
# A failed write leaves the input untouched and no temp file behind.
cp "$f" "$tmp/keep.gcode"
if SCAFFOLD_TEST_FAIL_WRITE=1 "$build/scaffold" -q --method none "$tmp/keep.gcode" 2>"$tmp/err"; then
  echo "FAIL: injected write failure not reported"; exit 1
fi
cmp "$f" "$tmp/keep.gcode" || { echo "FAIL: input changed after a failed write"; exit 1; }
grep -q "original file is unchanged" "$tmp/err" || { echo "FAIL: message: $(cat "$tmp/err")"; exit 1; }
[ -z "$(ls -A "$tmp" | grep scaffold- || true)" ] || { echo "FAIL: temp file left"; exit 1; }
echo "round trip identical on $n files"
