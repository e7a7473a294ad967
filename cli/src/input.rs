//! Reading and writing mesh files, with progress and exit-code failures.

use std::path::Path;

use meshloom::io::{self, ReadOptions};
use meshloom::repair::RepairReport;
use meshloom::Mesh;

use crate::cli::ReadArgs;
use crate::progress::Progress;
use crate::Failure;

/// Read `path`, strictly or with every repair on. The report is `Some`
/// when repairs were asked for.
pub fn read(path: &Path, how: ReadArgs) -> Result<(Mesh, Option<RepairReport>), Failure> {
    let _progress = Progress::spinner(format!("reading {}", path.display()));
    let read = if how.repair {
        io::read_with(path, &ReadOptions::repair_all()).map(|(m, r)| (m, Some(r)))
    } else {
        io::read(path).map(|m| (m, None))
    };
    read.map_err(Failure::input)
}

/// Write `mesh` to `path`, the format from its extension.
pub fn write(mesh: &Mesh, path: &Path) -> Result<(), Failure> {
    let _progress = Progress::spinner(format!("writing {}", path.display()));
    io::write(mesh, path).map_err(Failure::input)
}
