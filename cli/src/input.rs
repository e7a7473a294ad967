//! Reading and writing mesh files (or standard input and output), with
//! progress and exit-code failures.

use std::io::{Read, Write};
use std::path::Path;

use meshloom::io::gltf::{self, GltfEncoding, GltfOptions};
use meshloom::io::{self, Format, ReadOptions};
use meshloom::repair::RepairReport;
use meshloom::Mesh;

use crate::cli::ReadArgs;
use crate::progress::Progress;
use crate::Failure;

/// A mesh file format as the command line names it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MeshFormat {
    /// OBJ, OFF, PLY or STL, and whether gzipped.
    Plain(Format, bool),
    /// glTF, JSON or binary.
    Gltf(GltfEncoding),
}

impl MeshFormat {
    /// The format a path's extension names (`a.ply`, `b.obj.gz`, `c.glb`).
    pub fn of_path(path: &Path) -> Option<MeshFormat> {
        if let Some(e) = gltf::encoding_of(path) {
            return Some(MeshFormat::Gltf(e));
        }
        Format::from_path(path).map(|(f, gz)| MeshFormat::Plain(f, gz))
    }

    /// The extension, without a leading dot (`ply`, `obj.gz`, `glb`).
    pub fn extension(self) -> String {
        match self {
            MeshFormat::Plain(f, false) => f.extension().to_string(),
            MeshFormat::Plain(f, true) => format!("{}.gz", f.extension()),
            MeshFormat::Gltf(GltfEncoding::Json) => "gltf".into(),
            MeshFormat::Gltf(GltfEncoding::Binary) => "glb".into(),
        }
    }

    /// The format of the bytes without compression, or a message for
    /// standard input and output, which are never gzipped here.
    pub fn uncompressed(self) -> Result<MeshFormat, String> {
        match self {
            MeshFormat::Plain(f, true) => Err(format!(
                "standard input and output are not gzipped here; use --format {} and pipe through gzip",
                f.extension()
            )),
            other => Ok(other),
        }
    }
}

/// The largest standard input read, as the readers' default limit.
const MAX_STDIN: u64 = 4 << 30;

/// The repair policies `how` asks for.
fn options(how: ReadArgs) -> ReadOptions {
    if how.repair || how.weld {
        let mut options = ReadOptions::repair_all();
        options.repair.weld_vertices = how.weld;
        options
    } else {
        ReadOptions::strict()
    }
}

/// Read `path`, strictly or with every repair on (and welding, with
/// `--weld`). The report is `Some` when repairs were asked for. With
/// `quiet`, no spinner (several files are read at once under one bar).
pub fn read(
    path: &Path,
    how: ReadArgs,
    quiet: bool,
) -> Result<(Mesh, Option<RepairReport>), Failure> {
    let _progress = (!quiet).then(|| Progress::spinner(format!("reading {}", path.display())));
    let repairing = how.repair || how.weld;
    io::read_with(path, &options(how))
        .map(|(m, r)| (m, repairing.then_some(r)))
        .map_err(|e| Failure::input(message(&e)))
}

/// Read a mesh from standard input in `format` (which must be given).
pub fn read_stdin(
    format: Option<MeshFormat>,
    how: ReadArgs,
) -> Result<(Mesh, Option<RepairReport>), Failure> {
    let bytes = stdin_bytes(format)?;
    let format = format.ok_or_else(|| Failure::input("-: give --format"))?;
    let repairing = how.repair || how.weld;
    let read = match format {
        MeshFormat::Plain(f, _) => io::read_bytes(f, &bytes, &options(how)),
        MeshFormat::Gltf(_) => {
            gltf::read_gltf_bytes(&bytes, &options(how), &GltfOptions::default())
        }
    };
    read.map(|(m, r)| (m, repairing.then_some(r)))
        .map_err(|e| Failure::input(format!("standard input: {}", message(&e))))
}

/// All of standard input, once `format` is known to be readable from it.
fn stdin_bytes(format: Option<MeshFormat>) -> Result<Vec<u8>, Failure> {
    let Some(format) = format else {
        return Err(Failure::usage(
            "- (standard input) has no extension: give its format with --format (obj, off, ply, stl, gltf, glb)",
        ));
    };
    format.uncompressed().map_err(Failure::usage)?;
    let mut bytes = Vec::new();
    std::io::stdin()
        .lock()
        .take(MAX_STDIN + 1)
        .read_to_end(&mut bytes)
        .map_err(|e| Failure::input(format!("cannot read standard input: {e}")))?;
    if bytes.len() as u64 > MAX_STDIN {
        return Err(Failure::input(format!(
            "standard input is larger than {MAX_STDIN} bytes"
        )));
    }
    Ok(bytes)
}

/// The library's error in the CLI's words: where it names a repair policy
/// or a repairing read, name `--repair`.
pub fn message(e: &io::Error) -> String {
    match e {
        io::Error::Unreferenced { at, count, first } => format!(
            "{at}: {count} vertices are used by no face (vertex {first} is the first, 0-based); \
             a half-edge mesh holds no isolated vertex: rerun with --repair to drop them"
        ),
        io::Error::NonStandard { at, what } => format!(
            "{at}: {what}; other readers skip such a line: rerun with --repair to skip it with a warning"
        ),
        other => other.to_string(),
    }
}

/// Write `mesh` to `path`, the format from its extension (parent folders
/// are made with `make_parents`).
pub fn write(mesh: &Mesh, path: &Path, quiet: bool, make_parents: bool) -> Result<(), Failure> {
    let _progress = (!quiet).then(|| Progress::spinner(format!("writing {}", path.display())));
    if make_parents {
        if let Some(parent) = path.parent().filter(|p| !p.as_os_str().is_empty()) {
            std::fs::create_dir_all(parent).map_err(|e| {
                Failure::input(format!("{}: cannot make the folder: {e}", parent.display()))
            })?;
        }
    }
    io::write(mesh, path).map_err(|e| Failure::input(message(&e)))
}

/// Write `mesh` to standard output in `format` (PLY and STL binary, as
/// files are written).
pub fn write_stdout(mesh: &Mesh, format: Option<MeshFormat>) -> Result<(), Failure> {
    let Some(format) = format else {
        return Err(Failure::usage(
            "- (standard output) has no extension: give the format with --format (obj, off, ply, stl, gltf, glb)",
        ));
    };
    let format = format.uncompressed().map_err(Failure::usage)?;
    let mut bytes = Vec::new();
    let written = match format {
        MeshFormat::Plain(Format::Obj, _) => io::write_obj(mesh, &mut bytes),
        MeshFormat::Plain(Format::Off, _) => io::write_off(mesh, &mut bytes),
        MeshFormat::Plain(Format::Ply, _) => {
            io::write_ply(mesh, &mut bytes, io::PlyEncoding::BinaryLittleEndian)
        }
        MeshFormat::Plain(Format::Stl, _) => {
            io::write_stl(mesh, &mut bytes, io::StlEncoding::Binary)
        }
        MeshFormat::Plain(other, _) => {
            return Err(Failure::input(format!(
                "cannot write {other:?} to standard output"
            )))
        }
        MeshFormat::Gltf(e) => gltf::write_gltf(mesh, &mut bytes, e),
    };
    written.map_err(|e| Failure::input(format!("standard output: {}", message(&e))))?;
    let mut out = std::io::stdout().lock();
    match out.write_all(&bytes).and_then(|()| out.flush()) {
        Err(e) if e.kind() != std::io::ErrorKind::BrokenPipe => Err(Failure::input(format!(
            "cannot write to standard output: {e}"
        ))),
        _ => Ok(()),
    }
}
