"""Garbage collection of Python-rule columns, bulk attribute reads and
writes, and the all-or-nothing edit through the journal transaction."""

import gc
import weakref

import numpy as np
import pytest

import meshloom
from conftest import grid_arrays


class Keep:
    """A Python rule that keeps the first present value."""

    def merge(self, values, weights):
        return next((v for v in values if v is not None), None)

    def split(self, value, share):
        return value


class Box:
    """A value that refers to its mesh: a cycle through the column."""

    def __init__(self, mesh):
        self.mesh = mesh


def test_a_cycle_through_a_python_rule_column_is_collected():
    mesh = meshloom.Mesh.from_arrays(*grid_arrays(2))
    mesh.add_vertex_attr("box", rule=Keep())
    box = Box(mesh)
    mesh.set_attr("box", mesh.vertices[0], box)
    # A key object as a value is a cycle too (the key holds its mesh).
    mesh.add_face_attr("key", rule=Keep())
    f = mesh.faces[0]
    mesh.set_attr("key", f, f)
    dead_mesh, dead_box = weakref.ref(mesh), weakref.ref(box)
    del mesh, box, f
    gc.collect()
    assert dead_mesh() is None and dead_box() is None


def test_a_rule_object_that_holds_its_mesh_is_collected():
    class Holder(Keep):
        pass

    mesh = meshloom.Mesh.from_arrays(*grid_arrays(1))
    rule = Holder()
    rule.mesh = mesh
    mesh.add_edge_attr("h", rule=rule)
    dead = weakref.ref(rule)
    del mesh, rule
    gc.collect()
    assert dead() is None


def test_copies_share_values_without_confusing_the_collector():
    mesh = meshloom.Mesh.from_arrays(*grid_arrays(2))
    mesh.add_vertex_attr("box", rule=Keep())
    box = Box(None)
    for v in mesh.vertices:
        mesh.set_attr("box", v, box)
    copy = mesh.copy()
    del mesh
    gc.collect()
    # The copy's values are alive and usable.
    assert all(copy.attr("box", v) is box for v in copy.vertices)
    copy.split_edge(copy.edges[0])
    gc.collect()
    assert box.mesh is None


def test_live_meshes_survive_collection():
    mesh = meshloom.Mesh.from_arrays(*grid_arrays(2))
    mesh.add_vertex_attr("box", rule=Keep())
    mesh.set_attr("box", mesh.vertices[0], Box(mesh))
    gc.collect()
    assert mesh.attr("box", mesh.vertices[0]).mesh is mesh
    mesh.validate()


# ----- bulk reads and writes -------------------------------------------------


@pytest.mark.parametrize(
    "dtype, make",
    [
        (float, lambda n, r: r.random(n)),
        (int, lambda n, r: r.integers(-(2**40), 2**40, n)),
        (bool, lambda n, r: r.random(n) > 0.5),
        ("vec2", lambda n, r: r.random((n, 2))),
        ("vec3", lambda n, r: r.random((n, 3))),
        ("vec4", lambda n, r: r.random((n, 4))),
    ],
)
def test_bulk_write_then_read_is_exact(dtype, make):
    rng = np.random.default_rng(3)
    mesh = meshloom.Mesh.from_arrays(*grid_arrays(9))
    mesh.add_vertex_attr("x", dtype)
    values = make(mesh.vertex_count, rng)
    mesh.set_attr_array("x", values)
    back = mesh.attr_array("x")
    assert back.shape == values.shape
    assert np.array_equal(back, values)
    if back.dtype == np.float64:
        assert np.array_equal(back.view(np.uint64), values.view(np.uint64))


def test_bulk_read_after_removals_gathers_live_elements():
    mesh = meshloom.Mesh.from_arrays(*grid_arrays(4))
    mesh.add_vertex_attr("t", float)
    mesh.set_attr_array("t", np.arange(mesh.vertex_count, dtype=float))
    v = mesh.vertices[6]
    mesh.remove_vertex(v)
    t = mesh.attr_array("t")
    assert t.shape == (mesh.vertex_count,)
    assert 6.0 not in t
    # Keyed reads agree with the array.
    assert [mesh.attr("t", w) for w in mesh.vertices] == t.tolist()
    # Key by key, the same column reads the same.
    mesh.add_face_attr("area", float)
    for i, f in enumerate(mesh.faces):
        mesh.set_attr("area", f, float(i))
    assert mesh.attr_array("area", kind="face").tolist() == list(map(float, range(mesh.face_count)))


def test_gaps_read_as_nan_or_fill():
    mesh = meshloom.Mesh.from_arrays(*grid_arrays(2))
    mesh.add_vertex_attr("t", float)
    mesh.add_vertex_attr("i", int)
    vs = mesh.vertices
    mesh.set_attr("t", vs[1], 2.0)
    mesh.set_attr("i", vs[1], 7)
    t = mesh.attr_array("t")
    assert np.isnan(t[0]) and t[1] == 2.0
    assert mesh.attr_array("i", fill=-1).tolist()[:2] == [-1, 7]
    with pytest.raises(ValueError):
        mesh.attr_array("i")
    # Writing NaN clears; filling again makes the read whole.
    full = np.arange(9, dtype=float)
    full[4] = np.nan
    mesh.set_attr_array("t", full)
    assert mesh.attr("t", vs[4]) is None
    full[4] = 4.0
    mesh.set_attr_array("t", full)
    assert np.array_equal(mesh.attr_array("t"), np.arange(9.0))


# ----- Python-rule edits through the journal ---------------------------------


class Tally:
    def merge(self, values, weights):
        return sum(v for v in values if v is not None)

    def split(self, value, share):
        return value * share


class FailingSplit(Tally):
    def split(self, value, share):
        raise ZeroDivisionError("split refused")


def test_a_raising_rule_rolls_back_every_column_and_key():
    mesh = meshloom.Mesh.from_arrays(*grid_arrays(3))
    mesh.add_vertex_attr("t", float)
    mesh.set_attr_array("t", np.arange(16.0))
    mesh.add_edge_attr("mass", rule=FailingSplit())
    e = mesh.edges[4]
    mesh.set_attr("mass", e, 2.0)
    before = mesh.copy()
    keys = mesh.vertices + mesh.faces
    with pytest.raises(ZeroDivisionError) as err:
        mesh.split_edge(e, 0.25)
    assert any("unchanged" in n for n in getattr(err.value, "__notes__", []))
    assert mesh == before
    assert all(k.is_alive for k in keys)
    assert mesh.attr("mass", e) == 2.0
    mesh.validate()
    # Edits that do not touch the failing edge still work.
    other = mesh.edges[0]
    mesh.split_edge(other)
    assert mesh.vertex_count == 17


def test_python_rule_edits_run_many_times():
    mesh = meshloom.Mesh.from_arrays(*grid_arrays(10))
    mesh.add_edge_attr("mass", rule=Tally())
    for e in mesh.edges:
        mesh.set_attr("mass", e, 1.0)
    total = mesh.edge_count
    for _ in range(200):
        mesh.split_edge(mesh.edges[len(mesh.edges) // 2], 0.5)
    masses = [mesh.attr("mass", e) for e in mesh.edges]
    assert abs(sum(m for m in masses if m is not None) - total) < 1e-9
    mesh.validate()
