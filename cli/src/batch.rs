//! Several inputs at once: files, folders (searched recursively) and `-`,
//! processed in parallel (rayon) under one progress bar, reported as a
//! table or as JSON Lines, with a failure naming every file that failed.
//!
//! Every JSON object printed by `stats`, `validate`, `convert` and `repair`
//! has the same common fields: `command`, `file` (the input as given or
//! found in a folder, `-` for standard input), `ok`, `vertices` and `faces`
//! (numbers, `null` when the file could not be read) and `error` (`null`,
//! or what went wrong); the command's own fields follow.

use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};

use meshloom::repair::RepairReport;
use meshloom::Mesh;
use rayon::prelude::*;
use serde_json::{json, Map, Value};

use crate::cli::{OutArgs, ReadArgs, KNOWN};
use crate::input::{self, MeshFormat};
use crate::output;
use crate::progress::Progress;
use crate::Failure;

/// One input.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Source {
    /// Standard input.
    Stdin,
    /// A file, and its path relative to the folder argument it was found in
    /// (its file name when it was named on its own).
    File {
        /// The path to read.
        path: PathBuf,
        /// Where it goes under `--out-dir`.
        rel: PathBuf,
    },
}

impl Source {
    /// The name to show: the path, or `-`.
    pub fn name(&self) -> String {
        match self {
            Source::Stdin => "-".into(),
            Source::File { path, .. } => path.display().to_string(),
        }
    }

    /// Read the mesh (standard input in `format`).
    pub fn read(
        &self,
        how: ReadArgs,
        format: Option<MeshFormat>,
        quiet: bool,
    ) -> Result<(Mesh, Option<RepairReport>), Failure> {
        match self {
            Source::Stdin => input::read_stdin(format, how),
            Source::File { path, .. } => input::read(path, how, quiet),
        }
    }
}

/// Where a result is written.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Target {
    /// Standard output.
    Stdout,
    /// A file; `true` when it goes under `--out-dir` (folders are made).
    File(PathBuf, bool),
}

impl Target {
    /// The name to show.
    pub fn name(&self) -> String {
        match self {
            Target::Stdout => "-".into(),
            Target::File(p, _) => p.display().to_string(),
        }
    }

    /// The format written.
    pub fn format(&self, stdout_format: Option<MeshFormat>) -> Option<MeshFormat> {
        match self {
            Target::Stdout => stdout_format,
            Target::File(p, _) => MeshFormat::of_path(p),
        }
    }

    /// Write `mesh` here.
    pub fn write(
        &self,
        mesh: &Mesh,
        stdout_format: Option<MeshFormat>,
        quiet: bool,
    ) -> Result<(), Failure> {
        match self {
            Target::Stdout => input::write_stdout(mesh, stdout_format),
            Target::File(p, made) => input::write(mesh, p, quiet, *made),
        }
    }
}

/// The inputs of one command.
#[derive(Debug)]
pub struct Batch {
    /// The inputs, in order: arguments as given, each folder's files sorted
    /// by path.
    pub sources: Vec<Source>,
    /// Whether a table (or JSON Lines) is printed rather than one file's
    /// full report: more than one argument, or a folder.
    pub several: bool,
}

impl Batch {
    /// Expand the command line's paths. `-` needs `format`; a folder must
    /// hold at least one mesh file.
    pub fn expand(paths: &[PathBuf], format: Option<MeshFormat>) -> Result<Batch, Failure> {
        let mut sources = Vec::new();
        let mut several = paths.len() > 1;
        for path in paths {
            if path.as_os_str() == "-" {
                if sources.contains(&Source::Stdin) {
                    return Err(Failure::usage("- (standard input) is given twice"));
                }
                match format {
                    None => return Err(Failure::usage(
                        "- (standard input) has no extension: give its format with --format (obj, off, ply, stl, gltf, glb)",
                    )),
                    Some(f) => {
                        f.uncompressed().map_err(Failure::usage)?;
                    }
                }
                sources.push(Source::Stdin);
            } else if path.is_dir() {
                several = true;
                let before = sources.len();
                walk(path, path, &mut sources)?;
                if sources.len() == before {
                    return Err(Failure::input(format!(
                        "{}: a folder with no mesh files in it ({KNOWN})",
                        path.display()
                    )));
                }
            } else {
                let rel = path.file_name().map_or_else(|| path.clone(), PathBuf::from);
                sources.push(Source::File {
                    path: path.clone(),
                    rel,
                });
            }
        }
        Ok(Batch { sources, several })
    }

