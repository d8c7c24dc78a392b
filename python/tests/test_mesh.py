# Meshes from numpy arrays are the same meshes as from files: the same compiled scene and image.
import os

import numpy as np
import pytest

strahl = pytest.importorskip("strahl")


def torus(n=12, m=8, R=0.4, r=0.15):
    """A closed torus, as float64 arrays of float32 values (tinyobjloader, which reads OBJ files
    for strahl, keeps floats)."""
    u, v = np.meshgrid(np.arange(n) * 2 * np.pi / n, np.arange(m) * 2 * np.pi / m, indexing="ij")
    vertices = np.stack([(R + r * np.cos(v)) * np.cos(u), r * np.sin(v) + 0.3, (R + r * np.cos(v)) * np.sin(u)], -1)
    vertices = vertices.reshape(-1, 3)
    normals = np.stack([np.cos(v) * np.cos(u), np.sin(v), np.cos(v) * np.sin(u)], -1).reshape(-1, 3)
    faces = []
    for i in range(n):
        for j in range(m):
            a, b = i * m + j, ((i + 1) % n) * m + j
            c, d = ((i + 1) % n) * m + (j + 1) % m, i * m + (j + 1) % m
            faces += [[a, d, c], [a, c, b]]
    as_float = lambda a: a.astype(np.float32).astype(np.float64)
    return as_float(vertices), np.array(faces), as_float(normals)


def write_obj(path, vertices, faces, normals=None):
    # repr() of a float64 is its shortest round-trip form.
    with open(path, "w") as f:
        for p in vertices:
            f.write("v %r %r %r\n" % tuple(float(x) for x in p))
        if normals is not None:
            for n in normals:
                f.write("vn %r %r %r\n" % tuple(float(x) for x in n))
        for t in faces + 1:
            f.write("f " + " ".join(f"{i}//{i}" if normals is not None else f"{i}" for i in t) + "\n")


def scene_with(mesh):
    scene = strahl.Scene()
    scene.add(strahl.Plane((0, 1, 0), 0, color=(0.3, 0.3, 0.3)))
    scene.add(mesh)
    scene.add_light((1, 1.5, 1))
    return scene


@pytest.mark.parametrize("smooth", [False, True])
def test_numpy_mesh_equals_the_same_obj(tmp_path, smooth):
    vertices, faces, normals = torus()
    if not smooth:
        normals = None
    write_obj(tmp_path / "torus.obj", vertices, faces, normals)
    place = dict(color=(0.2, 0.6, 0.9), rotate=(20, 0, 0), translate=(0, 0.1, 0))
    from_file = strahl.Mesh.load(tmp_path / "torus.obj", **place)
    from_numpy = strahl.Mesh(vertices, faces, normals, **place)
    # The file reads back to the arrays.
    assert np.array_equal(from_file.vertices, vertices)
    assert np.array_equal(from_file.indices, faces)
    a, b = scene_with(from_file), scene_with(from_numpy)
    assert strahl._scene_hash(a) == strahl._scene_hash(b)
    image_a = strahl.render(a, width=64, height=48)
    assert np.array_equal(np.asarray(image_a), np.asarray(strahl.render(b, width=64, height=48)))
    # The torus is in the picture: without it the image differs.
    assert not np.array_equal(np.asarray(image_a), np.asarray(strahl.render(scene_with(strahl.Sphere((9, 9, 9), 0.1)),
                                                                             width=64, height=48)))
    # And a scene file naming the OBJ gives the same compiled scene.
    (tmp_path / "scene.yaml").write_text(
        "lights: [{type: point, position: [1, 1.5, 1]}]\n"
        "objects:\n"
        "  - {type: plane, normal: [0, 1, 0], distance: 0, material: {color: [0.3, 0.3, 0.3]}}\n"
        "  - {type: mesh, file: torus.obj, rotate: [20, 0, 0], translate: [0, 0.1, 0],"
        " material: {color: [0.2, 0.6, 0.9]}}\n")
    from_yaml = strahl.load(tmp_path / "scene.yaml")
    assert strahl._scene_hash(from_yaml) == strahl._scene_hash(a)


def test_a_different_mesh_hashes_differently():
    vertices, faces, _ = torus()
    other = vertices.copy()
    other[5, 1] = np.nextafter(other[5, 1], 1)
    assert strahl._scene_hash(scene_with(strahl.Mesh(vertices, faces))) != \
        strahl._scene_hash(scene_with(strahl.Mesh(other, faces)))


def test_mesh_arguments_are_checked():
    v = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0]], dtype=np.float32)
    with pytest.raises(strahl.Error, match="refers to vertex 3, which does not exist"):
        strahl.Mesh(v, [[0, 1, 3]])
    with pytest.raises(strahl.Error, match="refers to vertex -1"):
        strahl.Mesh(v, [[0, 1, -1]])
    with pytest.raises(ValueError, match=r"shape \(n, 3\)"):
        strahl.Mesh(v[:, :2], [[0, 1, 2]])
    with pytest.raises(ValueError, match=r"shape \(m, 3\)"):
        strahl.Mesh(v, [0, 1, 2])
    with pytest.raises(TypeError, match="integers"):
        strahl.Mesh(v, [[0.0, 1.0, 2.0]])
    with pytest.raises(TypeError):
        strahl.Mesh(v, "abc")
    with pytest.raises(strahl.Error, match="finite"):
        strahl.Mesh([[0, 0, np.nan], [1, 0, 0], [0, 1, 0]], [[0, 1, 2]])
    with pytest.raises(strahl.Error, match="no faces"):
        strahl.Mesh(v, np.zeros((0, 3), dtype=int))
    with pytest.raises(ValueError, match="one row per vertex"):
        strahl.Mesh(v, [[0, 1, 2]], normals=[[0, 0, 1]])
    with pytest.raises(strahl.Error, match="scale must not be zero"):
        strahl.Mesh(v, [[0, 1, 2]], scale=(1, 0, 1))
    with pytest.raises(strahl.Error, match=r"cannot open mesh file|no such file"):
        strahl.Mesh.load("/nonexistent/x.obj")
    mesh = strahl.Mesh(v, np.array([[0, 1, 2]], dtype=np.uint8))  # any integer dtype
    assert mesh.indices.tolist() == [[0, 1, 2]] and mesh.vertices.dtype == np.float64


