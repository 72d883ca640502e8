#!/usr/bin/env bash
# Time lines on a real file: the corpus's PrusaSlicer 2.5 overhang test (sliced
# without M73) given PrusaSlicer's M73 progress at every layer change, from
# its own estimate (1h 31m 38s), as PrusaSlicer writes them with "remaining
# time" on.
# After scaffold: the estimate is raised by the header's support print time,
# M73 starts at P0 with R raised by as much, never goes back, ends at P100
# R0, and scaffold-check --original still finds the model unchanged (M73
# lines may change like comments). Cura's ;TIME: and ;TIME_ELAPSED: on the
# Cura corpus file likewise.
set -euo pipefail
build="$1"; src="$2"
tmp="$(mktemp -d)"; trap 'rm -rf "$tmp"' EXIT
fail=0
bad() { echo "FAIL: $*"; fail=1; }
secs() {  # "1h 2m 3s" -> seconds
  echo "$1" | awk '{ t = 0; for (i = 1; i <= NF; i++) { v = $i + 0; u = substr($i, length($i));
    t += v * (u == "d" ? 86400 : u == "h" ? 3600 : u == "m" ? 60 : 1) } print t }'
}

zcat "$src/tests/data/corpus/overhang_test.prusaslicer25.nosup.gcode.gz" > "$tmp/raw.gcode"
n="$(grep -c '^;LAYER_CHANGE' "$tmp/raw.gcode")"
total=5498
grep -q "^; estimated printing time (normal mode) = 1h 31m 38s" "$tmp/raw.gcode" || bad "the corpus file's estimate changed"
awk -v n="$n" -v total="$total" '
  /^;LAYER_CHANGE/ { printf "M73 P%d R%d\n", int(100 * k / n), int((n - k) * total / n / 60 + 0.5); k++ }
  /^; estimated printing time \(normal/ { print "M73 P100 R0" }
  { print }' "$tmp/raw.gcode" > "$tmp/in.gcode"
"$build/scaffold" -q "$tmp/in.gcode" -o "$tmp/out.gcode"
support="$(secs "$(sed -n 's/^; scaffold: support print time = //p' "$tmp/out.gcode")")"
[ "$support" -gt 0 ] || bad "no support print time in the header"
est="$(secs "$(sed -n 's/^; estimated printing time (normal mode) = //p' "$tmp/out.gcode")")"
[ "$est" -eq $((total + support)) ] || bad "estimate $est s, want $total + $support"
first="$(grep -m1 '^M73 ' "$tmp/out.gcode")"
# R within a minute of the new total (the slicer's own R is rounded to minutes).
r="${first#M73 P0 R}"
[ "$first" != "$r" ] && [ $(( r * 60 - total - support )) -le 60 ] && [ $(( total + support - r * 60 )) -le 60 ] ||
  bad "first M73 is '$first' (total $total s, support $support s)"
[ "$(grep '^M73 ' "$tmp/out.gcode" | tail -1)" = "M73 P100 R0" ] || bad "the last M73 is not P100 R0"
grep '^M73 ' "$tmp/out.gcode" | awk '{ p = substr($2, 2) + 0; r = substr($3, 2) + 0
  if (NR > 1 && (p < lp || r > lr)) { print "M73 goes back at " NR ": " $0; bad = 1 } lp = p; lr = r } END { exit bad }' ||
  bad "M73 progress not monotonic"
[ "$(grep -c '^M73 ' "$tmp/out.gcode")" -eq "$((n + 1))" ] || bad "M73 lines added or lost"
"$build/scaffold-check" --min-stiffness 0 "$tmp/out.gcode" --original "$tmp/in.gcode" > "$tmp/check.txt" ||
  { bad "scaffold-check --original fails:"; cat "$tmp/check.txt"; }
grep -q "model vs original: unchanged" "$tmp/check.txt" || bad "the checker sees the model changed"

