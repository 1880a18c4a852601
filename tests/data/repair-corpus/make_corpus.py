#!/usr/bin/env python3
"""Writes the broken meshes of tests/data/repair-corpus and its manifest.json.

Every mesh is made here from cubes and spheres, with one kind of defect that
shared files carry (docs/repair.md): the tests repair each and check the
result. Deterministic: run again, the same bytes. Usage: make_corpus.py [DIR]
"""
import json
import math
import random
import struct
import sys
from pathlib import Path


def box(lo, size):
    """An outward axis-aligned box: 8 vertices, 12 triangles."""
    v = [(lo[0] + (size[0] if i & 1 else 0), lo[1] + (size[1] if i & 2 else 0), lo[2] + (size[2] if i & 4 else 0))
         for i in range(8)]
    quads = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
    f = []
    for q in quads:
        f += [(q[0], q[1], q[2]), (q[0], q[2], q[3])]
    return v, f


def sphere(centre, radius, levels):
    """An outward sphere: an octahedron subdivided `levels` times."""
    v = [(1, 0, 0), (-1, 0, 0), (0, 1, 0), (0, -1, 0), (0, 0, 1), (0, 0, -1)]
    f = [(0, 2, 4), (2, 1, 4), (1, 3, 4), (3, 0, 4), (2, 0, 5), (1, 2, 5), (3, 1, 5), (0, 3, 5)]
    for _ in range(levels):
        mid = {}

        def middle(a, b):
            key = (min(a, b), max(a, b))
            if key not in mid:
                p = [(v[a][k] + v[b][k]) / 2 for k in range(3)]
                n = math.sqrt(sum(c * c for c in p))
                v.append(tuple(c / n for c in p))
                mid[key] = len(v) - 1
            return mid[key]

        nf = []
        for a, b, c in f:
            ab, bc, ca = middle(a, b), middle(b, c), middle(c, a)
            nf += [(a, ab, ca), (ab, b, bc), (ca, bc, c), (ab, bc, ca)]
        f = nf
    out = []
    for p in v:
        n = math.sqrt(sum(c * c for c in p))
        out.append(tuple(centre[k] + radius * p[k] / n for k in range(3)))
    return out, f


def join(*meshes):
    v, f = [], []
    for mv, mf in meshes:
        base = len(v)
        v += mv
        f += [tuple(base + i for i in t) for t in mf]
    return v, f


def write_obj(path, mesh):
    v, f = mesh
    with open(path, "w") as out:
        out.write("# fabmesh repair corpus (tests/data/repair-corpus/make_corpus.py)\n")
        for p in v:
            out.write("v %r %r %r\n" % p)
        for t in f:
            out.write("f %d %d %d\n" % tuple(i + 1 for i in t))


def write_stl(path, mesh, jitter=0.0, seed=1):
    """Binary STL: every triangle its own corners, each moved by up to `jitter` per axis."""
    v, f = mesh
    rnd = random.Random(seed)
    with open(path, "wb") as out:
        out.write(b"fabmesh repair corpus".ljust(80, b" "))
        out.write(struct.pack("<I", len(f)))
        for t in f:
            out.write(struct.pack("<3f", 0, 0, 0))
            for i in t:
                out.write(struct.pack("<3f", *[c + rnd.uniform(-jitter, jitter) for c in v[i]]))
            out.write(b"\0\0")


def flipped(mesh, faces):
    v, f = mesh
    return v, [(t[0], t[2], t[1]) if i in faces else t for i, t in enumerate(f)]


