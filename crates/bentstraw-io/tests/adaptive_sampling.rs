//! Adaptive sampling against sampling every pixel. A picture traces every pixel's centre first,
//! then its 3x3 samples only where a pixel's centre and a neighbour's differ (an edge); a pixel
//! whose neighbourhood is flat keeps its centre's colour. That differs from the samples taken at
//! every pixel only where something finer than a pixel lies between the centres unseen (a thin
//! line, the tip of a total-reflection boundary), and where a gentle gradient's mean over the
//! pixel is not its centre. Measured on the four reference views and every gallery scene
//! (Fresnel mode, checkerboard, 320x240), per pixel on the largest of the three channels: a mean
//! of 0.02 levels (of 255) over all the views, at most 0.08 in one; 115 pixels of 2.9 million
//! more than 32 levels off (at most 28 in one view: a prism's edges); the largest difference
//! 236 levels, at the sun's glint in the rainbow's drop, smaller than a pixel, which a centre
//! may miss (elsewhere at most 44).

use bentstraw_io::camera::{scene_camera, CameraSpec};
use bentstraw_io::gallery::GALLERY;
use bentstraw_io::scene_input::gallery_setup;
use bentstraw_optics::scene::{DEFAULT_MAX_EVENTS, REFERENCES, WATER_INDEX};
use bentstraw_optics::setup::Setup;
use bentstraw_optics::shading::shaded_picture;
use bentstraw_optics::view::PictureSpec;

/// How the adaptive picture of `setup` differs from the fully sampled one: the largest
/// difference (levels of 255), the mean over all pixels, and the pixels more than 32 levels off.
fn compare(setup: &Setup) -> (u8, f64, usize, usize) {
    let size = CameraSpec {
        size: Some((320, 240)),
        ..CameraSpec::default()
    };
    let camera = scene_camera(setup, &size).unwrap();
    let adaptive = PictureSpec::default();
    let full = PictureSpec {
        adaptive: false,
        ..adaptive
    };
    let a = shaded_picture(&setup.world, &camera, &adaptive.shading());
    let f = shaded_picture(&setup.world, &camera, &full.shading());
    let diffs: Vec<u8> = a
        .pixels
        .chunks_exact(3)
        .zip(f.pixels.chunks_exact(3))
        .map(|(p, q)| (0..3).map(|c| p[c].abs_diff(q[c])).max().unwrap())
        .collect();
    let largest = diffs.iter().copied().max().unwrap();
    let mean = diffs.iter().map(|&d| d as f64).sum::<f64>() / diffs.len() as f64;
    let far = diffs.iter().filter(|&&d| d > 32).count();
    (largest, mean, far, diffs.len())
}

#[test]
fn adaptive_sampling_keeps_the_fully_sampled_picture() {
    let mut views: Vec<(String, Setup)> = REFERENCES
        .iter()
        .map(|r| {
            let setup = Setup::assignment(r.scene(WATER_INDEX), r.observer);
            (format!("reference {}", r.number), setup)
        })
        .collect();
    for (name, text) in GALLERY {
        let setup = gallery_setup(name, text, DEFAULT_MAX_EVENTS).unwrap();
        views.push((name.to_string(), setup));
    }
    let (mut worst, mut total, mut far_total, mut pixels) = (0u8, 0.0, 0, 0);
    for (name, setup) in &views {
        let (largest, mean, far, n) = compare(setup);
        eprintln!("{name}: largest {largest}, mean {mean:.3}, {far} pixels over 32 levels");
        // Each view: a mean under a fifth of a level, at most one pixel in a thousand far off.
        assert!(mean < 0.2, "{name}: mean {mean:.3} levels");
        assert!(
            far * 1000 <= n,
            "{name}: {far} pixels more than 32 levels off"
        );
        worst = worst.max(largest);
        total += mean * n as f64;
        far_total += far;
        pixels += n;
    }
    let mean = total / pixels as f64;
    eprintln!(
        "all {} views: largest {worst}, mean {mean:.3}, {far_total} of {pixels} pixels over 32 levels",
        views.len()
    );
    assert!(mean < 0.05, "mean {mean:.3} levels over every view");
    assert!(
        far_total * 10_000 <= pixels,
        "{far_total} pixels more than 32 levels off"
    );
}
