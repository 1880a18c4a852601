#!/usr/bin/env python3
"""Writes the fenced code blocks of one language in a Markdown page to OUTDIR/example_N.EXT.

Usage: extract-doc-examples.py PAGE LANGUAGE EXT OUTDIR. Prints the files written, one per
line; the test suite builds and runs each, so the page's examples cannot rot.
"""
import pathlib
import re
import sys


def main():
    page, language, ext, outdir = sys.argv[1:5]
    blocks = re.findall(r"^```" + re.escape(language) + r"\n(.*?)^```$", pathlib.Path(page).read_text(), re.S | re.M)
    out = pathlib.Path(outdir)
    out.mkdir(parents=True, exist_ok=True)
    for i, block in enumerate(blocks, 1):
        path = out / f"example_{i}.{ext}"
        if not path.exists() or path.read_text() != block:
            path.write_text(block)
        print(path)


if __name__ == "__main__":
    main()