    /// Run `work` on every input, in parallel, under one progress bar (when
    /// there are several); results in input order. A panic in one file's
    /// work is that file's failure, not the end of the run.
    pub fn run<F>(&self, work: F) -> Vec<Record>
    where
        F: Fn(usize, &Source) -> Record + Sync,
    {
        let progress = self
            .several
            .then(|| Progress::bar("files", self.sources.len()));
        let done = AtomicUsize::new(0);
        self.sources
            .par_iter()
            .enumerate()
            .map(|(i, source)| {
                let record =
                    catch_unwind(AssertUnwindSafe(|| work(i, source))).unwrap_or_else(|_| {
                        Record::failed(source.name(), "internal error (a panic): please report it")
                    });
                let n = done.fetch_add(1, Ordering::Relaxed) + 1;
                if let Some(p) = &progress {
                    p.set(n);
                }
                record
            })
            .collect()
    }

    /// Print the records: one JSON object per line with `json`; else a
    /// table for several inputs, or the one input's full report. Text goes
    /// to stderr with `to_stderr` (when the mesh itself went to stdout).
    /// Any failure is an exit-1 [`Failure`] naming every file that failed.
    pub fn report(
        &self,
        command: &str,
        records: &[Record],
        json: bool,
        to_stderr: bool,
    ) -> Result<(), Failure> {
        let text = if json {
            let mut text = String::new();
            for r in records {
                text.push_str(&r.json_line(command)?);
                text.push('\n');
            }
            text
        } else if self.several {
            table(records)
        } else {
            records.iter().map(|r| r.text.as_str()).collect()
        };
        if to_stderr {
            eprint!("{text}");
        } else {
            output::print(&text)?;
        }
        let failed: Vec<&Record> = records.iter().filter(|r| r.error.is_some()).collect();
        match failed.as_slice() {
            [] => Ok(()),
            [one] if !self.several => Err(Failure::input(one.error.clone().unwrap_or_default())),
            _ => {
                let mut message = format!("{} of {} files failed:", failed.len(), records.len());
                for r in failed {
                    let error = r.short_error().unwrap_or_default();
                    message.push_str(&format!(
                        "\n  {}: {}",
                        r.file,
                        error.lines().next().unwrap_or_default()
                    ));
                }
                Err(Failure::input(message))
            }
        }
    }
}

/// Collect the mesh files under `dir`, sorted by path, recursively.
/// Symbolic links to folders are not followed (no cycles); links to files
/// are read.
fn walk(root: &Path, dir: &Path, out: &mut Vec<Source>) -> Result<(), Failure> {
    let listing = std::fs::read_dir(dir)
        .map_err(|e| Failure::input(format!("{}: cannot list the folder: {e}", dir.display())))?;
    let mut entries = Vec::new();
    for entry in listing {
        let entry = entry.map_err(|e| {
            Failure::input(format!("{}: cannot list the folder: {e}", dir.display()))
        })?;
        entries.push(entry);
    }
    entries.sort_by_key(|e| e.file_name());
    for entry in entries {
        let path = entry.path();
        let is_dir = entry.file_type().is_ok_and(|t| t.is_dir());
        if is_dir {
            walk(root, &path, out)?;
        } else if !path.is_dir() && MeshFormat::of_path(&path).is_some() {
            let rel = path.strip_prefix(root).map_or_else(
                |_| path.file_name().map_or_else(|| path.clone(), PathBuf::from),
                Path::to_path_buf,
            );
            out.push(Source::File { path, rel });
        }
    }
    Ok(())
}

