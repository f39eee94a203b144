"""Pushing, moving and reading rigid bodies from Python: impulses, forces and torques against their
analytic effect, velocities and poses, mass and inertia, Bullet's contact points, collision
filters, hinge limits and motors; and what each call refuses, with the library's message."""

import math

import numpy as np
import pytest

import tandem
from conftest import G

NAN = math.nan
INF = math.inf


def box_desc(name, half, mass, position, **fields):
    return tandem.RigidBodyDesc(name=name, shape=tandem.RigidShape.box(half), mass=mass, position=position,
                                can_sleep=False, **fields)


def ground_desc(**fields):
    return tandem.RigidBodyDesc(name="ground", shape=tandem.RigidShape.plane((0, 1, 0), 0),
                                motion=tandem.MotionType.STATIC, **fields)


def zero_gravity_world(substeps=1):
    return tandem.World(tandem.WorldSettings(gravity=(0, 0, 0), solver=tandem.SolverSettings(substeps=substeps)))


def box_inertia(mass, sides):
    """A box's principal moments: m (b^2 + c^2) / 12 with b, c the full side lengths."""
    a, b, c = sides
    return np.diag([mass * (b * b + c * c) / 12, mass * (a * a + c * c) / 12, mass * (a * a + b * b) / 12])


# ---- Impulses, forces, torques ------------------------------------------------------------------

def test_an_impulse_at_a_point_changes_velocity_by_j_over_m_and_spin_by_inverse_inertia_r_cross_j():
    world = zero_gravity_world()
    m, centre = 2.0, np.array([1.0, 2.0, 3.0])
    box = world.add_rigid_body(box_desc("box", (0.5, 0.25, 0.1), m, centre))
    assert world.rigid_mass(box) == m
    inertia = world.rigid_inertia(box)
    np.testing.assert_allclose(inertia, box_inertia(m, (1.0, 0.5, 0.2)), rtol=1e-12, atol=1e-15)
    J, r = np.array([0.5, 3.0, -1.0]), np.array([0.4, 0.1, -0.05])
    world.apply_impulse_at_point(box, J, centre + r)
    np.testing.assert_allclose(world.rigid_linear_velocity(box), J / m, rtol=0, atol=1e-12)
    np.testing.assert_allclose(world.rigid_angular_velocity(box), np.linalg.solve(inertia, np.cross(r, J)),
                               rtol=0, atol=1e-9)
    # At the centre: the velocity changes by J/m and the spin not at all.
    world.set_rigid_angular_velocity(box, (0, 0, 0))
    world.apply_impulse(box, J)
    np.testing.assert_allclose(world.rigid_linear_velocity(box), 2 * J / m, rtol=0, atol=1e-12)
    assert np.linalg.norm(world.rigid_angular_velocity(box)) < 1e-15
    # An angular impulse L: dw = I^-1 L.
    L = np.array([0.1, -0.2, 0.3])
    world.apply_angular_impulse(box, L)
    np.testing.assert_allclose(world.rigid_angular_velocity(box), np.linalg.solve(inertia, L), rtol=0, atol=1e-12)


@pytest.mark.parametrize("substeps", [1, 4])
def test_a_constant_force_over_n_steps_gives_the_analytic_velocity_and_position(substeps):
    world = zero_gravity_world(substeps)
    m, h, n = 3.0, 0.01, 25
    box = world.add_rigid_body(box_desc("box", (0.2, 0.2, 0.2), m, (0, 0, 0)))
    F = np.array([10.0, -4.0, 2.0])
    for _ in range(n):
        world.apply_force(box, F / 2)
        world.apply_force(box, F / 2)  # forces accumulate until the step
        world.step(h)
    a = F / m
    np.testing.assert_allclose(world.rigid_linear_velocity(box), a * n * h, rtol=1e-12)
    # Symplectic Euler over k = n * substeps substeps of h / substeps: x = a dt^2 k (k + 1) / 2.
    k, dt = n * substeps, h / substeps
    np.testing.assert_allclose(world.rigid_position(box), a * dt * dt * k * (k + 1) / 2, rtol=1e-9)
    world.step(h)  # the force was cleared with the step
    np.testing.assert_allclose(world.rigid_linear_velocity(box), a * n * h, rtol=1e-12)

    # A torque on a cube (isotropic inertia, so its turning does not matter): w = I^-1 tau n h.
    world.set_rigid_linear_velocity(box, (0, 0, 0))
    inertia = world.rigid_inertia(box)
    torque = np.array([0.0, 0.3, 0.5])
    for _ in range(n):
        world.apply_torque(box, torque)
        world.step(h)
    np.testing.assert_allclose(world.rigid_angular_velocity(box), np.linalg.solve(inertia, torque) * n * h,
                               rtol=1e-9, atol=1e-12)
    # A force at a point is the force and the torque r x F, for one step.
    world.set_rigid_angular_velocity(box, (0, 0, 0))
    r, F1 = np.array([0.0, 0.2, 0.0]), np.array([1.0, 0.0, 0.0])
    world.apply_force_at_point(box, F1, world.rigid_position(box) + r)
    world.step(h)
    np.testing.assert_allclose(world.rigid_linear_velocity(box), F1 * h / m, rtol=0, atol=1e-12)
    np.testing.assert_allclose(world.rigid_angular_velocity(box), np.linalg.solve(inertia, np.cross(r, F1)) * h,
                               rtol=0, atol=1e-12)


