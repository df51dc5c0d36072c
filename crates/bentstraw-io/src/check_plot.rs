//! The figure of `bentstraw check`: the true image pale, the solution's points over it, wrong points
//! marked by kind, missing regions outlined; PNG, SVG or PDF from the same drawing code.

use std::path::Path;

use bentstraw_optics::check::{CheckReport, ClaimedPoint, VerdictKind};
use bentstraw_optics::Vec3;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use crate::error::Result;
use crate::files;
use crate::plot::{
    axis_box, dashed, draw_axis_labels, draw_legend_cell, draw_observer, draw_panes,
    draw_straw_outline, draw_water, figure_bytes, figure_views, font, layout, legend_cell,
    section_rgb8, three_view_size, AreaOn, DrawResultOn, FigureFormat, Heading, LegendMark, Panel,
    TEXT,
};
use bentstraw_optics::setup::Setup;

/// Most true-image samples and correct points drawn per panel in a PNG (an even subset beyond that).
const MAX_DRAWN_PNG: (usize, usize) = (30_000, 40_000);
/// The same in an SVG, where every point is an element of the file (keeps it to a few megabytes).
const MAX_DRAWN_SVG: (usize, usize) = (4_000, 6_000);
/// Most wrong points marked.
const MAX_MARKED: usize = 5_000;
/// Missing regions outlined (the largest, numbered as in the summary).
const MAX_OUTLINED: usize = 12;

/// The marker colour of a kind of wrong point.
fn kind_rgb(kind: VerdictKind) -> RGBColor {
    match kind {
        VerdictKind::Correct => RGBColor(0, 0, 0),
        VerdictKind::WrongColour => RGBColor(0, 0, 0),
        VerdictKind::WrongLength => RGBColor(150, 75, 0),
        VerdictKind::NoStraw => RGBColor(110, 110, 110),
        VerdictKind::TooManyEvents => RGBColor(0, 150, 150),
    }
}

/// A section's colour faded towards white: the true image in the background.
fn pale(code: u8) -> RGBColor {
    let c = section_rgb8(code);
    let f = |v: u8| (0.3 * v as f64 + 0.7 * 255.0).round() as u8;
    RGBColor(f(c[0]), f(c[1]), f(c[2]))
}

/// Draws the check figure of `points` (the solution) and `report` into `path` (.png, .svg or .pdf).
pub fn write_check_figure(
    path: &Path,
    scene: &Setup,
    observer: Vec3,
    points: &[ClaimedPoint],
    report: &CheckReport,
    title: &str,
) -> Result {
    let format = FigureFormat::of(path)?;
    let bytes = check_figure_bytes(path, format, scene, observer, points, report, title)?;
    files::write_bytes(path, &bytes)
}

/// The check figure's bytes in `format` (`name` names it in an error).
pub fn check_figure_bytes(
    name: &Path,
    format: FigureFormat,
    scene: &Setup,
    observer: Vec3,
    points: &[ClaimedPoint],
    report: &CheckReport,
    title: &str,
) -> Result<Vec<u8>> {
    let heading = check_heading(report, title, colours(scene));
    figure_bytes(
        name,
        format,
        three_view_size(&heading),
        |root| {
            draw_check(
                root,
                scene,
                observer,
                points,
                report,
                &heading,
                MAX_DRAWN_PNG,
            )
            .map_err(|x| x.to_string())
        },
        |root| {
            draw_check(
                root,
                scene,
                observer,
                points,
                report,
                &heading,
                MAX_DRAWN_SVG,
            )
            .map_err(|x| x.to_string())
        },
    )
}

/// The check figure's heading: `title`, then the tally and the coverage.
fn check_heading(report: &CheckReport, title: &str, colours: usize) -> Heading {
    let t = &report.tally;
    let cov: Vec<String> = (0..colours)
        .map(|k| format!("{:.0} %", 100.0 * report.coverage.per_colour[k].share()))
        .collect();
    let sub = format!(
        "{} points: {} correct, {} wrong colour, {} wrong length, {} no straw, {} need more events · \
         coverage per colour 1–{colours}: {} · lengths in metres, one scale for both axes of a panel",
        t.points,
        t.correct,
        t.wrong_colour,
        t.wrong_length,
        t.no_straw,
        t.too_many_events,
        cov.join(", ")
    );
    Heading::new(title, &sub)
}

