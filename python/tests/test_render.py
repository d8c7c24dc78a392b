# strahl.render drives the same render job as the CLI: the same scene gives the same floats, bit
# for bit (compared through the CLI's PFM, which stores float32 as they are).
import numpy as np
import pytest

strahl = pytest.importorskip("strahl")


def slide_scene():
    """The lecture's scene, written with the slide names as the README's C++ example."""
    scene = strahl.Scene()
    scene.addSceneObject(strahl.Plane((0.0, 1.0, 0.0), 0.0, (0.3, 0.3, 0.3)))
    scene.addSceneObject(strahl.Sphere((0.05, 0.3, 0.0), 0.3, (0.8, 0.2, 0.2)))
    scene.addSceneObject(strahl.Sphere((0.4, 0.1, 0.1), 0.1, (0.0, 1.0, 0.0)))
    scene.addSceneObject(strahl.Sphere((-0.35, 0.25, -0.15), 0.25, (0.5, 0.5, 0.1)))
    scene.addSceneObject(strahl.Sphere((-0.35, 0.15, 0.3), 0.15, (0.0, 0.0, 1.0)))
    scene.addSceneObject(strahl.Sphere((0.15, 0.6, -1.0), 0.6, (0.2, 0.4, 0.5)))
    scene.addLightSource((1.0, 1.5, 1.0))
    return scene


def assert_bits_equal(a, b):
    assert a.shape == b.shape and a.dtype == b.dtype == np.float32
    assert np.array_equal(a.view(np.uint32), b.view(np.uint32)), f"{np.count_nonzero(a != b)} values differ"


def test_lecture_scene_equals_cli_bit_for_bit(cli, tmp_path):
    cli("--width", 160, "--height", 90, "-q", "-o", tmp_path / "cli.pfm")
    expected = strahl.read(tmp_path / "cli.pfm")
    image = strahl.render(slide_scene(), width=160, height=90)
    assert isinstance(image, np.ndarray) and isinstance(image, strahl.Image)
    assert image.shape == (90, 160, 3) and image.dtype == np.float32
    assert_bits_equal(np.asarray(image), np.asarray(expected))
    assert_bits_equal(np.asarray(strahl.render(strahl.lecture_scene(), width=160, height=90, threads=1, tile_size=7)),
                      np.asarray(expected))


def test_render_options_equal_cli_flags(cli, tmp_path, source_dir):
    scene_file = f"{source_dir}/scenes/lecture-whitted.yaml"
    flags = dict(width=64, height=48, spp=5, sampler="sobol", seed=7, filter="gaussian", filter_radius=1.5,
                 max_depth=3, accel="kdtree")
    args = [a for k, v in flags.items() for a in (f"--{k.replace('_', '-')}", v)]
    cli(scene_file, *args, "-q", "-o", tmp_path / "cli.pfm", "--aov", "depth,normal")
    expected = strahl.read(tmp_path / "cli.pfm")
    image, aovs = strahl.render(strahl.load(scene_file), aovs=["depth", "normal"], threads=2, **flags)
    assert_bits_equal(np.asarray(image), np.asarray(expected))
    # The CLI writes its AOVs as EXR (float32); depth is one channel in Python.
    normal = strahl.read(tmp_path / "cli.normal.exr")
    depth = strahl.read(tmp_path / "cli.depth.exr")
    assert_bits_equal(np.asarray(aovs["normal"]), np.asarray(normal))
    assert aovs["depth"].shape == (48, 64)
    assert_bits_equal(np.asarray(aovs["depth"]), np.asarray(depth)[:, :, 0])
    # Something is hit and something is not: depth is finite and infinite somewhere.
    assert np.isfinite(aovs["depth"]).any() and np.isinf(aovs["depth"]).any()


def test_path_integrator_equals_cli_and_is_a_scene_setting(cli, tmp_path, source_dir):
    scene_file = f"{source_dir}/scenes/lecture-whitted.yaml"
    size = dict(width=48, height=36, spp=4)
    cli(scene_file, "--integrator", "path", "--width", 48, "--height", 36, "--spp", 4, "-q", "-o", tmp_path / "cli.pfm")
    expected = strahl.read(tmp_path / "cli.pfm")
    scene = strahl.load(scene_file)
    path = strahl.render(scene, integrator="path", **size)
    assert_bits_equal(np.asarray(path), np.asarray(expected))
    assert scene.settings.integrator == "whitted"  # the override is for one render
    whitted = strahl.render(scene, **size)
    assert not np.array_equal(np.asarray(whitted), np.asarray(path))
    scene.settings.integrator = "path"
    assert_bits_equal(np.asarray(strahl.render(scene, **size)), np.asarray(expected))
    with pytest.raises(strahl.Error, match="unknown integrator 'radiosity'"):
        scene.settings.integrator = "radiosity"
    with pytest.raises(strahl.Error, match="unknown integrator"):
        strahl.render(scene, integrator="photons", **size)


