#!/usr/bin/env bash
# The static ARM programs (tools/release --linux-cross-only: build-arm/ARCH)
# run under Debian's qemu-user and give the x86-64 build's bytes on every
# file of tests/data/corpus and the bundled binary G-code (default method),
# the same scaffold-check report, and on three of them (the binary one, a
# PrusaSlicer and a Cura file) the same pillars through stdin/stdout (the
# pipe and the method, not the file, are what those add: on every file they
# took a third of the test's emulated time).
# In CI (or with SCAFFOLD_ARM=1) qemu-user is installed here and tools/test
# builds the programs first; elsewhere a missing qemu or build skips (77).
set -uo pipefail
build="$1"; src="$2"
armbuild="${SCAFFOLD_ARM_BUILD:-$src/build-arm}"
if ! command -v qemu-aarch64 >/dev/null && { [ -n "${CI:-}" ] || [ "${SCAFFOLD_ARM:-}" = 1 ]; }; then
  echo "arm_qemu: installing qemu-user" >&2
  SUDO=""; [ "$(id -u)" -eq 0 ] || SUDO=sudo
  $SUDO apt-get update -qq && DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends qemu-user >/dev/null
fi
command -v qemu-aarch64 >/dev/null || { echo "SKIP: qemu-user is not installed (apt-get install qemu-user)"; exit 77; }
# The arches tools/test built (SCAFFOLD_ARM_ARCHES, default aarch64), not
# whatever an older build left in build-arm.
arches=()
for a in ${SCAFFOLD_ARM_ARCHES:-aarch64}; do [ -x "$armbuild/$a/scaffold" ] && arches+=("$a"); done
[ ${#arches[@]} -gt 0 ] || { echo "SKIP: no ARM build in $armbuild (tools/release --linux-cross-only builds it)"; exit 77; }
tmp="$(mktemp -d)"; trap 'rm -rf "$tmp"' EXIT
fail=0; n=0; p=0
bad() { echo "FAIL $*"; fail=1; }
qemu_of() { case "$1" in aarch64) echo qemu-aarch64 ;; armhf) echo qemu-arm ;; esac; }

inputs=()
for f in "$src"/tests/data/corpus/*.gcode.gz; do
  b="$(basename "$f" .gz)"; zcat "$f" > "$tmp/$b"; inputs+=("$tmp/$b")
done
cp "$src/tests/data/bgcode/overhang_test.prusaslicer25.nosup.prusaslicer.bgcode" "$tmp/bin.bgcode"
inputs+=("$tmp/bin.bgcode")
piped() { case "$(basename "$1")" in bin.bgcode|overhang_test.prusaslicer25.nosup.gcode|bunny.cura413.nosup.gcode) return 0 ;; esac; return 1; }
for in in "${inputs[@]}"; do
  b="$(basename "$in")"
  "$build/scaffold" -q "$in" -o "$tmp/$b.x86" || bad "x86-64 scaffold failed on $b"
  if piped "$in"; then "$build/scaffold" -q --method pillars - < "$in" > "$tmp/$b.x86.pillars"; fi
  cp "$tmp/$b.x86" "$tmp/out"   # the report names its file: the same name for both
  "$build/scaffold-check" "$tmp/out" --original "$in" > "$tmp/$b.x86.check" 2>&1
done
for a in "${arches[@]}"; do
  q="$(qemu_of "$a")"; exe="$armbuild/$a"
  "$q" "$exe/scaffold" --version | cmp -s - <("$build/scaffold" --version) || bad "$a: --version differs"
  for in in "${inputs[@]}"; do
    b="$(basename "$in")"
    "$q" "$exe/scaffold" -q "$in" -o "$tmp/$b.$a" || bad "$a: scaffold failed on $b"
    cmp -s "$tmp/$b.x86" "$tmp/$b.$a" || bad "$a: $b differs from the x86-64 output"
    if piped "$in"; then
      "$q" "$exe/scaffold" -q --method pillars - < "$in" > "$tmp/$b.$a.pillars"
      cmp -s "$tmp/$b.x86.pillars" "$tmp/$b.$a.pillars" || bad "$a: $b (pillars, piped) differs from the x86-64 output"
      p=$((p + 1))
    fi
    cp "$tmp/$b.$a" "$tmp/out"
    "$q" "$exe/scaffold-check" "$tmp/out" --original "$in" > "$tmp/$b.$a.check" 2>&1
    cmp -s "$tmp/$b.x86.check" "$tmp/$b.$a.check" || bad "$a: scaffold-check's report on $b differs"
    n=$((n + 1))
  done
done
[ "$fail" -eq 0 ] || exit 1
[ "$p" -eq $((3 * ${#arches[@]})) ] || { echo "FAIL: $p piped pillars runs, not 3 per arch (a piped file missing?)"; exit 1; }
echo "${arches[*]} under qemu-user: $n files byte-identical to x86-64 (default; pillars piped on $p), scaffold-check reports identical"
