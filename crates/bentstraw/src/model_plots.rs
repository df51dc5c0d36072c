//! Figures comparing the apparent-position models (issue 4): the course's, the eye's and the stereo
//! image clouds side by side, and the gap between the course's points and another model's along the
//! straw's height.

use std::path::Path;

use bentstraw_optics::image::ImagePoint;
use bentstraw_optics::scene::Scene;
use bentstraw_optics::Vec3;

use crate::error::{fail, CliResult};

/// One model's image cloud, for the comparison figure.
#[derive(Clone, Copy, Debug)]
pub struct ModelCloud<'a> {
    /// The model's name, e.g. "course (SPEC §4)".
    pub name: &'a str,
    /// Its placed points (position = where this model puts the image).
    pub points: &'a [ImagePoint],
}

/// One curve of the gap plot: for each point, `(z of the straw point Q (m), gap (m), colour code)`.
#[derive(Clone, Copy, Debug)]
pub struct GapSeries<'a> {
    /// The model compared with the course's, e.g. "eye".
    pub name: &'a str,
    /// The samples.
    pub samples: &'a [(f64, f64, u8)],
}

/// Draws the models' clouds side by side, same viewpoint and scale, into the PNG at `path`.
pub fn write_model_comparison(
    path: &Path,
    scene: &Scene,
    observer: Vec3,
    models: &[ModelCloud],
    title: &str,
) -> CliResult {
    let _ = (path, scene, observer, models, title);
    fail("model comparison figure not implemented yet")
}

/// Plots the gap between the course's image points and each series' model against the height of the
/// straw point, into the PNG at `path`.
pub fn write_gap_plot(path: &Path, series: &[GapSeries], title: &str) -> CliResult {
    let _ = (path, series, title);
    fail("gap plot not implemented yet")
}
