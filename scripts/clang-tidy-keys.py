#!/usr/bin/env python3
"""Content keys for clang-tidy: one SHA-256 per source file of everything its
verdict depends on, so that a file whose key is recorded as passing need not
be checked again.

The key covers the file as clang sees it: the translation unit preprocessed
by clang++ with the build's own flags, comments kept (NOLINT lives in them),
with the checkout's and the build folder's paths replaced by placeholders;
the flags themselves (paths likewise) except those of debug information
(-g, -g1, -gline-tables-only...), which change neither the source clang-tidy
reads nor what it reports; every .clang-tidy of the tree; and
`clang-tidy --version`. Any change to the file, to a header it includes
(fabmesh's, CGAL's, the system's), to its other flags, to the configuration
or to the tool changes the key.

Usage: clang_tidy_keys.py BUILD_DIR FILE...   prints "KEY  FILE" per file
       (FILE relative to the checkout), in the order given.
Environment: JOBS (parallel preprocessors, default 2)."""
import concurrent.futures
import hashlib
import json
import os
import re
import shlex
import subprocess
import sys

root = os.path.realpath(os.path.join(os.path.dirname(__file__), ".."))


def normalise(text, build):
    return text.replace(build, "@BUILD@").replace(root, "@SOURCE@")


def key(entry, build, common):
    args = shlex.split(entry["command"]) if "command" in entry else list(entry["arguments"])
    # The compiler is the command's first word after any launcher; clang-tidy
    # reads the rest with clang's driver, and so does this.
    flags, skip = [], False
    for a in args[1:]:
        if skip:
            skip = False
            continue
        if a in ("-o", "-c"):
            skip = a == "-o"
            continue
        if re.fullmatch(r"-g(gdb)?[0-3]?|-gline-tables-only", a):
            continue
        flags.append(a)
    source = os.path.realpath(entry["file"])
    flags = [f for f in flags if os.path.realpath(f) != source] if source else flags
    pre = subprocess.run(["clang++", *flags, "-E", "-P", "-C", "-w", source], cwd=entry["directory"],
                         capture_output=True, check=True).stdout.decode("utf-8", "surrogateescape")
    h = hashlib.sha256(common)
    h.update(normalise(" ".join(flags), build).encode())
    h.update(b"\0")
    h.update(normalise(pre, build).encode("utf-8", "surrogateescape"))
    return h.hexdigest()


def main():
    build = os.path.realpath(sys.argv[1])
    files = sys.argv[2:]
    commands = {os.path.realpath(e["file"]): e for e in json.load(open(os.path.join(build, "compile_commands.json")))}
    common = hashlib.sha256(subprocess.run(["clang-tidy", "--version"], capture_output=True, check=True).stdout)
    for dirpath, dirnames, filenames in sorted(os.walk(root)):
        dirnames[:] = sorted(d for d in dirnames if not d.startswith(".") and not d.startswith("build") and d != "node_modules")
        if ".clang-tidy" in filenames:
            common.update(os.path.relpath(dirpath, root).encode() + b"\0")
            common.update(open(os.path.join(dirpath, ".clang-tidy"), "rb").read())
    seed = common.digest()
    with concurrent.futures.ThreadPoolExecutor(int(os.environ.get("JOBS", "2"))) as pool:
        futures = [pool.submit(key, commands[os.path.realpath(os.path.join(root, f))], build, seed) for f in files]
        for f, fut in zip(files, futures):
            print(f"{fut.result()}  {f}")


if __name__ == "__main__":
    main()