# Cura 4.13: ;TIME: raised by the support, ;TIME_ELAPSED: never back, the last
# one raised by all of it.
zcat "$src/tests/data/corpus/overhang_test.cura413.nosup.gcode.gz" > "$tmp/cura.gcode"
"$build/scaffold" -q "$tmp/cura.gcode" -o "$tmp/cura.out.gcode"
support="$(secs "$(sed -n 's/^; scaffold: support print time = //p' "$tmp/cura.out.gcode")")"
t0="$(sed -n 's/^;TIME://p' "$tmp/cura.gcode")"; t1="$(sed -n 's/^;TIME://p' "$tmp/cura.out.gcode")"
[ "$t1" -eq $((t0 + support)) ] || [ "$t1" -eq $((t0 + support + 1)) ] || [ "$t1" -eq $((t0 + support - 1)) ] ||
  bad ";TIME: $t0 -> $t1, support $support s"
e0="$(grep '^;TIME_ELAPSED:' "$tmp/cura.gcode" | tail -1 | cut -d: -f2)"
e1="$(grep '^;TIME_ELAPSED:' "$tmp/cura.out.gcode" | tail -1 | cut -d: -f2)"
awk -v a="$e0" -v b="$e1" -v s="$support" 'BEGIN { d = b - a - s; exit !(d > -1 && d < 1) }' ||
  bad "last ;TIME_ELAPSED: $e0 -> $e1, support $support s"
"$build/scaffold-check" --min-stiffness 0 "$tmp/cura.out.gcode" --original "$tmp/cura.gcode" > "$tmp/check2.txt" ||
  { bad "scaffold-check --original fails on the Cura output:"; cat "$tmp/check2.txt"; }

# The print-time change scaffold reports is the validator's estimate of the
# input and of the file written, whether the estimates run on a second
# thread (the output parsed from memory while it is written) or not.
# (The input fails the check: its overhangs are unheld.)
"$build/scaffold-check" --min-stiffness 0 "$tmp/cura.gcode" > "$tmp/check_in.txt" || true
want_before="$(sed -n 's/^  print time estimate: \([0-9.]*\) min$/\1/p' "$tmp/check_in.txt")"
want_after="$(sed -n 's/^  print time estimate: \([0-9.]*\) min (original [0-9.]* min)$/\1/p' "$tmp/check2.txt")"
for threads in 1 2; do
  "$build/scaffold" --threads "$threads" "$tmp/cura.gcode" -o "$tmp/cura.t$threads.gcode" 2> "$tmp/log.txt"
  cmp -s "$tmp/cura.t$threads.gcode" "$tmp/cura.out.gcode" || bad "--threads $threads writes another file"
  said="$(sed -n 's/.*; print time \([0-9]*\) -> \([0-9]*\) min.*/\1 \2/p' "$tmp/log.txt")"
  want="$(awk -v a="$want_before" -v b="$want_after" 'BEGIN { printf "%.0f %.0f", a, b }')"
  [ -n "$want_before" ] && [ -n "$want_after" ] && [ "$said" = "$want" ] ||
    bad "--threads $threads says print time '$said' min, the checker '$want' ($want_before, $want_after)"
done
# Written to stdout the same file, and the same estimate (not read back).
"$build/scaffold" "$tmp/cura.gcode" -o - > "$tmp/cura.stdout.gcode" 2> "$tmp/log.txt"
cmp -s "$tmp/cura.stdout.gcode" "$tmp/cura.out.gcode" || bad "stdout gets another file"
said="$(sed -n 's/.*; print time \([0-9]*\) -> \([0-9]*\) min.*/\1 \2/p' "$tmp/log.txt")"
[ "$said" = "$want" ] || bad "written to stdout, says print time '$said' min, the checker '$want'"
[ "$fail" -eq 0 ] || exit 1
echo "time lines: PrusaSlicer estimate and M73 ($n layers) and Cura ;TIME:/;TIME_ELAPSED: raised by the support's time; checker passes; the print time said is the checker's on 1 and 2 threads and to stdout"
