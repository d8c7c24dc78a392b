# Scene files from Python: strahl.load with the CLI's errors (file, line, column), and scenes built
# in Python saved as YAML that read back to the same compiled scene.
import os

import numpy as np
import pytest

strahl = pytest.importorskip("strahl")


def test_load_errors_carry_file_line_and_column(tmp_path, cli):
    bad = tmp_path / "bad.yaml"
    bad.write_text("objects:\n  - {type: sphere, center: [0, 0, 0], radius: -1}\n")
    with pytest.raises(strahl.Error) as info:
        strahl.load(bad)
    e = info.value
    assert (e.file, e.line, e.column) == (str(bad), 2, 47)
    assert str(e) == f"{bad}:2:47: sphere radius must be positive (got -1)"
    # The very message the CLI prints after "strahl: error: ".
    result = cli(bad, "-o", tmp_path / "x.png", check=False)
    assert result.returncode == 2
    assert result.stderr.strip() == f"strahl: error: {e}"


def test_syntax_errors_and_missing_files(tmp_path):
    (tmp_path / "syntax.yaml").write_text("objects: [\n")
    with pytest.raises(strahl.Error) as info:
        strahl.load(tmp_path / "syntax.yaml")
    assert info.value.line == 2 and "syntax error" in str(info.value)
    with pytest.raises(strahl.Error) as info:
        strahl.load(tmp_path / "missing.yaml")
    assert info.value.file == str(tmp_path / "missing.yaml") and info.value.line is None
    with pytest.raises(strahl.Error, match=r"^<text>:1:10: unknown key 'spheres' in render"):
        strahl.loads("render: {spheres: 1}\n", name="<text>")


def test_errors_of_scenes_built_in_python_name_the_python_line():
    scene = strahl.Scene()
    mesh = strahl.Mesh([[0, 0, 0], [1, 0, 0], [2, 0, 0]], [[0, 1, 2]])  # all faces degenerate
    line = test_errors_of_scenes_built_in_python_name_the_python_line.__code__.co_firstlineno + 2
    scene.add(mesh)
    with pytest.raises(strahl.Error) as info:
        strahl.render(scene, width=4, height=4)
    assert info.value.file == __file__ and info.value.line == line
    assert str(info.value) == f"{__file__}:{line}: mesh has no triangle with an area (all 1 are degenerate)"


def python_scene():
    """Every kind of object, light, material setting and camera setting, built in Python."""
    scene = strahl.Scene()
    scene.camera = strahl.Camera(position=(0.1, 0.9, 2.5), look_at=(0, 0.3, 0), fov=40, aperture=0.02,
                                 focus_point=(0, 0.3, 0), shutter=(0.2, 0.8))
    s = scene.settings
    s.width, s.height, s.spp, s.sampler, s.seed = 48, 32, 3, "sobol", 2**40 + 1
    s.filter, s.filter_radius, s.max_depth, s.background = "tent", 1.25, 6, (0.05, 0.1, 0.2)
    glass = strahl.Material(color=(0.9, 1, 0.9), transparency=0.9, ior="glass", fresnel=True, filter=True)
    scene.add(strahl.Plane((0, 1, 0), 0, material=strahl.Material(checker_size=0.25, checker_color=(1, 1, 0))))
    scene.add(strahl.Sphere((0.05, 0.3, 0), 0.3, color=(0.8, 0.2, 0.2), motion=strahl.Motion.linear((0.1, 0, 0))))
    scene.add(strahl.Sphere((-0.4, 0.2, 0.2), 0.2, material=glass))
    scene.add(strahl.Triangle((0.3, 0, -0.5), (0.9, 0, -0.5), (0.6, 0.7, -0.5), (0.2, 0.7, 0.3)))
    v = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], dtype=float) * 0.3 + (0.4, 0.05, 0.3)
    scene.add(strahl.Mesh(v, [[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]], color=(0.3, 0.3, 0.9),
                          rotate=(0, 15, 0), scale=(1, 1.5, 1)))
    scene.add_light((1, 1.5, 1))
    scene.add(strahl.DirectionalLight((0.2, -1, -0.3), intensity=0.3))
    scene.add(strahl.SpotLight((0.3, 1.2, 0.4), (0, 0.2, 0), (1, 0.8, 0.6), 0.8, angle=15, falloff=22.5, tightness=3,
                              fade_distance=1.5, fade_power=2))
    scene.add(strahl.RectLight((-0.5, 1.8, -0.5), (0.4, 0, 0), (0, 0, 0.4), power=2, samples=2))
    scene.add(strahl.DiskLight((0.5, 1.8, 0.5), (0.1, -1, 0), 0.2, color=(1, 0.9, 0.8), samples=2))
    scene.add(strahl.SphereLight((0, 2, 1), 0.1, intensity=2, samples=1))
    grid = os.path.join(os.environ.get("STRAHL_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", "..")),
                        "scenes", "textures", "grid.png")
    globe = scene.add_texture(grid, mapping="spherical", interpolate="nearest", translate=(0.7, 0.25, 0.4))
    scene.add(strahl.Sphere((0.7, 0.25, 0.4), 0.15, material=strahl.Material(texture=globe)))
    label = scene.add_texture(grid, mapping="uv", interpolate="nearest", scale=(0.5, 1, 1))
    scene.add(strahl.Mesh([[-0.9, 0, -0.9], [-0.5, 0, -0.9], [-0.5, 0.4, -0.9], [-0.9, 0.4, -0.9]],
                          [[0, 1, 2], [0, 2, 3]], texcoords=[[0, 0], [1, 0], [1, 1], [0, 1]],
                          material=strahl.Material(texture=label)))
    return scene


