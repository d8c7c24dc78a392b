#!/usr/bin/env python3
"""Writes the small example meshes under scenes/meshes/ (run once from the repository root):

  torus.obj        a torus about the y axis (major radius 1, minor 0.35), 20 x 10 segments,
                   400 triangles with vertex normals (smooth shading)
  icosahedron.obj  a regular icosahedron of circumradius 1, 20 triangles, no normals (flat shading)
  torus-uv.obj     the torus with texture coordinates: u once around the ring, v once around the
                   tube (vertices doubled along the seams, where u or v jumps from 1 back to 0)
  cube-uv.obj      a cube from -1 to 1, each face's texture coordinates the whole unit square
                   (upright on the sides, the picture's top towards -z on the top and bottom)

Faces are wound counter-clockwise seen from outside, so their geometric normals point outwards."""
import math


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
