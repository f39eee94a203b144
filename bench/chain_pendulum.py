#!/usr/bin/env python3
"""A rope pendulum as a pinned chain of point masses, its last node carrying the load, stepped at
h = 20 ms with the end-of-step treatments bench/point_pendulum.py compares on a single mass:

  shake      gravity's whole kick, then the positions x + h v put back on every edge's length
             along the edges' directions at the step's start (SHAKE; damped Newton from λ = 0),
             and v = Δx / h;
  rattle     the same with gravity's kick split in halves around it and the end velocity
             projected onto the edges' tangent at the new positions (RATTLE);
  pbd-...    the positions put back along the edges' current directions instead (a position
             projection iterated to convergence, as a direct block's projection does once), then
             v = Δx / h, without or with RATTLE's split kick and end projection.

The free swing (20 nodes, 0.1 kg, a 1 kg load, from 45°) and the heavy pendulum (30 nodes, 30 g,
500 kg, from 60°) of the gauntlet, in 2-D, the load a point at the rope's end. Prints the least
and the most energy (above rest) as fractions of the start's, the worst edge error, the
period, and how many Newton steps the hardest step took (docs/solver.md, thirty-sixth session).

    /usr/bin/python3 bench/chain_pendulum.py
"""
import math

import numpy as np

GRAVITY = np.array([0.0, -9.81])


def chain(nodes, rope_mass, load, angle):
    direction = np.array([math.sin(angle), -math.cos(angle)])
    x = np.array([i / (nodes - 1) * direction for i in range(nodes)])  # a 1 m rope
    mass = np.full(nodes, rope_mass / nodes)
    mass[-1] += load
    w = 1.0 / mass
    w[0] = 0.0  # pinned
    return x, w, np.linalg.norm(x[1:] - x[:-1], axis=1)


def jacobian(x):  # edges × node coordinates
    d = x[1:] - x[:-1]
    n = d / np.linalg.norm(d, axis=1)[:, None]
    j = np.zeros((len(d), x.size))
    for i in range(len(d)):
        j[i, 2 * i:2 * i + 2], j[i, 2 * i + 2:2 * i + 4] = -n[i], n[i]
    return j


def error(x, rest):
    return np.linalg.norm(x[1:] - x[:-1], axis=1) - rest


def put_back(x, v, w, rest, h, along_start):
    """The end-of-step positions with every edge at its length; the Newton steps taken."""
    weights = np.repeat(w, 2)
    moved = x + h * v
    if not along_start:  # along the current directions, to convergence
        for steps in range(100):
            r = error(moved, rest)
            if np.max(np.abs(r)) < 1e-10:
                return moved, steps
            j = jacobian(moved)
            moved = moved + (weights * (j.T @ np.linalg.solve(j @ (weights[:, None] * j.T), -r))).reshape(-1, 2)
        return moved, 100
    j0 = jacobian(x)  # along the start's directions: x + h v + W J₀ᵀ λ, damped Newton on λ
    lam = np.zeros(len(rest))

    def at(l):
        end = moved + (weights * (j0.T @ l)).reshape(-1, 2)
        return end, error(end, rest)

    end, r = at(lam)
    for steps in range(100):
        if np.max(np.abs(r)) < 1e-10:
            return end, steps
        d = np.linalg.solve(jacobian(end) @ (weights[:, None] * j0.T), r)
        t = 1.0
        while t > 1e-4:
            trial, rt = at(lam - t * d)
            if np.linalg.norm(rt) < (1 - 0.5 * t) * np.linalg.norm(r):
                break
            t *= 0.5
        lam -= t * d
        end, r = trial, rt
    return end, 100


def step(x, v, w, rest, h, treatment):
    split = treatment.endswith("rattle")
    kick = (0.5 if split else 1.0) * h * GRAVITY * (w > 0)[:, None]
    end, steps = put_back(x, v + kick, w, rest, h, along_start=not treatment.startswith("pbd"))
    v = (end - x) / h
    if split:
        v = v + kick
        weights = np.repeat(w, 2)
        j = jacobian(end)
        mu = np.linalg.solve(j @ (weights[:, None] * j.T), -(j @ v.ravel()))
        v = (v.ravel() + weights * (j.T @ mu)).reshape(-1, 2)
    return end, v, steps


def energy(x, v, w):
    mass = np.where(w > 0, 1.0 / np.where(w > 0, w, 1.0), 0.0)
    return float(np.sum(0.5 * mass * np.sum(v * v, axis=1)) - np.sum(mass * (x @ GRAVITY)))


def swing(nodes, rope_mass, load, angle, treatment, h=0.02, seconds=10.0):
    x, w, rest = chain(nodes, rope_mass, load, angle)
    v = np.zeros_like(x)
    hanging, _, _ = chain(nodes, rope_mass, load, 0.0)
    rest_energy = energy(hanging, v, w)
    start = energy(x, v, w) - rest_energy
    least = most = 1.0
    worst, hardest, crossings, previous = 0.0, 0, [], x[-1, 0]
    for k in range(round(seconds / h)):
        x, v, steps = step(x, v, w, rest, h, treatment)
        if not np.all(np.isfinite(x)) or np.max(np.abs(x)) > 1e3:
            return f"diverged at step {k}"
        e = (energy(x, v, w) - rest_energy) / start
        least, most = min(least, e), max(most, e)
        worst = max(worst, float(np.max(np.abs(error(x, rest)) / rest)))
        hardest = max(hardest, steps)
        if previous > 0 >= x[-1, 0]:
            crossings.append((k + 1) * h)
        previous = x[-1, 0]
    period = np.mean(np.diff(crossings)) if len(crossings) > 1 else float("nan")
    return f"energy {least:7.4f} .. {most:7.4f}, worst edge {worst:.1e}, period {period:.3f} s, Newton steps <= {hardest}"


def main():
    for treatment in ("shake", "rattle", "pbd", "pbd-rattle"):
        print(f"free swing     {treatment:<11} {swing(20, 0.1, 1.0, math.radians(45), treatment)}")
        print(f"heavy pendulum {treatment:<11} {swing(30, 0.03, 500.0, math.radians(60), treatment)}")


if __name__ == "__main__":
    main()