def test_overrides_do_not_change_the_scene():
    scene = slide_scene()
    before = (scene.settings.width, scene.settings.height, scene.settings.spp, scene.settings.sampler)
    strahl.render(scene, width=8, height=4, spp=2, sampler="random")
    assert (scene.settings.width, scene.settings.height, scene.settings.spp, scene.settings.sampler) == before
    with pytest.raises(strahl.Error):
        strahl.render(scene, width=0)
    assert scene.settings.width == before[0]


def test_write_uses_the_cli_writers(cli, tmp_path):
    cli("--width", 40, "--height", 30, "-q", "-o", tmp_path / "cli.png")
    image = strahl.render(strahl.lecture_scene(), width=40, height=30)
    strahl.write(image, tmp_path / "py.png")
    assert (tmp_path / "py.png").read_bytes() == (tmp_path / "cli.png").read_bytes()
    assert image._repr_png_() == (tmp_path / "cli.png").read_bytes()
    strahl.write(image, str(tmp_path / "py.exr"))
    assert_bits_equal(np.asarray(strahl.read(tmp_path / "py.exr")), np.asarray(image))


def test_progress_reaches_the_total():
    calls = []
    strahl.render(strahl.lecture_scene(), width=64, height=36, spp=4, progress=lambda d, t: calls.append((d, t)))
    assert calls, "progress was never called"
    assert calls[-1][0] == calls[-1][1] == 64 * 36 * 4
    assert all(a[0] <= b[0] for a, b in zip(calls, calls[1:]))


def test_time_limit_stops_with_an_image():
    image = strahl.render(strahl.lecture_scene(), width=64, height=36, spp=1 << 20, time_limit=0.3)
    assert image.shape == (36, 64, 3) and np.isfinite(image).all() and image.max() > 0


def gpu_usable():
    try:
        strahl.render(strahl.lecture_scene(), width=8, height=6, device="cuda")
        return True
    except strahl.Error:
        return False


def test_device_without_a_gpu():
    """device= where no GPU is usable: 'cuda' raises with the reason, 'auto' warns and renders on
    the CPU the same image as 'cpu'; a misspelt device and Embree with 'cuda' are errors; the kd-tree
    asks for the GPU as the BVH does."""
    if gpu_usable():
        pytest.skip("a GPU is usable here")
    scene = strahl.lecture_scene()
    with pytest.raises(strahl.Error, match=r"^device='cuda': ") as bvh:
        strahl.render(scene, width=16, height=9, device="cuda")
    with pytest.raises(strahl.Error) as kdtree:
        strahl.render(scene, width=16, height=9, device="cuda", accel="kdtree")
    assert str(kdtree.value) == str(bvh.value)
    with pytest.warns(RuntimeWarning, match=r"^device='auto': .*; rendering on the CPU$"):
        auto = strahl.render(scene, width=16, height=9, device="auto")
    assert_bits_equal(auto, strahl.render(scene, width=16, height=9, device="cpu"))
    with pytest.raises(strahl.Error, match="unknown device 'gpu'"):
        strahl.render(scene, width=16, height=9, device="gpu")
    try:
        strahl.render(scene, width=4, height=3, accel="embree")
    except strahl.Error:
        return  # built without Embree
    with pytest.raises(strahl.Error, match="device='cuda' renders with accel 'bvh', 'kdtree', 'octree' or 'naive', not 'embree'"):
        strahl.render(scene, width=16, height=9, device="cuda", accel="embree")


def test_explain_is_the_clis_and_the_rendered_pixel(cli, source_dir):
    scene_file = f"{source_dir}/scenes/lecture-whitted.yaml"
    scene = strahl.load(scene_file)
    text = strahl.explain(scene, 22, 22, width=64, height=36)
    assert text == cli(scene_file, "--width", 64, "--height", 36, "--explain", "22,22").stdout
    assert "ray 1.T: refracted ray, depth 2" in text
    # The last line's radiance (printed to 6 digits) is the rendered pixel's, row 22 from the top.
    radiance = [float(v) for v in text.splitlines()[-1].split("(")[1].split(")")[0].split(",")]
    pixel = strahl.render(scene, width=64, height=36)[22, 22]
    assert np.allclose(pixel, radiance, rtol=1e-5, atol=1e-7)
    assert "sample 3 of its random sequence" in strahl.explain(scene, 0, 0, 3, width=8, height=8, spp=4, sampler="random")
    with pytest.raises(strahl.Error, match="sample 4 of a pixel of 4 samples"):
        strahl.explain(scene, 0, 0, 4, width=8, height=8, spp=4)
    with pytest.raises(strahl.Error, match="outside the image of 8×8 pixels"):
        strahl.explain(scene, 8, 0, width=8, height=8)
    assert scene.settings.width != 8  # the overrides were for that call only
