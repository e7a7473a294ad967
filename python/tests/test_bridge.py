"""Bridge edge loops and grid fill."""

import numpy as np
import pytest

import meshloom
from conftest import grid_arrays


def strips():
    """Two strips of 3 quads at y in [0, 1] and [2, 3]; the chains facing
    each other at y = 1 and y = 2."""
    p = np.array([[x, y, 0.0] for y in range(4) for x in range(4)], dtype=float)
    quad = lambda i: [i, i + 1, i + 5, i + 4]
    faces = np.array([quad(0), quad(1), quad(2), quad(8), quad(9), quad(10)], dtype=np.int64)
    mesh = meshloom.Mesh.from_arrays(p, faces)

    def chain(y):
        out = []
        for e in mesh.edges:
            ps = [v.position for v in e.vertices]
            if all(q[1] == y for q in ps):
                out.append(e)
        return out

    return mesh, chain(1.0), chain(2.0)


def test_bridge_two_chains_with_cuts():
    mesh, a, b = strips()
    made = mesh.bridge_loops(a, b, cuts=1)
    mesh.validate()
    assert len(made["faces"]) == 6 and len(made["vertices"]) == 4
    assert not made["closed"] and len(made["holes"]) == 1
    assert mesh.face_count == 12 and mesh.hole_count == 1


def test_bridge_refusals_change_nothing():
    mesh, a, b = strips()
    before = mesh.copy()
    with pytest.raises(meshloom.RefusedError):
        mesh.bridge_loops(a, a)
    with pytest.raises(meshloom.RefusedError):
        mesh.bridge_loops([a[0], a[2]], b)
    assert mesh == before


def test_grid_fill_of_a_four_by_four_hole():
    mesh = meshloom.Mesh.from_arrays(*grid_arrays(6))
    middle = [
        f
        for f in mesh.faces
        if all(1.0 <= c <= 5.0 for v in f.vertices for c in v.position[:2])
    ]
    assert len(middle) == 16
    for f in middle:
        mesh.remove_face(f)
    (hole,) = [h for h in mesh.holes if h.degree == 16]
    made = mesh.grid_fill(hole)
    mesh.validate()
    assert len(made["faces"]) == 16 and len(made["vertices"]) == 9
    assert made["span"] == 4
    assert mesh.face_count == 36


def test_grid_fill_refuses_an_odd_hole_or_a_bad_span():
    mesh = meshloom.Mesh.from_arrays(*grid_arrays(3))
    centre = [f for f in mesh.faces if all(1.0 <= c <= 2.0 for v in f.vertices for c in v.position[:2])]
    mesh.remove_face(centre[0])
    hole = [h for h in mesh.holes if h.degree == 4][0]
    before = mesh.copy()
    with pytest.raises(meshloom.RefusedError):
        mesh.grid_fill(hole, span=2)
    assert mesh == before
    made = mesh.grid_fill(hole, span=1)
    assert len(made["faces"]) == 1
