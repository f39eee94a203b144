"""Bad input raises exceptions carrying the library's messages; nothing crashes."""

import math

import numpy as np
import pytest

import tandem

NAN = math.nan


def test_generators_raise_the_library_messages():
    with pytest.raises(tandem.Error, match=r"^rope: node count must be >= 2, got 1$"):
        tandem.make_rope((0, 0, 0), (1, 0, 0), 1, 1.0)
    with pytest.raises(tandem.Error, match="total mass must be a positive number of kilograms, got -1"):
        tandem.make_rope((0, 0, 0), (1, 0, 0), 5, -1.0)
    with pytest.raises(tandem.Error, match="start is not finite"):
        tandem.make_rope((NAN, 0, 0), (1, 0, 0), 5, 1.0)
    with pytest.raises(tandem.Error, match="cloth grid: columns must be >= 2, got 1"):
        tandem.make_cloth_grid((0, 0, 0), (1, 0, 0), (0, 0, 1), 1, 5, 1.0)
    with pytest.raises(tandem.Error, match="tet box: cells along x must be >= 1, got 0"):
        tandem.make_tet_box((0, 0, 0), (1, 1, 1), (0, 1, 1), 1.0)
    assert issubclass(tandem.Error, RuntimeError)


def test_the_world_refuses_bad_bodies_and_constraints():
    world = tandem.World()
    mesh = tandem.make_rope((0, 1, 0), (0, 0, 0), 4, 0.1)
    masses = mesh.masses
    masses[2] = -1.0
    mesh.masses = masses
    with pytest.raises(tandem.Error, match="deformable 'rope': node 2 has mass -1 kg"):
        world.add_deformable(tandem.DeformableDesc(name="rope", mesh=mesh))
    rope = world.add_deformable(tandem.DeformableDesc(name="rope", mesh=tandem.make_rope((0, 1, 0), (0, 0, 0), 4, 0.1)))
    with pytest.raises(tandem.Error, match="rigid body 'crate': mass must be positive and finite for a dynamic body, got -2"):
        world.add_rigid_body(tandem.RigidBodyDesc(name="crate", mass=-2))
    with pytest.raises(tandem.Error, match="orientation must be a finite non-zero quaternion"):
        world.add_rigid_body(tandem.RigidBodyDesc(name="crate", orientation=(0, 0, 0, 0)))
    with pytest.raises(tandem.Error, match="a plane or a triangle mesh can only be static"):
        world.add_rigid_body(tandem.RigidBodyDesc(name="crate", shape=tandem.RigidShape.plane((0, 1, 0), 0)))
    crate = world.add_rigid_body(tandem.RigidBodyDesc(name="crate"))
    with pytest.raises(tandem.Error, match=r"fixed point: node 9 is out of range for deformable 'rope' \(4 nodes\)"):
        world.add_fixed_point(rope, 9, (0, 0, 0))
    with pytest.raises(tandem.Error, match="max force must be positive, got -3"):
        world.add_fixed_point(rope, 0, max_force=-3)
    with pytest.raises(tandem.Error, match=r"anchor: rigid body 9: no such rigid body \(the world has 1 slot\)"):
        world.add_anchor(tandem.AnchorDesc.node(rope, 0, tandem.RigidBodyId(9)))
    with pytest.raises(tandem.Error, match="weights must sum to 1, got 1.4"):
        world.add_anchor(tandem.AnchorDesc(deformable=rope, body=crate, nodes=[0, 1, -1, -1], weights=[0.7, 0.7, 0, 0],
                                           node_count=2))
    with pytest.raises(tandem.Error, match="body A and body B are the same body"):
        world.add_hinge(tandem.HingeDesc(body_a=crate, body_b=crate))
    with pytest.raises(tandem.Error, match="velocity is not finite"):
        world.set_node_velocity(rope, 0, (NAN, 0, 0))
    with pytest.raises(tandem.Error, match="set node position: node -1 is out of range"):
        world.set_node_position(rope, -1, (0, 0, 0))
    with pytest.raises(tandem.Error, match="kinematic target: pose is not finite"):
        world.set_kinematic_target(crate, (NAN, 0, 0))


