#!/usr/bin/env python3
"""Writes Tandem's teapot: a closed, outward-wound triangle mesh in three OBJ objects.

    /usr/bin/python3 scripts/make_teapot.py scenes/meshes/teapot.obj

  body    a surface of revolution about +y from one profile curve: a flat foot, the belly, the
          rim, the lid's lip and dome and a ball knob, closed at both poles
  spout   a tube of shrinking radius swept along a curve in the x-y plane (+x side), its ends
          closed by flat caps; its root sits inside the body
  handle  a tube swept along a C-shaped curve (-x side), both ends capped inside the body

Each object is a closed surface on its own (every edge in exactly two triangles, used once each
way round) with positive volume; the script checks both before writing. Units are metres: the
teapot stands on y = 0, its axis is the y axis, 0.139 m tall and 0.26 m from spout tip to handle.
Every number comes from the curves below; nothing is copied from another teapot.
"""
import math
import sys

SEGMENTS_AROUND_BODY = 36
PROFILE_SAMPLES_PER_SPAN = 2
SPOUT_SIDES, SPOUT_RINGS = 14, 20
HANDLE_SIDES, HANDLE_RINGS = 10, 25

# Body profile (radius, height) from the bottom pole to the knob's top pole, through the foot,
# belly, rim, the lid's lip and dome, and the knob.
BODY_PROFILE = [
    (0.0, 0.0), (0.030, 0.0), (0.047, 0.0), (0.053, 0.002), (0.061, 0.010), (0.070, 0.026),
    (0.075, 0.044), (0.073, 0.062), (0.065, 0.078), (0.054, 0.089), (0.047, 0.094), (0.049, 0.096),
    (0.047, 0.100), (0.040, 0.108), (0.029, 0.115), (0.016, 0.119), (0.008, 0.121), (0.007, 0.124),
    (0.011, 0.127), (0.013, 0.131), (0.011, 0.135), (0.006, 0.138), (0.0, 0.139),
]
# Spout centre line (x, y) and the tube's radius at each control point, root to tip.
SPOUT_PATH = [(0.052, 0.026), (0.080, 0.034), (0.100, 0.052), (0.113, 0.078), (0.125, 0.100), (0.140, 0.112)]
SPOUT_RADIUS = [0.016, 0.014, 0.012, 0.0105, 0.009, 0.0085]
# Handle centre line (x, y), root at the top, and its constant radius.
HANDLE_PATH = [(-0.056, 0.080), (-0.085, 0.088), (-0.112, 0.074), (-0.118, 0.046), (-0.102, 0.022), (-0.060, 0.016)]
HANDLE_RADIUS = 0.0075


def catmull_rom(points, samples_per_span):
    """Points along the centripetal-free (uniform) Catmull-Rom spline through `points`,
    ends repeated: every control point is on the curve."""
    out = []
    padded = [points[0]] + list(points) + [points[-1]]
    for i in range(1, len(padded) - 2):
        p0, p1, p2, p3 = padded[i - 1], padded[i], padded[i + 1], padded[i + 2]
        for s in range(samples_per_span):
            t = s / samples_per_span
            t2, t3 = t * t, t * t * t
            out.append(tuple(0.5 * ((2 * b) + (-a + c) * t + (2 * a - 5 * b + 4 * c - d) * t2 + (-a + 3 * b - 3 * c + d) * t3)
                             for a, b, c, d in zip(p0, p1, p2, p3)))
    out.append(tuple(points[-1]))
    return out


class Mesh:
    def __init__(self):
        self.vertices = []
        self.objects = []  # (name, [(i, j, k), ...])

    def vertex(self, p):
        self.vertices.append(tuple(float(c) for c in p))
        return len(self.vertices) - 1


def add_revolution(mesh, profile, segments):
    """A closed surface of revolution about +y; the profile starts and ends on the axis."""
    triangles = []
    rings = []
    for r, y in profile:
        if r == 0.0:
            rings.append([mesh.vertex((0.0, y, 0.0))] * segments)
        else:
            rings.append([mesh.vertex((r * math.cos(2 * math.pi * s / segments), y,
                                       -r * math.sin(2 * math.pi * s / segments))) for s in range(segments)])
    for lower, upper in zip(rings, rings[1:]):
        for s in range(segments):
            a, b = lower[s], lower[(s + 1) % segments]
            c, d = upper[s], upper[(s + 1) % segments]
            if a != b:
                triangles.append((a, b, d))
            if c != d:
                triangles.append((a, d, c))
    return triangles


