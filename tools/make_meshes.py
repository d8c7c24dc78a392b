#!/usr/bin/env python3
"""Writes the small example meshes under scenes/meshes/ (run once from the repository root):

  torus.obj        a torus about the y axis (major radius 1, minor 0.35), 20 x 10 segments,
                   400 triangles with vertex normals (smooth shading)
  icosahedron.obj  a regular icosahedron of circumradius 1, 20 triangles, no normals (flat shading)
  torus-uv.obj     the torus with texture coordinates: u once around the ring, v once around the
                   tube (vertices doubled along the seams, where u or v jumps from 1 back to 0)
  cube-uv.obj      a cube from -1 to 1, each face's texture coordinates the whole unit square
                   (upright on the sides, the picture's top towards -z on the top and bottom)
  cube-uv.glb      the same cube as binary glTF 2.0 (for tests/gltf_test.cpp: the same mesh)
  cornell-box.obj  the Cornell box (Cornell University's measured geometry, in millimetres): five
                   walls and two blocks as quads, with cornell-box.mtl — usemtl white, red and
                   green (their Kd) — for a mesh's file_materials
  carousel.glb     binary glTF with a node hierarchy: a turned stand holding the cube and a ring
                   of six tori (torus-uv, one mesh drawn by six nodes), each placed by its node's
                   translation, rotation (quaternion) and scale; two materials: the cube's shows
                   textures/grid.png (embedded), the tori's is a brass colour

Faces are wound counter-clockwise seen from outside, so their geometric normals point outwards."""
import json
import math
import struct


def fix_winding(verts, faces, outward):
    """Swaps two corners of every face whose winding disagrees with outward(face)."""
    fixed = []
    for f in faces:
        a, b, c = (verts[i] for i in f)
        e1 = [b[k] - a[k] for k in range(3)]
        e2 = [c[k] - a[k] for k in range(3)]
        n = [e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]]
        o = outward(f)
        fixed.append(f if sum(n[k] * o[k] for k in range(3)) > 0 else (f[0], f[2], f[1]))
    return fixed


def write(path, header, verts, faces, normals=None, texcoords=None):
    """Normals and texture coordinates, if any, one per vertex (a corner's index is its vertex's)."""
    with open(path, "w") as out:
        out.write("".join("# " + line + "\n" for line in header))
        for v in verts:
            out.write("v %.6f %.6f %.6f\n" % tuple(v))
        for t in texcoords or []:
            out.write("vt %.6f %.6f\n" % tuple(t))
        for n in normals or []:
            out.write("vn %.6f %.6f %.6f\n" % tuple(n))
        form = "%d/%d/%d" if texcoords and normals else "%d/%d" if texcoords else "%d//%d" if normals else "%d"
        for f in faces:
            out.write("f " + " ".join(form % ((i + 1,) * form.count("%d")) for i in f) + "\n")


def write_glb(path, meshes, nodes, roots, materials=None, images=None):
    """Binary glTF 2.0: meshes = [(verts, faces, normals, texcoords[, material])] (normals,
    texcoords: one per vertex or None; material: an index into materials), nodes = glTF node
    objects referring to them, roots = the scene's nodes, materials = glTF material objects,
    images = PNG files embedded in the BIN chunk (textures[i] shows images[i]).
    Positions, normals and texture coordinates as float32, indices as uint16; glTF's v runs down
    the picture from its top edge, so a coordinate (u, v) is written as (u, 1 - v)."""
    doc = {"asset": {"version": "2.0", "generator": "strahl tools/make_meshes.py"},
           "scene": 0, "scenes": [{"nodes": roots}], "nodes": nodes,
           "meshes": [], "accessors": [], "bufferViews": [], "buffers": []}
    if materials:
        doc["materials"] = materials
    blob = bytearray()

    def accessor(values, fmt, component, kind, count, target):
        while len(blob) % 4:
            blob.append(0)
        data = struct.pack("<%d%s" % (len(values), fmt), *values)
        doc["bufferViews"].append({"buffer": 0, "byteOffset": len(blob), "byteLength": len(data), "target": target})
        blob.extend(data)
        a = {"bufferView": len(doc["bufferViews"]) - 1, "componentType": component, "type": kind, "count": count}
        if kind == "VEC3" and fmt == "f":
            a["min"] = [min(values[k::3]) for k in range(3)]
            a["max"] = [max(values[k::3]) for k in range(3)]
        doc["accessors"].append(a)
        return len(doc["accessors"]) - 1

    for png in images or []:
        while len(blob) % 4:
            blob.append(0)
        with open(png, "rb") as f:
            data = f.read()
        doc["bufferViews"].append({"buffer": 0, "byteOffset": len(blob), "byteLength": len(data)})
        blob.extend(data)
        doc.setdefault("images", []).append({"bufferView": len(doc["bufferViews"]) - 1, "mimeType": "image/png"})
        doc.setdefault("textures", []).append({"source": len(doc["images"]) - 1})
    for verts, faces, normals, texcoords, *material in meshes:
        attributes = {"POSITION": accessor([c for v in verts for c in v], "f", 5126, "VEC3", len(verts), 34962)}
        if normals:
            attributes["NORMAL"] = accessor([c for n in normals for c in n], "f", 5126, "VEC3", len(normals), 34962)
        if texcoords:
            attributes["TEXCOORD_0"] = accessor([c for u, v in texcoords for c in (u, 1 - v)], "f", 5126, "VEC2",
                                                len(texcoords), 34962)
        indices = accessor([i for f in faces for i in f], "H", 5123, "SCALAR", 3 * len(faces), 34963)
        primitive = {"attributes": attributes, "indices": indices}
        if material:
            primitive["material"] = material[0]
        doc["meshes"].append({"primitives": [primitive]})
    while len(blob) % 4:
        blob.append(0)
    doc["buffers"].append({"byteLength": len(blob)})
    text = json.dumps(doc, separators=(",", ":")).encode()
    text += b" " * (-len(text) % 4)
    with open(path, "wb") as out:
        out.write(struct.pack("<4sII", b"glTF", 2, 12 + 8 + len(text) + 8 + len(blob)))
        out.write(struct.pack("<I4s", len(text), b"JSON") + text)
        out.write(struct.pack("<I4s", len(blob), b"BIN\0") + bytes(blob))


