"""Textured primitives: each mesh comes with a corner UV column ``"uv"``
laid out as Blender's primitives lay theirs out (UVs in [0, 1]², real
seams, no mirrored island) and, with ``materials=True``, an integer face
column ``"material"`` (incompatible rule) naming each natural side: `SIDE` (0) for walls and
one-sided shapes, `BOTTOM` (1) and `TOP` (2) for a box's ends and the caps.

Invalid parameters (a count out of range, a size that is not finite and
positive) raise `UnsuitableError`.

>>> from meshloom import shapes
>>> can = shapes.cylinder(0.5, 1.0, 24, materials=True)
>>> can.face_count, "uv" in can.attrs("halfedge")
(26, True)
"""

from typing import Sequence

from . import _meshloom
from ._meshloom import Mesh

__all__ = ["box", "cylinder", "cone", "grid", "uv_sphere", "icosphere", "torus", "SIDE", "BOTTOM", "TOP"]

#: The material id of walls and of every face of a one-sided shape.
SIDE = 0
#: The material id of the bottom (-z) end.
BOTTOM = 1
#: The material id of the top (+z) end.
TOP = 2


def box(size: Sequence[float] = (1.0, 1.0, 1.0), *, uv: bool = True, materials: bool = False) -> Mesh:
    """A box of sizes ``(x, y, z)`` centred on the origin: 8 vertices, 6
    quads; its UVs are Blender's cross (the four walls in a column, the
    bottom and the top beside the third), one island with 7 seam edges."""
    return _meshloom._shape_box(tuple(float(s) for s in size), uv, materials)


def cylinder(
    radius: float = 1.0,
    height: float = 2.0,
    segments: int = 32,
    *,
    caps: bool = True,
    uv: bool = True,
    materials: bool = False,
) -> Mesh:
    """A cylinder around the z axis from ``-height/2`` to ``height/2``,
    ``segments`` quads around and an n-gon cap at each end (``caps``).
    UVs: the wall a strip over the upper half (all of it without caps),
    the caps two disks below it."""
    return _meshloom._shape_cone(radius, radius, height, segments, caps, uv, materials, True)


def cone(
    radius_bottom: float = 1.0,
    radius_top: float = 0.0,
    height: float = 2.0,
    segments: int = 32,
    *,
    caps: bool = True,
    uv: bool = True,
    materials: bool = False,
) -> Mesh:
    """A cone (a frustum when both radii are positive) around the z axis,
    laid out as `cylinder`; an end of radius 0 is one apex vertex with no
    cap, and the wall's UVs are then its projection along the axis."""
    return _meshloom._shape_cone(radius_bottom, radius_top, height, segments, caps, uv, materials, False)


def grid(
    size: Sequence[float] = (2.0, 2.0),
    cols: int = 10,
    rows: int = 10,
    *,
    uv: bool = True,
    materials: bool = False,
) -> Mesh:
    """A flat grid of ``cols x rows`` quads in the z = 0 plane, of sizes
    ``(x, y)`` centred on the origin, with the unit square as its UVs."""
    return _meshloom._shape_grid(tuple(float(s) for s in size), cols, rows, uv, materials)


def uv_sphere(
    radius: float = 1.0,
    segments: int = 32,
    rings: int = 16,
    *,
    uv: bool = True,
    materials: bool = False,
) -> Mesh:
    """A latitude-longitude sphere (quads, a triangle fan at each pole);
    u is the longitude with the seam on the -x meridian, v the latitude."""
    return _meshloom._shape_uv_sphere(radius, segments, rings, uv, materials)


def icosphere(radius: float = 1.0, subdivisions: int = 2, *, uv: bool = True, materials: bool = False) -> Mesh:
    """A subdivided icosahedron on the sphere of ``radius`` with Blender's
    UV net (a band of ten triangles, a fan of five above and below)."""
    return _meshloom._shape_icosphere(radius, subdivisions, uv, materials)


def torus(
    major_radius: float = 1.0,
    minor_radius: float = 0.25,
    major_segments: int = 48,
    minor_segments: int = 12,
    *,
    uv: bool = True,
    materials: bool = False,
) -> Mesh:
    """A torus around the z axis in quads; u goes around the axis, v around
    the tube, each once over the unit square."""
    return _meshloom._shape_torus(major_radius, minor_radius, major_segments, minor_segments, uv, materials)
