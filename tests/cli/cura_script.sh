#!/usr/bin/env bash
# A Cura file for 2.85 mm filament, as Cura hands it to its scripts (no
# ;SETTING_3 block): scaffold derives the diameter from the model's own
# lines and says so; tools/cura/ScaffoldSupports.py passes Cura's settings
# on the command line, and then the same support comes out without a guess.
set -euo pipefail
build="$1"; src="$2"
tmp="$(mktemp -d)"; trap 'rm -rf "$tmp"' EXIT
# The 1.75 mm sample with every E scaled by (1.75 / 2.85)^2: the same beads
# on a 2.85 mm printer.
awk 'BEGIN { k = (1.75 / 2.85) ^ 2 }
     /^G[01] / && / E-?[0-9.]/ {
       out = ""; n = split($0, w, " ")
       for (i = 1; i <= n; ++i) {
         if (w[i] ~ /^E-?[0-9.]+$/) w[i] = sprintf("E%.5f", substr(w[i], 2) * k)
         out = out (i > 1 ? " " : "") w[i]
       }
       print out; next }
     { print }' "$src/tests/data/dialects/cura413.gcode" | grep -v '^;SETTING_3' > "$tmp/in.gcode"

"$build/scaffold" "$tmp/in.gcode" -o "$tmp/guessed.gcode" 2> "$tmp/log"
grep -q "2.85 mm filament" "$tmp/log" || { echo "FAIL: no warning about the derived diameter:"; cat "$tmp/log"; exit 1; }
"$build/scaffold-check" --min-stiffness 0 -q "$tmp/guessed.gcode" --original "$tmp/in.gcode" || {
  "$build/scaffold-check" --min-stiffness 0 "$tmp/guessed.gcode" --original "$tmp/in.gcode"; echo "FAIL: output fails scaffold-check"; exit 1; }
# Support bead cross-section implied at 2.85 mm: that of a 0.45 x 0.2 bead
# (0.08 mm^2), not 2.65 times it as with the 1.75 mm default.
awk '/^;TYPE:(Support material|SUPPORT)$/ { s = 1; next } /^;TYPE:/ { s = 0 }
     /^G1 / { x1 = x; y1 = y; e1 = ""; for (i = 2; i <= NF; ++i) {
                if ($i ~ /^X/) x = substr($i, 2); if ($i ~ /^Y/) y = substr($i, 2); if ($i ~ /^E/) e1 = substr($i, 2) }
              if (s && e1 != "" && e1 > e && (x != x1 || y != y1)) { len += sqrt((x - x1) ^ 2 + (y - y1) ^ 2); de += e1 - e }
              if (e1 != "") e = e1 }
     /^G92 E/ { e = substr($2, 2) }
     END { a = de * 3.14159265 * 2.85 * 2.85 / 4 / len; printf "%.4f\n", a
           if (len < 10 || a < 0.06 || a > 0.11) exit 1 }' "$tmp/guessed.gcode" > "$tmp/area" || {
  echo "FAIL: support bead cross-section $(cat "$tmp/area") mm^2 at 2.85 mm filament"; exit 1; }

# The Cura script, outside Cura, with the settings Cura would give it.
cat > "$tmp/run.py" <<PY
import importlib.util, sys
spec = importlib.util.spec_from_file_location("ScaffoldSupports", "$src/tools/cura/ScaffoldSupports.py")
m = importlib.util.module_from_spec(spec); spec.loader.exec_module(m)
m.cura_settings = lambda: {"material_diameter": "2.85", "machine_nozzle_size": "0.4", "layer_height": "0.2"}
s = m.ScaffoldSupports(); s._values = {"binary": "$build/scaffold", "method": "scaffold", "extra": ""}
text = open("$tmp/in.gcode", newline="").read()
out = s.execute([text])
open("$tmp/script.gcode", "w", newline="").write("".join(out))
PY
python3 "$tmp/run.py" 2> "$tmp/script.log"
if grep -q "implies\|filament" "$tmp/script.log"; then echo "FAIL: the script's run still guessed:"; cat "$tmp/script.log"; exit 1; fi
cmp "$tmp/guessed.gcode" "$tmp/script.gcode" || { echo "FAIL: support differs with Cura's settings given"; exit 1; }
echo "cura script: 2.85 mm derived ($(cat "$tmp/area") mm^2 support beads), same support with Cura's settings passed"
