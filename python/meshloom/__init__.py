"""meshloom: polygon meshes as a half-edge graph whose attributes follow
every edit.

- Edges own the connectivity; holes are faces (``mesh.holes``).
- Keys (`Vertex`, `Halfedge`, `Edge`, `Face`) are small hashable objects;
  one whose element was removed raises `StaleKeyError`.
- Attribute columns merge and split by rule inside every operator: the stock
  rules by name, or a Python object with ``merge`` and ``split`` methods.
- Every operator has a ``check_*`` twin; a refused edit (`RefusedError`), or
  one whose Python rule raised, leaves the mesh exactly as it was.
- `Mesh.from_arrays` / `Mesh.to_arrays` with numpy; meshes pickle.
"""

from . import shapes
from ._meshloom import Edge, Face, FaceTree, Halfedge, Mesh, Vertex, __version__, read, read_with, write
from .errors import (
    BuildError,
    CancelledError,
    ColumnError,
    MeshloomError,
    NonFiniteError,
    QueryError,
    ReadError,
    ReentrantError,
    RefusedError,
    StaleKeyError,
    StaleTreeError,
    TooLargeError,
    UnsuitableError,
    ValidationError,
)

__all__ = [
    "Mesh",
    "Vertex",
    "Halfedge",
    "Edge",
    "Face",
    "FaceTree",
    "read",
    "read_with",
    "write",
    "shapes",
    "MeshloomError",
    "StaleKeyError",
    "RefusedError",
    "BuildError",
    "ValidationError",
    "ReadError",
    "ColumnError",
    "CancelledError",
    "UnsuitableError",
    "TooLargeError",
    "NonFiniteError",
    "ReentrantError",
    "QueryError",
    "StaleTreeError",
    "__version__",
]
