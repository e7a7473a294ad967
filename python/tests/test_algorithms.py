"""The algorithms from Python: counts change as the schemes say, attribute
columns follow, options are checked, failures and cancellations leave the
mesh unchanged."""

import math

import numpy as np
import pytest

import meshloom
from conftest import grid_arrays


def tri_grid(n):
    """An n x n grid of quads cut into triangles, bumped so it is not flat."""
    positions, quads = grid_arrays(n)
    positions = positions.copy()
    positions[:, 2] = np.sin(positions[:, 0]) * np.cos(positions[:, 1]) * 0.3
    tris = np.concatenate([quads[:, [0, 1, 2]], quads[:, [0, 2, 3]]])
    return meshloom.Mesh.from_arrays(positions, tris)


def icosahedron():
    t = (1 + 5**0.5) / 2
    p = [[-1, t, 0], [1, t, 0], [-1, -t, 0], [1, -t, 0], [0, -1, t], [0, 1, t],
         [0, -1, -t], [0, 1, -t], [t, 0, -1], [t, 0, 1], [-t, 0, -1], [-t, 0, 1]]
    f = [[0, 11, 5], [0, 5, 1], [0, 1, 7], [0, 7, 10], [0, 10, 11], [1, 5, 9],
         [5, 11, 4], [11, 10, 2], [10, 7, 6], [7, 1, 8], [3, 9, 4], [3, 4, 2],
         [3, 2, 6], [3, 6, 8], [3, 8, 9], [4, 9, 5], [2, 4, 11], [6, 2, 10],
         [8, 6, 7], [9, 8, 1]]
    return meshloom.Mesh.from_arrays(np.array(p, float), np.array(f))


def with_columns(mesh):
    """A float vertex column, a Python-rule-free face id and a corner UV."""
    mesh.add_vertex_attr("temperature", float)
    mesh.set_attr_array("temperature", mesh.to_arrays()[0][:, 0])
    mesh.add_face_attr("material", int)
    mesh.set_attr_array("material", np.full(mesh.face_count, 3), kind="face")
    mesh.add_halfedge_attr("uv", "vec2")
    hs = mesh.halfedges
    uv = np.array([[h.origin.position[0], h.origin.position[1]] for h in hs])
    mesh.set_attr_array("uv", uv, kind="halfedge")
    return mesh


# ----- normals and curvature -------------------------------------------------


def test_normals_of_a_flat_grid_point_up():
    mesh = meshloom.Mesh.from_arrays(*grid_arrays(3))
    for kind, count in [("face", 9), ("vertex", 16), ("corner", mesh.halfedge_count)]:
        n = mesh.normals(kind)
        assert n.shape == (count, 3) and n.dtype == np.float64
        if kind != "corner":
            assert np.allclose(n, [0, 0, 1])
    corner = mesh.normals("corner")
    inner = [i for i, h in enumerate(mesh.halfedges) if not h.face.is_hole]
    assert np.allclose(corner[inner], [0, 0, 1])
    with pytest.raises(ValueError):
        mesh.normals("edge")
    with pytest.raises(ValueError):
        mesh.normals("vertex", weight="mass")


def test_stored_normals_follow_edits():
    mesh = meshloom.Mesh.from_arrays(*grid_arrays(2))
    mesh.normals("vertex", store=True)
    assert mesh.attrs("vertex")["normal"] == ("vec3", "interpolate")
    e = mesh.edges[0]
    m = mesh.split_edge(e, 0.5)
    assert np.allclose(mesh.attr("normal", m), [0, 0, 1])


def test_flat_corner_normals_split_at_a_crease():
    mesh = icosahedron()
    smooth = mesh.normals("corner", feature_angle=None)
    flat = mesh.normals("corner", feature_angle=0.0)
    faces = mesh.normals("face")
    face_of = {f: i for i, f in enumerate(mesh.faces)}
    for i, h in enumerate(mesh.halfedges):
        assert np.allclose(flat[i], faces[face_of[h.face]])
    assert not np.allclose(smooth, flat)


