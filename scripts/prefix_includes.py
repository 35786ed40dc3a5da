#!/usr/bin/env python3
"""Rewrites fairshape's own includes to the installed layout: "core/types.h" -> "fairshape/core/types.h".

fairshape's headers are installed under include/fairshape/<module>/ and the build tree
exposes the same prefix (build/include/fairshape/<module> -> src/<module>), so a project that uses
fairshape never sees bare "core/..." or "io/..." names that could collide with its own. Run it on a
branch made before the prefix to bring its sources along (it is idempotent):
    python3 scripts/prefix_includes.py [PATH ...]    (default: src reference experiments tests)
"""
import pathlib
import re
import sys

MODULES = ("bspline constraint core curve_design curves design energy experiment feature io mesh problem qp "
           "reference remesh render solver subdivision").split()
INCLUDE = re.compile(r'^(\s*#\s*include\s+")((?:%s)/)' % "|".join(MODULES), re.MULTILINE)
SUFFIXES = {".h", ".hpp", ".cpp", ".cc", ".in"}


def rewrite(path: pathlib.Path) -> bool:
    text = path.read_text(encoding="utf-8")
    new = INCLUDE.sub(r"\1fairshape/\2", text)
    if new != text:
        path.write_text(new, encoding="utf-8")
        return True
    return False


def main(argv):
    roots = [pathlib.Path(a) for a in (argv or ["src", "reference", "experiments", "tests"])]
    changed = 0
    for root in roots:
        files = [root] if root.is_file() else sorted(p for p in root.rglob("*") if p.suffix in SUFFIXES and p.is_file())
        changed += sum(rewrite(f) for f in files)
    print(f"prefix_includes: {changed} file(s) rewritten")


if __name__ == "__main__":
    main(sys.argv[1:])
