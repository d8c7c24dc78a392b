# Bad arguments raise Python exceptions (TypeError for wrong types, strahl.Error — a ValueError —
# for impossible values, with the scene files' messages); none crashes the interpreter.
import math

import numpy as np
import pytest

strahl = pytest.importorskip("strahl")

nan, inf = math.nan, math.inf


@pytest.mark.parametrize("make, message", [
    (lambda: strahl.Sphere((0, 0, 0), -1), r"^sphere radius must be positive \(got -1\)$"),
    (lambda: strahl.Sphere((0, 0, 0), 0), "sphere radius must be positive"),
    (lambda: strahl.Sphere((0, 0, 0), nan), "sphere radius must be a finite number"),
    (lambda: strahl.Sphere((0, nan, 0), 1), "sphere center must have finite components"),
    (lambda: strahl.Sphere((0, 0, 0), 1, color=(-1, 0, 0)), "material colour must not have negative"),
    (lambda: strahl.Plane((0, 0, 0), 1), "plane normal must not be the zero vector"),
    (lambda: strahl.Triangle((0, 0, 0), (1, 1, 1), (2, 2, 2)), "degenerate triangle"),
    (lambda: strahl.Material(reflectivity=2), r"reflectivity must lie in \[0, 1\] \(got 2\)"),
    (lambda: strahl.Material(ior="unobtainium"), "unknown ior 'unobtainium'"),
    (lambda: strahl.Material(ior=0), "ior must be positive"),
    (lambda: strahl.Material(emission=(0, -1, 0)), "emission must not have negative"),
    (lambda: strahl.PointLight((0, inf, 0)), "light position must have finite components"),
    (lambda: strahl.PointLight((0, 1, 0), intensity=-1), "intensity must not be negative"),
    (lambda: strahl.RectLight((0, 1, 0), (1, 0, 0), (1, 1, 0)), "rect light edges must be perpendicular"),
    (lambda: strahl.SpotLight((0, 1, 0), (0, 1, 0)), r"spotlight direction \(point_at − position\) must not be"),
    (lambda: strahl.SpotLight((0, 1, 0), (0, 0, 0), angle=91), r"spotlight angle must lie in \[0, 90\]"),
    (lambda: strahl.SpotLight((0, 1, 0), (0, 0, 0), tightness=-1), "spotlight tightness must not be negative"),
    (lambda: strahl.PointLight((0, 1, 0), fade_power=2), "fade_power needs a positive fade_distance"),
    (lambda: strahl.DiskLight((0, 1, 0), (0, -1, 0), -0.5), "light radius must be positive"),
    (lambda: strahl.SphereLight((0, 1, 0), 0.1, samples=0), r"light samples must lie in \[1, 64\]"),
    (lambda: strahl.Scene().add_texture("no-such-file.png"), "no-such-file.png"),
    (lambda: strahl.Scene().add_texture("x.png", mapping="torus"), "unknown image mapping 'torus'"),
    (lambda: strahl.Scene().add_texture("x.png", interpolate="cubic"), "unknown image interpolate 'cubic'"),
    (lambda: strahl.Camera(fov=180), r"fov must lie in \(0, 180\)"),
    (lambda: strahl.Camera(position=(0, 1, 0), look_at=(0, 1, 0)), "camera position and look_at coincide"),
    (lambda: strahl.Camera(up=(0, 0, 0)), "camera up must not be the zero vector"),
    (lambda: strahl.Camera(fov_axis="diagonal"), "fov_axis must be 'horizontal' or 'vertical'"),
    (lambda: strahl.Transform(scale=0), "transform scale must not be zero"),
    (lambda: strahl.Motion.linear((nan, 0, 0)), "motion velocity must have finite components"),
    (lambda: strahl.Spin((0, 0, 0), 90), "motion spin axis must not be zero"),
    (lambda: strahl.Spin((0, 1, 0), inf), "motion spin angle must be a finite number"),
    (lambda: strahl.Spin((0, 1, 0), 90, center=(nan, 0, 0)), "motion spin center must have finite components"),
])
def test_impossible_values_raise_strahl_error(make, message):
    with pytest.raises(strahl.Error, match=message) as info:
        make()
    assert isinstance(info.value, ValueError)


