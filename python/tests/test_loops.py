"""Edge loops, edge rings and face loops selected from one edge."""

import pytest

import meshloom
from conftest import grid_arrays


def test_grid_loops_run_side_to_side_and_rings_cross_the_quads():
    n = 4
    mesh = meshloom.Mesh.from_arrays(*grid_arrays(n))
    for e in mesh.edges:
        run = mesh.edge_loop(e)
        assert e in run and len(run) == n
        # End to end: consecutive edges share a vertex.
        for a, b in zip(run, run[1:]):
            assert set(a.vertices) & set(b.vertices)
        ring = mesh.edge_ring(e)
        assert e in ring and len(ring) == n + 1
        faces = mesh.face_loop(e)
        assert len(faces) == n
        for (a, b), f in zip(zip(ring, ring[1:]), faces):
            assert a in f.edges and b in f.edges


def test_loops_refuse_stale_edges_and_change_nothing():
    mesh = meshloom.Mesh.from_arrays(*grid_arrays(2))
    before = mesh.copy()
    e = mesh.edges[0]
    assert mesh.edge_loop(e) and mesh == before
    f = [f for f in e.faces if f is not None][0]
    mesh.remove_face(f)
    if e not in mesh.edges:
        for call in (mesh.edge_loop, mesh.edge_ring, mesh.face_loop):
            with pytest.raises(meshloom.StaleKeyError):
                call(e)


def test_loop_cut_adds_the_loops_and_refusals_change_nothing():
    n, cuts = 4, 3
    mesh = meshloom.Mesh.from_arrays(*grid_arrays(n))
    v0, f0 = mesh.vertex_count, mesh.face_count
    e = [e for e in mesh.edges if None not in e.faces][0]
    before = mesh.copy()
    with pytest.raises(meshloom.RefusedError):
        mesh.loop_cut(e, cuts=0)
    with pytest.raises(meshloom.RefusedError):
        mesh.loop_cut(e, factor=1.0)
    assert mesh == before
    out = mesh.loop_cut(e, cuts=cuts, factor=0.3)
    assert len(out["vertices"]) == cuts * (n + 1)
    assert len(out["edges"]) == cuts * n and not out["closed"]
    assert mesh.vertex_count == v0 + cuts * (n + 1)
    assert mesh.face_count == f0 + cuts * n
    mesh.validate()


def test_extrude_faces_region_and_individual():
    cube_positions = [[x, y, z] for z in (0.0, 1.0) for y in (0.0, 1.0) for x in (0.0, 1.0)]
    quads = [[0, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [1, 3, 7, 5], [3, 2, 6, 7], [2, 0, 4, 6]]
    mesh = meshloom.Mesh.from_arrays(cube_positions, quads)
    before = mesh.copy()
    with pytest.raises(meshloom.RefusedError):
        mesh.extrude_faces([], 1.0)
    with pytest.raises(meshloom.RefusedError):
        mesh.extrude_faces(mesh.faces[:1], float("nan"))
    assert mesh == before
    top = mesh.faces[1]
    out = mesh.extrude_faces([top], 0.5)
    assert out["top"] == [top] and len(out["sides"]) == 4 and len(out["vertices"]) == 4
    assert (mesh.vertex_count, mesh.edge_count, mesh.face_count) == (12, 20, 10)
    mesh.validate()
    out = mesh.extrude_faces(mesh.faces, 0.1, individual=True)
    assert len(out["sides"]) == 4 * 10
    mesh.validate()


def test_inset_faces_individual_and_region():
    n = 4
    mesh = meshloom.Mesh.from_arrays(*grid_arrays(n))
    before = mesh.copy()
    with pytest.raises(meshloom.RefusedError):
        mesh.inset_faces(mesh.faces[:1], float("inf"))
    assert mesh == before
    out = mesh.inset_faces(mesh.faces, 0.1, individual=True)
    assert len(out["inner"]) == n * n and len(out["rim"]) == 4 * n * n
    mesh.validate()
    mesh = meshloom.Mesh.from_arrays(*grid_arrays(n))
    out = mesh.inset_faces(mesh.faces, 0.2, depth=0.1)
    # The whole grid as one region: its outline of 4n edges.
    assert len(out["rim"]) == 4 * n and len(out["vertices"]) == 4 * n
    mesh.validate()


def test_transform_and_face_measures():
    import numpy as np

    mesh = meshloom.Mesh.from_arrays(*grid_arrays(2))
    areas = mesh.face_areas()
    assert np.allclose(areas, 1.0) and mesh.face_centroids().shape == (4, 3)
    f = mesh.faces[0]
    mesh.transform([f], scale=0.5)
    assert np.isclose(mesh.face_areas([f])[0], 0.25)
    before = mesh.copy()
    with pytest.raises(ValueError):
        mesh.transform([f], pivot="middle")
    with pytest.raises(meshloom.RefusedError):
        mesh.transform([f], translate=[float("nan"), 0, 0])
    assert mesh == before
    c = mesh.face_centroids([f])[0]
    mesh.transform(mesh.vertices, rotate=([0, 0, 1], np.pi / 2), pivot="origin")
    c2 = mesh.face_centroids([f])[0]
    assert np.allclose(c2, [-c[1], c[0], c[2]])
    mesh.validate()
