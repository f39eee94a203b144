"""Node positions and velocities are read-only views of the world's memory, not copies."""

import gc

import numpy as np
import pytest

import tandem


def make_world():
    world = tandem.World()
    rope = world.add_deformable(tandem.DeformableDesc(
        name="rope", mesh=tandem.make_rope((0, 1, 0), (1, 1, 0), 8, 0.1)))
    return world, rope


def address(array):
    return array.__array_interface__["data"][0]


def test_views_share_the_libraries_memory_and_follow_steps():
    world, rope = make_world()
    positions = world.node_positions(rope)
    velocities = world.node_velocities(rope)
    assert positions.shape == (8, 3) and positions.dtype == np.float64
    assert velocities.shape == (8, 3) and world.node_inverse_masses(rope).shape == (8,)
    # Not a copy: no data of its own, the world as its base, the same address every time, and
    # packed triples (the library's Vec3 layout).
    assert not positions.flags.owndata and positions.base is world
    assert address(world.node_positions(rope)) == address(positions)
    assert positions.strides == (24, 8)
    # Read-only: writes are refused, by item and by flag.
    assert not positions.flags.writeable
    with pytest.raises(ValueError, match="read-only"):
        positions[0, 1] = 5.0
    with pytest.raises(ValueError):
        positions.flags.writeable = True
    before = positions.copy()
    world.step(0.01)
    # The same object now shows the new state: every node fell by g h^2 (one symplectic Euler step).
    np.testing.assert_allclose(before[:, 1] - positions[:, 1], 9.81 * 0.01 ** 2, rtol=1e-9)
    np.testing.assert_allclose(velocities[:, 1], -9.81 * 0.01, rtol=1e-12)
    # A node moved through the API shows up in the view.
    world.set_node_position(rope, 3, (5, 6, 7))
    np.testing.assert_array_equal(positions[3], [5, 6, 7])


def test_a_view_keeps_its_world_alive():
    world, rope = make_world()
    positions = world.node_positions(rope)
    expected = positions.copy()
    del world
    gc.collect()
    np.testing.assert_array_equal(positions, expected)
    assert isinstance(positions.base, tandem.World)
    positions.base.step(0.01)
    assert positions[0, 1] < expected[0, 1]


def test_adding_a_deformable_is_refused_while_views_are_alive():
    world, rope = make_world()
    positions = world.node_positions(rope)
    column = positions[:, 1]  # a view of the view keeps it alive
    del positions
    desc = tandem.DeformableDesc(name="second", mesh=tandem.make_rope((0, 2, 0), (1, 2, 0), 4, 0.1))
    with pytest.raises(tandem.Error, match=r"add_deformable: 1 NumPy view\(s\) of this world's nodes"):
        world.add_deformable(desc)
    assert world.deformable_count == 1
    kept = np.array(column)  # a copy is fine to keep
    del column
    second = world.add_deformable(desc)
    assert world.deformable_count == 2 and kept.flags.owndata
    np.testing.assert_allclose(world.node_positions(second)[:, 1], 2.0)
