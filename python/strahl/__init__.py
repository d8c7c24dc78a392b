"""strahl, a Whitted-style ray tracer, from Python (docs/python.md).

    import strahl
    scene = strahl.Scene()
    scene.add(strahl.Plane((0, 1, 0), 0, color=(0.3, 0.3, 0.3)))
    scene.add(strahl.Sphere((0.05, 0.3, 0), 0.3, color=(0.8, 0.2, 0.2)))
    scene.add_light((1, 1.5, 1))
    image = strahl.render(scene, width=640, height=360)   # numpy float32, height × width × 3, linear
    strahl.write(image, "out.png")
"""

import os as _os
import tempfile as _tempfile

import numpy as _np

from ._strahl import (  # noqa: F401
    Box,
    Camera,
    Cone,
    Csg,
    Cylinder,
    Difference,
    DirectionalLight,
    Disk,
    DiskLight,
    Error,
    Implicit,
    Instance,
    Intersection,
    Inverse,
    Light,
    Material,
    Merge,
    Mesh,
    Motion,
    Plane,
    PointLight,
    Quadric,
    RectLight,
    RenderSettings,
    Scene,
    SceneObject,
    Sphere,
    SphereLight,
    Spin,
    SpotLight,
    Torus,
    Transform,
    Triangle,
    Union,
    __version__,
    lecture_scene,
    load,
    loads,

    version,
)
from . import _strahl
from ._strahl import _scene_hash  # noqa: F401  (tests: the fingerprint of the compiled scene)

__all__ = [
    "Box", "Camera", "Cone", "Csg", "Cylinder", "Difference", "DirectionalLight", "Disk", "DiskLight", "Error",
    "Image", "Implicit", "Instance", "Intersection", "Inverse", "Light", "Material", "Merge", "Mesh", "Motion",
    "Plane", "PointLight", "Quadric", "RectLight", "RenderSettings", "Scene", "SceneObject", "Sphere", "SphereLight",
    "Spin", "SpotLight", "Torus", "Transform", "Triangle", "Union", "explain", "lecture_scene", "load", "loads", "read", "render", "version",
    "write",
]


# The compiled classes show as strahl.Sphere, not strahl._strahl.Sphere.
for _name in ("Box", "Camera", "Cone", "Csg", "Disk", "Implicit", "Instance", "Light", "Material", "Mesh", "Motion",
              "Plane", "Quadric", "RenderSettings", "Scene", "SceneObject", "Sphere", "Spin", "Torus", "Transform",
              "Triangle"):
    getattr(_strahl, _name).__module__ = "strahl"


class Image(_np.ndarray):
    """A rendered image: a numpy float32 array, height × width × 3 (or height × width for the
    depth and id AOVs), linear RGB, row 0 at the top. It is an ordinary ndarray that also shows
    itself in Jupyter (_repr_png_: 8-bit sRGB, as strahl.write writes a .png)."""

    def _repr_png_(self):
        if self.ndim not in (2, 3) or (self.ndim == 3 and self.shape[2] != 3) or self.size == 0:
            return None
        with _tempfile.TemporaryDirectory(prefix="strahl-") as tmp:
            path = _os.path.join(tmp, "image.png")
            _strahl.write(_np.asarray(self), path)
            with open(path, "rb") as f:
                return f.read()


def _image(array):
    return array.view(Image)


def render(scene, *, width=None, height=None, spp=None, sampler=None, seed=None, filter=None,
           filter_radius=None, adaptive_min=None, adaptive_threshold=None, max_depth=None, supersample=None,
           accel=None, threads=0, tile_size=32, time_limit=0.0, progress=None, aovs=(), device="cpu",
           integrator=None):
    """Renders `scene` and returns a strahl.Image (a numpy float32 array, height × width × 3,
    linear RGB).

    The keyword arguments are the strahl CLI's flags and override the scene's settings for this
    render only: width, height, spp, sampler ('grid', 'stratified', 'random', 'sobol',
    'adaptive'), seed, filter ('box', 'tent', 'gaussian', 'mitchell'), filter_radius,
    adaptive_min, adaptive_threshold, max_depth, supersample, accel ('bvh', 'naive', 'kdtree',
    'octree', 'embree' where built), integrator ('whitted', 'path': path tracing, global
    illumination); threads (0: all cores), tile_size, time_limit (seconds;
    the image so far when it runs out). progress(done, total) is called from the calling thread
    about every 50 ms while samples are being taken. device: 'cpu', 'cuda' (an NVIDIA GPU;
    strahl.Error when none is usable) or 'auto' (the GPU when one is usable, else the CPU with a
    RuntimeWarning saying why) — the same image either way (docs/gpu.md).

    With aovs (a list of 'depth', 'normal', 'albedo', 'id') it returns (image, {name: array}):
    depth and id are height × width, normal and albedo height × width × 3.

    The GIL is released while rendering. Ctrl-C (KeyboardInterrupt) cancels the render within a
    fraction of a second and raises; so does an exception raised by progress.
    """
    if isinstance(aovs, str):
        aovs = [aovs]
    result = _strahl.render(
        scene, width=width, height=height, spp=spp, sampler=sampler, seed=seed, filter=filter,
        filter_radius=filter_radius, adaptive_min=adaptive_min, adaptive_threshold=adaptive_threshold,
        max_depth=max_depth, supersample=supersample, accel=accel, threads=threads, tile_size=tile_size,
        time_limit=time_limit, progress=progress, aovs=list(aovs), device=device, integrator=integrator)
    if isinstance(result, tuple):
        image, planes = result
        return _image(image), {name: _image(plane) for name, plane in planes.items()}
    return _image(result)


def explain(scene, x, y, sample=0, *, width=None, height=None, spp=None, sampler=None, seed=None, max_depth=None,
            supersample=None):
    """The ray tree of sample `sample` of pixel (x, y) — x from the left, y from the top — as text
    in the lecture's terms: the camera's formulas, every hit, light, shadow ray and spawned ray,
    and each ray's colour; its last line is the sample's radiance, which at one sample per pixel
    is the rendered pixel's (the CLI's --explain; docs/cli.md, "Explaining a pixel"). The keyword
    arguments override the scene's settings for this call, as in strahl.render."""
    return _strahl.explain(scene, x, y, sample, width=width, height=height, spp=spp, sampler=sampler, seed=seed,
                           max_depth=max_depth, supersample=supersample)


def write(image, path, *, linear=False):
    """Writes an image (height × width × 3, or height × width as grey; linear RGB) to `path`, the
    format by its extension as the strahl CLI: .png .jpg .ppm (8-bit sRGB, or the linear values
    with linear=True), .pfm .exr (float). An existing file is replaced only when the new one is
    complete. Errors raise strahl.Error with the CLI's message."""
    _strahl.write(_np.asarray(image), path, linear=linear)


def read(path):
    """Reads an image (.png .jpg .ppm .pfm .exr) as a strahl.Image, height × width × 3 float32;
    8- and 16-bit values are divided by 255 or 65535, not decoded from sRGB."""
    return _image(_strahl.read(path))
