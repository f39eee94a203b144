"""Tandem: rigid (Bullet) and deformable bodies simulated together with two-way coupling.

SI units (m, kg, s, N; impulses N*s). Vectors are NumPy arrays of 3 floats (any sequence of 3
numbers is accepted); quaternions are 4 floats (w, x, y, z). The library's errors are raised as
tandem.Error with the library's message. Node positions and velocities are read-only NumPy views
of the world's own memory (World.node_positions). See docs/python.md.
"""

from tandem._tandem import *  # noqa: F401,F403
from tandem._tandem import __version__  # noqa: F401

__all__ = [name for name in dir() if not name.startswith("_")]