def test_pushing_refuses_static_bodies_and_non_finite_values():
    world = tandem.World()
    ground = world.add_rigid_body(ground_desc())
    box = world.add_rigid_body(box_desc("box", (0.2, 0.2, 0.2), 1.0, (0, 1, 0)))
    with pytest.raises(tandem.Error, match=r"^apply force: force is not finite$"):
        world.apply_force(box, (NAN, 0, 0))
    with pytest.raises(tandem.Error, match=r"^apply force: rigid body 'ground' is static or kinematic$"):
        world.apply_force(ground, (1, 0, 0))
    with pytest.raises(tandem.Error, match=r"^apply force at point: point is not finite$"):
        world.apply_force_at_point(box, (1, 0, 0), (0, INF, 0))
    with pytest.raises(tandem.Error, match=r"^apply torque: torque is not finite$"):
        world.apply_torque(box, (0, NAN, 0))
    with pytest.raises(tandem.Error, match=r"^apply impulse: impulse is not finite$"):
        world.apply_impulse(box, (0, 0, -INF))
    with pytest.raises(tandem.Error, match=r"^apply impulse at point: impulse is not finite$"):
        world.apply_impulse_at_point(box, (NAN, 0, 0), (0, 1, 0))
    with pytest.raises(tandem.Error, match=r"^apply angular impulse: angular impulse is not finite$"):
        world.apply_angular_impulse(box, (NAN, NAN, NAN))
    with pytest.raises(tandem.IdError, match=r"^apply torque: rigid body 7: no such rigid body \(the world has 2 slots\)$"):
        world.apply_torque(tandem.RigidBodyId(7), (1, 0, 0))
    with pytest.raises(TypeError):
        world.apply_force(box, (1, 0))  # not 3 numbers
    world.step(1 / 60)
    # Nothing was applied: the box fell freely for one step.
    np.testing.assert_allclose(world.rigid_linear_velocity(box), [0, -G / 60, 0], rtol=1e-12)
    np.testing.assert_allclose(world.rigid_angular_velocity(box), [0, 0, 0], atol=1e-15)


# ---- Velocities and poses -----------------------------------------------------------------------

def test_set_velocities_then_step_in_zero_gravity_moves_the_body_by_v_t():
    world = zero_gravity_world()
    start = np.array([0.5, 1.0, -2.0])
    cube = world.add_rigid_body(box_desc("cube", (0.1, 0.1, 0.1), 1.5, start))
    v, spin = np.array([0.5, 0.0, -1.0]), 2.0
    world.set_rigid_linear_velocity(cube, v)
    world.set_rigid_angular_velocity(cube, (0, 0, spin))
    h, n = 0.01, 50
    world.step(h, steps=n)
    t = n * h
    np.testing.assert_allclose(world.rigid_position(cube), start + v * t, rtol=0, atol=1e-12)
    np.testing.assert_allclose(world.rigid_linear_velocity(cube), v, rtol=0, atol=1e-15)
    # A cube spins at a constant rate about z: (w, x, y, z) = (cos(a/2), 0, 0, sin(a/2)), a = w t.
    angle = spin * t
    np.testing.assert_allclose(world.rigid_orientation(cube), [math.cos(angle / 2), 0, 0, math.sin(angle / 2)],
                               atol=1e-9)
    static = world.add_rigid_body(ground_desc())
    with pytest.raises(tandem.Error, match=r"^set linear velocity: rigid body 'ground' is static or kinematic$"):
        world.set_rigid_linear_velocity(static, (1, 0, 0))
    with pytest.raises(tandem.Error, match=r"^set linear velocity: velocity is not finite$"):
        world.set_rigid_linear_velocity(cube, (NAN, 0, 0))
    with pytest.raises(tandem.Error, match=r"^set angular velocity: angular velocity is not finite$"):
        world.set_rigid_angular_velocity(cube, (0, INF, 0))
    np.testing.assert_allclose(world.rigid_linear_velocity(cube), v, rtol=0, atol=1e-15)  # unchanged


