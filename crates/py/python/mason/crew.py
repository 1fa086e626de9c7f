"""Crews and multi-agent path finding on grids.

Arrays: ``grid`` is a numpy bool array of shape (H, W), True where blocked; ``starts`` and
``goals`` are int arrays of shape (N, 2) holding (x, y) = (column, row), with (0, 0) at the
top left as in MovingAI; ``paths`` is an int array of shape (N, T, 2).
"""

from ._mason import crew as _crew

Solution = _crew.Solution
load_movingai = _crew.load_movingai
solve = _crew.solve
validate = _crew.validate

__all__ = ["Solution", "load_movingai", "solve", "validate"]
