#!/usr/bin/env bash
# Binary G-code that scaffold writes must read right with Prusa's reference
# decoder (libbgcode's `bgcode`, an external program in ../shared/tools; it
# is what PrusaSlicer's viewer and Prusa's printers go by), not only with
# scaffold's own decoder. For every PrusaSlicer file of ../shared/corpus in
# every variant (none, deflate, heatshrink 11/4 and 12/4, MeatPack with and
# without comment lines) and every file of ../shared/corpus/bgcode: the
# reference decoder's text of scaffold's binary output has the same commands,
# in order, as scaffold's ASCII output for the same input (for the corpus
# files in the variants that keep the comments, the ASCII output of the file
# they were made from, once per file: the same commands, and half the runs;
# MeatPack without comments drops the roles, and scaffold plans otherwise).
# The committed reproduction of the failing edge is MeatPack.PadsABlock... in
# tests/gcode/meatpack_test.cpp.
set -euo pipefail
build="$(cd "$1" && pwd)"; src="$(cd "$2" && pwd)"
shared="$src/../shared"
ref="$shared/tools/bgcode-ref/bgcode"
if [ ! -x "$ref" ] || [ ! -d "$shared/corpus" ]; then
  echo "SKIPPED: ../shared (the reference converter and the corpus) is not here"; exit 77
fi
tmp="$(mktemp -d)"; trap 'rm -rf "$tmp"' EXIT

# Variants: name and the reference converter's flags.
variants=(
  "none:--gcode_compression=0 --gcode_encoding=0"
  "deflate:--gcode_compression=1 --gcode_encoding=0"
  "heatshrink11:--gcode_compression=2 --gcode_encoding=0"
  "heatshrink12:--gcode_compression=3 --gcode_encoding=0"
  "meatpack:--gcode_compression=0 --gcode_encoding=1"
  "meatpack-comments:--gcode_compression=0 --gcode_encoding=2"
)

inputs=()
for f in "$shared"/corpus/*.prusaslicer25*.gcode.gz; do
  base="$(basename "$f" .gcode.gz)"
  gunzip -c "$f" > "$tmp/$base.gcode"
  for v in "${variants[@]}"; do
    name="${v%%:*}"; flags="${v#*:}"
    mkdir -p "$tmp/$name"
    cp "$tmp/$base.gcode" "$tmp/$name/$base.gcode"
    # shellcheck disable=SC2086
    "$ref" "$tmp/$name/$base.gcode" $flags > /dev/null 2>&1 || { echo "FAIL: the reference converter refused $base ($name)"; exit 1; }
    rm "$tmp/$name/$base.gcode"
    inputs+=("$tmp/$name/$base.bgcode")
  done
  mkdir -p "$tmp/ascii"
  "$build/scaffold" --method pillars "$tmp/$base.gcode" --output-format ascii -o "$tmp/ascii/$base.gcode" -q ||
    { echo "FAIL: scaffold (ascii) failed on $base"; exit 1; }
  rm "$tmp/$base.gcode"
done
mkdir -p "$tmp/given"
for f in "$shared"/corpus/bgcode/*.bgcode "$shared"/corpus/bgcode/*.bgcode.gz; do
  [ -e "$f" ] || continue
  case "$f" in *.gz) gunzip -c "$f" > "$tmp/given/$(basename "$f" .gz)";; *) cp "$f" "$tmp/given/";; esac
  inputs+=("$tmp/given/$(basename "${f%.gz}")")
done

# Commands only: comments and blank lines out, G lines without their spaces
# (the decoder's own spacing), other lines trimmed.
commands() {
  sed -e 's/;.*//' -e 's/[ \t]*$//' -e 's/^[ \t]*//' -e '/^G/s/[ \t]//g' -e '/^$/d' "$1"
}

