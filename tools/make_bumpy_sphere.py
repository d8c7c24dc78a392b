#!/usr/bin/env python3
"""Writes a bumpy sphere as a binary little-endian PLY: an n x n grid of vertices (latitude x
longitude) on the unit sphere displaced by 5 % sine bumps, 2 (n-1)^2 triangles. n = 709 gives the
1 002 528-triangle mesh of docs/cli.md (memory bound) and tools/gpu-check.sh (about 19 MB).
Standard library only, so it runs on the GPU machine's Python too.

  tools/make_bumpy_sphere.py out.ply [n]"""
import math
import struct
import sys
from array import array


def main():
    if len(sys.argv) not in (2, 3):
        sys.exit(__doc__)
    path = sys.argv[1]
    n = int(sys.argv[2]) if len(sys.argv) == 3 else 709
    verts = array("f")
    for i in range(n):
        theta = math.pi * (i + 0.5) / n  # no vertex at the poles: no degenerate triangles
        st, ct = math.sin(theta), math.cos(theta)
        for j in range(n):
            phi = 2 * math.pi * j / (n - 1)
            r = 1 + 0.05 * math.sin(12 * theta) * math.sin(12 * phi)
            verts.extend((r * st * math.cos(phi), r * ct, r * st * math.sin(phi)))
    faces = bytearray()
    pack = struct.Struct("<B3i").pack
    for i in range(n - 1):
        for j in range(n - 1):
            a, b = i * n + j, i * n + j + 1
            c, d = a + n, b + n
            faces += pack(3, a, c, b)
            faces += pack(3, b, c, d)
    if sys.byteorder != "little":
        verts.byteswap()
    header = ("ply\nformat binary_little_endian 1.0\ncomment bumpy sphere, tools/make_bumpy_sphere.py\n"
              "element vertex %d\nproperty float x\nproperty float y\nproperty float z\n"
              "element face %d\nproperty list uchar int vertex_indices\nend_header\n") % (n * n, 2 * (n - 1) ** 2)
    with open(path, "wb") as out:
        out.write(header.encode("ascii"))
        out.write(verts.tobytes())
        out.write(faces)


if __name__ == "__main__":
    main()
