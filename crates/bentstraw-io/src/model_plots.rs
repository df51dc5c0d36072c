//! Figures comparing the apparent-position models: the course's, the eye's and the stereo image
//! clouds side by side, and the gap between the course's points and another model's along the
//! straw's height. PNG, SVG or PDF by the file's extension, through the figures' one pipeline.
//!
//! The comparison figure shows every model from the same two viewpoints, one model a row, with one
//! box and one scale per column, so that a point's shift from one panel to the one below is the
//! models' difference: a level view from the side (along the axis nearest the perpendicular to the
//! observer's horizontal direction) and a view from above. The models differ mostly along the lines of sight, which both
//! views show at full length when the observer looks roughly horizontally; a view from the
//! observer would show none of it.

use std::collections::HashSet;
use std::path::Path;

use bentstraw_optics::apparent::{ApparentPoint, StereoImage};
use bentstraw_optics::image::ImagePoint;
use bentstraw_optics::scene::{SECTION_COUNT, SECTION_HEIGHT, STRAW_HEIGHT};
use bentstraw_optics::Vec3;
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use crate::error::Result;
use crate::files;
use crate::plot::{
    axis_box, common_legend, draw_axis_labels, draw_dots, draw_legend_cell, draw_observer,
    draw_panes, draw_straw_outline, draw_water, figure_bytes, figure_views, font, grid, rgb,
    section_rgb8, section_words, triple, visible_dots, AreaOn, AxisBox, FigureFormat, Heading,
    LegendMark, Panel, ViewDirection, CAPTION_LINE, FIGURE_WIDTH, LEGEND_LINE, TEXT, TITLE,
};
use crate::words::{self, Lang};
use bentstraw_optics::setup::Setup;

/// The three models' names in the comparison figure, in the order course, eye, stereo.
pub const MODEL_NAMES: [&str; 3] = [
    "course (P = O + L·u0)",
    "eye (small pupil)",
    "stereo (two eyes, 65 mm)",
];

/// The gap plot's samples of the eye model: `(z of the straw point, gap to the course's point,
/// colour code)` for each point the model places.
pub fn eye_gap_samples(eye: &[ApparentPoint]) -> Vec<(f64, f64, u8)> {
    eye.iter()
        .filter_map(|p| Some((p.image.straw_point.z, p.gap_to_course()?, p.image.color)))
        .collect()
}

/// The gap plot's samples of the stereo model, as [`eye_gap_samples`].
pub fn stereo_gap_samples(stereo: &StereoImage) -> Vec<(f64, f64, u8)> {
    stereo
        .points
        .iter()
        .filter_map(|p| Some((p.image.straw_point.z, p.gap_to_course()?, p.image.color)))
        .collect()
}

/// One model's image cloud, for the comparison figure.
#[derive(Clone, Copy, Debug)]
pub struct ModelCloud<'a> {
    /// The model's name, e.g. "course (P = O + L·u0)".
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

impl<'a> GapSeries<'a> {
    /// The two curves of the models' gap plot: the eye model's and the stereo model's gaps,
    /// named in `lang`.
    pub fn of_models(
        eye: &'a [(f64, f64, u8)],
        stereo: &'a [(f64, f64, u8)],
        lang: Lang,
    ) -> [GapSeries<'a>; 2] {
        [
            GapSeries {
                name: lang.of(words::EYE_MODEL),
                samples: eye,
            },
            GapSeries {
                name: lang.of(words::STEREO_MODEL),
                samples: stereo,
            },
        ]
    }
}

/// Height of one row of panels of the comparison figure (px).
const ROW_HEIGHT: i32 = 620;
/// Caption lines over each panel: the model, the view, the count.
const CAPTION_LINES: usize = 3;
/// Columns of the comparison figure: side view, view from above.
const COLUMNS: usize = 2;
/// Height of the comparison figure's legend (px).
const LEGEND_HEIGHT: i32 = CAPTION_LINE + 5 * LEGEND_LINE + 20;
/// Image points farther than this many times the scene's size from its centre (a focus near
/// infinity) are left off the frame and counted, so that one such point cannot shrink the glass
/// to a dot.
const FAR_POINT_SIZES: f64 = 3.0;

/// Draws the models' clouds one above the other, same viewpoints and scales, into `path` (PNG,
/// SVG or PDF by its extension).
pub fn write_model_comparison(
    path: &Path,
    scene: &Setup,
    observer: Vec3,
    models: &[ModelCloud],
    title: &str,
) -> Result {
    let bytes = render_model_comparison(path, scene, observer, models, title)?;
    files::write_bytes(path, &bytes)
}