def test_set_pose_moves_and_wakes_a_sleeping_body():
    world = tandem.World()
    box = world.add_rigid_body(tandem.RigidBodyDesc(
        name="box", shape=tandem.RigidShape.box((0.2, 0.3, 0.4)), mass=1.0, position=(0, 5, 0), can_sleep=True))
    world.put_rigid_to_sleep(box)
    assert not world.rigid_is_awake(box)
    h = 0.01
    world.step(h, steps=10)
    np.testing.assert_array_equal(world.rigid_position(box), [0, 5, 0])  # asleep: gravity does not move it
    angle = 0.7
    axis = np.array([1.0, 2.0, 3.0]) / np.linalg.norm([1.0, 2.0, 3.0])
    q = np.concatenate([[math.cos(angle / 2)], math.sin(angle / 2) * axis])
    position = np.array([1.5, 3.0, 0.25])
    world.set_rigid_pose(box, position, q)
    assert world.rigid_is_awake(box)
    np.testing.assert_allclose(world.rigid_position(box), position, rtol=0, atol=1e-12)
    np.testing.assert_allclose(world.rigid_orientation(box), q, rtol=0, atol=1e-12)
    # Awake, it falls from there: y = y0 - g h^2 n (n + 1) / 2 after n steps.
    n = 20
    world.step(h, steps=n)
    np.testing.assert_allclose(world.rigid_position(box), position - [0, G * h * h * n * (n + 1) / 2, 0],
                               rtol=0, atol=1e-12)
    # The 4x4 form, as rigid_pose gives it, round-trips.
    pose = world.rigid_pose(box)
    pose[:3, 3] = (0, 4, 0)
    world.set_rigid_pose(box, pose)
    np.testing.assert_allclose(world.rigid_pose(box), pose, rtol=0, atol=1e-12)
    # A kinematic body's target becomes its new pose: it stays there.
    paddle = world.add_rigid_body(tandem.RigidBodyDesc(
        name="paddle", shape=tandem.RigidShape.box((0.1, 0.1, 0.1)), motion=tandem.MotionType.KINEMATIC))
    world.set_rigid_pose(paddle, (2, 0, 0))
    world.step(h, steps=3)
    np.testing.assert_allclose(world.rigid_position(paddle), [2, 0, 0], rtol=0, atol=1e-12)

    where = world.rigid_position(box)
    with pytest.raises(tandem.Error, match=r"^set pose: orientation must be a finite non-zero quaternion$"):
        world.set_rigid_pose(box, (0, 0, 0), (0, 0, 0, 0))
    with pytest.raises(tandem.Error, match=r"^set pose: position is not finite$"):
        world.set_rigid_pose(box, (NAN, 0, 0))
    with pytest.raises(ValueError, match=r"set_rigid_pose: the 4x4 pose's upper-left 3x3 block is not a rotation"):
        world.set_rigid_pose(box, np.diag([2.0, 1.0, 1.0, 1.0]))
    with pytest.raises(ValueError, match=r"last row must be \(0, 0, 0, 1\)"):
        world.set_rigid_pose(box, np.ones((4, 4)) * 0 + np.diag([1.0, 1.0, 1.0, 2.0]))
    np.testing.assert_array_equal(world.rigid_position(box), where)  # unchanged


def test_mass_and_inertia_of_a_box_and_bad_masses():
    world = tandem.World()
    m, half = 4.0, (0.3, 0.2, 0.05)
    box = world.add_rigid_body(box_desc("box", half, m, (0, 1, 0)))
    sides = [2 * s for s in half]
    assert world.rigid_mass(box) == m
    inertia = world.rigid_inertia(box)
    np.testing.assert_allclose(np.diag(inertia), np.diag(box_inertia(m, sides)), rtol=1e-12)
    assert inertia[0, 0] == pytest.approx(m * (sides[1] ** 2 + sides[2] ** 2) / 12, rel=1e-12)
    ground = world.add_rigid_body(ground_desc())
    assert world.rigid_mass(ground) == 0.0
    np.testing.assert_array_equal(world.rigid_inertia(ground), np.zeros((3, 3)))
    for bad in (-1.0, 0.0, NAN, INF):
        with pytest.raises(tandem.Error, match="rigid body 'heavy': mass must be positive and finite for a dynamic body"):
            world.add_rigid_body(box_desc("heavy", half, bad, (0, 2, 0)))
    assert world.rigid_body_count == 2


