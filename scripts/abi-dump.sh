#!/usr/bin/env bash
# Dumps the ABI of libmechgraph_sdk.so.1 with abidw (abigail-tools), the way GStreamer's CI saves
# the ABI of its libraries: only the types reachable from exported functions, with the public C
# headers of sdk/include/mechgraph/c telling public from private. mg_abi_anchor names every public
# struct, so every function table is in the dump. Report only, for now: after the sdk-1.0 tag, CI
# compares this dump with the tag's (abidiff --suppressions sdk/abi/sdk-1.0.abignore old new).
#   scripts/abi-dump.sh BUILD_DIR [OUT_FILE]   (default OUT_FILE: BUILD_DIR/abi/libmechgraph_sdk.abi)
set -euo pipefail
build=${1:?usage: scripts/abi-dump.sh BUILD_DIR [OUT_FILE]}
out=${2:-$build/abi/libmechgraph_sdk.abi}
src=$(cd "$(dirname "$0")/.." && pwd)
library=$(ls "$build"/lib/libmechgraph_sdk.so.1 2>/dev/null || true)
[ -n "$library" ] || { echo "abi-dump: no $build/lib/libmechgraph_sdk.so.1; build mechgraph_sdk_library first" >&2; exit 2; }
command -v abidw >/dev/null || { echo "abi-dump: abidw not found (apt-get install abigail-tools)" >&2; exit 2; }
mkdir -p "$(dirname "$out")"
abidw --drop-private-types --headers-dir "$src/sdk/include/mechgraph/c" --out-file "$out" "$library"
functions=$(grep -c '<function-decl name=.mg_' "$out" || true)
structs=$(grep -o "<class-decl name='mg_[a-z0-9_]*'" "$out" | sort -u | wc -l)
echo "abi-dump: $out: $functions mg_* functions, $structs mg_* structs" >&2
