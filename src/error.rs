//! Error types. Every error names what was wrong and where.

use std::fmt;
use std::sync::Arc;

use crate::keys::{AnyKey, ElementKind};

/// What can go wrong in a mesh operation.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    /// Occurs when a key names an element that was removed, or was never
    /// issued by this mesh.
    #[error("{0} is stale: its element was removed or never existed in this mesh")]
    StaleKey(AnyKey),
    /// Occurs when a geometric operation needs positions and the mesh has
    /// none (it was built with [`Mesh::from_faces`](crate::Mesh::from_faces)).
    #[error("the mesh has no vertex positions")]
    NoPositions,
    /// Occurs when a position is NaN or infinite.
    #[error("{key} would get the non-finite position {position:?}")]
    NonFinitePosition {
        /// The vertex.
        key: AnyKey,
        /// The rejected position.
        position: [f64; 3],
    },
    /// Occurs when an attribute is added under a name its arena already uses.
    #[error("the {kind} attribute {name:?} exists already")]
    AttributeExists {
        /// The arena.
        kind: ElementKind,
        /// The name.
        name: String,
    },
    /// Occurs when no attribute of that name exists on that arena.
    #[error("no {kind} attribute named {name:?}")]
    AttributeMissing {
        /// The arena.
        kind: ElementKind,
        /// The name.
        name: String,
    },
    /// Occurs when an attribute exists with another value type or rule.
    #[error("the {kind} attribute {name:?} holds {found}, not {expected}")]
    AttributeType {
        /// The arena.
        kind: ElementKind,
        /// The name.
        name: String,
        /// The type asked for.
        expected: &'static str,
        /// The type stored.
        found: &'static str,
    },
    /// Occurs when an attribute handle names a column that was removed, or
    /// one of another mesh.
    #[error("the {kind} attribute handle {name:?} is stale: its column was removed or belongs to another mesh")]
    AttributeHandle {
        /// The arena.
        kind: ElementKind,
        /// The name the handle was made for.
        name: String,
    },
    /// Occurs when an operator's preconditions fail. The mesh is unchanged.
    #[error("{op} refused on {key}: {reason}")]
    Refused {
        /// The operator's name, as in its method.
        op: &'static str,
        /// The element the operator was called on (or the offending one).
        key: AnyKey,
        /// Why.
        reason: Refusal,
    },
    /// Occurs when a long-running algorithm's progress callback asked it
    /// to stop. The mesh is exactly as it was before the call.
    #[error("{algorithm} was cancelled; the mesh is unchanged")]
    Cancelled {
        /// The algorithm that stopped.
        algorithm: &'static str,
    },
    /// Occurs when a mesh does not meet what an algorithm needs (a face
    /// that is not a triangle for Loop subdivision, a region mask that
    /// selects nothing, options that contradict each other). The mesh is
    /// unchanged.
    #[error("{algorithm} cannot run{}: {reason}", .key.map(|k| format!(" at {k}")).unwrap_or_default())]
    Unsuitable {
        /// The algorithm.
        algorithm: &'static str,
        /// The element where the need was not met, when one can be named.
        key: Option<AnyKey>,
        /// What was needed and not found.
        reason: String,
    },
    /// Occurs when an algorithm's options ask for a result larger than the
    /// limit the caller set (or the default limit): the estimate is made
    /// from the mesh and the options before any work. The mesh is
    /// unchanged; raise the named option to allow it.
    #[error("{algorithm} would make about {estimate} faces, more than the limit of {limit} (raise `{option}` to allow it)")]
    TooLarge {
        /// The algorithm.
        algorithm: &'static str,
        /// The estimated number of faces of the result.
        estimate: u64,
        /// The limit in force.
        limit: u64,
        /// The option that sets the limit.
        option: &'static str,
    },
    /// Occurs when an algorithm's arithmetic leaves the range of `f64` on
    /// this input (coordinates near the largest finite values): the result
    /// would hold a NaN or an infinity. The mesh is unchanged.
    #[error("{algorithm} would give {key} the non-finite position {position:?} (the coordinates are too large for its arithmetic)")]
    NonFiniteResult {
        /// The algorithm.
        algorithm: &'static str,
        /// The first element of the result with a non-finite value.
        key: AnyKey,
        /// That value.
        position: [f64; 3],
    },
    /// Occurs when input polygons cannot form a half-edge mesh.
    #[error(transparent)]
    Build(#[from] BuildError),
    /// Occurs when a mesh (deserialized, or edited through the low-level
    /// setters) breaks a structural rule.
    #[error(transparent)]
    Invalid(#[from] ValidationError),
    /// Occurs when a column's rule failed (a
    /// [fallible rule](crate::attr::Rule::FALLIBLE) returned an error): the
    /// operator, algorithm or transaction that ran it changed nothing. The
    /// [`RuleError`] names the column ([`RuleError::column`]) and says what
    /// the rule said.
    #[error("{}; the mesh is unchanged", .0.in_context())]
    Rule(#[source] RuleError),
}

/// Why an operator refused. The mesh is left exactly as it was.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum Refusal {
    /// The link condition fails: the collapse would pinch the surface.
    #[error("the link condition fails (the collapse would make the mesh non-manifold)")]
    LinkCondition,
    /// The result would not be a manifold half-edge mesh.
    #[error("the result would be non-manifold")]
    NonManifold,
    /// The operator needs triangles on both sides.
    #[error("the faces beside the edge are not both triangles")]
    NotTriangles,
    /// The edge to be made exists already.
    #[error("the edge to be made exists already")]
    EdgeExists,
    /// The element lies on a boundary where the operator needs an interior
    /// one (or the reverse).
    #[error("the element is on the boundary")]
    Boundary,
    /// The operator works on faces, not holes (or on holes, not faces).
    #[error("the face is a hole")]
    Hole,
    /// The operator needs a hole.
    #[error("the face is not a hole")]
    NotHole,
    /// Removing the edge would disconnect the mesh.
    #[error("the edge is a bridge: removing it would disconnect the mesh")]
    Bridge,
    /// A face would be left with fewer than three sides.
    #[error("a face would be left with fewer than three sides")]
    Degenerate,
    /// The face has no area (its corners are collinear or coincide), so it
    /// has no normal to move along.
    #[error("the face has zero area, so it has no normal to move along")]
    ZeroArea,
    /// The vertices are not both corners of the face.
    #[error("the vertices are not corners of the face")]
    NotInFace,
    /// The two elements are the same, or already adjacent.
    #[error("the elements are the same or already adjacent")]
    Adjacent,
    /// The two elements are not adjacent.
    #[error("the elements are not adjacent")]
    NotAdjacent,
    /// A parameter is out of its range (for example `t` outside 0..=1).
    #[error("parameter out of range: {0}")]
    Parameter(&'static str),
    /// The operator needs quads where it found none (a loop cut's edge
    /// with no quad beside it).
    #[error("no quad beside the edge")]
    NotQuads,
    /// The path or ring the operator follows passes through an element
    /// twice, or comes back reversed.
    #[error("the path crosses itself or comes back reversed")]
    Crossing,
    /// The operation would remove every element of the mesh or of a
    /// component that must remain.
    #[error("the operation would leave nothing behind")]
    Empty,
}

/// Why polygons could not be built into a mesh. Face and vertex numbers are
/// the caller's indices (0-based positions in the input).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum BuildError {
    /// Occurs when a face refers to a vertex index past the vertex count.
    #[error(
        "face {face}: vertex index {index} is out of range (the mesh has {vertex_count} vertices)"
    )]
    IndexOutOfRange {
        /// Face index.
        face: usize,
        /// The offending index, as given (negative ones as given too).
        index: i64,
        /// How many vertices there are.
        vertex_count: usize,
    },
    /// Occurs when a face has fewer than three corners.
    #[error("face {face} has {degree} corners; a face needs at least three")]
    TooFewVertices {
        /// Face index.
        face: usize,
        /// Corners given.
        degree: usize,
    },
    /// Occurs when a face names a vertex twice.
    #[error("face {face} uses vertex {vertex} more than once")]
    RepeatedVertex {
        /// Face index.
        face: usize,
        /// The repeated vertex.
        vertex: usize,
    },
    /// Occurs when an edge is used by more than two faces.
    #[error("edge {a}-{b} is used by more than two faces ({faces:?} at least)")]
    NonManifoldEdge {
        /// One end.
        a: usize,
        /// The other end.
        b: usize,
        /// Three of the faces using it.
        faces: [usize; 3],
    },
    /// Occurs when two faces use an edge in the same direction: their
    /// orientations disagree, or one face is a duplicate of the other.
    #[error("faces {faces:?} both use edge {a}->{b} in the same direction (inconsistent orientation or duplicate face)")]
    InconsistentOrientation {
        /// Start of the directed edge.
        a: usize,
        /// End of the directed edge.
        b: usize,
        /// The two faces.
        faces: [usize; 2],
    },
    /// Occurs when the faces around a vertex form more than one closed fan,
    /// or a closed fan and an open one: no single ring of half-edges can
    /// circle it.
    #[error("vertex {vertex} is non-manifold: its faces (face {face} among them) form separate fans that cannot be joined through a boundary")]
    NonManifoldVertex {
        /// The vertex.
        vertex: usize,
        /// One face at the vertex.
        face: usize,
    },
    /// Occurs when a position is NaN or infinite.
    #[error("vertex {vertex} has the non-finite position {position:?}")]
    NonFinitePosition {
        /// The vertex.
        vertex: usize,
        /// Its position.
        position: [f64; 3],
    },
    /// Occurs when compact buffers' offsets do not cut the index array into
    /// faces: they must start at 0, never decrease and end at its length.
    #[error("the {offsets} face offsets do not cut the {indices} indices into faces (they must start at 0, never decrease and end at the index count)")]
    MalformedOffsets {
        /// How many offsets were given.
        offsets: usize,
        /// How many indices were given.
        indices: usize,
    },
    /// Occurs when the input has more elements than 32-bit indices address.
    #[error("the input is too large: {what}")]
    TooLarge {
        /// What overflowed.
        what: &'static str,
    },
}

