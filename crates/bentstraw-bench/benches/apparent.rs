//! Cost of the apparent-position models (eye and stereo) per image point, on reference
//! simulation 1.
//!
//! Run: `cargo bench -p bentstraw-bench --bench apparent`

use std::hint::black_box;

use bentstraw_optics::apparent::StereoEyes;
use bentstraw_optics::sampling::sample_image;
use bentstraw_optics::scene::{REFERENCES, WATER_INDEX};
use bentstraw_optics::world::World;
use criterion::{criterion_group, criterion_main, Criterion};

fn models(c: &mut Criterion) {
    let r = REFERENCES[0];
    let scene = World::assignment(&r.scene(WATER_INDEX));
    let cloud = sample_image(&scene, r.observer, 1000, &|_| {});
    let points: Vec<_> = cloud.points.iter().step_by(10).copied().collect();
    let eyes = StereoEyes::around(r.observer);
    c.bench_function("eye model, 100 points", |b| {
        b.iter(|| {
            for p in &points {
                black_box(scene.apparent_point(r.observer, black_box(p)));
            }
        })
    });
    c.bench_function("stereo model, 100 points", |b| {
        b.iter(|| {
            for p in &points {
                black_box(scene.stereo_point(&eyes, r.observer, black_box(p)));
            }
        })
    });
}

criterion_group!(benches, models);
criterion_main!(benches);
