"""meshloom.shapes: textured primitives with a corner "uv" column laid out as
Blender's and a face "material" column per side."""

import math

import numpy as np
import pytest

import meshloom
from meshloom import shapes


def counts(m):
    return (m.vertex_count, m.edge_count, m.face_count)


def face_uvs(m):
    """Each face's corner UVs, as a list of (k, 2) arrays."""
    uv = m.attr_array("uv", "halfedge")
    index = {h: i for i, h in enumerate(m.halfedges)}
    return [uv[[index[h] for h in f.halfedges]] for f in m.faces]


def check_uvs(m):
    """Every corner of a face has a UV in [0, 1]², every face counter-clockwise."""
    assert "uv" in m.attrs("halfedge")
    area = 0.0
    for c in face_uvs(m):
        assert np.all(np.isfinite(c))
        assert np.all((c >= 0.0) & (c <= 1.0))
        for k in range(1, len(c) - 1):
            a, b = c[k] - c[0], c[k + 1] - c[0]
            cross = a[0] * b[1] - a[1] * b[0]
            assert cross > 0.0
            area += 0.5 * cross
    return area


def materials(m):
    values = m.attr_array("material", "face")
    return [int(np.sum(values == k)) for k in (shapes.SIDE, shapes.BOTTOM, shapes.TOP)]


def test_box():
    m = shapes.box((2.0, 1.0, 0.5), materials=True)
    m.validate()
    assert counts(m) == (8, 12, 6)
    assert m.is_closed
    assert check_uvs(m) == pytest.approx(0.375)
    assert materials(m) == [4, 1, 1]
    p, _ = m.to_arrays()
    assert np.allclose(np.abs(p), [1.0, 0.5, 0.25])


def test_cylinder_caps_and_open():
    m = shapes.cylinder(0.5, 1.0, 16, materials=True)
    m.validate()
    assert counts(m) == (32, 48, 18)
    assert m.euler_characteristic == 2
    disk = 0.5 * 16 * 0.24**2 * math.sin(2 * math.pi / 16)
    assert check_uvs(m) == pytest.approx(0.5 + 2 * disk)
    assert materials(m) == [16, 1, 1]
    tube = shapes.cylinder(segments=8, caps=False)
    assert counts(tube) == (16, 24, 8)
    assert tube.hole_count == 2
    assert check_uvs(tube) == pytest.approx(1.0)
    assert "material" not in tube.attrs("face")


def test_cone_and_frustum():
    m = shapes.cone(1.0, 0.0, 2.0, 12, materials=True)
    m.validate()
    assert counts(m) == (13, 24, 13)
    assert m.is_closed
    check_uvs(m)
    assert materials(m) == [12, 1, 0]
    f = shapes.cone(1.0, 0.5, 1.0, 12)
    assert f.face_count == 14


def test_grid():
    m = shapes.grid((4.0, 2.0), 4, 2)
    m.validate()
    assert counts(m) == (15, 22, 8)
    assert check_uvs(m) == pytest.approx(1.0)
    p, _ = m.to_arrays()
    assert p[:, 0].min() == -2.0 and p[:, 1].max() == 1.0


def test_spheres_and_torus():
    s = shapes.uv_sphere(2.0, 8, 4)
    s.validate()
    assert counts(s) == (26, 56, 32)
    assert check_uvs(s) == pytest.approx(3 / 4)
    i = shapes.icosphere(1.0, 2)
    i.validate()
    assert counts(i) == (162, 480, 320)
    assert check_uvs(i) == pytest.approx(20 * math.sqrt(3) / 121)
    t = shapes.torus(1.0, 0.25, 12, 6, materials=True)
    t.validate()
    assert counts(t) == (72, 144, 72)
    assert t.euler_characteristic == 0
    assert check_uvs(t) == pytest.approx(1.0)
    assert materials(t) == [72, 0, 0]


def test_without_uvs():
    m = shapes.box(uv=False)
    assert "uv" not in m.attrs("halfedge")


@pytest.mark.parametrize(
    "make",
    [
        lambda: shapes.box((1.0, 0.0, 1.0)),
        lambda: shapes.box((1.0, float("nan"), 1.0)),
        lambda: shapes.cylinder(segments=2),
        lambda: shapes.cylinder(segments=-3),
        lambda: shapes.cylinder(radius=-1.0),
        lambda: shapes.cone(0.0, 0.0),
        lambda: shapes.grid(cols=0),
        lambda: shapes.uv_sphere(rings=10**9),
        lambda: shapes.icosphere(subdivisions=40),
        lambda: shapes.torus(minor_radius=float("inf")),
    ],
)
def test_invalid_parameters_raise(make):
    with pytest.raises(meshloom.UnsuitableError) as info:
        make()
    assert info.value.algorithm in {"box", "cylinder", "cone", "grid", "uv_sphere", "icosphere", "torus"}
