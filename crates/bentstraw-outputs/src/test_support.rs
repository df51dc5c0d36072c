//! The rule for tests that need a tool from outside Rust (node, Chromium, poppler's pdftoppm and
//! pdftotext): under CI (the `CI` variable set, as CI services do) a missing tool fails the test,
//! since `.ci/run` installs them before testing; on a developer's machine the test is skipped with
//! a note. The unit tests use this module; the integration tests include the same file.

use std::path::PathBuf;

/// Whether this is a CI run: `CI` set to anything but empty, `0` or `false`.
pub fn in_ci() -> bool {
    std::env::var("CI").is_ok_and(|v| !matches!(v.trim(), "" | "0" | "false"))
}

/// How to install `tool` on Debian (as `.ci/run` does).
fn install_hint(tool: &str) -> &'static str {
    match tool {
        "pdftoppm" | "pdftotext" => "apt-get install poppler-utils",
        "chromium" => "apt-get install chromium",
        "node" => "apt-get install nodejs (Node 20 or later)",
        _ => "install it",
    }
}

/// `tool`'s path on `PATH`, if it is there. Under CI a missing tool fails the test (naming it and
/// how to install it); elsewhere the caller skips, after a note on stderr.
pub fn require_tool(tool: &str) -> Option<PathBuf> {
    let found = std::env::var_os("PATH").and_then(|paths| {
        std::env::split_paths(&paths)
            .map(|dir| dir.join(tool))
            .find(|p| p.is_file())
    });
    if found.is_none() {
        unavailable(&format!("`{tool}` not found on PATH"), install_hint(tool));
    }
    found
}

/// Something a test needs is not there (`what`; `remedy` says how to get it): fails the test under
/// CI, else notes on stderr that the test skips that check. The caller then returns.
pub fn unavailable(what: &str, remedy: &str) {
    if in_ci() {
        panic!("{what}: this test needs it and CI must not skip it ({remedy})");
    }
    eprintln!("{what}: skipping this check ({remedy}; under CI=true this fails)");
}
