//! A class's hand-ins: a folder with one sub-folder per student, or a zip of such folders (as
//! Moodle's "download all submissions" gives them, its folder names included). A student's files
//! are those directly in their folder; a file that cannot be trusted (a link, a path that leaves
//! the folder, an entry that expands like a zip bomb, one larger than any image) is that file's
//! refusal, with the reason: the student's case is unreadable, and the rest of the class is graded.

use std::fs::File;
use std::io::{self, Read, Seek, SeekFrom};
use std::path::{Path, PathBuf};
use std::sync::Arc;

use zip::ZipArchive;

use crate::error::{Error, Result};
use crate::files::{read_input, Unread};
use crate::solution::{unread_words, MAX_FILE_BYTES};

/// Most students in a class (sub-folders read): a folder or zip with more is not a class.
pub const MAX_STUDENTS: usize = 5000;
/// Most entries a class's zip may list: beyond, it is not a class's hand-ins.
pub const MAX_ZIP_ENTRIES: usize = 200_000;
/// Most a zip entry may expand over its compressed size: image points written as text compress
/// a few times; an entry that expands more is taken for a zip bomb and not read further.
pub const MAX_EXPANSION: u64 = 100;
/// The suffix Moodle gives each student's folder in "download all submissions".
const MOODLE_SUFFIX: &str = "_assignsubmission_file_";

/// A student: a name and the files they handed in.
#[derive(Clone, Debug)]
pub struct Student {
    /// The name shown in the gradebook: the folder's, or Moodle's name part of it.
    pub name: String,
    /// The name of the student's folder (unique in the class): their outputs' folder too.
    pub folder: String,
    /// Where the files are.
    files: Files,
}

/// Where a student's files are.
#[derive(Clone, Debug)]
enum Files {
    /// In a folder.
    Folder(PathBuf),
    /// In a zip: the archive (shared by the class) and the student's entries.
    Zip(ZipArchive<SharedFile>, Vec<Entry>),
}

/// A file of a student's folder in a zip.
#[derive(Clone, Debug)]
struct Entry {
    /// Its name in the student's folder.
    name: String,
    /// Its index in the archive.
    index: usize,
    /// Why it is not read, if it is not.
    refusal: Option<String>,
}

/// A file a student handed in.
#[derive(Clone, Debug)]
pub struct HandIn {
    /// Its name, as the student named it.
    pub name: String,
    /// Where it is.
    place: Place,
}

/// Where a handed-in file is.
#[derive(Clone, Debug)]
enum Place {
    /// On disk.
    Path(PathBuf),
    /// In the class's zip, at this index.
    Zip(usize),
    /// Nowhere it can be read from: why.
    Refused(String),
}

impl Student {
    /// The names of the files directly in the student's folder, with where they are.
    pub fn hand_ins(&self) -> Vec<HandIn> {
        match &self.files {
            Files::Folder(folder) => std::fs::read_dir(folder)
                .map(|entries| {
                    entries
                        .flatten()
                        .map(|e| {
                            let name = e.file_name().to_string_lossy().into_owned();
                            let path = e.path();
                            let place = if std::fs::symlink_metadata(&path)
                                .is_ok_and(|m| m.file_type().is_symlink())
                            {
                                Place::Refused(link_refusal(&name))
                            } else {
                                Place::Path(path)
                            };
                            HandIn { name, place }
                        })
                        .collect()
                })
                .unwrap_or_default(),
            Files::Zip(_, entries) => entries
                .iter()
                .map(|e| HandIn {
                    name: e.name.clone(),
                    place: match &e.refusal {
                        Some(why) => Place::Refused(why.clone()),
                        None => Place::Zip(e.index),
                    },
                })
                .collect(),
        }
    }

    /// The bytes of `file` (one of [`Student::hand_ins`]), or why they cannot be read, in words
    /// naming the file as the student named it.
    pub fn read(&self, file: &HandIn) -> std::result::Result<Vec<u8>, String> {
        let unread = match &file.place {
            Place::Refused(why) => return Err(why.clone()),
            Place::Path(path) => read_input(path, MAX_FILE_BYTES),
            Place::Zip(index) => match &self.files {
                Files::Zip(archive, _) => read_entry(archive, *index),
                Files::Folder(_) => unreachable!("a zip entry of a folder's student"),
            },
        };
        unread.map_err(|u| unread_words(&file.name, u))
    }
}

/// Why a link is not read.
fn link_refusal(name: &str) -> String {
    format!("{name} is a link: hand in the file itself")
}

