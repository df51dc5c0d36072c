//! Project tasks, run as `cargo xtask TASK`:
//!
//! - `cargo xtask site [DIR]` builds the static site (default `target/site`): the explorer's page,
//!   its scripts, and the engine compiled to WebAssembly (with SIMD), plain files that any static
//!   host serves. It needs the `wasm32-unknown-unknown` target and `wasm-bindgen` of the version
//!   the engine is built against.

use std::path::{Path, PathBuf};
use std::process::{Command, ExitCode};

use bentstraw_explore::page::{index_html, Engine, PAGE_FILES};

/// The `wasm-bindgen` the engine's crate is pinned to (its command must be the same version).
const WASM_BINDGEN: &str = "0.2.130";

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let result = match args.iter().map(String::as_str).collect::<Vec<_>>().as_slice() {
        ["site"] => site(Path::new("target/site")),
        ["site", dir] => site(Path::new(dir)),
        _ => Err("usage: cargo xtask site [DIR]   (builds the static site into DIR, default target/site)".into()),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}

/// One of the site's two builds of the engine.
struct WasmEngine {
    /// Its folder in the site.
    pkg: &'static str,
    /// Its own cargo target folder.
    target_dir: &'static str,
    /// The WebAssembly features it is compiled with (SIMD in both: the packets are their own code).
    rustflags: &'static str,
    /// Whether it is built with threads (shared memory, the standard library rebuilt).
    threads: bool,
}

impl WasmEngine {
    const ALL: [WasmEngine; 2] = [
        WasmEngine {
            pkg: "pkg",
            target_dir: "target/site-build",
            rustflags: "-C target-feature=+simd128",
            threads: false,
        },
        WasmEngine {
            pkg: "pkg-threads",
            target_dir: "target/site-build-threads",
            // Shared memory, imported so that every thread's instance has the same one (at most
            // 1 GiB, reserved by the browser from the start), and the thread-local storage that
            // wasm-bindgen sets up for each thread.
            rustflags: "-C target-feature=+simd128,+atomics,+bulk-memory,+mutable-globals \
                -C link-arg=--shared-memory -C link-arg=--import-memory -C link-arg=--max-memory=1073741824 \
                -C link-arg=--export=__wasm_init_tls -C link-arg=--export=__tls_size \
                -C link-arg=--export=__tls_align -C link-arg=--export=__tls_base",
            threads: true,
        },
    ];
}

/// Builds the site into `dir`: written into a fresh folder beside it, then renamed into place,
/// so `dir` is either the old site or the whole new one.
fn site(dir: &Path) -> Result<(), String> {
    let root = workspace_root();
    // Two engines: one thread per worker, which any browser runs, and one whose frames are split
    // over the cores, which needs shared memory (a cross-origin isolated page) and the standard
    // library rebuilt with atomics (`build-std`: rustc's own sources, unstable, so enabled for
    // this build alone with RUSTC_BOOTSTRAP rather than a second, nightly, toolchain). Each has
    // its own target folder: their settings never rebuild the native build or each other.
    for engine in WasmEngine::ALL {
        let mut cargo = Command::new(std::env::var("CARGO").unwrap_or_else(|_| "cargo".into()));
        cargo
            .current_dir(&root)
            .args(["build", "--release", "--locked", "-p", "bentstraw-web"])
            .args(["--target", "wasm32-unknown-unknown", "--target-dir"])
            .arg(root.join(engine.target_dir))
            .env(
                "CARGO_TARGET_WASM32_UNKNOWN_UNKNOWN_RUSTFLAGS",
                engine.rustflags,
            )
            .env("CARGO_PROFILE_RELEASE_DEBUG", "0");
        if engine.threads {
            cargo
                .args(["-Z", "build-std=panic_abort,std"])
                .env("RUSTC_BOOTSTRAP", "1");
        }
        run(&mut cargo).map_err(|e| {
            if engine.threads {
                format!("{e}\n(the threaded engine rebuilds the standard library: `rustup component add rust-src`)")
            } else {
                e
            }
        })?;
    }
    let version = Command::new("wasm-bindgen")
        .arg("--version")
        .output()
        .map_err(|e| format!("cannot run wasm-bindgen ({e}): install it with `cargo install wasm-bindgen-cli --version {WASM_BINDGEN}`"))?;
    let version = String::from_utf8_lossy(&version.stdout);
    if version.split_whitespace().nth(1) != Some(WASM_BINDGEN) {
        return Err(format!(
            "wasm-bindgen {} is installed, the engine needs {WASM_BINDGEN}: `cargo install wasm-bindgen-cli --version {WASM_BINDGEN}`",
            version.trim()
        ));
    }
    let parent = match dir.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => PathBuf::from("."),
    };
    std::fs::create_dir_all(&parent)
        .map_err(|e| format!("cannot create {}: {e}", parent.display()))?;
    let fresh = parent.join(format!(
        ".{}.new",
        dir.file_name()
            .map_or("site".into(), |n| n.to_string_lossy())
    ));
    let _ = std::fs::remove_dir_all(&fresh);
    for engine in WasmEngine::ALL {
        run(Command::new("wasm-bindgen")
            .args(["--target", "web", "--no-typescript", "--out-dir"])
            .arg(fresh.join(engine.pkg))
            .arg(
                root.join(engine.target_dir)
                    .join("wasm32-unknown-unknown/release/bentstraw_web.wasm"),
            ))?;
    }
    let write = |name: &str, text: &str| {
        std::fs::write(fresh.join(name), text).map_err(|e| format!("cannot write {name}: {e}"))
    };
    write("index.html", &index_html("", Engine::Wasm))?;
    for f in PAGE_FILES.iter().filter(|f| f.name != "sw.js") {
        write(f.name, f.text)?;
    }
    // The service worker last: it lists every file written, each with its hash.
    let sw = PAGE_FILES
        .iter()
        .find(|f| f.name == "sw.js")
        .ok_or("the page has no service worker")?;
    write("sw.js", &with_manifest(sw.text, &fresh)?)?;
    // GitHub Pages serves the files as they are (no Jekyll).
    write(".nojekyll", "")?;
    let _ = std::fs::remove_dir_all(dir);
    std::fs::rename(&fresh, dir)
        .map_err(|e| format!("cannot move the site into {}: {e}", dir.display()))?;
    let bytes = folder_bytes(dir);
    println!(
        "site written to {} ({:.1} MB): serve it with `python3 -m http.server -d {}`",
        dir.display(),
        bytes as f64 / 1e6,
        dir.display()
    );
    Ok(())
}

