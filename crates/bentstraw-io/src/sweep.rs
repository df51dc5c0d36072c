//! Apparent depth against the viewing angle, as files: the sweep's CSV (one row per seat) and its
//! figure (the height of each model's point against the eye's angle).
//!
//! The CSV's header names every column with its unit:
//! `angle_deg` (the turn from the observer's seat round the glass, or the eye's elevation),
//! `eye_x_m,eye_y_m,eye_z_m`, `current` (1 on the observer's own seat), `sight` (`seen`,
//! `not_seen`, `eye_inside`), `path` (the kind of light path, e.g. `top`, `wall+1`), then the
//! course's point `course_*_m`, the eye model's horizontal and vertical focal points on the line
//! of sight `focus_h_*_m`, `focus_v_*_m`, the stereo point `stereo_*_m`, and the eye model's two
//! focal distances `s_h_m`, `s_v_m`. A value that does not exist (a seat that does not see the
//! point, a focus not in front of the eye) is left empty. Numbers in their shortest exact form.

use std::fmt::Write as _;
use std::io::{self, Write};

use bentstraw_optics::apparent::{Sight, SweepRow};
use bentstraw_optics::Vec3;

#[cfg(feature = "figures")]
pub use figure::write_sweep_plot;

/// How far above or below the object point (m) the sweep's figures show a model's point: the
/// question is how deep the point looks, and a focus far away (nearly parallel light) would
/// squash everything else into a line.
pub const SWEEP_SHOWN_SPAN: f64 = 0.1;

/// The heights (m) the sweep's figures show for the object point `point`.
pub fn shown_heights(point: Vec3) -> (f64, f64) {
    (point.z - SWEEP_SHOWN_SPAN, point.z + SWEEP_SHOWN_SPAN)
}

/// The CSV's header line (without its newline).
pub const SWEEP_CSV_HEADER: &str = "angle_deg,eye_x_m,eye_y_m,eye_z_m,current,sight,path,\
course_x_m,course_y_m,course_z_m,focus_h_x_m,focus_h_y_m,focus_h_z_m,\
focus_v_x_m,focus_v_y_m,focus_v_z_m,stereo_x_m,stereo_y_m,stereo_z_m,s_h_m,s_v_m";

/// The four models' points of a seat, in the figure's and the CSV's order: the course's point,
/// the horizontal and vertical focal points, the stereo point.
pub fn model_points(row: &SweepRow) -> [Option<Vec3>; 4] {
    match row.seen() {
        Some(s) => [
            Some(s.course_point()),
            s.horizontal_focus(row.eye),
            s.vertical_focus(row.eye),
            s.stereo_point(),
        ],
        None => [None; 4],
    }
}

/// The word the CSV gives a seat's sight.
fn sight_word(sight: &Sight) -> &'static str {
    match sight {
        Sight::Seen(_) => "seen",
        Sight::NotSeen => "not_seen",
        Sight::EyeInside => "eye_inside",
    }
}

/// Writes the sweep's rows as CSV (see the module's documentation).
pub fn write_sweep_csv(w: &mut dyn Write, rows: &[SweepRow]) -> io::Result<()> {
    let mut out = String::with_capacity(64 + rows.len() * 320);
    out.push_str(SWEEP_CSV_HEADER);
    out.push('\n');
    let number = |out: &mut String, v: Option<f64>| {
        out.push(',');
        if let Some(v) = v.filter(|v| v.is_finite()) {
            let _ = write!(out, "{v}");
        }
    };
    for row in rows {
        let _ = write!(out, "{}", row.angle);
        for v in row.eye.to_array() {
            number(&mut out, Some(v));
        }
        let path = row.seen().map(|s| s.path.key()).unwrap_or_default();
        let _ = write!(
            out,
            ",{},{},{}",
            u8::from(row.current),
            sight_word(&row.sight),
            path
        );
        for p in model_points(row) {
            for k in 0..3 {
                number(&mut out, p.map(|p| p.to_array()[k]));
            }
        }
        let seen = row.seen();
        number(&mut out, seen.and_then(|s| s.apparent.s_h.distance()));
        number(&mut out, seen.and_then(|s| s.apparent.s_v.distance()));
        out.push('\n');
    }
    w.write_all(out.as_bytes())
}

