//! Writing output files without ever losing the user's previous ones.
//!
//! A run's outputs form one *output set*. Before any work, each target is reserved: its folder must
//! exist and be writable, the target must be absent or a writable regular file (never a device, a
//! folder or a link to one), its extension right, and no two targets the same file. A temporary
//! file (`.bentstraw-XXXXXX.tmp`, short, so that long target names still work) is made beside each
//! target. Writing a target fills its temporary; only when every target of the set is written and
//! synced are the temporaries renamed into place, all together. On any failure, or on Ctrl-C or
//! SIGTERM, the temporaries are removed and the previous files stay as they were.
//!
//! `write_atomically` and `write_bytes` (used by every writer) fill the reserved temporary when
//! their path belongs to a live set, and otherwise make a set of one file on the spot.

use std::fs::{self, File};
use std::io::{self, BufWriter, Seek, Write};
use std::path::{Path, PathBuf};
use std::sync::{Mutex, MutexGuard};

use tempfile::{Builder, TempPath};

pub use crate::error::shown;
use crate::error::{Error, Result};

/// Longest file name (bytes) the usual file systems accept.
const NAME_MAX: usize = 255;
/// One output a command is about to write.
pub struct Output<'a> {
    /// The option that names it in messages (`--output`), or empty.
    pub flag: &'a str,
    /// The path as the user gave it.
    pub path: &'a Path,
    /// Allowed extensions, lower-case without the dot (any when empty).
    pub extensions: &'a [&'a str],
}

/// A target reserved by a live output set, and its temporary.
struct Staged {
    /// The set it belongs to.
    set: u64,
    /// Where it goes: the canonical folder joined with the file name (a link to a regular file
    /// resolved to that file).
    target: PathBuf,
    /// The path as the user gave it, for messages.
    shown: PathBuf,
    /// The temporary beside the target, removed when dropped.
    temp: TempPath,
    /// A handle on the temporary: writes through it never recreate a temporary removed meanwhile.
    file: File,
    /// Whether the content is complete.
    written: bool,
}

/// Every live temporary of the process, so that an interruption can remove them.
struct Registry {
    next_set: u64,
    staged: Vec<Staged>,
    /// Folders made by this run, removed on interruption if still empty.
    created: Vec<PathBuf>,
    /// Folders whose every output a live set has reserved (set, canonical folder).
    claimed: Vec<(u64, PathBuf)>,
    /// Whether the run was interrupted: no set may be reserved or put in place any more.
    stopped: bool,
}

static LIVE: Mutex<Registry> = Mutex::new(Registry {
    next_set: 0,
    staged: Vec::new(),
    created: Vec::new(),
    claimed: Vec::new(),
    stopped: false,
});

/// The refusal of a set after an interruption.
const INTERRUPTED: &str = "interrupted: no output was replaced";

/// Whether the run was interrupted ([`remove_all_temporaries`] was called): every output set
/// still live was dropped, and none will be put in place.
pub fn interrupted() -> bool {
    live().stopped
}

/// The registry, even after a panic elsewhere (its content stays consistent under the lock).
fn live() -> MutexGuard<'static, Registry> {
    LIVE.lock().unwrap_or_else(|e| e.into_inner())
}

/// Removes every live temporary (and every folder this run made that is still empty), for an
/// interruption; says whether some output set was still live (then no output of it was replaced).
/// A set being renamed into place holds the registry, so this waits until the whole set is in place.
pub fn remove_all_temporaries() -> bool {
    let mut reg = live();
    reg.stopped = true;
    let replaced_none = !reg.staged.is_empty();
    reg.staged.clear();
    for dir in reg.created.iter().rev() {
        let _ = fs::remove_dir(dir);
    }
    replaced_none
}

/// A set of outputs replaced all together by [`OutputSet::commit`], or not at all.
#[must_use = "an output set replaces nothing until it is committed"]
pub struct OutputSet {
    id: u64,
}