/// The inputs and outputs of `convert` and `repair`: `IN OUT`, or any
/// number of inputs with `--out-dir DIR`.
pub fn plan(paths: &[PathBuf], out: &OutArgs) -> Result<(Batch, Vec<Target>), Failure> {
    if let Some(dir) = &out.out_dir {
        if dir.exists() && !dir.is_dir() {
            return Err(Failure::usage(format!(
                "--out-dir {}: a file, not a folder",
                dir.display()
            )));
        }
        if paths.iter().any(|p| p.as_os_str() == "-") {
            return Err(Failure::usage(
                "- (standard input) has no name to write under --out-dir: use IN OUT",
            ));
        }
        let mut batch = Batch::expand(paths, None)?;
        batch.several = true;
        let mut targets = Vec::with_capacity(batch.sources.len());
        let mut seen = std::collections::HashMap::new();
        for source in &batch.sources {
            let Source::File { path, rel } = source else {
                continue;
            };
            let rel = match out.format {
                Some(f) => with_format(rel, f),
                None => rel.clone(),
            };
            let target = dir.join(rel);
            if let Some(first) = seen.insert(target.clone(), path.clone()) {
                return Err(Failure::usage(format!(
                    "{} and {} would both be written to {}",
                    first.display(),
                    path.display(),
                    target.display()
                )));
            }
            targets.push(Target::File(target, true));
        }
        return Ok((batch, targets));
    }
    let (input, output) = match paths {
        [input, output] => (input, output),
        [input] if input.is_dir() => {
            return Err(Failure::usage(format!(
                "{} is a folder: give --out-dir DIR to write the meshes in it",
                input.display()
            )))
        }
        [_] => return Err(Failure::usage("give IN OUT, or inputs and --out-dir DIR")),
        _ => {
            return Err(Failure::usage(format!(
                "{} paths: several inputs need --out-dir DIR (IN OUT is for one file)",
                paths.len()
            )))
        }
    };
    if input.is_dir() {
        return Err(Failure::usage(format!(
            "{} is a folder: give --out-dir DIR to write the meshes in it",
            input.display()
        )));
    }
    let target = if output.as_os_str() == "-" {
        match out.format {
            None => return Err(Failure::usage(
                "- (standard output) has no extension: give the format with --format (obj, off, ply, stl, gltf, glb)",
            )),
            Some(f) => {
                f.uncompressed().map_err(Failure::usage)?;
            }
        }
        Target::Stdout
    } else if output.is_dir() {
        return Err(Failure::usage(format!(
            "{} is a folder: name the output file, or use --out-dir {}",
            output.display(),
            output.display()
        )));
    } else {
        Target::File(output.clone(), false)
    };
    let batch = Batch::expand(std::slice::from_ref(input), out.format)?;
    Ok((batch, vec![target]))
}

/// `rel` with its mesh extension (and `.gz`) replaced by `format`'s.
pub fn with_format(rel: &Path, format: MeshFormat) -> PathBuf {
    let name = rel
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let mut stem = name.as_str();
    if stem.to_ascii_lowercase().ends_with(".gz") {
        stem = &stem[..stem.len() - 3];
    }
    if let Some(dot) = stem.rfind('.') {
        if MeshFormat::of_path(Path::new(stem)).is_some() {
            stem = &stem[..dot];
        }
    }
    rel.with_file_name(format!("{stem}.{}", format.extension()))
}

/// What one command did with one input.
#[derive(Debug, Default)]
pub struct Record {
    /// The input's name.
    pub file: String,
    /// Vertices of the mesh read (or written), if it was read.
    pub vertices: Option<usize>,
    /// Faces, likewise.
    pub faces: Option<usize>,
    /// What went wrong; `None`: all went well.
    pub error: Option<String>,
    /// The table's status column when all went well.
    pub status: String,
    /// The command's own JSON fields.
    pub fields: Map<String, Value>,
    /// The full text report of a single input.
    pub text: String,
}

impl Record {
    /// A record of success.
    pub fn ok(file: String, mesh: &Mesh) -> Record {
        Record {
            file,
            vertices: Some(mesh.vertex_count()),
            faces: Some(mesh.face_count()),
            ..Record::default()
        }
    }

    /// A record of failure.
    pub fn failed(file: String, error: impl Into<String>) -> Record {
        Record {
            file,
            error: Some(error.into()),
            ..Record::default()
        }
    }

    /// The error without a leading `FILE: ` (the table names the file);
    /// `FILE:12: ...` becomes `line 12: ...`.
    pub fn short_error(&self) -> Option<String> {
        let e = self.error.as_deref()?;
        let Some(rest) = e.strip_prefix(self.file.as_str()) else {
            return Some(e.to_string());
        };
        if let Some(rest) = rest.strip_prefix(": ") {
            return Some(rest.to_string());
        }
        match rest.strip_prefix(':') {
            Some(rest) if rest.starts_with(|c: char| c.is_ascii_digit()) => {
                Some(format!("line {rest}"))
            }
            _ => Some(e.to_string()),
        }
    }

