#!/usr/bin/env bash
# The OctoPrint plugin (integrations/octoprint) through a driver that calls
# its preprocessor hook as OctoPrint's FileManager.add_file does (OctoPrint
# is not in Debian): an upload is stored with scaffold's supports, byte for
# byte what scaffold writes itself, from a disk upload or a stream; a second
# upload of the result, a file with '; scaffold: off', a disabled plugin and
# a non-G-code file are stored as they came; a file scaffold refuses is
# stored unchanged and the log says why; a missing executable too. The
# settings page binds every setting.
set -euo pipefail
build="$1"; src="$2"
py=/usr/bin/python3; [ -x "$py" ] || py=python3
export PYTHONDONTWRITEBYTECODE=1  # nothing written into the source tree
plugin="$src/integrations/octoprint"
tmp="$(mktemp -d)"; trap 'rm -rf "$tmp"' EXIT
fail=0
bad() { echo "FAIL: $*"; fail=1; }
upload() {  # NAME INPUT MODE [KEY=VALUE...]: stores $tmp/store/NAME, log in $tmp/NAME.log
  local name="$1" in="$2" mode="$3"; shift 3
  "$py" "$src/tests/cli/octoprint_driver.py" "$plugin" "$in" "$tmp/store/$name" "$mode" "path=$build/scaffold" "$@" \
    > "$tmp/$name.out" 2> "$tmp/$name.log" || { bad "the driver failed on $name:"; cat "$tmp/$name.log"; }
}
mkdir -p "$tmp/store"
zcat "$src/tests/data/corpus/overhang_test.prusaslicer25.nosup.gcode.gz" > "$tmp/in.gcode"
"$build/scaffold" -q "$tmp/in.gcode" -o "$tmp/expected.gcode"
"$build/scaffold" -q "$tmp/in.gcode" --method pillars -o "$tmp/expected-pillars.gcode"

upload a.gcode "$tmp/in.gcode" disk
cmp -s "$tmp/expected.gcode" "$tmp/store/a.gcode" || bad "a disk upload is not stored as scaffold writes it"
grep -q "scaffold added supports to a.gcode" "$tmp/a.gcode.log" || bad "no log line for the upload"
grep -q "DiskFileWrapper" "$tmp/a.gcode.out" || bad "the hook did not return a disk-file wrapper"
[ -z "$(ls "$tmp"/store/*.upload 2>/dev/null)" ] || bad "the upload's temporary file was left behind"
upload b.gcode "$tmp/in.gcode" stream method=pillars
cmp -s "$tmp/expected-pillars.gcode" "$tmp/store/b.gcode" || bad "a streamed upload with method pillars is not as scaffold writes it"

upload again.gcode "$tmp/store/a.gcode" disk
cmp -s "$tmp/store/a.gcode" "$tmp/store/again.gcode" || bad "a second upload was changed"
grep -q "already processed by scaffold [0-9]" "$tmp/again.gcode.log" || bad "the second upload's log does not say so"

{ head -1 "$tmp/in.gcode"; echo "; scaffold: off"; tail -n +2 "$tmp/in.gcode"; } > "$tmp/off.gcode"
upload off.gcode "$tmp/off.gcode" disk
cmp -s "$tmp/off.gcode" "$tmp/store/off.gcode" || bad "a file with '; scaffold: off' was changed"

upload disabled.gcode "$tmp/in.gcode" disk enabled=false
cmp -s "$tmp/in.gcode" "$tmp/store/disabled.gcode" || bad "the disabled plugin changed the file"

printf 'solid x\nendsolid x\n' > "$tmp/model.stl"
upload model.stl "$tmp/model.stl" disk
cmp -s "$tmp/model.stl" "$tmp/store/model.stl" || bad "a non-G-code upload was changed"

{ cat "$tmp/in.gcode"; echo "; spiral_vase = 1"; } > "$tmp/vase.gcode"
upload vase.gcode "$tmp/vase.gcode" disk
cmp -s "$tmp/vase.gcode" "$tmp/store/vase.gcode" || bad "a refused file was not stored unchanged"
grep -q "scaffold failed with code 1 on .*stored unchanged: scaffold: error: .*spiral vase mode is not supported" "$tmp/vase.gcode.log" ||
  { bad "the log does not say why the file was refused:"; cat "$tmp/vase.gcode.log"; }

upload missing.gcode "$tmp/in.gcode" disk path=/nonexistent/scaffold
cmp -s "$tmp/in.gcode" "$tmp/store/missing.gcode" || bad "a missing executable changed the file"
grep -q "scaffold did not run on .*No such file" "$tmp/missing.gcode.log" || bad "a missing executable is not logged"

# The settings page binds the five settings the plugin reads.
for key in enabled path method options timeout; do
  grep -q "settings.plugins.scaffold.$key" "$plugin/octoprint_scaffold/templates/scaffold_settings.jinja2" ||
    bad "the settings page has no field for $key"
done
[ "$fail" -eq 0 ] || exit 1
echo "OctoPrint preprocessor hook: uploads stored as scaffold writes them (disk and stream), processed/off/disabled/non-G-code/refused/missing-executable stored unchanged with the reason logged"
