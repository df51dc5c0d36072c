//! Figures comparing the apparent-position models (issue 4): the course's, the eye's and the stereo
//! image clouds side by side, and the gap between the course's points and another model's along the
//! straw's height.
//!
//! The comparison figure shows every model from the same two viewpoints, with one box and one scale
//! per row, so that a point's shift from one panel to the next is the models' difference: a level view
//! from the side (perpendicular to the observer's horizontal direction) and a view from above. The
//! models differ mostly along the lines of sight, which both views show at full length when the
//! observer looks roughly horizontally; a view from the observer would show none of it.

use std::collections::HashSet;
use std::path::Path;

use bentstraw_optics::image::ImagePoint;
use bentstraw_optics::scene::{
    Scene, GLASS_HEIGHT, SCENE_CENTRE, SECTION_COUNT, SECTION_HEIGHT, SECTION_NAMES, STRAW_HEIGHT,
};
use bentstraw_optics::Vec3;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use crate::error::CliResult;
use crate::files;
use crate::plot::{
    axis_box, dashed, draw_axis_labels, draw_err, draw_observer, draw_panes, draw_points,
    draw_straw_outline, draw_water, encode_png, figure_views, fit_scale, font, num, register_font,
    rgb, section_rgb8, text_width, triple, Area, AxisBox, DrawResult, Panel, Projection,
    ViewDirection, CAPTION_BAND, DOT, FIGURE_WIDTH, LEGEND_BAND, PAD_BOTTOM, PAD_SIDE, PAD_TOP,
    PAD_TOP_NOTE, STRAW_OUTLINE_RGB, TITLE_BAND, WATER_RGB,
};

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

/// Height of one row of panels of the comparison figure (px).
const ROW_HEIGHT: i32 = 560;
/// Rows of the comparison figure: side view, view from above.
const ROWS: usize = 2;
/// Height of the comparison figure (px).
pub const COMPARISON_HEIGHT: u32 = (TITLE_BAND + ROWS as i32 * ROW_HEIGHT + LEGEND_BAND) as u32;
/// Columns the figure always has room for, so that the scale does not depend on the models' count.
const MIN_COLUMNS: usize = 3;
/// Image points farther than this from the scene's centre (a focus near infinity) are left off the
/// frame and counted, so that one such point cannot shrink the glass to a dot.
const FAR_POINT_LIMIT: f64 = 3.0 * GLASS_HEIGHT;

/// Draws the models' clouds side by side, same viewpoint and scale, into the PNG at `path`.
pub fn write_model_comparison(
    path: &Path,
    scene: &Scene,
    observer: Vec3,
    models: &[ModelCloud],
    title: &str,
) -> CliResult {
    let png = render_model_comparison(scene, observer, models, title).map_err(draw_err(path))?;
    files::write_bytes(path, &png)
}

/// Whether an image point is drawn in the comparison (finite and not absurdly far).
fn on_frame(p: &ImagePoint) -> bool {
    p.position.is_finite() && (p.position - SCENE_CENTRE).length() <= FAR_POINT_LIMIT
}

/// The one box shared by every panel: glass, straw, the observer when near, and every model's points
/// on the frame. Also returns the count of points left off per model.
fn shared_box(scene: &Scene, observer: Vec3, models: &[ModelCloud]) -> (AxisBox, Vec<usize>) {
    let all: Vec<ImagePoint> = models
        .iter()
        .flat_map(|m| m.points.iter().copied().filter(on_frame))
        .collect();
    let off = models
        .iter()
        .map(|m| m.points.iter().filter(|p| !on_frame(p)).count())
        .collect();
    (axis_box(scene, observer, &all), off)
}

