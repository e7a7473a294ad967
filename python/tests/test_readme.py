"""The core API in one walk (two triangles, an interpolated column, a refused
flip, a stale key), and every Python block of the READMEs, run as written."""

import pathlib
import re

import pytest

import meshloom


def test_readme_example():
    # Two triangles sharing an edge; the outside of the square is one hole face.
    p = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]]
    mesh = meshloom.Mesh.from_arrays(p, [[0, 1, 2], [0, 2, 3]])
    assert (mesh.face_count, mesh.hole_count) == (2, 1)

    # A temperature on every vertex. Floats interpolate when edges split.
    mesh.add_vertex_attr("temperature", float)
    v = mesh.vertices
    for key, t in zip(v, [0.0, 10.0, 20.0, 30.0]):
        mesh.set_attr("temperature", key, t)
    h = mesh.find_halfedge(v[0], v[1])
    assert h is not None
    e = h.edge
    m = mesh.split_edge(e, 0.5)
    assert mesh.attr("temperature", m) == 5.0
    assert m.position == [0.5, 0.0, 0.0]

    # Operators check first; a refused one leaves the mesh exactly as it was.
    boundary = next(e for e in mesh.edges if e.is_boundary)
    before = mesh.copy()
    with pytest.raises(meshloom.RefusedError) as refused:
        mesh.check_flip_edge(boundary)
    assert refused.value.reason == "boundary"
    with pytest.raises(meshloom.RefusedError) as refused:
        mesh.flip_edge(boundary)
    assert refused.value.op == "flip_edge"
    assert refused.value.element == boundary
    assert mesh == before

    # Collapse m into v[1]: m's key is now stale, not a different vertex.
    h = mesh.find_halfedge(m, v[1])
    assert mesh.collapse_edge(h) == v[1]
    with pytest.raises(meshloom.StaleKeyError):
        m.position
    mesh.validate()


ROOT = pathlib.Path(__file__).resolve().parents[2]


@pytest.mark.parametrize("readme", ["README.md", "python/README.md"])
def test_readme_python_blocks_run(readme):
    # Every ```python block of the README, in order, in one namespace (a
    # later block may use what an earlier one made).
    text = (ROOT / readme).read_text(encoding="utf-8")
    blocks = re.findall(r"```python\n(.*?)```", text, flags=re.S)
    assert blocks, f"{readme} has no python block"
    namespace = {"__name__": "readme"}
    for i, block in enumerate(blocks):
        exec(compile(block, f"{readme}, python block {i + 1}", "exec"), namespace)
