"""Removing rigid bodies, deformables, joints, anchors, fixed points and grabs from Python: what
was removed is gone from the queries, its id (and the ids of what went with it) are refused with
tandem.IdError naming them, a new thing gets an id that differs, and what is left moves on as
physics says."""

import numpy as np
import pytest

import tandem
from conftest import G, hanging_rope_with_box

H = 1.0 / 60


def test_ids_carry_a_generation_and_compare_by_it():
    assert tandem.RigidBodyId(2).generation == 0
    assert tandem.RigidBodyId(2, 1) != tandem.RigidBodyId(2)
    assert tandem.RigidBodyId(2, generation=1) == tandem.RigidBodyId(2, 1)
    assert len({tandem.RigidBodyId(2), tandem.RigidBodyId(2, 1)}) == 2
    assert repr(tandem.JointId(3, 2)) == "JointId(3, generation=2)"
    assert issubclass(tandem.IdError, tandem.Error) and issubclass(tandem.IdError, IndexError)


def test_a_removed_body_is_gone_its_id_refused_and_a_new_body_gets_another_id():
    world = tandem.World()
    first = world.add_rigid_body(tandem.RigidBodyDesc(name="first", position=(0, 5, 0)))
    box = world.add_rigid_body(tandem.RigidBodyDesc(name="box", position=(1, 5, 0)))
    assert world.rigid_bodies() == [first, box] and world.rigid_body_count == 2
    world.remove_rigid_body(box)
    assert world.rigid_bodies() == [first] and world.rigid_body_count == 1
    assert not world.contains(box) and world.contains(first)
    assert world.find_rigid_body("box") is None
    with pytest.raises(tandem.IdError, match=r"^rigid_position: rigid body 1 \(generation 0\) was removed$"):
        world.rigid_position(box)
    with pytest.raises(tandem.IdError, match=r"^apply impulse: rigid body 1 \(generation 0\) was removed$"):
        world.apply_impulse(box, (1, 0, 0))
    with pytest.raises(tandem.IdError, match=r"^remove rigid body: rigid body 1 \(generation 0\) was removed$"):
        world.remove_rigid_body(box)
    # A new body takes the slot with the next generation: its id differs, the old one stays refused.
    crate = world.add_rigid_body(tandem.RigidBodyDesc(name="crate", position=(3, 0, 0), mass=2.0))
    assert crate != box and crate.index == box.index and crate.generation == box.generation + 1
    assert world.rigid_name(crate) == "crate" and world.rigid_mass(crate) == 2.0
    with pytest.raises(tandem.IdError, match=r"^set linear velocity: rigid body 1 \(generation 0\) was removed "
                                             r"\(its slot now holds generation 1\)$"):
        world.set_rigid_linear_velocity(box, (1, 0, 0))
    np.testing.assert_array_equal(world.rigid_linear_velocity(crate), [0, 0, 0])  # the stale call did not reach it
    with pytest.raises(tandem.IdError, match=r"^rigid_mass: rigid body 1: generation 7 was never made "
                                             r"\(the slot is at generation 1\)$"):
        world.rigid_mass(tandem.RigidBodyId(1, 7))
    with pytest.raises(IndexError, match=r"^rigid_name: rigid body 9: no such rigid body \(the world has 2 slots\)$"):
        world.rigid_name(tandem.RigidBodyId(9))


def test_removing_the_rope_lets_the_box_it_held_fall_freely():
    world = tandem.World()
    rope, box, top, knot = hanging_rope_with_box(world, nodes=11)
    world.step(H, steps=60)
    assert -world.anchor_state(knot).impulse[1] == pytest.approx(G * H, rel=0.05)  # it holds the box
    positions = world.node_positions(rope)
    world.remove_deformable(rope)
    assert world.deformable_ids() == [] and world.deformable_count == 0
    assert not world.contains(rope) and not world.contains(knot) and not world.contains(top)
    with pytest.raises(tandem.IdError, match=r"^node_positions: deformable 0 \(generation 0\) was removed$"):
        world.node_positions(rope)
    with pytest.raises(tandem.IdError, match=r"^anchor_state: anchor 0 \(generation 0\) was removed$"):
        world.anchor_state(knot)
    with pytest.raises(tandem.IdError, match=r"^remove fixed point: fixed point 0 \(generation 0\) was removed$"):
        world.remove_fixed_point(top)
    v0 = world.rigid_linear_velocity(box)[1]
    steps = 30
    world.step(H, steps=steps)
    # Free fall from the velocity it had: nothing holds it any more.
    assert world.rigid_linear_velocity(box)[1] == pytest.approx(v0 - G * H * steps, abs=1e-9)
    np.testing.assert_array_equal(world.deformable_impulse_on_rigid(box), [0, 0, 0])
    assert world.last_report.row_counts["anchor"] == 0
    # The view taken before the removal still reads the (now inert) nodes: no dangling memory.
    assert positions.shape == (11, 3) and np.all(np.isfinite(positions))
    del positions
    # A new deformable gets a new id and hangs its length below its fixed point.
    second = world.add_deformable(tandem.DeformableDesc(
        name="second", mesh=tandem.make_rope((2, 2, 0), (2, 1, 0), 5, 0.1),
        inextensibility=tandem.InextensibilitySettings(enabled=True)))
    assert second != rope and second.index == 1
    world.add_fixed_point(second, 0)
    world.step(H, steps=60)
    assert world.node_positions(second)[-1][1] == pytest.approx(1.0, abs=0.01)


