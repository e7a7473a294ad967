"""Pickling through the serde form, files with repair policies, errors."""

import pickle
from concurrent.futures import ProcessPoolExecutor

import numpy as np
import pytest

import meshloom
from conftest import grid_arrays


class Sum:
    def merge(self, values, weights):
        return sum(v for v in values if v is not None)

    def split(self, value, share):
        return value * share


def test_pickle_round_trip_equals_the_original():
    mesh = meshloom.Mesh.from_arrays(*grid_arrays(6))
    mesh.add_vertex_attr("t", float)
    mesh.set_attr_array("t", np.random.default_rng(3).random(mesh.vertex_count))
    mesh.add_face_attr("material", int)
    mesh.set_attr_array("material", np.arange(mesh.face_count), kind="face")
    mesh.add_edge_attr("mass", rule=Sum())
    for e in mesh.edges:
        mesh.set_attr("mass", e, 2.0)
    # Edits first, so that keys have generations and free slots.
    mesh.remove_vertex(next(v for v in mesh.vertices if v.degree == 4))
    back = pickle.loads(pickle.dumps(mesh))
    assert back == mesh
    assert back is not mesh
    assert np.array_equal(back.attr_array("t"), mesh.attr_array("t"))
    assert back.attrs("edge") == {"mass": ("object", "python")}
    # The Python rule travels too: it runs in the copy's edits.
    e = next(e for e in back.edges if not e.is_boundary)
    back.split_edge(e)
    assert sorted(x for x in back.attr_array("mass", kind="edge") if x != 2.0) == [1.0, 1.0]
    back.validate()
    # Changing the copy makes it differ.
    assert back != mesh


def test_unpickling_a_corrupt_state_raises():
    mesh = meshloom.Mesh.from_arrays(*grid_arrays(2))
    state = mesh.__getstate__()
    broken = meshloom.Mesh()
    with pytest.raises(ValueError):
        broken.__setstate__((state[0][:-20], state[1]))


def _faces(mesh):
    return mesh.face_count


def test_meshes_travel_to_worker_processes():
    meshes = [meshloom.Mesh.from_arrays(*grid_arrays(n)) for n in (1, 2, 3)]
    with ProcessPoolExecutor(max_workers=2) as pool:
        assert list(pool.map(_faces, meshes)) == [1, 4, 9]


def test_write_and_read_files(tmp_path):
    mesh = meshloom.Mesh.from_arrays(*grid_arrays(3))
    for ext in ("obj", "off", "ply", "stl", "obj.gz"):
        path = tmp_path / f"grid.{ext}"
        meshloom.write(mesh, path)
        back = meshloom.read(path)
        if ext == "stl":  # triangles only
            assert back.face_count == 18
        else:
            p, f = back.to_arrays()
            assert np.array_equal(f, mesh.to_arrays()[1])
            assert np.array_equal(p, mesh.positions)


def test_read_error_names_file_and_line(tmp_path):
    path = tmp_path / "bad.off"
    path.write_text("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n")
    with pytest.raises(meshloom.ReadError) as err:
        meshloom.read(path)
    assert err.value.file == str(path)
    assert err.value.line == 6
    assert isinstance(err.value, OSError)
    with pytest.raises(meshloom.ReadError) as err:
        meshloom.read(tmp_path / "missing.obj")
    assert err.value.file.endswith("missing.obj")


def test_repair_policies(tmp_path):
    path = tmp_path / "dirty.obj"
    # The second face repeats the first one, and vertex 5 is unused.
    path.write_text("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 9 9 9\nf 1 2 3\nf 1 2 3\nf 1 3 4\n")
    with pytest.raises(meshloom.ReadError) as err:
        meshloom.read(path)
    assert err.value.line is not None
    mesh, report = meshloom.read_with(path, repair="all")
    assert mesh.face_count == 2 and mesh.vertex_count == 4
    assert report["duplicate_faces"] == 1
    assert report["unreferenced_vertices"] == 1
    mesh, report = meshloom.read_with(path, repair=["drop_duplicate_faces", "drop_unreferenced_vertices"])
    assert mesh.face_count == 2
    with pytest.raises(ValueError):
        meshloom.read_with(path, repair=["tidy_up"])


def test_folder_example_runs(tmp_path):
    import pathlib
    import subprocess
    import sys

    example = pathlib.Path(__file__).resolve().parent.parent / "examples" / "process_folder.py"
    src = tmp_path / "in"
    src.mkdir()
    meshloom.write(meshloom.Mesh.from_arrays(*grid_arrays(3)), src / "grid.off")
    meshloom.write(meshloom.Mesh.from_arrays(*grid_arrays(1)), src / "quad.obj")
    run = subprocess.run(
        [sys.executable, str(example), str(src), str(tmp_path / "out"), "--workers", "2"],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert run.returncode == 0, run.stderr
    assert run.stdout.count("->") == 2
    grid = meshloom.read(tmp_path / "out" / "grid.obj")
    assert grid.is_closed and grid.hole_count == 0
    assert all(f.degree == 3 for f in grid.faces)