def test_gltf_mesh_equals_its_obj_twin(source_dir):
    """Mesh.load reads glTF (.glb) as the scene files do: the example cube equals its OBJ twin
    (the glTF's v runs down the picture, turned on reading), and a glTF error is a strahl.Error."""
    meshes = os.path.join(source_dir, "scenes", "meshes")
    obj = strahl.Mesh.load(os.path.join(meshes, "cube-uv.obj"))
    glb = strahl.Mesh.load(os.path.join(meshes, "cube-uv.glb"))
    for name in ("vertices", "indices", "texcoords", "texcoord_indices"):
        assert np.array_equal(getattr(glb, name), getattr(obj, name)), name
    bad = os.path.join(source_dir, "tests", "bad-input", "meshes", "gltf-node-cycle.gltf")
    with pytest.raises(strahl.Error, match=r"nodes\[0\]: is reached twice"):
        strahl.Mesh.load(bad)
    with pytest.raises(strahl.Error, match="only glTF .* and OBJ files"):
        strahl.Mesh.load(os.path.join(source_dir, "tests", "bad-input", "meshes", "ply-empty.ply"), file_materials=True)


def test_gltf_file_materials_as_in_a_scene_file(source_dir, tmp_path):
    """Mesh.load(..., file_materials=True) added to a scene (or a group) is the scene file's
    `file_materials: true`: the same compiled scene; without them, another."""
    glb = os.path.join(source_dir, "scenes", "meshes", "carousel.glb")
    (tmp_path / "s.yaml").write_text("objects:\n  - {type: mesh, file: %s, file_materials: true, "
                                     "material: {specular: 0.3}}\n" % glb)
    from_file = strahl.load(tmp_path / "s.yaml")
    material = strahl.Material(specular=0.3)
    scene = strahl.Scene()
    scene.add(strahl.Mesh.load(glb, material=material, file_materials=True))
    assert strahl._scene_hash(scene) == strahl._scene_hash(from_file)
    plain = strahl.Scene()
    plain.add(strahl.Mesh.load(glb, material=material))
    assert strahl._scene_hash(plain) != strahl._scene_hash(from_file)
    # Saved, the scene names the glTF file again, and reads back to the same scene.
    scene.save(tmp_path / "saved.yaml")
    assert "file_materials: true" in (tmp_path / "saved.yaml").read_text()
    assert strahl._scene_hash(strahl.load(tmp_path / "saved.yaml")) == strahl._scene_hash(scene)


def test_mesh_texcoords_equal_the_same_obj(tmp_path):
    """Texture coordinates (one (u, v) row per vertex) are the OBJ's vt: the same compiled scene,
    and a uv-mapped image reads them (the image differs from the planar one's)."""
    vertices, faces, normals = torus()
    texcoords = np.stack([np.arctan2(vertices[:, 2], vertices[:, 0]) / (2 * np.pi) + 0.5, vertices[:, 1]], -1)
    texcoords = texcoords.astype(np.float32).astype(np.float64)
    with open(tmp_path / "torus.obj", "w") as f:
        for p in vertices:
            f.write("v %r %r %r\n" % tuple(float(x) for x in p))
        for t in texcoords:
            f.write("vt %r %r\n" % tuple(float(x) for x in t))
        for t in faces + 1:
            f.write("f " + " ".join(f"{i}/{i}" for i in t) + "\n")
    grid = np.zeros((2, 4, 3), dtype=np.float32)
    grid[0, ::2] = grid[1, 1::2] = 1
    strahl.write(grid, tmp_path / "grid.pfm")
    from_file = strahl.Mesh.load(tmp_path / "torus.obj")
    assert np.array_equal(from_file.texcoords, texcoords)
    assert np.array_equal(from_file.texcoord_indices, faces)
    images = {}
    for mapping in ("uv", "planar"):
        scenes = []
        for from_numpy in (False, True):
            scene = strahl.Scene()
            material = strahl.Material(texture=scene.add_texture(tmp_path / "grid.pfm", mapping=mapping))
            scene.add(strahl.Mesh(vertices, faces, texcoords=texcoords, material=material) if from_numpy
                      else strahl.Mesh.load(tmp_path / "torus.obj", material=material))
            scene.add_light((1, 1.5, 1))
            scenes.append(scene)
        assert strahl._scene_hash(scenes[0]) == strahl._scene_hash(scenes[1])
        images[mapping] = np.asarray(strahl.render(scenes[0], width=64, height=48))
    assert not np.array_equal(images["uv"], images["planar"])
    with pytest.raises(ValueError, match=r"shape \(n, 2\)"):
        strahl.Mesh(vertices, faces, texcoords=vertices)
    with pytest.raises(ValueError, match="one row per vertex"):
        strahl.Mesh(vertices, faces, texcoords=texcoords[:3])
