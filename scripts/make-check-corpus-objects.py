#!/usr/bin/env python3
"""Writes tests/data/check-corpus/objects/: mesh files of several objects
(3MF build items, OBJ `o` objects and `g` groups, glTF nodes) and
manifest.json, the verdicts `fabmesh check` must give them.

Usage: scripts/make-check-corpus-objects.py [OUTDIR]
Deterministic: the same bytes every run (zip entries without timestamps).
"""

import base64
import json
import struct
import sys
import zipfile
from pathlib import Path

# A unit cube's corners and its 12 triangles, counter-clockwise seen from outside.
CUBE_CORNERS = [(x, y, z) for z in (0, 1) for y in (0, 1) for x in (0, 1)]
CUBE_TRIANGLES = [
    (0, 2, 1), (1, 2, 3),  # bottom, z = 0
    (4, 5, 6), (5, 7, 6),  # top, z = 1
    (0, 1, 4), (1, 5, 4),  # front, y = 0
    (2, 6, 3), (3, 6, 7),  # back, y = 1
    (0, 4, 2), (2, 4, 6),  # left, x = 0
    (1, 3, 5), (3, 7, 5),  # right, x = 1
]


def box(lo, hi):
    """The vertices and triangles of the box [lo, hi]."""
    vertices = [tuple(lo[k] + c[k] * (hi[k] - lo[k]) for k in range(3)) for c in CUBE_CORNERS]
    return vertices, list(CUBE_TRIANGLES)


def number(x):
    return repr(float(x)) if x != int(x) else str(int(x))


# ---------------------------------------------------------------- 3MF

CONTENT_TYPES = (
    '<?xml version="1.0" encoding="UTF-8"?>'
    '<Types xmlns="http://schemas.openxmlformats.org/package/2006/content-types">'
    '<Default Extension="rels" ContentType="application/vnd.openxmlformats-package.relationships+xml"/>'
    '<Default Extension="model" ContentType="application/vnd.ms-package.3dmanufacturing-3dmodel+xml"/>'
    '</Types>')
RELS = (
    '<?xml version="1.0" encoding="UTF-8"?>'
    '<Relationships xmlns="http://schemas.openxmlformats.org/package/2006/relationships">'
    '<Relationship Target="/3D/3dmodel.model" Id="rel0" '
    'Type="http://schemas.microsoft.com/3dmanufacturing/2013/01/3dmodel"/></Relationships>')


def model_xml(objects):
    """A 3MF model part: one mesh object and one build item per (name, vertices, triangles)."""
    parts = ['<?xml version="1.0" encoding="UTF-8"?>',
             '<model unit="millimeter" xml:lang="en-US" '
             'xmlns="http://schemas.microsoft.com/3dmanufacturing/core/2015/02">', '<resources>']
    for i, (name, vertices, triangles) in enumerate(objects):
        name_attribute = f' name="{name}"' if name else ''
        parts.append(f'<object id="{i + 1}" type="model"{name_attribute}><mesh><vertices>')
        parts += [f'<vertex x="{number(x)}" y="{number(y)}" z="{number(z)}"/>' for x, y, z in vertices]
        parts.append('</vertices><triangles>')
        parts += [f'<triangle v1="{a}" v2="{b}" v3="{c}"/>' for a, b, c in triangles]
        parts.append('</triangles></mesh></object>')
    parts.append('</resources><build>')
    parts += [f'<item objectid="{i + 1}"/>' for i in range(len(objects))]
    parts.append('</build></model>')
    return '\n'.join(parts)


def write_zip(path, entries):
    with zipfile.ZipFile(path, 'w', zipfile.ZIP_DEFLATED) as archive:
        for name, text in entries:
            info = zipfile.ZipInfo(name, date_time=(1980, 1, 1, 0, 0, 0))
            info.compress_type = zipfile.ZIP_DEFLATED
            archive.writestr(info, text)


def write_3mf(path, objects):
    write_zip(path, [('[Content_Types].xml', CONTENT_TYPES), ('_rels/.rels', RELS),
                     ('3D/3dmodel.model', model_xml(objects))])


# ---------------------------------------------------------------- OBJ

def obj_text(sections):
    """OBJ text of (record, vertices, triangles) sections, each record ('o NAME', 'g NAME' or
    None) before its faces; vertices None reuse the previous section's."""
    lines = ['# written by scripts/make-check-corpus-objects.py']
    base = 0
    previous = 0
    for record, vertices, triangles in sections:
        if vertices is not None:
            base += previous
            lines += [f'v {number(x)} {number(y)} {number(z)}' for x, y, z in vertices]
            previous = len(vertices)
        if record:
            lines.append(record)
        lines += [f'f {a + 1 + base} {b + 1 + base} {c + 1 + base}' for a, b, c in triangles]
    return '\n'.join(lines) + '\n'


# ---------------------------------------------------------------- glTF