/// How many colour codes the scene can show.
fn colours(scene: &Setup) -> usize {
    scene.colour_names().len()
}

/// Whether pixel `(x, y)` lies inside `panel`.
fn inside(panel: &Panel, (x, y): (f64, f64)) -> bool {
    x >= panel.left as f64
        && x < (panel.left + panel.width) as f64
        && y >= panel.top as f64
        && y < (panel.top + panel.height) as f64
}

/// Every `stride`-th index so that at most `max` of `n` remain.
fn stride(n: usize, max: usize) -> usize {
    n.div_ceil(max).max(1)
}

/// The figure on any backend: the same code draws the PNG and the SVG.
fn draw_check<DB: DrawingBackend>(
    root: &AreaOn<DB>,
    scene: &Setup,
    observer: Vec3,
    points: &[ClaimedPoint],
    report: &CheckReport,
    heading: &Heading,
    (max_background, max_correct): (usize, usize),
) -> DrawResultOn<DB> {
    root.fill(&WHITE)?;
    heading.draw(root)?;
    let truth = &report.truth.points;
    let bx = axis_box(scene, observer, truth);
    let panels = layout(&bx, &figure_views(observer), heading.height());
    for panel in &panels {
        let proj = &panel.proj;
        draw_panes(root, panel, &bx)?;
        draw_water(root, proj, scene, false)?;
        draw_straw_outline(root, proj, scene)?;
        // The true image, pale.
        for p in truth.iter().step_by(stride(truth.len(), max_background)) {
            let (x, y) = proj.pixel(p.position);
            if inside(panel, (x, y)) {
                let (x, y) = (x.round() as i32, y.round() as i32);
                root.draw(&Rectangle::new(
                    [(x - 1, y - 1), (x + 1, y + 1)],
                    pale(p.color).filled(),
                ))?;
            }
        }
        // The correct points in their colours, far to near.
        let correct: Vec<usize> = (0..points.len())
            .filter(|&i| report.judged[i].verdict.kind() == VerdictKind::Correct)
            .collect();
        let mut shown: Vec<(f64, usize)> = correct
            .iter()
            .step_by(stride(correct.len(), max_correct))
            .map(|&i| (proj.nearness(points[i].position), i))
            .collect();
        shown.sort_by(|a, b| a.0.total_cmp(&b.0));
        for (_, i) in shown {
            let p = &points[i];
            let (x, y) = proj.pixel(p.position);
            if inside(panel, (x, y)) {
                let c = section_rgb8(p.color);
                let (x, y) = (x.round() as i32, y.round() as i32);
                root.draw(&Rectangle::new(
                    [(x - 1, y - 1), (x + 2, y + 2)],
                    RGBColor(c[0], c[1], c[2]).filled(),
                ))?;
            }
        }
        // The missing regions, outlined and numbered as in the summary.
        for (n, m) in report
            .coverage
            .missing
            .iter()
            .take(MAX_OUTLINED)
            .enumerate()
        {
            let px: Vec<(f64, f64)> = m
                .samples
                .iter()
                .map(|&i| proj.pixel(truth[i].position))
                .collect();
            let mut hull = convex_hull(&px);
            if let Some(&first) = hull.first() {
                hull.push(first);
                dashed(root, &hull, BLACK)?;
                let top = hull
                    .iter()
                    .copied()
                    .fold(first, |a, b| if b.1 < a.1 { b } else { a });
                if inside(panel, top) {
                    root.draw(&Text::new(
                        (n + 1).to_string(),
                        (top.0.round() as i32, top.1.round() as i32 - 4),
                        font(TEXT).pos(Pos::new(HPos::Center, VPos::Bottom)),
                    ))?;
                }
            }
        }
        // The wrong points, marked by kind.
        let wrong: Vec<usize> = (0..points.len())
            .filter(|&i| report.judged[i].verdict.kind() != VerdictKind::Correct)
            .collect();
        for &i in wrong.iter().step_by(stride(wrong.len(), MAX_MARKED)) {
            let kind = report.judged[i].verdict.kind();
            let (x, y) = proj.pixel(points[i].position);
            if inside(panel, (x, y)) {
                marker(root, (x.round() as i32, y.round() as i32), kind)?;
            }
        }
        draw_water(root, proj, scene, true)?;
        draw_axis_labels(root, panel, &bx)?;
        draw_observer(root, panel, &bx, observer, &[])?;
    }
    draw_check_legend(root, report, legend_cell(heading.height()), scene)
}