impl OutputSet {
    /// Checks every output and makes its temporary, before any work; refuses with one line naming
    /// the output and the rule it breaks.
    pub fn reserve(outputs: &[Output]) -> Result<OutputSet> {
        let mut targets: Vec<(PathBuf, Option<FileId>)> = Vec::new();
        for (k, out) in outputs.iter().enumerate() {
            let (target, id) = resolve(out)?;
            for (j, (other, other_id)) in targets.iter().enumerate() {
                if *other == target || (id.is_some() && id == *other_id) {
                    return Err(Error::Refused(format!(
                        "{} and {} are the same file: give different files",
                        named(&outputs[j]),
                        named(&outputs[k])
                    )));
                }
            }
            check_extension(out)?;
            targets.push((target, id));
        }
        let mut reg = live();
        if reg.stopped {
            return Err(Error::Refused(INTERRUPTED.into()));
        }
        for (out, (target, _)) in outputs.iter().zip(&targets) {
            if reg.staged.iter().any(|s| s.target == *target) {
                return Err(Error::Refused(format!(
                    "{}: this file is already being written",
                    named(out)
                )));
            }
        }
        let id = reg.next_set;
        reg.next_set += 1;
        let set = OutputSet { id };
        for (out, (target, _)) in outputs.iter().zip(targets) {
            // Made under the lock: an interruption cannot miss a temporary.
            let (temp, file) = match make_temporary(&target) {
                Ok(made) => made,
                Err(e) => {
                    // Unlocked first: dropping the set removes the temporaries made so far.
                    drop(reg);
                    drop(set);
                    return Err(Error::Refused(format!(
                        "{}: cannot write into folder {} ({e})",
                        named(out),
                        shown(parent_dir(out.path))
                    )));
                }
            };
            reg.staged.push(Staged {
                set: id,
                target,
                shown: out.path.to_path_buf(),
                temp,
                file,
                written: false,
            });
        }
        Ok(set)
    }

    /// Like [`OutputSet::reserve`], for outputs that are all of a run's files in `folder`: writing
    /// any other file there while the set lives is refused, so that no file escapes the set.
    pub fn reserve_folder(folder: &Path, outputs: &[Output]) -> Result<OutputSet> {
        let set = OutputSet::reserve(outputs)?;
        let folder = fs::canonicalize(folder)
            .map_err(|e| Error::Refused(format!("cannot open folder {} ({e})", shown(folder))))?;
        live().claimed.push((set.id, folder));
        Ok(set)
    }

    /// Renames every temporary of the set into place, all or none: if one rename fails, the targets
    /// already replaced get their previous content back. Every target must have been written.
    pub fn commit(self) -> Result {
        let mut reg = live();
        // An interruption that came first removed the set's temporaries: nothing to put in place,
        // and no success to report.
        if reg.stopped {
            return Err(Error::Refused(INTERRUPTED.into()));
        }
        if let Some(s) = reg.staged.iter().find(|s| s.set == self.id && !s.written) {
            return Err(Error::Refused(format!(
                "{} was not written: no output was replaced",
                shown(&s.shown)
            )));
        }
        let (mine, others): (Vec<Staged>, Vec<Staged>) = std::mem::take(&mut reg.staged)
            .into_iter()
            .partition(|s| s.set == self.id);
        reg.staged = others;
        reg.claimed.retain(|(set, _)| *set != self.id);
        let targets: Vec<PathBuf> = mine.iter().map(|s| s.target.clone()).collect();
        let previous: Vec<Previous> = targets.iter().map(|t| keep_previous(t)).collect();
        let mut failure = None;
        for (k, s) in mine.into_iter().enumerate() {
            // Checked again: something may have taken the target's place during the work.
            let result = still_replaceable(&s.target)
                .and_then(|()| s.temp.persist(&s.target).map_err(|e| e.error));
            if let Err(e) = result {
                failure = Some(format!("cannot write {}: {e}", shown(&s.shown)));
                // Undo the renames done: the previous content back, or no file where there was none.
                for (target, before) in targets.iter().zip(&previous).take(k) {
                    let _ = match before {
                        Previous::Absent => fs::remove_file(target),
                        Previous::Kept(backup) => fs::rename(backup, target),
                        Previous::Lost => Ok(()),
                    };
                }
                break;
            }
        }
        for before in &previous {
            if let Previous::Kept(backup) = before {
                let _ = fs::remove_file(backup);
            }
        }
        if failure.is_none() {
            // The renames themselves reach the disk.
            for dir in targets.iter().filter_map(|t| t.parent()) {
                let _ = File::open(dir).and_then(|d| d.sync_all());
            }
        }
        match failure {
            Some(msg) => Err(Error::Refused(format!("{msg}: no output was replaced"))),
            None => {
                COMMITTED.store(true, std::sync::atomic::Ordering::SeqCst);
                Ok(())
            }
        }
    }
}

/// Whether an output set was put in place whole by this run.
static COMMITTED: std::sync::atomic::AtomicBool = std::sync::atomic::AtomicBool::new(false);