def add_tube(mesh, path, radii, sides):
    """A tube swept along a curve in the x-y plane (ring frames: the in-plane normal and z),
    closed by a flat cap at each end."""
    triangles = []
    rings = []
    for i, (centre, radius) in enumerate(zip(path, radii)):
        a, b = path[max(i - 1, 0)], path[min(i + 1, len(path) - 1)]
        tx, ty = b[0] - a[0], b[1] - a[1]
        length = math.hypot(tx, ty)
        tx, ty = tx / length, ty / length
        nx, ny = -ty, tx  # in-plane normal; (n, z, t) is right-handed
        rings.append([mesh.vertex((centre[0] + radius * (math.cos(2 * math.pi * s / sides) * nx),
                                   centre[1] + radius * (math.cos(2 * math.pi * s / sides) * ny),
                                   radius * math.sin(2 * math.pi * s / sides))) for s in range(sides)])
    for lower, upper in zip(rings, rings[1:]):
        for s in range(sides):
            a, b = lower[s], lower[(s + 1) % sides]
            c, d = upper[s], upper[(s + 1) % sides]
            triangles += [(a, d, b), (a, c, d)]
    start = mesh.vertex((path[0][0], path[0][1], 0.0))
    end = mesh.vertex((path[-1][0], path[-1][1], 0.0))
    for s in range(sides):
        triangles.append((start, rings[0][s], rings[0][(s + 1) % sides]))
        triangles.append((end, rings[-1][(s + 1) % sides], rings[-1][s]))
    return triangles


def signed_volume(vertices, triangles):
    volume = 0.0
    for i, j, k in triangles:
        a, b, c = vertices[i], vertices[j], vertices[k]
        volume += (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
                   a[2] * (b[0] * c[1] - b[1] * c[0])) / 6.0
    return volume


def check_closed(name, triangles):
    directed = {}
    for t in triangles:
        for e in ((t[0], t[1]), (t[1], t[2]), (t[2], t[0])):
            directed[e] = directed.get(e, 0) + 1
    for (i, j), count in directed.items():
        if count != 1 or directed.get((j, i), 0) != 1:
            raise SystemExit(f"make_teapot: {name}: edge ({i}, {j}) is not shared by exactly two triangles wound "
                             "opposite ways")


def make_teapot():
    mesh = Mesh()
    profile = catmull_rom(BODY_PROFILE, PROFILE_SAMPLES_PER_SPAN)
    profile = [(0.0 if i in (0, len(profile) - 1) else max(r, 1e-4), y) for i, (r, y) in enumerate(profile)]
    parts = [("body", add_revolution(mesh, profile, SEGMENTS_AROUND_BODY))]
    spout_path = catmull_rom(SPOUT_PATH, SPOUT_RINGS // (len(SPOUT_PATH) - 1))
    spout_radius = [r for r, in catmull_rom([(r,) for r in SPOUT_RADIUS], SPOUT_RINGS // (len(SPOUT_PATH) - 1))]
    parts.append(("spout", add_tube(mesh, spout_path, spout_radius, SPOUT_SIDES)))
    handle_path = catmull_rom(HANDLE_PATH, HANDLE_RINGS // (len(HANDLE_PATH) - 1))
    parts.append(("handle", add_tube(mesh, handle_path, [HANDLE_RADIUS] * len(handle_path), HANDLE_SIDES)))
    for name, triangles in parts:
        if signed_volume(mesh.vertices, triangles) < 0:  # wound inwards: turn every triangle round
            triangles[:] = [(i, k, j) for i, j, k in triangles]
        check_closed(name, triangles)
        if not signed_volume(mesh.vertices, triangles) > 0:
            raise SystemExit(f"make_teapot: {name} has no volume")
    mesh.objects = parts
    return mesh


def main():
    if len(sys.argv) != 2:
        raise SystemExit("usage: make_teapot.py OUT.obj")
    mesh = make_teapot()
    triangles = sum(len(t) for _, t in mesh.objects)
    with open(sys.argv[1], "w") as out:
        out.write("# Tandem's teapot, made by scripts/make_teapot.py (a closed, outward-wound surface per object).\n")
        out.write(f"# {len(mesh.vertices)} vertices, {triangles} triangles; metres, standing on y = 0 about the y axis.\n")
        for name, parts_triangles in mesh.objects:
            out.write(f"# {name}: {len(parts_triangles)} triangles, {signed_volume(mesh.vertices, parts_triangles) * 1e6:.1f} cm^3\n")
        for x, y, z in mesh.vertices:
            out.write(f"v {x:.6f} {y:.6f} {z:.6f}\n")
        for name, parts_triangles in mesh.objects:
            out.write(f"o {name}\n")
            for i, j, k in parts_triangles:
                out.write(f"f {i + 1} {j + 1} {k + 1}\n")


if __name__ == "__main__":
    main()
