"""A cloth on a sphere (contacts), grabs and ray casts."""

import numpy as np
import pytest

import tandem
from conftest import G

RADIUS, CENTRE, THICKNESS = 0.4, np.array([0.0, 0.9, 0.0]), 0.008


def cloth_on_sphere(columns=15):
    world = tandem.World()
    sphere = world.add_rigid_body(tandem.RigidBodyDesc(
        name="sphere", shape=tandem.RigidShape.sphere(RADIUS), motion=tandem.MotionType.STATIC, position=CENTRE))
    cloth = world.add_deformable(tandem.DeformableDesc(
        name="cloth", mesh=tandem.make_cloth_grid((-0.5, 1.4, -0.5), (1, 0, 0), (0, 0, 1), columns, columns, 0.2),
        inextensibility=tandem.InextensibilitySettings(enabled=True),
        collision=tandem.CollisionSettings(thickness=THICKNESS, friction=0.5), damping=1.0))
    return world, sphere, cloth


def test_cloth_on_a_sphere_never_penetrates_and_its_contacts_carry_it(scenes_dir):
    # The paper's scene: a 51x51 cloth, 1.5 m square, 0.45 kg, onto a sphere of radius 0.4 m.
    scene = tandem.load_scene(str(scenes_dir / "cloth_sphere.json"))
    world = scene.build()
    sphere, cloth = world.find_rigid_body("sphere"), world.find_deformable("cloth")
    assert world.rigid_shape(sphere).radius == RADIUS and scene.deformables[0].desc.collision.thickness == THICKNESS
    np.testing.assert_array_equal(world.rigid_position(sphere), CENTRE)
    mass = 1.0 / world.node_inverse_masses(cloth).copy()
    positions = world.node_positions(cloth)
    closest = np.inf
    for _ in range(75):  # 1.5 s at 1/50 s: falls 0.1 m, lands, drapes
        world.step(1.0 / 50)
        distance = np.linalg.norm(positions - CENTRE, axis=1).min()
        closest = min(closest, distance)
    # No node ever closer to the centre than the radius (thickness kept, less a 1 mm tolerance).
    assert closest >= RADIUS + THICKNESS - 1e-3
    assert closest < RADIUS + THICKNESS + 0.01  # it does rest on it
    contacts = world.contacts()
    assert len(contacts) > 10
    for contact in contacts:
        assert contact.deformable == cloth and contact.rigid == sphere and contact.other is None
        outward = (contact.point - CENTRE) / np.linalg.norm(contact.point - CENTRE)
        assert np.dot(contact.normal, outward) > 0.99
        assert contact.normal_impulse >= 0.0
        assert abs(np.dot(contact.friction_impulse, contact.normal)) < 1e-9
    as_dict = contacts[0].to_dict()
    assert as_dict["rigid"] == sphere.index and as_dict["other"] is None and len(as_dict["point"]) == 3
    # Draped and nearly still, the cloth's weight goes into the sphere: the vertical impulses of
    # its contacts add up to the weight per step (friction included), within 10 %.
    vertical = sum(c.normal_impulse * c.normal[1] + c.friction_impulse[1] for c in contacts)
    assert vertical / (1.0 / 50) == pytest.approx(mass.sum() * G, rel=0.1)
    assert world.last_report.row_counts["contact"] == len(contacts)


def test_ray_casts_hit_rigid_shapes_and_deformable_faces():
    world, sphere, cloth = cloth_on_sphere(columns=5)
    # Straight down onto the sphere, from beside the cloth: the top of the sphere.
    hit = world.cast_ray((0, 3, 0), (0, -1, 0))
    assert hit is not None and hit.deformable == cloth  # the cloth is above the sphere
    assert hit.distance == pytest.approx(3 - 1.4, abs=1e-9)
    assert sum(hit.weights) == pytest.approx(1.0)
    rest = world.rest_mesh(cloth).positions
    np.testing.assert_allclose(sum(w * rest[n] for w, n in zip(hit.weights, hit.nodes)), hit.point, atol=1e-9)
    hit = world.cast_ray((0, 0.9, 3), (0, 0, -1))
    assert hit.rigid == sphere and hit.deformable is None
    assert hit.distance == pytest.approx(3 - RADIUS, abs=1e-6)
    np.testing.assert_allclose(hit.normal, [0, 0, 1], atol=1e-6)
    assert world.cast_ray((0, 5, 0), (0, 1, 0)) is None
    assert world.cast_ray((0, 3, 0), (0, -1, 0), max_distance=1.0) is None
    with pytest.raises(ValueError, match="direction non-zero"):
        world.cast_ray((0, 3, 0), (0, 0, 0))


def test_a_grab_lifts_a_box_and_lets_go():
    world = tandem.World()
    box = world.add_rigid_body(tandem.RigidBodyDesc(
        name="box", shape=tandem.RigidShape.box((0.1, 0.1, 0.1)), mass=1.0, position=(0, 0, 0), can_sleep=False))
    grab = world.add_grab(tandem.GrabDesc(body=box, point=(0, 0.1, 0), target=(0, 0.6, 0), frequency=4.0))
    for _ in range(180):
        world.step(1.0 / 60)
    # Held still at the target against gravity: the spring carries the weight.
    np.testing.assert_allclose(world.grab_point(grab), [0, 0.6, 0], atol=0.02)
    assert world.grab_impulse(grab)[1] * 60 == pytest.approx(G, rel=0.05)
    world.set_grab_target(grab, (0.2, 0.6, 0))
    world.step(1.0 / 60, steps=120)
    assert world.grab_point(grab)[0] == pytest.approx(0.2, abs=0.02)
    world.remove_grab(grab)
    assert not world.contains(grab)
    with pytest.raises(tandem.IdError, match=r"^grab_impulse: grab 0 \(generation 0\) was removed$"):
        world.grab_impulse(grab)
    with pytest.raises(tandem.Error, match="grab"):
        world.set_grab_target(grab, (0, 0, 0))
    world.step(1.0 / 60, steps=10)
    assert world.rigid_linear_velocity(box)[1] < -1.0  # falling again


def test_a_grab_on_cloth_pulls_its_nodes():
    world, sphere, cloth = cloth_on_sphere(columns=5)
    grab = world.add_grab(tandem.GrabDesc(deformable=cloth, nodes=[0, -1, -1, -1], weights=[1, 0, 0, 0],
                                          node_count=1, target=(-0.5, 2.0, -0.5)))
    world.step(1.0 / 50, steps=100)
    corner = world.node_positions(cloth)[0]
    assert corner[1] > 1.7  # pulled up while the rest hangs from it
    np.testing.assert_allclose(world.grab_point(grab), corner, atol=1e-12)
