"""Every option word Python takes is the library's (read by its FromStr):
each word is accepted, `_` for `-` and any case too, and an unknown word
raises ValueError listing the library's words. The reports use the
library's vocabulary (`fixed`, `input`/`output` counts)."""

import numpy as np
import pytest

import meshloom
from conftest import grid_arrays


def bumpy_grid(n=6):
    positions, quads = grid_arrays(n)
    positions[:, 2] = np.sin(positions[:, 0]) * np.sin(positions[:, 1])
    tris = np.concatenate([quads[:, [0, 1, 2]], quads[:, [0, 2, 3]]])
    return meshloom.Mesh.from_arrays(positions, tris)


@pytest.mark.parametrize("method", ["uniform", "cotan", "taubin", "implicit", "TAUBIN"])
def test_smooth_methods(method):
    mesh = bumpy_grid()
    report = mesh.smooth(method, iterations=1)
    assert report["moved"] > 0 and report["fixed"] > 0


@pytest.mark.parametrize("weight", ["angle", "area", "uniform"])
def test_normal_weights(weight):
    mesh = bumpy_grid()
    fc = mesh.face_count() if callable(mesh.face_count) else mesh.face_count
    for kind, rows in [("vertex", 49), ("corner", 3 * fc)]:
        n = mesh.normals(kind, weight=weight)
        norms = np.linalg.norm(n, axis=1)
        unit = np.isclose(norms, 1)
        # Corner rows are per half-edge slot: a hole's half-edges have none.
        assert np.all(unit | (norms == 0))
        assert unit.sum() == rows
    b = mesh.to_triangle_buffers(weight=weight)
    assert b["normals"].shape[0] == b["positions"].shape[0]


@pytest.mark.parametrize("boundary", ["from_interior", "one_sided", "from-interior", "one-sided"])
def test_curvature_boundaries(boundary):
    c = bumpy_grid().curvature(boundary=boundary)
    assert c["mean"].shape == (49,)


@pytest.mark.parametrize("weights", ["cotan", "uniform"])
def test_fair_weights_and_fixed(weights):
    mesh = bumpy_grid()
    report = mesh.fair(order=1, weights=weights)
    assert report["moved"] == 25 and report["fixed"] > 0
    assert "constraints" not in report


@pytest.mark.parametrize("index_type,dtype", [("auto", np.uint16), ("uint16", np.uint16), ("uint32", np.uint32), ("u32", np.uint32)])
def test_index_types(index_type, dtype):
    b = bumpy_grid().to_triangle_buffers(index_type=index_type)
    assert b["indices"].dtype == dtype


@pytest.mark.parametrize("source", ["vertex", "corner", "halfedge"])
def test_column_sources(source):
    mesh = bumpy_grid()
    if source == "vertex":
        mesh.add_vertex_attr("t", float)
    else:
        mesh.add_halfedge_attr("t", float)
    b = mesh.to_triangle_buffers(columns=[("t", source)], normals=False)
    assert "t" in b["columns"]


def test_unknown_words_list_the_library_words():
    mesh = bumpy_grid()
    before = mesh.copy()
    for call, listed in [
        (lambda: mesh.smooth("gaussian"), "uniform, cotan, taubin, implicit"),
        (lambda: mesh.normals("vertex", weight="mass"), "angle, area, uniform"),
        (lambda: mesh.to_triangle_buffers(weight="mass"), "angle, area, uniform"),
        (lambda: mesh.curvature(boundary="inside"), "from-interior, one-sided"),
        (lambda: mesh.fair(weights="mean"), "cotan, uniform"),
        (lambda: mesh.to_triangle_buffers(index_type="int8"), "auto, u32"),
        (lambda: mesh.to_triangle_buffers(columns=[("x", "face")]), "vertex, corner"),
    ]:
        with pytest.raises(ValueError, match=listed):
            call()
    assert mesh == before


def test_reports_share_the_counts_vocabulary():
    mesh = bumpy_grid()
    mesh.remove_face(mesh.faces[0])
    holes = mesh.hole_count
    report = mesh.fill_holes()
    assert report["input"]["faces"] + report["faces_added"] == report["output"]["faces"]
    assert report["input"]["holes"] == holes
    d = bumpy_grid().decimate(0.5)
    assert d["stopped_by"] in ("target", "max_error", "no_collapses")
    assert set(d["input"]) == set(d["output"]) == set(report["input"])
