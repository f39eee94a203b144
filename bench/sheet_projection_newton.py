"""The sheet projection's Newton step of the edges' lengths, solved exactly, on a draped cloth.

A study for docs/solver.md (thirty-fifth session): does the Gauss-Newton step that
`projectSheetEdgesTogether` (src/solver/strain_limiting.h) takes converge when its linear system
is solved exactly (a sparse LU, not the step's conjugate gradients)? The script steps one of the
cloth-on-sphere scenes through the Python bindings, takes its nodes' positions (at the end of a
step, or predicted one step on, x + h (v + h g)), and applies exact Newton steps

    (J W Jᵀ) δλ = clamp(ℓ, 0.99 L, 1.01 L) − ℓ,   Δx = W Jᵀ δλ,

W = w (I − s sᵀ) for nodes within 1.5 thicknesses of the sphere (held to its tangent plane, as
the step holds them) or w I with --free, printing each step's largest edge error, the edges past
1.1 %, the moves and how deep nodes go into the sphere.

    PYTHONPATH=build/python /usr/bin/python3 bench/sheet_projection_newton.py --size 201 --time 0.8 --end
    (needs python3-scipy; a 201 x 201 step takes about 25 s)
"""
import argparse
import pathlib

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spl
import tandem

ROOT = pathlib.Path(__file__).resolve().parent.parent


def scene_file(size):
    return ROOT / ("scenes/cloth_sphere.json" if size == 51 else f"scenes/gauntlet/cloth_sphere_{size}.json")


def edge_lengths(x, edges):
    return np.linalg.norm(x[edges[:, 1]] - x[edges[:, 0]], axis=1)


def newton_step(x, edges, rest, weight, held_normal):
    """One exact Gauss-Newton step of the lengths; returns the moves and the linear residual."""
    d = x[edges[:, 1]] - x[edges[:, 0]]
    length = np.linalg.norm(d, axis=1)
    n = d / length[:, None]
    target = np.clip(length, 0.99 * rest, 1.01 * rest) - length
    rows = np.repeat(np.arange(len(edges)), 6)
    columns = np.concatenate([3 * edges[:, [0]] + np.arange(3), 3 * edges[:, [1]] + np.arange(3)], 1).ravel()
    jacobian = sp.csr_matrix((np.concatenate([-n, n], 1).ravel(), (rows, columns)), shape=(len(edges), 3 * len(x)))
    blocks = weight[:, None, None] * (np.eye(3)[None] - held_normal[:, :, None] * held_normal[:, None, :])
    response = sp.block_diag(list(blocks), format="csr")
    system = (jacobian @ response @ jacobian.T).tocsc()
    impulse = spl.spsolve(system, target)
    residual = np.linalg.norm(system @ impulse - target) / np.linalg.norm(target)
    return (response @ (jacobian.T @ impulse)).reshape(-1, 3), residual


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--size", type=int, default=101, choices=[51, 101, 201])
    parser.add_argument("--time", type=float, default=0.6, help="seconds stepped before the study")
    parser.add_argument("--end", action="store_true", help="start from the step's end, not the prediction")
    parser.add_argument("--free", action="store_true", help="no node held to the sphere's tangent plane")
    parser.add_argument("--steps", type=int, default=4, help="Newton steps")
    args = parser.parse_args()

    scene = tandem.load_scene(str(scene_file(args.size)))
    world = scene.build()
    h = scene.time_step
    cloth = world.deformable_ids()[0]
    sphere = world.find_rigid_body("sphere")
    centre = np.array(world.rigid_position(sphere))
    radius = world.rigid_shape(sphere).radius
    thickness = scene.deformables[0].desc.collision.thickness
    for _ in range(round(args.time / h)):
        world.step(h)
    x = np.array(world.node_positions(cloth))
    v = np.array(world.node_velocities(cloth))
    weight = np.array(world.node_inverse_masses(cloth))
    mesh = world.rest_mesh(cloth)
    edges = np.array(mesh.edges)
    rest = edge_lengths(np.array(mesh.positions), edges)
    if not args.end:
        x = x + h * (v + h * np.array(world.settings.gravity))

    radial = x - centre
    distance = np.linalg.norm(radial, axis=1)
    held = (distance < radius + 1.5 * thickness) & (not args.free)
    held_normal = np.where(held[:, None], radial / distance[:, None], 0.0)

    stretch = edge_lengths(x, edges) / rest - 1
    print(f"{args.size} x {args.size} at {args.time} s ({'step end' if args.end else 'predicted'}, "
          f"{'free' if args.free else 'held'}): worst {stretch.max():.4f}, "
          f"{(stretch > 0.011).sum()} of {len(edges)} edges past 1.1 %")
    start = x.copy()
    for step in range(args.steps):
        move, residual = newton_step(x, edges, rest, weight, held_normal)
        x = x + move
        stretch = edge_lengths(x, edges) / rest - 1
        moved = np.linalg.norm(move, axis=1)
        depth = radius + thickness - np.linalg.norm(x - centre, axis=1)
        print(f"  step {step}: worst {stretch.max():.4f}, {(stretch > 0.011).sum()} past; largest move "
              f"{1e3 * moved.max():.2f} mm (median {1e3 * np.median(moved):.3f}); deepest in the sphere "
              f"{1e3 * depth.max():.2f} mm; linear residual {residual:.1e}")
    print(f"  moved in all: largest {1e3 * np.linalg.norm(x - start, axis=1).max():.2f} mm")


if __name__ == "__main__":
    main()