def gltf_text(vertices, triangles, nodes):
    """A self-contained .gltf: one mesh instanced by each (name, translation) node."""
    positions = b''.join(struct.pack('<3f', *v) for v in vertices)
    indices = b''.join(struct.pack('<3H', *t) for t in triangles)
    data = positions + indices
    lo = [min(v[k] for v in vertices) for k in range(3)]
    hi = [max(v[k] for v in vertices) for k in range(3)]
    document = {
        'asset': {'version': '2.0', 'generator': 'scripts/make-check-corpus-objects.py'},
        'scene': 0,
        'scenes': [{'nodes': list(range(len(nodes)))}],
        'nodes': [dict({'mesh': 0, 'translation': list(t)}, **({'name': n} if n else {})) for n, t in nodes],
        'meshes': [{'name': 'cube', 'primitives': [{'attributes': {'POSITION': 0}, 'indices': 1, 'mode': 4}]}],
        'accessors': [
            {'bufferView': 0, 'componentType': 5126, 'count': len(vertices), 'type': 'VEC3', 'min': lo, 'max': hi},
            {'bufferView': 1, 'componentType': 5123, 'count': 3 * len(triangles), 'type': 'SCALAR'},
        ],
        'bufferViews': [
            {'buffer': 0, 'byteOffset': 0, 'byteLength': len(positions)},
            {'buffer': 0, 'byteOffset': len(positions), 'byteLength': len(indices)},
        ],
        'buffers': [{'byteLength': len(data),
                     'uri': 'data:application/octet-stream;base64,' + base64.b64encode(data).decode()}],
    }
    return json.dumps(document, indent=1) + '\n'


# ---------------------------------------------------------------- the corpus

def open_box(lo, hi):
    vertices, triangles = box(lo, hi)
    return vertices, triangles[:-1]


def main():
    out = Path(sys.argv[1]) if len(sys.argv) > 1 else (
        Path(__file__).resolve().parent.parent / 'tests/data/check-corpus/objects')
    out.mkdir(parents=True, exist_ok=True)
    cases = []

    def case(file, fmt, objects, interpenetrating, why):
        valid = all(v for _, v in objects) if objects else True
        cases.append({'file': file, 'format': fmt, 'valid': valid, 'exit_code': 0 if valid else 1,
                      'objects': [{'name': n, 'valid': v} for n, v in objects],
                      'interpenetrating': interpenetrating, 'why': why})

    write_3mf(out / 'touching-cubes.3mf', [('left', *box((0, 0, 0), (1, 1, 1))),
                                          ('right', *box((1, 0, 0), (2, 1, 1)))])
    case('touching-cubes.3mf', '3MF', [('left', True), ('right', True)], [],
         'two cubes sharing a face (back to back): together they are non-manifold, apart each is valid; '
         'touching is not interpenetration')

    write_3mf(out / 'interpenetrating-cubes.3mf', [('a', *box((0, 0, 0), (2, 2, 2))),
                                                   ('b', *box((1, 1, 1), (3, 3, 3)))])
    case('interpenetrating-cubes.3mf', '3MF', [('a', True), ('b', True)], [[0, 1]],
         "a corner of each cube lies strictly inside the other")

    write_3mf(out / 'crossing-bars.3mf', [('along x', *box((0, 1, 0), (3, 2, 1))),
                                          ('along y', *box((1, 0, -0.5), (2, 3, 1.5)))])
    case('crossing-bars.3mf', '3MF', [('along x', True), ('along y', True)], [[0, 1]],
         'two bars crossing like a plus sign: no corner inside the other, edges cross faces')

    write_3mf(out / 'copies.3mf', [('', *box((0, 0, 0), (1, 1, 1))), ('', *box((0, 0, 0), (1, 1, 1)))])
    case('copies.3mf', '3MF', [('object 1', True), ('object 2', True)], [[0, 1]],
         'one cube placed twice: their faces coincide facing alike (unnamed objects are named by id)')

    write_3mf(out / 'open-and-closed.3mf', [('closed', *box((0, 0, 0), (1, 1, 1))),
                                           ('open', *open_box((2, 0, 0), (3, 1, 1)))])
    case('open-and-closed.3mf', '3MF', [('closed', True), ('open', False)], [],
         'one object has a hole: the file is invalid, the other object is still valid')

    left, cube = box((0, 0, 0), (1, 1, 1))
    right, _ = box((1, 0, 0), (2, 1, 1))
    (out / 'two-objects.obj').write_text(obj_text([('o left', left, cube), ('o right', right, cube)]))
    case('two-objects.obj', 'OBJ', [('left', True), ('right', True)], [],
         'two `o` objects touching on a face')

    (out / 'one-shell-two-groups.obj').write_text(
        obj_text([('g red', left, cube[:6]), ('g blue', None, cube[6:])]))
    case('one-shell-two-groups.obj', 'OBJ', [], [],
         'one cube whose faces are split in two `g` groups sharing vertices: one object')

    (out / 'groups-in-objects.obj').write_text(obj_text(
        [('o cup\ng red', left, cube[:6]), ('g blue', None, cube[6:]), ('o saucer', right, cube)]))
    case('groups-in-objects.obj', 'OBJ', [('cup', True), ('saucer', True)], [],
         'two `o` objects touching on a face, the first split in two `g` groups sharing vertices: the groups '
         'stay one object')

    far, _ = box((3, 0, 0), (4, 1, 1))
    (out / 'two-shells-groups.obj').write_text(obj_text([('g first', left, cube), ('g second', far, cube)]))
    case('two-shells-groups.obj', 'OBJ', [('first', True), ('second', True)], [],
         'two cubes written as `g` groups that share no vertex: separate shells, two objects')

    (out / 'two-nodes.gltf').write_text(gltf_text(left, cube, [('left', (0, 0, 0)), ('', (0.5, 0.5, 0.5))]))
    case('two-nodes.gltf', 'glTF', [('left', True), ('cube (node 1)', True)], [[0, 1]],
         'one mesh instanced by two nodes, the second moved into the first: each valid, they interpenetrate')

    manifest = {'generated_by': 'scripts/make-check-corpus-objects.py',
                'meaning': 'expected `fabmesh check` verdicts; objects is empty for a file checked as one '
                           'object; interpenetrating pairs index objects',
                'cases': cases}
    (out / 'manifest.json').write_text(json.dumps(manifest, indent=2) + '\n')


if __name__ == '__main__':
    main()
