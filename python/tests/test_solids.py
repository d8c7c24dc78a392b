# The solids and CSG from Python: each made with its arguments compiles to exactly the scene that
# the same object written in a scene file compiles to (every argument reaches its field), values
# are checked when a solid is made (the scene files' messages, naming the Python line), Scene.add
# and the CSG operations take copies, and a scene of solids renders.
import numpy as np
import pytest

strahl = pytest.importorskip("strahl")

RED = dict(color=(0.9, 0.2, 0.1))
TURN = strahl.Motion.keyframes(strahl.Transform(translate=(0, 1, 0)),
                               strahl.Transform(rotate=(0, 0, 30), scale=1.2, translate=(0.5, 1, 0)))

# (object made in Python, the same object in a scene file)
CASES = [
    (lambda: strahl.Box((0, 0, 0), (1, 2, 3), **RED, rotate=(0, 30, 0)),
     "{type: box, corners: [[0, 0, 0], [1, 2, 3]], material: {color: [0.9, 0.2, 0.1]}, rotate: [0, 30, 0]}"),
    (lambda: strahl.Cylinder((0, 0, 0), (0, 1, 0), 0.5, open=True, translate=(1, 0, 0)),
     "{type: cylinder, base: [0, 0, 0], cap: [0, 1, 0], radius: 0.5, open: true, translate: [1, 0, 0]}"),
    (lambda: strahl.Cone((0, 0, 0), 0.5, (0, 1, 0), 0.1, motion=strahl.Motion.linear((1, 0, 0))),
     "{type: cone, base: [0, 0, 0], base_radius: 0.5, cap: [0, 1, 0], cap_radius: 0.1, motion: {velocity: [1, 0, 0]}}"),
    (lambda: strahl.Disk((0, 1, 0), (0, 0, 1), 2, scale=(1, 0.5, 1)),
     "{type: disk, center: [0, 1, 0], normal: [0, 0, 1], radius: 2, scale: [1, 0.5, 1]}"),
    (lambda: strahl.Torus((0, 0, 0), 1, 0.25, axis=(0, 0, 1), motion=TURN),
     "{type: torus, center: [0, 0, 0], axis: [0, 0, 1], major_radius: 1, minor_radius: 0.25, "
     "motion: {from: {translate: [0, 1, 0]}, to: {rotate: [0, 0, 30], scale: 1.2, translate: [0.5, 1, 0]}}}"),
    (lambda: strahl.Quadric([1, 1, 0, 0, 0, 0, 0, 0, 0, -1], clipped_by=((-1, -1, -1), (1, 1, 1))),
     "{type: quadric, coefficients: [1, 1, 0, 0, 0, 0, 0, 0, 0, -1], "
     "clipped_by: {type: box, corners: [[-1, -1, -1], [1, 1, 1]]}}"),
    (lambda: strahl.Implicit("x^2 + y^2 + z^2 - r^2", contained_by_sphere=((0, 0, 0), 2), parameters={"r": 1.5},
                             max_gradient=4, accuracy=1e-4, method="distance"),
     "{type: implicit, expression: 'x^2 + y^2 + z^2 - r^2', contained_by: {type: sphere, center: [0, 0, 0], "
     "radius: 2}, parameters: {r: 1.5}, max_gradient: 4, accuracy: 0.0001, method: distance}"),
    (lambda: strahl.Implicit("x^4 + y^4 + z^4 - 1", contained_by=((-2, -2, -2), (2, 2, 2)), method="march",
                             step=0.01),
     "{type: implicit, expression: 'x^4 + y^4 + z^4 - 1', contained_by: {type: box, corners: [[-2, -2, -2], "
     "[2, 2, 2]]}, method: march, step: 0.01}"),
    (lambda: strahl.Sphere((0, 0, 0), 1, scale=(1, 2, 1), motion=strahl.Motion.linear((0, -1, 0))),
     "{type: sphere, center: [0, 0, 0], radius: 1, scale: [1, 2, 1], motion: {velocity: [0, -1, 0]}}"),
    (lambda: strahl.Difference([strahl.Intersection([strahl.Box((-1, -1, -1), (1, 1, 1)),
                                                     strahl.Sphere((0, 0, 0), 1.3)], rotate=(0, 45, 0)),
                                strahl.Cylinder((-2, 0, 0), (2, 0, 0), 0.5)],
                               **RED, motion=strahl.Motion.linear((0, 0, 1))),
     "{type: difference, material: {color: [0.9, 0.2, 0.1]}, motion: {velocity: [0, 0, 1]}, objects: ["
     "{type: intersection, rotate: [0, 45, 0], objects: [{type: box, corners: [[-1, -1, -1], [1, 1, 1]]}, "
     "{type: sphere, center: [0, 0, 0], radius: 1.3}]}, "
     "{type: cylinder, base: [-2, 0, 0], cap: [2, 0, 0], radius: 0.5}]}"),
    (lambda: strahl.Box((0, 0, 0), (1, 1, 1), motion=strahl.Motion.spinning(strahl.Spin((0, 1, 0), 720, (0.5, 0, 0.5)))),
     "{type: box, corners: [[0, 0, 0], [1, 1, 1]], motion: {spin: {axis: [0, 1, 0], angle: 720, center: [0.5, 0, 0.5]}}}"),
    (lambda: strahl.Torus((0, 0, 0), 1, 0.25, motion=strahl.Motion.linear((1, 0, 0), spin=strahl.Spin((0, 0, 1), -400))),
     "{type: torus, center: [0, 0, 0], major_radius: 1, minor_radius: 0.25, "
     "motion: {velocity: [1, 0, 0], spin: {axis: [0, 0, 1], angle: -400}}}"),
    (lambda: strahl.Merge([strahl.Sphere((0, 0, 0), 1), strahl.Sphere((1, 0, 0), 1)]),
     "{type: merge, objects: [{type: sphere, center: [0, 0, 0], radius: 1}, {type: sphere, center: [1, 0, 0], "
     "radius: 1}]}"),
    (lambda: strahl.Union([strahl.Box((0, 0, 0), (1, 1, 1)), strahl.Inverse(strahl.Sphere((0, 0, 0), 0.5))]),
     "{type: union, objects: [{type: box, corners: [[0, 0, 0], [1, 1, 1]]}, {type: inverse, objects: "
     "[{type: sphere, center: [0, 0, 0], radius: 0.5}]}]}"),
    (lambda: strahl.Csg("intersection", [strahl.Box((0, 0, 0), (1, 1, 1)), strahl.Sphere((0, 0, 0), 1)]),
     "{type: intersection, objects: [{type: box, corners: [[0, 0, 0], [1, 1, 1]]}, {type: sphere, "
     "center: [0, 0, 0], radius: 1}]}"),
]


