#!/usr/bin/env bash
# Compares the SDK's C boundary of a release with the current one, the two ways that together
# leave no gap (used by scripts/test-sdk-compat.sh and tests/sdk/abi_policy_test.sh):
#  1. abidiff of the two libmechgraph_sdk.so.1 dumps (scripts/abi-dump.sh) with the internal
#     suppressions of sdk/abi/sdk-1.0.abignore, its leaf report read line by line: removed or
#     changed functions, any change of a function table or frozen struct fail; new functions and
#     fields appended at the end of a growable struct (the file's `# growable:` list) pass.
#  2. the release's own tests/sdk/c_layout_test.cpp compiled against the current headers: every
#     offset it names, and the size of every frozen struct, must be the same (the sizes of the
#     growable structs, the ones the suppression file names, may grow).
#   scripts/sdk-abi-compare.sh OLD.abi NEW.abi OLD_C_LAYOUT_TEST.cpp NEW_INCLUDE_DIR [MORE_INCLUDE_DIR...]
set -euo pipefail
old_abi=${1:?usage: sdk-abi-compare.sh OLD.abi NEW.abi OLD_C_LAYOUT_TEST.cpp NEW_INCLUDE_DIR [MORE_INCLUDE_DIR...]}
new_abi=$2
old_layout=$3
shift 3
src=$(cd "$(dirname "$0")/.." && pwd)
suppressions=$src/sdk/abi/sdk-1.0.abignore
work=$(mktemp -d "${TMPDIR:-/tmp}/mechgraph-abi-compare.XXXXXX")
trap 'rm -rf "$work"' EXIT

growable=$(sed -n 's/^# growable:[[:space:]]*//p' "$suppressions" | head -n 1)
[ -n "$growable" ] || { echo "sdk-abi-compare: no '# growable:' line in $suppressions" >&2; exit 2; }
set +e
abidiff --no-added-syms --leaf-changes-only --impacted-interfaces --suppressions "$suppressions" "$old_abi" "$new_abi" \
  > "$work/abidiff.txt" 2>&1
code=$?
set -e
# Exit 0: nothing changed. Exit 4 (a change, not judged incompatible by libabigail): allowed only
# when every changed leaf type is a growable struct that grew by fields appended at its end.
if [ "$code" != 0 ]; then
  verdict=0
  [ "$code" = 4 ] && /usr/bin/python3 - "$work/abidiff.txt" "$growable" > "$work/verdict.txt" <<'PY' || verdict=1
import re, sys
report, growable = open(sys.argv[1]).read().splitlines(), set(sys.argv[2].split())
problems = []
for line in report:
    m = re.match(r"Removed/Changed/Added (functions|variables) summary: (\d+) Removed, (\d+) Changed", line)
    if m and (int(m.group(2)) or int(m.group(3))):
        problems.append(line)
block, size = None, None
for line in report:
    head = re.match(r"'(?:struct |typedef )?(\S+)[^']*' changed:$", line)
    if head:
        block, size = head.group(1), None
        if block not in growable:
            problems.append(f"{block}: a frozen type changed")
        continue
    if block is None or not line.startswith("  "):
        continue
    text = line.strip()
    if re.match(r"(one|\d+) impacted interfaces?:", text) or line.startswith("    function ") or line.startswith("    variable "):
        continue
    grew = re.match(r"type size changed from (\d+) to (\d+) \(in bits\)", text)
    if grew and int(grew.group(2)) > int(grew.group(1)):
        size = int(grew.group(1))
        continue
    if re.match(r"\d+ data member insertions?:", text):
        continue
    inserted = re.match(r"'.*', at offset (\d+) \(in bits\)", text)
    if inserted and size is not None and int(inserted.group(1)) >= size:
        continue
    problems.append(f"{block}: {text}")
print("\n".join(problems))
sys.exit(1 if problems else 0)
PY
  if [ "$code" != 4 ] || [ "$verdict" != 0 ]; then
    cat "$work/abidiff.txt" >&2
    [ ! -s "$work/verdict.txt" ] || { echo "not allowed:" >&2; cat "$work/verdict.txt" >&2; }
    echo "sdk-abi-compare: abidiff: libmechgraph_sdk.so.1 changed incompatibly (exit $code); only fields appended to a growable struct and new functions are allowed: a new capability is a new function, struct or interface version, never a change (docs/writing-plugins.md, \"Adding a versioned interface\")" >&2
    exit 1
  fi
fi

# The release's layout test without the sizes of the growable structs.
grep -v -E "static_assert\(sizeof\(($(tr ' ' '|' <<< "$growable"))\) == " "$old_layout" > "$work/c_layout_test.cpp"
includes=()
for dir in "$@"; do includes+=(-I"$dir"); done
if ! c++ -std=c++20 -fsyntax-only "${includes[@]}" "$work/c_layout_test.cpp" 2> "$work/layout.txt"; then
  grep -E "error|static assertion" "$work/layout.txt" | head -n 20 >&2
  echo "sdk-abi-compare: the release's layout (its tests/sdk/c_layout_test.cpp) does not hold for the current headers: a field moved, renamed or retyped, or a frozen struct changed size" >&2
  exit 1
fi
echo "sdk-abi-compare: abidiff: no change beyond the allowed ones; the release's offsets hold" >&2
