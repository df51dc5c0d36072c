//! A self-contained, offline, rotatable and zoomable 3D view of the image points (one HTML file).

use std::path::Path;

use bentstraw_optics::image::ImagePoint;
use bentstraw_optics::scene::Scene;
use bentstraw_optics::Vec3;

use crate::error::{fail, CliResult};

/// Writes an interactive 3D view of `points`, the water wireframe and the observer to `path`.
pub fn write_cloud_viewer(
    path: &Path,
    scene: &Scene,
    observer: Vec3,
    points: &[ImagePoint],
    title: &str,
) -> CliResult {
    let _ = (path, scene, observer, points, title);
    fail("the 3D view is not implemented yet")
}
