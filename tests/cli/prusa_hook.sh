#!/usr/bin/env bash
# The real PrusaSlicer CLI runs scaffold as its post-processing script on a
# model with a shelf; the file it leaves must pass scaffold-check against the
# G-code the slicer handed the hook (kept by a wrapper: PrusaSlicer 2.5 does
# not slice the same model to the same bytes every time, so a second slice
# is no fair original). tools/test installs prusa-slicer if missing.
set -euo pipefail
build="$1"; src="$2"
if ! command -v prusa-slicer >/dev/null; then echo "FAIL: prusa-slicer not installed (tools/test installs it)"; exit 1; fi
tmp="$(mktemp -d)"; trap 'rm -rf "$tmp"' EXIT
common=(--nozzle-diameter 0.4 --filament-diameter 1.75 --layer-height 0.2 --first-layer-height 0.2
        --bed-shape 0x0,250x0,250x210,0x210 --center 125,105 --gcode-flavor marlin2)
export HOME="$tmp"  # PrusaSlicer wants a writable config dir
printf '#!/bin/sh\ncp "$1" "%s/plain.gcode" && exec "%s" "$1"\n' "$tmp" "$build/scaffold" > "$tmp/hook.sh"
chmod +x "$tmp/hook.sh"
prusa-slicer --export-gcode "${common[@]}" --post-process "$tmp/hook.sh" \
  "$src/tests/data/models/shelf.stl" -o "$tmp/hooked.gcode" > "$tmp/slicer.log" 2>&1 || {
  echo "FAIL: prusa-slicer with the hook failed:"; cat "$tmp/slicer.log"; exit 1; }
grep -q "^; scaffold " "$tmp/hooked.gcode" || { echo "FAIL: the hook did not run"; exit 1; }
grep -q "^;TYPE:Support material" "$tmp/hooked.gcode" || { echo "FAIL: no support written"; exit 1; }
"$build/scaffold-check" "$tmp/plain.gcode" > "$tmp/plain.txt" && { echo "FAIL: the unsupported shelf passed the check"; cat "$tmp/plain.txt"; exit 1; }
"$build/scaffold-check" --min-stiffness 0 "$tmp/hooked.gcode" --original "$tmp/plain.gcode" || { echo "FAIL: hooked output fails scaffold-check"; exit 1; }
echo "prusa-slicer hook: supported file passes scaffold-check"