/// The sweep's figure (with the `figures` feature: plotters).
#[cfg(feature = "figures")]
mod figure {
    use std::path::Path;

    use bentstraw_optics::apparent::{SweepKind, SweepRow};
    use bentstraw_optics::Vec3;
    use plotters::coord::Shift;
    use plotters::prelude::*;
    use plotters::style::text_anchor::{HPos, Pos, VPos};

    use super::model_points;
    use crate::error::Result;
    use crate::files;
    use crate::plot::{figure_bytes, font, rgb, FigureFormat, Heading, FIGURE_WIDTH, TEXT};
    use crate::words::{self, Lang};

    /// The figure's size (pixels, before its heading): the chart and its legend.
    const SWEEP_CHART: (u32, u32) = (FIGURE_WIDTH, 900);
    /// The legend's strip under the chart (pixels): three rows.
    const LEGEND_HEIGHT: u32 = 150;
    /// One row of the legend (pixels).
    const LEGEND_ROW: i32 = 42;
    /// The models' colours: the course's point, the two focal lines, the stereo point.
    const MODEL_RGB: [(u8, u8, u8); 4] = [(20, 40, 140), (210, 80, 0), (150, 0, 150), (0, 130, 60)];

    /// Plots the height of each model's point against the eye's angle into `path` (PNG, SVG or PDF
    /// by its extension): one line per model (broken where the seat does not see the point or the
    /// light path changes), the object point's own height dashed, the observer's seat marked.
    /// `limits` bounds the heights shown (m, [`super::shown_heights`]): a focus far away is left
    /// out.
    pub fn write_sweep_plot(
        path: &Path,
        kind: SweepKind,
        rows: &[SweepRow],
        point: Vec3,
        limits: (f64, f64),
        title: &str,
        lang: Lang,
    ) -> Result {
        let heading = Heading::new(title, "");
        let size = (SWEEP_CHART.0, SWEEP_CHART.1 + heading.height() as u32);
        let bytes = figure_bytes(
            path,
            FigureFormat::of(path)?,
            size,
            |root| draw_sweep(root, kind, rows, point, limits, &heading, lang),
            |root| draw_sweep(root, kind, rows, point, limits, &heading, lang),
        )?;
        files::write_bytes(path, &bytes)
    }