def test_curvature_of_a_sphere_like_mesh():
    mesh = icosahedron()
    mesh.subdivide("loop", 3)
    p, _ = mesh.to_arrays()
    p /= np.linalg.norm(p, axis=1)[:, None]  # onto the unit sphere
    mesh2 = meshloom.Mesh.from_arrays(p, mesh.to_arrays()[1])
    c = mesh2.curvature()
    assert set(c) == {"mean", "gaussian", "min", "max", "area"}
    assert c["mean"].shape == (mesh2.vertex_count,)
    assert abs(np.median(c["mean"]) - 1.0) < 0.05
    assert abs(np.median(c["gaussian"]) - 1.0) < 0.1
    assert abs(c["area"].sum() - 4 * math.pi) < 0.1
    mesh2.curvature(store=True)
    assert "mean_curvature" in mesh2.attrs("vertex")


# ----- subdivision -----------------------------------------------------------


@pytest.mark.parametrize(
    "scheme, levels, expect",
    [
        ("loop", 1, lambda v, e, f: (v + e, 4 * f)),
        ("loop", 2, lambda v, e, f: (v + e + (2 * e + 3 * f), 16 * f)),
        ("catmull_clark", 1, lambda v, e, f: (v + e + f, 3 * f)),
        ("sqrt3", 1, lambda v, e, f: (v + f, 3 * f)),
        ("midpoint", 1, lambda v, e, f: (v + e, 4 * f)),
    ],
)
def test_subdivision_counts(scheme, levels, expect):
    mesh = icosahedron()
    v, e, f = mesh.vertex_count, mesh.edge_count, mesh.face_count
    report = mesh.subdivide(scheme, levels)
    assert (mesh.vertex_count, mesh.face_count) == expect(v, e, f)
    assert report["input"] == {"vertices": v, "edges": e, "faces": f, "holes": 0}
    assert report["output"]["faces"] == mesh.face_count
    assert len(report["levels"]) == levels
    mesh.validate()


def test_subdivision_keeps_attribute_columns():
    mesh = with_columns(tri_grid(3))
    t_before = mesh.attr_array("temperature")
    mesh.subdivide("loop", 1, linear_columns=["temperature"])
    assert set(mesh.attrs("vertex")) >= {"position", "temperature"}
    t = mesh.attr_array("temperature")
    assert t.shape == (mesh.vertex_count,) and not np.isnan(t).any()
    assert t.min() >= t_before.min() - 1e-12 and t.max() <= t_before.max() + 1e-12
    # Linear: old vertices keep their values, new ones take their edge's
    # mean, so every old value is still there.
    assert np.isin(t_before, t).all()
    assert (mesh.attr_array("material", kind="face") == 3).all()
    uv = mesh.attr_array("uv", kind="halfedge")
    assert uv.shape == (mesh.halfedge_count, 2)


def test_loop_on_quads_is_refused_and_changes_nothing():
    mesh = meshloom.Mesh.from_arrays(*grid_arrays(2))
    before = mesh.copy()
    with pytest.raises(meshloom.UnsuitableError) as err:
        mesh.subdivide("loop")
    assert err.value.algorithm == "loop_subdivide"
    assert mesh == before
    with pytest.raises(ValueError):
        mesh.subdivide("butterfly")


def test_progress_callback_can_cancel():
    mesh = icosahedron()
    before = mesh.copy()
    seen = []

    def stop(info):
        seen.append(info)
        return False

    with pytest.raises(meshloom.CancelledError) as err:
        mesh.subdivide("catmull_clark", 2, progress=stop)
    assert err.value.algorithm == "catmull_clark"
    assert seen and set(seen[0]) == {"algorithm", "stage", "done", "total"}
    assert mesh == before

    calls = []
    mesh.subdivide("catmull_clark", 1, progress=lambda info: calls.append(info["done"]))
    assert calls and mesh.face_count == 60


def test_progress_callback_exception_propagates():
    mesh = icosahedron()
    before = mesh.copy()

    def boom(info):
        raise RuntimeError("from the callback")

    with pytest.raises(RuntimeError, match="from the callback"):
        mesh.subdivide("loop", 1, progress=boom)
    assert mesh == before


# ----- smoothing and fairing -------------------------------------------------


@pytest.mark.parametrize("method", ["uniform", "cotan", "taubin", "implicit"])
def test_smoothing_flattens_a_bumpy_grid(method):
    mesh = with_columns(tri_grid(8))
    p0, _ = mesh.to_arrays()
    report = mesh.smooth(method, iterations=5 if method != "implicit" else 1, step=None)
    p1, _ = mesh.to_arrays()
    boundary = np.array([v.is_boundary for v in mesh.vertices])
    assert np.array_equal(p0[boundary], p1[boundary])  # fixed by default
    assert np.abs(p1[~boundary, 2]).sum() < np.abs(p0[~boundary, 2]).sum()
    assert report["moved"] == (~boundary).sum()
    assert report["fixed"] == boundary.sum()
    assert "temperature" in mesh.attrs("vertex")


