//! The validation figure: as the water's index goes from 1 to 1.333, how far the image points seen
//! through the water lie from the straw's surface (those seen straight through air lie on it
//! whatever the water). With index 1 the water bends nothing, so every image point must lie on
//! the straw (to rounding, ~1e-16 m); as soon as the index grows the image leaves the straw, by
//! millimetres to centimetres. One curve of the largest and one of the median distance per
//! simulation.

use std::path::Path;

use bentstraw_optics::sampling::sample_image;
use bentstraw_optics::scene::{Scene, WATER_INDEX};
use bentstraw_optics::world::World;
use bentstraw_optics::Vec3;
use plotters::coord::Shift;
use plotters::prelude::*;

use crate::error::Result;
use crate::files;
use crate::plot::{figure_bytes, font, FigureFormat, Heading, FIGURE_WIDTH, TEXT};
use crate::words::{self, Lang};
use bentstraw_optics::setup::{SceneValues, Setup};

/// Indices of the water the figure is made for: 8 values from 1 to 1.333.
pub fn indices() -> Vec<f64> {
    indices_to(WATER_INDEX)
}

/// 8 indices evenly from 1 to `top`.
pub fn indices_to(top: f64) -> Vec<f64> {
    (0..8).map(|k| 1.0 + (top - 1.0) * k as f64 / 7.0).collect()
}

/// Image points per index (enough for a stable median and largest distance).
pub const VALIDATION_POINTS: usize = 4000;

/// The distances of one simulation's image points from the straw, for each index.
#[derive(Clone, Debug, PartialEq)]
pub struct ValidationSeries {
    /// Label of the simulation, e.g. "simulation 1".
    pub label: String,
    /// `(index, largest distance, median distance)` (m), in increasing index.
    pub rows: Vec<(f64, f64, f64)>,
}

/// Largest and median distance (m) from `points` to the straw's surface.
pub fn distance_stats(world: &World, points: &[Vec3]) -> (f64, f64) {
    let mut d: Vec<f64> = points
        .iter()
        .map(|p| world.distance_to_objects(*p))
        .collect();
    if d.is_empty() {
        return (f64::NAN, f64::NAN);
    }
    d.sort_by(f64::total_cmp);
    let median = if d.len() % 2 == 1 {
        d[d.len() / 2]
    } else {
        0.5 * (d[d.len() / 2 - 1] + d[d.len() / 2])
    };
    (d[d.len() - 1], median)
}

/// The series of one simulation (`scene` with its own index replaced by each of [`indices`]).
pub fn series(label: &str, scene: &Scene, observer: Vec3) -> ValidationSeries {
    // The points seen straight through air lie on the straw whatever the water: only those whose
    // light crossed the water tell (`row` leaves the others out).
    let rows = indices()
        .into_iter()
        .map(|n| {
            let s = World::assignment(&scene.with_n_water(n).expect("indices are >= 1"));
            row(&s, observer, n)
        })
        .collect();
    ValidationSeries {
        label: label.to_string(),
        rows,
    }
}

/// The series of the scene `loaded` seen from its observer, the index of its first (bottom)
/// liquid replaced by each of [`indices_to`] its own: `None` when the scene has no liquid (or a
/// liquid of index 1, with nothing to vary). The same tracing as the default report's series.
pub fn liquid_series(label: &str, loaded: &Setup) -> Result<Option<ValidationSeries>> {
    let observer = loaded.observer;
    let Some(top) = loaded.description.liquids.first().map(|l| l.index) else {
        return Ok(None);
    };
    if top == 1.0 {
        return Ok(None);
    }
    // The same scene, its bottom liquid's index changed, made by the same rules as any other.
    let values = SceneValues {
        observer: Some(observer.to_array()),
        max_events: loaded.world.max_events(),
        ..SceneValues::default()
    };
    let mut rows = Vec::new();
    for n in indices_to(top) {
        let mut d = loaded.description.clone();
        d.liquids[0].index = n;
        let setup = Setup::from_description(loaded.name(), d, &values)?;
        rows.push(row(&setup.world, observer, n));
    }
    Ok(Some(ValidationSeries {
        label: label.to_string(),
        rows,
    }))
}

/// `(n, largest, median)` distance from the objects of the image points of `world` seen from
/// `observer` whose light crossed a surface; when no light crosses one (a liquid of index 1 in
/// a glass of no thickness is air, so it has no surface), of all the points, which then lie on
/// the objects.
fn row(world: &World, observer: Vec3, n: f64) -> (f64, f64, f64) {
    let cloud = sample_image(world, observer, VALIDATION_POINTS, &|_| {});
    let crossed: Vec<Vec3> = cloud
        .points
        .iter()
        .filter(|p| p.events > 0)
        .map(|p| p.position)
        .collect();
    let points = if crossed.is_empty() {
        cloud.points.iter().map(|p| p.position).collect()
    } else {
        crossed
    };
    let (max, median) = distance_stats(world, &points);
    (n, max, median)
}

