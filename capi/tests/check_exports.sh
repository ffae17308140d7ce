#!/usr/bin/env bash
# check_exports.sh LIB INCLUDE_DIR — ctest capi/exports: libtandem.so exports only
# C symbols named tandem_* (no C++ symbol, no runtime symbol leaks out of the
# static modules linked into it), every function the headers (include/tandem_c*.h) declare is
# exported, and the library has a versioned soname.
set -euo pipefail
lib=$1 incdir=$2
fail() { echo "capi/exports: $*" >&2; exit 1; }

# Defined dynamic symbols, without the version node itself (type A).
exported=$(nm -D --defined-only "$lib" | awk '$2 != "A" {print $3}' | sed 's/@.*//' | sort -u)
[ -n "$exported" ] || fail "no exported symbols in $lib"
bad=$(grep -v '^tandem_' <<<"$exported" || true)
[ -z "$bad" ] || fail "symbols not named tandem_*: $(head -20 <<<"$bad" | tr '\n' ' ')"
# The version node is TANDEM_C_1 (shown by nm as an absolute symbol).
nm -D "$lib" | grep ' A TANDEM_C_1$' >/dev/null || fail "no TANDEM_C_1 version node"

declared=$(cat "$incdir"/tandem_c*.h | grep -oE '\btandem_[a-z0-9_]+\(' | tr -d '(' | sort -u)
missing=$(comm -23 <(echo "$declared") <(echo "$exported"))
[ -z "$missing" ] || fail "declared in tandem_c*.h but not exported: $missing"
extra=$(comm -13 <(echo "$declared") <(echo "$exported"))
[ -z "$extra" ] || fail "exported but not declared in tandem_c*.h: $extra"

soname=$(objdump -p "$lib" | awk '$1 == "SONAME" {print $2}')
[[ "$soname" =~ ^libtandem\.so\.[0-9]+\.[0-9]+$ ]] || fail "soname '$soname' is not libtandem.so.MAJOR.MINOR"
echo "capi/exports: $(wc -l <<<"$exported") tandem_* functions exported, soname $soname"