/// The service worker's text `sw` with the list of the site's files in `dir` (all but itself and
/// `.nojekyll`), each with its SHA-256, and the version they make together, in place of its
/// `const MANIFEST = null;`.
fn with_manifest(sw: &str, dir: &Path) -> Result<String, String> {
    use sha2::{Digest, Sha256};
    let mut names = Vec::new();
    list_files(dir, dir, &mut names)?;
    names.sort();
    let mut files = Vec::new();
    let mut all = Sha256::new();
    for name in names
        .iter()
        .filter(|n| *n != "sw.js" && !n.starts_with('.'))
    {
        let bytes =
            std::fs::read(dir.join(name)).map_err(|e| format!("cannot read {name}: {e}"))?;
        let hash = hex(&Sha256::digest(&bytes));
        all.update(format!("{name} {hash}\n"));
        files.push(format!("{name:?}: {hash:?}"));
    }
    let version = hex(&all.finalize())[..16].to_string();
    let manifest = format!(
        "const MANIFEST = {{ version: {version:?}, files: {{ {} }} }};",
        files.join(", ")
    );
    let line = sw
        .lines()
        .find(|l| l.starts_with("const MANIFEST = null;"))
        .ok_or("sw.js has no `const MANIFEST = null;` line to fill in")?;
    Ok(sw.replacen(line, &manifest, 1))
}

/// Lowercase hexadecimal digits of `bytes`.
fn hex(bytes: &[u8]) -> String {
    bytes.iter().map(|b| format!("{b:02x}")).collect()
}

/// The files under `dir`, as paths relative to `root` with `/` between folders.
fn list_files(root: &Path, dir: &Path, out: &mut Vec<String>) -> Result<(), String> {
    let entries =
        std::fs::read_dir(dir).map_err(|e| format!("cannot list {}: {e}", dir.display()))?;
    for entry in entries.flatten() {
        let path = entry.path();
        if path.is_dir() {
            list_files(root, &path, out)?;
        } else if let Ok(rel) = path.strip_prefix(root) {
            let parts: Vec<String> = rel
                .components()
                .map(|c| c.as_os_str().to_string_lossy().into_owned())
                .collect();
            out.push(parts.join("/"));
        }
    }
    Ok(())
}

/// The workspace's root (this crate's parent).
fn workspace_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("xtask lies in the workspace")
        .to_path_buf()
}

/// Runs `command`, an error naming it if it fails.
fn run(command: &mut Command) -> Result<(), String> {
    let shown = format!("{command:?}");
    let status = command
        .status()
        .map_err(|e| format!("cannot run {shown}: {e}"))?;
    if status.success() {
        Ok(())
    } else {
        Err(format!("{shown} failed ({status})"))
    }
}

/// Bytes of every file under `dir`.
fn folder_bytes(dir: &Path) -> u64 {
    std::fs::read_dir(dir)
        .into_iter()
        .flatten()
        .flatten()
        .map(|e| match e.file_type() {
            Ok(t) if t.is_dir() => folder_bytes(&e.path()),
            _ => e.metadata().map_or(0, |m| m.len()),
        })
        .sum()
}