/// Whether every output of this run is complete and in place: a set was committed and none is
/// still being written (an interruption now loses nothing).
pub fn outputs_complete() -> bool {
    let reg = live();
    reg.staged.is_empty() && COMMITTED.load(std::sync::atomic::Ordering::SeqCst)
}

impl Drop for OutputSet {
    /// Removes the temporaries of a set that was not committed.
    fn drop(&mut self) {
        let mut reg = live();
        reg.staged.retain(|s| s.set != self.id);
        reg.claimed.retain(|(set, _)| *set != self.id);
    }
}

/// What a target held before its set was renamed into place.
enum Previous {
    /// No file.
    Absent,
    /// A file, whose content a hard link beside it keeps.
    Kept(PathBuf),
    /// A file that could not be linked (a file system without hard links).
    Lost,
}

/// A hard link to `target`'s current content, if it has one, beside it.
fn keep_previous(target: &Path) -> Previous {
    if !target.is_file() {
        return Previous::Absent;
    }
    use std::sync::atomic::{AtomicU64, Ordering};
    static N: AtomicU64 = AtomicU64::new(0);
    let name = format!(
        ".bentstraw-{}-{}.old",
        std::process::id(),
        N.fetch_add(1, Ordering::Relaxed)
    );
    let backup = parent_dir(target).join(name);
    match fs::hard_link(target, &backup) {
        Ok(()) => Previous::Kept(backup),
        Err(_) => Previous::Lost,
    }
}

/// Checks, before any work, that `path` can be written (see [`OutputSet::reserve`]).
pub fn check_writable(path: &Path) -> Result {
    let out = Output {
        flag: "",
        path,
        extensions: &[],
    };
    let (target, _) = resolve(&out)?;
    if live().staged.iter().any(|s| s.target == target) {
        return Ok(());
    }
    // Reserving makes (and dropping removes) a temporary: the folder takes new files.
    OutputSet::reserve(&[out]).map(drop)
}

/// Writes `path` through `fill`: into its reserved temporary when a live set holds it (renamed with
/// the set), else into a temporary renamed into place at once. On failure the target is untouched.
pub fn write_atomically(
    path: &Path,
    fill: impl FnOnce(&mut dyn Write) -> io::Result<()>,
) -> Result {
    let out = Output {
        flag: "",
        path,
        extensions: &[],
    };
    let resolved = resolve(&out).ok().map(|(target, _)| target);
    let held = resolved.as_ref().and_then(|target| {
        let reg = live();
        let s = reg.staged.iter().find(|s| s.target == *target)?;
        Some((target.clone(), s.file.try_clone()))
    });
    if held.is_none() {
        let folder = resolved.as_deref().and_then(Path::parent);
        if live()
            .claimed
            .iter()
            .any(|(_, f)| Some(f.as_path()) == folder)
        {
            return Err(Error::Refused(format!(
                "cannot write {}: it is not among the files reserved in its folder",
                shown(path)
            )));
        }
    }
    match held {
        Some((target, file)) => {
            let result = file.and_then(|f| fill_file(f, fill));
            result.map_err(|source| Error::Io {
                action: "write",
                path: path.to_path_buf(),
                source,
            })?;
            if let Some(s) = live().staged.iter_mut().find(|s| s.target == target) {
                s.written = true;
            }
            Ok(())
        }
        None => {
            let set = OutputSet::reserve(&[out])?;
            write_atomically(path, fill)?;
            set.commit()
        }
    }
}

/// The bytes written to `path`: while its output set is live, its temporary's (an output read back
/// before the set is put in place), else the file's.
pub fn read_written(path: &Path) -> Result<Vec<u8>> {
    let out = Output {
        flag: "",
        path,
        extensions: &[],
    };
    let staged = resolve(&out).ok().and_then(|(target, _)| {
        live()
            .staged
            .iter()
            .find(|s| s.target == target)
            .map(|s| s.temp.to_path_buf())
    });
    fs::read(staged.as_deref().unwrap_or(path)).map_err(|source| Error::Io {
        action: "read",
        path: path.to_path_buf(),
        source,
    })
}

/// Writes bytes all-or-nothing (see [`write_atomically`]).
pub fn write_bytes(path: &Path, bytes: &[u8]) -> Result {
    write_atomically(path, |w| w.write_all(bytes))
}

