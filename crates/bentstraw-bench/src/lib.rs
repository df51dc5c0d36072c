//! Criterion benchmarks of bentstraw-optics: `cargo bench -p bentstraw-bench` (see `benches/`).