def scene_of(*objects):
    scene = strahl.Scene()
    scene.camera.shutter = (0, 1)
    for o in objects:
        scene.add(o)
    return scene


@pytest.mark.parametrize("make,yaml", CASES)
def test_each_solid_compiles_as_in_a_scene_file(make, yaml):
    built = scene_of(make())
    loaded = strahl.loads("camera: {shutter: [0, 1]}\nobjects:\n  - " + yaml + "\n")
    assert strahl._scene_hash(built) == strahl._scene_hash(loaded)


def test_the_cases_are_different_scenes():
    assert len({strahl._scene_hash(scene_of(make())) for make, _ in CASES}) == len(CASES)


def test_values_are_checked_when_made():
    with pytest.raises(strahl.Error, match=r"test_solids.py:\d+: torus minor radius \(1\) must be smaller than its "
                                           r"major radius \(0.5\)"):
        strahl.Torus((0, 0, 0), 0.5, 1)
    with pytest.raises(strahl.Error, match="box is flat"):
        strahl.Box((0, 0, 0), (1, 0, 1))
    with pytest.raises(strahl.Error, match="cannot move on its own"):
        strahl.Union([strahl.Box((0, 0, 0), (1, 1, 1), motion=strahl.Motion.linear((1, 0, 0)))])
    with pytest.raises(strahl.Error, match="a solid without bounds cannot move"):
        strahl.Quadric([1, 1, 0, 0, 0, 0, 0, 0, 0, -1], motion=strahl.Motion.linear((1, 0, 0)))
    with pytest.raises(strahl.Error, match="implicit expression"):
        strahl.Implicit("x^2 +", contained_by=((-1, -1, -1), (1, 1, 1)))
    with pytest.raises(TypeError, match="one bound"):
        strahl.Implicit("x^2 + y^2 + z^2 - 1")
    with pytest.raises(strahl.Error, match="unknown CSG operation"):
        strahl.Csg("xor", [strahl.Box((0, 0, 0), (1, 1, 1))])
    with pytest.raises(strahl.Error, match="has no inside"):
        strahl.Union([strahl.Cylinder((0, 0, 0), (0, 1, 0), 1, open=True)])


