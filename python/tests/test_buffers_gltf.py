"""glTF read and write, triangle buffers both ways."""

import os

import numpy as np
import pytest

import meshloom
from conftest import grid_arrays

DATA = "/work/shared/data/meshes"
GLTF = os.path.join(DATA, "gltf")
need_data = pytest.mark.skipif(not os.path.isdir(GLTF), reason="shared test meshes not present")


def cube():
    p = np.array([[x, y, z] for z in (0, 1) for y in (0, 1) for x in (0, 1)], float)
    f = [[0, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [2, 6, 7, 3], [0, 4, 6, 2], [1, 3, 7, 5]]
    return meshloom.Mesh.from_arrays(p, f)


@need_data
@pytest.mark.parametrize("name", ["BoxTextured.glb", "BoxTextured/BoxTextured.gltf"])
def test_read_gltf_box_welds_to_a_closed_cube(name):
    mesh = meshloom.read(os.path.join(GLTF, name))
    assert (mesh.vertex_count, mesh.face_count) == (8, 12)
    assert mesh.is_closed
    assert "texcoord" in mesh.attrs("halfedge")
    uv = mesh.attr_array("texcoord", kind="halfedge")
    assert uv.shape == (mesh.halfedge_count, 2)


@need_data
@pytest.mark.parametrize("ext", [".glb", ".gltf"])
def test_gltf_round_trip_keeps_triangles_and_uvs(tmp_path, ext):
    mesh = meshloom.read(os.path.join(GLTF, "BoxTextured.glb"))
    out = tmp_path / ("box" + ext)
    meshloom.write(mesh, out)
    back = meshloom.read(out)
    assert (back.vertex_count, back.face_count) == (mesh.vertex_count, mesh.face_count)
    p0, f0 = mesh.to_arrays()
    p1, f1 = back.to_arrays()
    assert np.allclose(np.sort(p0, axis=0), np.sort(p1, axis=0))
    a = mesh.to_triangle_buffers(columns=["texcoord"], normals=False)
    b = back.to_triangle_buffers(columns=["texcoord"], normals=False)
    key = lambda buf: sorted(map(tuple, np.round(np.hstack([buf["positions"], buf["columns"]["texcoord"]]), 5)))
    assert key(a) == key(b)


@need_data
def test_read_gltf_engine_and_bad_files():
    mesh, report = meshloom.read_with(os.path.join(GLTF, "2CylinderEngine.glb"), repair="all")
    assert mesh.face_count > 1000
    with pytest.raises(meshloom.ReadError) as err:
        meshloom.read(os.path.join(GLTF, "invalid", "BoxWithInfinites.glb"))
    assert err.value.file.endswith("BoxWithInfinites.glb")


def test_triangle_buffers_shapes_and_dtypes():
    mesh = cube()
    b = mesh.to_triangle_buffers()
    assert b["positions"].shape == (24, 3) and b["positions"].dtype == np.float32
    assert b["normals"].shape == (24, 3) and b["normals"].dtype == np.float32
    assert b["indices"].shape == (12, 3) and b["indices"].dtype == np.uint16
    assert b["triangle_faces"].shape == (12,)
    assert b["vertex_sources"].shape == (24,)
    assert np.allclose(np.linalg.norm(b["normals"], axis=1), 1)
    smooth = mesh.to_triangle_buffers(crease_angle=None, index_type="uint32", dtype="float64")
    assert smooth["positions"].shape == (8, 3) and smooth["positions"].dtype == np.float64
    assert smooth["indices"].dtype == np.uint32
    plain = mesh.to_triangle_buffers(normals=False)
    assert "normals" not in plain and plain["positions"].shape == (8, 3)
    with pytest.raises(ValueError):
        mesh.to_triangle_buffers(index_type="int8")


def test_triangle_buffers_split_at_uv_seams_and_come_back():
    positions, faces = grid_arrays(2)
    mesh = meshloom.Mesh.from_arrays(positions, faces)
    mesh.add_halfedge_attr("uv", "vec2")
    mesh.add_vertex_attr("heat", float)
    mesh.set_attr_array("heat", np.arange(mesh.vertex_count, dtype=float))
    # A seam along x = 1: corners of faces left of it get u, right u + 10.
    uv = []
    for h in mesh.halfedges:
        x, y, _ = h.origin.position
        right = (not h.face.is_hole) and np.mean([v.position[0] for v in h.face.vertices]) > 1
        uv.append([x + (10 if right else 0), y])
    mesh.set_attr_array("uv", np.array(uv), kind="halfedge")
    b = mesh.to_triangle_buffers(normals=False, columns=["uv", ("heat", "vertex")])
    assert b["columns"]["uv"].shape == (12, 2)  # 9 vertices + 3 on the seam
    assert b["columns"]["heat"].shape == (12, 1)
    assert b["indices"].shape == (8, 3)
    back = meshloom.Mesh.from_triangle_buffers(
        b["positions"], b["indices"],
        columns={"uv": (b["columns"]["uv"], "corner"), "heat": b["columns"]["heat"][:, 0]},
    )
    assert (back.vertex_count, back.face_count, back.hole_count) == (9, 8, 1)
    assert "uv" in back.attrs("halfedge") and "heat" in back.attrs("vertex")
    heat = dict(zip(map(tuple, back.positions), back.attr_array("heat")))
    for p, h in zip(mesh.positions, mesh.attr_array("heat")):
        assert heat[tuple(p)] == h


def test_from_triangle_buffers_errors():
    p = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0]], float)
    m = meshloom.Mesh.from_triangle_buffers(p, np.array([[0, 1, 2]], np.uint32), normals=np.tile([0, 0, 1.0], (3, 1)))
    assert (m.vertex_count, m.face_count) == (3, 1)
    assert "normal" in m.attrs("halfedge")
    with pytest.raises(ValueError):
        meshloom.Mesh.from_triangle_buffers(p, np.array([[0, 1, 5]]))
    with pytest.raises(ValueError):
        meshloom.Mesh.from_triangle_buffers(p, np.array([0, 1]))
    # Three triangles on one edge: not a half-edge mesh.
    p4 = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1]], float)
    with pytest.raises(meshloom.BuildError):
        meshloom.Mesh.from_triangle_buffers(p4, np.array([[0, 1, 2], [1, 0, 3], [0, 1, 4]]))
