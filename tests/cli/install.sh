#!/usr/bin/env bash
# `cmake --install` puts both programs, the README, the docs and the Cura
# script where a user finds them, and the installed scaffold gives the
# build's bytes; the .deb (CPack) holds the same files and names its
# library dependencies (where dpkg-shlibdeps, from dpkg-dev, is installed).
set -euo pipefail
build="$1"; src="$2"
tmp="$(mktemp -d)"; trap 'rm -rf "$tmp"' EXIT
files=(bin/scaffold bin/scaffold-check share/doc/scaffold/README.md share/doc/scaffold/docs/slicer-setup.md
       share/scaffold/cura/ScaffoldSupports.py)
cmake --install "$build" --prefix "$tmp/usr" >/dev/null
for f in "${files[@]}"; do [ -f "$tmp/usr/$f" ] || { echo "FAIL: cmake --install left out $f"; exit 1; }; done
in="$src/golden/two-level-pillars/input.gcode"
"$build/scaffold" -q "$in" -o "$tmp/built.gcode"
"$tmp/usr/bin/scaffold" -q "$in" -o "$tmp/installed.gcode"
cmp "$tmp/built.gcode" "$tmp/installed.gcode" || { echo "FAIL: the installed scaffold writes other bytes"; exit 1; }
"$tmp/usr/bin/scaffold-check" --min-stiffness 0 -q "$tmp/installed.gcode" --original "$in" || { echo "FAIL: installed scaffold-check"; exit 1; }
if ! command -v dpkg-shlibdeps >/dev/null; then
  echo "cmake --install: ${#files[@]} files, installed programs run (.deb not built: no dpkg-dev)"; exit 0
fi
(cd "$build" && cpack -G DEB -B "$tmp/deb" >/dev/null 2>"$tmp/cpack.err") || { echo "FAIL: cpack:"; cat "$tmp/cpack.err"; exit 1; }
deb="$(ls "$tmp"/deb/scaffold_*.deb)"
dpkg-deb -c "$deb" | awk '{print $6}' > "$tmp/deb.txt"
for f in "${files[@]}"; do grep -qx "./usr/$f" "$tmp/deb.txt" || { echo "FAIL: the .deb lacks /usr/$f"; exit 1; }; done
dpkg-deb -f "$deb" Depends | grep -q libboost-program-options || { echo "FAIL: .deb Depends: $(dpkg-deb -f "$deb" Depends)"; exit 1; }
echo "cmake --install and the .deb: ${#files[@]} files, installed programs run, Depends: $(dpkg-deb -f "$deb" Depends)"
