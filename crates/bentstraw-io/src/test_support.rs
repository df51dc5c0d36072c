//! The rule for tests that need a tool from outside Rust (node, Chromium, poppler's pdftoppm,
//! pdftotext and pdfinfo): such a test is marked `#[ignore = "needs …"]`, naming the tool, so that
//! `cargo test` lists it as not run instead of passing it; `cargo test -- --ignored` runs it (as
//! `.ci/run` does, after installing the tools), and there a missing tool fails it. The unit tests
//! use this module; the integration tests include the same file.

use std::path::PathBuf;

/// How to install `tool` on Debian (as `.ci/run` does).
fn install_hint(tool: &str) -> &'static str {
    match tool {
        "pdftoppm" | "pdftotext" | "pdfinfo" => "apt-get install poppler-utils",
        "chromium" => "apt-get install chromium",
        "node" => "apt-get install nodejs (Node 20 or later)",
        _ => "install it",
    }
}

/// `tool`'s path on `PATH`; a missing tool fails the test, naming it and how to install it.
pub fn require_tool(tool: &str) -> PathBuf {
    let found = std::env::var_os("PATH").and_then(|paths| {
        std::env::split_paths(&paths)
            .map(|dir| dir.join(tool))
            .find(|p| p.is_file())
    });
    found.unwrap_or_else(|| unavailable(&format!("`{tool}` not found on PATH"), install_hint(tool)))
}

/// Something a test needs is not there (`what`; `remedy` says how to get it): fails the test.
pub fn unavailable(what: &str, remedy: &str) -> ! {
    panic!("{what}: this test needs it ({remedy})");
}