# ---- Contacts -----------------------------------------------------------------------------------

def test_rigid_contacts_of_a_box_resting_on_the_ground_carry_its_weight():
    world = tandem.World()
    ground = world.add_rigid_body(ground_desc())
    m, h = 2.5, 1.0 / 60
    box = world.add_rigid_body(box_desc("box", (0.3, 0.2, 0.25), m, (0, 0.2, 0)))
    world.step(h, steps=120)
    contacts = world.rigid_contacts()
    assert len(contacts) == 4  # the box's four bottom corners
    total, friction = 0.0, np.zeros(3)
    for c in contacts:
        assert isinstance(c, tandem.RigidContact)
        assert {c.body_a, c.body_b} == {box, ground}
        up = 1.0 if c.body_a == box else -1.0  # the normal points from B to A
        np.testing.assert_allclose(c.normal, [0, up, 0], atol=1e-9)
        ground_point = c.point_on_b if c.body_a == box else c.point_on_a
        assert abs(ground_point[1]) < 2e-3
        assert abs(abs(ground_point[0]) - 0.3) < 2e-3 and abs(abs(ground_point[2]) - 0.25) < 2e-3  # at the corners
        assert c.normal_impulse >= 0
        assert abs(np.dot(c.friction_impulse, c.normal)) < 1e-12  # tangential
        total += c.normal_impulse
        friction += c.friction_impulse
    # Over one step the ground holds the box's weight: impulses sum to m g h.
    assert total == pytest.approx(m * G * h, rel=0.01)
    assert np.linalg.norm(friction) < 1e-3 * total
    assert total == world.rigid_contact_impulse(box, ground)
    as_dict = contacts[0].to_dict()
    assert set(as_dict) == {"body_a", "body_b", "point_on_a", "point_on_b", "normal", "distance", "normal_impulse",
                            "friction_impulse"}
    assert as_dict["normal_impulse"] == contacts[0].normal_impulse


# ---- Collision filters --------------------------------------------------------------------------

def stacked_boxes(upper_group=1, upper_mask=tandem.ALL_COLLISION_GROUPS, lower_group=1,
                  lower_mask=tandem.ALL_COLLISION_GROUPS):
    world = tandem.World()
    world.add_rigid_body(ground_desc())
    lower = world.add_rigid_body(box_desc("lower", (0.2, 0.2, 0.2), 1.0, (0, 0.2, 0), collision_group=lower_group,
                                          collision_mask=lower_mask))
    upper = world.add_rigid_body(box_desc("upper", (0.2, 0.2, 0.2), 1.0, (0, 1.0, 0), collision_group=upper_group,
                                          collision_mask=upper_mask))
    return world, lower, upper


def test_bodies_that_mask_each_other_pass_through_and_with_the_mask_they_collide():
    everything = tandem.ALL_COLLISION_GROUPS
    # Groups 2 and 4, each masking the other out (both still meet the ground in group 1).
    world, lower, upper = stacked_boxes(4, everything & ~2, 2, everything & ~4)
    assert world.rigid_collision_group(upper) == 4 and world.rigid_collision_mask(upper) == everything & ~2
    assert not tandem.collision_groups_meet(4, everything & ~2, 2, everything & ~4)
    assert tandem.collision_groups_meet(4, everything, 2, everything)
    h = 1.0 / 60
    impulse_between = 0.0
    for _ in range(90):
        world.step(h)
        impulse_between += world.rigid_contact_impulse(upper, lower)
    assert impulse_between == 0.0
    assert world.rigid_position(upper)[1] == pytest.approx(0.2, abs=0.01)  # through the lower box to the ground
    assert world.rigid_position(lower)[1] == pytest.approx(0.2, abs=0.01)

    # The same groups with masks that let them meet: the upper box lands on the lower one.
    world, lower, upper = stacked_boxes(4, everything, 2, everything)
    world.step(h, steps=90)
    assert world.rigid_position(upper)[1] == pytest.approx(0.6, abs=0.01)
    assert world.rigid_contact_impulse(upper, lower) == pytest.approx(1.0 * G * h, rel=0.02)

    # Changed on the fly: mask the lower box out of the upper's and it drops through.
    world.set_rigid_collision_filter(upper, 4, everything & ~2)
    world.step(h, steps=60)
    assert world.rigid_position(upper)[1] == pytest.approx(0.2, abs=0.01)
    assert world.rigid_collision_mask(upper) == everything & ~2