def test_saved_scenes_read_back_to_the_same_compiled_scene(tmp_path, cli):
    scene = python_scene()
    path = tmp_path / "saved.yaml"
    scene.save(path)
    back = strahl.load(path)
    assert strahl._scene_hash(back) == strahl._scene_hash(scene)
    assert back.to_yaml() == scene.to_yaml()
    image = strahl.render(scene)
    assert np.array_equal(np.asarray(strahl.render(back)), np.asarray(image))
    # The CLI reads it too, to the same floats.
    cli(path, "-q", "-o", tmp_path / "cli.pfm")
    assert np.array_equal(np.asarray(strahl.read(tmp_path / "cli.pfm")), np.asarray(image))


def test_the_hash_sees_a_change():
    """The round-trip check could fail: a scene that differs in one light's last bit hashes differently."""
    a, b = python_scene(), python_scene()
    b.add_light((1, 1.5, 1.0000000000000002))
    a.add_light((1, 1.5, 1))
    assert strahl._scene_hash(a) != strahl._scene_hash(b)


def test_save_refuses_bad_paths(tmp_path):
    scene = python_scene()
    with pytest.raises(strahl.Error, match="unknown scene format '.png'"):
        scene.save(tmp_path / "x.png")
    with pytest.raises(strahl.Error):
        scene.save(tmp_path / "missing-dir" / "x.yaml")
    assert list(tmp_path.iterdir()) == []


def test_pov_ray_scenes_load_with_their_size_and_declared_names(tmp_path, source_dir):
    lecture = f"{source_dir}/scenes/lecture.pov"
    whitted = strahl.load(lecture, width=32, height=18, declare={"WHITTED": 1})
    twin = strahl.render(strahl.load(f"{source_dir}/scenes/lecture-whitted.yaml"), width=32, height=18)
    assert (whitted.settings.width, whitted.settings.height) == (32, 18)
    assert np.array_equal(strahl.render(whitted), twin)
    assert not np.array_equal(strahl.render(strahl.load(lecture, width=32, height=18)), twin)
    # Errors name the .pov file's line and column; saved, the scene is strahl's YAML.
    bad = tmp_path / "bad.pov"
    bad.write_text("sphere { 0, 1 }\nsphere { 0, -1 }\n")
    with pytest.raises(strahl.Error) as info:
        strahl.load(bad)
    assert (info.value.file, info.value.line, info.value.column) == (str(bad), 2, 1)
    # width and height override any scene's size, as the CLI's flags do.
    small = strahl.load(f"{source_dir}/scenes/lecture-whitted.yaml", width=32, height=18)
    assert (small.settings.width, small.settings.height) == (32, 18)
    assert np.array_equal(strahl.render(small), twin)
    whitted.save(tmp_path / "whitted.yaml")
    assert np.array_equal(strahl.render(strahl.load(tmp_path / "whitted.yaml")), twin)
