//! The reader and writer error: what was wrong, in which file, and where in
//! it (a line for text, a byte offset for binary data).

use std::fmt;
use std::path::{Path, PathBuf};

use crate::error::BuildError;

/// Where in the input something went wrong.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct Location {
    /// The file, when reading from a path (`None` for a plain reader).
    pub path: Option<PathBuf>,
    /// The place inside it.
    pub position: Position,
}

/// A place inside the input.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub enum Position {
    /// The file as a whole.
    #[default]
    Whole,
    /// A line of text, counted from 1.
    Line(u64),
    /// A byte offset into binary data (after gzip decompression), from 0.
    Byte(u64),
}

impl Location {
    /// A line of text in an input with no path yet.
    pub(crate) fn line(line: u64) -> Location {
        Location {
            path: None,
            position: Position::Line(line),
        }
    }

    /// A byte offset in an input with no path yet.
    pub(crate) fn byte(offset: u64) -> Location {
        Location {
            path: None,
            position: Position::Byte(offset),
        }
    }

    /// The input as a whole.
    pub(crate) fn whole() -> Location {
        Location::default()
    }
}

impl fmt::Display for Location {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match &self.path {
            Some(p) => write!(f, "{}", p.display())?,
            None => write!(f, "<input>")?,
        }
        match self.position {
            Position::Whole => Ok(()),
            Position::Line(l) => write!(f, ":{l}"),
            Position::Byte(b) => write!(f, ": byte {b}"),
        }
    }
}

/// What can go wrong reading or writing a mesh file. Every kind names the
/// file and, where it can, the line (text) or byte offset (binary data).
///
/// ```
/// let off = "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n";
/// let err = meshloom::io::read_off(off.as_bytes()).unwrap_err();
/// assert_eq!(err.line(), Some(6));
/// assert_eq!(err.to_string(), "<input>:6: vertex index 7 is out of range (there are 3 vertices)");
/// ```
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    /// Occurs when the operating system refuses a read or write, or gzip
    /// data is corrupt.
    #[error("{at}: {source}")]
    Io {
        /// The file.
        at: Location,
        /// The underlying error.
        source: std::io::Error,
    },
    /// Occurs when a token is not what the format allows at that place.
    #[error("{at}: expected {expected}, found {found}")]
    Syntax {
        /// Where.
        at: Location,
        /// What the format allows there.
        expected: String,
        /// What was there (quoted, cut to a few dozen characters).
        found: String,
    },
    /// Occurs when a header is malformed, or announces something this
    /// reader cannot take (an unknown property type, say).
    #[error("{at}: bad header: {message}")]
    Header {
        /// Where.
        at: Location,
        /// What is wrong with it.
        message: String,
    },
    /// Occurs when the input ends before everything its header announced.
    #[error("{at}: unexpected end of input: expected {expected}")]
    Truncated {
        /// Where the input ended.
        at: Location,
        /// What was still expected.
        expected: String,
    },
    /// Occurs when a face names a vertex (or, in OBJ, a texture coordinate
    /// or normal) that does not exist.
    #[error(
        "{at}: {what} index {index} is out of range (there are {count} {})",
        plural(what)
    )]
    IndexOutOfRange {
        /// Where the index was read.
        at: Location,
        /// What the index names: `"vertex"`, `"texture coordinate"` or
        /// `"normal"`.
        what: &'static str,
        /// The index as written in the file (1-based for OBJ; negative ones
        /// as written).
        index: i64,
        /// How many vertices had been read at that point.
        count: usize,
    },
    /// Occurs when a file has no faces at all.
    #[error("{at}: the file holds no faces")]
    Empty {
        /// The file.
        at: Location,
    },
    /// Occurs when the extension, magic or a variant of a format is not
    /// supported (binary OFF, an unknown extension).
    #[error("{at}: unsupported format: {what}")]
    UnsupportedFormat {
        /// The file.
        at: Location,
        /// What is not supported.
        what: String,
    },
    /// Occurs when the input has more elements or bytes than the reader's
    /// limits allow.
    #[error("{at}: too large: {what}")]
    TooLarge {
        /// Where.
        at: Location,
        /// What overflowed.
        what: String,
    },
    /// Occurs when the polygons read cannot form a half-edge mesh and no
    /// repair policy covers the problem. `face` is the 0-based face index
    /// in the file; `at` the line or byte offset where it was read.
    #[error("{at}: {source}")]
    Build {
        /// Where the face was read.
        at: Location,
        /// The face, 0-based, in file order.
        face: usize,
        /// What the builder found.
        source: BuildError,
    },
    /// Occurs when a vertex position is NaN or infinite (`nan`, `inf`, or a
    /// number too large for its type).
    #[error("{at}: vertex {vertex} has the non-finite position {position:?}")]
    NonFinite {
        /// The file.
        at: Location,
        /// The vertex, 0-based in file order.
        vertex: usize,
        /// Its position.
        position: [f64; 3],
    },
    /// Occurs when vertices are used by no face and the policy to drop
    /// them is off (a half-edge mesh cannot hold an isolated vertex).
    #[error("{at}: {count} vertices are used by no face (vertex {first} is the first, 0-based); a half-edge mesh holds no isolated vertex: the drop_unreferenced_vertices repair policy drops them")]
    Unreferenced {
        /// The file.
        at: Location,
        /// How many.
        count: usize,
        /// The first one, 0-based in file order.
        first: usize,
    },
    /// Occurs when a file holds something its format does not allow but
    /// other readers skip (a PLY header line that is not a keyword, such as
    /// Blender's `Created by Blender ...`) and the read is strict. A read
    /// with any repair policy skips it and reports a warning
    /// ([`RepairReport::warnings`](crate::repair::RepairReport::warnings)).
    #[error("{at}: {what}; a strict read refuses it (a read with repair policies skips it with a warning, as other readers do)")]
    NonStandard {
        /// Where.
        at: Location,
        /// What is there.
        what: String,
    },
    /// Occurs when the repair policies dropped every face of a file that
    /// had faces (all of them degenerate, say).
    #[error(
        "{at}: the repairs dropped all {faces} faces of the file ({why}); nothing is left to build"
    )]
    NothingLeft {
        /// The file.
        at: Location,
        /// How many faces the file had.
        faces: usize,
        /// What the repairs did.
        why: String,
    },
    /// Occurs when a mesh cannot be written in a format (no positions, or a
    /// value the format cannot hold).
    #[error("{at}: cannot write: {what}")]
    Unwritable {
        /// The file.
        at: Location,
        /// Why.
        what: String,
    },
}

