"""One meaning for the constraint words in every algorithm (issue 25): on
an open, noisy grid, decimate, remesh, smooth and fair with
boundary="lock" leave every boundary vertex bit for bit, with
boundary="slide" keep every boundary vertex on the input's boundary
polyline (within 1e-9 of the bounding box's diagonal), with "free" smooth
moves some off it, and pinned vertices stay bit for bit. The old keywords
warn and mean one thing."""

import numpy as np
import pytest

import meshloom


def noisy_grid(n=20, seed=25):
    """An n x n triangle grid (cells of 1) whose interior vertices are
    jittered (+-0.25 in x and y, +-0.3 in z) by a fixed generator."""
    rng = np.random.default_rng(seed)
    ij = np.array([(i, j) for j in range(n + 1) for i in range(n + 1)], float)
    p = np.column_stack([ij, np.zeros(len(ij))])
    inner = (ij[:, 0] > 0) & (ij[:, 0] < n) & (ij[:, 1] > 0) & (ij[:, 1] < n)
    jitter = rng.uniform(-1, 1, (len(p), 3)) * [0.25, 0.25, 0.3]
    p[inner] += jitter[inner]
    tris = []
    for j in range(n):
        for i in range(n):
            a = j * (n + 1) + i
            tris += [[a, a + 1, a + n + 2], [a, a + n + 2, a + n + 1]]
    return meshloom.Mesh.from_arrays(p, np.array(tris))


def exact(p):
    return tuple(float(c).hex() for c in p)


def boundary(mesh):
    """{vertex: its position, exactly} for the boundary vertices."""
    return {v: exact(v.position) for v in mesh.vertices if v.is_boundary}


def polyline(mesh):
    segments = []
    for e in mesh.edges:
        if e.is_boundary:
            a, b = e.vertices
            segments.append((np.array(a.position), np.array(b.position)))
    return segments


def distance_to(segments, p):
    p = np.asarray(p, float)
    best = np.inf
    for a, b in segments:
        d = b - a
        t = np.clip(np.dot(p - a, d) / np.dot(d, d), 0.0, 1.0)
        best = min(best, np.linalg.norm(p - (a + t * d)))
    return best


def diagonal(mesh):
    p, _ = mesh.to_arrays()
    return float(np.linalg.norm(p.max(axis=0) - p.min(axis=0)))


ALGORITHMS = {
    "decimate": lambda m, **kw: m.decimate(0.3, **kw),
    "remesh": lambda m, **kw: m.remesh(iterations=5, **kw),
    "smooth": lambda m, **kw: m.smooth("taubin", **kw),
    "smooth cotan": lambda m, **kw: m.smooth("cotan", **kw),
    "fair": lambda m, **kw: m.fair(**kw),
}


@pytest.mark.parametrize("name", ALGORITHMS)
def test_lock_leaves_every_boundary_vertex_bit_for_bit(name):
    mesh = noisy_grid()
    before = boundary(mesh)
    edges = sum(e.is_boundary for e in mesh.edges)
    ALGORITHMS[name](mesh, boundary="lock")
    mesh.validate()
    assert boundary(mesh) == before
    assert sum(e.is_boundary for e in mesh.edges) == edges


@pytest.mark.parametrize("name", ALGORITHMS)
def test_slide_keeps_every_boundary_vertex_on_the_input_boundary(name):
    mesh = noisy_grid()
    before = boundary(mesh)
    line = polyline(mesh)
    tolerance = 1e-9 * diagonal(mesh)
    ALGORITHMS[name](mesh, boundary="slide")
    mesh.validate()
    for v in mesh.vertices:
        if v.is_boundary:
            assert distance_to(line, v.position) <= tolerance, v
    if name != "fair":
        assert boundary(mesh) != before


def test_free_lets_smoothing_move_the_boundary_off_it():
    mesh = noisy_grid()
    line = polyline(mesh)
    tolerance = 1e-9 * diagonal(mesh)
    rim = [v for v in mesh.vertices if v.is_boundary]
    mesh.smooth("uniform", boundary="free")
    assert sum(distance_to(line, v.position) > tolerance for v in rim) > 0


@pytest.mark.parametrize("name", ALGORITHMS)
@pytest.mark.parametrize("as_array", [False, True])
def test_pinned_vertices_stay_bit_for_bit(name, as_array):
    mesh = noisy_grid()
    pins = np.arange(mesh.vertex_count) % 7 == 3
    kept = {v: exact(v.position) for v, pin in zip(mesh.vertices, pins) if pin}
    if as_array:
        pinned = pins
    else:
        mesh.add_vertex_attr("pin", bool)
        mesh.set_attr_array("pin", pins)
        pinned = "pin"
    ALGORITHMS[name](mesh, pinned=pinned)
    for v, p in kept.items():
        assert exact(v.position) == p, (name, v)
    assert "__meshloom_pinned" not in mesh.attrs("vertex")


def test_old_keywords_warn_and_mean_one_thing():
    calls = [
        lambda m: m.decimate(0.3, keep_boundary=True),
        lambda m: m.decimate(0.3, keep_boundary="lock"),
        lambda m: m.remesh(iterations=3, keep_boundary=True),
        lambda m: m.smooth(fix_boundary=True),
    ]
    for call in calls:
        mesh = noisy_grid()
        before = boundary(mesh)
        with pytest.warns(DeprecationWarning, match='use boundary="lock"'):
            call(mesh)
        assert boundary(mesh) == before
    mesh = noisy_grid()
    mesh.add_vertex_attr("pin", bool)
    with pytest.warns(DeprecationWarning, match="locked is deprecated; use pinned"):
        mesh.decimate(0.3, locked="pin")
    with pytest.warns(DeprecationWarning, match="crease_angle"):
        flat = mesh.normals("corner", crease_angle=0.0)
    assert np.array_equal(flat, mesh.normals("corner", feature_angle=0.0))


def test_bad_words_are_refused_with_the_words():
    mesh = noisy_grid(4)
    for call in (
        lambda: mesh.smooth(boundary="locked"),
        lambda: mesh.decimate(0.5, seams="sliding"),
        lambda: mesh.remesh(boundary="fixed"),
        lambda: mesh.fair(boundary="nope"),
    ):
        with pytest.raises(ValueError, match="free, slide, lock"):
            call()
    with pytest.raises(TypeError):
        mesh.smooth(boundary=True)
    with pytest.raises(meshloom.ColumnError):
        mesh.smooth(pinned="missing")
