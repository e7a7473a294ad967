"""The exceptions meshloom raises. Every one derives from `MeshloomError`
and carries, as attributes, what the Rust error carries."""

from __future__ import annotations

from typing import Any, Optional


class MeshloomError(Exception):
    """Base class of every meshloom error."""


class StaleKeyError(MeshloomError, KeyError):
    """A key names an element that was removed (or one of another mesh).

    `element` is the stale key."""

    element: Any = None

    def __str__(self) -> str:  # KeyError would quote the message
        return str(self.args[0]) if self.args else ""


class RefusedError(MeshloomError, ValueError):
    """An operator's preconditions failed; the mesh is unchanged.

    `op` is the operator's name, `reason` a short identifier
    (``"link_condition"``, ``"boundary"``, ...), `element` the key it was
    called on (or the offending one)."""

    op: str = ""
    reason: str = ""
    element: Any = None


class BuildError(MeshloomError, ValueError):
    """Polygons that cannot form a half-edge mesh. `face` is the index of the
    offending face in the input (or None), `kind` a short identifier
    (``"non_manifold_edge"``, ``"index_out_of_range"``, ...)."""

    face: Optional[int] = None
    kind: str = ""


class ValidationError(MeshloomError):
    """A structural rule is broken. `rule` is its number, `element` the key
    where it broke (or None)."""

    rule: int = 0
    element: Any = None


class ReadError(MeshloomError, OSError):
    """A mesh file could not be read or written. `file` is its path (or
    None), `line` the 1-based line for text input, `byte` the offset for
    binary input (either may be None)."""

    file: Optional[str] = None
    line: Optional[int] = None
    byte: Optional[int] = None


class ColumnError(MeshloomError, LookupError):
    """An attribute column is missing, exists already, or holds another type
    or rule than asked."""


class CancelledError(MeshloomError):
    """An algorithm was cancelled by its progress callback (which returned
    False); the mesh is unchanged. `algorithm` names it."""

    algorithm: str = ""


class UnsuitableError(MeshloomError, ValueError):
    """An algorithm cannot run on this mesh or with these options (a face
    that is not a triangle, a step out of range, a region with nothing
    fixed, ...); the mesh is unchanged. `algorithm` names it, `reason` says
    why, `element` is the key it names (or None)."""

    algorithm: str = ""
    reason: str = ""
    element: Any = None


class ReentrantError(MeshloomError, RuntimeError):
    """A mesh was used from inside one of its own attribute rules while
    meshloom was editing it (a rule's merge or split may only compute a
    value). The edit is rolled back and this is raised."""


class TooLargeError(MeshloomError, ValueError):
    """An algorithm's options ask for a result larger than its limit (the
    estimate is made before any work; the mesh is unchanged). `algorithm`
    names it, `estimate` and `limit` are face counts, `option` names the
    keyword that raises the limit."""

    algorithm: str = ""
    estimate: int = 0
    limit: int = 0
    option: str = ""


class NonFiniteError(MeshloomError, ArithmeticError):
    """An algorithm's arithmetic would leave the range of float64 on this
    input (coordinates near the largest finite values); the mesh is
    unchanged. `algorithm` names it, `element` is the first key it names."""

    algorithm: str = ""
    element: Any = None


class QueryError(MeshloomError, ValueError):
    """A spatial query refused its input (a point, ray or bound that is
    not finite or is negative, a mesh without positions)."""


class StaleTreeError(QueryError):
    """A `FaceTree` was used after its mesh changed: `refit()` it when only
    positions moved, or build a new one with `Mesh.tree()`."""


__all__ = [
    "MeshloomError",
    "StaleKeyError",
    "RefusedError",
    "BuildError",
    "ValidationError",
    "ReadError",
    "ColumnError",
    "CancelledError",
    "UnsuitableError",
    "ReentrantError",
    "TooLargeError",
    "NonFiniteError",
    "QueryError",
    "StaleTreeError",
]
