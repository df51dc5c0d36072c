//! Criterion benchmarks of the hot functions: intersections, one ray's trace, one picture row.

use std::hint::black_box;

use bentstraw_optics::camera::Camera;
use bentstraw_optics::geometry::Ray;
use bentstraw_optics::picture::{
    course_picture, course_picture_exact, fresnel_picture, fresnel_picture_exact,
};
use bentstraw_optics::scene::REFERENCES;
use bentstraw_optics::world::{World, FRESNEL_SEGMENTS_PER_RAY};
use bentstraw_optics::Vec3;
use criterion::{criterion_group, criterion_main, BatchSize, Criterion, Throughput};

/// Reference simulation 2's scene and its benchmark camera (zoomed where the straw enters the water).
fn view(w: u32, h: u32) -> (World, Camera) {
    let r = REFERENCES[1];
    let scene = World::assignment(&r.scene(1.333));
    let target = Vec3::new(r.straw.0, r.straw.1, r.water_height);
    (
        scene,
        Camera::new(r.observer, target, w, h, 50f64.to_radians()),
    )
}

/// One row of rays through the middle of the benchmark view (a mix of straw, water and sky).
fn middle_row(camera: &Camera) -> Vec<Ray> {
    (0..camera.width)
        .map(|j| camera.pixel_ray(camera.height / 2, j))
        .collect()
}

fn intersections(c: &mut Criterion) {
    let (world, camera) = view(256, 192);
    let rays = middle_row(&camera);
    let mut g = c.benchmark_group("intersection");
    g.throughput(Throughput::Elements(rays.len() as u64));
    g.bench_function("World::nearest", |b| {
        b.iter(|| {
            rays.iter()
                .filter_map(|r| world.nearest(black_box(r), None))
                .count()
        })
    });
    g.finish();
}

fn one_ray(c: &mut Criterion) {
    let (world, camera) = view(256, 192);
    let rays = middle_row(&camera);
    let mut g = c.benchmark_group("trace");
    g.throughput(Throughput::Elements(rays.len() as u64));
    g.bench_function("course World::trace", |b| {
        b.iter(|| {
            rays.iter()
                .map(|r| world.trace(black_box(*r)).color() as u32)
                .sum::<u32>()
        })
    });
    g.bench_function("fresnel World::fresnel_steps", |b| {
        b.iter(|| {
            rays.iter()
                .map(|r| {
                    world.fresnel_steps::<false>(
                        black_box(*r),
                        1e-4,
                        FRESNEL_SEGMENTS_PER_RAY,
                        |_| {},
                    )[0]
                })
                .sum::<f64>()
        })
    });
    g.finish();
}

fn picture_row(c: &mut Criterion) {
    // A one-row picture: the same view's middle row, through the picture code path (1 thread).
    let (scene, camera) = view(1024, 768);
    let row_camera = {
        let mut cam = camera;
        cam.height = 1;
        // Keep the aspect of the full view: the row's rays are the full view's middle row.
        cam.tan_half_fov = camera.tan_half_fov / 768.0;
        cam
    };
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    let mut g = c.benchmark_group("picture");
    g.throughput(Throughput::Elements(1024));
    g.bench_function("course row 1024 px", |b| {
        b.iter_batched(
            || (),
            |_| pool.install(|| course_picture(black_box(&scene), black_box(&row_camera))),
            BatchSize::SmallInput,
        )
    });
    g.bench_function("course row 1024 px, double precision", |b| {
        b.iter(|| pool.install(|| course_picture_exact(black_box(&scene), black_box(&row_camera))))
    });
    g.bench_function("fresnel row 1024 px", |b| {
        b.iter(|| pool.install(|| fresnel_picture(black_box(&scene), black_box(&row_camera), 1e-4)))
    });
    g.bench_function("fresnel row 1024 px, double precision", |b| {
        b.iter(|| {
            pool.install(|| fresnel_picture_exact(black_box(&scene), black_box(&row_camera), 1e-4))
        })
    });
    g.finish();
}

criterion_group!(benches, intersections, one_ray, picture_row);
criterion_main!(benches);