/// The mark of a wrong point: a cross for a wrong colour or length, a ring for no straw or too
/// many events.
fn marker<DB: DrawingBackend>(
    root: &AreaOn<DB>,
    (x, y): (i32, i32),
    kind: VerdictKind,
) -> DrawResultOn<DB> {
    let c = kind_rgb(kind);
    match kind {
        VerdictKind::WrongColour | VerdictKind::WrongLength => {
            let s = c.stroke_width(2);
            root.draw(&PathElement::new(vec![(x - 3, y - 3), (x + 3, y + 3)], s))?;
            root.draw(&PathElement::new(vec![(x - 3, y + 3), (x + 3, y - 3)], s))
        }
        _ => root.draw(&Circle::new((x, y), 3, c.stroke_width(2))),
    }
}

/// The legend: colours of the sections, the marks of the wrong points, the outlines.
fn draw_check_legend<DB: DrawingBackend>(
    root: &AreaOn<DB>,
    report: &CheckReport,
    cell: (i32, i32, i32, i32),
    scene: &Setup,
) -> DrawResultOn<DB> {
    let mut items: Vec<(LegendMark, String)> =
        vec![(LegendMark::None, "pale: true, full: correct".to_string())];
    let names = scene.colour_names();
    for (k, name) in names.iter().enumerate() {
        let full = section_rgb8(k as u8 + 1);
        let p = pale(k as u8 + 1);
        items.push((
            LegendMark::TwoSwatches([p.0, p.1, p.2], full),
            format!("{} {name}", k + 1),
        ));
    }
    let kinds = [
        VerdictKind::WrongColour,
        VerdictKind::WrongLength,
        VerdictKind::NoStraw,
        VerdictKind::TooManyEvents,
    ];
    let first_kind = items.len();
    for (kind, short) in kinds.iter().zip([
        "wrong colour",
        "wrong length",
        "no straw",
        "too many events",
    ]) {
        items.push((
            LegendMark::Room,
            format!("{short}: {}", report.tally.count(*kind)),
        ));
    }
    items.push((
        LegendMark::Dashed((0, 0, 0)),
        "missing (numbered)".to_string(),
    ));
    let rows = draw_legend_cell(root, cell, &items)?;
    // The wrong points' marks, where the cell left room before their lines.
    for (k, kind) in kinds.iter().enumerate() {
        marker(root, (cell.0 + 46, rows[first_kind + k]), *kind)?;
    }
    Ok(())
}