def cornell_box():
    """(name, material, corners) of each quad, wound counter-clockwise seen from inside the room
    (walls) or from outside (blocks)."""
    quads = [
        ("floor", "white", [(552.8, 0, 0), (0, 0, 0), (0, 0, 559.2), (549.6, 0, 559.2)]),
        ("ceiling", "white", [(556, 548.8, 0), (556, 548.8, 559.2), (0, 548.8, 559.2), (0, 548.8, 0)]),
        ("back wall", "white", [(549.6, 0, 559.2), (0, 0, 559.2), (0, 548.8, 559.2), (556, 548.8, 559.2)]),
        ("right wall", "green", [(0, 0, 559.2), (0, 0, 0), (0, 548.8, 0), (0, 548.8, 559.2)]),
        ("left wall", "red", [(552.8, 0, 0), (549.6, 0, 559.2), (556, 548.8, 559.2), (556, 548.8, 0)]),
    ]
    short = [[(130, 165, 65), (82, 165, 225), (240, 165, 272), (290, 165, 114)],
             [(290, 0, 114), (290, 165, 114), (240, 165, 272), (240, 0, 272)],
             [(130, 0, 65), (130, 165, 65), (290, 165, 114), (290, 0, 114)],
             [(82, 0, 225), (82, 165, 225), (130, 165, 65), (130, 0, 65)],
             [(240, 0, 272), (240, 165, 272), (82, 165, 225), (82, 0, 225)]]
    tall = [[(423, 330, 247), (265, 330, 296), (314, 330, 456), (472, 330, 406)],
            [(423, 0, 247), (423, 330, 247), (472, 330, 406), (472, 0, 406)],
            [(472, 0, 406), (472, 330, 406), (314, 330, 456), (314, 0, 456)],
            [(314, 0, 456), (314, 330, 456), (265, 330, 296), (265, 0, 296)],
            [(265, 0, 296), (265, 330, 296), (423, 330, 247), (423, 0, 247)]]
    centre = (278, 274.4, 279.6)
    out = []
    for name, material, q in quads:  # walls face the room's centre
        out.append((name, material, wind(q, lambda c: [centre[k] - c[k] for k in range(3)])))
    for blocks, name in ((short, "short block"), (tall, "tall block")):
        mid = [sum(c[k] for q in blocks for c in q) / (4 * len(blocks)) for k in range(3)]
        for q in blocks:  # block faces face away from the block's centre
            out.append((name, "white", wind(q, lambda c, m=mid: [c[k] - m[k] for k in range(3)])))
    return out


def wind(quad, towards):
    """The quad, its corners reversed if its normal (right-hand rule) points away from towards(centre)."""
    a, b, c = quad[0], quad[1], quad[2]
    e1 = [b[k] - a[k] for k in range(3)]
    e2 = [c[k] - a[k] for k in range(3)]
    n = [e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]]
    mid = [sum(p[k] for p in quad) / 4 for k in range(3)]
    return quad if sum(n[k] * d for k, d in enumerate(towards(mid))) > 0 else quad[::-1]


