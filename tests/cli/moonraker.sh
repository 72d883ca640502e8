#!/usr/bin/env bash
# The Moonraker component (integrations/moonraker/scaffold.py) against the
# real Moonraker code (../shared/tools/moonraker, commit d5ee171): the
# processor configuration the component registers is handed to Moonraker's
# own metadata.py, as its file manager does on an upload. scaffold runs on
# the file, 'scaffold' is in file_processors, the slicer, layer height,
# object height, thumbnails still come through, filament and time are
# raised by the support; a second upload is skipped by the ident regex, as
# is a file with '; scaffold: off'; enabled: False runs nothing; a file
# scaffold refuses is left as it was and the log says why. Then the
# installer (link, [scaffold] and [update_manager scaffold] sections, once).
# Skips (77) without ../shared (Moonraker's source, the wild corpus).
set -euo pipefail
build="$1"; src="$2"
shared="${SCAFFOLD_SHARED:-$src/../shared}"
[ -d "$shared" ] || shared=/work/shared
tarball="$shared/tools/moonraker/moonraker-d5ee171.tar.gz"
benchy="$shared/corpus/wild/prusaslicer261_benchy.gcode.gz"
vase="$shared/corpus/wild/prusaslicer274_spiral_vase.gcode.gz"
for f in "$tarball" "$benchy" "$vase"; do
  [ -f "$f" ] || { echo "SKIP: $f is absent (Moonraker's source and the wild corpus are in ../shared)"; exit 77; }
done
"$src/tools/deps" python3-pil >/dev/null   # what metadata.py needs, from Debian
py=/usr/bin/python3
export PYTHONDONTWRITEBYTECODE=1  # nothing written into the source tree
tmp="$(mktemp -d)"; trap 'rm -rf "$tmp"' EXIT
tar -xzf "$tarball" -C "$tmp"
metadata="$tmp/moonraker/moonraker/components/file_manager/metadata.py"
fail=0
bad() { echo "FAIL: $*"; fail=1; }

# The component, loaded as Moonraker loads it, with this [scaffold] section.
component_config() {  # extra lines for [scaffold] on stdin
  { echo "[scaffold]"; echo "path: $build/scaffold"; echo "timeout: 300"; cat; } > "$tmp/moonraker.conf"
  "$py" "$src/tests/cli/moonraker_component.py" "$src/integrations/moonraker/scaffold.py" "$tmp/moonraker.conf"
}
component_config <<< "method: scaffold" > "$tmp/proc.json"
"$py" - "$tmp/proc.json" "$build/scaffold" <<'PY' || bad "the registered configuration is not as expected"
import json, sys
c = json.load(open(sys.argv[1]))
assert c["name"] == "scaffold" and c["enabled"] is True and c["timeout"] == 300, c
assert c["command"] == [sys.argv[2], "--method", "scaffold", "{gcode_file_path}"], c["command"]
assert c["version"] != "?" and c["ident"]["location"] == "header", c
PY

# One upload: the file in a gcodes folder, metadata.py -c config.json.
upload() {  # NAME PROCESSOR_JSON -> $tmp/NAME.json (metadata), $tmp/NAME.log
  local name="$1" procs="$2"
  "$py" - "$tmp/gcodes" "$name" "$procs" > "$tmp/$name.cfg.json" <<'PY'
import json, sys
procs = json.load(open(sys.argv[3])) if sys.argv[3] != "none" else None
print(json.dumps({"gcode_dir": sys.argv[1], "filename": sys.argv[2], "check_objects": False,
                  "processors": [procs] if procs else []}))
PY
  "$py" "$metadata" -c "$tmp/$name.cfg.json" > "$tmp/$name.json" 2> "$tmp/$name.log" ||
    { bad "metadata.py failed on $name:"; cat "$tmp/$name.log"; }
}
field() { "$py" -c 'import json,sys; m=json.load(open(sys.argv[1]))["metadata"]; print(json.dumps(m.get(sys.argv[2])))' "$tmp/$1.json" "$2"; }