/// Makes folder `dir` and any missing parents; the ones made are removed again by
/// [`remove_made_folders`] or an interruption, if still empty.
pub fn make_folder(dir: &Path) -> Result<Vec<PathBuf>> {
    let mut missing = Vec::new();
    let mut d = Some(dir);
    while let Some(p) = d.filter(|p| !p.as_os_str().is_empty() && !p.exists()) {
        missing.push(p.to_path_buf());
        d = p.parent();
    }
    missing.reverse();
    let mut reg = live();
    for p in &missing {
        fs::create_dir(p).map_err(|source| Error::Io {
            action: "create folder",
            path: p.clone(),
            source,
        })?;
        reg.created.push(p.clone());
    }
    Ok(missing)
}

/// Removes the folders `made` by [`make_folder`] that are still empty, deepest first.
pub fn remove_made_folders(made: &[PathBuf]) {
    let mut reg = live();
    for p in made.iter().rev() {
        let _ = fs::remove_dir(p);
        reg.created.retain(|c| c != p);
    }
}

/// What identifies an existing file whatever its name (device and inode), to catch hard links.
type FileId = (u64, u64);

#[cfg(unix)]
fn file_id(m: &fs::Metadata) -> Option<FileId> {
    use std::os::unix::fs::MetadataExt;
    Some((m.dev(), m.ino()))
}

#[cfg(not(unix))]
fn file_id(_: &fs::Metadata) -> Option<FileId> {
    None
}

/// Where `out` will be written, after checking that it may be: its folder exists, its name is not
/// too long, and it is absent or a writable regular file (a link to one is followed).
fn resolve(out: &Output) -> Result<(PathBuf, Option<FileId>)> {
    let refusal = |rule: String| Error::Refused(format!("{}: {rule}", named(out)));
    let refuse = |rule: String| Err(refusal(rule));
    let Some(name) = out.path.file_name() else {
        return refuse("this is not a file name".into());
    };
    if name.len() > NAME_MAX {
        return refuse(format!(
            "the file name is {} bytes long; file systems accept at most {NAME_MAX}",
            name.len()
        ));
    }
    let dir = parent_dir(out.path);
    if !dir.is_dir() {
        return refuse(format!("folder {} does not exist", shown(dir)));
    }
    let dir = fs::canonicalize(dir)
        .map_err(|e| refusal(format!("cannot open folder {} ({e})", shown(dir))))?;
    let mut target = dir.join(name);
    let meta = match fs::symlink_metadata(&target) {
        Ok(m) if m.file_type().is_symlink() => match fs::metadata(&target) {
            Ok(m) if m.is_file() => {
                target = fs::canonicalize(&target)
                    .map_err(|e| refusal(format!("cannot follow the link ({e})")))?;
                m
            }
            Ok(_) => {
                return refuse(
                    "it is a link to something that is not a regular file; only regular files are replaced".into(),
                )
            }
            Err(_) => return refuse("it is a link to nothing; only regular files are replaced".into()),
        },
        Ok(m) => m,
        Err(e) if e.kind() == io::ErrorKind::NotFound => return Ok((target, None)),
        Err(e) => return refuse(format!("cannot look at it ({e})")),
    };
    if meta.is_dir() {
        return refuse("it is a folder".into());
    }
    if !meta.is_file() {
        return refuse(
            "it is not a regular file (a device, pipe or socket); only regular files are replaced"
                .into(),
        );
    }
    if meta.permissions().readonly() {
        return refuse("the file is read-only; make it writable to replace it".into());
    }
    Ok((target, file_id(&meta)))
}

/// Checked just before the rename: the target is still absent or a regular file.
fn still_replaceable(target: &Path) -> io::Result<()> {
    match fs::symlink_metadata(target) {
        Ok(m) if !m.is_file() => Err(io::Error::new(
            io::ErrorKind::AlreadyExists,
            "something that is not a regular file took its place",
        )),
        _ => Ok(()),
    }
}

/// A new temporary beside `target`, with the target's permissions if it exists.
fn make_temporary(target: &Path) -> io::Result<(TempPath, File)> {
    let dir = target.parent().unwrap_or(Path::new("."));
    let temp = Builder::new()
        .prefix(".bentstraw-")
        .suffix(".tmp")
        .rand_bytes(6)
        .permissions(default_permissions())
        .tempfile_in(dir)?;
    if let Ok(m) = fs::metadata(target) {
        // Best effort: where permissions cannot be set, the file gets a new file's.
        let _ = fs::set_permissions(temp.path(), m.permissions());
    }
    let file = temp.as_file().try_clone()?;
    Ok((temp.into_temp_path(), file))
}