/// A broken structural rule: its number (see [`validate`](crate::validate)), the
/// element where it broke and what was found.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ValidationError {
    /// The rule's number, 1 to 11.
    pub rule: u8,
    /// The element where the rule broke, when one can be named.
    pub key: Option<AnyKey>,
    /// What was found.
    pub detail: String,
}

impl ValidationError {
    /// The rule's short name.
    pub fn rule_name(&self) -> &'static str {
        match self.rule {
            1 => "storage",
            2 => "links in range",
            3 => "no loops",
            4 => "next is a permutation",
            5 => "faces are cycles",
            6 => "face links",
            7 => "face size",
            8 => "vertex links",
            9 => "no dangling edges",
            10 => "no multi-edges",
            11 => "boundary vertices point into a hole",
            _ => "unknown rule",
        }
    }
}

impl fmt::Display for ValidationError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "rule {} ({}) broken", self.rule, self.rule_name())?;
        if let Some(k) = &self.key {
            write!(f, " at {k}")?;
        }
        write!(f, ": {}", self.detail)
    }
}

impl std::error::Error for ValidationError {}

/// Why a [fallible rule](crate::attr::Rule::FALLIBLE) gave no value: a
/// message, and the error that caused it, if any, kept whole so that the
/// caller of the failed edit can take it back out of [`Error::Rule`]
/// (a language binding re-raises its own exception this way).
///
/// ```
/// use meshloom::error::RuleError;
/// let e = RuleError::from_source(std::fmt::Error);
/// assert_eq!(e.message(), "an error occurred when formatting an argument");
/// assert!(e.cause().unwrap().downcast_ref::<std::fmt::Error>().is_some());
/// assert_eq!(RuleError::new("no labels to merge").to_string(), "no labels to merge");
/// ```
///
/// One pointer wide (clones share it), so that [`Error`] stays as small
/// and as cheap to drop as it was.
#[derive(Clone, Debug)]
pub struct RuleError(Arc<RuleErrorData>);