    /// The sweep's figure on any backend: the chart, and its legend in a strip under it (the
    /// lines may run anywhere in the chart).
    fn draw_sweep<DB: DrawingBackend>(
        root: &DrawingArea<DB, Shift>,
        kind: SweepKind,
        rows: &[SweepRow],
        point: Vec3,
        limits: (f64, f64),
        heading: &Heading,
        lang: Lang,
    ) -> Result<(), String> {
        let e = |x: DrawingAreaErrorKind<DB::ErrorType>| x.to_string();
        root.fill(&WHITE).map_err(e)?;
        heading.draw(root).map_err(e)?;
        let area = root.margin(heading.height() as u32, 0, 0, 0);
        let (chart_area, legend_area) = area.split_vertically(SWEEP_CHART.1 - LEGEND_HEIGHT);
        // Heights in centimetres: the scene's scale.
        let cm = |z: f64| z * 100.0;
        let shown = |z: f64| z >= limits.0 && z <= limits.1;
        let mut lo = point.z;
        let mut hi = point.z;
        for row in rows {
            for z in model_points(row).iter().flatten().map(|p| p.z) {
                if shown(z) {
                    lo = lo.min(z);
                    hi = hi.max(z);
                }
            }
        }
        let pad = ((hi - lo) * 0.08).max(0.002);
        let (y0, y1) = (cm(lo - pad), cm(hi + pad));
        let (x0, x1) = kind.range();
        // Ticks every 45° round the glass, every 30° up and down.
        let step = match kind {
            SweepKind::Around => 45.0,
            SweepKind::UpDown => 30.0,
        };
        let ticks: Vec<f64> = (0..)
            .map(|k| x0 + k as f64 * step)
            .take_while(|a| *a <= x1)
            .collect();
        let mut chart = ChartBuilder::on(&chart_area)
            .margin(20)
            .margin_right(40)
            .x_label_area_size(100)
            .y_label_area_size(130)
            .build_cartesian_2d(x0..x1, y0..y1)
            .map_err(e)?;
        let x_axis = match kind {
            SweepKind::Around => words::SWEEP_AROUND_AXIS,
            SweepKind::UpDown => words::SWEEP_UPDOWN_AXIS,
        };
        chart
            .configure_mesh()
            .x_desc(lang.of(x_axis))
            .y_desc(lang.of(words::SWEEP_HEIGHT_AXIS))
            .axis_desc_style(font(TEXT))
            .label_style(font(TEXT))
            .y_labels(7)
            // The angle's ticks are drawn below, at round angles.
            .x_labels(0)
            .disable_x_mesh()
            .max_light_lines(1)
            .light_line_style(RGBColor(235, 235, 235))
            .bold_line_style(RGBColor(200, 200, 200))
            .y_label_formatter(&|v| format!("{v:.1}"))
            .draw()
            .map_err(e)?;
        for &a in &ticks {
            chart
                .draw_series(std::iter::once(PathElement::new(
                    vec![(a, y0), (a, y1)],
                    RGBColor(200, 200, 200).stroke_width(1),
                )))
                .map_err(e)?;
            // In the backend's pixels: the root's own.
            let (px, py) = chart.backend_coord(&(a, y0));
            root.draw(&Text::new(
                format!("{a:.0}").replace('-', "−"),
                (px, py + 12),
                font(TEXT).pos(Pos::new(HPos::Center, VPos::Top)),
            ))
            .map_err(e)?;
        }
        // The object point's own height, dashed: where it would seem without refraction.
        let grey = RGBColor(90, 90, 90);
        let dashes = (0..60).map(|k| {
            let a = x0 + (x1 - x0) * k as f64 / 60.0;
            let b = a + (x1 - x0) * 0.55 / 60.0;
            PathElement::new(
                vec![(a, cm(point.z)), (b, cm(point.z))],
                grey.stroke_width(2),
            )
        });
        chart.draw_series(dashes).map_err(e)?;
        // The observer's seat.
        let black = RGBColor(0, 0, 0);
        if let Some(seat) = rows.iter().find(|r| r.current) {
            chart
                .draw_series(std::iter::once(PathElement::new(
                    vec![(seat.angle, y0), (seat.angle, y1)],
                    black.stroke_width(1),
                )))
                .map_err(e)?;
        }
        for (m, &colour) in MODEL_RGB.iter().enumerate() {
            let color = rgb(colour);
            // Runs of seats that see the point along one kind of path.
            let mut runs: Vec<Vec<(f64, f64)>> = Vec::new();
            let mut last_path = None;
            for row in rows {
                let value = model_points(row)[m]
                    .map(|p| p.z)
                    .filter(|&z| shown(z))
                    .map(|z| (row.angle, cm(z)));
                let path = row.seen().map(|s| s.path);
                match value {
                    Some(v) if path == last_path && !runs.is_empty() => {
                        runs.last_mut().expect("a run").push(v)
                    }
                    Some(v) => runs.push(vec![v]),
                    None => runs.push(Vec::new()),
                }
                last_path = if value.is_some() { path } else { None };
            }
            let style = color.stroke_width(if m == 0 { 4 } else { 3 });
            for run in runs.iter().filter(|r| !r.is_empty()) {
                chart
                    .draw_series(LineSeries::new(run.iter().copied(), style))
                    .map_err(e)?;
                chart
                    .draw_series(run.iter().map(|&p| Circle::new(p, 4, color.filled())))
                    .map_err(e)?;
            }
        }
        // The legend: two columns, three rows, a sample of each line and its words.
        let entries = words::SWEEP_MODELS
            .iter()
            .enumerate()
            .map(|(m, name)| (lang.of(*name), Mark::Line(rgb(MODEL_RGB[m]))))
            .chain([
                (lang.of(words::SWEEP_TRUE), Mark::Dashed(grey)),
                (lang.of(words::SWEEP_SEAT), Mark::Upright(black)),
            ]);
        let (width, _) = legend_area.dim_in_pixel();
        let column = width as i32 / 2;
        for (k, (label, mark)) in entries.enumerate() {
            let x = 60 + (k as i32 / 3) * column;
            let y = 20 + (k as i32 % 3) * LEGEND_ROW;
            match mark {
                Mark::Line(c) => legend_area.draw(&PathElement::new(
                    vec![(x, y), (x + 50, y)],
                    c.stroke_width(5),
                )),
                Mark::Dashed(c) => (0..3).try_for_each(|d| {
                    let a = x + d * 20;
                    legend_area.draw(&PathElement::new(
                        vec![(a, y), (a + 12, y)],
                        c.stroke_width(3),
                    ))
                }),
                Mark::Upright(c) => legend_area.draw(&PathElement::new(
                    vec![(x + 25, y - 14), (x + 25, y + 14)],
                    c.stroke_width(2),
                )),
            }
            .map_err(e)?;
            legend_area
                .draw(&Text::new(
                    label.to_string(),
                    (x + 66, y),
                    font(TEXT).pos(Pos::new(HPos::Left, VPos::Center)),
                ))
                .map_err(e)?;
        }
        root.present().map_err(e)?;
        Ok(())
    }

