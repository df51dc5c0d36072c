//! The rule for tests that need something of the machine (AVX2 for the packet tracer's SIMD
//! builds): under CI (the `CI` variable set, as CI services do) its absence fails the test; on a
//! developer's machine the test is skipped with a note.

/// Whether this is a CI run: `CI` set to anything but empty, `0` or `false`.
pub fn in_ci() -> bool {
    std::env::var("CI").is_ok_and(|v| !matches!(v.trim(), "" | "0" | "false"))
}

/// Something a test needs is not there (`what`; `remedy` says how to get it): fails the test under
/// CI, else notes on stderr that the test skips that check. The caller then returns.
pub fn unavailable(what: &str, remedy: &str) {
    if in_ci() {
        panic!("{what}: this test needs it and CI must not skip it ({remedy})");
    }
    eprintln!("{what}: skipping this check ({remedy}; under CI=true this fails)");
}
