"""Rewrites the generated blocks of a paper README: each sits between `<!-- numbers:NAME -->` and
`<!-- /numbers:NAME -->` and is made whole by a function from the paper's data/; text outside
the markers is left as it is. Used by papers/*/figures/readme_numbers.py:

    readme_blocks.main(README, {"name": make_block, ...})   # argv: [--check]

--check only reports blocks that differ from the data (exit 1), for CI (ctest
docs.readme_numbers.<paper>) or a reviewer.
"""
import os
import sys


def main(readme, blocks, argv=None):
    check = "--check" in (sys.argv[1:] if argv is None else argv)
    text = open(readme).read()
    stale, missing = [], []
    for name, make in blocks.items():
        begin, end = f"<!-- numbers:{name} -->", f"<!-- /numbers:{name} -->"
        if begin not in text:
            continue
        if end not in text:
            sys.exit(f"readme_numbers: {begin} without {end}")
        i, j = text.index(begin) + len(begin), text.index(end)
        try:
            block = "\n" + make() + "\n"
        except FileNotFoundError as e:
            missing.append(f"{name} ({e.filename})")
            continue
        if text[i:j] != block:
            stale.append(name)
            text = text[:i] + block + text[j:]
    if check:
        if stale:
            print("readme_numbers: stale blocks: " + ", ".join(stale))
            sys.exit(1)
        return
    tmp = readme + ".tmp"
    with open(tmp, "w") as f:
        f.write(text)
    os.replace(tmp, readme)
    print("readme_numbers: " + (("rewrote " + ", ".join(stale)) if stale else "every block matches data/"))
    if missing:
        sys.exit("readme_numbers: no data for " + ", ".join(missing) + " (run make_figures.sh for them)")
