#!/usr/bin/env python3
"""Writes a bumpy sphere as a binary little-endian PLY: an n x n grid of vertices (latitude x
longitude) on the unit sphere displaced by 5 % sine bumps, 2 (n-1)^2 triangles. n = 709 gives the
1 002 528-triangle mesh of docs/cli.md (memory bound) and tools/gpu-check.sh (about 19 MB).
Standard library only, so it runs on the GPU machine's Python too. A name ending in .glb writes
the same mesh as binary glTF 2.0 instead (float positions, uint32 indices; for timing the glTF
reader against the PLY reader on the same triangles).

  tools/make_bumpy_sphere.py out.ply|out.glb [n]"""
import json
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
    glb = path.lower().endswith(".glb")
    faces = bytearray() if not glb else array("I")
    pack = struct.Struct("<B3i").pack
    for i in range(n - 1):
        for j in range(n - 1):
            a, b = i * n + j, i * n + j + 1
            c, d = a + n, b + n
            if glb:
                faces.extend((a, c, b, b, c, d))
            else:
                faces += pack(3, a, c, b)
                faces += pack(3, b, c, d)
    if sys.byteorder != "little":
        verts.byteswap()
        if glb:
            faces.byteswap()
    if glb:
        write_glb(path, verts, faces)
        return
    header = ("ply\nformat binary_little_endian 1.0\ncomment bumpy sphere, tools/make_bumpy_sphere.py\n"
              "element vertex %d\nproperty float x\nproperty float y\nproperty float z\n"
              "element face %d\nproperty list uchar int vertex_indices\nend_header\n") % (n * n, 2 * (n - 1) ** 2)
    with open(path, "wb") as out:
        out.write(header.encode("ascii"))
        out.write(verts.tobytes())
        out.write(faces)


def write_glb(path, verts, indices):
    """One mesh, one node: POSITION (float32) and indices (uint32) in the BIN chunk."""
    vb, ib = verts.tobytes(), indices.tobytes()
    xs, ys, zs = verts[0::3], verts[1::3], verts[2::3]
    doc = {"asset": {"version": "2.0", "generator": "strahl tools/make_bumpy_sphere.py"},
           "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
           "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
           "accessors": [{"bufferView": 0, "componentType": 5126, "type": "VEC3", "count": len(verts) // 3,
                          "min": [min(xs), min(ys), min(zs)], "max": [max(xs), max(ys), max(zs)]},
                         {"bufferView": 1, "componentType": 5125, "type": "SCALAR", "count": len(indices)}],
           "bufferViews": [{"buffer": 0, "byteLength": len(vb)},
                           {"buffer": 0, "byteOffset": len(vb), "byteLength": len(ib)}],
           "buffers": [{"byteLength": len(vb) + len(ib)}]}
    text = json.dumps(doc).encode()
    text += b" " * (-len(text) % 4)
    with open(path, "wb") as out:
        out.write(struct.pack("<4sII", b"glTF", 2, 12 + 8 + len(text) + 8 + len(vb) + len(ib)))
        out.write(struct.pack("<I4s", len(text), b"JSON") + text)
        out.write(struct.pack("<I4s", len(vb) + len(ib), b"BIN\0"))
        out.write(vb)
        out.write(ib)


if __name__ == "__main__":
    main()
