//! Times `sample_image` for the four reference simulations: `cargo run --release --example
//! sample_points -- 1000000` (the library side of `bentstraw simulate --points N`).

use std::time::Instant;

use bentstraw_optics::sampling::sample_image;
use bentstraw_optics::scene::REFERENCES;
use bentstraw_optics::world::World;

fn main() {
    let n: usize = std::env::args()
        .nth(1)
        .map_or(1_000_000, |s| s.parse().expect("a number of points"));
    for r in REFERENCES {
        let scene = r.scene(1.333);
        let start = Instant::now();
        let cloud = sample_image(&World::assignment(&scene), r.observer, n, &|_| {});
        let seconds = start.elapsed().as_secs_f64();
        // An order-sensitive checksum, to compare runs bit for bit.
        let checksum = cloud.points.iter().enumerate().fold(0u64, |acc, (n, p)| {
            let bits = p.position.x.to_bits()
                ^ p.position.y.to_bits().rotate_left(21)
                ^ p.position.z.to_bits().rotate_left(42)
                ^ u64::from(p.color);
            acc.rotate_left(5) ^ bits.wrapping_mul(n as u64 + 1)
        });
        println!(
            "simulation {}: {} points, {} rays, {:.3} s, checksum {checksum:016x}",
            r.number,
            cloud.points.len(),
            cloud.rays_traced,
            seconds
        );
    }
}