def test_smoothing_leaves_pinned_vertices_where_they_are():
    mesh = tri_grid(6)
    p0, _ = mesh.to_arrays()
    free = np.zeros(mesh.vertex_count, bool)
    free[[10, 11, 12]] = True
    mesh.smooth("uniform", pinned=~free)
    p1, _ = mesh.to_arrays()
    moved = np.any(p0 != p1, axis=1)
    assert moved[[10, 11, 12]].any() and not moved[~free].any()
    assert "__meshloom_pinned" not in mesh.attrs("vertex")
    # The same through a bool column.
    mesh.add_vertex_attr("pin", bool)
    mesh.set_attr_array("pin", ~free)
    mesh.smooth("cotan", pinned="pin")
    with pytest.raises(meshloom.UnsuitableError):
        mesh.smooth("uniform", step=2.0)
    with pytest.raises(meshloom.ColumnError):
        mesh.smooth("uniform", pinned="nope")
    with pytest.raises(ValueError):
        mesh.smooth("uniform", boundary="locked")


def test_smoothing_mask_is_a_deprecated_pinned_complement():
    mesh = tri_grid(6)
    p0, _ = mesh.to_arrays()
    mask = np.zeros(mesh.vertex_count, bool)
    mask[[10, 11, 12]] = True
    with pytest.warns(DeprecationWarning, match="mask is deprecated"):
        mesh.smooth("uniform", mask=mask)
    p1, _ = mesh.to_arrays()
    moved = np.any(p0 != p1, axis=1)
    assert moved[[10, 11, 12]].any() and not moved[~mask].any()
    assert "__meshloom_pinned" not in mesh.attrs("vertex")
    with pytest.warns(DeprecationWarning, match="fix_boundary"):
        report = mesh.smooth("uniform", fix_boundary=False)
    assert report["fixed"] == 0


def test_fair_a_region_and_refuse_a_closed_mesh():
    mesh = tri_grid(8)
    p0, _ = mesh.to_arrays()
    region = [v for v in mesh.vertices if not v.is_boundary and 2 < v.position[0] < 6]
    report = mesh.fair(region, order=2)
    # Region vertices within `order` rings of the boundary stay fixed.
    assert 0 < report["moved"] <= len(region)
    p1, _ = mesh.to_arrays()
    idx = {v: i for i, v in enumerate(mesh.vertices)}
    outside = np.ones(mesh.vertex_count, bool)
    outside[[idx[v] for v in region]] = False
    assert np.array_equal(p0[outside], p1[outside])
    assert np.any(p0[~outside] != p1[~outside], axis=1).sum() == report["moved"]
    closed = icosahedron()
    before = closed.copy()
    with pytest.raises(meshloom.UnsuitableError):
        closed.fair()
    assert closed == before


# ----- decimation and LOD ----------------------------------------------------


def test_decimate_to_a_face_count_keeps_columns_and_boundary():
    mesh = with_columns(tri_grid(12))
    holes = mesh.hole_count
    report = mesh.decimate(faces=100)
    assert report["stopped_by"] == "target"
    assert mesh.face_count in (99, 100)
    assert report["output"]["faces"] == mesh.face_count
    assert report["input"]["faces"] == 288
    assert mesh.hole_count == holes
    assert (mesh.attr_array("material", kind="face") == 3).all()
    t = mesh.attr_array("temperature")
    assert not np.isnan(t).any()
    mesh.validate()


