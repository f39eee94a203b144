"""Worlds, settings, rigid bodies, joints and ids, asserted with numbers."""

import numpy as np
import pytest

import tandem
from conftest import G


def test_module_has_a_version_and_docstrings():
    assert tandem.__version__.count(".") == 2
    for name in ("World", "RigidBodyDesc", "DeformableDesc", "make_rope", "load_scene", "StepReport"):
        assert getattr(tandem, name).__doc__, name
    assert tandem.World.step.__doc__ and "StepReport" in tandem.World.step.__doc__


def test_settings_round_trip_and_defaults():
    world = tandem.World()
    settings = world.settings
    np.testing.assert_array_equal(settings.gravity, [0, -G, 0])
    assert settings.solver.iterations == 4
    settings.solver.iterations = 8
    settings.solver.friction = tandem.FrictionModel.PRESSURE
    settings.gravity = (0, -1.62, 0)
    world.settings = settings
    assert world.settings.solver.iterations == 8
    assert world.settings.solver.friction == tandem.FrictionModel.PRESSURE
    assert world.settings.gravity[1] == -1.62
    moon = tandem.World(tandem.WorldSettings(gravity=(0, -1.62, 0), solver=tandem.SolverSettings(substeps=2)))
    assert moon.settings.solver.substeps == 2


def test_free_fall_matches_g_t_squared_over_two():
    world = tandem.World()
    ball = world.add_rigid_body(tandem.RigidBodyDesc(
        name="ball", shape=tandem.RigidShape.sphere(0.1), mass=2.0, position=(0, 10, 0), can_sleep=False))
    rope = world.add_deformable(tandem.DeformableDesc(
        name="rope", mesh=tandem.make_rope((1, 10, 0), (2, 10, 0), 5, 0.1),
        collision=tandem.CollisionSettings(enabled=False)))
    h, steps = 1.0 / 100, 100
    report = world.step(h, steps=steps)
    t = world.time
    assert world.step_count == steps and t == pytest.approx(1.0)
    assert isinstance(report, tandem.StepReport)
    # Symplectic Euler: y = y0 - g h^2 n (n + 1) / 2, within g h t of the exact g t^2 / 2.
    fallen = 10.0 - world.rigid_position(ball)[1]
    assert fallen == pytest.approx(G * h * h * steps * (steps + 1) / 2, rel=1e-9)
    assert abs(fallen - G * t * t / 2) <= G * h * t
    assert world.rigid_linear_velocity(ball)[1] == pytest.approx(-G * t, rel=1e-9)
    # The free rope's nodes fall exactly as the ball does, and keep their shape.
    positions = world.node_positions(rope)
    np.testing.assert_allclose(positions[:, 1], 10.0 - fallen, rtol=0, atol=1e-9)
    np.testing.assert_allclose(positions[:, 0], np.linspace(1, 2, 5), atol=1e-12)
    # Momentum of the ball and the rope: (2 + 0.1) kg * g * t downwards.
    np.testing.assert_allclose(world.total_linear_momentum(), [0, -2.1 * G * t, 0], rtol=1e-9, atol=1e-12)


def test_damping_takes_its_fraction_of_the_velocity_per_second():
    world = tandem.World(tandem.WorldSettings(gravity=(0, 0, 0)))
    ball = world.add_rigid_body(tandem.RigidBodyDesc(
        name="ball", shape=tandem.RigidShape.sphere(0.1), linear_velocity=(1.0, 0.0, 0.0),
        angular_velocity=(0.0, 2.0, 0.0), linear_damping=0.2, angular_damping=0.6, can_sleep=False))
    world.step(0.02, steps=100)  # 2 s: v = v0 (1 - d)^t
    np.testing.assert_allclose(world.rigid_linear_velocity(ball), [0.8 ** 2, 0, 0], rtol=1e-12, atol=1e-15)
    np.testing.assert_allclose(world.rigid_angular_velocity(ball), [0, 2.0 * 0.4 ** 2, 0], rtol=1e-12, atol=1e-15)
    world.set_rigid_damping(ball, 0.0, 0.0)
    world.step(0.02, steps=50)
    np.testing.assert_allclose(world.rigid_linear_velocity(ball), [0.8 ** 2, 0, 0], rtol=1e-12, atol=1e-15)
    with pytest.raises(tandem.Error, match="angular damping must be in"):
        world.set_rigid_damping(ball, 0.0, -1.0)
    with pytest.raises(tandem.Error, match="linear damping must be in"):
        world.add_rigid_body(tandem.RigidBodyDesc(name="bad", shape=tandem.RigidShape.sphere(0.1), linear_damping=2.0))


