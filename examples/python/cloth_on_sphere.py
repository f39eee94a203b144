#!/usr/bin/env python3
"""The paper's cloth on a sphere (scenes/cloth_sphere.json): a 51x51 inextensible cloth dropped on a
rigid sphere. Records the cloth's edge stretch (worst and mean) and its closest approach to the
sphere every step, and plots the stretch over time into a PNG.

    PYTHONPATH=build/python MPLBACKEND=Agg /usr/bin/python3 examples/python/cloth_on_sphere.py \\
        [--quick] [--seconds S] [--out cloth_stretch.png]
"""

import argparse
import os
import pathlib

import matplotlib

if "MPLBACKEND" not in os.environ:
    matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import tandem  # noqa: E402

SCENES = pathlib.Path(__file__).resolve().parents[2] / "scenes"

parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("--quick", action="store_true", help="1.5 s: the drop and the landing (for tests)")
parser.add_argument("--seconds", type=float, default=None, help="simulated seconds (default 3, quick 1.5)")
parser.add_argument("--out", default="cloth_stretch.png", help="the plot (PNG)")
args = parser.parse_args()

scene = tandem.load_scene(str(SCENES / "cloth_sphere.json"))
seconds = args.seconds or (1.5 if args.quick else 3.0)
world = scene.build()
cloth = world.find_deformable("cloth")
sphere = world.find_rigid_body("sphere")
radius = world.rigid_shape(sphere).radius
centre = world.rigid_position(sphere)

edges = world.rest_mesh(cloth).edges
rest = world.rest_mesh(cloth).positions
rest_lengths = np.linalg.norm(rest[edges[:, 1]] - rest[edges[:, 0]], axis=1)
positions = world.node_positions(cloth)

times, worst, mean, clearance = [], [], [], []
for _ in range(round(seconds / scene.time_step)):
    world.step(scene.time_step)
    strain = np.linalg.norm(positions[edges[:, 1]] - positions[edges[:, 0]], axis=1) / rest_lengths - 1.0
    times.append(world.time)
    worst.append(100 * strain.max())
    mean.append(100 * np.abs(strain).mean())
    clearance.append(np.linalg.norm(positions - centre, axis=1).min() - radius)

print(f"{len(positions)} nodes, {len(edges)} edges, {world.step_count} steps of {scene.time_step} s")
print(f"edge stretch at the end: worst {worst[-1]:.2f} %, mean {mean[-1]:.3f} %; worst over the run {max(worst):.2f} %")
print(f"closest approach to the sphere's surface: {1000 * min(clearance):.2f} mm "
      f"(thickness {1000 * scene.deformables[0].desc.collision.thickness:.1f} mm); contacts now: {len(world.contacts())}")

figure, axes = plt.subplots(figsize=(7, 4), dpi=100)
axes.plot(times, worst, label="worst edge")
axes.plot(times, mean, label="mean |strain|")
axes.set_xlabel("time (s)")
axes.set_ylabel("edge stretch (%)")
axes.set_title(f"cloth on a sphere: {int(np.sqrt(len(positions)))}x{int(np.sqrt(len(positions)))} nodes")
axes.grid(True, alpha=0.3)
axes.legend()
figure.tight_layout()
pathlib.Path(args.out).parent.mkdir(parents=True, exist_ok=True)
figure.savefig(args.out)
print(f"wrote {args.out}")