/// The name of a student's folder: Moodle's `Name_Id_assignsubmission_file_` gives `Name`.
pub fn student_name(folder_name: &str) -> String {
    match folder_name.strip_suffix(MOODLE_SUFFIX) {
        Some(rest) => match rest.rsplit_once('_') {
            Some((name, id)) if !name.is_empty() && id.chars().all(|c| c.is_ascii_digit()) => {
                name.to_string()
            }
            _ => rest.to_string(),
        },
        None => folder_name.to_string(),
    }
}

/// Whether a folder's name is no student's: hidden ones, and the resource forks macOS adds to
/// the zips it makes.
fn not_a_student(folder_name: &str) -> bool {
    folder_name.starts_with('.') || folder_name == "__MACOSX"
}

/// The students of `class`: a folder with one sub-folder per student (links are not followed),
/// or a zip of such folders (`.zip`, or any file that is one), in the order of their names.
pub fn students(class: &Path) -> Result<Vec<Student>> {
    let mut found = if class.is_file() {
        zip_students(class)?
    } else {
        folder_students(class)?
    };
    if found.is_empty() {
        return Err(Error::Refused(format!(
            "{} has no sub-folder: give a folder (or a zip) with one sub-folder per student",
            class.display()
        )));
    }
    if found.len() > MAX_STUDENTS {
        return Err(Error::Refused(format!(
            "{} has more than {MAX_STUDENTS} sub-folders: not a class",
            class.display()
        )));
    }
    found.sort_by(|a, b| a.name.cmp(&b.name).then(a.folder.cmp(&b.folder)));
    Ok(found)
}

/// The students of a class folder.
fn folder_students(class: &Path) -> Result<Vec<Student>> {
    let entries = std::fs::read_dir(class).map_err(|e| {
        Error::Refused(format!(
            "cannot read the class folder {} ({e}): give a folder (or a zip) with one \
             sub-folder per student",
            class.display()
        ))
    })?;
    let mut found = Vec::new();
    for entry in entries.flatten() {
        let Ok(kind) = entry.file_type() else {
            continue;
        };
        if !kind.is_dir() {
            continue; // files beside the students' folders, and links, are not students
        }
        let folder = entry.file_name().to_string_lossy().into_owned();
        if not_a_student(&folder) {
            continue;
        }
        found.push(Student {
            name: student_name(&folder),
            folder,
            files: Files::Folder(entry.path()),
        });
        if found.len() > MAX_STUDENTS {
            break;
        }
    }
    Ok(found)
}

/// A file read at positions of its own: clones share the open file, each with its own position,
/// so that students are read in parallel from one archive.
#[derive(Clone, Debug)]
struct SharedFile {
    file: Arc<File>,
    position: u64,
    len: u64,
}

impl Read for SharedFile {
    fn read(&mut self, buf: &mut [u8]) -> io::Result<usize> {
        #[cfg(unix)]
        let n = std::os::unix::fs::FileExt::read_at(&*self.file, buf, self.position)?;
        #[cfg(windows)]
        let n = std::os::windows::fs::FileExt::seek_read(&*self.file, buf, self.position)?;
        #[cfg(not(any(unix, windows)))]
        let n = {
            let _ = buf;
            return Err(io::Error::other("reading a zip needs a native target"));
        };
        self.position += n as u64;
        Ok(n)
    }
}

impl Seek for SharedFile {
    fn seek(&mut self, to: SeekFrom) -> io::Result<u64> {
        let target = match to {
            SeekFrom::Start(p) => Some(p),
            SeekFrom::End(d) => self.len.checked_add_signed(d),
            SeekFrom::Current(d) => self.position.checked_add_signed(d),
        };
        self.position = target.ok_or_else(|| {
            io::Error::new(io::ErrorKind::InvalidInput, "seek before the file's start")
        })?;
        Ok(self.position)
    }
}

