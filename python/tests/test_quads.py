"""Mesh.join_triangles: triangles into quads, stopped by delimiters."""

import math

import numpy as np
import pytest

import meshloom


def tri_grid(n):
    """An n x n grid of unit cells, each split on its diagonal."""
    xs, ys = np.meshgrid(np.arange(n + 1, dtype=float), np.arange(n + 1, dtype=float))
    positions = np.column_stack([xs.ravel(), ys.ravel(), np.zeros((n + 1) ** 2)])
    faces = []
    for j in range(n):
        for i in range(n):
            a = j * (n + 1) + i
            faces += [[a, a + 1, a + n + 2], [a, a + n + 2, a + n + 1]]
    return meshloom.Mesh.from_arrays(positions, np.array(faces, dtype=np.int64))


def test_a_triangle_grid_joins_back_to_quads():
    n = 4
    mesh = tri_grid(n)
    out = mesh.join_triangles()
    assert len(out["quads"]) == n * n and out["triangles_left"] == 0
    assert mesh.face_count == n * n
    assert all(len(f.vertices) == 4 for f in mesh.faces)
    mesh.validate()


def test_material_and_seams_keep_edges_and_values_follow():
    n = 3
    mesh = tri_grid(n)
    faces = mesh.faces
    mesh.add_face_attr("material", int)
    mesh.add_face_attr("mass", float, rule="conserved")
    mesh.add_halfedge_attr("uv", float)
    for i, f in enumerate(faces):
        # The first cell's two triangles differ in material.
        mesh.set_attr("material", f, 1 if i == 1 else 0)
        mesh.set_attr("mass", f, 1.0 + i)
    total = sum(mesh.attr("mass", f) for f in faces)
    # UVs: the vertex x, except on the second cell's upper triangle.
    for i, f in enumerate(faces):
        for h in f.halfedges:
            x = h.origin.position[0]
            mesh.set_attr("uv", h, x + (10.0 if i == 3 else 0.0))
    before = mesh.copy()
    out = before.copy().join_triangles()
    assert len(out["quads"]) == n * n
    out = mesh.join_triangles(material="material", seams="uv")
    assert len(out["quads"]) == n * n - 2 and out["triangles_left"] == 4
    mesh.validate()
    assert math.isclose(sum(mesh.attr("mass", f) for f in mesh.faces), total)
    # Each quad keeps its first triangle's key; its mass is both triangles'.
    for q in out["quads"]:
        i = faces.index(q)
        assert mesh.attr("mass", q) == (1.0 + i) + (1.0 + (i ^ 1))
    for f in mesh.faces:
        for h in f.halfedges:
            x = h.origin.position[0]
            shift = 10.0 if f == faces[3] else 0.0
            assert mesh.attr("uv", h) == x + shift


def test_sharp_edges_and_angles():
    mesh = tri_grid(2)
    mesh.add_edge_attr("sharp", bool)
    def slanted(e):
        a, b = (v.position for v in e.vertices)
        return a[0] != b[0] and a[1] != b[1]

    diagonal = next(e for e in mesh.edges if slanted(e))
    mesh.set_attr("sharp", diagonal, True)
    out = mesh.copy().join_triangles(sharp="sharp")
    assert len(out["quads"]) == 3
    # A tiny shape angle still joins the unit squares.
    assert len(mesh.copy().join_triangles(shape_angle=0.01)["quads"]) == 4


def test_refusals_leave_the_mesh_as_it_was():
    mesh = tri_grid(2)
    before = mesh.copy()
    with pytest.raises(meshloom.RefusedError):
        mesh.join_triangles(angle=float("nan"))
    with pytest.raises(meshloom.RefusedError):
        mesh.join_triangles(shape_angle=-1.0)
    with pytest.raises(Exception):
        mesh.join_triangles(material="nope")
    assert mesh == before
    f = mesh.faces[0]
    other = tri_grid(2)
    other.remove_face(other.faces[0])
    stale = other.faces  # keys of another mesh are refused as such
    with pytest.raises(ValueError):
        mesh.join_triangles(faces=stale[:1])
    mesh.remove_face(f)
    with pytest.raises(meshloom.StaleKeyError):
        mesh.join_triangles(faces=[f])