one() {  # input.bgcode -> prints "ok" or the failure
  local in="$1" out="${1%.bgcode}.out" dec
  # --method pillars: the codec is under test, not the planner (it adds
  # support blocks all the same, at a tenth of the bridge search's time).
  "$build/scaffold" --method pillars "$in" -o "$out.bgcode" -q 2> "$out.err" || { echo "FAIL: scaffold failed on $in: $(cat "$out.err")"; return; }
  local ascii="$tmp/ascii/$(basename "$in" .bgcode).gcode"
  if [ -f "$ascii" ] && [ "$(basename "$(dirname "$in")")" != meatpack ]; then cp "$ascii" "$out.gcode"
  else "$build/scaffold" --method pillars "$in" --output-format ascii -o "$out.gcode" -q 2> "$out.err" || { echo "FAIL: scaffold (ascii) failed on $in"; return; }
  fi
  mkdir -p "$out.ref" && cp "$out.bgcode" "$out.ref/x.bgcode"
  "$ref" "$out.ref/x.bgcode" > "$out.err" 2>&1 || { echo "FAIL: the reference decoder refused scaffold's output for $in: $(tail -1 "$out.err")"; return; }
  if ! diff <(commands "$out.gcode") <(commands "$out.ref/x.gcode") > "$out.diff"; then
    echo "FAIL: the reference decoder reads scaffold's output for $in differently ($(grep -c '^>' "$out.diff") lines):"
    head -6 "$out.diff"; return
  fi
  echo "ok $(commands "$out.gcode" | wc -l)"
  # Kept for Klipper: the reference's text of three models and of the
  # corpus's own binary files. Two variants of the models: their commands
  # are the same in every variant (the diff above), only written with
  # spaces (heatshrink) or without (MeatPack, here with its comments).
  case "$in" in
    */heatshrink12/bunny.prusaslicer25.nosup.bgcode|*/heatshrink12/overhang_test.prusaslicer25.nosup.bgcode|*/heatshrink12/elephant.prusaslicer25.nosup.bgcode|\
    */meatpack-comments/bunny.prusaslicer25.nosup.bgcode|*/meatpack-comments/overhang_test.prusaslicer25.nosup.bgcode|*/meatpack-comments/elephant.prusaslicer25.nosup.bgcode|*/given/*)
      cp "$out.ref/x.gcode" "$klipper_dir/$(basename "$(dirname "$in")")-$(basename "$in" .bgcode).gcode" ;;
  esac
  rm -rf "$out.ref" "$out.gcode" "$out.bgcode"
}
klipper_dir="$tmp/klipper"; mkdir -p "$klipper_dir"
export -f one commands
export build ref klipper_dir tmp
printf '%s\n' "${inputs[@]}" | xargs -P "$(nproc)" -I{} bash -c 'one "$1"' _ {} > "$tmp/results.txt"
fails="$(grep -c '^FAIL' "$tmp/results.txt" || true)"
if [ "$fails" -gt 0 ]; then grep -A6 '^FAIL' "$tmp/results.txt"; echo "FAIL: $fails of ${#inputs[@]} outputs"; exit 1; fi
n="$(grep -c '^ok' "$tmp/results.txt")"
[ "$n" -eq "${#inputs[@]}" ] || { echo "FAIL: $n results for ${#inputs[@]} inputs"; exit 1; }
lines="$(awk '{s += $2} END {print s}' "$tmp/results.txt")"
# What a printer host gets from the binary output (the reference's text)
# must pass real firmware too: Klipper's batch check, where it is here.
klipper="$shared/tools/klipper-check/check.sh"
kmsg="Klipper not here"
if [ -f "$klipper" ]; then
  bash "$shared/tools/klipper-check/build.sh" > "$tmp/kbuild.log" 2>&1 || { echo "FAIL: Klipper's build failed"; tail "$tmp/kbuild.log"; exit 1; }
  if ! ( cd "$klipper_dir" && AUTO=1 JOBS="$(nproc)" bash "$klipper" *.gcode ) > "$tmp/klipper.txt" 2>&1; then
    echo "FAIL: Klipper refuses the reference's text of scaffold's binary output:"; grep -v ': OK' "$tmp/klipper.txt" | head; exit 1
  fi
  kmsg="Klipper accepts the reference's text of $(grep -c ': OK' "$tmp/klipper.txt") of them (bunny, overhang_test, elephant in heatshrink and MeatPack; the corpus's own files)"
fi
echo "reference decoder: all $n binary outputs read right (${#variants[@]} variants of each PrusaSlicer corpus file, and the corpus's own .bgcode files), $lines commands compared; $kmsg"
