"""Shared pieces of the Python tests: where the scenes are, and small scene builders."""

import pathlib

import numpy as np
import pytest

import tandem

SOURCE_DIR = pathlib.Path(__file__).resolve().parents[2]
SCENES = SOURCE_DIR / "scenes"
G = 9.81


@pytest.fixture
def scenes_dir():
    return SCENES


def hanging_rope_with_box(world, nodes=20, rope_mass=0.2, box_mass=1.0):
    """The README's rope: 1 m from (0, 2, 0) down, a box anchored at its lower end."""
    rope = world.add_deformable(tandem.DeformableDesc(
        name="rope", mesh=tandem.make_rope((0, 2, 0), (0, 1, 0), nodes, rope_mass),
        inextensibility=tandem.InextensibilitySettings(enabled=True)))
    box = world.add_rigid_body(tandem.RigidBodyDesc(
        name="box", shape=tandem.RigidShape.box((0.1, 0.1, 0.1)), mass=box_mass, position=(0, 0.9, 0),
        can_sleep=False))
    top = world.add_fixed_point(rope, 0, (0, 2, 0))
    knot = world.add_anchor(tandem.AnchorDesc.node(rope, nodes - 1, box))
    return rope, box, top, knot


def edge_strains(positions, edges, rest_lengths):
    lengths = np.linalg.norm(positions[edges[:, 1]] - positions[edges[:, 0]], axis=1)
    return lengths / rest_lengths - 1.0