/// Whether an image point is drawn in the comparison (finite and not absurdly far from the scene:
/// for a scene file, three times its box's size from the box's middle).
fn on_frame(scene: &Setup, p: &ImagePoint) -> bool {
    let centre = scene.frame().2;
    p.position.is_finite() && (p.position - centre).length() <= FAR_POINT_SIZES * scene.size()
}

/// The one box shared by every panel: glass, straw, the observer when near, and every model's points
/// on the frame. Also returns the count of points left off per model.
fn shared_box(scene: &Setup, observer: Vec3, models: &[ModelCloud]) -> (AxisBox, Vec<usize>) {
    let all: Vec<ImagePoint> = models
        .iter()
        .flat_map(|m| m.points.iter().copied().filter(|p| on_frame(scene, p)))
        .collect();
    let off = models
        .iter()
        .map(|m| m.points.iter().filter(|p| !on_frame(scene, p)).count())
        .collect();
    (axis_box(scene, observer, &all), off)
}

/// The two views (side, above) with their captions.
fn comparison_views(observer: Vec3) -> [(ViewDirection, String); COLUMNS] {
    let [_, (side, side_caption), (above, above_caption)] = figure_views(observer);
    [
        (side, side_caption[0].clone()),
        (above, above_caption[0].clone()),
    ]
}

/// The comparison figure's heading: the observer and the scene's values figures name.
fn comparison_heading(scene: &Setup, observer: Vec3, title: &str) -> Heading {
    let mut parts = vec![format!("observer {} m", triple(observer))];
    parts.extend(scene.inputs().iter().filter_map(|i| i.heading_phrase()));
    parts.push("same box and scale in every panel of a column, lengths in metres".to_string());
    Heading::new(title, &parts.join(" · "))
}

/// The size of the comparison figure of `rows` models under `heading`.
fn comparison_size(heading: &Heading, rows: usize) -> (u32, u32) {
    (
        FIGURE_WIDTH,
        (heading.height() + rows.max(1) as i32 * ROW_HEIGHT + LEGEND_HEIGHT) as u32,
    )
}

/// The panels: one row per model, one column per view; within a column all panels have the same
/// projection up to a shift, so positions compare directly.
fn comparison_layout(
    bx: &AxisBox,
    observer: Vec3,
    models: &[ModelCloud],
    off: &[usize],
    top: i32,
) -> Vec<Panel> {
    let views = comparison_views(observer);
    let cells: Vec<(ViewDirection, Vec<String>)> = (0..models.len().max(1))
        .flat_map(|i| {
            let (name, count) = match models.get(i) {
                None => ("no model".to_string(), "no points".to_string()),
                Some(m) if m.points.is_empty() => (m.name.to_string(), "no points".to_string()),
                Some(m) => {
                    let shown = m.points.len() - off[i];
                    let count = if off[i] > 0 {
                        format!("{shown} points, {} not shown", off[i])
                    } else {
                        format!("{shown} points")
                    };
                    (m.name.to_string(), count)
                }
            };
            views
                .iter()
                .map(move |(v, caption)| (*v, vec![name.clone(), caption.clone(), count.clone()]))
                .collect::<Vec<_>>()
        })
        .collect();
    grid(bx, &cells, top, COLUMNS, ROW_HEIGHT, CAPTION_LINES)
}

/// The comparison figure as the bytes of its file.
fn render_model_comparison(
    path: &Path,
    scene: &Setup,
    observer: Vec3,
    models: &[ModelCloud],
    title: &str,
) -> Result<Vec<u8>> {
    let heading = comparison_heading(scene, observer, title);
    figure_bytes(
        path,
        FigureFormat::of(path)?,
        comparison_size(&heading, models.len()),
        |root| draw_comparison(root, scene, observer, models, &heading),
        |root| draw_comparison(root, scene, observer, models, &heading),
    )
}

