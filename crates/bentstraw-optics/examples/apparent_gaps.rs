//! How far the course's image points (`O + L·u0`) are from the eye model's and the stereo model's
//! apparent points, for the four reference simulations, 20000 points each.
//!
//! Run: `cargo run --release -p bentstraw-optics --example apparent_gaps`

use std::time::Instant;

use bentstraw_optics::apparent::{eye_model_points, stereo_points, Focus};
use bentstraw_optics::sampling::sample_image;
use bentstraw_optics::scene::{REFERENCES, WATER_INDEX};
use bentstraw_optics::world::World;

/// The median of `values` (sorted here); NaN if empty.
fn median(values: &mut [f64]) -> f64 {
    if values.is_empty() {
        return f64::NAN;
    }
    values.sort_by(f64::total_cmp);
    let n = values.len();
    if n % 2 == 1 {
        values[n / 2]
    } else {
        0.5 * (values[n / 2 - 1] + values[n / 2])
    }
}

fn main() {
    println!(
        "ref  points  eye: max gap (m)  median gap (m)  undefined  [unresolved behind_eye at_infinity foci]  \
         stereo: max gap (m)  median gap (m)  skipped  no crossing  max miss (m)  time (s)"
    );
    for r in REFERENCES {
        let scene = r.scene(WATER_INDEX);
        let cloud = sample_image(&World::assignment(&scene), r.observer, 20_000, &|_| {});
        let start = Instant::now();
        let eye = eye_model_points(&World::assignment(&scene), r.observer, &cloud.points);
        let stereo = stereo_points(&World::assignment(&scene), r.observer, &cloud.points);
        let seconds = start.elapsed().as_secs_f64();
        let mut gaps: Vec<f64> = eye.iter().filter_map(|p| p.gap_to_course()).collect();
        let undefined = eye.len() - gaps.len();
        let count = |kind: fn(&Focus) -> bool| {
            eye.iter()
                .map(|p| kind(&p.s_h) as usize + kind(&p.s_v) as usize)
                .sum::<usize>()
        };
        let unresolved = count(|f| matches!(f, Focus::Unresolved));
        let behind = count(|f| matches!(f, Focus::BehindEye(_)));
        let infinity = count(|f| matches!(f, Focus::AtInfinity));
        let max_gap = gaps.iter().copied().fold(0.0, f64::max);
        let median_gap = median(&mut gaps);
        // `median` sorted the gaps: upper quantiles, and the worst point's story.
        let quantile = |q: f64| gaps[((q * gaps.len() as f64) as usize).min(gaps.len() - 1)];
        let worst = eye
            .iter()
            .filter(|p| p.gap_to_course() == Some(max_gap))
            .map(|p| {
                format!(
                    "{} events, colour {}, path {:.4} m, s_h {:?}, s_v {:?}",
                    p.image.events, p.image.color, p.image.path_length, p.s_h, p.s_v
                )
            })
            .next()
            .unwrap_or_default();
        let notes = format!(
            "     eye gap quantiles: 90% {:.6} m, 99% {:.6} m; largest gap: {worst}",
            quantile(0.9),
            quantile(0.99)
        );
        let mut stereo_gaps: Vec<f64> = stereo
            .points
            .iter()
            .filter_map(|p| p.gap_to_course())
            .collect();
        let max_stereo = stereo_gaps.iter().copied().fold(0.0, f64::max);
        let median_stereo = median(&mut stereo_gaps);
        let no_crossing = stereo
            .points
            .iter()
            .filter(|p| p.position.is_none())
            .count();
        let max_miss = stereo
            .points
            .iter()
            .map(|p| p.miss_distance)
            .fold(0.0, f64::max);
        println!(
            "{:>3}  {:>6}  {:>16.6}  {:>14.6}  {:>8.4}%  [{} {} {}]  {:>19.6}  {:>14.6}  {:>7}  {:>11}  {:>12.6}  {:>8.2}",
            r.number,
            eye.len(),
            max_gap,
            median_gap,
            100.0 * undefined as f64 / eye.len().max(1) as f64,
            unresolved,
            behind,
            infinity,
            max_stereo,
            median_stereo,
            stereo.skipped,
            no_crossing,
            max_miss,
            seconds
        );
        println!("{notes}");
    }
}