/// The students of a class's zip: its folders (under one enclosing folder, if it has one), each
/// with the files directly in it.
fn zip_students(class: &Path) -> Result<Vec<Student>> {
    let unzip = |why: String| {
        Error::Refused(format!(
            "cannot read the class {} as a zip ({why}): give a zip (or a folder) with one \
             sub-folder per student",
            class.display()
        ))
    };
    let file = File::open(class).map_err(|e| unzip(e.to_string()))?;
    let len = file.metadata().map_err(|e| unzip(e.to_string()))?.len();
    let reader = SharedFile {
        file: Arc::new(file),
        position: 0,
        len,
    };
    let archive = ZipArchive::new(reader).map_err(|e| unzip(e.to_string()))?;
    if archive.len() > MAX_ZIP_ENTRIES {
        return Err(unzip(format!(
            "{} entries: more than {MAX_ZIP_ENTRIES}",
            archive.len()
        )));
    }
    // Each entry's path, in parts; those that start outside the archive (absolute, `..`) belong
    // to no student and are passed over.
    let mut listed: Vec<(usize, Vec<String>, bool)> = Vec::new();
    for index in 0..archive.len() {
        let Ok(entry) = archive.by_index_data(index) else {
            continue;
        };
        let Ok(name) = entry.name() else {
            continue;
        };
        let raw = name.replace('\\', "/");
        if raw.starts_with('/') || raw.get(1..2) == Some(":") {
            continue;
        }
        let parts: Vec<String> = raw
            .split('/')
            .filter(|p| !p.is_empty() && *p != ".")
            .map(str::to_string)
            .collect();
        if parts.is_empty() || parts[0] == ".." || not_a_student(&parts[0]) {
            continue;
        }
        let link = entry.is_symlink();
        listed.push((index, parts, entry.is_dir() && !link));
    }
    // A zip of one folder holding the students' folders: that folder is passed through.
    let first = listed.first().map(|(_, p, _)| p[0].clone());
    let enclosed = first.as_ref().is_some_and(|top| {
        !top.ends_with(MOODLE_SUFFIX)
            && listed.iter().all(|(_, p, _)| &p[0] == top)
            && listed
                .iter()
                .any(|(_, p, dir)| p.len() >= 3 || (*dir && p.len() == 2))
    });
    let mut found: Vec<Student> = Vec::new();
    for (index, mut parts, dir) in listed {
        if enclosed {
            parts.remove(0);
        }
        let Some(folder) = parts.first().cloned() else {
            continue;
        };
        if folder == ".." || not_a_student(&folder) || (parts.len() == 1 && !dir) {
            continue; // files beside the students' folders are not students
        }
        let k = match found.iter().position(|s| s.folder == folder) {
            Some(k) => k,
            None => {
                if found.len() == MAX_STUDENTS {
                    return Err(unzip(format!("more than {MAX_STUDENTS} students' folders")));
                }
                found.push(Student {
                    name: student_name(&folder),
                    folder: folder.clone(),
                    files: Files::Zip(archive.clone(), Vec::new()),
                });
                found.len() - 1
            }
        };
        if dir || parts.len() == 1 {
            continue;
        }
        let rest = &parts[1..];
        let name = rest.last().cloned().unwrap_or_default();
        let refusal = if rest.iter().any(|p| p == "..") {
            Some(format!(
                "{name} lies at {}, a path out of the student's folder: not read",
                parts.join("/")
            ))
        } else if rest.len() > 1 {
            continue; // files in the student's sub-folders, as for a class folder
        } else if archive.by_index_data(index).is_ok_and(|e| e.is_symlink()) {
            Some(link_refusal(&name))
        } else {
            None
        };
        if let Files::Zip(_, entries) = &mut found[k].files {
            entries.push(Entry {
                name,
                index,
                refusal,
            });
        }
    }
    Ok(found)
}