def test_decimate_targets_and_errors():
    mesh = tri_grid(10)
    mesh.decimate(0.5)
    assert mesh.vertex_count == math.ceil(121 * 0.5)
    mesh = tri_grid(10)
    mesh.decimate(vertices=40, seams="free")
    assert mesh.vertex_count == 40
    # Locked boundary vertices never move.
    mesh = tri_grid(10)
    rim = {tuple(v.position) for v in mesh.vertices if v.is_boundary}
    mesh.decimate(vertices=60, boundary="lock")
    assert rim == {tuple(v.position) for v in mesh.vertices if v.is_boundary}
    # The old keyword means lock too, with a warning.
    mesh = tri_grid(10)
    with pytest.warns(DeprecationWarning, match="keep_boundary"):
        mesh.decimate(vertices=60, keep_boundary=True)
    assert rim == {tuple(v.position) for v in mesh.vertices if v.is_boundary}
    with pytest.raises(ValueError):
        mesh.decimate(ratio=0.5, faces=10)
    quads = meshloom.Mesh.from_arrays(*grid_arrays(3))
    with pytest.raises(meshloom.UnsuitableError) as err:
        quads.decimate(0.5)
    assert err.value.element is not None
    with pytest.raises(meshloom.UnsuitableError):
        tri_grid(3).decimate(1.5)


def test_lod_chain_levels_shrink_and_the_mesh_stays():
    mesh = with_columns(tri_grid(12))
    before = mesh.copy()
    levels = mesh.lod_chain([0.5, {"vertices": 30}, {"faces": 20}])
    assert mesh == before
    counts = [lv["mesh"].vertex_count for lv in levels]
    assert counts[0] == math.ceil(169 * 0.5) and counts[1] == 30
    assert levels[2]["mesh"].face_count <= 20
    for lv in levels:
        assert lv["report"]["output"]["vertices"] == lv["mesh"].vertex_count
        assert "temperature" in lv["mesh"].attrs("vertex")
        lv["mesh"].validate()
    with pytest.raises(meshloom.UnsuitableError):
        mesh.lod_chain([0.1, 0.5])


def test_remesh_evens_edge_lengths_keeps_columns_and_is_one_undo_unit():
    mesh = with_columns(tri_grid(12))
    positions, faces = mesh.to_arrays()
    lengths = [np.linalg.norm(positions[a] - positions[b])
               for f in faces for a, b in zip(f, np.roll(f, -1))]
    target = float(np.mean(lengths))
    holes = mesh.hole_count
    report = mesh.remesh(target, iterations=5)
    assert report["target_length"] == pytest.approx(target)
    assert report["output"]["faces"] == mesh.face_count
    assert mesh.hole_count == holes
    assert (mesh.attr_array("material", kind="face") == 3).all()
    assert not np.isnan(mesh.attr_array("temperature")).any()
    mesh.validate()
    with pytest.raises(ValueError):
        mesh.remesh(0.1, adaptive=0.01)
    with pytest.raises(ValueError):
        mesh.remesh(resample="sideways")
    quads = meshloom.Mesh.from_arrays(*grid_arrays(3))
    before = quads.copy()
    with pytest.raises(meshloom.UnsuitableError):
        quads.remesh()
    assert quads == before


def test_fill_holes_closes_every_hole_and_keeps_columns():
    mesh = with_columns(tri_grid(8))
    # Open two holes inside the grid, a triangle each, far apart (the
    # outer boundary is one more).
    faces = list(mesh.faces)
    for f in (faces[27], faces[45]):
        mesh.remove_face(f)
    assert mesh.hole_count == 3
    report = mesh.fill_holes(max_rim=20)
    assert report["holes_filled"] == 2
    assert mesh.hole_count == 1
    assert report["faces_added"] > 0
    assert (mesh.attr_array("material", kind="face") == 3).all()
    mesh.validate()


class Count:
    """A conserved count, as a Python rule."""

    def merge(self, values, weights):
        return sum(v for v in values if v is not None)

    def split(self, value, share):
        return value * share


def test_algorithms_run_python_rules_and_roll_back_when_they_raise():
    mesh = tri_grid(6)
    mesh.add_vertex_attr("count", rule=Count())
    for v in mesh.vertices:
        mesh.set_attr("count", v, 1)
    n = mesh.vertex_count
    mesh.decimate(vertices=20)
    total = sum(mesh.attr("count", v) for v in mesh.vertices)
    assert total == n  # merged counts add up

    class Boom(Count):
        calls = 0

        def merge(self, values, weights):
            Boom.calls += 1
            if Boom.calls > 3:
                raise ArithmeticError("rule failed")
            return super().merge(values, weights)

    mesh = tri_grid(6)
    mesh.add_vertex_attr("count", rule=Boom())
    for v in mesh.vertices:
        mesh.set_attr("count", v, 1)
    before = mesh.copy()
    with pytest.raises(ArithmeticError):
        mesh.decimate(vertices=20)
    assert mesh == before
