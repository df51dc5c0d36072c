//! Descartes' construction as a figure: the angle from the antisolar point of light leaving a
//! drop after one and after two reflections inside it, against the impact parameter, one curve
//! per wavelength in its own colour, each bow (where the curve turns) marked with its angle.

use std::path::Path;

use bentstraw_optics::rainbow::DeviationCurve;
use bentstraw_optics::shading::linear_to_srgb;
use bentstraw_optics::spectrum::{cie_1931, xyz_to_linear_srgb};
use plotters::coord::Shift;
use plotters::prelude::*;

use crate::error::Result;
use crate::files;
use crate::plot::{figure_bytes, font, FigureFormat, Heading, FIGURE_WIDTH, TEXT};
use crate::words::{self, Lang};

/// The chart's size (pixels, before its heading).
const CHART: (u32, u32) = (FIGURE_WIDTH, 900);

/// A wavelength's colour as the eye sees it, made darker where it is pale so that it shows on
/// white paper (sRGB bytes).
fn spectral_rgb(nm: f64) -> RGBColor {
    let rgb = xyz_to_linear_srgb(cie_1931(nm)).map(|c| c.max(0.0));
    let top = rgb.iter().cloned().fold(1e-9, f64::max);
    let [r, g, b] = rgb.map(|c| (linear_to_srgb(c / top) * 200.0) as u8);
    RGBColor(r, g, b)
}

/// Plots `curves` (the first bow's and the second's, any wavelengths) into `path` (PNG, SVG or
/// PDF by its extension).
pub fn write_rainbow_plot(
    path: &Path,
    curves: &[DeviationCurve],
    title: &str,
    lang: Lang,
) -> Result {
    let heading = Heading::new(title, "");
    let size = (CHART.0, CHART.1 + heading.height() as u32);
    let bytes = figure_bytes(
        path,
        FigureFormat::of(path)?,
        size,
        |root| draw(root, curves, &heading, lang),
        |root| draw(root, curves, &heading, lang),
    )?;
    files::write_bytes(path, &bytes)
}

fn draw<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    curves: &[DeviationCurve],
    heading: &Heading,
    lang: Lang,
) -> std::result::Result<(), String> {
    let e = |x: DrawingAreaErrorKind<DB::ErrorType>| x.to_string();
    root.fill(&WHITE).map_err(e)?;
    heading.draw(root).map_err(e)?;
    let area = root.margin(heading.height() as u32, 0, 0, 0);
    let mut chart = ChartBuilder::on(&area)
        .margin(20)
        .margin_right(60)
        .x_label_area_size(100)
        .y_label_area_size(130)
        .build_cartesian_2d(0.0..1.0, 0.0..180.0)
        .map_err(e)?;
    chart
        .configure_mesh()
        .x_desc(lang.of(words::RAINBOW_X_AXIS))
        .y_desc(lang.of(words::RAINBOW_Y_AXIS))
        .axis_desc_style(font(TEXT))
        .label_style(font(TEXT))
        .x_labels(6)
        .y_labels(7)
        .max_light_lines(1)
        .light_line_style(RGBColor(235, 235, 235))
        .bold_line_style(RGBColor(200, 200, 200))
        .x_label_formatter(&|v| format!("{v:.1}"))
        .y_label_formatter(&|v| format!("{v:.0}°"))
        .draw()
        .map_err(e)?;
    for c in curves {
        let colour = spectral_rgb(c.nm);
        chart
            .draw_series(LineSeries::new(
                c.points.iter().map(|p| (p[0], p[1])),
                colour.stroke_width(3),
            ))
            .map_err(e)?;
        // The bow: a dot where the curve turns, and its angle beside it.
        chart
            .draw_series(std::iter::once(Circle::new(
                (c.bow[0], c.bow[1]),
                7,
                colour.filled(),
            )))
            .map_err(e)?;
    }
    // The angles of each bow's two ends of the spectrum, written once per bow.
    for reflections in [1, 2] {
        let of: Vec<&DeviationCurve> = curves
            .iter()
            .filter(|c| c.reflections == reflections)
            .collect();
        let (Some(first), Some(last)) = (of.first(), of.last()) else {
            continue;
        };
        let label = lang.fill(
            if reflections == 1 {
                words::RAINBOW_FIRST_LABEL
            } else {
                words::RAINBOW_SECOND_LABEL
            },
            &[
                &format!("{:.1}", first.bow[1]),
                &format!("{:.1}", last.bow[1]),
            ],
        );
        // Between the curves, where the impact parameter is small: one reflection's light is
        // turned less than 40° there, two reflections' more than 90°.
        let y = if reflections == 1 { 60.0 } else { 78.0 };
        let (px, py) = chart.backend_coord(&(0.02, y));
        root.draw(&Text::new(label, (px, py), font(TEXT)))
            .map_err(e)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use bentstraw_optics::rainbow::deviation_curves;
    use bentstraw_optics::scene_file::SceneDescription;

    /// The gallery's drop: both bows drawn, each labelled with its violet and red angles (water's
    /// at 405 and 755 nm: 40.7° and 42.7°, then 53.4° and 49.8°).
    #[test]
    fn the_figure_names_each_bow_with_its_angles() {
        let d = SceneDescription::from_toml(include_str!("../scenes/rainbow.toml")).unwrap();
        let nms = bentstraw_optics::spectrum::white_bands().map(|b| b.nm);
        let curves: Vec<_> = [1, 2]
            .iter()
            .flat_map(|&k| deviation_curves(&d, 0, k, &nms).unwrap())
            .collect();
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("rainbow.svg");
        write_rainbow_plot(&path, &curves, "The rainbow", Lang::En).unwrap();
        let svg = std::fs::read_to_string(&path).unwrap();
        assert!(
            svg.contains("first bow: 40.7° (violet) to 42.7° (red)"),
            "{svg}"
        );
        assert!(svg.contains("second bow: 53.4° (violet) to 49.8° (red)"));
    }
}