def test_add_and_operations_take_copies():
    box = strahl.Box((0, 0, 0), (1, 1, 1))
    tree = strahl.Difference([box, strahl.Sphere((1, 1, 1), 0.5)])
    scene = scene_of(tree)
    before = strahl._scene_hash(scene)
    box.corner_b = (2, 2, 2)          # the tree holds its own copy
    tree.objects[1].radius = 0.7      # the scene holds its own copy of the tree
    assert strahl._scene_hash(scene) == before
    assert tree.operation == "difference" and tree.objects[1].radius == 0.7
    scene.objects[0].objects[1].radius = 0.7  # the scene's own tree: changes the scene
    assert strahl._scene_hash(scene) != before
    assert strahl._scene_hash(scene) == strahl._scene_hash(scene_of(tree))


def test_loaded_solids_show_as_their_classes_and_copy_into_other_scenes(source_dir):
    loaded = strahl.load(f"{source_dir}/scenes/motion-solids.yaml")
    kinds = [type(o).__name__ for o in loaded.objects]
    assert kinds == ["Plane", "Box", "Torus", "Csg", "Sphere", "Cone", "Implicit", "Cone"]
    copy = strahl.Scene()
    copy.camera = loaded.camera
    copy.settings = loaded.settings
    for o in loaded.objects:
        copy.add(o)
    for light in loaded.lights:
        copy.add(light)
    assert strahl._scene_hash(copy) == strahl._scene_hash(loaded)


def test_solids_render():
    scene = scene_of(strahl.Box((-0.3, 0, -0.3), (0.3, 0.6, 0.3), color=(1, 0, 0)),
                     strahl.Plane((0, 1, 0), 0, color=0.5))
    scene.add_light((1, 2, 1))
    image = strahl.render(scene, width=32, height=24)
    red = image[:, :, 0] - image[:, :, 1]
    assert red.max() > 0.3 and np.count_nonzero(red > 0.3) > 20


def test_groups_and_moving_instances_compile_as_in_a_scene_file():
    built = strahl.Scene()
    built.camera.shutter = (0, 1)
    built.add_group("pair", [strahl.Box((0, 0, 0), (1, 1, 1)), strahl.Sphere((2, 0, 0), 0.5, color=(1, 0, 0))])
    built.add_instance("pair", translate=(0, 0, -3))
    built.add_instance("pair", scale=0.5, rotate=(0, 45, 0), motion=strahl.Motion.linear((1, 0, 0)))
    loaded = strahl.loads("""
camera: {shutter: [0, 1]}
groups:
  pair:
    - {type: box, corners: [[0, 0, 0], [1, 1, 1]]}
    - {type: sphere, center: [2, 0, 0], radius: 0.5, material: {color: [1, 0, 0]}}
objects:
  - {type: instance, of: pair, translate: [0, 0, -3]}
  - {type: instance, of: pair, scale: 0.5, rotate: [0, 45, 0], motion: {velocity: [1, 0, 0]}}
""")
    assert built.groups == ["pair"]
    assert [type(o).__name__ for o in built.objects] == ["Instance", "Instance"]
    assert strahl._scene_hash(built) == strahl._scene_hash(loaded)
    with pytest.raises(strahl.Error, match="unknown group 'trio'"):
        built.add_instance("trio")
    with pytest.raises(strahl.Error, match="defined twice"):
        built.add_group("pair", [strahl.Box((0, 0, 0), (1, 1, 1))])
    with pytest.raises(TypeError):
        strahl.Scene().add(built.objects[0])  # an instance belongs to its scene's groups


