#!/usr/bin/env python3
"""A rope holding a box: a 1 m, 0.2 kg rope hangs from a fixed point with a 1 kg box anchored to
its end. Prints how far the rope stretches, where the box settles and the anchor's force against
the box's weight.

    PYTHONPATH=build/python /usr/bin/python3 examples/python/rope_holding_box.py [--quick]
"""

import argparse

import numpy as np

import tandem

parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("--quick", action="store_true", help="simulate 1 s instead of 5 s")
args = parser.parse_args()

world = tandem.World()
nodes = 20
rope = world.add_deformable(tandem.DeformableDesc(
    name="rope",
    mesh=tandem.make_rope(start=(0, 2, 0), end=(0, 1, 0), node_count=nodes, total_mass=0.2),
    inextensibility=tandem.InextensibilitySettings(enabled=True)))
box = world.add_rigid_body(tandem.RigidBodyDesc(
    name="box", shape=tandem.RigidShape.box((0.1, 0.1, 0.1)), mass=1.0, position=(0, 0.9, 0), can_sleep=False))
top = world.add_fixed_point(rope, 0, target=(0, 2, 0))
knot = world.add_anchor(tandem.AnchorDesc.node(rope, nodes - 1, box))

h = 1.0 / 60
seconds = 1.0 if args.quick else 5.0
positions = world.node_positions(rope)  # a read-only view: it follows the world, no copying
edges = world.rest_mesh(rope).edges
rest_length = 1.0 / (nodes - 1)
worst_stretch = 0.0
for step in range(round(seconds / h)):
    world.step(h)
    lengths = np.linalg.norm(positions[edges[:, 1]] - positions[edges[:, 0]], axis=1)
    worst_stretch = max(worst_stretch, lengths.max() / rest_length - 1.0)

anchor = world.anchor_state(knot)
weight = world.rigid_mass(box) * -world.settings.gravity[1]
print(f"simulated {world.time:.2f} s in {world.step_count} steps")
print(f"worst edge stretch: {worst_stretch:.3%}")
print(f"box centre at y = {world.rigid_position(box)[1]:.4f} m (1 m of rope below y = 2: 0.9 m)")
print(f"anchor force on the box: {-anchor.impulse[1] / h:.3f} N up; the box's weight: {weight:.3f} N")
print(f"fixed point carries {world.fixed_point_impulse(top)[1] / h:.3f} N (rope and box: {1.2 * 9.81:.3f} N)")
