"""Every operator agrees with its check twin: where the check passes the
operator succeeds and the mesh validates; where it raises, the operator
raises the same refusal and the mesh is unchanged."""

import random

import pytest

import meshloom
from conftest import grid_arrays


def tri_grid():
    positions, quads = grid_arrays(3)
    tris = []
    for a, b, c, d in quads.tolist():
        tris += [[a, b, c], [a, c, d]]
    return meshloom.Mesh.from_arrays(positions, tris)


def calls(mesh, rng):
    """(name, args) of one random call of each operator."""
    f = rng.choice(mesh.faces)
    e = rng.choice(mesh.edges)
    h = rng.choice(mesh.halfedges)
    v = rng.choice(mesh.vertices)
    corners = f.vertices
    out = [
        ("split_edge", (e, rng.choice([0.5, 0.0, 1.5]))),
        ("split_face", (f, corners[0], corners[rng.randrange(len(corners))])),
        ("insert_edge", (corners[0], corners[-2])),
        ("poke_face", (f,)),
        ("collapse_edge", (h,)),
        ("flip_edge", (e,)),
        ("remove_edge", (e,)),
        ("remove_vertex", (v,)),
        ("remove_face", (f,)),
        ("triangulate", (f,)),
        ("extrude_face", (f, 0.5)),
        ("merge_faces", (f, rng.choice(mesh.faces))),
    ]
    if mesh.holes:
        hole = rng.choice(mesh.holes)
        out += [("fill_hole", (hole,)), ("fill_hole_triangulated", (hole,))]
    out.append(("split_vertex", (h, rng.choice(h.origin.outgoing))))
    return out


@pytest.mark.parametrize("seed", range(6))
def test_operators_agree_with_their_check_twins(seed):
    rng = random.Random(seed)
    for make in (tri_grid, lambda: meshloom.Mesh.from_arrays(*grid_arrays(3))):
        mesh = make()
        done = refused = 0
        for _ in range(12):
            for name, args in calls(mesh, rng):
                if not all(getattr(a, "is_alive", True) for a in args):
                    continue
                before = mesh.copy()
                try:
                    getattr(mesh, "check_" + name)(*args)
                except meshloom.RefusedError as check:
                    with pytest.raises(meshloom.RefusedError) as err:
                        getattr(mesh, name)(*args)
                    assert err.value.reason == check.reason
                    # insert_edge reports itself as split_face, the operator
                    # it runs: the check and the operator name the same one.
                    assert err.value.op == check.op
                    assert mesh == before
                    refused += 1
                    continue
                getattr(mesh, name)(*args)
                mesh.validate()
                done += 1
                if mesh.face_count < 4:
                    break
            if mesh.face_count < 4:
                break
        assert done > 0 and refused > 0


def test_cut_path_opens_a_seam():
    mesh = meshloom.Mesh.from_arrays(*grid_arrays(4))
    row = [v for v in mesh.vertices if v.position[1] == 2.0]
    row.sort(key=lambda v: v.position[0])
    mesh.check_cut_path(row)
    assert mesh.hole_count == 1
    opened = mesh.cut_path(row)
    mesh.validate()
    # A cut from boundary to boundary across the whole grid: the five path
    # vertices are doubled and the grid falls into two halves, each with
    # its own boundary loop.
    assert mesh.vertex_count == 25 + 5
    assert mesh.hole_count == 2 and len(opened) == 2
    assert mesh.face_count == 16


def test_triangulate_all_and_compact():
    mesh = meshloom.Mesh.from_arrays(*grid_arrays(3))
    left = mesh.triangulate_all()  # the faces it could not cut: none
    assert left == [] and mesh.face_count == 18
    assert all(f.degree == 3 for f in mesh.faces)
    maps = mesh.compact()
    assert len(maps) == mesh.vertex_count + mesh.halfedge_count + mesh.edge_count + mesh.face_count + mesh.hole_count
    mesh.validate()