/// The comparison figure on any backend.
fn draw_comparison<DB: DrawingBackend>(
    root: &AreaOn<DB>,
    scene: &Setup,
    observer: Vec3,
    models: &[ModelCloud],
    heading: &Heading,
) -> Result<(), String> {
    let e = |x: DrawingAreaErrorKind<DB::ErrorType>| x.to_string();
    root.fill(&WHITE).map_err(e)?;
    heading.draw(root).map_err(e)?;
    let (bx, off) = shared_box(scene, observer, models);
    let panels = comparison_layout(&bx, observer, models, &off, heading.height());
    let drawn: Vec<Vec<ImagePoint>> = models
        .iter()
        .map(|m| {
            m.points
                .iter()
                .copied()
                .filter(|p| on_frame(scene, p))
                .collect()
        })
        .collect();
    let ghost: Vec<(ImagePoint, [u8; 3])> = drawn
        .first()
        .map(|d| d.iter().map(|p| (*p, GHOST_RGB)).collect())
        .unwrap_or_default();
    for (k, p) in panels.iter().enumerate() {
        let i = k / COLUMNS;
        draw_panes(root, p, &bx).map_err(e)?;
        draw_water(root, &p.proj, scene, false).map_err(e)?;
        draw_straw_outline(root, &p.proj, scene).map_err(e)?;
        let mut dots = Vec::new();
        if let Some(points) = drawn.get(i) {
            // The first model's points, pale, behind each other model's: the shift is the difference.
            let behind: &[(ImagePoint, [u8; 3])] = if i > 0 { &ghost } else { &[] };
            dots = visible_dots(p, behind, points);
            draw_dots(root, &dots).map_err(e)?;
        } else {
            root.draw(&Text::new(
                "no model to show",
                (p.left + p.width / 2, p.top + p.height / 2),
                font(TEXT).pos(Pos::new(HPos::Center, VPos::Center)),
            ))
            .map_err(e)?;
        }
        draw_water(root, &p.proj, scene, true).map_err(e)?;
        draw_axis_labels(root, p, &bx).map_err(e)?;
        draw_observer(root, p, &bx, observer, &dots).map_err(e)?;
    }
    // The legend under the panels, in two columns.
    let top = heading.height() + models.len().max(1) as i32 * ROW_HEIGHT;
    let half = FIGURE_WIDTH as i32 / 2;
    let sections: Vec<(LegendMark, String)> = (0..SECTION_COUNT)
        .map(|k| {
            (
                LegendMark::Swatch(section_rgb8(k as u8 + 1)),
                section_words(k),
            )
        })
        .collect();
    let mut others = common_legend(scene, bx.observer_inside);
    if let Some(m) = models.first() {
        others.push((
            LegendMark::Swatch(GHOST_RGB),
            format!("{}, behind", short_name(m.name)),
        ));
    }
    others.push((
        LegendMark::None,
        format!("not shown: beyond {:.1} m", FAR_POINT_SIZES * scene.size()),
    ));
    draw_legend_cell(
        root,
        (0, top - CAPTION_LINE / 2, half, LEGEND_HEIGHT),
        &sections,
    )
    .map_err(e)?;
    draw_legend_cell(
        root,
        (half, top - CAPTION_LINE / 2, half, LEGEND_HEIGHT),
        &others,
    )
    .map_err(e)?;
    Ok(())
}

/// A model's name without its explanation in brackets: "course (P = O + L·u0)" → "course".
fn short_name(name: &str) -> &str {
    name.split(" (").next().unwrap_or(name).trim()
}

/// Colour of the first model's points shown behind the other models' points.
const GHOST_RGB: [u8; 3] = [206, 200, 194];

/// Size of the gap plot's chart, under its heading (px).
const GAP_CHART: (u32, u32) = (FIGURE_WIDTH, 700);
/// Margin around the gap plot (px).
const GAP_MARGIN: u32 = 20;
/// Room for the x axis's tick labels and name (px).
const GAP_X_LABELS: u32 = 100;
/// Room for the y axis's tick labels and name (px).
const GAP_Y_LABELS: u32 = 130;
/// The series' colours and marker shapes, in order (then repeated).
const SERIES_RGB: [(u8, u8, u8); 3] = [(20, 40, 140), (210, 80, 0), (0, 130, 60)];

/// The top of the gap axis (mm): the largest gap plus a little room, at least 0.1 mm.
fn gap_axis_top(series: &[GapSeries]) -> f64 {
    let largest = series
        .iter()
        .flat_map(|s| s.samples.iter())
        .filter(|(z, g, _)| z.is_finite() && g.is_finite())
        .map(|&(_, g, _)| g * 1e3)
        .fold(0.0, f64::max);
    (1.08 * largest).max(0.1)
}

