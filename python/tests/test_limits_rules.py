"""Requests past their limits, rules that reach into their own mesh, and
fills over Python-rule columns: typed meshloom errors, the mesh unchanged."""

import numpy as np
import pytest

import meshloom


def tetra():
    p = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], float)
    f = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])
    return meshloom.Mesh.from_arrays(p, f)


class FirstRule:
    def merge(self, values, weights):
        v = [x for x in values if x is not None]
        return v[0] if v else None

    def split(self, value, share):
        return value


class ReachingRule(FirstRule):
    """A rule that uses its own mesh while an edit of it runs."""

    def __init__(self, how):
        self.how = how
        self.mesh = None

    def merge(self, values, weights):
        if self.how == "read":
            self.mesh.vertex_count
        elif self.how == "edit":
            self.mesh.split_edge(self.mesh.edges[0], 0.5)
        elif self.how == "columns":
            self.mesh.remove_attr("w")
        return super().merge(values, weights)


@pytest.mark.parametrize("how", ["read", "edit", "columns"])
@pytest.mark.parametrize("op", ["decimate", "collapse"])
def test_a_rule_that_uses_its_own_mesh_raises_a_meshloom_error(how, op):
    m = tetra()
    m.subdivide("loop", 2)
    rule = ReachingRule(how)
    rule.mesh = m
    m.add_vertex_attr("w", float, rule=rule)
    m.set_attr_array("w", np.arange(m.vertex_count, dtype=float))
    before = m.copy()
    with pytest.raises(meshloom.ReentrantError) as caught:
        if op == "decimate":
            m.decimate(0.5)
        else:
            for h in m.halfedges:
                try:
                    m.collapse_edge(h)
                    break
                except meshloom.RefusedError:
                    pass
    # An ordinary `except Exception` catches it; the mesh is as before.
    assert isinstance(caught.value, meshloom.MeshloomError)
    assert isinstance(caught.value, Exception)
    m.validate()
    assert m == before


def test_fill_stands_in_for_absent_values_of_a_python_rule_column():
    m = tetra()
    m.subdivide("loop", 1)
    m.add_vertex_attr("w", float, rule=FirstRule())
    m.set_attr_array("w", np.arange(m.vertex_count, dtype=float))
    m.decimate(0.5)
    dense = m.attr_array("w")
    filled = m.attr_array("w", fill=-1.0)
    assert list(filled) == [(-1.0 if x is None else x) for x in dense]


def test_subdivision_past_max_faces_raises_too_large_and_changes_nothing():
    m = tetra()
    with pytest.raises(meshloom.TooLargeError) as caught:
        m.subdivide("sqrt3", 100)
    e = caught.value
    assert (e.algorithm, e.option, e.limit) == ("sqrt3_subdivide", "max_faces", 10_000_000)
    assert e.estimate > e.limit
    assert (m.vertex_count, m.face_count) == (4, 4)
    with pytest.raises(meshloom.TooLargeError):
        m.subdivide("loop", 3, max_faces=100)
    m.subdivide("loop", 3, max_faces=256)
    assert m.face_count == 256


def test_positions_are_settable():
    m = tetra()
    p = m.positions
    m.positions = p * 2.0
    assert np.array_equal(m.positions, p * 2.0)
    with pytest.raises(meshloom.MeshloomError):
        m.positions = np.full((4, 3), np.inf)
    assert np.array_equal(m.positions, p * 2.0)


class RaisingMerge(FirstRule):
    def merge(self, values, weights):
        raise ZeroDivisionError("merge refused")


def test_a_raising_rule_in_a_collapse_restores_every_corner_value():
    # The defect: the rollback restored links and keys, but two corners
    # came back with other corners' values.
    m = tetra()
    m.subdivide("catmull_clark", 1)
    m.add_halfedge_attr("uv", "vec2")
    uv = np.stack([np.arange(m.halfedge_count, dtype=float), np.zeros(m.halfedge_count)], 1)
    m.set_attr_array("uv", uv, kind="halfedge")
    m.add_vertex_attr("w", float, rule=RaisingMerge())
    m.set_attr_array("w", np.arange(m.vertex_count, dtype=float))
    with pytest.raises(ZeroDivisionError) as caught:
        m.collapse_edge(m.halfedges[0])
    assert any("unchanged" in n for n in getattr(caught.value, "__notes__", []))
    assert np.array_equal(m.attr_array("uv", kind="halfedge"), uv)


def test_rims_over_max_refined_rim_are_filled_unrefined():
    # A 12-sided hole: refined by default, triangulated only below the bound.
    m = meshloom.Mesh.from_arrays(
        np.array(
            [[np.cos(a), np.sin(a), 0.0] for a in np.linspace(0, 2 * np.pi, 12, endpoint=False)]
            + [[0.0, 0.0, -1.0]],
            float,
        ),
        np.array([[(i + 1) % 12, i, 12] for i in range(12)]),
    )
    plain = m.copy()
    report = m.fill_holes(max_refined_rim=11)
    assert (report["holes_filled"], report["unrefined"], report["vertices_added"]) == (1, 1, 0)
    report = plain.fill_holes()
    assert report["unrefined"] == 0


class Refusal(Exception):
    """An exception of the caller's own, with a field of its own."""

    def __init__(self, message, code):
        super().__init__(message)
        self.code = code


class RefusingRule(FirstRule):
    """Refuses to merge (and so to interpolate) values; keeps what it raised."""

    def __init__(self):
        self.raised = []

    def merge(self, values, weights):
        e = Refusal("no merging here", 7)
        self.raised.append(e)
        raise e


def collapse_some_edge(m):
    for h in m.halfedges:
        try:
            return m.collapse_edge(h)
        except meshloom.RefusedError:
            pass


EDITS = {
    "collapse_edge": collapse_some_edge,
    "split_edge": lambda m: m.split_edge(m.edges[0], 0.5),
    "decimate": lambda m: m.decimate(0.5),
    "decimate on a copy": lambda m: m.decimate(0.5, progress=lambda info: True),
    "subdivide": lambda m: m.subdivide("loop", 1),
    "remesh": lambda m: m.remesh(0.2),
    "lod_chain": lambda m: m.lod_chain([0.5]),
}


@pytest.mark.parametrize("edit", list(EDITS))
def test_the_exception_a_rule_raised_reaches_the_caller_itself(edit):
    m = tetra()
    m.subdivide("loop", 2)
    rule = RefusingRule()
    m.add_vertex_attr("w", float, rule=rule)
    m.set_attr_array("w", np.arange(m.vertex_count, dtype=float))
    before = m.copy()
    keys = (m.vertices, m.edges, m.faces)
    with pytest.raises(Refusal) as caught:
        EDITS[edit](m)
    # The very object the rule raised: its type, message and fields.
    assert rule.raised and caught.value is rule.raised[0]
    assert (str(caught.value), caught.value.code) == ("no merging here", 7)
    assert any(
        "vertex column \"w\"" in n and "unchanged" in n
        for n in getattr(caught.value, "__notes__", [])
    )
    m.validate()
    # The same elements under the same keys, with the same values. (After
    # a rebuild is rolled back, the keys it issued stay stale: the pickled
    # state records that, so `m == before` holds only for local edits.)
    assert (m.vertices, m.edges, m.faces) == keys
    (p, f), (p0, f0) = m.to_arrays(), before.to_arrays()
    assert np.array_equal(p, p0) and np.array_equal(f, f0)
    assert m.attr_array("w") == before.attr_array("w")
    if edit not in ("subdivide", "remesh"):
        assert m == before
    # The column's rule reads back without probing.
    assert m.attrs()["w"] == ("object", "python")
