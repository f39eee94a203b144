"""Snapshots from Python: stepping on from a restored snapshot repeats the original run bit for bit
(np.array_equal on every number a user can read), and a snapshot restores into its own world only."""

import gc

import numpy as np
import pytest

import tandem

H = 1.0 / 60


def build(world):
    """A box stack on the ground (one box pushed off-centre), a cloth falling onto a sphere and a
    swinging rope holding a box: rigid contacts, deformable contacts, anchors, fixed points."""
    world.add_rigid_body(tandem.RigidBodyDesc(name="ground", shape=tandem.RigidShape.plane((0, 1, 0), 0),
                                              motion=tandem.MotionType.STATIC))
    world.add_rigid_body(tandem.RigidBodyDesc(name="bottom", shape=tandem.RigidShape.box((0.3, 0.1, 0.3)), mass=2.0,
                                              position=(2, 0.1, 0)))
    top = world.add_rigid_body(tandem.RigidBodyDesc(name="top", shape=tandem.RigidShape.box((0.15, 0.1, 0.15)),
                                                    mass=1.0, position=(2.05, 0.32, 0.02)))
    world.add_rigid_body(tandem.RigidBodyDesc(name="sphere", shape=tandem.RigidShape.sphere(0.25),
                                              motion=tandem.MotionType.STATIC, position=(0, 0.25, 0)))
    world.add_deformable(tandem.DeformableDesc(
        name="cloth", mesh=tandem.make_cloth_grid((-0.4, 0.7, -0.4), (0.8, 0, 0), (0, 0, 0.8), 10, 10, 0.2),
        inextensibility=tandem.InextensibilitySettings(enabled=True),
        bending=tandem.BendingSettings(enabled=True)))
    rope = world.add_deformable(tandem.DeformableDesc(
        name="rope", mesh=tandem.make_rope((-2, 2, 0), (-1.2, 2, 0), 12, 0.1),
        inextensibility=tandem.InextensibilitySettings(enabled=True)))
    world.add_fixed_point(rope, 0)
    hanging = world.add_rigid_body(tandem.RigidBodyDesc(name="hanging", shape=tandem.RigidShape.box((0.05,) * 3),
                                                        mass=0.5, position=(-1.15, 2, 0)))
    world.add_anchor(tandem.AnchorDesc.node(rope, 11, hanging))
    world.apply_impulse_at_point(top, (0.3, 0, 0), (2.05, 0.42, 0.1))
    return top


def record(world):
    """Every number of the state a user can read, in order, as one array."""
    parts = []
    for b in world.rigid_bodies():
        parts += [world.rigid_position(b), world.rigid_orientation(b), world.rigid_linear_velocity(b),
                  world.rigid_angular_velocity(b), world.deformable_impulse_on_rigid(b)]
    for d in world.deformable_ids():
        parts += [world.node_positions(d).ravel(), world.node_velocities(d).ravel()]
    for c in world.contacts():
        parts += [c.point, [c.normal_impulse], c.friction_impulse]
    for c in world.rigid_contacts():
        parts += [c.point_on_a, [c.normal_impulse], c.friction_impulse]
    return np.concatenate([np.asarray(p, dtype=float).ravel() for p in parts])


def run(world, steps):
    records = []
    for _ in range(steps):
        world.step(H)
        records.append(record(world))
    return records


@pytest.mark.parametrize("substeps", [1, 3])
def test_stepping_on_from_a_restored_snapshot_repeats_the_run_bit_for_bit(substeps):
    world = tandem.World(tandem.WorldSettings(solver=tandem.SolverSettings(substeps=substeps)))
    top = build(world)
    run(world, 30)
    assert world.contacts() and world.rigid_contacts()  # contacts made: warm starts matter
    world.apply_force(top, (2, 0, 0))  # a push applied before the snapshot is part of its state
    snapshot = world.snapshot()
    assert isinstance(snapshot, tandem.WorldSnapshot)
    assert snapshot.step_count == 30 and snapshot.time == world.time
    saved = record(world)
    original = run(world, 30)
    world.restore(snapshot)
    assert world.step_count == 30 and world.time == snapshot.time
    assert np.array_equal(record(world), saved)
    repeated = run(world, 30)
    assert len(repeated) == len(original)
    for step, (a, b) in enumerate(zip(original, repeated)):
        assert a.shape == b.shape, step
        assert np.array_equal(a, b), f"step {step}: {np.count_nonzero(a != b)} numbers differ, by up to {np.max(np.abs(a - b))}"
    # Not a run that stood still: the stack and the cloth moved over those 30 steps.
    assert not np.array_equal(original[0], original[-1])
    # A snapshot restores any number of times.
    world.restore(snapshot)
    assert np.array_equal(run(world, 5)[-1], original[4])


def test_a_snapshot_restores_only_into_its_own_world_and_only_while_the_rigid_bodies_are_the_same():
    world = tandem.World()
    build(world)
    run(world, 10)
    snapshot = world.snapshot()
    other = tandem.World()
    build(other)
    run(other, 3)
    before = record(other)
    with pytest.raises(tandem.Error, match=r"^restore: the snapshot was taken from another world$"):
        other.restore(snapshot)
    assert other.step_count == 3 and np.array_equal(record(other), before)  # nothing changed
    world.add_rigid_body(tandem.RigidBodyDesc(name="late", position=(5, 1, 0)))
    with pytest.raises(tandem.Error,
                       match=r"^restore: rigid bodies or joints were added or removed since the snapshot was taken$"):
        world.restore(snapshot)
    with pytest.raises(TypeError):
        tandem.WorldSnapshot()  # only World.snapshot makes one


def test_a_snapshot_of_a_world_that_is_gone_restores_into_no_other():
    world = tandem.World()
    build(world)
    world.step(H)
    snapshot = world.snapshot()
    del world
    gc.collect()
    # New worlds may well be made where the old one was: each refuses the stranger's snapshot.
    for _ in range(4):
        fresh = tandem.World()
        build(fresh)
        with pytest.raises(tandem.Error, match=r"^restore: the snapshot was taken from another world$"):
            fresh.restore(snapshot)
        assert fresh.step_count == 0
        del fresh


def test_restore_brings_back_what_was_removed_and_takes_away_what_was_added():
    world = tandem.World()
    build(world)
    run(world, 10)
    cloth, rope = world.find_deformable("cloth"), world.find_deformable("rope")
    snapshot = world.snapshot()
    saved = record(world)
    world.remove_deformable(cloth)
    run(world, 5)
    world.restore(snapshot)
    assert world.contains(cloth) and np.array_equal(record(world), saved)

    # A deformable added after the snapshot goes with the restore; its id is refused then. Restoring
    # another layout of the node arrays is refused while views of them are alive (they could move).
    late = world.add_deformable(tandem.DeformableDesc(name="late", mesh=tandem.make_rope((3, 2, 0), (4, 2, 0), 5, 0.1)))
    later = world.snapshot()
    view = world.node_positions(rope)
    with pytest.raises(tandem.Error, match=r"^restore: 1 NumPy view\(s\) of this world's nodes"):
        world.restore(snapshot)
    assert world.contains(late)  # refused: nothing changed
    del view
    world.restore(snapshot)
    assert not world.contains(late) and world.deformable_ids() == [cloth, rope]
    with pytest.raises(tandem.IdError, match=r"^node_positions: deformable 2"):
        world.node_positions(late)
    # The later snapshot brings it back; views of the same layout do not stop a restore.
    world.restore(later)
    assert world.contains(late)
    view = world.node_positions(late)
    world.restore(later)
    np.testing.assert_array_equal(view[:, 0], np.linspace(3, 4, 5))