    /// The JSON object, on one line.
    pub fn json_line(&self, command: &str) -> Result<String, Failure> {
        let mut object = Map::new();
        object.insert("command".into(), json!(command));
        object.insert("file".into(), json!(self.file));
        object.insert("ok".into(), json!(self.error.is_none()));
        object.insert("vertices".into(), json!(self.vertices));
        object.insert("faces".into(), json!(self.faces));
        object.insert("error".into(), json!(self.error));
        for (k, v) in &self.fields {
            object.entry(k.clone()).or_insert_with(|| v.clone());
        }
        serde_json::to_string(&Value::Object(object))
            .map_err(|e| Failure::input(format!("cannot encode JSON: {e}")))
    }
}

/// The summary table: file, vertices, faces, status.
fn table(records: &[Record]) -> String {
    let width = records
        .iter()
        .map(|r| r.file.chars().count())
        .max()
        .unwrap_or(0)
        .max(4);
    let count = |n: Option<usize>| n.map_or("-".to_string(), |n| n.to_string());
    let mut text = format!(
        "{:<width$}  {:>9}  {:>9}  status\n",
        "file", "vertices", "faces"
    );
    for r in records {
        let status = match r.short_error() {
            Some(e) => format!("FAILED: {}", e.lines().next().unwrap_or_default()),
            None => r.status.clone(),
        };
        text.push_str(&format!(
            "{:<width$}  {:>9}  {:>9}  {status}\n",
            r.file,
            count(r.vertices),
            count(r.faces)
        ));
    }
    let failed = records.iter().filter(|r| r.error.is_some()).count();
    text.push_str(&format!(
        "{} files: {} ok, {failed} failed\n",
        records.len(),
        records.len() - failed
    ));
    text
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn output_names_take_the_new_extension() {
        let ply = MeshFormat::of_path(Path::new("x.ply")).unwrap();
        assert_eq!(with_format(Path::new("a/b.off"), ply), Path::new("a/b.ply"));
        assert_eq!(
            with_format(Path::new("a/b.obj.gz"), ply),
            Path::new("a/b.ply")
        );
        assert_eq!(with_format(Path::new("c.d.stl"), ply), Path::new("c.d.ply"));
        let gz = MeshFormat::of_path(Path::new("x.off.gz")).unwrap();
        assert_eq!(with_format(Path::new("m.glb"), gz), Path::new("m.off.gz"));
    }

    #[test]
    fn errors_lose_the_file_name_in_the_table_only() {
        let r = Record::failed("a/b.off".into(), "a/b.off: byte 3: bad");
        assert_eq!(r.short_error().as_deref(), Some("byte 3: bad"));
        let r = Record::failed("a/b.offx".into(), "a/b.offx: other");
        assert_eq!(r.short_error().as_deref(), Some("other"));
        let r = Record::failed("a/b.off".into(), "a/b.offx: other");
        assert_eq!(r.short_error().as_deref(), Some("a/b.offx: other"));
        let r = Record::failed("a/b.off".into(), "a/b.off:3: bad\nhint: more");
        assert_eq!(r.short_error().as_deref(), Some("line 3: bad\nhint: more"));
        let mut ok = Record::ok("c.off".into(), &meshloom::shapes::cube());
        ok.status = "fine".into();
        let t = table(&[r, ok]);
        assert!(t.contains("a/b.off"), "{t}");
        assert!(t.contains("FAILED: line 3: bad\n"), "{t}");
        assert!(!t.contains("hint"), "{t}");
        let row: Vec<&str> = t.lines().nth(2).unwrap().split_whitespace().collect();
        assert_eq!(row, ["c.off", "8", "6", "fine"], "{t}");
        assert!(t.contains("2 files: 1 ok, 1 failed"), "{t}");
    }

    #[test]
    fn json_lines_have_the_common_fields() {
        let mut r = Record::ok("m.off".into(), &meshloom::shapes::cube());
        r.fields.insert("ok".into(), json!("overridden?"));
        r.fields.insert("extra".into(), json!(1));
        let line = r.json_line("stats").unwrap();
        assert!(!line.contains('\n'));
        let v: Value = serde_json::from_str(&line).unwrap();
        assert_eq!(v["ok"], true);
        assert_eq!(v["vertices"], 8);
        assert_eq!(v["faces"], 6);
        assert_eq!(v["error"], Value::Null);
        assert_eq!(v["extra"], 1);
        assert_eq!(v["command"], "stats");
    }
}
