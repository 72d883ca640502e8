#!/usr/bin/env bash
# The real PrusaSlicer CLI runs scaffold as its post-processing script on a
# model with a shelf; the file it leaves must pass scaffold-check against the
# same slice without the hook. tools/test installs prusa-slicer if missing.
set -euo pipefail
build="$1"; src="$2"
if ! command -v prusa-slicer >/dev/null; then echo "FAIL: prusa-slicer not installed (tools/test installs it)"; exit 1; fi
tmp="$(mktemp -d)"; trap 'rm -rf "$tmp"' EXIT
common=(--nozzle-diameter 0.4 --filament-diameter 1.75 --layer-height 0.2 --first-layer-height 0.2
        --bed-shape 0x0,250x0,250x210,0x210 --center 125,105 --gcode-flavor marlin2)
export HOME="$tmp"  # PrusaSlicer wants a writable config dir
prusa-slicer --export-gcode "${common[@]}" "$src/tests/data/models/shelf.stl" -o "$tmp/plain.gcode" >/dev/null 2>&1
prusa-slicer --export-gcode "${common[@]}" --post-process "$build/scaffold" \
  "$src/tests/data/models/shelf.stl" -o "$tmp/hooked.gcode" > "$tmp/slicer.log" 2>&1 || {
  echo "FAIL: prusa-slicer with the hook failed:"; cat "$tmp/slicer.log"; exit 1; }
grep -q "^; scaffold " "$tmp/hooked.gcode" || { echo "FAIL: the hook did not run"; exit 1; }
grep -q "^;TYPE:Support material" "$tmp/hooked.gcode" || { echo "FAIL: no support written"; exit 1; }
"$build/scaffold-check" "$tmp/plain.gcode" > "$tmp/plain.txt" && { echo "FAIL: the unsupported shelf passed the check"; cat "$tmp/plain.txt"; exit 1; }
"$build/scaffold-check" "$tmp/hooked.gcode" --original "$tmp/plain.gcode" || { echo "FAIL: hooked output fails scaffold-check"; exit 1; }
echo "prusa-slicer hook: supported file passes scaffold-check"
