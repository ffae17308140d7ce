#!/usr/bin/env python3
"""check_coverage.py SOURCE_DIR — ctest capi/coverage: every function that
capi/include/tandem_c*.h (the umbrella and its parts) declares is called by the C API tests or examples
(capi/tests/test_*.cpp, capi/examples/*.c; the bindings' own tests are not
counted). Adding a C function without a test fails here, naming it."""
import pathlib
import re
import sys

root = pathlib.Path(sys.argv[1])
header = "\n".join(p.read_text(encoding="utf-8") for p in sorted((root / "capi/include").glob("tandem_c*.h")))
declared = sorted(set(re.findall(r"TANDEM_C_API[^;]*?\b(tandem_[a-z0-9_]+)\(", header, re.S)))
sources = list((root / "capi/tests").glob("test_*.cpp")) + list((root / "capi/examples").glob("*.c"))
calls = set()
for path in sources:
    text = path.read_text(encoding="utf-8")
    calls.update(re.findall(r"\b(tandem_[a-z0-9_]+)\b", text))
missing = [name for name in declared if name not in calls]
if len(declared) < 100:
    sys.exit(f"capi/coverage: only {len(declared)} functions found in tandem_c*.h; the parser is broken")
if missing:
    sys.exit("capi/coverage: not called by any test: " + ", ".join(missing))
print(f"capi/coverage: all {len(declared)} functions of tandem_c*.h are called by a test")