mkdir -p "$tmp/gcodes"
zcat "$benchy" > "$tmp/gcodes/plain.gcode"          # without any processor: the reference
cp "$tmp/gcodes/plain.gcode" "$tmp/gcodes/benchy.gcode"
upload plain.gcode none
upload benchy.gcode "$tmp/proc.json"
grep -q "Running processor scaffold" "$tmp/benchy.gcode.log" || bad "scaffold did not run"
grep -q "File processor scaffold successfully complete" "$tmp/benchy.gcode.log" || { bad "scaffold did not complete:"; cat "$tmp/benchy.gcode.log"; }
[ "$(sed -n 2p "$tmp/gcodes/benchy.gcode" | cut -c1-11)" = "; scaffold " ] || bad "the uploaded file carries no scaffold header"
[ "$(field benchy.gcode file_processors)" = '["scaffold"]' ] || bad "file_processors: $(field benchy.gcode file_processors)"
for f in slicer slicer_version layer_height first_layer_height object_height nozzle_diameter filament_type; do
  [ "$(field benchy.gcode $f)" = "$(field plain.gcode $f)" ] && [ "$(field benchy.gcode $f)" != null ] ||
    bad "$f: $(field plain.gcode $f) -> $(field benchy.gcode $f)"
done
"$py" - "$tmp/plain.gcode.json" "$tmp/benchy.gcode.json" "$tmp/gcodes" <<'PY' || bad "filament, time or thumbnails not as expected"
import json, os, sys
a = json.load(open(sys.argv[1]))["metadata"]; b = json.load(open(sys.argv[2]))["metadata"]
assert b["filament_total"] > a["filament_total"], (a["filament_total"], b["filament_total"])
assert b["filament_weight_total"] > a["filament_weight_total"]
assert b["estimated_time"] > a["estimated_time"], (a["estimated_time"], b["estimated_time"])
assert len(b["thumbnails"]) == len(a["thumbnails"]) >= 1
for t in b["thumbnails"]:
    assert os.path.getsize(os.path.join(sys.argv[3], t["relative_path"])) > 0, t
print(f"  filament_total {a['filament_total']} -> {b['filament_total']} mm, estimated_time "
      f"{a['estimated_time']} -> {b['estimated_time']} s, {len(b['thumbnails'])} thumbnails, "
      f"slicer {b['slicer']} {b['slicer_version']}, layer {b['layer_height']}, height {b['object_height']}")
PY

# A second upload of the processed file: skipped by the ident regex.
cp "$tmp/gcodes/benchy.gcode" "$tmp/gcodes/again.gcode"
upload again.gcode "$tmp/proc.json"
grep -q "File again.gcode previously processed by scaffold [0-9]" "$tmp/again.gcode.log" || { bad "the second upload was not skipped by ident:"; cat "$tmp/again.gcode.log"; }
grep -q "Running processor scaffold" "$tmp/again.gcode.log" && bad "scaffold ran on the second upload"
cmp -s "$tmp/gcodes/benchy.gcode" "$tmp/gcodes/again.gcode" || bad "the second upload was changed"
[ "$(field again.gcode filament_total)" = "$(field benchy.gcode filament_total)" ] || bad "the second upload's filament differs"

# Off for one file: a '; scaffold: off' line (the slicer's start G-code).
{ sed -n 1p "$tmp/gcodes/plain.gcode"; echo "; scaffold: off"; sed 1d "$tmp/gcodes/plain.gcode"; } > "$tmp/gcodes/off.gcode"
cp "$tmp/gcodes/off.gcode" "$tmp/off.before"
upload off.gcode "$tmp/proc.json"
grep -q "Running processor scaffold" "$tmp/off.gcode.log" && bad "scaffold ran on a file with '; scaffold: off'"
cmp -s "$tmp/off.before" "$tmp/gcodes/off.gcode" || bad "a file with '; scaffold: off' was changed"

# enabled: False: registered, never run.
component_config <<< "enabled: False" > "$tmp/proc-off.json"
cp "$tmp/gcodes/plain.gcode" "$tmp/gcodes/disabled.gcode"
upload disabled.gcode "$tmp/proc-off.json"
grep -q "Processor scaffold is disabled" "$tmp/disabled.gcode.log" || bad "enabled: False did not disable it"
cmp -s "$tmp/gcodes/plain.gcode" "$tmp/gcodes/disabled.gcode" || bad "a disabled processor changed the file"