type Cause = Arc<dyn std::error::Error + Send + Sync + 'static>;

#[derive(Debug)]
struct RuleErrorData {
    message: String,
    cause: Option<Cause>,
    /// The column's arena and name, once meshloom reports it.
    column: Option<(ElementKind, String)>,
}

impl RuleError {
    /// An error that says `message`.
    pub fn new(message: impl Into<String>) -> RuleError {
        RuleError(Arc::new(RuleErrorData {
            message: message.into(),
            cause: None,
            column: None,
        }))
    }

    /// An error caused by `cause`, saying what it says.
    pub fn from_source(cause: impl std::error::Error + Send + Sync + 'static) -> RuleError {
        RuleError(Arc::new(RuleErrorData {
            message: cause.to_string(),
            cause: Some(Arc::new(cause)),
            column: None,
        }))
    }

    /// This error, of the rule of the `kind` column `name`.
    pub(crate) fn of_column(&self, kind: ElementKind, name: &str) -> RuleError {
        RuleError(Arc::new(RuleErrorData {
            message: self.0.message.clone(),
            cause: self.0.cause.clone(),
            column: Some((kind, name.to_owned())),
        }))
    }

    /// What the rule said.
    pub fn message(&self) -> &str {
        &self.0.message
    }

    /// The error that caused it, if it was made by
    /// [`from_source`](RuleError::from_source): downcast it to get it back.
    pub fn cause(&self) -> Option<&(dyn std::error::Error + Send + Sync + 'static)> {
        self.0.cause.as_deref()
    }

    /// The arena and name of the column whose rule failed (in an
    /// [`Error::Rule`]; `None` as the rule made it).
    pub fn column(&self) -> Option<(ElementKind, &str)> {
        self.0.column.as_ref().map(|(k, n)| (*k, n.as_str()))
    }

    /// The message with the column it is about.
    fn in_context(&self) -> String {
        match self.column() {
            Some((kind, name)) => format!(
                "the rule of the {kind} attribute {name:?} failed: {}",
                self.0.message
            ),
            None => format!("a rule failed: {}", self.0.message),
        }
    }
}

impl PartialEq for RuleError {
    /// The same message and column, and the same cause (the very same error
    /// object, or none).
    fn eq(&self, other: &Self) -> bool {
        let (a, b) = (&self.0, &other.0);
        a.message == b.message
            && a.column == b.column
            && match (&a.cause, &b.cause) {
                (None, None) => true,
                (Some(x), Some(y)) => Arc::ptr_eq(x, y),
                _ => false,
            }
    }
}

impl fmt::Display for RuleError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0.message)
    }
}

impl std::error::Error for RuleError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        self.cause()
            .map(|e| e as &(dyn std::error::Error + 'static))
    }
}

/// The result type of meshloom's fallible operations.
pub type Result<T, E = Error> = std::result::Result<T, E>;
