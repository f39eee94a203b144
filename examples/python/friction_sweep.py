#!/usr/bin/env python3
"""A sweep over friction on the rope over a wheel (scenes/rope_wheel.json, the paper's Fig. 4): a
1.3 kg and a 1 kg body hang from a rope strip over a hinged wheel. With enough friction the rope
grips the wheel and turns it (no slip); with little, the rope slides over a wheel that hardly
turns. For each friction coefficient of the rope, prints how far the heavy body fell, how far the
wheel's rim turned, and the slip between them (measured after 0.2 s in which the strip settles
onto the wheel); plots them against friction.

    PYTHONPATH=build/python MPLBACKEND=Agg /usr/bin/python3 examples/python/friction_sweep.py \\
        [--quick] [--out friction_sweep.png]
"""

import argparse
import os
import pathlib

import matplotlib

if "MPLBACKEND" not in os.environ:
    matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import tandem  # noqa: E402

SCENES = pathlib.Path(__file__).resolve().parents[2] / "scenes"

parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("--quick", action="store_true", help="three values for 1 s (for tests)")
parser.add_argument("--seconds", type=float, default=None, help="simulated seconds per run (default 2)")
parser.add_argument("--out", default="friction_sweep.png", help="the plot (PNG)")
args = parser.parse_args()

frictions = [0.0, 0.2, 0.9] if args.quick else [0.0, 0.02, 0.05, 0.1, 0.2, 0.4, 0.9]
seconds = args.seconds or (1.0 if args.quick else 2.0)

print(f"{'rope friction':>13} {'contact mu':>10} {'heavy fell (m)':>14} {'rim turned (m)':>14} {'slip (m)':>9}")
rows = []
for friction in frictions:
    scene = tandem.load_scene(str(SCENES / "rope_wheel.json"))
    rope = scene.deformables[0]
    rope.desc.collision.friction = friction  # a contact's mu is the product of both sides'
    wheel_friction = next(b.desc.friction for b in scene.rigid_bodies if b.desc.name == "wheel")
    world = scene.build()
    heavy, wheel = world.find_rigid_body("heavy"), world.find_rigid_body("wheel")
    radius = world.rigid_shape(wheel).radius
    world.step(scene.time_step, steps=10)  # the strip settles onto the wheel
    start = world.rigid_position(heavy)[1]
    turned = 0.0
    for _ in range(round(seconds / scene.time_step)):
        world.step(scene.time_step)
        turned += -world.rigid_angular_velocity(wheel)[2] * scene.time_step  # clockwise: heavy side down
    fell = start - world.rigid_position(heavy)[1]
    rim = turned * radius
    rows.append((friction, fell, rim))
    print(f"{friction:13.2f} {friction * wheel_friction:10.3f} {fell:14.4f} {rim:14.4f} {fell - rim:9.4f}")

figure, axes = plt.subplots(figsize=(7, 4), dpi=100)
axes.plot([r[0] for r in rows], [r[1] - r[2] for r in rows], "o-", label="slip: fall - rim travel (m)")
axes.plot([r[0] for r in rows], [r[1] for r in rows], "s--", label="heavy body fell (m)")
axes.plot([r[0] for r in rows], [r[2] for r in rows], "^:", label="wheel rim turned (m)")
axes.set_xlabel("rope friction coefficient")
axes.set_ylabel(f"metres after {seconds:g} s")
axes.set_title("rope over a wheel: friction sweep")
axes.grid(True, alpha=0.3)
axes.legend()
figure.tight_layout()
pathlib.Path(args.out).parent.mkdir(parents=True, exist_ok=True)
figure.savefig(args.out)
print(f"wrote {args.out}")