    /// How a legend entry's sample is drawn.
    enum Mark {
        /// A model's line, in its colour.
        Line(RGBColor),
        /// The object point's own height, dashed.
        Dashed(RGBColor),
        /// The observer's seat, an upright line.
        Upright(RGBColor),
    }
}

#[cfg(all(test, feature = "figures"))]
mod tests {
    use super::*;
    use crate::words::{self, Lang};
    use bentstraw_optics::apparent::SweepKind;
    use bentstraw_optics::apparent::{default_sweep_point, sweep_apparent, Sweep};
    use bentstraw_optics::sampling::sample_image;
    use bentstraw_optics::scene::{REFERENCES, SCENE_CENTRE, WATER_INDEX};
    use bentstraw_optics::setup::Setup;

    /// The CSV: one header, one row per seat with as many fields, numbers read back exactly.
    #[test]
    fn the_csv_has_a_row_per_seat_and_reads_back_exactly() {
        let r = REFERENCES[1];
        let setup = Setup::assignment(r.scene(WATER_INDEX), r.observer);
        let cloud = sample_image(&setup.world, r.observer, 300, &|_| {});
        let p = default_sweep_point(&cloud.points).unwrap();
        let sweep = Sweep {
            kind: SweepKind::UpDown,
            centre: SCENE_CENTRE,
            rows: 31,
        };
        let rows = sweep_apparent(&setup, r.observer, p.straw_point, Some(p.direction), &sweep);
        let mut bytes = Vec::new();
        write_sweep_csv(&mut bytes, &rows).unwrap();
        let text = String::from_utf8(bytes).unwrap();
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(lines[0], SWEEP_CSV_HEADER);
        assert_eq!(lines.len(), rows.len() + 1);
        let columns = SWEEP_CSV_HEADER.split(',').count();
        for (line, row) in lines[1..].iter().zip(&rows) {
            let f: Vec<&str> = line.split(',').collect();
            assert_eq!(f.len(), columns, "{line}");
            assert_eq!(f[0].parse::<f64>().unwrap(), row.angle);
            assert_eq!(f[4], if row.current { "1" } else { "0" });
            if row.current {
                let course: f64 = f[9].parse().unwrap();
                assert_eq!(course, p.position.z);
                assert_eq!(f[5], "seen");
            }
            if f[5] != "seen" {
                assert!(f[7..].iter().all(|v| v.is_empty()), "{line}");
            }
        }
        let dir = tempfile::tempdir().unwrap();
        let svg = dir.path().join("sweep.svg");
        for lang in [Lang::En, Lang::Fr] {
            write_sweep_plot(
                &svg,
                sweep.kind,
                &rows,
                p.straw_point,
                (-0.2, 0.4),
                "sweep",
                lang,
            )
            .unwrap();
            let text = std::fs::read_to_string(&svg).unwrap();
            assert!(text.contains(lang.of(words::SWEEP_UPDOWN_AXIS).split(' ').next().unwrap()));
        }
    }
}
