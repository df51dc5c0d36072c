//! Cost of judging a solution (`check`, and each case `grade` grades) on reference simulation 1:
//! 100 000 distinct points of the true image against 100 000 and 2 000 000 copies of one point,
//! the file a careless or hostile hand-in may be. The neighbour search on the map makes the
//! coinciding points cost about what distinct ones cost (a scan of each cell took hours).
//!
//! Run: `cargo bench -p bentstraw-bench --bench check`

use std::hint::black_box;

use bentstraw_optics::check::{
    check_solution, ClaimedPoint, DEFAULT_MIN_COVERAGE, DEFAULT_TOLERANCE,
};
use bentstraw_optics::sampling::sample_image;
use bentstraw_optics::scene::{REFERENCES, WATER_INDEX};
use bentstraw_optics::world::World;
use criterion::{criterion_group, criterion_main, Criterion};

fn judging(c: &mut Criterion) {
    let r = REFERENCES[0];
    let scene = World::assignment(&r.scene(WATER_INDEX));
    let cloud = sample_image(&scene, r.observer, 100_000, &|_| {});
    let claimed = |p: &bentstraw_optics::image::ImagePoint| ClaimedPoint {
        position: p.position,
        color: p.color,
    };
    let distinct: Vec<ClaimedPoint> = cloud.points.iter().take(100_000).map(claimed).collect();
    let one = claimed(&cloud.points[cloud.points.len() / 2]);
    let mut group = c.benchmark_group("check");
    group.sample_size(10);
    for (name, points) in [
        ("100 000 distinct points", distinct),
        ("100 000 coinciding points", vec![one; 100_000]),
        ("2 000 000 coinciding points", vec![one; 2_000_000]),
    ] {
        group.bench_function(name, |b| {
            b.iter(|| {
                black_box(check_solution(
                    &scene,
                    r.observer,
                    black_box(&points),
                    DEFAULT_TOLERANCE,
                    DEFAULT_MIN_COVERAGE,
                ))
            })
        });
    }
    group.finish();
}

criterion_group!(benches, judging);
criterion_main!(benches);