# A file scaffold refuses (spiral vase): left as it was, the log says why,
# and Moonraker still reads its metadata.
zcat "$vase" > "$tmp/gcodes/vase.gcode"
cp "$tmp/gcodes/vase.gcode" "$tmp/vase.before"
upload vase.gcode "$tmp/proc.json"
grep -q "File processor scaffold failed with code 1" "$tmp/vase.gcode.log" || { bad "the failure is not logged:"; cat "$tmp/vase.gcode.log"; }
grep -q "scaffold: error: .*spiral vase mode is not supported" "$tmp/vase.gcode.log" || { bad "the log does not say why:"; cat "$tmp/vase.gcode.log"; }
cmp -s "$tmp/vase.before" "$tmp/gcodes/vase.gcode" || bad "the refused file was changed"
[ "$(field vase.gcode file_processors)" = '[]' ] || bad "a failed run is listed in file_processors"
[ "$(field vase.gcode slicer)" = '"PrusaSlicer"' ] || bad "no metadata for the refused file"

# A bad [scaffold] section is a config error, as Moonraker reports them.
if component_config <<< "method: trees" > /dev/null 2> "$tmp/cfgerr.txt"; then bad "method: trees accepted"; fi
grep -q "option 'method' must be one of scaffold, pillars" "$tmp/cfgerr.txt" || bad "no config error for method: trees"

# The installer: a link in moonraker/components, the two sections, once.
mkdir -p "$tmp/home/moonraker/moonraker/components" "$tmp/home/printer_data/config" "$tmp/bin"
printf '[server]\nhost: 0.0.0.0\n\n[update_manager]\n' > "$tmp/home/printer_data/config/moonraker.conf"
cp "$build/scaffold" "$tmp/bin/scaffold-linux-aarch64"
for run in 1 2; do
  HOME="$tmp/home" bash "$src/integrations/moonraker/install.sh" --binary "$tmp/bin/scaffold-linux-aarch64" \
    --repo example/scaffold --no-restart > "$tmp/install$run.log" 2>&1 || { bad "install.sh run $run failed:"; cat "$tmp/install$run.log"; }
done
link="$tmp/home/moonraker/moonraker/components/scaffold.py"
[ -L "$link" ] && [ "$(readlink -f "$link")" = "$(readlink -f "$src/integrations/moonraker/scaffold.py")" ] || bad "no link to the component"
conf="$tmp/home/printer_data/config/moonraker.conf"
[ "$(grep -c '^\[scaffold\]' "$conf")" = 1 ] || bad "[scaffold] not there exactly once"
[ "$(grep -c '^\[update_manager scaffold\]' "$conf")" = 1 ] || bad "[update_manager scaffold] not there exactly once"
grep -A6 '^\[update_manager scaffold\]' "$conf" | grep -q '^type: executable' || bad "the update manager entry is not type: executable"
grep -A6 '^\[update_manager scaffold\]' "$conf" | grep -q '^repo: example/scaffold' || bad "the update manager entry has no repo"
"$py" - "$tmp/home/scaffold/release_info.json" <<'PY' || bad "release_info.json is not what Moonraker's executable updater reads"
import json, sys
r = json.load(open(sys.argv[1]))
assert r["project_name"] == "scaffold" and r["project_owner"] == "example", r
assert r["asset_name"] == "scaffold-linux-aarch64" and r["version"].startswith("v"), r
PY
[ -x "$tmp/home/scaffold/scaffold-linux-aarch64" ] || bad "the executable was not put in ~/scaffold"
# What the installer wrote is a section the component loads.
{ sed -n '/^\[scaffold\]/,/^$/p' "$conf"; } > "$tmp/installed.conf"
HOME="$tmp/home" "$py" "$src/tests/cli/moonraker_component.py" "$src/integrations/moonraker/scaffold.py" "$tmp/installed.conf" > "$tmp/installed.json" ||
  bad "the installed [scaffold] section does not load"
grep -q '"enabled": true' "$tmp/installed.json" || bad "the installed section does not run the installed executable: $(cat "$tmp/installed.json")"

[ "$fail" -eq 0 ] || exit 1
echo "Moonraker d5ee171 metadata.py runs scaffold on upload, skips processed/off/disabled files, survives a refused file; installer idempotent"
