"""Construction from numpy arrays and lists, export back, triangle buffers."""

import numpy as np
import pytest

import meshloom
from conftest import grid_arrays


def test_numpy_round_trip_is_exact():
    rng = np.random.default_rng(7)
    positions, faces = grid_arrays(20)
    positions = positions + rng.random(positions.shape)  # bits beyond printing
    mesh = meshloom.Mesh.from_arrays(positions, faces)
    p, f = mesh.to_arrays()
    assert p.dtype == np.float64 and p.shape == positions.shape
    assert np.array_equal(p.view(np.uint64), positions.view(np.uint64))
    assert f.dtype == np.int64
    assert np.array_equal(f, faces)


def test_lists_and_int32_arrays_build_the_same_mesh():
    positions, faces = grid_arrays(4)
    a = meshloom.Mesh.from_arrays(positions, faces)
    b = meshloom.Mesh.from_arrays(positions.tolist(), faces.tolist())
    c = meshloom.Mesh.from_arrays(positions, faces.astype(np.int32))
    assert a == b == c


def test_ngons_of_mixed_degree_come_back_as_lists():
    p = [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [2, 0.5, 0]]
    mesh = meshloom.Mesh.from_arrays(p, [[0, 1, 2, 3], [1, 4, 2]])
    assert (mesh.face_count, mesh.hole_count) == (2, 1)
    _, faces = mesh.to_arrays()
    assert faces == [[0, 1, 2, 3], [1, 4, 2]]
    _, indices, offsets = mesh.to_buffers()
    assert indices.tolist() == [0, 1, 2, 3, 1, 4, 2]
    assert offsets.tolist() == [0, 4, 7]


def test_halfedge_style_vertex_list_and_face_index_set():
    # The halfedge package builds from a vertex list and a set of index tuples.
    vl = [(0, 0), (1, 0), (1, 1), (0, 1)]
    vi = {(0, 1, 2), (0, 2, 3)}
    positions = [(x, y, 0.0) for x, y in vl]
    mesh = meshloom.Mesh.from_arrays(positions, sorted(vi))
    assert (mesh.vertex_count, mesh.edge_count, mesh.face_count, mesh.hole_count) == (4, 5, 2, 1)


def test_bad_input_raises_build_error_naming_the_face():
    p = np.zeros((3, 3))
    with pytest.raises(meshloom.BuildError) as err:
        meshloom.Mesh.from_arrays(p, [[0, 1, 7]])
    assert err.value.face == 0
    assert err.value.kind == "index_out_of_range"
    with pytest.raises(meshloom.BuildError) as err:
        meshloom.Mesh.from_arrays(np.zeros((4, 3)), [[0, 1, 2], [0, 1, 3]])
    assert err.value.kind == "inconsistent_orientation"
    with pytest.raises(ValueError):
        meshloom.Mesh.from_arrays(np.zeros((4, 2)), [[0, 1, 2]])


def test_triangle_buffers_are_numpy_arrays():
    positions, faces = grid_arrays(2)
    mesh = meshloom.Mesh.from_arrays(positions, faces)
    b = mesh.triangle_buffers()
    assert b["positions"].dtype == np.float32 and b["positions"].shape[1] == 3
    assert b["normals"].shape == b["positions"].shape
    assert b["indices"].shape == (8, 3)  # 4 quads, 2 triangles each
    assert b["indices"].max() < len(b["positions"])
    assert np.allclose(b["normals"], [0, 0, 1])
    no_normals = mesh.triangle_buffers(normals=False)
    assert "normals" not in no_normals
    assert len(no_normals["triangle_faces"]) == 8