def write_cornell_box(stem):
    colours = {"white": (0.725, 0.71, 0.68), "red": (0.63, 0.065, 0.05), "green": (0.14, 0.45, 0.091)}
    with open(stem + ".mtl", "w") as out:
        out.write("# the Cornell box's three diffuse colours (written by tools/make_meshes.py)\n")
        for name, kd in colours.items():
            out.write("newmtl %s\nKd %g %g %g\n" % ((name,) + kd))
    with open(stem + ".obj", "w") as out:
        out.write("# the Cornell box (Cornell University Program of Computer Graphics' measured data, in mm):\n"
                  "# five walls and two blocks; its materials in cornell-box.mtl (written by tools/make_meshes.py)\n")
        out.write("mtllib cornell-box.mtl\n")
        quads = cornell_box()
        for _, _, q in quads:
            for p in q:
                out.write("v %g %g %g\n" % p)
        current = None
        for i, (name, material, _) in enumerate(quads):
            if material != current:
                out.write("usemtl %s\n" % material)
                current = material
            out.write("f %d %d %d %d\n" % tuple(4 * i + k + 1 for k in range(4)))


def quaternion(axis, degrees):
    """glTF's rotation (x, y, z, w) about a unit axis."""
    h = math.radians(degrees) / 2
    return [axis[0] * math.sin(h), axis[1] * math.sin(h), axis[2] * math.sin(h), math.cos(h)]


def carousel():
    """Nodes: 0 the stand (turned 20 degrees about y, raised 0.68), its children 1 the cube (scale 0.55)
    and 2..7 six tori at radius 2 (scale 0.5, each turned about y and stood up about its own x)."""
    nodes = [{"name": "stand", "translation": [0, 0.68, 0], "rotation": quaternion((0, 1, 0), 20),
              "children": list(range(1, 8))},
             {"name": "cube", "mesh": 0, "scale": [0.55, 0.55, 0.55], "rotation": quaternion((1, 0, 0), 15)}]
    for k in range(6):
        a = 60 * k
        # Stood up about x, then turned about y to face the centre: q_y * q_x.
        qy, qx = quaternion((0, 1, 0), -a), quaternion((1, 0, 0), 90)
        q = [qy[3] * qx[0] + qy[0] * qx[3] + qy[1] * qx[2] - qy[2] * qx[1],
             qy[3] * qx[1] - qy[0] * qx[2] + qy[1] * qx[3] + qy[2] * qx[0],
             qy[3] * qx[2] + qy[0] * qx[1] - qy[1] * qx[0] + qy[2] * qx[3],
             qy[3] * qx[3] - qy[0] * qx[0] - qy[1] * qx[1] - qy[2] * qx[2]]
        nodes.append({"name": "torus %d" % k, "mesh": 1, "scale": [0.5, 0.5, 0.5], "rotation": q,
                      "translation": [2 * math.cos(math.radians(a)), 0, 2 * math.sin(math.radians(a))]})
    return nodes


def torus_uv(big_r=1.0, small_r=0.35, nu=24, nv=12):
    """The torus with a grid of (nu + 1) x (nv + 1) vertices: u = i / nu, v = j / nv."""
    verts, normals, texcoords, faces = [], [], [], []
    for i in range(nu + 1):
        u = 2 * math.pi * i / nu
        for j in range(nv + 1):
            v = 2 * math.pi * j / nv
            normals.append((math.cos(v) * math.cos(u), math.sin(v), math.cos(v) * math.sin(u)))
            verts.append(((big_r + small_r * math.cos(v)) * math.cos(u), small_r * math.sin(v),
                          (big_r + small_r * math.cos(v)) * math.sin(u)))
            texcoords.append((i / nu, j / nv))
    idx = lambda i, j: i * (nv + 1) + j
    tris = []
    for i in range(nu):
        for j in range(nv):
            a, b, c, d = idx(i, j), idx(i + 1, j), idx(i + 1, j + 1), idx(i, j + 1)
            tris += [(a, b, c), (a, c, d)]
    outward = lambda f: [sum(normals[i][k] for i in f) for k in range(3)]
    return verts, normals, texcoords, fix_winding(verts, tris, outward)


