//! What the figures' tests share: image points to draw, PNGs decoded, and the classic figure's
//! panels and pixels.

use std::path::Path;

use bentstraw_optics::image::ImagePoint;
use bentstraw_optics::setup::Setup;
use bentstraw_optics::Vec3;

use super::axis_box::axis_box;
use super::cloud::{cloud_heading, layout, render_cloud_figure};
use super::panel::Panel;
use super::views::figure_views;

/// A point of colour `color` at `position` (the other fields do not matter for drawing).
pub(crate) fn point(position: Vec3, color: u8) -> ImagePoint {
    ImagePoint {
        position,
        color,
        direction: Vec3::X,
        path_length: 0.1,
        straw_point: position,
        events: 0,
        band: None,
    }
}

pub(crate) fn decode(png: &[u8]) -> image::RgbImage {
    image::load_from_memory_with_format(png, image::ImageFormat::Png)
        .expect("a valid PNG")
        .to_rgb8()
}

/// The panels of the classic figure of `points`, as drawn under its heading.
pub(super) fn panels_of(scene: &Setup, observer: Vec3, points: &[ImagePoint]) -> Vec<Panel> {
    let heading = cloud_heading(observer, points.len(), "t");
    layout(
        &axis_box(scene, observer, points),
        &figure_views(observer),
        heading.height(),
    )
}

/// Whether some pixel of the panels (not the heading or the legend) has exactly colour `c`.
pub(super) fn panels_have(img: &image::RgbImage, panels: &[Panel], c: [u8; 3]) -> bool {
    panels.iter().any(|p| {
        (p.top..p.top + p.height)
            .any(|y| (p.left..p.left + p.width).any(|x| img.get_pixel(x as u32, y as u32).0 == c))
    })
}

pub(super) fn png_of(scene: &Setup, observer: Vec3, points: &[ImagePoint]) -> image::RgbImage {
    decode(&render_cloud_figure(Path::new("f.png"), scene, observer, points, "t").unwrap())
}