/// Size of the chart under the heading (px); every text at least 30 px, 7.2 pt when printed
/// 8.5 cm wide.
const CHART: (u32, u32) = (FIGURE_WIDTH, 760);
/// Colours of the four simulations.
const RGB: [RGBColor; 4] = [
    RGBColor(31, 119, 180),
    RGBColor(214, 39, 40),
    RGBColor(44, 160, 44),
    RGBColor(148, 103, 189),
];
/// Distances below this are drawn at it (the plot's floor, below any rounding of a centimetre).
const FLOOR: f64 = 1e-18;

/// Writes the figure to `path` (PNG, SVG or PDF by its extension), the index named by `axis` on
/// the horizontal axis ([`words::INDEX_AXIS`] for the water).
pub fn write_validation_figure(
    path: &Path,
    series: &[ValidationSeries],
    axis: words::Text,
    lang: Lang,
) -> Result {
    let heading = Heading::new(lang.of(words::VALIDATION_FIGURE_TITLE), "");
    let bytes = figure_bytes(
        path,
        FigureFormat::of(path)?,
        (CHART.0, CHART.1 + heading.height() as u32),
        |root| draw(root, series, &heading, axis, lang),
        |root| draw(root, series, &heading, axis, lang),
    )?;
    files::write_bytes(path, &bytes)
}

