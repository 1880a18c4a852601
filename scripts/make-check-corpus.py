#!/usr/bin/env python3
"""Writes the meshes of tests/data/check-corpus/ and its manifest.json.

Each case is a mesh file and the verdict `fabmesh check` must give it: one
manifest entry per file, {"file", "valid", "defect_kinds", "about"}, where
defect_kinds are the `defect_kinds` keys of `check --json` (an unordered set;
empty for a valid mesh). tests/pipeline/check_orientation_test.cpp runs
`check` on every entry. To add cases (other formats, multi-object files), add
a function that writes the file and returns its entry to CASES; entries this
script does not write can be kept by listing them in EXTRA_ENTRIES.

Plain Python 3 (no numpy): every coordinate is an integer, so the files are
exact and the same on every machine.

Usage: scripts/make-check-corpus.py [--check]   (--check: fail if the
committed files differ from what this script writes)
"""

import json
import os
import sys

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests", "data", "check-corpus")

# Vertex i of a box has x from bit 0, y from bit 1, z from bit 2; outward faces.
BOX_FACES = [(0, 2, 1), (1, 2, 3), (4, 5, 6), (5, 7, 6), (0, 1, 4), (1, 5, 4),
             (2, 6, 3), (3, 6, 7), (0, 4, 2), (2, 4, 6), (1, 3, 5), (3, 7, 5)]

# A regular octahedron |x - 10| + |y - 10| + |z - 10| <= 15, outward.
OCTAHEDRON = ([(10, 10, -5), (25, 10, 10), (10, 25, 10), (-5, 10, 10), (10, -5, 10), (10, 10, 25)],
              [(0, 2, 1), (0, 3, 2), (0, 4, 3), (0, 1, 4), (5, 1, 2), (5, 2, 3), (5, 3, 4), (5, 4, 1)])

# Entries for files this script does not write (e.g. multi-object 3MF), kept as they are.
EXTRA_ENTRIES = []


def box(lo, hi, inward=False):
    """The axis-aligned box [lo, hi] as (vertices, faces)."""
    vertices = [(hi[0] if i & 1 else lo[0], hi[1] if i & 2 else lo[1], hi[2] if i & 4 else lo[2])
                for i in range(8)]
    return vertices, [flip(f) if inward else f for f in BOX_FACES]


def cube(lo, hi, inward=False):
    return box((lo, lo, lo), (hi, hi, hi), inward)


def flip(face):
    return (face[0], face[2], face[1])


def inverted(shell):
    vertices, faces = shell
    return vertices, [flip(f) for f in faces]


def obj_text(shells, comment):
    """An OBJ file of the shells, each with its own vertices."""
    lines = ["# " + line for line in comment.splitlines()]
    lines.append("# written by scripts/make-check-corpus.py")
    base = 1
    faces = []
    for vertices, shell_faces in shells:
        lines += ["v %d %d %d" % v for v in vertices]
        faces += ["f %d %d %d" % tuple(base + i for i in f) for f in shell_faces]
        base += len(vertices)
    return "\n".join(lines + faces) + "\n"


def stl_text(shells, name):
    """An ASCII STL of the shells (normals zero: readers recompute them)."""
    lines = ["solid " + name]
    for vertices, faces in shells:
        for f in faces:
            lines.append("  facet normal 0 0 0")
            lines.append("    outer loop")
            lines += ["      vertex %d %d %d" % vertices[i] for i in f]
            lines.append("    endloop")
            lines.append("  endfacet")
    lines.append("endsolid " + name)
    return "\n".join(lines) + "\n"


def case(file, valid, kinds, about, shells):
    text = stl_text(shells, file[:-4]) if file.endswith(".stl") else obj_text(shells, about)
    return {"file": file, "valid": valid, "defect_kinds": kinds, "about": about}, text


CASES = [
    lambda: case("cavity.obj", True, [],
                 "a 20 mm cube with a 5 mm cubic cavity facing inward: volume 8000 - 125",
                 [cube(0, 20), cube(5, 10, inward=True)]),
    lambda: case("inverted-component.obj", False, ["inverted_component"],
                 "a 20 mm cube and a separate 5 mm cube facing inward (total volume 7875 > 0)",
                 [cube(0, 20), box((30, 0, 0), (35, 5, 5), inward=True)]),
    lambda: case("nested-same-orientation.obj", False, ["nested_same_orientation"],
                 "a 5 mm cube inside a 20 mm cube, both facing outward",
                 [cube(0, 20), cube(5, 10)]),
    lambda: case("island-in-cavity.obj", True, [],
                 "a solid cube in the cavity of a solid cube: outward, inward, outward",
                 [cube(0, 30), cube(5, 25, inward=True), cube(10, 20)]),
    lambda: case("inverted-island.obj", False, ["nested_same_orientation"],
                 "a cube in a cavity facing inward like the cavity",
                 [cube(0, 30), cube(5, 25, inward=True), cube(10, 20, inward=True)]),
    lambda: case("separate-cubes.stl", True, [],
                 "two separate outward cubes (ASCII STL, welded by check)",
                 [cube(0, 20), box((30, 0, 0), (35, 5, 5))]),
    lambda: case("inside-out-cube.obj", False, ["inside_out"],
                 "one cube facing inward: inside-out, not an inverted component",
                 [cube(0, 20, inward=True)]),
    lambda: case("inside-out-pair.obj", False, ["inside_out", "inverted_component"],
                 "two separate cubes facing inward: the total volume is negative and each is inverted",
                 [cube(0, 20, inward=True), box((30, 0, 0), (35, 5, 5), inward=True)]),
    lambda: case("shared-plane-cavity.obj", True, [],
                 "an octahedron with a box cavity whose top face lies in the plane of its four equator vertices",
                 [OCTAHEDRON, box((8, 8, 8), (12, 12, 10), inward=True)]),
    lambda: case("shared-plane-nested.obj", False, ["nested_same_orientation"],
                 "the same box facing outward inside the octahedron",
                 [OCTAHEDRON, box((8, 8, 8), (12, 12, 10))]),
]


def main():
    check = "--check" in sys.argv[1:]
    entries = []
    files = {}
    for make in CASES:
        entry, text = make()
        entries.append(entry)
        files[entry["file"]] = text
    manifest = {
        "about": "Meshes and the verdict `fabmesh check` must give each; written by "
                 "scripts/make-check-corpus.py. valid: the expected verdict (exit 0 or 1); "
                 "defect_kinds: the expected `defect_kinds` of `check --json`, as a set.",
        "cases": entries + EXTRA_ENTRIES,
    }
    files["manifest.json"] = json.dumps(manifest, indent=2) + "\n"
    stale = []
    for name, text in sorted(files.items()):
        path = os.path.join(ROOT, name)
        if check:
            try:
                with open(path, encoding="utf-8") as f:
                    if f.read() != text:
                        stale.append(name)
            except FileNotFoundError:
                stale.append(name)
            continue
        os.makedirs(ROOT, exist_ok=True)
        with open(path, "w", encoding="utf-8", newline="\n") as f:
            f.write(text)
    if stale:
        print("make-check-corpus: out of date: " + ", ".join(stale), file=sys.stderr)
        return 1
    if not check:
        print("make-check-corpus: wrote %d files to tests/data/check-corpus" % len(files))
    return 0


if __name__ == "__main__":
    sys.exit(main())
