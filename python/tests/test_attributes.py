"""Attribute columns: stock rules by name, numpy bulk access, Python rules
inside split and collapse, and all-or-nothing when a Python rule raises."""

import numpy as np
import pytest

import meshloom
from conftest import grid_arrays


def test_stock_rules_by_name(square):
    square.add_face_attr("area", float, rule="conserved")
    square.add_face_attr("material", int)  # incompatible by default
    square.add_vertex_attr("selected", bool)  # contagion by default
    for f in square.faces:
        square.set_attr("area", f, 0.5)
        square.set_attr("material", f, 3)
    square.set_attr("selected", square.vertices[0], True)
    square.set_attr("selected", square.vertices[1], False)
    assert square.attrs("face") == {"area": ("float", "conserved"), "material": ("int", "incompatible")}
    inner = next(e for e in square.edges if not e.is_boundary)
    f = square.remove_edge(inner)
    assert square.attr("area", f) == 1.0  # conserved: sums
    assert square.attr("material", f) == 3  # incompatible: all agree
    h = square.find_halfedge(square.vertices[0], square.vertices[1])
    v = square.split_edge(h.edge)
    assert square.attr("selected", v) is True  # contagion: true wins


def test_unknown_rule_and_bad_combination_raise(square):
    with pytest.raises(ValueError):
        square.add_vertex_attr("x", float, rule="average")
    with pytest.raises(TypeError):
        square.add_vertex_attr("x", int, rule="interpolate")
    with pytest.raises(meshloom.ColumnError):
        square.add_vertex_attr("position", "vec3")
    with pytest.raises(meshloom.ColumnError):
        square.attr("nope", square.vertices[0])


def test_numpy_bulk_get_and_set():
    mesh = meshloom.Mesh.from_arrays(*grid_arrays(10))
    mesh.add_vertex_attr("t", float)
    assert np.isnan(mesh.attr_array("t")).all()  # absent reads as NaN
    values = np.linspace(0.0, 1.0, mesh.vertex_count)
    mesh.set_attr_array("t", values)
    out = mesh.attr_array("t")
    assert out.dtype == np.float64 and np.array_equal(out, values)
    assert mesh.attr("t", mesh.vertices[7]) == values[7]
    mesh.add_face_attr("id", int)
    with pytest.raises(ValueError):
        mesh.attr_array("id", kind="face")  # gaps and no fill
    assert (mesh.attr_array("id", kind="face", fill=-1) == -1).all()
    ids = np.arange(mesh.face_count, dtype=np.int64)
    mesh.set_attr_array("id", ids, kind="face")
    assert np.array_equal(mesh.attr_array("id", kind="face"), ids)
    mesh.add_vertex_attr("colour", "vec3")
    colours = np.random.default_rng(1).random((mesh.vertex_count, 3))
    mesh.set_attr_array("colour", colours)
    assert np.array_equal(mesh.attr_array("colour"), colours)
    with pytest.raises(ValueError):
        mesh.set_attr_array("t", values[:-1])
    # Positions are the vertex column "position".
    assert np.array_equal(mesh.attr_array("position"), mesh.positions)


def test_bulk_read_after_removals_skips_dead_slots(grid3):
    grid3.add_vertex_attr("t", float)
    grid3.set_attr_array("t", np.arange(16, dtype=float))
    interior = [v for v in grid3.vertices if v.degree == 4]
    grid3.remove_vertex(interior[0])
    out = grid3.attr_array("t")
    assert len(out) == 15
    assert np.array_equal(out, [grid3.attr("t", v) for v in grid3.vertices])


class Recorder:
    """A Python rule in the halfedge package's Attrib style: values merge by
    weighted sum and split by share; every call is recorded."""

    def __init__(self):
        self.calls = []

    def merge(self, values, weights):
        self.calls.append(("merge", list(values), list(weights)))
        return sum(v * w for v, w in zip(values, weights) if v is not None)

    def split(self, value, share):
        self.calls.append(("split", value, share))
        return value * share


def test_python_rules_run_inside_split_edge(square):
    vr, er = Recorder(), Recorder()
    square.add_vertex_attr("heat", rule=vr)
    square.add_edge_attr("length", rule=er)
    for v, t in zip(square.vertices, [0.0, 10.0, 20.0, 30.0]):
        square.set_attr("heat", v, t)
    for e in square.edges:
        square.set_attr("length", e, 1.0)
    h = square.find_halfedge(square.vertices[0], square.vertices[1])
    m = square.split_edge(h.edge, 0.25)
    # The new vertex: interpolated from both ends (no interpolate method, so
    # merge) with weights 0.75 / 0.25.
    assert ("merge", [0.0, 10.0], [0.75, 0.25]) in vr.calls
    assert square.attr("heat", m) == pytest.approx(2.5)
    # The edge: split into two pieces with shares 0.25 and 0.75.
    shares = sorted(c[2] for c in er.calls if c[0] == "split")
    assert shares == [0.25, 0.75]
    # The half from the origin (v0) takes share t = 0.25, the other 0.75.
    halves = {tuple(e.vertices): square.attr("length", e) for e in m.edges}
    assert halves == {(square.vertices[0], m): 0.25, (m, square.vertices[1]): 0.75}


def test_python_rules_run_inside_collapse(square):
    vr = Recorder()
    square.add_vertex_attr("heat", rule=vr)
    for v, t in zip(square.vertices, [0.0, 10.0, 20.0, 30.0]):
        square.set_attr("heat", v, t)
    h = square.find_halfedge(square.vertices[0], square.vertices[1])
    m = square.split_edge(h.edge, 0.5)
    vr.calls.clear()
    keep = square.vertices[1]
    h = square.find_halfedge(m, keep)
    assert square.collapse_edge(h) == keep
    merges = [c for c in vr.calls if c[0] == "merge"]
    assert merges, "collapse merged the vertex values through the Python rule"
    # The survivor comes first.
    assert merges[0][1][0] == 10.0


class Exploding(Recorder):
    def split(self, value, share):
        raise RuntimeError("no splitting today")


class ExplodingMerge(Recorder):
    def merge(self, values, weights):
        raise ZeroDivisionError("no merging today")


def test_raising_rule_leaves_the_mesh_unchanged(square):
    square.add_vertex_attr("t", float)
    square.set_attr_array("t", np.array([0.0, 10.0, 20.0, 30.0]))
    square.add_edge_attr("e", rule=Exploding())
    for e in square.edges:
        square.set_attr("e", e, 1.0)
    before = square.copy()
    vertices, edges = square.vertices, square.edges
    h = square.find_halfedge(vertices[0], vertices[1])
    with pytest.raises(RuntimeError, match="no splitting today") as err:
        square.split_edge(h.edge, 0.5)
    assert any("unchanged" in n for n in getattr(err.value, "__notes__", []))
    assert square == before
    assert square.vertices == vertices and square.edges == edges
    assert all(e.is_alive for e in edges)
    square.validate()
    # And the mesh still edits normally once the rule behaves.
    square.remove_attr("e", kind="edge")
    square.split_edge(h.edge, 0.5)
    assert square.vertex_count == 5


def test_raising_merge_during_collapse_leaves_the_mesh_unchanged(grid3):
    grid3.add_vertex_attr("v", rule=ExplodingMerge())
    for v in grid3.vertices:
        grid3.set_attr("v", v, 1.0)
    before = grid3.copy()
    h = next(h for h in grid3.halfedges if not h.edge.is_boundary and not h.origin.is_boundary)
    with pytest.raises(ZeroDivisionError):
        grid3.collapse_edge(h)
    assert grid3 == before
    assert h.is_alive
