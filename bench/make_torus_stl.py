#!/usr/bin/env python3
"""Writes a closed, outward-oriented torus as binary STL: 2 * nu * nv triangles.

Usage: make_torus_stl.py OUT.stl [nu] [nv]   (defaults 1000 x 500 = 1e6 triangles)
"""
import math
import struct
import sys


def main():
    out = sys.argv[1]
    nu = int(sys.argv[2]) if len(sys.argv) > 2 else 1000
    nv = int(sys.argv[3]) if len(sys.argv) > 3 else 500
    big, small = 3.0, 1.0
    ring = []
    for i in range(nu):
        u = 2 * math.pi * i / nu
        row = []
        for j in range(nv):
            v = 2 * math.pi * j / nv
            r = big + small * math.cos(v)
            # float32 up front so that equal vertices are bit-identical in every triangle
            row.append(struct.unpack("<3f", struct.pack("<3f", r * math.cos(u), r * math.sin(u), small * math.sin(v))))
        ring.append(row)
    record = struct.Struct("<12f2x")
    with open(out, "wb") as f:
        f.write(b"fabmesh bench torus".ljust(80, b" "))
        f.write(struct.pack("<I", 2 * nu * nv))
        for i in range(nu):
            a_row, b_row = ring[i], ring[(i + 1) % nu]
            for j in range(nv):
                k = (j + 1) % nv
                a, b, c, d = a_row[j], b_row[j], b_row[k], a_row[k]
                # outward: (u, v) with u around the axis, v around the tube
                f.write(record.pack(0, 0, 0, *a, *b, *c))
                f.write(record.pack(0, 0, 0, *a, *c, *d))


if __name__ == "__main__":
    main()
