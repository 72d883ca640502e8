#!/usr/bin/env bash
# scaffold's header line (after the slicer's first line; in binary G-code at
# the top of the G-code) marks a file it processed: a second run, in place
# or to another file, ASCII or binary, leaves the bytes as they are and says
# so on stderr. Upload hooks (Moonraker, OctoPrint) may see a file twice.
# The header also matches the ident regex of integrations/moonraker.
set -euo pipefail
build="$1"; src="$2"
tmp="$(mktemp -d)"; trap 'rm -rf "$tmp"' EXIT
fail=0
bad() { echo "FAIL: $*"; fail=1; }
ident='^; scaffold (?P<version>\d+\.\d+\.\d+) \(post-processed supports\)'

zcat "$src/tests/data/corpus/overhang_test.prusaslicer25.nosup.gcode.gz" > "$tmp/in.gcode"
cp "$src/tests/data/bgcode/overhang_test.prusaslicer25.nosup.prusaslicer.bgcode" "$tmp/in.bgcode"
for ext in gcode bgcode; do
  "$build/scaffold" -q "$tmp/in.$ext" -o "$tmp/once.$ext"
  cmp -s "$tmp/in.$ext" "$tmp/once.$ext" && bad "$ext: the first run changed nothing"
  # To another file.
  "$build/scaffold" "$tmp/once.$ext" -o "$tmp/twice.$ext" 2> "$tmp/err.$ext"
  cmp -s "$tmp/once.$ext" "$tmp/twice.$ext" || bad "$ext: a second run to another file changed the bytes"
  grep -q "already processed by scaffold [0-9.]* (its header line): left unchanged" "$tmp/err.$ext" ||
    { bad "$ext: stderr does not say so:"; cat "$tmp/err.$ext"; }
  # In place (the slicer's and the hosts' way): not even rewritten.
  cp -p "$tmp/once.$ext" "$tmp/inplace.$ext"
  touch -d "2001-01-01 00:00:00" "$tmp/inplace.$ext"
  "$build/scaffold" -q "$tmp/inplace.$ext"
  cmp -s "$tmp/once.$ext" "$tmp/inplace.$ext" || bad "$ext: a second run in place changed the bytes"
  [ "$(stat -c %Y "$tmp/inplace.$ext")" = "$(date -d "2001-01-01 00:00:00" +%s)" ] || bad "$ext: rewritten in place"
  # Through a pipe.
  "$build/scaffold" -q - < "$tmp/once.$ext" > "$tmp/piped.$ext"
  cmp -s "$tmp/once.$ext" "$tmp/piped.$ext" || bad "$ext: a second run through a pipe changed the bytes"
done
# Where the header is, and that Moonraker's ident regex (Python's re, as
# metadata.py uses it) finds it in the first MiB.
"$build/scaffold" -q "$tmp/once.bgcode" --method none --output-format ascii -o "$tmp/once-bin.gcode"
[ "$(sed -n 2p "$tmp/once.gcode" | cut -c1-11)" = "; scaffold " ] || bad "ASCII: the header is not the second line"
for f in "$tmp/once.gcode" "$tmp/once-bin.gcode"; do
  py="$(command -v /usr/bin/python3 python3 | head -1)"
  v="$("$py" -c 'import re,sys; d=open(sys.argv[1],"rb").read(1<<20).decode(errors="ignore"); m=re.search(sys.argv[2],d,re.MULTILINE); print(m.group("version") if m else "")' "$f" "$ident")"
  [ -n "$v" ] || bad "the ident regex does not match $(basename "$f")"
done
[ "$fail" -eq 0 ] || exit 1
echo "second runs leave ASCII and binary outputs byte-identical (to a file, in place without a rewrite, piped) and say so; ident matches"
