//! The outputs' bytes, kept: the reference simulations' and the gallery's points, figures,
//! pictures, pages and verdicts (`golden/commands.txt`) hashed and compared with the hashes in
//! `golden/outputs.txt`, which an earlier build made. A change of code that is meant to keep
//! every output as it is (a refactoring) must pass it unchanged; a change meant to alter an
//! output says so by writing the manifest anew (below) in the same commit.
//!
//! To write the manifest with a given build of the program:
//! `BENTSTRAW_GOLDEN_WRITE=path/to/bentstraw cargo test -p bentstraw golden`.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::Command;

/// The folder of this test's data.
fn golden_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/golden")
}

/// FNV-1a, 64 bits: enough to tell two files apart, and no dependency.
fn fnv1a(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325, |h, &b| {
        (h ^ b as u64).wrapping_mul(0x0000_0100_0000_01b3)
    })
}

/// `bytes` less what changes from run to run by design: a `check --json` verdict's `seconds`,
/// and the order of a PDF's lines (its resource dictionaries list their entries in any order, so
/// a PDF is compared as the sorted list of its lines).
fn stable(name: &str, bytes: Vec<u8>) -> Vec<u8> {
    if name.ends_with(".pdf") {
        let mut lines: Vec<&[u8]> = bytes.split(|&b| b == b'\n').collect();
        lines.sort_unstable();
        return lines.join(&b'\n');
    }
    let key = b"\"seconds\":";
    let Some(at) = bytes.windows(key.len()).position(|w| w == key) else {
        return bytes;
    };
    let start = at + key.len();
    let end = bytes[start..]
        .iter()
        .position(|b| !(b.is_ascii_digit() || b".eE+-".contains(b)))
        .map_or(bytes.len(), |n| start + n);
    [&bytes[..start], &bytes[end..]].concat()
}

/// Runs every command of `commands.txt` with `program` in an empty folder; the hash and size of
/// every file left there and of each command's standard output, by name.
fn outputs_of(program: &Path) -> BTreeMap<String, (u64, usize)> {
    let scenes = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenes");
    let commands = std::fs::read_to_string(golden_dir().join("commands.txt")).unwrap();
    let dir = tempfile::tempdir().unwrap();
    let input = "spec.toml";
    std::fs::copy(scenes.join(input), dir.path().join(input)).unwrap();
    let mut outputs = BTreeMap::new();
    let lines = commands
        .lines()
        .filter(|l| !l.starts_with('#') && !l.trim().is_empty());
    for (k, line) in lines.enumerate() {
        let out = Command::new(program)
            .current_dir(dir.path())
            .args(line.split_whitespace())
            .output()
            .expect("the program runs");
        // `check` exits 1 on a failing solution: its verdict is an output like any other.
        assert!(
            matches!(out.status.code(), Some(0 | 1)),
            "`{line}` failed: {}",
            String::from_utf8_lossy(&out.stderr)
        );
        let name = format!("command-{:02}.stdout", k + 1);
        let bytes = stable(&name, out.stdout);
        outputs.insert(name, (fnv1a(&bytes), bytes.len()));
    }
    for entry in std::fs::read_dir(dir.path()).unwrap() {
        let entry = entry.unwrap();
        let name = entry.file_name().to_string_lossy().into_owned();
        if name == input {
            continue;
        }
        let bytes = stable(&name, std::fs::read(entry.path()).unwrap());
        outputs.insert(name, (fnv1a(&bytes), bytes.len()));
    }
    outputs
}

/// The manifest's text for `outputs`: a line per output, `hash size name`.
fn manifest(outputs: &BTreeMap<String, (u64, usize)>) -> String {
    outputs
        .iter()
        .map(|(name, (hash, size))| format!("{hash:016x} {size:>9} {name}\n"))
        .collect()
}

#[test]
fn every_output_keeps_its_bytes() {
    let path = golden_dir().join("outputs.txt");
    if let Some(program) = std::env::var_os("BENTSTRAW_GOLDEN_WRITE") {
        std::fs::write(&path, manifest(&outputs_of(Path::new(&program)))).unwrap();
        return;
    }
    let want = std::fs::read_to_string(&path).unwrap();
    let got = manifest(&outputs_of(Path::new(env!("CARGO_BIN_EXE_bentstraw"))));
    let (want_lines, got_lines): (Vec<&str>, Vec<&str>) =
        (want.lines().collect(), got.lines().collect());
    let differ: Vec<String> = want_lines
        .iter()
        .filter(|l| !got_lines.contains(l))
        .map(|l| format!("  was: {l}"))
        .chain(
            got_lines
                .iter()
                .filter(|l| !want_lines.contains(l))
                .map(|l| format!("  now: {l}")),
        )
        .collect();
    assert!(
        differ.is_empty(),
        "{} outputs changed their bytes (hash, size, name):\n{}",
        differ.len() / 2,
        differ.join("\n")
    );
}
