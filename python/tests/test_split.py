"""Rip (split_edges), duplicate_faces and separate, with their columns."""

import pytest

import meshloom
from conftest import grid_arrays


def textured_grid(n=4):
    """An n x n quad grid: corner uv in two islands (below and above the
    middle row), a material per face."""
    mesh = meshloom.Mesh.from_arrays(*grid_arrays(n))
    mesh.add_halfedge_attr("uv", "vec2")
    mesh.add_face_attr("material", int, rule="incompatible")
    for i, f in enumerate(mesh.faces):
        mesh.set_attr("material", f, i)
        y = sum(v.position[1] for v in f.vertices) / len(f.vertices)
        shift = 0.0 if y < n / 2 else 10.0
        for h in f.halfedges:
            p = h.origin.position
            mesh.set_attr("uv", h, [p[0] + shift, p[1]])
    return mesh


def test_split_edges_rips_along_uv_seams():
    mesh = textured_grid()
    seams = mesh.delimited_edges(seams="uv")
    assert len(seams) == 16 + 4  # the boundary and the seam row
    out = mesh.split_edges(seams)
    assert len(out["edges"]) == 4 and len(out["vertices"]) == 5
    assert (mesh.vertex_count, mesh.edge_count) == (30, 44)
    mesh.validate()
    assert mesh.hole_count == 2


def test_split_edges_refuses_a_lone_edge_and_changes_nothing():
    mesh = textured_grid()
    before = mesh.copy()
    inner = [e for e in mesh.edges if not e.is_boundary and not any(v.is_boundary for v in e.vertices)]
    with pytest.raises(meshloom.RefusedError):
        mesh.split_edges(inner[:1])
    assert mesh == before


def test_duplicate_faces_copies_values_and_separate_moves_faces_out():
    mesh = textured_grid()
    before = mesh.copy()
    with pytest.raises(meshloom.RefusedError):
        mesh.duplicate_faces([])
    assert mesh == before
    chosen = mesh.faces[:2]
    out = mesh.duplicate_faces(chosen)
    assert len(out["faces"]) == 2 and len(out["holes"]) == 1
    assert len(out["vertices"]) == len(out["vertex_sources"])
    for src, copy in zip(chosen, out["faces"]):
        assert mesh.attr("material", src) == mesh.attr("material", copy)
        assert [mesh.attr("uv", h) for h in src.halfedges] == [mesh.attr("uv", h) for h in copy.halfedges]
    assert mesh.face_count == 18
    mesh.validate()
    mesh = textured_grid()
    part = mesh.separate(mesh.faces[:4])
    assert (part.face_count, mesh.face_count) == (4, 12)
    part.validate()
    mesh.validate()
    assert sorted(part.attr("material", f) for f in part.faces) == [0, 1, 2, 3]
