//! What CI's machine must have for the tests to test everything: a processor with AVX2, or the
//! library's unit test `every_instruction_set_gives_the_same_pixels` (the packet code's AVX2 and
//! AVX-512 builds against its portable one) has nothing to compare and passes without checking.
//! Ignored, so that `cargo test` on another machine says it did not check this; `cargo test --
//! --ignored` (as `.ci/run` runs it) fails without AVX2.

use bentstraw_optics::packet::Instructions;

#[test]
#[ignore = "needs a processor with AVX2 (CI's machine: the packet code's SIMD builds are tested there)"]
fn ci_has_a_simd_build_to_compare() {
    assert_ne!(
        Instructions::detect(),
        Instructions::Baseline,
        "this processor has no AVX2, so the packet code's SIMD builds go untested \
         (run CI on an x86-64 machine with AVX2)"
    );
}
