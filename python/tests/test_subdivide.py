"""subdivide() on the library's one driver: the scheme and option words
are the library's, the crease-column check is the library's, the report
names the scheme by its word."""

import numpy as np
import pytest

import meshloom
from conftest import grid_arrays


def icosahedron():
    t = (1 + 5**0.5) / 2
    p = [[-1, t, 0], [1, t, 0], [-1, -t, 0], [1, -t, 0], [0, -1, t], [0, 1, t],
         [0, -1, -t], [0, 1, -t], [t, 0, -1], [t, 0, 1], [-t, 0, -1], [-t, 0, 1]]
    f = [[0, 11, 5], [0, 5, 1], [0, 1, 7], [0, 7, 10], [0, 10, 11], [1, 5, 9],
         [5, 11, 4], [11, 10, 2], [10, 7, 6], [7, 1, 8], [3, 9, 4], [3, 4, 2],
         [3, 2, 6], [3, 6, 8], [3, 8, 9], [4, 9, 5], [2, 4, 11], [6, 2, 10],
         [8, 6, 7], [9, 8, 1]]
    return meshloom.Mesh.from_arrays(np.array(p, float), np.array(f))


@pytest.mark.parametrize(
    "given, word",
    [("loop", "loop"), ("catmull_clark", "catmull-clark"),
     ("catmull-clark", "catmull-clark"), ("SQRT3", "sqrt3"), ("midpoint", "midpoint")],
)
def test_scheme_words_and_the_report(given, word):
    mesh = icosahedron()
    report = mesh.subdivide(given)
    assert report["scheme"] == word
    mesh.validate()


def test_unknown_words_list_the_choices():
    mesh = icosahedron()
    before = mesh.copy()
    for kwargs, listed in [
        ({"scheme": "butterfly"}, "loop, catmull-clark, sqrt3, midpoint"),
        ({"boundary": "corners"}, "crease, crease-and-corners"),
        ({"faces": "hexagons"}, "auto, quads, triangles"),
    ]:
        with pytest.raises(ValueError, match=listed):
            mesh.subdivide(**kwargs)
    assert mesh == before


@pytest.mark.parametrize("scheme", ["sqrt3", "midpoint"])
def test_a_crease_column_is_refused_where_the_scheme_takes_none(scheme):
    mesh = icosahedron()
    mesh.add_edge_attr("sharpness", float)
    before = mesh.copy()
    with pytest.raises(meshloom.UnsuitableError) as err:
        mesh.subdivide(scheme, crease_column="sharpness")
    assert "crease" in str(err.value)
    assert mesh == before
    # Loop takes it.
    report = mesh.subdivide("loop", crease_column="sharpness")
    assert report["output"]["faces"] == 80


def test_midpoint_faces_and_boundary_words():
    mesh = icosahedron()
    mesh.subdivide("midpoint", faces="quads")
    assert mesh.face_count == 60
    quads = meshloom.Mesh.from_arrays(*grid_arrays(2))
    with pytest.raises(meshloom.UnsuitableError):
        quads.subdivide("midpoint", faces="triangles")
    quads.subdivide("catmull_clark", boundary="crease_and_corners")
    p, _ = quads.to_arrays()
    # The grid's four corners stay.
    for corner in ([0, 0, 0], [2, 0, 0], [0, 2, 0], [2, 2, 0]):
        assert np.isclose(p, corner).all(axis=1).any()
