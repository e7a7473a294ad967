"""Dissolve vertices, edges, faces, and limited dissolve with delimiters."""

import math

import numpy as np
import pytest

import meshloom
from conftest import grid_arrays


def triangle_grid(n):
    """An n x n grid of quads, each split into two triangles."""
    positions, quads = grid_arrays(n)
    tris = []
    for a, b, c, d in quads:
        tris += [[a, b, c], [a, c, d]]
    return meshloom.Mesh.from_arrays(positions, np.array(tris, dtype=np.int64))


def test_dissolve_faces_makes_one_face_and_refusals_change_nothing():
    mesh = meshloom.Mesh.from_arrays(*grid_arrays(5))
    before = mesh.copy()
    ring = [f for f in mesh.faces if all(1 <= v.position[0] <= 4 and 1 <= v.position[1] <= 4 for v in f.vertices)
            and not all(2 <= v.position[0] <= 3 and 2 <= v.position[1] <= 3 for v in f.vertices)]
    assert len(ring) == 8
    with pytest.raises(meshloom.RefusedError):
        mesh.dissolve_faces(ring)  # an annulus: not one face
    assert mesh == before
    middle = [f for f in mesh.faces if all(1 <= v.position[0] <= 4 and 1 <= v.position[1] <= 4 for v in f.vertices)]
    assert len(middle) == 9
    out = mesh.dissolve_faces(middle)
    assert len(out["faces"]) == 1 and len(out["faces"][0].vertices) == 12
    assert (mesh.vertex_count, mesh.edge_count, mesh.face_count) == (32, 48, 17)
    mesh.validate()


def test_dissolve_limited_merges_a_flat_grid_and_material_stops_it():
    mesh = triangle_grid(4)
    out = mesh.dissolve_limited(math.radians(5))
    assert mesh.face_count == 1 and out["removed_faces"] == 31
    mesh.validate()
    mesh = triangle_grid(4)
    mesh.add_face_attr("material", int, rule="incompatible")
    for f in mesh.faces:
        x = sum(v.position[0] for v in f.vertices) / 3
        mesh.set_attr("material", f, 0 if x < 2 else 1)
    mesh.dissolve_limited(math.radians(5), material="material")
    assert mesh.face_count == 2
    mesh.validate()


def test_dissolve_edges_and_vertices():
    mesh = meshloom.Mesh.from_arrays(*grid_arrays(2))
    inner = [e for e in mesh.edges if not e.is_boundary]
    out = mesh.dissolve_edges(inner[:1])
    assert mesh.face_count == 3 and len(out["faces"]) == 1
    mesh.validate()
    mesh = meshloom.Mesh.from_arrays(*grid_arrays(2))
    centre = [v for v in mesh.vertices if not v.is_boundary][0]
    mesh.dissolve_vertices([centre])
    assert (mesh.vertex_count, mesh.face_count) == (8, 1)
    mesh.validate()
