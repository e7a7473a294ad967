//! [`AnyError`]: one error type for callers that read or write files and
//! edit meshes in one function.
//!
//! It sits above every module whose error it wraps ([`io`](crate::io),
//! [`buffers`](crate::buffers) and the core's [`Error`]), so that those
//! modules never depend on it.

use crate::buffers::BufferError;
use crate::error::{BuildError, Error, ValidationError};

/// Any error of this crate, for callers that read or write files and edit
/// meshes in one function: a mesh operation's [`Error`] (and so a
/// [`BuildError`] or [`ValidationError`]) or a file's
/// [`io::Error`](crate::io::Error) (and so a [`std::io::Error`]) converts
/// into it with `?`. Its message is the inner error's, which names what
/// and where.
///
/// ```
/// use meshloom::{io, AnyError};
///
/// fn close_one_hole(path: &std::path::Path) -> Result<usize, AnyError> {
///     let mut mesh = io::read(path)?; // io::Error
///     if let Some(hole) = mesh.holes().next() {
///         mesh.fill_hole(hole)?; // meshloom::Error
///     }
///     mesh.validate()?; // ValidationError
///     io::write(&mesh, path)?;
///     Ok(mesh.hole_count())
/// }
///
/// let path = std::env::temp_dir().join(format!("meshloom-anyerror-{}.off", std::process::id()));
/// let mut cube = meshloom::shapes::cube();
/// let f = cube.faces().next().unwrap();
/// cube.remove_face(f)?;
/// io::write(&cube, &path)?;
/// assert_eq!(close_one_hole(&path)?, 0);
/// let missing = close_one_hole(std::path::Path::new("no/such/file.off")).unwrap_err();
/// assert!(matches!(missing, AnyError::File(_)));
/// assert!(missing.to_string().contains("no/such/file.off"));
/// # std::fs::remove_file(&path)?;
/// # Ok::<(), AnyError>(())
/// ```
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum AnyError {
    /// A mesh operation failed.
    #[error(transparent)]
    Mesh(#[from] Error),
    /// Reading or writing a file failed.
    #[error(transparent)]
    File(#[from] crate::io::Error),
    /// Making or reading engine buffers failed.
    #[error(transparent)]
    Buffers(#[from] BufferError),
}

impl From<BuildError> for AnyError {
    fn from(e: BuildError) -> Self {
        AnyError::Mesh(e.into())
    }
}

impl From<ValidationError> for AnyError {
    fn from(e: ValidationError) -> Self {
        AnyError::Mesh(e.into())
    }
}

impl From<std::io::Error> for AnyError {
    fn from(e: std::io::Error) -> Self {
        AnyError::File(crate::io::Error::io(e))
    }
}
