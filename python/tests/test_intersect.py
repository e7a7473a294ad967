"""Mesh.self_intersections(): none on a closed cube, the crossing faces of
two tetrahedra pushed into each other, and an empty (0, 2) array when clean."""

import numpy as np

import meshloom

TET_P = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]
TET_F = [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]]


def two_tetrahedra(shift):
    p = np.array(TET_P + [[x + shift for x in q] for q in TET_P])
    f = np.array(TET_F + [[i + 4 for i in t] for t in TET_F])
    return meshloom.Mesh.from_arrays(p, f)


def test_clean_meshes_give_an_empty_array():
    pairs = two_tetrahedra(2.0).self_intersections()
    assert pairs.shape == (0, 2)
    assert pairs.dtype == np.int64
    cube_p = np.array([[x, y, z] for z in (0.0, 1.0) for y in (0.0, 1.0) for x in (0.0, 1.0)])
    cube_f = np.array(
        [[0, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [2, 6, 7, 3], [0, 4, 6, 2], [1, 3, 7, 5]]
    )
    assert meshloom.Mesh.from_arrays(cube_p, cube_f).self_intersections().shape == (0, 2)


def test_crossing_tetrahedra_name_faces_of_both():
    pairs = two_tetrahedra(0.2).self_intersections()
    assert pairs.ndim == 2 and pairs.shape[1] == 2
    assert len(pairs) >= 3
    # Each row pairs a face of the first tetrahedron with one of the second,
    # sorted and without repeats.
    assert np.all(pairs[:, 0] < 4) and np.all((pairs[:, 1] >= 4) & (pairs[:, 1] < 8))
    rows = [tuple(r) for r in pairs.tolist()]
    assert rows == sorted(set(rows))
