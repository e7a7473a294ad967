import numpy as np
import pytest

import meshloom


def grid_arrays(n):
    """An n x n grid of quads: (n+1)^2 vertices."""
    xs, ys = np.meshgrid(np.arange(n + 1, dtype=float), np.arange(n + 1, dtype=float))
    positions = np.column_stack([xs.ravel(), ys.ravel(), np.zeros((n + 1) ** 2)])
    faces = []
    for j in range(n):
        for i in range(n):
            a = j * (n + 1) + i
            faces.append([a, a + 1, a + n + 2, a + n + 1])
    return positions, np.array(faces, dtype=np.int64)


@pytest.fixture
def grid3():
    """The halfedge package's 3 x 3 grid of quads."""
    return meshloom.Mesh.from_arrays(*grid_arrays(3))


@pytest.fixture
def square():
    """Two triangles sharing an edge, as the Rust README builds them."""
    p = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]]
    return meshloom.Mesh.from_arrays(p, [[0, 1, 2], [0, 2, 3]])
