"""Mesh generators and meshes as NumPy arrays."""

import numpy as np
import pytest

import tandem


def test_rope_cloth_box_cylinder_sizes_and_masses():
    rope = tandem.make_rope((0, 0, 0), (1, 0, 0), 11, 0.5)
    assert rope.node_count == 11 and rope.edges.shape == (10, 2) and rope.edges.dtype == np.int32
    np.testing.assert_allclose(rope.masses.sum(), 0.5)
    np.testing.assert_allclose(np.diff(rope.positions[:, 0]), 0.1)
    cloth = tandem.make_cloth_grid((0, 0, 0), (1, 0, 0), (0, 0, 2), 4, 3, 1.2)
    assert cloth.node_count == 12 and cloth.triangles.shape == (2 * 3 * 2, 3)
    np.testing.assert_allclose(cloth.positions[3 * 4 - 1], [1, 0, 2])  # node (c, r) = r * columns + c
    assert len(cloth.shear_edges) == 3 * 2 and len(cloth.edges) == 3 * 3 + 4 * 2
    box = tandem.make_tet_box((0, 0, 0), (1, 2, 3), (1, 2, 3), 6.0)
    assert box.tetrahedra.shape == (5 * 6, 4) and box.node_count == 2 * 3 * 4
    np.testing.assert_allclose(box.masses.sum(), 6.0)
    # The tets fill the box: their volumes add up to 1 * 2 * 3.
    p = box.positions[box.tetrahedra]
    volumes = np.abs(np.einsum("ij,ij->i", p[:, 1] - p[:, 0], np.cross(p[:, 2] - p[:, 0], p[:, 3] - p[:, 0]))) / 6
    assert volumes.sum() == pytest.approx(6.0)
    cylinder = tandem.make_tet_cylinder((0, 0, 0), 0.1, 0.3, 2, 8, 3, 1.0)
    assert cylinder.positions[:, 1].min() == pytest.approx(0) and cylinder.positions[:, 1].max() == pytest.approx(0.3)
    assert np.linalg.norm(cylinder.positions[:, [0, 2]], axis=1).max() == pytest.approx(0.1)
    path = tandem.make_rope_along_path([(0, 0, 0), (1, 0, 0), (1, 1, 0)], 5, 1.0)
    np.testing.assert_allclose(path.positions[2], [1, 0, 0], atol=1e-12)
    tandem.validate_mesh(cylinder)


def test_meshes_from_files(scenes_dir):
    strip = tandem.load_obj(str(scenes_dir / "meshes" / "rope_strip.obj"), 0.2)
    assert strip.node_count == 50 and strip.masses.sum() == pytest.approx(0.2)
    with pytest.raises(tandem.Error, match="no_such.obj"):
        tandem.load_obj("no_such.obj", 1.0)


def test_a_mesh_built_from_arrays_and_a_tet_jelly_resting_on_the_floor():
    mesh = tandem.DeformableMesh()
    mesh.positions = [(0, 0, 0), (1, 0, 0), (0, 1, 0)]
    mesh.masses = [1, 1, 1]
    mesh.edges = [(0, 1), (1, 2), (2, 0)]
    mesh.triangles = np.array([[0, 1, 2]])
    tandem.validate_mesh(mesh)
    assert mesh.tetrahedra.shape == (0, 4)
    world = tandem.World()
    world.add_rigid_body(tandem.RigidBodyDesc(name="floor", shape=tandem.RigidShape.plane((0, 1, 0), 0),
                                              motion=tandem.MotionType.STATIC))
    jelly = world.add_deformable(tandem.DeformableDesc(
        name="jelly", mesh=tandem.make_tet_box((-0.1, 0.05, -0.1), (0.1, 0.25, 0.1), (2, 2, 2), 1.0),
        paradigm=tandem.ParadigmSettings(type=tandem.ParadigmType.COROTATIONAL_FEM, youngs_modulus=50e3),
        collision=tandem.CollisionSettings(thickness=0.005)))
    world.step(1.0 / 50, steps=50)
    positions = world.node_positions(jelly)
    assert positions[:, 1].min() >= 0.005 - 1e-3  # on the floor, not in it
    assert positions[:, 1].max() > 0.15  # and not flattened
    assert np.abs(world.node_velocities(jelly)).max() < 0.05
