//! `picture-speed`: millions of rays per second of the picture tracer on one thread, on
//! `bentstraw bench`'s four zoomed views (1024x768, field of view 50°, course and Fresnel with the
//! default prune), the median of 20 pictures after one to warm up, for each compilation of the
//! packet code this processor runs (AVX-512, AVX2, the baseline).
//!
//! Built for WebAssembly (`wasm32-wasip1` with SIMD, run by Node.js, whose engine is Chromium's),
//! it times the page's engine on the same work: `bench/wasm_native.mjs` runs both and prints the
//! ratio. One line per case: `INSTRUCTIONS MODE VIEW MRAYS_PER_S`.

use bentstraw_bench::median_seconds;
use bentstraw_optics::camera::Camera;
use bentstraw_optics::packet::{FresnelWave, Instructions, PacketTracer};
use bentstraw_optics::scene::{REFERENCES, SECTION_COUNT, WATER_INDEX};
use bentstraw_optics::world::World;

/// Timed pictures per case (the median is printed).
const REPEAT: usize = 20;
/// Fresnel branches lighter than this are abandoned (`render`'s and `bench`'s default).
const PRUNE: f64 = bentstraw_optics::view::DEFAULT_PRUNE;
/// Picture size and vertical field of view (`bench`'s).
const SIZE: (u32, u32) = (1024, 768);
const FOV_DEG: f64 = 50.0;

fn main() {
    let (w, h) = SIZE;
    let compilations = [
        (Instructions::Avx512, "avx512"),
        (Instructions::Avx2, "avx2"),
        (Instructions::Baseline, "baseline"),
    ];
    for r in REFERENCES.iter() {
        let world = World::assignment(&r.scene(WATER_INDEX));
        let camera = Camera::new(r.observer, r.zoom_target(), w, h, FOV_DEG.to_radians());
        let mut codes = vec![0u8; (w * h) as usize];
        let mut weights = vec![[0.0f64; SECTION_COUNT]; (w * h) as usize];
        let mut wave = FresnelWave::default();
        let rays = f64::from(w * h) / 1e6;
        for (instructions, name) in compilations {
            let Some(tracer) = PacketTracer::new(&world).with_instructions(instructions) else {
                continue;
            };
            let course = median_seconds(REPEAT, || {
                for (row, codes) in codes.chunks_mut(w as usize).enumerate() {
                    tracer.course_row(&camera, row as u32, codes);
                }
            });
            let fresnel = median_seconds(REPEAT, || {
                for (row, weights) in weights.chunks_mut(w as usize).enumerate() {
                    tracer.fresnel_row(&camera, row as u32, PRUNE, &mut wave, weights);
                }
            });
            println!("{name} course {} {:.1}", r.number, rays / course);
            println!("{name} fresnel {} {:.1}", r.number, rays / fresnel);
            std::hint::black_box((&codes, &weights));
        }
    }
}
