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
    with pytest.raises(ValueError, match="face or vertex"):
        tree.within([0, 0, 0], 1.0, kind="edge")


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