/// The permissions a new file gets (before the umask): what `File::create` gives.
#[cfg(unix)]
fn default_permissions() -> fs::Permissions {
    use std::os::unix::fs::PermissionsExt;
    fs::Permissions::from_mode(0o666)
}

#[cfg(not(unix))]
fn default_permissions() -> fs::Permissions {
    fs::metadata(".")
        .map(|m| m.permissions())
        .unwrap_or_else(|_| unreachable!())
}

/// Fills `file` from the start with `fill`, then syncs it to disk.
fn fill_file(
    mut file: File,
    fill: impl FnOnce(&mut dyn Write) -> io::Result<()>,
) -> io::Result<()> {
    file.set_len(0)?;
    file.rewind()?;
    let mut w = BufWriter::with_capacity(1 << 20, file);
    fill(&mut w)?;
    w.into_inner().map_err(|e| e.into_error())?.sync_all()
}

/// "--raw v.png" or "v.png": the output as the user named it.
fn named(out: &Output) -> String {
    if out.flag.is_empty() {
        format!("cannot write {}", shown(out.path))
    } else {
        format!("{} {}", out.flag, shown(out.path))
    }
}

/// Checks that `out` ends in one of its allowed extensions.
fn check_extension(out: &Output) -> Result {
    if out.extensions.is_empty() {
        return Ok(());
    }
    let ext = out
        .path
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase());
    if ext.as_deref().is_some_and(|e| out.extensions.contains(&e)) {
        return Ok(());
    }
    let names: Vec<String> = out.extensions.iter().map(|a| format!(".{a}")).collect();
    // ".png", ".png or .svg", ".png, .svg or .pdf".
    let expected = match names.split_last() {
        Some((last, rest)) if !rest.is_empty() => format!("{} or {last}", rest.join(", ")),
        _ => names.join(""),
    };
    Err(Error::Refused(format!(
        "{}: the file name must end in {expected}",
        named(out)
    )))
}

fn parent_dir(path: &Path) -> &Path {
    match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    }
}

/// Why an input file was not read.
#[derive(Debug)]
pub enum Unread {
    /// It could not be opened or read.
    Io(io::Error),
    /// It is no regular file: a folder, or a device, a pipe or a socket (which may never end, or
    /// never start: `/dev/zero`, a FIFO no one writes), and why, in words.
    NotAFile(&'static str),
    /// It holds more than the limit: its size in words.
    TooLarge(String),
}

/// The bytes of the input file at `path`, at most `limit` of them: a file that is no regular file
/// is refused before it is opened, and none is read further than one byte past the limit,
/// whatever its size said (it may grow while it is read).
pub fn read_input(path: &Path, limit: u64) -> std::result::Result<Vec<u8>, Unread> {
    use std::io::Read as _;
    let meta = fs::metadata(path).map_err(Unread::Io)?;
    if meta.is_dir() {
        return Err(Unread::NotAFile("it is a folder"));
    }
    if !meta.is_file() {
        return Err(Unread::NotAFile(
            "it is not a regular file (a device, a pipe or a socket): save its content to a file",
        ));
    }
    if meta.len() > limit {
        return Err(Unread::TooLarge(format!("{} bytes", meta.len())));
    }
    let mut bytes = Vec::new();
    File::open(path)
        .and_then(|f| f.take(limit + 1).read_to_end(&mut bytes))
        .map_err(Unread::Io)?;
    if bytes.len() as u64 > limit {
        return Err(Unread::TooLarge(format!(
            "more than {limit} bytes (it grew)"
        )));
    }
    Ok(bytes)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The names in `dir`, sorted.
    fn names(dir: &Path) -> Vec<String> {
        let mut n: Vec<String> = fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        n.sort();
        n
    }

    fn output(path: &Path) -> Output<'_> {
        Output {
            flag: "--output",
            path,
            extensions: &[],
        }
    }

    #[test]
    fn a_writer_failing_midway_keeps_the_previous_file() {
        let dir = tempfile::tempdir().unwrap();
        let a = dir.path().join("a.csv");
        fs::write(&a, b"old").unwrap();
        let err = write_atomically(&a, |w| {
            w.write_all(&[b'x'; 5000])?;
            Err(io::Error::other("no space left"))
        })
        .unwrap_err();
        assert!(
            err.to_string().contains("a.csv") && err.to_string().contains("no space left"),
            "{err}"
        );
        assert_eq!(fs::read(&a).unwrap(), b"old");
        assert_eq!(names(dir.path()), ["a.csv"]);
    }