/// Decimals of the gap axis's labels (mm): none above 10 mm, else enough for about 5 ticks.
fn gap_decimals(top_mm: f64) -> usize {
    if top_mm >= 10.0 {
        0
    } else if top_mm >= 1.0 {
        1
    } else {
        2
    }
}

/// Plots the gap between the course's image points and each series' model against the height of the
/// straw point, into `path` (PNG, SVG or PDF by its extension).
pub fn write_gap_plot(path: &Path, series: &[GapSeries], title: &str, lang: Lang) -> Result {
    let heading = Heading::new(title, "");
    let size = (GAP_CHART.0, GAP_CHART.1 + heading.height() as u32);
    let bytes = figure_bytes(
        path,
        FigureFormat::of(path)?,
        size,
        |root| draw_gap_plot(root, series, &heading, lang),
        |root| draw_gap_plot(root, series, &heading, lang),
    )?;
    files::write_bytes(path, &bytes)
}

/// The gap plot on any backend.
fn draw_gap_plot<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    series: &[GapSeries],
    heading: &Heading,
    lang: Lang,
) -> Result<(), String> {
    let e = |x: DrawingAreaErrorKind<DB::ErrorType>| x.to_string();
    root.fill(&WHITE).map_err(e)?;
    heading.draw(root).map_err(e)?;
    let area = root.margin(heading.height() as u32, 50, 0, 0);
    let top = gap_axis_top(series);
    let mut chart = ChartBuilder::on(&area)
        .margin(GAP_MARGIN)
        .margin_right(40)
        .x_label_area_size(GAP_X_LABELS)
        .y_label_area_size(GAP_Y_LABELS)
        .build_cartesian_2d(0.0..STRAW_HEIGHT, 0.0..top)
        .map_err(e)?;
    // The sections as light bands in their colours, under the grid and the points.
    for k in 0..SECTION_COUNT {
        let c = section_rgb8(k as u8 + 1);
        chart
            .draw_series(std::iter::once(Rectangle::new(
                [
                    (k as f64 * SECTION_HEIGHT, 0.0),
                    ((k + 1) as f64 * SECTION_HEIGHT, top),
                ],
                RGBColor(c[0], c[1], c[2]).mix(0.13).filled(),
            )))
            .map_err(e)?;
    }
    chart
        .configure_mesh()
        .x_desc(lang.of(words::HEIGHT_AXIS))
        .y_desc(lang.of(words::GAP_AXIS))
        .axis_desc_style(font(TEXT))
        .label_style(font(TEXT))
        .x_labels(6)
        .y_labels(6)
        .max_light_lines(1)
        .light_line_style(RGBColor(235, 235, 235))
        .bold_line_style(RGBColor(200, 200, 200))
        .x_label_formatter(&|v| format!("{v:.2}"))
        .y_label_formatter(&|v| format!("{v:.*}", gap_decimals(top)))
        .draw()
        .map_err(e)?;
    // In reverse, so that the first series (the eye model) is drawn on top.
    for (k, s) in series.iter().enumerate().rev() {
        let color = rgb(SERIES_RGB[k % SERIES_RGB.len()]);
        // Thinned to one sample per pixel: 20 000 dots on 1 000 columns would only overdraw.
        let mut seen = HashSet::new();
        let kept: Vec<(f64, f64)> = s
            .samples
            .iter()
            .filter(|(z, g, _)| z.is_finite() && g.is_finite())
            .map(|&(z, g, _)| (z, g * 1e3))
            .filter(|&p| seen.insert(chart.backend_coord(&p)))
            .collect();
        let style = color.mix(if k == 0 { 0.8 } else { 0.5 });
        if k % 2 == 0 {
            chart.draw_series(kept.iter().map(|&p| Circle::new(p, 2, style.filled())))
        } else {
            chart.draw_series(
                kept.iter()
                    .map(|&p| Cross::new(p, 3, style.stroke_width(1))),
            )
        }
        .map_err(e)?;
    }
    // The legend's entries, in the series' order (plotters lists them in drawing order).
    for (k, s) in series.iter().enumerate() {
        let color = rgb(SERIES_RGB[k % SERIES_RGB.len()]);
        let label = if s.samples.is_empty() {
            lang.fill(words::NO_POINTS, &[&s.name])
        } else {
            lang.fill(words::N_POINTS, &[&s.name, &s.samples.len()])
        };
        chart
            .draw_series(std::iter::empty::<Circle<(f64, f64), u32>>())
            .map_err(e)?
            .label(label)
            .legend(move |(x, y)| {
                if k % 2 == 0 {
                    Circle::new((x + 8, y), 7, color.filled()).into_dyn()
                } else {
                    Cross::new((x + 8, y), 7, color.stroke_width(3)).into_dyn()
                }
            });
    }
    if series.is_empty() || series.iter().all(|s| s.samples.is_empty()) {
        let (px, py) = chart.backend_coord(&(STRAW_HEIGHT / 2.0, top / 2.0));
        root.draw(&Text::new(
            "no points",
            (px, py),
            font(TITLE).pos(Pos::new(HPos::Center, VPos::Center)),
        ))
        .map_err(e)?;
    }
    if !series.is_empty() {
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::UpperRight)
            .background_style(WHITE.mix(0.85))
            .border_style(RGBColor(160, 160, 160))
            .label_font(font(TEXT))
            .draw()
            .map_err(e)?;
    }
    root.draw(&Text::new(
        "bands: the straw's coloured sections",
        (
            GAP_MARGIN as i32 + GAP_Y_LABELS as i32,
            root.dim_in_pixel().1 as i32 - 44,
        ),
        font(TEXT),
    ))
    .map_err(e)?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::plot::tests::{decode, point};
    use bentstraw_optics::scene::SCENE_CENTRE;
    use bentstraw_optics::scene::{Scene, STRAW_RADIUS};

    /// Points on the straw's surface in section `color`, around its axis at `(x, y)`.
    fn ring(x: f64, y: f64, color: u8, n: usize) -> Vec<ImagePoint> {
        (0..n)
            .map(|i| {
                let t = i as f64 * 0.37;
                let z = (color as f64 - 1.0 + (i % 10) as f64 / 10.0) * SECTION_HEIGHT;
                point(
                    Vec3::new(x + STRAW_RADIUS * t.cos(), y + STRAW_RADIUS * t.sin(), z),
                    color,
                )
            })
            .collect()
    }

    /// The pixel rectangle of model `i`'s panel in column `c` (as the figure lays them out).
    fn panel_rect(
        scene: &Setup,
        observer: Vec3,
        models: &[ModelCloud],
        i: usize,
        c: usize,
    ) -> (u32, u32, u32, u32) {
        let (bx, off) = shared_box(scene, observer, models);
        let heading = comparison_heading(scene, observer, "test");
        let panels = comparison_layout(&bx, observer, models, &off, heading.height());
        let p = &panels[i * COLUMNS + c];
        (p.left as u32, p.top as u32, p.width as u32, p.height as u32)
    }

    fn has_colour(img: &image::RgbImage, rect: (u32, u32, u32, u32), c: [u8; 3]) -> bool {
        let (l, t, w, h) = rect;
        (t..t + h).any(|y| (l..l + w).any(|x| img.get_pixel(x, y).0 == c))
    }

    fn render(scene: &Setup, observer: Vec3, models: &[ModelCloud]) -> image::RgbImage {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("models.png");
        write_model_comparison(&path, scene, observer, models, "test").unwrap();
        decode(&std::fs::read(&path).unwrap())
    }

    #[test]
    fn each_panel_shows_the_colours_of_its_own_points_only() {
        let scene = Setup::assignment(Scene::with_defaults(0.02, 0.01, 0.15).unwrap(), Vec3::ZERO);
        let observer = Vec3::new(0.1, 0.0, 0.1);
        let a = ring(0.02, 0.01, 1, 400);
        let b = ring(0.01, 0.01, 4, 400);
        let mut c = ring(0.0, 0.01, 2, 400);
        // Apart from the others, so that no view hides it behind them.
        c.extend(ring(-0.02, -0.01, 5, 400));
        let models = [
            ModelCloud {
                name: "a",
                points: &a,
            },
            ModelCloud {
                name: "b",
                points: &b,
            },
            ModelCloud {
                name: "c",
                points: &c,
            },
        ];
        let img = render(&scene, observer, &models);
        let heading = comparison_heading(&scene, observer, "test");
        assert_eq!(img.dimensions(), comparison_size(&heading, 3));
        let wanted: [&[u8]; 3] = [&[1], &[4], &[2, 5]];
        for (i, codes) in wanted.iter().enumerate() {
            for r in 0..COLUMNS {
                let rect = panel_rect(&scene, observer, &models, i, r);
                for code in 1..=5u8 {
                    assert_eq!(
                        has_colour(&img, rect, section_rgb8(code)),
                        codes.contains(&code),
                        "model {i}, row {r}, colour {code}"
                    );
                }
                // The first model's points stand pale behind the others'.
                assert_eq!(
                    has_colour(&img, rect, GHOST_RGB),
                    i > 0,
                    "model {i}, row {r}"
                );
            }
        }
    }

    #[test]
    fn equal_models_give_panels_equal_up_to_a_shift() {
        let scene = Setup::assignment(Scene::with_defaults(0.02, 0.01, 0.15).unwrap(), Vec3::ZERO);
        let observer = Vec3::new(0.0, 0.1, 0.1);
        let mut pts = ring(0.02, 0.01, 3, 500);
        pts.extend(ring(0.03, 0.02, 1, 500));
        let m = ModelCloud {
            name: "same",
            points: &pts,
        };
        let other = ring(-0.02, 0.0, 5, 100);
        let models = [
            m,
            m,
            ModelCloud {
                name: "same",
                points: &other,
            },
        ];
        let img = render(&scene, observer, &models);
        for c in 0..COLUMNS {
            let (l, t0, w, h) = panel_rect(&scene, observer, &models, 0, c);
            let (_, t1, ..) = panel_rect(&scene, observer, &models, 1, c);
            let (_, t2, ..) = panel_rect(&scene, observer, &models, 2, c);
            let differ = |ta: u32, tb: u32| {
                (0..h)
                    .flat_map(|y| (l..l + w).map(move |x| (x, y)))
                    .filter(|&(x, y)| {
                        // Plotters' anti-aliased lines may round one unit differently elsewhere.
                        let (a, b) = (img.get_pixel(x, ta + y).0, img.get_pixel(x, tb + y).0);
                        (0..3).any(|c| a[c].abs_diff(b[c]) > 2)
                    })
                    .count()
            };
            assert_eq!(
                differ(t0, t1),
                0,
                "column {c}: same points, different pixels"
            );
            // The comparison is not vacuous: other points do change the panel.
            assert!(differ(t0, t2) > 100, "column {c}");
        }
    }

    #[test]
    fn shared_box_holds_every_model_and_leaves_off_only_far_points() {
        let scene = Setup::assignment(Scene::with_defaults(0.02, 0.01, 0.15).unwrap(), Vec3::ZERO);
        let observer = Vec3::new(0.1, 0.0, 0.1);
        let a = [point(Vec3::new(-0.09, 0.0, 0.1), 1)];
        let b = [
            point(Vec3::new(0.0, 0.07, -0.06), 2),
            point(Vec3::new(40.0, 0.0, 0.1), 2),
            point(Vec3::new(f64::NAN, 0.0, 0.1), 2),
        ];
        let models = [
            ModelCloud {
                name: "a",
                points: &a,
            },
            ModelCloud {
                name: "b",
                points: &b,
            },
        ];
        let (bx, off) = shared_box(&scene, observer, &models);
        assert_eq!(off, vec![0, 2]);
        assert!(bx.contains(a[0].position) && bx.contains(b[0].position));
        assert!(bx.contains(observer));
        assert!((bx.max - bx.min).max_element() < 0.5, "{bx:?}");
        // The box is the one of the models' points together, whichever model holds them.
        let together = [a[0], b[0]];
        let one = [ModelCloud {
            name: "both",
            points: &together,
        }];
        assert_eq!(shared_box(&scene, observer, &one).0, bx);
    }

    #[test]
    fn first_column_looks_level_across_the_observers_line_of_sight() {
        for observer in [
            Vec3::new(0.0, 0.1, 0.1),
            Vec3::new(0.1, 0.0, -0.1),
            Vec3::new(0.8, 0.3, 0.25),
        ] {
            let [(side, ..), (above, ..)] = comparison_views(observer);
            let t = side.toward_viewer();
            let horizontal = Vec3::new(
                observer.x - SCENE_CENTRE.x,
                observer.y - SCENE_CENTRE.y,
                0.0,
            );
            // Within 45° of perpendicular to the observer's horizontal direction (along the
            // nearest axis), and level: depth along the lines of sight runs across the panel.
            assert!(
                t.dot(horizontal.normalize()).abs() <= 0.5f64.sqrt() + 1e-12,
                "{observer}"
            );
            let ideal = Vec3::new(-horizontal.y, horizontal.x, 0.0).normalize();
            assert!(t.dot(ideal).abs() >= 0.5f64.sqrt() - 1e-12, "{observer}");
            assert!(t.z.abs() < 1e-12);
            assert!((above.toward_viewer() - Vec3::Z).length() < 1e-12);
        }
    }

    #[test]
    fn empty_models_and_no_models_still_draw() {
        let scene = Setup::assignment(Scene::with_defaults(0.0, 0.0, 0.0).unwrap(), Vec3::ZERO);
        let observer = Vec3::new(5.0, 0.0, 0.3);
        for models in [
            vec![],
            vec![ModelCloud {
                name: "empty",
                points: &[],
            }],
        ] {
            let img = render(&scene, observer, &models);
            let heading = comparison_heading(&scene, observer, "test");
            assert_eq!(img.dimensions(), comparison_size(&heading, models.len()));
        }
    }

    /// The plotting area of a gap plot, found in the picture: the black axis lines along its left
    /// and bottom edges, which span it whole.
    fn plot_area(img: &image::RgbImage) -> (u32, u32, u32, u32) {
        let (w, h) = img.dimensions();
        let black = |x: u32, y: u32| img.get_pixel(x, y).0.iter().all(|&v| v < 40);
        let left = (0..w / 2)
            .max_by_key(|&x| (0..h).filter(|&y| black(x, y)).count())
            .unwrap();
        let bottom = (h / 2..h)
            .max_by_key(|&y| (0..w).filter(|&x| black(x, y)).count())
            .unwrap();
        let top = (0..bottom).find(|&y| black(left, y)).unwrap();
        let right = (left..w).rev().find(|&x| black(x, bottom)).unwrap();
        (left, right, top, bottom)
    }

    fn gap_image(series: &[GapSeries]) -> image::RgbImage {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("gap.png");
        write_gap_plot(&path, series, "gap", Lang::En).unwrap();
        decode(&std::fs::read(&path).unwrap())
    }

    #[test]
    fn gap_plot_puts_a_sample_where_its_height_and_gap_are() {
        // Gaps in metres: the largest, 2 mm, sets the axis to 2 × 1.08 mm.
        let samples = [(0.12, 0.001, 3), (0.03, 0.002, 1)];
        let img = gap_image(&[GapSeries {
            name: "eye",
            samples: &samples,
        }]);
        assert_eq!(img.width(), FIGURE_WIDTH);
        assert!(
            (gap_axis_top(&[GapSeries {
                name: "eye",
                samples: &samples
            }]) - 2.16)
                .abs()
                < 1e-12
        );
        let (left, right, top, bottom) = plot_area(&img);
        assert!(
            right > left + 800 && bottom > top + 400,
            "{left} {right} {top} {bottom}"
        );
        let at = |z: f64, gap_mm: f64| {
            (
                left as f64 + z / STRAW_HEIGHT * (right - left) as f64,
                bottom as f64 - gap_mm / 2.16 * (bottom - top) as f64,
            )
        };
        // Dark blue pixels of the first series, never the pale bands.
        let dark_blue = |x: i64, y: i64| {
            let p = img.get_pixel(x as u32, y as u32).0;
            p[0] < 120 && p[2] as i32 > p[0] as i32 + 40
        };
        let near = |(x, y): (f64, f64)| {
            let (x, y) = (x.round() as i64, y.round() as i64);
            (-3..=3).any(|dx| (-3..=3).any(|dy| dark_blue(x + dx, y + dy)))
        };
        assert!(near(at(0.12, 1.0)), "no dot at (0.12 m, 1 mm)");
        assert!(near(at(0.03, 2.0)), "no dot at (0.03 m, 2 mm)");
        // And not where the axes would be swapped or flipped.
        assert!(!near(at(0.12, 2.16 - 1.0)));
        assert!(!near(at(0.25 - 0.12, 1.0)));
    }

    #[test]
    fn gap_plot_draws_without_points() {
        for series in [
            vec![],
            vec![GapSeries {
                name: "eye",
                samples: &[],
            }],
        ] {
            assert_eq!(gap_image(&series).width(), FIGURE_WIDTH);
        }
    }

    #[test]
    fn gap_plot_to_an_unwritable_path_is_an_error() {
        let path = Path::new("/nonexistent-folder/gap.png");
        assert!(write_gap_plot(path, &[], "t", Lang::En).is_err());
    }
}
