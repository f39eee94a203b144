#!/usr/bin/env python3
"""A point pendulum (1 m, released at 45 degrees, 10 s) stepped the ways Tandem's rows can be.

The energy a free swing keeps depends on how the constraint's drift is treated far more than on
the solver's convergence; this model, with nothing but the constraint, shows which treatment
costs what (docs/solver.md, twenty-eighth session). Each step: gravity, then the velocity row
|x| = L with J at the step's start, then x += h v, then the drift treatment:

  bias β     the velocity row aims at -β C / h (Baumgarte; Tandem's default β = 0.1),
  project    the position is put back on the circle, velocity unchanged (post-stabilisation),
  shake      the position is put back along the old radius and v = Δx / h (SHAKE: symplectic),
  rattle     SHAKE with gravity's kick split in halves around it and the velocity at the step's
             end projected onto the circle's tangent there (RATTLE): the same positions as
             SHAKE, but the velocity kept (and measured) is the one at the step's end, not the
             one half a kick before it.

Prints the least and the most energy (above rest) over the run, as fractions of the start's.

    /usr/bin/python3 bench/point_pendulum.py
"""
import math

G, LENGTH, RELEASE, SECONDS = 9.81, 1.0, math.radians(45.0), 10.0


def swing(h, treatment, beta=0.1):
    x = [LENGTH * math.sin(RELEASE), -LENGTH * math.cos(RELEASE)]
    v = [0.0, 0.0]
    rest = -G * LENGTH
    start = G * x[1] - rest
    least = most = 1.0
    kick = 0.5 * h * G if treatment == "rattle" else h * G
    for _ in range(round(SECONDS / h)):
        v[1] -= kick
        r = math.hypot(*x)
        n = [x[0] / r, x[1] / r]
        target = -beta * (r - LENGTH) / h if treatment == "bias" else 0.0
        if treatment not in ("shake", "rattle"):  # no velocity row: the projection carries the force
            radial = v[0] * n[0] + v[1] * n[1]
            v = [v[0] + (target - radial) * n[0], v[1] + (target - radial) * n[1]]
        moved = [x[0] + h * v[0], x[1] + h * v[1]]
        if treatment == "project":
            r = math.hypot(*moved)
            moved = [moved[0] * LENGTH / r, moved[1] * LENGTH / r]
        elif treatment in ("shake", "rattle"):  # moved + μ x on the circle: the larger root of a quadratic
            a = x[0] ** 2 + x[1] ** 2
            b = 2.0 * (moved[0] * x[0] + moved[1] * x[1])
            c = moved[0] ** 2 + moved[1] ** 2 - LENGTH ** 2
            mu = (-b + math.sqrt(b * b - 4.0 * a * c)) / (2.0 * a)
            moved = [moved[0] + mu * x[0], moved[1] + mu * x[1]]
            v = [(moved[0] - x[0]) / h, (moved[1] - x[1]) / h]
        if treatment == "rattle":  # the second half kick, then v on the tangent at the new x
            v[1] -= kick
            n = [moved[0] / LENGTH, moved[1] / LENGTH]
            radial = v[0] * n[0] + v[1] * n[1]
            v = [v[0] - radial * n[0], v[1] - radial * n[1]]
        x = moved
        energy = (G * x[1] + 0.5 * (v[0] ** 2 + v[1] ** 2) - rest) / start
        least, most = min(least, energy), max(most, energy)
    return least, most


def main():
    print(f"{'h (s)':>7}  {'treatment':<12} {'least':>7} {'most':>7}")
    for h in (0.02, 0.005):
        for name, treatment, beta in (("bias 0.1", "bias", 0.1), ("bias 1", "bias", 1.0),
                                      ("project", "project", 0.0), ("shake", "shake", 0.0),
                                      ("rattle", "rattle", 0.0)):
            least, most = swing(h, treatment, beta)
            print(f"{h:7.3f}  {name:<12} {least:7.4f} {most:7.4f}")


if __name__ == "__main__":
    main()
