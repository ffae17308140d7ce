#!/usr/bin/env python3
"""check_readme.py SOURCE_DIR — ctest capi/readme: the C block of the README's
"From other languages" section is capi/examples/hello.c (which ctest compiles
with -std=c11 -pedantic -Werror and runs), so the README cannot drift."""
import pathlib
import re
import sys

root = pathlib.Path(sys.argv[1])
readme = (root / "README.md").read_text(encoding="utf-8")
start = readme.find("## From other languages")
if start < 0:
    sys.exit('capi/readme: README.md has no "## From other languages" section')
section = readme[start:]
end = section.find("\n## ", 3)
section = section if end < 0 else section[:end]
blocks = re.findall(r"```c\n(.*?)```", section, re.S)
if not blocks:
    sys.exit("capi/readme: no ```c block in the section")
example = (root / "capi/examples/hello.c").read_text(encoding="utf-8")
body = example[example.index("#include <inttypes.h>"):]
if blocks[0] != body:
    sys.exit("capi/readme: the README's C block differs from capi/examples/hello.c (from '#include <inttypes.h>' on)")
print("capi/readme: the README's C example is capi/examples/hello.c")