def cases():
    s = sphere((0, 0, 0), 20.0, 3)
    yield ("jitter-sphere.stl", write_stl, sphere((0, 0, 0), 20.0, 3), {"jitter": 1e-4},
           "a 20 mm sphere whose STL corners were each moved by up to 1e-4 mm (an exporter's rounding)",
           ["weld"], 1)
    yield ("holes.obj", write_obj, (s[0], [t for i, t in enumerate(s[1]) if i not in (5, 6, 7, 200, 201, 202, 203, 300)]), {},
           "the sphere with three holes (one of a face, two of several, not planar)", ["hole_fill"], 1)
    yield ("flipped-faces.obj", write_obj, flipped(s, {3, 50, 51, 400}), {},
           "the sphere with four faces facing the other way", ["orientation"], 1)
    yield ("inside-out.stl", write_stl, flipped(s, set(range(len(s[1])))), {},
           "the sphere with every face reversed", ["outward"], 1)
    yield ("cavity-outward.obj", write_obj, join(box((0, 0, 0), (40, 40, 40)), box((10, 10, 10), (20, 20, 20))), {},
           "a 40 mm cube with a 20 mm cavity whose faces point into the cavity's air (outward)", ["outward"], 1)
    yield ("duplicate-faces.obj", write_obj, (s[0], s[1] + [s[1][i] for i in (10, 11, 12)]), {},
           "the sphere with three faces written twice", ["duplicate_face"], 1)
    c = box((0, 0, 0), (10, 10, 10))
    cv = c[0] + [(5.0, 0.0, 0.0)]
    cf = list(c[1])
    cf[4] = (0, 8, 5)
    cf += [(8, 1, 5), (1, 8, 0), (2, 2, 3)]
    yield ("degenerate-faces.obj", write_obj, (cv, cf), {},
           "a 10 mm cube with a needle (collinear corners) and a face with a repeated corner",
           ["degenerate_face", "stitch"], 1)
    yield ("shared-wall.stl", write_stl, join(box((0, 0, 0), (10, 10, 10)), box((10, 0, 0), (10, 10, 10))), {},
           "two 10 mm cubes exported as closed parts that share a wall (written once by each)",
           ["duplicate_face"], 1)
    yield ("touching-edge.stl", write_stl, join(box((0, 0, 0), (10, 10, 10)), box((10, 10, 0), (10, 10, 10))), {},
           "two 10 mm cubes touching along an edge (non-manifold edge)", ["non_manifold_edge"], 2)
    yield ("touching-corner.obj", write_obj, join(box((0, 0, 0), (10, 10, 10)), box((10, 10, 10), (10, 10, 10))), {},
           "two 10 mm cubes touching at a corner (non-manifold vertex)", ["non_manifold_vertex"], 2)
    yield ("overlapping-parts.stl", write_stl, join(box((0, 0, 0), (20, 20, 20)), sphere((20, 20, 20), 8.0, 2)), {},
           "a 20 mm cube and an 8 mm sphere about its corner, exported without a union", ["union"], 1)
    tv = c[0] + [(5.0, 0.0, 10.0)]
    tf = list(c[1])
    tf[2] = (4, 8, 7)
    tf += [(8, 5, 7)]
    yield ("t-junction.obj", write_obj, (tv, tf), {},
           "a 10 mm cube whose top is split at an edge's midpoint on one side only (a crack)", ["stitch"], 1)
    sheet = ([(30, 0, 0), (40, 0, 0), (30, 10, 0)], [(0, 1, 2)])
    yield ("stray-sheet.obj", write_obj, join(c, sheet), {},
           "a 10 mm cube and a stray triangle beside it (no volume: removed and reported)", ["drop_component"], 1)


def main():
    folder = Path(sys.argv[1] if len(sys.argv) > 1 else Path(__file__).parent)
    manifest = {"about": "Broken meshes and what `fabmesh repair` must do with each; written by make_corpus.py "
                         "(made in code, no outside source). steps: repair steps (JSON keys) that must act; "
                         "components: solids after the repair (an outer shell with its cavities is one).", "cases": []}
    for name, writer, mesh, extra, about, steps, components in cases():
        writer(folder / name, mesh, **extra)
        manifest["cases"].append({"file": name, "about": about, "steps": steps, "components": components})
    (folder / "manifest.json").write_text(json.dumps(manifest, indent=2) + "\n")


if __name__ == "__main__":
    main()
