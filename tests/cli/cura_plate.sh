#!/usr/bin/env bash
# A plate from a slicer that makes no exact copies: four corpus bunnies
# sliced by CuraEngine 4.13 (the Debian package; Ender 3 defaults, 0.1 mm
# layers, supports off; 14 s of CuraEngine and 5 of scaffold). They form
# two objects, planned as two groups whose plans come within 2 mm, then
# joined as one. The joined group's first round is its parts' plans side
# by side, braced and checked as one: they hold, so the whole is not
# searched again (since stop 55: 7.4 s against 5.3). It starts without the
# bars its parts' plans found not held as built, and is made once. The
# output passes scaffold-check (held, standing). Skipped (77) without
# CuraEngine or ../shared's bunny; no synthetic scene in the suite gets bars
# not held by its plans.
set -euo pipefail
build="$1"; src="$2"
stl_gz="$src/../shared/corpus/bunny.stl.gz"
defs=/usr/share/cura/resources/definitions
if ! command -v CuraEngine >/dev/null || [ ! -f "$defs/creality_ender3.def.json" ] || [ ! -f "$stl_gz" ]; then
  echo "SKIPPED: needs CuraEngine (apt-get install cura-engine cura) and ../shared/corpus/bunny.stl.gz"; exit 77
fi
tmp="$(mktemp -d)"; trap 'rm -rf "$tmp"' EXIT
gzip -dc "$stl_gz" > "$tmp/bunny.stl"
meshes=()
for at in "-30 -25" "30 -25" "-30 25" "30 25"; do
  set -- $at
  meshes+=(-l bunny.stl -s "mesh_position_x=$1" -s "mesh_position_y=$2")
done
# As sliced in stop 52, where the plate was found: the extruders' folder not
# on CuraEngine's search path, so it takes its own defaults for the
# extruder's settings (it says so and slices). With the extruder's profile
# these four bunnies plan apart: this is the plate whose plans come close.
(cd "$tmp" && CURA_ENGINE_SEARCH_PATH="$defs" \
  CuraEngine slice -j "$defs/creality_ender3.def.json" -s support_enable=false -s adhesion_type=skirt \
  -s machine_end_gcode=M84 "${meshes[@]}" -o plate.gcode > slice.log 2>&1) ||
  { echo "FAIL: CuraEngine could not slice the plate:"; tail -5 "$tmp/slice.log"; exit 1; }
"$build/scaffold" -v "$tmp/plate.gcode" -o "$tmp/out.gcode" 2> "$tmp/log" || { echo "FAIL: scaffold:"; tail -5 "$tmp/log"; exit 1; }
fail=0
grep -q "plans of 2 groups came close: planned again as 1" "$tmp/log" ||
  { echo "FAIL: the plate was not planned as two groups joined (the scene no longer tests the joined plan)"; fail=1; }
learned="$(sed -n 's/.*a joined group starts without the \([0-9]*\) bars.*/\1/p' "$tmp/log")"
[ -n "$learned" ] && [ "$learned" -gt 0 ] || { echo "FAIL: the joined group started with no bar its parts found not held"; fail=1; }
grep -q "the parts' plans side by side hold: not planned again" "$tmp/log" ||
  { echo "FAIL: the joined group's parts' plans did not hold side by side"; fail=1; }
again="$(sed -n '/came close/,$p' "$tmp/log" | grep -c "planning again without them" || true)"
[ "$again" -eq 0 ] || { echo "FAIL: the joined plan was made again $again times for bars not held"; fail=1; }
"$build/scaffold-check" "$tmp/out.gcode" --original "$tmp/plate.gcode" > "$tmp/check" 2>&1 ||
  { echo "FAIL: scaffold-check:"; tail -8 "$tmp/check"; fail=1; }
[ "$fail" -eq 0 ] || exit 1
echo "cura plate: 4 bunnies, 2 groups joined; their plans held side by side (no search of the whole); the joined plan started without $learned bars its parts found not held and was made once; scaffold-check passes"