fn draw<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    series: &[ValidationSeries],
    heading: &Heading,
    axis: words::Text,
    lang: Lang,
) -> Result<(), String> {
    let e = |x: DrawingAreaErrorKind<DB::ErrorType>| x.to_string();
    root.fill(&WHITE).map_err(e)?;
    heading.draw(root).map_err(e)?;
    let top = series
        .iter()
        .flat_map(|s| s.rows.iter().map(|r| r.1))
        .filter(|v| v.is_finite())
        .fold(1e-3, f64::max)
        * 3.0;
    let right = series
        .iter()
        .flat_map(|s| s.rows.iter().map(|r| r.0))
        .fold(WATER_INDEX, f64::max);
    let area = root.margin(heading.height() as u32, 50, 0, 0);
    let mut chart = ChartBuilder::on(&area)
        .margin(20)
        .margin_right(40)
        .x_label_area_size(90)
        .y_label_area_size(150)
        .build_cartesian_2d(1.0..right + 0.005, (FLOOR..top).log_scale())
        .map_err(e)?;
    chart
        .configure_mesh()
        .x_labels(6)
        .y_labels(8)
        .label_style(font(TEXT))
        .axis_desc_style(font(TEXT))
        .x_desc(lang.of(axis))
        .y_desc(lang.of(words::DISTANCE_LOG_AXIS))
        .x_label_formatter(&|v| format!("{v:.2}"))
        .y_label_formatter(&|v| format!("{v:.0e}"))
        .light_line_style(WHITE)
        .draw()
        .map_err(e)?;
    for (k, s) in series.iter().enumerate() {
        let c = RGB[k % RGB.len()];
        let at = |v: f64| v.max(FLOOR);
        let largest: Vec<(f64, f64)> = s.rows.iter().map(|r| (r.0, at(r.1))).collect();
        let median: Vec<(f64, f64)> = s.rows.iter().map(|r| (r.0, at(r.2))).collect();
        chart
            .draw_series(LineSeries::new(largest.clone(), c.stroke_width(4)))
            .map_err(e)?
            .label(s.label.clone())
            .legend(move |(x, y)| {
                PathElement::new(vec![(x - 5, y), (x + 15, y)], c.stroke_width(4))
            });
        chart
            .draw_series(largest.iter().map(|p| Circle::new(*p, 6, c.filled())))
            .map_err(e)?;
        chart
            .draw_series(DashedLineSeries::new(median, 10, 8, c.stroke_width(3)))
            .map_err(e)?;
    }
    chart
        .configure_series_labels()
        .label_font(font(TEXT))
        .position(SeriesLabelPosition::LowerRight)
        .background_style(WHITE.mix(0.9))
        .border_style(BLACK)
        .draw()
        .map_err(e)?;
    root.draw(&Text::new(
        lang.of(words::SOLID_DASHED),
        (170, root.dim_in_pixel().1 as i32 - 44),
        font(TEXT),
    ))
    .map_err(e)?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use bentstraw_optics::scene::REFERENCES;

    /// Zero at n = 1 (to rounding), and growing with n, for every reference simulation.
    #[test]
    fn the_image_leaves_the_straw_as_the_index_grows() {
        for r in REFERENCES {
            let s = series(
                &format!("simulation {}", r.number),
                &r.scene(1.333),
                r.observer,
            );
            assert_eq!(s.rows.len(), 8);
            assert_eq!(s.rows[0].0, 1.0);
            assert!((s.rows[7].0 - WATER_INDEX).abs() < 1e-15);
            assert!(
                s.rows[0].1 < 1e-12,
                "{}: {:e} at n = 1",
                r.number,
                s.rows[0].1
            );
            // Any water that bends light moves the image off the straw, far above rounding
            // (the median need not grow steadily: the mix of light paths changes with n).
            for row in &s.rows[1..] {
                assert!(row.1 > 1e-5 && row.2 > 1e-7, "{}: {row:?}", r.number);
            }
            assert!(s.rows[7].1 > s.rows[1].1, "{}: {:?}", r.number, s.rows);
            assert!(
                s.rows[7].2 > 1e-4,
                "{}: median {:e} at n = 1.333",
                r.number,
                s.rows[7].2
            );
        }
    }

    /// A scene file's series: its bottom liquid's index from 1 (the image on the straw, to
    /// rounding) to its own, the image leaving the straw as it grows; none without a liquid.
    #[test]
    fn a_scene_files_image_leaves_its_straw_as_its_liquids_index_grows() {
        let text = crate::gallery::GALLERY
            .iter()
            .find(|(stem, _)| *stem == "dense-liquid")
            .unwrap()
            .1;
        let loaded = crate::scene_input::gallery_setup("dense-liquid", text, 10).unwrap();
        let own = loaded.description.liquids[0].index;
        assert!(own > 1.5, "{own}");
        let s = liquid_series("observer 1", &loaded).unwrap().unwrap();
        assert_eq!(s.rows.len(), 8);
        assert_eq!(s.rows[0].0, 1.0);
        assert!((s.rows[7].0 - own).abs() < 1e-12);
        assert!(s.rows[0].1 < 1e-12, "{:e} at n = 1", s.rows[0].1);
        for row in &s.rows[1..] {
            assert!(row.1 > 1e-5 && row.2 > 1e-7, "{row:?}");
        }
        assert!(s.rows[7].2 > s.rows[1].2, "{:?}", s.rows);

        // The same glass emptied: nothing to vary.
        let dry: String = text.split("[[liquid]]").next().unwrap().to_string()
            + &text[text.find("[[straw]]").unwrap()..];
        let loaded = crate::scene_input::gallery_setup("dry", &dry, 10).unwrap();
        assert!(loaded.description.liquids.is_empty());
        assert!(liquid_series("observer 1", &loaded).unwrap().is_none());
    }

    /// The numbers are the points' own: the statistics of a known set.
    #[test]
    fn largest_and_median_of_known_distances() {
        let scene = Scene::with_defaults(0.0, 0.0, 0.1).unwrap();
        // Points straight out from the side at 0.1, 0.2 and 0.4 m from the surface.
        let pts: Vec<Vec3> = [0.1, 0.2, 0.4]
            .iter()
            .map(|d| Vec3::new(0.005 + d, 0.0, 0.1))
            .collect();
        let (max, median) = distance_stats(&World::assignment(&scene), &pts);
        assert!((max - 0.4).abs() < 1e-15 && (median - 0.2).abs() < 1e-15);
    }

    #[test]
    fn the_figure_is_drawn_in_png_and_svg() {
        let dir = tempfile::tempdir().unwrap();
        let r = REFERENCES[1];
        let s = vec![series("simulation 2", &r.scene(1.333), r.observer)];
        for name in ["v.png", "v.svg"] {
            let path = dir.path().join(name);
            write_validation_figure(&path, &s, words::INDEX_AXIS, Lang::En).unwrap();
            assert!(std::fs::metadata(&path).unwrap().len() > 1000);
        }
        let svg = std::fs::read_to_string(dir.path().join("v.svg")).unwrap();
        let doc = roxmltree::Document::parse(&svg).unwrap();
        assert!(doc
            .descendants()
            .any(|n| n.text().is_some_and(|t| t.contains("index of the water"))));
        if let Ok(look) = std::env::var("BENTSTRAW_LOOK") {
            std::fs::copy(
                dir.path().join("v.png"),
                Path::new(&look).join("validation.png"),
            )
            .unwrap();
        }
    }
}