def test_nested_instances_compile_as_in_a_scene_file():
    built = strahl.Scene()
    built.add_group("pair", [strahl.Box((0, 0, 0), (1, 1, 1)), strahl.Sphere((2, 0, 0), 0.5, color=(1, 0, 0))])
    built.add_group("row")
    built.add_instance("pair", translate=(0, 0, -3), into="row")
    built.add_instance("pair", rotate=(0, 45, 0), scale=0.5, into="row")
    built.add_instance("row", translate=(1, 0, 0))
    loaded = strahl.loads("""
groups:
  pair:
    - {type: box, corners: [[0, 0, 0], [1, 1, 1]]}
    - {type: sphere, center: [2, 0, 0], radius: 0.5, material: {color: [1, 0, 0]}}
  row:
    - {type: instance, of: pair, translate: [0, 0, -3]}
    - {type: instance, of: pair, scale: 0.5, rotate: [0, 45, 0]}
objects:
  - {type: instance, of: row, translate: [1, 0, 0]}
""")
    assert built.groups == ["pair", "row"] and len(built.objects) == 1
    assert strahl._scene_hash(built) == strahl._scene_hash(loaded)
    # A group's own objects, read back as the file gave them; editing them edits the group.
    assert [type(o).__name__ for o in loaded.group("pair")] == ["Box", "Sphere"]
    row = loaded.group("row")
    assert [(o.group, repr(o)) for o in row] == [(0, "<strahl.Instance of group 0>")] * 2
    assert row[1].placement.scale == (0.5, 0.5, 0.5) and row[1].location == "<string>:8:7"
    loaded.group("pair")[1].radius = 0.25
    built.group("pair")[1].radius = 0.25
    assert strahl._scene_hash(built) == strahl._scene_hash(loaded)
    loaded.group("pair")[1].radius = 0.3
    assert strahl._scene_hash(built) != strahl._scene_hash(loaded)
    with pytest.raises(strahl.Error, match="unknown group 'trio'"):
        loaded.group("trio")
    with pytest.raises(strahl.Error, match="group 'pair' can place only the groups added before it"):
        built.add_instance("row", into="pair")
    built.add_instance("pair", into="row", motion=strahl.Motion.spinning(strahl.Spin((0, 0, 1), 45)))  # moving inside a group
    built.add_instance("row", translate=(0, 1, 0), motion=strahl.Motion.spinning(strahl.Spin((0, 1, 0), 90)))
    assert strahl.render(built, width=4, height=4).shape == (4, 4, 3)  # two motions that turn compose
    built.add_group("field")
    built.add_instance("row", into="field", motion=strahl.Motion.spinning(strahl.Spin((1, 0, 0), 30)))
    built.add_instance("field", motion=strahl.Motion.spinning(strahl.Spin((0, 1, 0), 20)))  # a third that turns
    with pytest.raises(strahl.Error, match="and so does the object at .* in group 'row', inside a placement that moves too"):
        strahl.render(built, width=4, height=4)
    with pytest.raises(strahl.Error, match="unknown group 'trio'"):
        built.add_instance("pair", into="trio")
    empty = strahl.Scene()
    empty.add_group("nothing")
    empty.add_instance("nothing")
    with pytest.raises(strahl.Error, match="group 'nothing' has no objects"):
        strahl.render(empty, width=4, height=4)


def test_moving_shapes_of_a_group_compile_as_in_a_scene_file():
    built = strahl.Scene()
    built.camera.shutter = (0, 1)
    spin = strahl.Motion.spinning(strahl.Spin((0, 1, 0), 720, center=(0.5, 0, 0.5)))
    built.add_group("rotor", [strahl.Box((0, 0, 0), (1, 0.1, 1), motion=spin), strahl.Sphere((2, 0, 0), 0.5)])
    built.add_instance("rotor", translate=(0, 1, 0))
    loaded = strahl.loads("""
camera: {shutter: [0, 1]}
groups:
  rotor:
    - {type: box, corners: [[0, 0, 0], [1, 0.1, 1]], motion: {spin: {axis: [0, 1, 0], angle: 720, center: [0.5, 0, 0.5]}}}
    - {type: sphere, center: [2, 0, 0], radius: 0.5}
objects:
  - {type: instance, of: rotor, translate: [0, 1, 0]}
""")
    assert strahl._scene_hash(built) == strahl._scene_hash(loaded)
    built.add_light((1, 3, 2))
    built.camera = strahl.Camera(position=(0, 3, 6), look_at=(1, 1, 0))
    built.camera.shutter = (0, 1)
    image = strahl.render(built, width=16, height=12, spp=4)
    assert image.max() > 0.1


def test_a_motion_shows_its_spin():
    spin = strahl.Spin((0, 1, 0), 1080, center=(1, 0, 0))
    assert (spin.axis, spin.angle, spin.center) == ((0, 1, 0), 1080, (1, 0, 0))
    assert repr(spin) == "strahl.Spin((0, 1, 0), 1080, center=(1, 0, 0))"
    moving = strahl.Motion.keyframes(strahl.Transform(), strahl.Transform(translate=(0, 1, 0)), spin=spin)
    assert moving.kind == "keyframes" and moving.spin.angle == 1080 and moving.to.translate == (0, 1, 0)
    assert strahl.Motion.linear((1, 0, 0)).spin is None
    assert strahl.Motion.spinning(spin).kind == "none" and strahl.Motion.spinning(spin).spin.center == (1, 0, 0)