def test_a_cloth_masked_against_a_sphere_falls_through_it():
    def cloth_mean_height(mask=None, filter_after=False):
        world = tandem.World()
        world.add_rigid_body(tandem.RigidBodyDesc(name="sphere", shape=tandem.RigidShape.sphere(0.3),
                                                  motion=tandem.MotionType.STATIC, collision_group=4))
        desc = tandem.DeformableDesc(name="cloth",
                                     mesh=tandem.make_cloth_grid((-0.5, 0.5, -0.5), (1, 0, 0), (0, 0, 1), 9, 9, 0.2),
                                     inextensibility=tandem.InextensibilitySettings(enabled=True))
        if mask is not None and not filter_after:
            desc.collision.mask = mask
        cloth = world.add_deformable(desc)
        if mask is not None and filter_after:
            world.set_deformable_collision_filter(cloth, 1, mask)
        world.step(1.0 / 60, steps=45)
        return float(np.mean(world.node_positions(cloth)[:, 1])), len(world.contacts())

    resting, touching = cloth_mean_height()
    assert resting > 0.0 and touching > 0  # draped over the sphere's top at 0.3
    for filter_after in (False, True):
        fallen, touching = cloth_mean_height(tandem.ALL_COLLISION_GROUPS & ~4, filter_after)
        assert touching == 0
        assert fallen < 0.5 - 0.5 * G * 0.7 ** 2  # fell freely for 0.75 s (less its slack)


def test_collision_filters_refuse_bad_values():
    world = tandem.World()
    box = world.add_rigid_body(box_desc("box", (0.1, 0.1, 0.1), 1.0, (0, 1, 0)))
    with pytest.raises(ValueError, match=r"set_rigid_collision_filter: mask must be in \[0, 2\*\*32\).*got -3"):
        world.set_rigid_collision_filter(box, 1, ~2)
    with pytest.raises(ValueError, match=r"RigidBodyDesc.collision_group must be in \[0, 2\*\*32\).*got 4294967296"):
        tandem.RigidBodyDesc(collision_group=1 << 32)
    with pytest.raises(ValueError, match=r"CollisionSettings.mask must be in \[0, 2\*\*32\)"):
        tandem.CollisionSettings(mask=-1)
    with pytest.raises(tandem.IdError,
                       match=r"^collision filter: deformable 4: no such deformable \(the world has 0 slots\)$"):
        world.set_deformable_collision_filter(tandem.DeformableId(4), 1, 1)
    with pytest.raises(tandem.IdError, match=r"^rigid_collision_group: rigid body 3: no such rigid body"):
        world.rigid_collision_group(tandem.RigidBodyId(3))
    assert world.rigid_collision_mask(box) == tandem.ALL_COLLISION_GROUPS  # unchanged
    assert tandem.CollisionSettings().group == tandem.DEFAULT_COLLISION_GROUP == 1


# ---- Hinges -------------------------------------------------------------------------------------

def hinged_bar(world, pivot, **hinge):
    """A 1 kg bar 1 m long along x, hinged about z through `pivot`."""
    bar = world.add_rigid_body(box_desc("bar", (0.5, 0.05, 0.05), 1.0, (0, 1, 0)))
    joint = world.add_hinge(tandem.HingeDesc(body_a=bar, pivot=pivot, axis=(0, 0, 1), **hinge))
    return bar, joint