def test_rigid_pose_mass_and_inertia():
    world = tandem.World(tandem.WorldSettings(gravity=(0, 0, 0)))
    angle = 0.3
    q = (np.cos(angle / 2), 0.0, 0.0, np.sin(angle / 2))  # (w, x, y, z): angle about z
    box = world.add_rigid_body(tandem.RigidBodyDesc(
        name="box", shape=tandem.RigidShape.box((0.5, 0.25, 0.125)), mass=3.0, position=(1, 2, 3), orientation=q,
        angular_velocity=(0, 0, 0.0)))
    assert world.find_rigid_body("box") == box and world.find_rigid_body("nothing") is None
    assert world.rigid_name(box) == "box" and world.rigid_body_count == 1
    np.testing.assert_allclose(world.rigid_orientation(box), q, atol=1e-12)
    pose = world.rigid_pose(box)
    assert pose.shape == (4, 4)
    np.testing.assert_allclose(pose[:3, 3], [1, 2, 3])
    np.testing.assert_allclose(pose[:3, :3], [[np.cos(angle), -np.sin(angle), 0],
                                              [np.sin(angle), np.cos(angle), 0], [0, 0, 1]], atol=1e-12)
    np.testing.assert_allclose(pose[3], [0, 0, 0, 1])
    assert world.rigid_mass(box) == 3.0
    # A box's inertia about z: m (a^2 + b^2) / 3 with half extents a, b; world frame = rotated body frame.
    inertia = world.rigid_inertia(box)
    assert inertia[2, 2] == pytest.approx(3.0 * (0.5 ** 2 + 0.25 ** 2) / 3, rel=1e-9)
    body_inertia = np.diag([3.0 * (0.25 ** 2 + 0.125 ** 2) / 3, 3.0 * (0.5 ** 2 + 0.125 ** 2) / 3,
                            3.0 * (0.5 ** 2 + 0.25 ** 2) / 3])
    rotation = pose[:3, :3]
    np.testing.assert_allclose(inertia, rotation @ body_inertia @ rotation.T, atol=1e-9)
    assert world.rigid_shape(box).type == tandem.ShapeType.BOX
    np.testing.assert_allclose(world.rigid_shape(box).half_extents, [0.5, 0.25, 0.125])


def test_hinge_keeps_a_pendulum_at_its_length_and_fixed_joint_holds_pose():
    world = tandem.World()
    bob = world.add_rigid_body(tandem.RigidBodyDesc(
        name="bob", shape=tandem.RigidShape.sphere(0.05), mass=1.0, position=(0.5, 1, 0), can_sleep=False))
    rider = world.add_rigid_body(tandem.RigidBodyDesc(
        name="rider", shape=tandem.RigidShape.box((0.02, 0.02, 0.02)), mass=0.1, position=(0.6, 1, 0),
        can_sleep=False))
    world.add_hinge(tandem.HingeDesc(body_a=bob, pivot=(0, 1, 0), axis=(0, 0, 1)))
    world.add_fixed_joint(tandem.FixedJointDesc(body_a=rider, body_b=bob))
    lowest = 1.0
    for _ in range(60):
        world.step(1.0 / 120)
        p, r = world.rigid_position(bob), world.rigid_position(rider)
        # Bullet's joints at 4 iterations: the hinge within 1 % of its arm (3 mm measured), the
        # fixed joint within 1 mm (0.6 mm measured); the swing stays in its plane.
        assert np.linalg.norm(p - (0, 1, 0)) == pytest.approx(0.5, abs=5e-3)
        assert np.linalg.norm(r - p) == pytest.approx(0.1, abs=1e-3)
        assert abs(p[2]) < 1e-6
        lowest = min(lowest, p[1])
    assert lowest < 0.9  # it swung down
    assert world.last_report.bullet_joints == 2


def test_kinematic_target_moves_the_body():
    world = tandem.World()
    paddle = world.add_rigid_body(tandem.RigidBodyDesc(
        name="paddle", shape=tandem.RigidShape.box((0.1, 0.1, 0.1)), motion=tandem.MotionType.KINEMATIC))
    world.set_kinematic_target(paddle, (0.5, 0, 0))
    world.step(0.01)
    np.testing.assert_allclose(world.rigid_position(paddle), [0.5, 0, 0], atol=1e-9)
    assert world.rigid_mass(paddle) == 0.0


def test_ids_compare_hash_and_do_not_mix():
    assert tandem.RigidBodyId(2) == tandem.RigidBodyId(2)
    assert tandem.RigidBodyId(2) != tandem.RigidBodyId(3)
    assert tandem.RigidBodyId(2) != tandem.DeformableId(2)
    assert len({tandem.RigidBodyId(1), tandem.RigidBodyId(1), tandem.DeformableId(1)}) == 2
    assert repr(tandem.AnchorId(4)) == "AnchorId(4)" and int(tandem.JointId(7)) == 7


def test_step_report_as_objects_and_dicts():
    world = tandem.World()
    world.add_rigid_body(tandem.RigidBodyDesc(name="floor", shape=tandem.RigidShape.plane((0, 1, 0), 0),
                                              motion=tandem.MotionType.STATIC))
    rope = world.add_deformable(tandem.DeformableDesc(
        name="rope", mesh=tandem.make_rope((0, 0.5, 0), (1, 0.5, 0), 11, 0.1),
        inextensibility=tandem.InextensibilitySettings(enabled=True)))
    world.add_fixed_point(rope, 0)
    report = world.step(1.0 / 60)
    assert set(report.stage_seconds) == {"models", "rigid_prediction", "collision_detection", "row_setup",
                                         "interleaved_solve", "integrate"}
    counts = report.row_counts
    assert counts["fixed_point"] == 3 and counts["inextensibility"] == 10
    assert report.total_rows == sum(counts.values())
    assert len(report.rms_delta_lambda) == world.settings.solver.iterations
    assert report.total_seconds >= sum(report.stage_seconds.values()) * 0.5
    as_dict = report.to_dict()
    assert as_dict["row_counts"] == counts and as_dict["violations"] == []
    assert world.last_report.to_dict()["total_rows"] == report.total_rows