/// The bytes of entry `index` of `archive`: at most [`MAX_FILE_BYTES`] of them, and at most
/// [`MAX_EXPANSION`] times its compressed size (a zip bomb stops there), whatever its header
/// says.
fn read_entry(
    archive: &ZipArchive<SharedFile>,
    index: usize,
) -> std::result::Result<Vec<u8>, Unread> {
    let mut archive = archive.clone();
    let mut entry = archive
        .by_index(index)
        .map_err(|e| Unread::Io(io::Error::other(e.to_string())))?;
    if entry.size() > MAX_FILE_BYTES {
        return Err(Unread::TooLarge(format!("{} bytes", entry.size())));
    }
    // A megabyte whatever its compression: small files may compress well.
    let bomb = MAX_EXPANSION
        .saturating_mul(entry.compressed_size())
        .saturating_add(1 << 20);
    let limit = MAX_FILE_BYTES.min(bomb);
    let mut bytes = Vec::new();
    (&mut entry)
        .take(limit + 1)
        .read_to_end(&mut bytes)
        .map_err(Unread::Io)?;
    if bytes.len() as u64 > limit {
        return Err(Unread::TooLarge(if limit < MAX_FILE_BYTES {
            format!(
                "more than {MAX_EXPANSION} times its compressed size of {} bytes once \
                 unzipped (a zip bomb)",
                entry.compressed_size()
            )
        } else {
            format!("more than {MAX_FILE_BYTES} bytes once unzipped")
        }));
    }
    Ok(bytes)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::io::Write;
    use zip::write::{SimpleFileOptions, ZipWriter};
    use zip::CompressionMethod;

    #[test]
    fn moodle_folders_give_the_students_names() {
        assert_eq!(
            student_name("Marie Curie_123456_assignsubmission_file_"),
            "Marie Curie"
        );
        assert_eq!(student_name("ada"), "ada");
        // Not Moodle's id: kept whole.
        assert_eq!(student_name("x_y_assignsubmission_file_"), "x_y");
    }

    /// A zip of `entries` (name, bytes) and `links` (name, target), deflated, at `path`.
    fn zip_of(path: &Path, entries: &[(&str, &[u8])], links: &[(&str, &str)]) {
        let mut zip = ZipWriter::new(File::create(path).unwrap());
        let options = SimpleFileOptions::default().compression_method(CompressionMethod::Deflated);
        for (name, bytes) in entries {
            if name.ends_with('/') {
                zip.add_directory(*name, options).unwrap();
            } else {
                zip.start_file(*name, options).unwrap();
                zip.write_all(bytes).unwrap();
            }
        }
        for (name, target) in links {
            zip.add_symlink(*name, *target, options).unwrap();
        }
        zip.finish().unwrap();
    }

    /// Each student's files, as (name, bytes or why not).
    fn read_all(s: &Student) -> Vec<(String, std::result::Result<Vec<u8>, String>)> {
        let mut files: Vec<_> = s
            .hand_ins()
            .iter()
            .map(|f| (f.name.clone(), s.read(f)))
            .collect();
        files.sort_by(|a, b| a.0.cmp(&b.0));
        files
    }

    #[test]
    fn a_zip_gives_its_students_files_and_refuses_the_untrusted_ones_alone() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("class.zip");
        let zeros = vec![b'0'; 20 << 20];
        zip_of(
            &path,
            &[
                ("class/ada/sim1.csv", b"0 0 0 1\n"),
                ("class/ada/old/sim2.csv", b"in a sub-folder: not read"),
                (
                    "class/Marie Curie_12_assignsubmission_file_/SIM2.TXT",
                    b"1 2 3 4\n",
                ),
                ("class/eve/../../../etc/sim3.csv", b"outside"),
                ("class/bomb/sim1.csv", &zeros),
                ("class/empty/", b""),
                ("class/notes.txt", b"beside the folders: no student"),
                ("__MACOSX/class/ada/._sim1.csv", b"macOS's resource fork"),
                ("../evil.csv", b"outside the archive"),
            ],
            &[("class/eve/sim4.csv", "../ada/sim1.csv")],
        );
        let class = students(&path).unwrap();
        let names: Vec<&str> = class.iter().map(|s| s.name.as_str()).collect();
        assert_eq!(names, ["Marie Curie", "ada", "bomb", "empty", "eve"]);
        assert_eq!(class[0].folder, "Marie Curie_12_assignsubmission_file_");
        let ada = read_all(&class[1]);
        assert_eq!(ada.len(), 1, "{ada:?}");
        assert_eq!(ada[0], ("sim1.csv".into(), Ok(b"0 0 0 1\n".to_vec())));
        assert_eq!(read_all(&class[0])[0].1, Ok(b"1 2 3 4\n".to_vec()));
        // A bomb: 20 MB of one byte compress a thousandfold; the reading stops far before.
        let bomb = read_all(&class[2]);
        let why = bomb[0].1.as_ref().unwrap_err();
        assert!(why.starts_with("sim1.csv is more than 100 times"), "{why}");
        assert!(why.contains("zip bomb"), "{why}");
        assert!(class[3].hand_ins().is_empty());
        let eve = read_all(&class[4]);
        let out = eve[0].1.as_ref().unwrap_err();
        assert_eq!(eve[0].0, "sim3.csv");
        assert!(out.contains("out of the student's folder"), "{out}");
        let link = eve[1].1.as_ref().unwrap_err();
        assert_eq!(eve[1].0, "sim4.csv");
        assert!(link.contains("is a link"), "{link}");
    }

    #[test]
    fn a_zip_of_the_students_folders_themselves_and_a_broken_zip() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("class.zip");
        zip_of(
            &path,
            &[("ada/sim1.csv", b"x"), ("bob/sim1.csv", b"y")],
            &[],
        );
        let class = students(&path).unwrap();
        let names: Vec<&str> = class.iter().map(|s| s.name.as_str()).collect();
        assert_eq!(names, ["ada", "bob"]);
        // One student's folder alone is a class of one, not a folder to pass through.
        zip_of(&path, &[("ada/sim1.csv", b"x")], &[]);
        assert_eq!(students(&path).unwrap()[0].name, "ada");
        std::fs::write(&path, b"PK but not a zip").unwrap();
        let e = students(&path).unwrap_err().to_string();
        assert!(e.contains("as a zip"), "{e}");
    }
}
