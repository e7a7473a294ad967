"""Mesh.tree(): ray casts, closest points, inside tests, winding numbers and
radius queries against a numpy brute force on small closed meshes; a tree
used after an edit raises StaleTreeError until refit."""

import numpy as np
import pytest

import meshloom

CUBE_P = np.array(
    [[x, y, z] for z in (0.0, 1.0) for y in (0.0, 1.0) for x in (0.0, 1.0)]
)
# Six outward quads (polygons: the tree fans them).
CUBE_F = np.array(
    [[0, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [2, 6, 7, 3], [0, 4, 6, 2], [1, 3, 7, 5]]
)
OCTA_P = np.array(
    [[1, 0, 0], [-1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1], [0, 0, -1]], dtype=float
)
OCTA_F = np.array(
    [[0, 2, 4], [2, 1, 4], [1, 3, 4], [3, 0, 4], [2, 0, 5], [1, 2, 5], [3, 1, 5], [0, 3, 5]]
)


def fan(faces):
    """(triangle corner indices, face index of each) of the faces' fans."""
    tris, owner = [], []
    for fi, f in enumerate(faces):
        for i in range(1, len(f) - 1):
            tris.append([f[0], f[i], f[i + 1]])
            owner.append(fi)
    return np.array(tris), np.array(owner)


def brute_ray(p, faces, o, d):
    tris, owner = fan(faces)
    best_t, best_f = np.inf, -1
    for (a, b, c), f in zip(p[tris], owner):
        e1, e2 = b - a, c - a
        h = np.cross(d, e2)
        det = e1 @ h
        if abs(det) < 1e-14:
            continue
        s = o - a
        u = (s @ h) / det
        q = np.cross(s, e1)
        v = (d @ q) / det
        t = (e2 @ q) / det
        if u >= 0 and v >= 0 and u + v <= 1 and 0 <= t < best_t:
            best_t, best_f = t, f
    return best_t, best_f


def closest_on_triangle(q, a, b, c):
    # Dense barycentric search is too coarse; project and clamp to edges.
    n = np.cross(b - a, c - a)
    n = n / np.linalg.norm(n)
    x = q - ((q - a) @ n) * n
    m = np.array([b - a, c - a]).T
    uv, *_ = np.linalg.lstsq(m, x - a, rcond=None)
    if uv[0] >= 0 and uv[1] >= 0 and uv.sum() <= 1:
        return x
    best = None
    for s, e in ((a, b), (b, c), (c, a)):
        t = np.clip((q - s) @ (e - s) / ((e - s) @ (e - s)), 0, 1)
        y = s + t * (e - s)
        if best is None or np.linalg.norm(q - y) < np.linalg.norm(q - best):
            best = y
    return best


def brute_closest(p, faces, q):
    tris, owner = fan(faces)
    return min(np.linalg.norm(q - closest_on_triangle(q, *p[t])) for t in tris)


@pytest.fixture(params=["cube", "octahedron"])
def shape(request):
    p, f = (CUBE_P, CUBE_F) if request.param == "cube" else (OCTA_P, OCTA_F)
    return meshloom.Mesh.from_arrays(p, f), p, f


def test_ray_cast_matches_brute_force(shape):
    mesh, p, f = shape
    rng = np.random.default_rng(1)
    o = rng.uniform(-2, 2, (60, 3))
    # Aimed near the middle: most hit, some miss.
    d = rng.uniform(-0.8, 1.2, (60, 3)) - o
    hits = mesh.tree().ray_cast(o, d)
    assert hits["face"].shape == (60,) and hits["point"].shape == (60, 3)
    slots = [face.index for face in mesh.faces]
    for i in range(60):
        t, fi = brute_ray(p, f, o[i], d[i])
        if fi < 0:
            assert hits["face"][i] == -1 and np.isinf(hits["t"][i])
            continue
        assert hits["t"][i] == pytest.approx(t, abs=1e-9)
        np.testing.assert_allclose(hits["point"][i], o[i] + t * d[i], atol=1e-9)
        assert hits["face"][i] in slots
        # The face reported holds the point (a tie on an edge may name either).
        face = mesh.faces[slots.index(hits["face"][i])]
        corners = p[[v.index for v in face.vertices]]
        w = hits["weights"][i]
        np.testing.assert_allclose(w @ corners[hits["corners"][i]], hits["point"][i], atol=1e-9)
    assert (hits["face"] >= 0).sum() > 10


def test_closest_points_match_brute_force(shape):
    mesh, p, f = shape
    q = np.random.default_rng(2).uniform(-2, 2, (40, 3))
    c = mesh.tree().closest_points(q)
    for i in range(40):
        assert c["distance"][i] == pytest.approx(brute_closest(p, f, q[i]), abs=1e-9)
        np.testing.assert_allclose(np.linalg.norm(c["point"][i] - q[i]), c["distance"][i])
    far = mesh.tree().closest_points([[10.0, 10.0, 10.0]], max_distance=1.0)
    assert far["face"][0] == -1 and np.isinf(far["distance"][0])


def test_contains_and_winding_numbers(shape):
    mesh, p, f = shape
    q = np.random.default_rng(3).uniform(-1.5, 1.5, (200, 3))
    if len(f) == 6:  # the unit cube
        truth = np.all((q > 0) & (q < 1), axis=1)
    else:  # the octahedron |x| + |y| + |z| < 1
        truth = np.abs(q).sum(axis=1) < 1
    tree = mesh.tree()
    inside = tree.contains(q)
    assert inside.dtype == bool and np.array_equal(inside, truth)
    exact = tree.winding_number(q, mode="exact")
    np.testing.assert_allclose(exact, truth.astype(float), atol=1e-9)
    fast = tree.winding_number(q)
    np.testing.assert_allclose(fast, exact, atol=0.05)
    with pytest.raises(ValueError, match="fast or exact"):
        tree.winding_number(q, mode="slow")


def test_within_and_nearest_vertex():
    mesh = meshloom.Mesh.from_arrays(OCTA_P, OCTA_F)
    tree = mesh.tree()
    v, dist = tree.nearest_vertex([0.9, 0.1, 0.0])
    assert v.index == 0 and dist == pytest.approx(np.hypot(0.1, 0.1))
    near = sorted(x.index for x in tree.within([2.0, 0.0, 0.0], 1.0, kind="vertex"))
    assert near == [0]
    faces = tree.within([2.0, 0.0, 0.0], 1.0 + 1e-9, kind="face")
    assert sorted(x.index for x in faces) == [0, 3, 4, 7]
    with pytest.raises(ValueError, match="face, vertex or edge"):
        tree.within([0, 0, 0], 1.0, kind="corner")


def test_a_stale_tree_raises_until_refit():
    mesh = meshloom.Mesh.from_arrays(OCTA_P, OCTA_F)
    tree = mesh.tree()
    assert tree.is_current()
    p = mesh.positions
    mesh.positions = p + [5.0, 0.0, 0.0]
    assert not tree.is_current()
    with pytest.raises(meshloom.StaleTreeError, match="refit or rebuild") as err:
        tree.closest_points([[0.0, 0.0, 0.0]])
    assert isinstance(err.value, meshloom.MeshloomError)
    tree.refit()
    assert tree.is_current()
    c = tree.closest_points([[7.0, 0.0, 0.0]])
    assert c["distance"][0] == pytest.approx(1.0)


def test_bad_input_raises_query_error():
    tree = meshloom.Mesh.from_arrays(OCTA_P, OCTA_F).tree()
    with pytest.raises(meshloom.QueryError, match="not finite"):
        tree.closest_points([[np.nan, 0.0, 0.0]])
    with pytest.raises(meshloom.QueryError, match="direction is zero"):
        tree.ray_cast([[0.0, 0.0, 0.0]], [[0.0, 0.0, 0.0]])
    with pytest.raises(ValueError, match="origins"):
        tree.ray_cast(np.zeros((2, 3)), np.ones((3, 3)))


def test_within_edges_and_nearest_edge():
    mesh = meshloom.Mesh.from_arrays(OCTA_P, OCTA_F)
    tree = mesh.tree()
    edges = tree.within([1.0, 1.0, 0.0], 0.75, kind="edge")
    assert len(edges) == 1
    assert sorted(v.index for v in edges[0].vertices) == [0, 2]
    e, dist, point = tree.nearest_edge([1.0, 1.0, 0.0])
    assert dist == pytest.approx(np.sqrt(0.5))
    np.testing.assert_allclose(point, [0.5, 0.5, 0.0], atol=1e-12)
    with pytest.raises(ValueError, match="face, vertex or edge"):
        tree.within([0, 0, 0], 1.0, kind="corner")


def test_pick_sees_the_near_vertex_and_through_with_xray():
    mesh = meshloom.Mesh.from_arrays(OCTA_P, OCTA_F)
    tree = mesh.tree()
    # Looking down -z at the top vertex (0, 0, 1); the bottom one (0, 0, -1)
    # lies on the same axis behind the surface.
    key, point, t, offset = tree.pick([0.05, 0.0, 5.0], [0.0, 0.0, -1.0], angle=0.05)
    assert tuple(point) == (0.0, 0.0, 1.0) and t == pytest.approx(4.0)
    assert 0.0 < offset < 1.0
    key, point, t, offset = tree.pick([0.05, 0.0, 5.0], [0.0, 0.0, -1.0], angle=0.05, occlusion="xray")
    assert tuple(point) == (0.0, 0.0, -1.0)  # farther, so nearer the axis on screen
    edge = tree.pick([0.5, 0.52, 5.0], [0.0, 0.0, -1.0], radius=0.1, kind="edge")
    # The equator's edge between (1, 0, 0) and (0, 1, 0), the top faces' rim.
    assert sorted(v.index for v in edge[0].vertices) == [0, 2]
    assert edge[1][2] == pytest.approx(0.0) and edge[3] < 0.2
    assert tree.pick([9.0, 9.0, 5.0], [0.0, 0.0, -1.0], radius=0.1) is None
    with pytest.raises(ValueError, match="angle"):
        tree.pick([0, 0, 5], [0, 0, -1])
    with pytest.raises(meshloom.QueryError, match="cone"):
        tree.pick([0, 0, 5], [0, 0, -1], radius=-1.0)


def sphere_arrays(cols=16, rows=10):
    """A latitude-longitude unit sphere of triangles."""
    p = [[0.0, 0.0, 1.0], [0.0, 0.0, -1.0]]
    for j in range(1, rows):
        th = np.pi * j / rows
        for i in range(cols):
            ph = 2 * np.pi * i / cols
            p.append([np.sin(th) * np.cos(ph), np.sin(th) * np.sin(ph), np.cos(th)])
    ring = lambda j, i: 2 + (j - 1) * cols + i % cols
    f = []
    for i in range(cols):
        f.append([0, ring(1, i), ring(1, i + 1)])
        f.append([1, ring(rows - 1, i + 1), ring(rows - 1, i)])
        for j in range(1, rows - 1):
            a, b, c, d = ring(j, i), ring(j + 1, i), ring(j + 1, i + 1), ring(j, i + 1)
            f += [[a, b, c], [a, c, d]]
    return np.array(p), np.array(f)


def test_update_after_edits_answers_as_a_fresh_tree():
    mesh = meshloom.Mesh.from_arrays(*sphere_arrays())
    tree = mesh.tree()
    rng = np.random.default_rng(7)
    faces = list(mesh.faces)
    for f in faces[:5]:
        mesh.poke_face(f)
    assert not tree.is_current()
    report = tree.update()
    assert tree.is_current() and not report["full_rebuild"]
    assert report["removed_triangles"] >= 5 and report["inserted_triangles"] >= 15
    origins = rng.normal(size=(200, 3)) * 3.0
    directions = -origins + rng.normal(size=(200, 3)) * 0.2
    fresh = mesh.tree()
    a = tree.ray_cast(origins, directions)
    b = fresh.ray_cast(origins, directions)
    np.testing.assert_array_equal(a["t"], b["t"])
    # The fresh tree took the mesh's changes: the first tree rebuilds.
    mesh.poke_face(list(mesh.faces)[0])
    fresh.update()
    assert tree.update()["full_rebuild"] and tree.is_current()
