//! `picture-parts`: where a picture's time goes, on one thread, in the program itself (no process
//! to start, no file to write, so that figures vary far less from run to run than whole
//! commands). For each reference view at 1024x768, as `render` frames it, in Fresnel and course
//! mode, the median of [`REPEAT`] runs (after one to warm up) of:
//! - `traced`: the pixel centres traced by the packet tracer, their branches' ends made but not
//!   shaded;
//! - `centres`: the picture of one sample per pixel (the centres traced and shaded, the outline,
//!   the bytes);
//! - `picture`: the picture as `render` makes it (3x3 samples at the edges, adaptive).
//!
//! and the differences: shading the centres (`centres − traced`) and the edges (`picture −
//! centres`: finding them, the closed-form backdrop, their samples traced and shaded). One line
//! per case: `MODE VIEW TRACED_MS CENTRES_MS PICTURE_MS SHADING_MS EDGES_MS BRANCH_ENDS`.
//!
//! Build it on its own (`cargo build --release -p bentstraw-bench --bin picture-parts`): built in
//! one command with the program, the library's features are unified, and its pictures then take
//! every core.
//!
//! Built for WebAssembly (`wasm32-wasip1` with SIMD, as `bench/wasm_native.mjs` builds
//! `picture-speed`) it gives the same parts for the page's engine.

use std::hint::black_box;

use bentstraw_bench::median_seconds;
use bentstraw_optics::camera::{framing_fov, framing_target, Camera};
use bentstraw_optics::packet::{FresnelWave, PacketTracer};
use bentstraw_optics::scene::{REFERENCES, WATER_INDEX};
use bentstraw_optics::shading::{
    shaded_picture_into, Backdrop, RgbPicture, ShadingBuffers, ShadingMode, ShadingOptions,
};
use bentstraw_optics::view::{DEFAULT_PRUNE, DEFAULT_SAMPLES};
use bentstraw_optics::world::World;

/// Timed runs per case (the median is printed).
const REPEAT: usize = 15;
/// `render`'s picture size.
const SIZE: (u32, u32) = (1024, 768);

fn main() {
    let (w, h) = SIZE;
    for (mode_name, mode) in [
        (
            "fresnel",
            ShadingMode::Fresnel {
                prune_below: DEFAULT_PRUNE,
            },
        ),
        ("course", ShadingMode::Course),
    ] {
        for r in REFERENCES.iter() {
            let world = World::assignment(&r.scene(WATER_INDEX));
            let target = framing_target(r.observer);
            let fov = framing_fov(r.observer, target, w as f64 / h as f64);
            let camera = Camera::new(r.observer, target, w, h, fov);
            let tracer = PacketTracer::new(&world);
            let (split, prune) = match mode {
                ShadingMode::Fresnel { prune_below } => (true, prune_below),
                ShadingMode::Course => (false, 0.0),
            };
            let mut wave = FresnelWave::default();
            let mut ends = 0usize;
            let traced = median_ms(|| {
                ends = 0;
                for row in 0..h {
                    let on_end = &mut |_, end| {
                        ends += 1;
                        black_box(end);
                    };
                    tracer.branch_ends_row(&camera, row, split, prune, &mut wave, on_end);
                }
            });
            let options = |samples| ShadingOptions {
                mode,
                backdrop: Backdrop::Checker,
                samples,
                adaptive: true,
                outline: true,
                white: false,
            };
            let mut buffers = ShadingBuffers::default();
            let mut picture = RgbPicture::default();
            let mut draw = |samples| {
                median_ms(|| {
                    let options = options(samples);
                    shaded_picture_into(&world, &camera, &options, &mut buffers, &mut picture);
                    black_box(&picture);
                })
            };
            let centres = draw(1);
            let whole = draw(DEFAULT_SAMPLES);
            println!(
                "{mode_name} {} {traced:.1} {centres:.1} {whole:.1} {:.1} {:.1} {ends}",
                r.number,
                centres - traced,
                whole - centres
            );
        }
    }
}

/// Median time (ms) of [`REPEAT`] runs of `work`, after one.
fn median_ms(work: impl FnMut()) -> f64 {
    median_seconds(REPEAT, work) * 1e3
}
