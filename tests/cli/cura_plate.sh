#!/usr/bin/env bash
# A plate from a slicer that makes no exact copies: four corpus bunnies
# sliced by CuraEngine 4.13 (the Debian package; Ender 3 defaults, 0.1 mm
# layers, supports off; 14 s of CuraEngine and 2 of scaffold). They form
# two objects, planned as two independent groups. Cura's
# skins leave gaps between their lines: over them rule (a) holds what the
# layer beneath encloses, and the detector must hold it as the validator
# does. Before stop 57 it kept a cell of a bead's side over each gap's rim
# as overhang, chained over layers: 33 points dropped, 911 mm of support
# (columns up to 45 mm tall under specks inside solid skin) where 74.5 mm
# hold every overhang. No point is dropped now, and the output passes
# scaffold-check (held, standing). (Those tall columns also made the two
# groups' plans meet: this plate was the suite's joined plate with bars its
# parts found not held; joining is tested on synthetic plates in
# plates_test and plate_test.) Skipped (77) without CuraEngine or
# ../shared's bunny.
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
# extruder's settings (it says so and slices).
(cd "$tmp" && CURA_ENGINE_SEARCH_PATH="$defs" \
  CuraEngine slice -j "$defs/creality_ender3.def.json" -s support_enable=false -s adhesion_type=skirt \
  -s machine_end_gcode=M84 "${meshes[@]}" -o plate.gcode > slice.log 2>&1) ||
  { echo "FAIL: CuraEngine could not slice the plate:"; tail -5 "$tmp/slice.log"; exit 1; }
"$build/scaffold" -v "$tmp/plate.gcode" -o "$tmp/out.gcode" 2> "$tmp/log" || { echo "FAIL: scaffold:"; tail -5 "$tmp/log"; exit 1; }
fail=0
grep -q "support points in 2 independent groups" "$tmp/log" ||
  { echo "FAIL: the plate was not planned as two independent groups"; fail=1; }
summary="$(grep -E "info: [0-9]+ support points, " "$tmp/log" || true)"
[ -n "$summary" ] || { echo "FAIL: no summary line"; fail=1; }
if grep -q "points dropped" <<< "$summary"; then
  echo "FAIL: points dropped (specks over a skin's gaps?): $summary"; fail=1
fi
"$build/scaffold-check" "$tmp/out.gcode" --original "$tmp/plate.gcode" > "$tmp/check" 2>&1 ||
  { echo "FAIL: scaffold-check:"; tail -8 "$tmp/check"; fail=1; }
[ "$fail" -eq 0 ] || exit 1
echo "cura plate: 4 bunnies, 2 independent groups, no point dropped; scaffold-check passes (${summary#*info: })"