def test_bad_settings_and_time_steps_change_nothing():
    world = tandem.World()
    settings = world.settings
    settings.solver.iterations = 0
    with pytest.raises(tandem.Error, match=r"solver iterations must be in \[1, 1000\], got 0"):
        world.settings = settings
    assert world.settings.solver.iterations == 4
    with pytest.raises(tandem.Error, match="gravity must be finite"):
        tandem.World(tandem.WorldSettings(gravity=(NAN, 0, 0)))
    with pytest.raises(tandem.Error, match=r"time step must be in \(0, 1\] seconds, got 0"):
        world.step(0.0)
    with pytest.raises(tandem.Error, match="got 5"):
        world.step(5.0)
    with pytest.raises(ValueError, match="steps must be >= 1, got 0"):
        world.step(0.01, steps=0)
    assert world.step_count == 0


def test_a_diverging_step_names_the_body():
    world = tandem.World()
    rope = world.add_deformable(tandem.DeformableDesc(
        name="stiff rope", mesh=tandem.make_rope((0, 1, 0), (1, 1, 0), 10, 0.01),
        springs=tandem.MassSpringSettings(stiffness=1e7, implicit=False)))
    world.set_node_velocity(rope, 3, (0, 1, 0))
    with pytest.raises(tandem.Error, match="deformable 'stiff rope' node .*the simulation diverged"):
        world.step(1.0 / 60, steps=200)


def test_ids_that_name_nothing_are_id_errors_naming_the_call_and_the_id():
    world = tandem.World()
    world.add_rigid_body(tandem.RigidBodyDesc(name="only"))
    with pytest.raises(tandem.IdError, match=r"^rigid_position: rigid body 3: no such rigid body \(the world has 1 slot\)$"):
        world.rigid_position(tandem.RigidBodyId(3))
    with pytest.raises(IndexError, match=r"^node_positions: deformable 0: no such deformable \(the world has 0 slots\)$"):
        world.node_positions(tandem.DeformableId(0))
    with pytest.raises(tandem.Error, match=r"^anchor_state: anchor 2: no such anchor"):
        world.anchor_state(tandem.AnchorId(2))
    with pytest.raises(tandem.IdError, match=r"^fixed_point_impulse: fixed point 0: no such fixed point"):
        world.fixed_point_impulse(tandem.FixedPointId(0))
    with pytest.raises(tandem.IdError, match=r"^rigid_name: rigid body -1: no such rigid body"):
        world.rigid_name(tandem.RigidBodyId(-1))
    with pytest.raises(TypeError):
        world.rigid_position(tandem.DeformableId(0))  # ids do not mix
    assert not world.contains(tandem.RigidBodyId(3)) and world.contains(tandem.RigidBodyId(0))


def test_python_side_mistakes_are_type_and_value_errors():
    with pytest.raises(TypeError, match="RigidBodyDesc: no field named 'weight'"):
        tandem.RigidBodyDesc(weight=3)
    mesh = tandem.DeformableMesh()
    with pytest.raises(ValueError, match=r"DeformableMesh.positions: expected an \(N, 3\) array, got shape \(2, 2\)"):
        mesh.positions = [[0, 0], [1, 1]]
    with pytest.raises(ValueError, match=r"DeformableMesh.edges: expected an \(N, 2\) array"):
        mesh.edges = [0, 1, 2]
    with pytest.raises(TypeError):
        tandem.RigidBodyDesc(position=(1, 2))  # not 3 numbers
    with pytest.raises(TypeError):
        tandem.RigidBodyDesc(orientation=(1, 0, 0))  # not 4 numbers
    np.testing.assert_array_equal(tandem.RigidBodyDesc(position=np.arange(3.0)).position, [0, 1, 2])
