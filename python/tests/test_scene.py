"""Scene files: load, validate, build, change and write back."""

import json

import numpy as np
import pytest

import tandem


def test_load_and_build_rope_wheel(scenes_dir):
    scene = tandem.load_scene(str(scenes_dir / "rope_wheel.json"))
    assert scene.name == "rope_wheel" and scene.time_step == 0.02 and scene.duration == 10
    assert [b.desc.name for b in scene.rigid_bodies] == ["floor", "wheel", "flange front", "flange back", "light",
                                                       "heavy"]
    assert len(scene.joints) == 3 and scene.joints[0].kind == tandem.SceneJoint.Kind.HINGE
    rope = scene.deformables[0]
    assert rope.mesh.kind == tandem.SceneMesh.Kind.OBJ and rope.mass == 0.2 and rope.density is None
    assert rope.desc.collision.friction == 0.9 and len(scene.anchors) == 4
    world = scene.build()
    assert world.rigid_body_count == 6 and world.deformable_count == 1
    heavy, light = world.find_rigid_body("heavy"), world.find_rigid_body("light")
    world.step(scene.time_step, steps=10)  # the strip settles onto the wheel
    heavy_start, light_start = world.rigid_position(heavy)[1], world.rigid_position(light)[1]
    world.step(scene.time_step, steps=25)
    # The heavier body goes down, the lighter one up, by the same amount within 5 % (the rope
    # does not stretch; 3 % measured).
    down = heavy_start - world.rigid_position(heavy)[1]
    assert down > 0.1
    assert world.rigid_position(light)[1] - light_start == pytest.approx(down, rel=0.05)


def test_changes_in_place_reach_the_json_and_the_world(scenes_dir):
    scene = tandem.load_scene(str(scenes_dir / "rope_wheel.json"))
    scene.deformables[0].desc.collision.friction = 0.3
    scene.settings.solver.iterations = 2
    scene.rigid_bodies[5].desc.mass = 2.0
    text = scene.to_json()
    data = json.loads(text)
    assert data["deformables"][0]["friction"] == 0.3
    assert data["solver"]["iterations"] == 2
    again = tandem.parse_scene(text, "changed.json", str(scenes_dir))
    assert again.deformables[0].desc.collision.friction == 0.3
    world = tandem.World()
    tandem.build_scene(again, world)
    assert world.settings.solver.iterations == 2
    assert world.rigid_mass(world.find_rigid_body("heavy")) == 2.0


def test_every_shipped_scene_validates(scenes_dir):
    files = sorted(scenes_dir.glob("*.json")) + sorted((scenes_dir / "gauntlet").glob("*.json"))
    assert len(files) >= 8
    for path in files:
        assert tandem.validate_scene(str(path)) is None


def test_bad_scenes_name_the_file_the_path_and_the_problem(tmp_path):
    with pytest.raises(tandem.Error, match=r"bad\.json: /rigid_bodies/0/mass"):
        tandem.parse_scene('{"format": 1, "rigid_bodies": [{"name": "b", "shape": {"type": "sphere", "radius": 1},'
                           ' "mass": -1}]}', "bad.json")
    with pytest.raises(tandem.Error, match="format"):
        tandem.parse_scene('{"format": 99}', "future.json")
    missing = tmp_path / "missing_mesh.json"
    missing.write_text(json.dumps({"format": 1, "deformables": [
        {"name": "d", "mesh": {"type": "obj", "file": "nowhere.obj"}, "mass": 1}]}))
    scene = tandem.load_scene(str(missing))  # reads fine: the mesh is loaded when built
    with pytest.raises(tandem.Error, match="nowhere.obj"):
        scene.build()
    with pytest.raises(tandem.Error, match="nowhere.obj"):
        tandem.validate_scene(str(missing))
    with pytest.raises(tandem.Error, match="no_such_file.json"):
        tandem.load_scene(str(tmp_path / "no_such_file.json"))


def test_builtin_scenes():
    names = tandem.builtin_scene_names()
    assert "hanging_rope" in names and "curtain" in names
    world = tandem.World()
    h = tandem.build_builtin_scene("hanging_rope", world)
    assert h > 0 and world.find_deformable("rope") is not None
    with pytest.raises(tandem.Error, match="no built-in scene named 'nope'"):
        tandem.build_builtin_scene("nope", tandem.World())