    #[test]
    fn a_set_replaces_all_its_files_only_on_commit() {
        let dir = tempfile::tempdir().unwrap();
        let (a, b) = (dir.path().join("a.txt"), dir.path().join("b.txt"));
        fs::write(&a, b"old a").unwrap();
        let set = OutputSet::reserve(&[output(&a), output(&b)]).unwrap();
        write_bytes(&a, b"new a").unwrap();
        write_bytes(&b, b"new b").unwrap();
        // Written, not yet in place.
        assert_eq!(fs::read(&a).unwrap(), b"old a");
        assert!(!b.exists());
        set.commit().unwrap();
        assert_eq!(fs::read(&a).unwrap(), b"new a");
        assert_eq!(fs::read(&b).unwrap(), b"new b");
        assert_eq!(names(dir.path()), ["a.txt", "b.txt"]);
    }

    #[test]
    fn a_set_not_fully_written_replaces_nothing() {
        let dir = tempfile::tempdir().unwrap();
        let (a, b) = (dir.path().join("a.txt"), dir.path().join("b.txt"));
        fs::write(&a, b"old a").unwrap();
        let set = OutputSet::reserve(&[output(&a), output(&b)]).unwrap();
        write_bytes(&a, b"new a").unwrap();
        assert!(set.commit().unwrap_err().to_string().contains("b.txt"));
        assert_eq!(fs::read(&a).unwrap(), b"old a");
        assert_eq!(names(dir.path()), ["a.txt"]);
        // Dropped without a commit: the same.
        let set = OutputSet::reserve(&[output(&a)]).unwrap();
        write_bytes(&a, b"new a").unwrap();
        drop(set);
        assert_eq!(fs::read(&a).unwrap(), b"old a");
        assert_eq!(names(dir.path()), ["a.txt"]);
    }

    #[test]
    fn a_rename_failing_midway_puts_the_earlier_files_back() {
        let dir = tempfile::tempdir().unwrap();
        let (a, b, c) = (
            dir.path().join("a.txt"),
            dir.path().join("b.txt"),
            dir.path().join("c.txt"),
        );
        fs::write(&a, b"old a").unwrap();
        fs::write(&c, b"old c").unwrap();
        let set = OutputSet::reserve(&[output(&a), output(&b), output(&c)]).unwrap();
        for p in [&a, &b, &c] {
            write_bytes(p, b"new").unwrap();
        }
        // During the work, a folder takes c's place: a and b are renamed, then c fails.
        fs::remove_file(&c).unwrap();
        fs::create_dir(&c).unwrap();
        let err = set.commit().unwrap_err();
        assert!(
            err.to_string().contains("c.txt") && err.to_string().contains("no output was replaced"),
            "{err}"
        );
        assert_eq!(fs::read(&a).unwrap(), b"old a");
        assert!(!b.exists(), "b had no previous file");
        assert!(c.is_dir());
        assert_eq!(names(dir.path()), ["a.txt", "c.txt"]);
    }

    #[test]
    fn a_claimed_folder_takes_no_file_outside_the_set() {
        let dir = tempfile::tempdir().unwrap();
        let (x, y) = (dir.path().join("x.txt"), dir.path().join("y.txt"));
        let set = OutputSet::reserve_folder(dir.path(), &[output(&x)]).unwrap();
        write_bytes(&x, b"x").unwrap();
        assert!(write_bytes(&y, b"y")
            .unwrap_err()
            .to_string()
            .contains("not among"));
        set.commit().unwrap();
        assert_eq!(names(dir.path()), ["x.txt"]);
        // Once committed, the folder is free again.
        write_bytes(&y, b"y").unwrap();
        assert_eq!(names(dir.path()), ["x.txt", "y.txt"]);
    }

    #[test]
    fn two_names_of_one_file_are_refused() {
        let dir = tempfile::tempdir().unwrap();
        let a = dir.path().join("a.txt");
        let dotted = dir.path().join(".").join("a.txt");
        let err = OutputSet::reserve(&[output(&a), output(&dotted)])
            .err()
            .unwrap();
        assert!(err.to_string().contains("same file"), "{err}");
        fs::write(&a, b"old").unwrap();
        let linked = dir.path().join("b.txt");
        fs::hard_link(&a, &linked).unwrap();
        let err = OutputSet::reserve(&[output(&a), output(&linked)])
            .err()
            .unwrap();
        assert!(err.to_string().contains("same file"), "{err}");
        assert_eq!(names(dir.path()), ["a.txt", "b.txt"]);
    }
}
