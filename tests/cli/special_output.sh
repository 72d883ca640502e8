#!/usr/bin/env bash
# Output to what is not a plain file. A device or a pipe (-o /dev/null, a
# FIFO a viewer reads) is written to, never replaced: the atomic rename
# over /dev/null left a plain file there, which broke every program that
# wrote to it after. A symbolic link (a slicer's output folder linked
# elsewhere) keeps being a link: its target is replaced, in place.
set -euo pipefail
build="$1"; src="$2"
tmp="$(mktemp -d)"; trap 'rm -rf "$tmp"' EXIT
fail=0
bad() { echo "FAIL: $*"; fail=1; }
zcat "$src/tests/data/corpus/overhang_test.prusaslicer25.nosup.gcode.gz" > "$tmp/in.gcode"
"$build/scaffold" -q "$tmp/in.gcode" -o "$tmp/file.gcode"

mkfifo "$tmp/fifo"
cat "$tmp/fifo" > "$tmp/got.gcode" &
reader=$!
"$build/scaffold" -q "$tmp/in.gcode" -o "$tmp/fifo"
if [ -p "$tmp/fifo" ]; then
  wait "$reader"
else
  kill "$reader" 2>/dev/null || true  # it waits on the FIFO that was replaced
  bad "the FIFO was replaced by a file"
fi
cmp -s "$tmp/got.gcode" "$tmp/file.gcode" || bad "what came through the FIFO differs from the file output"
ls -a "$tmp" | grep -q scaffold- && bad "a temporary file was left: $(ls -a "$tmp")"

cp "$tmp/in.gcode" "$tmp/real.gcode"
ln -s real.gcode "$tmp/link.gcode"
"$build/scaffold" -q "$tmp/link.gcode"
[ -L "$tmp/link.gcode" ] || bad "the symbolic link was replaced by a file"
cmp -s "$tmp/real.gcode" "$tmp/file.gcode" || bad "the link's target was not edited in place"
[ $fail -eq 0 ] && echo "ok: FIFO written through, symbolic link kept"
exit $fail
