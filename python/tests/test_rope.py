"""A rope holding a box, and momentum through the coupling."""

import numpy as np
import pytest

import tandem
from conftest import G, edge_strains, hanging_rope_with_box

H = 1.0 / 60


def test_hanging_rope_holds_the_box_without_stretching_and_carries_its_weight():
    world = tandem.World()
    rope, box, top, knot = hanging_rope_with_box(world)
    edges = world.rest_mesh(rope).edges
    rest = np.full(len(edges), 1.0 / 19)
    worst = 0.0
    positions = world.node_positions(rope)  # a view: it follows the world
    for _ in range(240):  # 4 s
        world.step(H)
        worst = max(worst, edge_strains(positions, edges, rest).max())
    # No edge more than 1 % longer at any step.
    assert worst < 0.01
    # The box hangs 1 m below the fixed point, its top face at the rope's end, at rest.
    assert world.rigid_position(box)[1] == pytest.approx(2.0 - 1.0 - 0.1, abs=0.02)
    assert np.linalg.norm(world.rigid_linear_velocity(box)) < 0.01
    # The anchor pulls the box up with its weight (the rope gets the opposite) ...
    anchor = world.anchor_state(knot)
    assert -anchor.impulse[1] / H == pytest.approx(1.0 * G, rel=0.02)
    assert np.linalg.norm(anchor.world_point_on_body - anchor.world_point_on_deformable) < 1e-3
    # ... which is what Tandem's rows put on the body, and the fixed point carries rope and box.
    np.testing.assert_allclose(world.deformable_force_on_rigid(box), [0, G, 0], rtol=0.02, atol=0.02)
    assert world.fixed_point_impulse(top)[1] / H == pytest.approx(1.2 * G, rel=0.02)
    assert world.last_report.violations == []


def test_momentum_is_conserved_through_an_anchor_in_zero_gravity():
    world = tandem.World(tandem.WorldSettings(gravity=(0, 0, 0)))
    rope = world.add_deformable(tandem.DeformableDesc(
        name="rope", mesh=tandem.make_rope((0, 0, 0), (1, 0, 0), 11, 0.5),
        inextensibility=tandem.InextensibilitySettings(enabled=True),
        collision=tandem.CollisionSettings(enabled=False)))
    box = world.add_rigid_body(tandem.RigidBodyDesc(
        name="box", shape=tandem.RigidShape.box((0.05, 0.05, 0.05)), mass=2.0, position=(1.05, 0, 0),
        linear_velocity=(0.5, 1.0, 0.0), can_sleep=False))
    world.add_anchor(tandem.AnchorDesc.node(rope, 10, box))
    world.set_node_velocity(rope, 0, (0, -2.0, 0.3))
    before = world.total_linear_momentum()
    np.testing.assert_allclose(before, [2.0 * 0.5, 2.0 * 1.0 - 0.5 / 11 * 2.0, 0.5 / 11 * 0.3], atol=1e-12)
    positions = world.node_positions(rope)

    def centre_of_mass():
        return (0.5 / 11 * positions.sum(axis=0) + 2.0 * world.rigid_position(box)) / 2.5

    start = centre_of_mass()
    for _ in range(120):
        world.step(H)
        np.testing.assert_allclose(world.total_linear_momentum(), before, atol=1e-9)
    # The rope and box tumble about their centre of mass, which moves at P / M.
    np.testing.assert_allclose(centre_of_mass(), start + before / 2.5 * world.time, atol=1e-6)


def test_fixed_points_move_with_their_target_and_fix_node_pins():
    world = tandem.World()
    rope = world.add_deformable(tandem.DeformableDesc(
        name="rope", mesh=tandem.make_rope((0, 1, 0), (0, 0.5, 0), 6, 0.06),
        inextensibility=tandem.InextensibilitySettings(enabled=True)))
    top = world.add_fixed_point(rope, 0)
    world.set_fixed_point_target(top, (0.1, 1, 0))
    world.step(H, steps=30)
    np.testing.assert_allclose(world.node_positions(rope)[0], [0.1, 1, 0], atol=1e-6)
    world.fix_node(rope, 5)
    assert world.node_inverse_masses(rope)[5] == 0.0
    assert world.node_inverse_masses(rope)[1] == pytest.approx(1 / 0.01)
    pinned = np.array(world.node_positions(rope)[5])
    world.step(H, steps=10)
    np.testing.assert_array_equal(world.node_positions(rope)[5], pinned)
    world.set_node_position(rope, 5, (0.3, 0.2, 0))
    np.testing.assert_array_equal(world.node_positions(rope)[5], [0.3, 0.2, 0])
