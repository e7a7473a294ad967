"""Keys, navigation, stale keys; the halfedge package's scenarios with
meshloom's semantics (holes are faces, reflection, removal)."""

import pytest

import meshloom


def test_keys_are_hashable_and_equal_by_key(square):
    a = square.vertices
    b = square.vertices
    assert a == b and a is not b
    assert len(set(a) | set(b)) == 4
    assert {v: i for i, v in enumerate(a)}[b[2]] == 2
    assert a[0] != a[1]
    assert all(v in square for v in a)


def test_navigation_names_follow_the_rust_api(square):
    for h in square.halfedges:
        assert h.twin.twin == h
        assert h.next.prev == h
        assert h.next.origin == h.dest
        assert h.twin.origin == h.dest
        assert h.edge == h.twin.edge
        assert h.face.is_hole == h.is_boundary
        assert h in h.origin.outgoing
        assert h in h.dest.incoming
    v0 = square.vertices[0]
    assert sorted(v0.neighbors) == sorted(square.vertices[1:])
    assert v0.degree == 3 and v0.is_boundary
    assert len(v0.faces) == 2  # the hole is skipped
    f = square.faces[0]
    assert len(f.vertices) == 3 and f.degree == 3
    assert f.neighbors == [square.faces[1]]
    assert not f.is_hole


def test_holes_are_faces(square):
    (hole,) = square.holes
    assert hole.is_hole and hole.degree == 4
    assert all(h.is_boundary for h in hole.halfedges)
    assert hole not in square.faces and hole in square.faces_and_holes
    # Every half-edge has a twin and a face, also on the boundary.
    assert all(h.twin is not None and h.face is not None for h in square.halfedges)
    e = next(e for e in square.edges if e.is_boundary)
    assert None in e.faces


def test_setters_reflect(square):
    # Setting a position through a key is seen through every path to it.
    v = square.vertices[2]
    v.position = (5.0, 6.0, 7.0)
    h = square.find_halfedge(square.vertices[1], v)
    assert h.dest.position == [5.0, 6.0, 7.0]
    assert square.positions[2].tolist() == [5.0, 6.0, 7.0]
    # Removing an edge: both faces' half-edges now reach the same face.
    inner = next(e for e in square.edges if not e.is_boundary)
    f = square.remove_edge(inner)
    assert square.face_count == 1 and f.degree == 4
    assert all(h.face == f for h in f.halfedges)


def test_stale_keys_raise(square):
    inner = next(e for e in square.edges if not e.is_boundary)
    gone = inner.faces
    square.remove_edge(inner)
    stale = [f for f in gone if not f.is_alive]
    assert len(stale) == 1
    with pytest.raises(meshloom.StaleKeyError) as err:
        stale[0].vertices
    assert err.value.element == stale[0]
    assert isinstance(err.value, KeyError)
    with pytest.raises(meshloom.StaleKeyError):
        inner.vertices
    with pytest.raises(meshloom.StaleKeyError):
        square.remove_edge(inner)
    assert inner not in square


def test_stale_after_compact():
    mesh = meshloom.Mesh.from_arrays(
        [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [2, 0.5, 0]], [[0, 1, 2, 3], [1, 4, 2]]
    )
    v = mesh.vertices
    mesh.remove_face(mesh.faces[1])
    assert not v[4].is_alive
    survivors = {x: x.position for x in v if x.is_alive}
    maps = mesh.compact()
    assert v[4] not in maps
    for old, position in survivors.items():
        assert maps[old].position == position
    with pytest.raises(meshloom.StaleKeyError):
        v[4].position
    mesh.validate()


def test_key_of_another_mesh_is_refused(square):
    other = square.copy()
    with pytest.raises(ValueError):
        square.split_edge(other.edges[0])


def test_grid_remove_corner_vertices_leaves_a_plus(grid3):
    # halfedge: removing the four valence-2 corners of a 3x3 grid leaves five
    # quads and one 12-sided hole. In meshloom the corner's face goes with it.
    corners = [v for v in grid3.vertices if v.degree == 2]
    assert len(corners) == 4
    for c in corners:
        grid3.remove_face(c.faces[0])
    assert sorted(f.degree for f in grid3.faces) == [4, 4, 4, 4, 4]
    assert [h.degree for h in grid3.holes] == [12]
    grid3.validate()


def test_grid_remove_interior_vertices_leaves_one_face(grid3):
    interior = [v for v in grid3.vertices if v.degree == 4]
    assert len(interior) == 4
    for v in interior:
        grid3.remove_vertex(v)
        grid3.validate()
    assert [f.degree for f in grid3.faces] == [12]
    assert [h.degree for h in grid3.holes] == [12]


def test_remove_then_reinsert_every_edge(grid3):
    for e in grid3.edges:
        if e.is_boundary or not e.is_alive:
            continue
        a, b = e.vertices
        grid3.remove_edge(e)
        grid3.validate()
        h = grid3.insert_edge(a, b)
        assert (h.origin, h.dest) == (a, b)
        grid3.validate()
    assert grid3.face_count == 9 and grid3.edge_count == 24


def test_removing_a_bridge_is_refused():
    # halfedge: in a row of quads, removing the boundary edges of the middle
    # quad would leave its other edges as bridges between two islands.
    # meshloom refuses at the first such edge (the middle quad would open
    # into the hole and leave the top edge with the hole on both sides),
    # with reason "bridge"; remove_edge_allowing_bridge does it on request.
    p = [[x, y, 0.0] for y in (0, 1) for x in range(4)]
    mesh = meshloom.Mesh.from_arrays(p, [[0, 1, 5, 4], [1, 2, 6, 5], [2, 3, 7, 6]])
    middle = [e for e in mesh.faces[1].edges if e.is_boundary]
    assert len(middle) == 2
    before = mesh.copy()
    with pytest.raises(meshloom.RefusedError) as err:
        mesh.remove_edge(middle[0])
    assert err.value.reason == "bridge"
    assert err.value.element == middle[0]
    assert mesh == before
    mesh.remove_edge_allowing_bridge(middle[0])
    mesh.validate()
    assert mesh.face_count == 2


def test_validate_raises_nothing_on_valid_meshes(grid3):
    grid3.validate()
    for f in list(grid3.faces):
        grid3.poke_face(f)
    grid3.validate()
    assert grid3.face_count == 36