def cube_uv():
    """Six faces of two triangles, each face's corners at texture coordinates (0,0) (1,0) (1,1) (0,1)."""
    verts, texcoords, faces = [], [], []
    corners = [(0, 0), (1, 0), (1, 1), (0, 1)]
    # Each face: its centre's axis, and the directions of u and v across it (seen from outside).
    sides = [((0, 0, 1), (1, 0, 0), (0, 1, 0)), ((1, 0, 0), (0, 0, -1), (0, 1, 0)),
             ((0, 0, -1), (-1, 0, 0), (0, 1, 0)), ((-1, 0, 0), (0, 0, 1), (0, 1, 0)),
             ((0, 1, 0), (1, 0, 0), (0, 0, -1)), ((0, -1, 0), (1, 0, 0), (0, 0, 1))]
    for n, du, dv in sides:
        first = len(verts)
        for su, sv in corners:
            verts.append(tuple(n[k] + (2 * su - 1) * du[k] + (2 * sv - 1) * dv[k] for k in range(3)))
            texcoords.append((su, sv))
        faces += [(first, first + 1, first + 2), (first, first + 2, first + 3)]
    return verts, texcoords, faces


def torus(big_r=1.0, small_r=0.35, nu=20, nv=10):
    verts, normals, faces = [], [], []
    for i in range(nu):
        u = 2 * math.pi * i / nu
        for j in range(nv):
            v = 2 * math.pi * j / nv
            n = (math.cos(v) * math.cos(u), math.sin(v), math.cos(v) * math.sin(u))
            verts.append(((big_r + small_r * math.cos(v)) * math.cos(u), small_r * math.sin(v),
                          (big_r + small_r * math.cos(v)) * math.sin(u)))
            normals.append(n)
    idx = lambda i, j: (i % nu) * nv + (j % nv)
    for i in range(nu):
        for j in range(nv):
            a, b, c, d = idx(i, j), idx(i + 1, j), idx(i + 1, j + 1), idx(i, j + 1)
            faces += [(a, b, c), (a, c, d)]
    outward = lambda f: [sum(normals[i][k] for i in f) for k in range(3)]
    return verts, normals, fix_winding(verts, faces, outward)


def icosahedron():
    p = (1 + math.sqrt(5)) / 2
    raw = [(-1, p, 0), (1, p, 0), (-1, -p, 0), (1, -p, 0), (0, -1, p), (0, 1, p),
           (0, -1, -p), (0, 1, -p), (p, 0, -1), (p, 0, 1), (-p, 0, -1), (-p, 0, 1)]
    s = 1 / math.sqrt(1 + p * p)
    verts = [tuple(c * s for c in v) for v in raw]
    # The 20 faces: vertex triples at the edge length (2 before scaling) from one another.
    near = lambda a, b: abs(sum((verts[a][k] - verts[b][k]) ** 2 for k in range(3)) - 4 * s * s) < 1e-9
    faces = [(a, b, c) for a in range(12) for b in range(a + 1, 12) for c in range(b + 1, 12)
             if near(a, b) and near(b, c) and near(a, c)]
    assert len(faces) == 20
    outward = lambda f: [sum(verts[i][k] for i in f) for k in range(3)]
    return verts, fix_winding(verts, faces, outward)


if __name__ == "__main__":
    v, n, f = torus()
    write("scenes/meshes/torus.obj", ["torus about the y axis: major radius 1, minor radius 0.35, 20 x 10 segments,",
                                      "%d triangles with vertex normals (written by tools/make_meshes.py)" % len(f)],
          v, f, n)
    v, f = icosahedron()
    write("scenes/meshes/icosahedron.obj", ["regular icosahedron, circumradius 1, 20 triangles, no normals",
                                            "(flat shaded; written by tools/make_meshes.py)"], v, f)
    v, n, t, f = torus_uv()
    write("scenes/meshes/torus-uv.obj",
             ["torus about the y axis: major radius 1, minor radius 0.35, 24 x 12 segments, %d triangles" % len(f),
              "with vertex normals and texture coordinates: u once around the ring, v once around the tube",
              "(written by tools/make_meshes.py)"], v, f, n, t)
    v, t, f = cube_uv()
    write("scenes/meshes/cube-uv.obj",
             ["cube from -1 to 1, 12 triangles, each face's texture coordinates the whole unit square",
              "(written by tools/make_meshes.py)"], v, f, texcoords=t)
    write_glb("scenes/meshes/cube-uv.glb", [(v, f, None, t)], [{"mesh": 0}], [0])
    tv, tn, tt, tf = torus_uv()
    write_cornell_box("scenes/meshes/cornell-box")
    # The cube's material shows the picture (embedded), the tori's is a colour.
    write_glb("scenes/meshes/carousel.glb", [(v, f, None, t, 0), (tv, tf, tn, tt, 1)], carousel(), [0],
              materials=[{"name": "picture", "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}},
                         {"name": "brass", "pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.5, 0.12, 1]}}],
              images=["scenes/textures/grid.png"])