@pytest.mark.parametrize("make", [
    lambda: strahl.Sphere("abc", 1),
    lambda: strahl.Sphere((0, 0), 1),
    lambda: strahl.Sphere((0, 0, 0, 0), 1),
    lambda: strahl.Sphere((0, "x", 0), 1),
    lambda: strahl.Sphere((0, 0, 0), "1"),
    lambda: strahl.Sphere((0, 0, 0), None),
    lambda: strahl.Sphere((0, 0, 0), 1, color="red"),
    lambda: strahl.Sphere((0, 0, 0), 1, color=(1, 0, 0), material=strahl.Material()),
    lambda: strahl.Sphere((0, 0, 0), 1, material=(1, 0, 0)),
    lambda: strahl.Scene().add(42),
    lambda: strahl.Scene().add_light("up"),
    lambda: strahl.render(42),
    lambda: strahl.render(strahl.lecture_scene(), width="wide"),
    lambda: strahl.render(strahl.lecture_scene(), aovs=[1]),
    lambda: strahl.render(strahl.lecture_scene(), progress=5),
    lambda: strahl.render(strahl.lecture_scene(), bogus=1),
    lambda: strahl.write("not an image", "x.png"),
    lambda: strahl.write(np.array([["a"]]), "x.png"),
])
def test_wrong_types_raise_typeerror(make):
    with pytest.raises(TypeError):
        make()


@pytest.mark.parametrize("options, message", [
    (dict(width=0), r"width must lie in \[1, 65536\] \(got 0\)"),
    (dict(width=-5), "width must lie in"),
    (dict(height=100000), "height must lie in"),
    (dict(spp=0), r"spp must lie in \[1, 1048576\]"),
    (dict(sampler="best"), r"unknown sampler 'best' \(grid, stratified, random, sobol, adaptive\)"),
    (dict(filter="lanczos"), "unknown filter 'lanczos'"),
    (dict(filter_radius=nan), "filter_radius must be a finite number"),
    (dict(filter_radius=9), r"filter_radius must lie in \[0.5, 4\]"),
    (dict(accel="grid"), "unknown accel 'grid'"),
    (dict(max_depth=0), "max_depth must lie in"),
    (dict(threads=-1), r"threads must lie in \[0, 4096\]"),
    (dict(tile_size=0), "tile_size must lie in"),
    (dict(time_limit=-1), "time_limit must not be negative"),
    (dict(time_limit=nan), "time_limit must be a finite number"),
    (dict(aovs=["depth", "colour"]), r"unknown aov 'colour' \(depth, normal, albedo, id\)"),
    (dict(adaptive_threshold=0), "adaptive_threshold must be positive"),
])
def test_bad_render_options_raise(options, message):
    with pytest.raises(strahl.Error, match=message):
        strahl.render(strahl.lecture_scene(), **options)


def test_bad_writes_raise(tmp_path):
    image = np.zeros((4, 4, 3), dtype=np.float32)
    with pytest.raises(strahl.Error, match="unknown|extension"):
        strahl.write(image, tmp_path / "x.bmp")
    with pytest.raises(strahl.Error):
        strahl.write(image, tmp_path / "missing" / "x.png")
    with pytest.raises(ValueError, match="shape"):
        strahl.write(np.zeros((4, 4, 4)), tmp_path / "x.png")
    with pytest.raises(ValueError):
        strahl.write(np.zeros((0, 4, 3)), tmp_path / "x.png")
    with pytest.raises(strahl.Error):
        strahl.read(tmp_path / "nothing.png")
    # Grey images and other dtypes are fine.
    strahl.write(np.full((3, 5), 0.5), tmp_path / "grey.pfm")
    assert np.all(strahl.read(tmp_path / "grey.pfm") == 0.5)
    assert list(p.name for p in tmp_path.iterdir()) == ["grey.pfm"]


def test_the_scene_api_reads_back():
    scene = strahl.Scene()
    sphere = strahl.Sphere((0.05, 0.3, 0), 0.3, color=(0.8, 0.2, 0.2))
    scene.add(sphere)
    sphere.radius = 5  # add() copied it
    assert scene.objects[0].radius == 0.3
    scene.objects[0].material.reflectivity = 0.5  # the scene's own object
    assert scene.objects[0].material.reflectivity == 0.5
    scene.addLightSource((1, 1.5, 1))
    assert scene.getNumLightSources() == 1 and scene.getLightSource(0) == (1, 1.5, 1)
    with pytest.raises(IndexError):
        scene.getLightSource(1)
    assert scene.lights[0].kind == "point" and len(scene) == 1
    scene.settings.sampler = "stratified"
    assert scene.settings.sampler == "stratified"
    with pytest.raises(strahl.Error):
        scene.settings.sampler = "nope"
    assert strahl.Material(ior="water").ior == 1.333
    assert tuple(strahl.Material(emission=(0.5, 1, 2)).emission) == (0.5, 1, 2)
    assert repr(strahl.Sphere((0, 1, 0), 0.5)).startswith("strahl.Sphere((0, 1, 0), 0.5")
