#!/usr/bin/env bash
# determinism-lint.sh — fails when floating point appears in the simulation
# modules (fixed/, physics/, replay/), where rule 1 bans it: the types float,
# double, long double, __float128, _FloatN; the headers <cmath>, <math.h>,
# <cfloat>, <float.h>, <tgmath.h>, <complex>; std:: and C math functions
# (std::sqrt, sqrtf, __builtin_sin, ...); floating literals (0.5, 1e9, 2.f,
# 0x1p-3). A line that carries `tandem-edge` (the marked edge-only debug
# conversions) is allowed.
#
# Comments, string and character literals are blanked before matching (a
# comment may say "double"), so only code is checked. Identifiers merely
# containing a banned word (to_double, isqrt_round, sqrt of our own Q32) are
# not flagged; user-defined literals such as 1.5_q32 are integer-parsed and
# allowed. Digit separators (1'000) are understood.
#
# Usage: determinism-lint.sh [REPO_ROOT]   lint REPO_ROOT (default: this repo)
#        determinism-lint.sh --self-test   check the lint on planted violations
# Prints one line per finding, "file:line: reason: code", then a count; exit 1
# when anything was found.
set -euo pipefail

# lint_files FILE...: prints findings; the awk program does all the work.
lint_files() {
  awk '
    function flag(reason) {
      printf "%s:%d: %s: %s\n", FILENAME, FNR, reason, raw
      found++
    }
    # Blanks comments, strings and char literals of one line; block-comment
    # state carries across lines in in_block.
    function strip(line,    out, i, n, c, d, prev, in_str, in_chr, in_num) {
      out = ""; n = length(line); in_str = 0; in_chr = 0; in_num = 0; prev = ""
      for (i = 1; i <= n; i++) {
        c = substr(line, i, 1); d = substr(line, i + 1, 1)
        if (in_block) {
          if (c == "*" && d == "/") { in_block = 0; i++ }
          out = out " "; continue
        }
        if (in_str) {
          if (c == "\\") { i++; out = out "  "; continue }
          if (c == "\"") { in_str = 0; out = out "\""; continue }
          out = out " "; continue
        }
        if (in_chr) {
          if (c == "\\") { i++; out = out "  "; continue }
          if (c == "\047") { in_chr = 0; out = out "\047"; continue }
          out = out " "; continue
        }
        if (c == "/" && d == "/") break
        if (c == "/" && d == "*") { in_block = 1; i++; out = out "  "; continue }
        # Numbers: track the token so a digit separator is not a char literal.
        if (c ~ /[0-9]/ && prev !~ /[A-Za-z0-9_]/) in_num = 1
        else if (in_num && c !~ /[A-Za-z0-9_.\047+-]/) in_num = 0
        if (c == "\"") { in_str = 1; out = out "\""; prev = c; continue }
        if (c == "\047" && !in_num) { in_chr = 1; out = out "\047"; prev = c; continue }
        out = out c; prev = c
      }
      return out
    }
    FNR == 1 { in_block = 0 }
    {
      raw = $0
      code = strip($0)
      if (raw ~ /tandem-edge/) next
      if (raw ~ /^[ \t]*#[ \t]*include[ \t]*[<"](cmath|math\.h|cfloat|float\.h|tgmath\.h|ctgmath|complex|ccomplex)[>"]/) {
        flag("floating-point header"); next
      }
      padded = " " code " "
      gsub(/\047/, "", padded)  # digit separators: 1\0470.5 reads as 10.5
      if (padded ~ /[^A-Za-z0-9_](float|double|float_t|double_t|__float128|__float80|__ibm128|_Float[0-9]+x?|__bf16)[^A-Za-z0-9_]/) {
        flag("floating-point type"); next
      }
      if (padded ~ /std::(sqrt|cbrt|hypot|sin|cos|tan|asin|acos|atan|atan2|sinh|cosh|tanh|exp|exp2|expm1|log|log2|log10|log1p|pow|fabs|fmod|remainder|floor|ceil|round|lround|llround|trunc|nearbyint|rint|lrint|fma|fmin|fmax|fdim|frexp|ldexp|modf|copysign|nextafter|isnan|isinf|isfinite|signbit)[^A-Za-z0-9_]/) {
        flag("floating-point std:: function"); next
      }
      if (padded ~ /[^A-Za-z0-9_](__builtin_(sqrt|cbrt|hypot|sin|cos|tan|asin|acos|atan|atan2|exp|exp2|log|log2|log10|pow|powi|fabs|fmod|floor|ceil|round|lround|llround|trunc|rint|fma|fmin|fmax|copysign|huge_val|inf|nan|nans|isnan|isinf|isfinite|signbit)(f|l|f16|f32|f64|f128|f32x|f64x)?|(sqrt|cbrt|hypot|sin|cos|tan|asin|acos|atan|atan2|exp|exp2|log|log2|log10|pow|fabs|fmod|floor|ceil|round|trunc)[fl]|fabs)[ \t]*\(/) {
        flag("floating-point C function"); next
      }
      if (padded ~ /[^A-Za-z0-9_.]([0-9]+\.[0-9]*|\.[0-9]+)([eE][-+]?[0-9]+)?[fFlL]?[^A-Za-z0-9_.]/ ||
          padded ~ /[^A-Za-z0-9_.][0-9]+[eE][-+]?[0-9]+[fFlL]?[^A-Za-z0-9_.]/ ||
          padded ~ /[^A-Za-z0-9_.]0[xX][0-9A-Fa-f]*\.?[0-9A-Fa-f]*[pP][-+]?[0-9]+[fFlL]?[^A-Za-z0-9_.]/) {
        flag("floating-point literal"); next
      }
    }
    END { exit found > 0 ? 1 : 0 }
  ' "$@"
}

# lint_tree ROOT: lints fixed/, physics/, replay/ under ROOT.
lint_tree() {
  local root=$1 files=() d f
  for d in fixed physics replay; do
    [ -d "$root/$d" ] || continue
    while IFS= read -r -d '' f; do files+=("$f"); done \
      < <(find "$root/$d" -type f \( -name '*.h' -o -name '*.hpp' -o -name '*.cpp' -o -name '*.cc' -o -name '*.inl' -o -name '*.ipp' \) -print0 | sort -z)
  done
  if [ ${#files[@]} -eq 0 ]; then
    echo "determinism lint: no sources under $root/{fixed,physics,replay}" >&2
    return 2
  fi
  local out rc=0
  out=$(cd "$root" && lint_files "${files[@]#"$root"/}") || rc=$?
  if [ $rc -eq 1 ]; then
    printf '%s\n' "$out"
    echo "determinism lint: $(printf '%s\n' "$out" | grep -c .) floating-point use(s) in ${#files[@]} files;" \
      "remove them, or mark an edge-only debug conversion with // tandem-edge: why"
    return 1
  elif [ $rc -ne 0 ]; then
    printf '%s\n' "$out"
    return $rc
  fi
  echo "determinism lint: ${#files[@]} files clean"
}

# self_test: plants each kind of violation next to look-alikes that are fine,
# and checks that exactly the planted lines are reported.
self_test() {
  local tmp
  tmp=$(mktemp -d)
  trap 'rm -rf "$tmp"' RETURN
  mkdir -p "$tmp/fixed" "$tmp/physics"
  # Lines marked BAD must be flagged, every other line must not.
  cat > "$tmp/fixed/sample.h" <<'SRC'
// sample.h: a comment may say float, double and std::sqrt(2.0).
/* a block comment with 0.5 and
   double on its second line */
#include <cstdint>
#include <cmath>  // BAD
#include <math.h>  // BAD
#include "fixed/fixed.h"
namespace tandem {
inline double half(int64_t v) { return static_cast<double>(v); }  // BAD
inline float f(int x) { return x; }  // BAD
long double ld();  // BAD
int64_t a = 1'000'000;
int64_t b = 0x7FFF'FFFF;
const char* s = "double float 0.5 std::sqrt";
char c = '.';
Q32 q = 1.5_q32;
Q32 r = sqrt(q);
uint64_t i = isqrt_round(n);
double to_double() const;  // tandem-edge: debug output only
int64_t x = std::sqrt(y);  // BAD
int64_t y = sqrtf(z);  // BAD
int64_t z = __builtin_sqrt(w);  // BAD
int64_t w = 3 * 0.5;  // BAD
int64_t v = 1e9;  // BAD
int64_t u = 2.f;  // BAD
int64_t t = .25;  // BAD
int64_t k = 0x1p-3;  // BAD
int64_t m = 0x1e5 + 1'0.5;  // BAD
int64_t version = 3;  /* 1.5 */ int64_t after = 2;
auto e = std::exp(1);  // BAD
auto mn = std::min(a, b);
if (__builtin_expect(a > 0, 1) && __builtin_constant_p(b)) {}
bool o = __builtin_add_overflow(a, b, &x);
double_t dt;  // BAD
auto ab = std::abs(a);
}  // namespace tandem
SRC
  printf 'int64_t ok = 1;\n/* open\n float */ int64_t fine = 2;\nfloat g;  // BAD\n' > "$tmp/physics/second.cpp"

  local expected actual out rc=0
  expected=$(cd "$tmp" && grep -n 'BAD' fixed/sample.h physics/second.cpp | cut -d: -f1,2 | sort)
  out=$(lint_tree "$tmp" 2>&1) || rc=$?
  actual=$(printf '%s\n' "$out" | grep -E '^(fixed|physics)/' | cut -d: -f1,2 | sort || true)
  if [ $rc -ne 1 ] || [ "$expected" != "$actual" ]; then
    echo "determinism lint self-test FAILED (exit $rc)"
    echo "--- expected findings:"; printf '%s\n' "$expected"
    echo "--- actual output:"; printf '%s\n' "$out"
    diff <(printf '%s\n' "$expected") <(printf '%s\n' "$actual") || true
    return 1
  fi
  # A clean tree passes.
  printf 'int64_t ok = 1;\n' > "$tmp/physics/second.cpp"
  rm "$tmp/fixed/sample.h"
  printf '// double in a comment\n' > "$tmp/fixed/clean.h"
  if ! lint_tree "$tmp" >/dev/null 2>&1; then
    echo "determinism lint self-test FAILED: a clean tree was rejected"
    return 1
  fi
  echo "determinism lint self-test: $(printf '%s\n' "$expected" | grep -c .) planted violations found, look-alikes passed"
}

if [ "${1:-}" = "--self-test" ]; then
  self_test
else
  lint_tree "${1:-$(cd "$(dirname "$0")/.." && pwd)}"
fi