/// The two views (side, above) with short names and the description for the subtitle.
fn comparison_views(observer: Vec3) -> [(ViewDirection, &'static str, String); ROWS] {
    let [_, (side, side_caption), (third, third_caption)] = figure_views(observer);
    let third_name = if third.elevation > 1.0 {
        "from above"
    } else {
        "level, from the observer's side"
    };
    [
        (side, "from the side", side_caption),
        (third, third_name, third_caption),
    ]
}

/// The panels: one column per model, one row per view; within a row all panels have the same
/// projection up to a shift, so positions compare directly.
fn comparison_layout(bx: &AxisBox, observer: Vec3, models: &[ModelCloud]) -> Vec<Vec<Panel>> {
    let columns = models.len().max(MIN_COLUMNS);
    let panel_w = FIGURE_WIDTH as i32 / columns as i32;
    // Fewer models than columns: the panels keep their width and are centred.
    let shown = models.len().max(1) as i32;
    let first_left = (FIGURE_WIDTH as i32 - shown * panel_w) / 2;
    let pad_top = if bx.observer_inside {
        PAD_TOP
    } else {
        PAD_TOP_NOTE
    };
    // Wider side margins than the classic figure's: an oblique box puts the z labels farther out.
    let fit_w = panel_w as f64 - 2.0 * (PAD_SIDE + 20.0);
    let fit_h = (ROW_HEIGHT - CAPTION_BAND) as f64 - pad_top - PAD_BOTTOM;
    comparison_views(observer)
        .iter()
        .enumerate()
        .map(|(r, (view, view_name, _))| {
            let scale = fit_scale(bx, *view, fit_w, fit_h);
            let top = TITLE_BAND + r as i32 * ROW_HEIGHT;
            (0..shown)
                .map(|i| {
                    let left = first_left + i * panel_w;
                    let name = models.get(i as usize).map_or("no model", |m| m.name);
                    let origin = (
                        left as f64 + panel_w as f64 / 2.0,
                        (top + CAPTION_BAND) as f64 + pad_top + fit_h / 2.0,
                    );
                    Panel {
                        proj: Projection::new(*view, bx.centre(), origin, scale),
                        caption: format!("{name} — {view_name}"),
                        left,
                        top,
                        width: panel_w,
                        height: ROW_HEIGHT,
                    }
                })
                .collect()
        })
        .collect()
}

/// The comparison figure as PNG bytes.
fn render_model_comparison(
    scene: &Scene,
    observer: Vec3,
    models: &[ModelCloud],
    title: &str,
) -> Result<Vec<u8>, String> {
    register_font();
    let (w, h) = (FIGURE_WIDTH, COMPARISON_HEIGHT);
    let mut buf = vec![255u8; (w * h * 3) as usize];
    let (bx, off) = shared_box(scene, observer, models);
    let rows = comparison_layout(&bx, observer, models);
    let drawn: Vec<Vec<ImagePoint>> = models
        .iter()
        .map(|m| m.points.iter().copied().filter(on_frame).collect())
        .collect();
    let e = |e: DrawingAreaErrorKind<_>| e.to_string();
    {
        let root = BitMapBackend::with_buffer(&mut buf, (w, h)).into_drawing_area();
        draw_comparison_titles(&root, scene, observer, title).map_err(e)?;
        for p in rows.iter().flatten() {
            draw_panes(&root, p, &bx).map_err(e)?;
            draw_water(&root, &p.proj, scene, false).map_err(e)?;
            draw_straw_outline(&root, &p.proj, scene).map_err(e)?;
        }
        if models.is_empty() {
            for row in &rows {
                let p = &row[0];
                root.draw(&Text::new(
                    "no model to show",
                    (p.left + p.width / 2, p.top + p.height / 2),
                    font(18.0).pos(Pos::new(HPos::Center, VPos::Center)),
                ))
                .map_err(e)?;
            }
        }
        root.present().map_err(e)?;
    }
    for row in &rows {
        for (i, (p, points)) in row.iter().zip(&drawn).enumerate() {
            // The first model's points, pale, behind each other model's: the shift is the difference.
            if i > 0 {
                draw_ghost(&mut buf, w, p, &drawn[0]);
            }
            draw_points(&mut buf, w, h, p, points);
        }
    }
    {
        let root = BitMapBackend::with_buffer(&mut buf, (w, h)).into_drawing_area();
        for row in &rows {
            for (i, p) in row.iter().enumerate() {
                draw_water(&root, &p.proj, scene, true).map_err(e)?;
                draw_axis_labels(&root, p, &bx).map_err(e)?;
                draw_observer(&root, p, &bx, observer).map_err(e)?;
                if let Some(m) = models.get(i) {
                    draw_count(&root, p, drawn[i].len(), off[i], m.points.is_empty()).map_err(e)?;
                }
            }
        }
        draw_comparison_legend(&root, h, models.first().map(|m| m.name)).map_err(e)?;
        root.present().map_err(e)?;
    }
    encode_png(&buf, w, h)
}

/// Colour of the first model's points shown behind the other models' points.
const GHOST_RGB: [u8; 3] = [206, 200, 194];

/// `points` as pale grey dots in the panel, for reference behind another model's points.
fn draw_ghost(buf: &mut [u8], w: u32, p: &Panel, points: &[ImagePoint]) {
    let (x0, y0) = (p.left.max(0), p.top.max(0));
    let (x1, y1) = (p.left + p.width, p.top + p.height);
    for q in points {
        let (px, py) = p.proj.pixel(q.position);
        // Placed exactly as `draw_points` places a dot, so that an equal point hides it.
        let half = DOT as f64 / 2.0;
        let (cx, cy) = ((px - half).round() as i32, (py - half).round() as i32);
        for y in cy.max(y0)..(cy + DOT).min(y1) {
            for x in cx.max(x0)..(cx + DOT).min(x1).min(w as i32) {
                let k = ((y as u32 * w + x as u32) * 3) as usize;
                if k + 3 <= buf.len() {
                    buf[k..k + 3].copy_from_slice(&GHOST_RGB);
                }
            }
        }
    }
}

/// Title and a subtitle with the scene and the two views.
fn draw_comparison_titles(root: &Area, scene: &Scene, observer: Vec3, title: &str) -> DrawResult {
    let w = FIGURE_WIDTH as i32;
    root.draw(&Text::new(
        title.to_string(),
        (w / 2, 20),
        font(24.0).pos(Pos::new(HPos::Center, VPos::Center)),
    ))?;
    let [(_, _, side), (_, _, third)] = comparison_views(observer);
    let sub = format!(
        "observer {} m · straw axis ({}, {}) m · water height {} m · n_water = {} · top row {side}, bottom row {third} · same box and scale in every panel of a row, lengths in metres",
        triple(observer),
        num(scene.straw_x),
        num(scene.straw_y),
        num(scene.water_height),
        num(scene.n_water),
    );
    root.draw(&Text::new(
        sub,
        (w / 2, 48),
        font(14.0)
            .color(&RGBColor(60, 60, 60))
            .pos(Pos::new(HPos::Center, VPos::Center)),
    ))
}

/// The number of points drawn in a panel (and of those left off), under its caption.
fn draw_count(root: &Area, p: &Panel, drawn: usize, off: usize, empty: bool) -> DrawResult {
    let s = if empty {
        "no points".to_string()
    } else if off > 0 {
        format!("{drawn} points, {off} farther than {FAR_POINT_LIMIT} m not shown")
    } else {
        format!("{drawn} points")
    };
    let at = (p.left + PAD_SIDE as i32 / 2, p.top + p.height - 14);
    root.draw(&Text::new(
        s,
        at,
        font(13.0)
            .color(&RGBColor(60, 60, 60))
            .pos(Pos::new(HPos::Left, VPos::Center)),
    ))
}

/// The sections' colours and heights, the observer, the wireframes.
fn draw_comparison_legend(root: &Area, h: u32, first: Option<&str>) -> DrawResult {
    let y = h as i32 - LEGEND_BAND / 2;
    let style = font(14.0).pos(Pos::new(HPos::Left, VPos::Center));
    let mut items: Vec<String> = (0..SECTION_COUNT)
        .map(|k| {
            format!(
                "{} {}, z {:.2}–{:.2} m",
                k + 1,
                SECTION_NAMES[k],
                k as f64 * SECTION_HEIGHT,
                (k + 1) as f64 * SECTION_HEIGHT
            )
        })
        .collect();
    items.extend(["observer", "water (wireframe)", "straw, true outline"].map(String::from));
    if let Some(name) = first {
        items.push(format!("{name}, behind the others"));
    }
    let width: i32 = items.iter().map(|s| 30 + text_width(s, 14.0) + 22).sum();
    let mut x = ((FIGURE_WIDTH as i32 - width) / 2).max(10);
    for (k, s) in items.iter().enumerate() {
        match k {
            k if k < SECTION_COUNT => {
                let c = section_rgb8(k as u8 + 1);
                root.draw(&Rectangle::new(
                    [(x + 8, y - 7), (x + 22, y + 7)],
                    RGBColor(c[0], c[1], c[2]).filled(),
                ))?;
            }
            k if k == SECTION_COUNT => {
                root.draw(&Circle::new((x + 15, y), 5, BLACK.filled()))?;
            }
            k if k == SECTION_COUNT + 1 => {
                root.draw(&PathElement::new(
                    vec![(x, y), (x + 24, y)],
                    rgb(WATER_RGB).stroke_width(2),
                ))?;
            }
            k if k == SECTION_COUNT + 2 => dashed(
                root,
                &[(x as f64, y as f64), (x as f64 + 24.0, y as f64)],
                rgb(STRAW_OUTLINE_RGB),
            )?,
            _ => {
                let c = GHOST_RGB;
                root.draw(&Rectangle::new(
                    [(x + 8, y - 7), (x + 22, y + 7)],
                    RGBColor(c[0], c[1], c[2]).filled(),
                ))?;
            }
        }
        root.draw(&Text::new(s.clone(), (x + 30, y), style.clone()))?;
        x += 30 + text_width(s, 14.0) + 22;
    }
    Ok(())
}

/// Size of the gap plot (px).
pub const GAP_PLOT_SIZE: (u32, u32) = (1200, 700);
/// Margin around the gap plot (px).
const GAP_MARGIN: u32 = 20;
/// Room for the x axis's tick labels and name (px).
const GAP_X_LABELS: u32 = 60;
/// Room for the y axis's tick labels and name (px).
const GAP_Y_LABELS: u32 = 80;
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
/// straw point, into the PNG at `path`.
pub fn write_gap_plot(path: &Path, series: &[GapSeries], title: &str) -> CliResult {
    let png = render_gap_plot(series, title).map_err(draw_err(path))?;
    files::write_bytes(path, &png)
}

/// The gap plot as PNG bytes.
fn render_gap_plot(series: &[GapSeries], title: &str) -> Result<Vec<u8>, String> {
    register_font();
    let (w, h) = GAP_PLOT_SIZE;
    let mut buf = vec![255u8; (w * h * 3) as usize];
    let e = |e: DrawingAreaErrorKind<_>| e.to_string();
    {
        let root = BitMapBackend::with_buffer(&mut buf, (w, h)).into_drawing_area();
        let top = gap_axis_top(series);
        let mut chart = ChartBuilder::on(&root)
            .caption(title, font(22.0))
            .margin(GAP_MARGIN)
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
            .x_desc("height z of the straw point Q (m); bands: the straw's coloured sections")
            .y_desc("gap |course point − model point| (mm)")
            .axis_desc_style(font(16.0))
            .label_style(font(13.0))
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
                chart.draw_series(kept.iter().map(|&p| Circle::new(p, 1, style.filled())))
            } else {
                chart.draw_series(
                    kept.iter()
                        .map(|&p| Cross::new(p, 2, style.stroke_width(1))),
                )
            }
            .map_err(e)?;
        }
        // The legend's entries, in the series' order (plotters lists them in drawing order).
        for (k, s) in series.iter().enumerate() {
            let color = rgb(SERIES_RGB[k % SERIES_RGB.len()]);
            let label = if s.samples.is_empty() {
                format!("{}: no points", s.name)
            } else {
                format!("{} ({} points)", s.name, s.samples.len())
            };
            chart
                .draw_series(std::iter::empty::<Circle<(f64, f64), u32>>())
                .map_err(e)?
                .label(label)
                .legend(move |(x, y)| {
                    if k % 2 == 0 {
                        Circle::new((x + 8, y), 4, color.filled()).into_dyn()
                    } else {
                        Cross::new((x + 8, y), 4, color.stroke_width(2)).into_dyn()
                    }
                });
        }
        if series.is_empty() || series.iter().all(|s| s.samples.is_empty()) {
            let (px, py) = chart.backend_coord(&(STRAW_HEIGHT / 2.0, top / 2.0));
            root.draw(&Text::new(
                "no points",
                (px, py),
                font(20.0).pos(Pos::new(HPos::Center, VPos::Center)),
            ))
            .map_err(e)?;
        }
        if !series.is_empty() {
            chart
                .configure_series_labels()
                .position(SeriesLabelPosition::UpperRight)
                .background_style(WHITE.mix(0.85))
                .border_style(RGBColor(160, 160, 160))
                .label_font(font(14.0))
                .draw()
                .map_err(e)?;
        }
        root.present().map_err(e)?;
    }
    encode_png(&buf, w, h)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::plot::tests::{decode, point};
    use crate::plot::FIGURE_WIDTH;
    use bentstraw_optics::scene::STRAW_RADIUS;

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

    /// The pixel rectangle of column `i` of `n` shown models, row `r` (panel rectangles, by layout).
    fn panel_rect(n: usize, i: usize, r: usize) -> (u32, u32, u32, u32) {
        let pw = FIGURE_WIDTH / n.max(3) as u32;
        let left = (FIGURE_WIDTH - n as u32 * pw) / 2 + i as u32 * pw;
        let top = (TITLE_BAND + r as i32 * ROW_HEIGHT) as u32;
        (left, top, pw, ROW_HEIGHT as u32)
    }

    fn has_colour(img: &image::RgbImage, rect: (u32, u32, u32, u32), c: [u8; 3]) -> bool {
        let (l, t, w, h) = rect;
        (t..t + h).any(|y| (l..l + w).any(|x| img.get_pixel(x, y).0 == c))
    }

    fn render(scene: &Scene, observer: Vec3, models: &[ModelCloud]) -> image::RgbImage {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("models.png");
        write_model_comparison(&path, scene, observer, models, "test").unwrap();
        decode(&std::fs::read(&path).unwrap())
    }

    #[test]
    fn each_panel_shows_the_colours_of_its_own_points_only() {
        let scene = Scene::with_defaults(0.02, 0.01, 0.15).unwrap();
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
        assert_eq!(img.dimensions(), (FIGURE_WIDTH, COMPARISON_HEIGHT));
        let wanted: [&[u8]; 3] = [&[1], &[4], &[2, 5]];
        for (i, codes) in wanted.iter().enumerate() {
            for r in 0..ROWS {
                let rect = panel_rect(3, i, r);
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
        let scene = Scene::with_defaults(0.02, 0.01, 0.15).unwrap();
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
        for r in 0..ROWS {
            let (l0, t, w, h) = panel_rect(3, 0, r);
            let (l1, ..) = panel_rect(3, 1, r);
            let (l2, ..) = panel_rect(3, 2, r);
            let differ = |la: u32, lb: u32| {
                (t..t + h)
                    .flat_map(|y| (0..w).map(move |x| (x, y)))
                    .filter(|&(x, y)| {
                        // Plotters' anti-aliased lines may round one unit differently elsewhere.
                        let (a, b) = (img.get_pixel(la + x, y).0, img.get_pixel(lb + x, y).0);
                        (0..3).any(|c| a[c].abs_diff(b[c]) > 2)
                    })
                    .count()
            };
            assert_eq!(differ(l0, l1), 0, "row {r}: same points, different pixels");
            // The comparison is not vacuous: other points do change the panel.
            assert!(differ(l0, l2) > 100, "row {r}");
        }
    }

    #[test]
    fn shared_box_holds_every_model_and_leaves_off_only_far_points() {
        let scene = Scene::with_defaults(0.02, 0.01, 0.15).unwrap();
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
    fn top_row_looks_level_across_the_observers_line_of_sight() {
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
            // Perpendicular to the observer's horizontal direction, and level: depth along the
            // lines of sight runs across the panel.
            assert!(t.dot(horizontal.normalize()).abs() < 1e-12, "{observer}");
            assert!(t.z.abs() < 1e-12);
            assert!((above.toward_viewer() - Vec3::Z).length() < 1e-12);
        }
    }

    #[test]
    fn empty_models_and_no_models_still_draw() {
        let scene = Scene::with_defaults(0.0, 0.0, 0.0).unwrap();
        let observer = Vec3::new(5.0, 0.0, 0.3);
        for models in [
            vec![],
            vec![ModelCloud {
                name: "empty",
                points: &[],
            }],
        ] {
            let img = render(&scene, observer, &models);
            assert_eq!(img.dimensions(), (FIGURE_WIDTH, COMPARISON_HEIGHT));
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
        write_gap_plot(&path, series, "gap").unwrap();
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
        assert_eq!(img.dimensions(), GAP_PLOT_SIZE);
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
            assert_eq!(gap_image(&series).dimensions(), GAP_PLOT_SIZE);
        }
    }

    #[test]
    fn gap_plot_to_an_unwritable_path_is_an_error() {
        let path = Path::new("/nonexistent-folder/gap.png");
        assert!(write_gap_plot(path, &[], "t").is_err());
    }
}
