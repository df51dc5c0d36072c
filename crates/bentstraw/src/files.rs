//! Writing output files all-or-nothing: a file appears complete, or not at all.

use std::fs;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

use crate::error::{CliError, CliResult};

/// Checks, before any work, that `path` can be written: its folder exists and is writable.
pub fn check_writable(path: &Path) -> CliResult {
    let dir = parent_dir(path);
    if !dir.is_dir() {
        return Err(CliError(format!(
            "cannot write {}: folder {} does not exist",
            path.display(),
            dir.display()
        )));
    }
    if path.is_dir() {
        return Err(CliError(format!(
            "cannot write {}: it is a folder",
            path.display()
        )));
    }
    // Probe by creating (and removing) a scratch file beside the target.
    let probe = scratch_path(path);
    match fs::File::create(&probe) {
        Ok(_) => {
            let _ = fs::remove_file(&probe);
            Ok(())
        }
        Err(e) => Err(CliError(format!("cannot write {}: {e}", path.display()))),
    }
}

/// Writes `path` through `fill`: into a scratch file first, renamed into place only on success.
pub fn write_atomically(
    path: &Path,
    fill: impl FnOnce(&mut dyn Write) -> std::io::Result<()>,
) -> CliResult {
    let scratch = scratch_path(path);
    let result = (|| {
        let file = fs::File::create(&scratch)?;
        let mut w = BufWriter::with_capacity(1 << 20, file);
        fill(&mut w)?;
        w.into_inner().map_err(|e| e.into_error())?.sync_all()?;
        fs::rename(&scratch, path)
    })();
    result.map_err(|e| {
        let _ = fs::remove_file(&scratch);
        CliError(format!("cannot write {}: {e}", path.display()))
    })
}

/// Writes bytes all-or-nothing.
pub fn write_bytes(path: &Path, bytes: &[u8]) -> CliResult {
    write_atomically(path, |w| w.write_all(bytes))
}

fn parent_dir(path: &Path) -> PathBuf {
    match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => PathBuf::from("."),
    }
}

fn scratch_path(path: &Path) -> PathBuf {
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    parent_dir(path).join(format!(".{name}.{}.partial", std::process::id()))
}