def test_a_hinge_limit_holds_the_angle_under_gravity_torque():
    h = 1.0 / 240
    # Hinged at its left end, the bar swings down (negative about +z); a limit at -0.4 rad stops it.
    world = tandem.World()
    bar, joint = hinged_bar(world, (-0.5, 1, 0), lower_limit=-0.4, upper_limit=0.4)
    angles = []
    for _ in range(480):
        world.step(h)
        angles.append(world.hinge_angle(joint))
    assert min(angles) > -0.4 - 0.03
    # It comes to rest against the limit: the last half second within 3 cm-rad of -0.4.
    np.testing.assert_allclose(angles[-120:], -0.4, atol=0.03)
    # Its orientation agrees: a turn of the hinge's angle about z.
    w, x, y, z = world.rigid_orientation(bar)
    assert 2 * math.atan2(z, w) == pytest.approx(world.hinge_angle(joint), abs=1e-6)
    # Without a limit (lower > upper) it swings on, well past the old limit.
    world.set_hinge_limits(joint, 1, -1)
    lowest = 0.0
    for _ in range(240):
        world.step(h)
        lowest = min(lowest, world.hinge_angle(joint))
    assert lowest < -1.2
    # Set at run time: a tight limit on the free bar holds it again.
    world.set_hinge_limits(joint, -0.2, 0.2)
    world.step(h, steps=480)
    assert world.hinge_angle(joint) == pytest.approx(-0.2, abs=0.03)


def test_a_hinge_motor_reaches_its_target_speed_or_accelerates_at_max_torque_over_inertia():
    h = 1.0 / 240
    world = zero_gravity_world()
    bar, joint = hinged_bar(world, (0, 1, 0), motor=True, motor_target_speed=3.0, motor_max_torque=50.0)
    world.step(h, steps=60)
    assert world.hinge_speed(joint) == pytest.approx(3.0, abs=0.01)
    assert world.rigid_angular_velocity(bar)[2] == pytest.approx(3.0, abs=0.01)
    # A weak motor set at run time: the speed grows at tau / I for 0.5 s, short of the target.
    world2 = zero_gravity_world()
    bar2, joint2 = hinged_bar(world2, (0, 1, 0))
    inertia = 1.0 * (1.0 ** 2 + 0.1 ** 2) / 12
    world2.set_hinge_motor(joint2, True, target_speed=3.0, max_torque=0.1)
    steps = 120
    world2.step(h, steps=steps)
    expected = 0.1 / inertia * steps * h
    assert world2.hinge_speed(joint2) == pytest.approx(expected, rel=0.01)
    # Switched off, the bar turns on at the speed it has.
    world2.set_hinge_motor(joint2, False)
    speed = world2.hinge_speed(joint2)
    world2.step(h, steps=60)
    assert world2.hinge_speed(joint2) == pytest.approx(speed, rel=1e-3)


def test_bad_hinge_settings_are_refused():
    world = tandem.World()
    a = world.add_rigid_body(box_desc("a", (0.1, 0.1, 0.1), 1.0, (0, 0, 0)))
    with pytest.raises(tandem.Error, match=r"^hinge: limits must lie in \[-pi, pi\] rad, got \[-4, 0\]$"):
        world.add_hinge(tandem.HingeDesc(body_a=a, lower_limit=-4, upper_limit=0))
    with pytest.raises(tandem.Error, match=r"^hinge: motor max torque must be >= 0 and finite, got -1 N·m$"):
        world.add_hinge(tandem.HingeDesc(body_a=a, motor=True, motor_max_torque=-1))
    hinge = world.add_hinge(tandem.HingeDesc(body_a=a))
    fixed = world.add_fixed_joint(tandem.FixedJointDesc(body_a=a))
    with pytest.raises(tandem.Error, match=r"^hinge limits: limits must lie in \[-pi, pi\] rad \(lower > upper for none\), got \[nan, 1\]$"):
        world.set_hinge_limits(hinge, NAN, 1)
    with pytest.raises(tandem.Error, match=r"got \[-0.5, 4\]$"):
        world.set_hinge_limits(hinge, -0.5, 4)
    with pytest.raises(tandem.Error, match=r"^hinge motor: target speed must be finite$"):
        world.set_hinge_motor(hinge, True, INF, 1)
    with pytest.raises(tandem.Error, match=r"^hinge motor: max torque must be >= 0 and finite, got nan N·m$"):
        world.set_hinge_motor(hinge, True, 1, NAN)
    with pytest.raises(tandem.Error, match=r"^hinge motor: joint 1 is a fixed joint, not a hinge$"):
        world.set_hinge_motor(fixed, True, 1, 1)
    with pytest.raises(tandem.Error, match=r"^hinge_angle: joint 1 is not a hinge$"):
        world.hinge_angle(fixed)
    with pytest.raises(tandem.IdError, match=r"^hinge_speed: joint 5: no such joint \(the world has 2 slots\)$"):
        world.hinge_speed(tandem.JointId(5))
    assert world.hinge_angle(hinge) == 0.0
