//! The classic figure (SPEC §5) as a PNG: the image points in their section colours, the water as a
//! wireframe, the observer, equal axes, three views side by side.

use std::path::Path;

use bentstraw_optics::image::ImagePoint;
use bentstraw_optics::scene::Scene;
use bentstraw_optics::Vec3;

use crate::error::{fail, CliResult};

/// Draws the classic three-view figure of `points` seen from `observer` into the PNG at `path`.
pub fn write_cloud_figure(
    path: &Path,
    scene: &Scene,
    observer: Vec3,
    points: &[ImagePoint],
    title: &str,
) -> CliResult {
    let _ = (path, scene, observer, points, title);
    fail("plots are not implemented yet")
}