/// The convex hull of pixel positions, counter-clockwise on screen (Andrew's monotone chain).
fn convex_hull(points: &[(f64, f64)]) -> Vec<(f64, f64)> {
    let mut p: Vec<(f64, f64)> = points
        .iter()
        .copied()
        .filter(|q| q.0.is_finite() && q.1.is_finite())
        .collect();
    p.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.total_cmp(&b.1)));
    p.dedup();
    if p.len() < 3 {
        return p;
    }
    let cross = |o: (f64, f64), a: (f64, f64), b: (f64, f64)| {
        (a.0 - o.0) * (b.1 - o.1) - (a.1 - o.1) * (b.0 - o.0)
    };
    let mut hull: Vec<(f64, f64)> = Vec::with_capacity(2 * p.len());
    for pass in 0..2 {
        let start = hull.len();
        let iter: Box<dyn Iterator<Item = &(f64, f64)>> = if pass == 0 {
            Box::new(p.iter())
        } else {
            Box::new(p.iter().rev())
        };
        for &q in iter {
            while hull.len() >= start + 2
                && cross(hull[hull.len() - 2], hull[hull.len() - 1], q) <= 0.0
            {
                hull.pop();
            }
            hull.push(q);
        }
        hull.pop();
    }
    hull
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::plot::tests::decode;
    use crate::plot::{CELL_HEIGHT, FIGURE_WIDTH};
    use bentstraw_optics::check::{check_solution, DEFAULT_TOLERANCE};
    use bentstraw_optics::sampling::sample_image;
    use bentstraw_optics::scene::REFERENCES;
    use bentstraw_optics::scene::SECTION_COUNT;

    /// The figure of reference 2's own points, changed by `change`, as decoded pixels.
    fn figure(change: impl Fn(usize, &mut ClaimedPoint) -> bool) -> (image::RgbImage, i32) {
        let r = &REFERENCES[1];
        let scene = Setup::assignment(r.scene(1.333), r.observer);
        let cloud = sample_image(&scene.world, r.observer, 3000, &|_| {});
        let mut points = Vec::new();
        for (i, p) in cloud.points.iter().enumerate() {
            let mut c = ClaimedPoint {
                position: p.position,
                color: p.color,
            };
            if change(i, &mut c) {
                points.push(c);
            }
        }
        let report = check_solution(&scene.world, r.observer, &points, DEFAULT_TOLERANCE, 0.98);
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("f.png");
        write_check_figure(&path, &scene, r.observer, &points, &report, "t").unwrap();
        let top = check_heading(&report, "t", SECTION_COUNT).height();
        (decode(&std::fs::read(path).unwrap()), top)
    }

    /// Whether colour `c` appears in the panels (not the heading or the legend's cell).
    fn in_panels((img, top): &(image::RgbImage, i32), c: RGBColor) -> bool {
        let (top, cell) = (*top as u32, CELL_HEIGHT as u32);
        img.enumerate_pixels().any(|(x, y, p)| {
            let legend = x >= FIGURE_WIDTH / 2 && y >= top + cell;
            y >= top && y < top + 2 * cell && !legend && p.0 == [c.0, c.1, c.2]
        })
    }

    #[test]
    fn figure_shows_the_true_image_pale_the_points_full_and_wrong_lengths_marked() {
        let magenta = section_rgb8(3);
        let full = RGBColor(magenta[0], magenta[1], magenta[2]);
        // Magenta removed: its true image shows pale, no magenta point in full colour.
        let img = figure(|_, p| p.color != 3);
        assert!(in_panels(&img, pale(3)) && !in_panels(&img, full));
        assert!(!in_panels(&img, kind_rgb(VerdictKind::WrongLength)));
        // Every 50th point 1 mm too far: marked in the wrong-length colour; magenta back in full.
        let img = figure(|i, p| {
            if i % 50 == 0 {
                let o = REFERENCES[1].observer;
                p.position += 1e-3 * (p.position - o).normalize();
            }
            true
        });
        assert!(in_panels(&img, kind_rgb(VerdictKind::WrongLength)));
        assert!(in_panels(&img, full));
    }

    #[test]
    fn hull_of_a_square_with_inner_points_is_its_corners() {
        let pts = [
            (0.0, 0.0),
            (2.0, 0.0),
            (2.0, 2.0),
            (0.0, 2.0),
            (1.0, 1.0),
            (1.0, 0.0),
        ];
        let mut h = convex_hull(&pts);
        h.sort_by(|a, b| a.partial_cmp(b).unwrap());
        assert_eq!(h, vec![(0.0, 0.0), (0.0, 2.0), (2.0, 0.0), (2.0, 2.0)]);
        assert_eq!(convex_hull(&[(1.0, 1.0)]), vec![(1.0, 1.0)]);
    }
}
