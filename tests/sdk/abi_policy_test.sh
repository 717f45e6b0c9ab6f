#!/usr/bin/env bash
# scripts/sdk-abi-compare.sh (abidiff with sdk/abi/sdk-1.0.abignore, then the release's
# c_layout_test against the new headers) lets through exactly what the SDK's rules allow
# (c/base.h) and nothing else: a small library over the C headers is built as they are and with
# one change at a time, and the comparison (as scripts/test-sdk-compat.sh runs it) must
#   pass: no change; a field appended to a growable struct (mg_port_decl, mg_node_desc);
#   fail: a function inserted into a suite (mg_eval_suite_v1), a field appended to a function table
#         (mg_cam_law_v1) or to a frozen struct (mg_column), fields of a growable struct reordered
#         (mg_param_decl), two fields of one type swapped, a field retyped (mg_node_type::evaluate).
# (abidiff alone lets the reordering through: libabigail reads a field moved to the end as one
# appended; and two fields of one type swapped look like a rename. The layout test names every
# offset, so it catches both.)
#   tests/sdk/abi_policy_test.sh SOURCE_DIR        (CTest: "sdk: the abidiff suppressions ...")
set -euo pipefail
src=$(cd "${1:?usage: abi_policy_test.sh SOURCE_DIR}" && pwd)
work=$(mktemp -d "${TMPDIR:-/tmp}/mechgraph-abi-policy.XXXXXX")
trap 'rm -rf "$work"' EXIT
fail() { echo "abi_policy_test: FAIL: $*" >&2; exit 1; }
command -v abidw >/dev/null && command -v abidiff >/dev/null || fail "abidw/abidiff not found (apt-get install abigail-tools)"

cat > "$work/anchor.c" <<'C'
#include <mechgraph/c/sdk_lib.h>
/* Reaches every struct a variant changes. */
MG_API void policy_anchor(const mg_plugin* a, const mg_eval_suite_v1* b, const mg_node_type* c, const mg_column* d,
                          const mg_param_decl* e, const mg_cam_law_v1* f, const mg_table* g) {
  (void)a, (void)b, (void)c, (void)d, (void)e, (void)f, (void)g;
}
C
# variant NAME FILE PYTHON-EXPRESSION: a copy of the headers with FILE (under mechgraph/c) changed.
variant() {
  mkdir -p "$work/$1"
  cp -r "$src/sdk/include/mechgraph" "$work/$1/"
  [ -z "$2" ] || /usr/bin/python3 - "$work/$1/mechgraph/c/$2" "$3" <<'PY'
import sys
path, change = sys.argv[1], sys.argv[2]
old, new = change.split("=>")
text = open(path).read()
assert text.count(old) == 1, f"{path}: {old!r} found {text.count(old)} times"
open(path, "w").write(text.replace(old, new))
PY
  cc -std=c11 -g -O0 -fPIC -shared -fvisibility=hidden -I"$work/$1" "$work/anchor.c" -o "$work/$1.so"
  abidw --drop-private-types --headers-dir "$work/$1/mechgraph/c" --out-file "$work/$1.abi" "$work/$1.so"
}
check() {  # check NAME EXPECT(pass|fail): as scripts/test-sdk-compat.sh compares a release with today
  set +e
  "$src/scripts/sdk-abi-compare.sh" "$work/base.abi" "$work/$1.abi" "$src/tests/sdk/c_layout_test.cpp" "$work/$1" \
    > "$work/$1.diff" 2>&1
  local code=$?
  set -e
  if [ "$2" = pass ] && [ "$code" != 0 ]; then cat "$work/$1.diff" >&2; fail "$1: refused what the rules allow (exit $code)"; fi
  if [ "$2" = fail ] && [ "$code" = 0 ]; then fail "$1: let through what the rules forbid"; fi
  # A refusal is exit 1 with one of the comparison's two verdicts, not any failure (a crash, a
  # missing tool, a malformed suppression file exits otherwise or says something else).
  if [ "$2" = fail ] && { [ "$code" != 1 ] ||
       ! grep -q -e "changed incompatibly" -e "does not hold for the current headers" "$work/$1.diff"; }; then
    cat "$work/$1.diff" >&2
    fail "$1: failed (exit $code) without the comparison's refusal"
  fi
  echo "abi_policy_test: $1: $2 as expected ($(tail -n 1 "$work/$1.diff" | cut -c1-90))" >&2
}

variant base "" ""
variant same "" ""
variant port_appended node.h '  const struct mg_presentation* presentation;   /* tables and series; NULL: plain */
} mg_port_decl;=>  const struct mg_presentation* presentation;   /* tables and series; NULL: plain */
  const char* added_later;
} mg_port_decl;'
variant desc_appended node.h '  size_t note_count;
} mg_node_desc;=>  size_t note_count;
  double added_later;
} mg_node_desc;'
variant suite_inserted host.h '  int32_t (*cancelled)(mg_eval_ctx* ctx);=>  int32_t (*cancelled)(mg_eval_ctx* ctx);
  void (*progress)(mg_eval_ctx* ctx, double fraction);'
variant table_appended domain/cam_law.h '  double (*roller_radius)(const mg_object* self); /* 0: flat face */
} mg_cam_law_v1;=>  double (*roller_radius)(const mg_object* self); /* 0: flat face */
  double (*added_later)(const mg_object* self);
} mg_cam_law_v1;'
variant frozen_appended value.h '  const double* values;
} mg_column;=>  const double* values;
  const char* added_later;
} mg_column;'
variant growable_reordered node.h '  uint32_t flags;           /* MG_PF_* */
  double min, max;          /* SI; -inf/+inf when open */=>  double min, max;          /* SI; -inf/+inf when open */
  uint32_t flags;           /* MG_PF_* */'
variant growable_swapped node.h '  const char* display_unit; /* "mm"; NULL: SI */
  const char* label;        /* NULL: the name with '"'"'_'"'"' as '"'"' '"'"' */=>  const char* label;        /* NULL: the name with '"'"'_'"'"' as '"'"' '"'"' */
  const char* display_unit; /* "mm"; NULL: SI */'
variant evaluate_retyped node.h '  mg_status (*evaluate)(const struct mg_node_type* self, const mg_eval_args* args, mg_eval_ctx* ctx);=>  mg_status (*evaluate)(const struct mg_node_type* self, const mg_eval_args* args, mg_eval_ctx* ctx, int32_t extra);'

check same pass
check port_appended pass
check desc_appended pass
check suite_inserted fail
check table_appended fail
check frozen_appended fail
check growable_reordered fail
check growable_swapped fail
check evaluate_retyped fail
echo "abi_policy_test: PASS" >&2