impl Error {
    /// Where the error happened.
    pub fn location(&self) -> &Location {
        match self {
            Error::Io { at, .. }
            | Error::Syntax { at, .. }
            | Error::Header { at, .. }
            | Error::Truncated { at, .. }
            | Error::IndexOutOfRange { at, .. }
            | Error::Empty { at }
            | Error::UnsupportedFormat { at, .. }
            | Error::TooLarge { at, .. }
            | Error::Build { at, .. }
            | Error::NonFinite { at, .. }
            | Error::Unreferenced { at, .. }
            | Error::NonStandard { at, .. }
            | Error::NothingLeft { at, .. }
            | Error::Unwritable { at, .. } => at,
        }
    }

    fn location_mut(&mut self) -> &mut Location {
        match self {
            Error::Io { at, .. }
            | Error::Syntax { at, .. }
            | Error::Header { at, .. }
            | Error::Truncated { at, .. }
            | Error::IndexOutOfRange { at, .. }
            | Error::Empty { at }
            | Error::UnsupportedFormat { at, .. }
            | Error::TooLarge { at, .. }
            | Error::Build { at, .. }
            | Error::NonFinite { at, .. }
            | Error::Unreferenced { at, .. }
            | Error::NonStandard { at, .. }
            | Error::NothingLeft { at, .. }
            | Error::Unwritable { at, .. } => at,
        }
    }

    /// The same error, naming `path` as its file.
    pub fn with_path(mut self, path: &Path) -> Error {
        self.location_mut().path = Some(path.to_path_buf());
        self
    }

    /// The line it happened on, for text input.
    pub fn line(&self) -> Option<u64> {
        match self.location().position {
            Position::Line(l) => Some(l),
            _ => None,
        }
    }

    /// The byte offset it happened at, for binary input.
    pub fn byte_offset(&self) -> Option<u64> {
        match self.location().position {
            Position::Byte(b) => Some(b),
            _ => None,
        }
    }

    pub(crate) fn io(source: std::io::Error) -> Error {
        Error::Io {
            at: Location::whole(),
            source,
        }
    }

    pub(crate) fn syntax(at: Location, expected: impl Into<String>, found: &[u8]) -> Error {
        Error::Syntax {
            at,
            expected: expected.into(),
            found: quote(found),
        }
    }
}

/// The plural of what an index names.
fn plural(what: &str) -> String {
    match what {
        "vertex" => "vertices".to_owned(),
        other => format!("{other}s"),
    }
}

/// A token for an error message: quoted, escaped, cut to 40 bytes.
pub(crate) fn quote(token: &[u8]) -> String {
    if token.is_empty() {
        return "nothing".to_owned();
    }
    let cut = &token[..token.len().min(40)];
    let mut s = String::from("\"");
    s.push_str(&cut.escape_ascii().to_string());
    if cut.len() < token.len() {
        s.push_str("...");
    }
    s.push('"');
    s
}