def test_removing_an_anchor_or_a_fixed_point_lets_go_of_what_it_held():
    world = tandem.World()
    rope, box, top, knot = hanging_rope_with_box(world, nodes=11)
    world.step(H, steps=60)
    world.remove_anchor(knot)
    assert not world.contains(knot) and world.contains(box) and world.contains(rope)
    with pytest.raises(tandem.IdError, match=r"^remove anchor: anchor 0 \(generation 0\) was removed$"):
        world.remove_anchor(knot)
    v0 = world.rigid_linear_velocity(box)[1]
    world.step(H, steps=20)
    assert world.rigid_linear_velocity(box)[1] == pytest.approx(v0 - G * H * 20, abs=1e-9)
    # The rope still hangs from its top: the fixed point now carries only the rope's 0.2 kg.
    world.step(H, steps=180)
    assert world.fixed_point_impulse(top)[1] == pytest.approx(0.2 * G * H, rel=0.05)
    world.remove_fixed_point(top)
    with pytest.raises(tandem.IdError, match=r"^fixed_point_impulse: fixed point 0 \(generation 0\) was removed$"):
        world.fixed_point_impulse(top)
    with pytest.raises(tandem.IdError, match=r"fixed point 0 \(generation 0\) was removed$"):
        world.set_fixed_point_target(top, (0, 3, 0))
    before = np.array(world.node_velocities(rope))
    world.step(H, steps=10)
    # Nothing holds the rope: its momentum grows by m g t, all of it downwards.
    momentum = world.total_linear_momentum() - 1.0 * world.rigid_linear_velocity(box)
    masses = 1.0 / np.array(world.node_inverse_masses(rope))
    assert momentum[1] == pytest.approx(float(masses @ before[:, 1]) - 0.2 * G * H * 10, rel=1e-6)


def test_removing_a_body_takes_its_joints_and_removing_a_joint_lets_the_body_fall():
    world = tandem.World()
    bob = world.add_rigid_body(tandem.RigidBodyDesc(
        name="bob", shape=tandem.RigidShape.sphere(0.05), mass=1.0, position=(0.5, 1, 0), can_sleep=False))
    hinge = world.add_hinge(tandem.HingeDesc(body_a=bob, pivot=(0, 1, 0), axis=(0, 0, 1)))
    world.step(H, steps=10)
    world.remove_joint(hinge)
    assert not world.contains(hinge)
    with pytest.raises(tandem.IdError, match=r"^hinge_angle: joint 0 \(generation 0\) was removed$"):
        world.hinge_angle(hinge)
    with pytest.raises(tandem.IdError, match=r"^hinge limits: joint 0 \(generation 0\) was removed$"):
        world.set_hinge_limits(hinge, -0.1, 0.1)
    v0 = world.rigid_linear_velocity(bob)
    world.step(H, steps=30)
    np.testing.assert_allclose(world.rigid_linear_velocity(bob), v0 + [0, -G * H * 30, 0], atol=1e-9)
    assert world.last_report.bullet_joints == 0

    # A body's removal takes its joints and grabs with it.
    arm = world.add_rigid_body(tandem.RigidBodyDesc(name="arm", position=(0, 2, 0), can_sleep=False))
    joint = world.add_fixed_joint(tandem.FixedJointDesc(body_a=arm))
    grab = world.add_grab(tandem.GrabDesc(body=arm, point=(0, 2, 0), target=(0, 2.5, 0)))
    world.remove_rigid_body(arm)
    assert not world.contains(joint) and not world.contains(grab)
    with pytest.raises(tandem.IdError, match=r"^remove joint: joint 0 \(generation 1\) was removed$"):
        world.remove_joint(joint)
    with pytest.raises(tandem.IdError, match=r"^grab_point: grab 0 \(generation 0\) was removed$"):
        world.grab_point(grab)
    with pytest.raises(tandem.IdError, match=r"grab 0 \(generation 0\) was removed"):
        world.remove_grab(grab)
    world.step(H)
    assert world.last_report.bullet_joints == 0 and world.last_report.row_counts["grab"] == 0
