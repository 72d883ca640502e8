#!/usr/bin/env bash
# Differential test of scaffold's binary G-code codec against Prusa's
# reference converter (../shared/tools/bgcode-ref, an external program):
# a fixed set of random G-code files (seeds 1-4, 32 files, around 2 MB,
# biased toward MeatPack's edges) through scaffold's encoder and the
# reference decoder, and through the reference encoder and scaffold's
# decoder, in six variants. Longer runs: tools/bgcode-diff-fuzz BUILD SECONDS.
set -euo pipefail
build="$1"; src="$2"
ref="$src/../shared/tools/bgcode-ref/bgcode"
[ -x "$ref" ] || { echo "SKIPPED: the reference converter ($ref) is not here"; exit 77; }
python3 "$src/tools/bgcode-diff-fuzz" "$build" --rounds 4 1 "$ref"
