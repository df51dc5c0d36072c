//! Criterion benchmarks of bentstraw-optics: `cargo bench -p bentstraw-bench` (see `benches/`);
//! and what the benchmark programs share.

use std::time::Instant;

/// Median time (s) of `repeat` runs of `work`, after one to warm up.
pub fn median_seconds(repeat: usize, mut work: impl FnMut()) -> f64 {
    work();
    let mut t: Vec<f64> = (0..repeat)
        .map(|_| {
            let start = Instant::now();
            work();
            start.elapsed().as_secs_f64()
        })
        .collect();
    t.sort_by(f64::total_cmp);
    t[repeat / 2]
}
