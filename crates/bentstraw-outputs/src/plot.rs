//! The classic figure: the image points in their section colours, the water as a
//! wireframe, the observer, equal axes, three views (front, side, from above) in a 2 × 2 grid with
//! the legend in the fourth cell; and what every figure shares: one pipeline writing PNG, SVG or
//! PDF by the file's extension (`figure_bytes`), text sizes legible at 8.5 cm, headings, legends.
//!
//! The views are orthographic projections computed here (not plotters' 3D charts), so that one metre
//! has the same length on screen along both axes of a panel, and so that the drawing order (back of
//! the glass, points from far to near, front of the glass) is under our control. Each view looks
//! along one axis of the scene, so that each panel has exactly one horizontal and one vertical
//! scale, each a coordinate of the scene.

use std::f64::consts::FRAC_PI_2;
use std::path::Path;
use std::sync::Once;

use bentstraw_optics::image::ImagePoint;
use bentstraw_optics::scene::{SCENE_CENTRE, SECTION_COUNT, SECTION_HEIGHT, SECTION_NAMES};
use bentstraw_optics::world::{COLOR_COUNT, COLOR_NAMES, COLOR_RGB};
use bentstraw_optics::Vec3;
use image::ImageEncoder;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use plotters::style::FontTransform;
use rayon::slice::ParallelSliceMut;

use crate::error::{Error, Result};
use crate::files;
use crate::svg_marks::merge_marks;
use bentstraw_optics::scene::Scene;
use bentstraw_optics::setup::Setup;

/// Width of every figure in pixels (printed 8.5 cm wide: see [`TEXT`]).
pub const FIGURE_WIDTH: u32 = 1000;

/// The font of every text in the figure, shipped with the program so pictures look the same anywhere.
pub(crate) static FONT: &[u8] = include_bytes!("../../../assets/DejaVuSans.ttf");
/// The family name the font is registered under.
const FONT_FAMILY: &str = "sans-serif";
static FONT_ONCE: Once = Once::new();

/// An observer farther out than this many times the scene's size is shown by an arrow, not to scale.
pub(crate) const FAR_OBSERVER_FACTOR: f64 = 2.5;

/// Colour of the water's wireframe.
pub(crate) const WATER_RGB: (u8, u8, u8) = (40, 120, 200);
/// Colour of the straw's true outline.
pub(crate) const STRAW_OUTLINE_RGB: (u8, u8, u8) = (120, 120, 120);

/// The axis ranges of a figure: one box holding the glass, the straw, every image point and (when not
/// too far) the observer. Drawn with one scale for all axes, so the ranges may differ in length.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct AxisBox {
    /// Lower corner (m).
    pub min: Vec3,
    /// Upper corner (m).
    pub max: Vec3,
    /// Whether the observer is inside the box (drawn to scale), or too far and drawn as an arrow.
    pub observer_inside: bool,
    /// For a far observer: tail and tip of an arrow pointing to it, in room left for it in the box.
    pub observer_arrow: Option<(Vec3, Vec3)>,
}

impl AxisBox {
    /// Centre of the box.
    pub fn centre(&self) -> Vec3 {
        0.5 * (self.min + self.max)
    }

    /// The eight corners, corner `i` taking `max` on axis `a` when bit `a` of `i` is set.
    pub fn corners(&self) -> [Vec3; 8] {
        std::array::from_fn(|i| {
            Vec3::new(
                if i & 1 != 0 { self.max.x } else { self.min.x },
                if i & 2 != 0 { self.max.y } else { self.min.y },
                if i & 4 != 0 { self.max.z } else { self.min.z },
            )
        })
    }

    /// Whether `p` lies in the box.
    #[cfg(test)]
    pub fn contains(&self, p: Vec3) -> bool {
        p.cmpge(self.min).all() && p.cmple(self.max).all()
    }
}

/// The axis box of a figure: tight around the scene (glass and straw, or a world's container and
/// objects) and the points, with a margin; the observer is included unless that would make the
/// box more than [`FAR_OBSERVER_FACTOR`] times larger.
pub(crate) fn axis_box(scene: &Setup, observer: Vec3, points: &[ImagePoint]) -> AxisBox {
    let (mut lo, mut hi, centre) = scene.frame();
    for p in points {
        if p.position.is_finite() {
            lo = lo.min(p.position);
            hi = hi.max(p.position);
        }
    }
    let size = (hi - lo).max_element();
    let (with_lo, with_hi) = (lo.min(observer), hi.max(observer));
    let observer_inside = (with_hi - with_lo).max_element() <= FAR_OBSERVER_FACTOR * size;
    let mut observer_arrow = None;
    if observer_inside {
        lo = with_lo;
        hi = with_hi;
    } else {
        // Widen the box a little towards the observer and put an arrow pointing to it there.
        let c = centre;
        let d = (observer - c).normalize();
        let exit = (0..3)
            .filter(|&a| d[a].abs() > 1e-12)
            .map(|a| ((if d[a] > 0.0 { hi[a] } else { lo[a] }) - c[a]) / d[a])
            .fold(f64::INFINITY, f64::min);
        let tail = c + (exit + 0.04 * size) * d;
        let tip = c + (exit + 0.3 * size) * d;
        lo = lo.min(tip);
        hi = hi.max(tip);
        observer_arrow = Some((tail, tip));
    }
    // One margin for all axes, so the observer's marker and the outermost points are not on the edge.
    let margin = 0.04 * (hi - lo).max_element();
    AxisBox {
        min: lo - Vec3::splat(margin),
        max: hi + Vec3::splat(margin),
        observer_inside,
        observer_arrow,
    }
}

/// A direction to look at the scene from: azimuth from +x towards +y, elevation above the horizon.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct ViewDirection {
    /// Azimuth of the viewer as seen from the scene (rad).
    pub azimuth: f64,
    /// Elevation of the viewer above the horizontal plane (rad).
    pub elevation: f64,
}

impl ViewDirection {
    /// Unit vector from the scene towards the viewer.
    pub fn toward_viewer(&self) -> Vec3 {
        let (se, ce) = self.elevation.sin_cos();
        let (sa, ca) = self.azimuth.sin_cos();
        Vec3::new(ce * ca, ce * sa, se)
    }

    /// Unit vector pointing right on the screen (always horizontal, so `z` stays upright).
    pub fn right(&self) -> Vec3 {
        let (sa, ca) = self.azimuth.sin_cos();
        Vec3::new(-sa, ca, 0.0)
    }

    /// Unit vector pointing up on the screen.
    pub fn up(&self) -> Vec3 {
        self.toward_viewer().cross(self.right())
    }
}

/// The observer's direction as seen from the scene's centre (straight down or up: azimuth −90°).
pub(crate) fn observer_direction(observer: Vec3) -> ViewDirection {
    let d = observer - SCENE_CENTRE;
    let horizontal = d.x.hypot(d.y);
    let azimuth = if horizontal < 1e-12 {
        -FRAC_PI_2
    } else {
        d.y.atan2(d.x)
    };
    ViewDirection {
        azimuth,
        elevation: d.z.atan2(horizontal),
    }
}

/// The name of the direction a level view looks from, e.g. "+x".
fn from_words(azimuth: f64) -> &'static str {
    let quarter = ((azimuth / FRAC_PI_2).round() as i64).rem_euclid(4);
    ["+x", "+y", "−x", "−y"][quarter as usize]
}

/// The three views of the figure with their captions (one entry a line): a level front view from
/// the axis direction nearest the observer's azimuth, a level side view a quarter turn from it with
/// the observer's side on the right, and the view from above, x to the right and y up. Each looks
/// along an axis of the scene, so that a panel's scales are two of x, y and z; z is always up.
pub(crate) fn figure_views(observer: Vec3) -> [(ViewDirection, Vec<String>); 3] {
    let o = observer_direction(observer);
    let front = (o.azimuth / FRAC_PI_2).round() * FRAC_PI_2;
    let side = front - FRAC_PI_2;
    let level = |azimuth| ViewDirection {
        azimuth,
        elevation: 0.0,
    };
    [
        (
            level(front),
            vec![
                format!("front view, from {}", from_words(front)),
                "(the observer's side)".to_string(),
            ],
        ),
        (
            level(side),
            vec![
                format!("side view, from {}", from_words(side)),
                "(observer to the right)".to_string(),
            ],
        ),
        (
            ViewDirection {
                azimuth: -FRAC_PI_2,
                elevation: FRAC_PI_2,
            },
            vec!["top view, from above".to_string(), "(x →, y ↑)".to_string()],
        ),
    ]
}

/// A number rounded to a whole, never written "-0".
pub(crate) fn whole(v: f64) -> String {
    let r = v.round();
    if r == 0.0 {
        "0".to_string()
    } else {
        format!("{r:.0}")
    }
}

/// An angle in degrees in (−180, 180].
pub(crate) fn degrees(angle: f64) -> f64 {
    let mut d = angle.to_degrees() % 360.0;
    if d > 180.0 {
        d -= 360.0;
    } else if d <= -180.0 {
        d += 360.0;
    }
    d
}

/// An orthographic projection of the scene into one panel of the figure.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Projection {
    right: Vec3,
    up: Vec3,
    toward: Vec3,
    centre: Vec3,
    /// Pixel where `centre` lands.
    origin: (f64, f64),
    /// Pixels per metre, the same along every axis.
    pub scale: f64,
}

impl Projection {
    /// A projection of `view` putting `centre` at pixel `origin`, `scale` pixels per metre.
    pub fn new(view: ViewDirection, centre: Vec3, origin: (f64, f64), scale: f64) -> Self {
        Projection {
            right: view.right(),
            up: view.up(),
            toward: view.toward_viewer(),
            centre,
            origin,
            scale,
        }
    }

    /// Pixel coordinates of `p` (x to the right, y down).
    pub fn pixel(&self, p: Vec3) -> (f64, f64) {
        let d = p - self.centre;
        (
            self.origin.0 + self.scale * d.dot(self.right),
            self.origin.1 - self.scale * d.dot(self.up),
        )
    }

    /// Pixel coordinates rounded for drawing.
    pub fn at(&self, p: Vec3) -> (i32, i32) {
        let (x, y) = self.pixel(p);
        (x.round() as i32, y.round() as i32)
    }

    /// How near `p` is to the viewer (larger is nearer).
    pub fn nearness(&self, p: Vec3) -> f64 {
        (p - self.centre).dot(self.toward)
    }
}

/// Pixels per metre that fit the box, seen from `view`, in a `width` × `height` area.
pub(crate) fn fit_scale(bx: &AxisBox, view: ViewDirection, width: f64, height: f64) -> f64 {
    let c = bx.centre();
    let (r, u) = (view.right(), view.up());
    let (mut hw, mut hh) = (0f64, 0f64);
    for k in bx.corners() {
        hw = hw.max((k - c).dot(r).abs());
        hh = hh.max((k - c).dot(u).abs());
    }
    (width / (2.0 * hw.max(1e-9))).min(height / (2.0 * hh.max(1e-9)))
}

/// A step between axis ticks giving about `count` ticks over `span`: 1, 2 or 5 times a power of ten.
pub(crate) fn tick_step(span: f64, count: f64) -> f64 {
    let raw = (span / count).max(1e-12);
    let power = 10f64.powf(raw.log10().floor());
    let m = raw / power;
    let nice = if m < 1.5 {
        1.0
    } else if m < 3.5 {
        2.0
    } else if m < 7.5 {
        5.0
    } else {
        10.0
    };
    nice * power
}

/// The tick values within `[lo, hi]` for `step`.
pub(crate) fn ticks(lo: f64, hi: f64, step: f64) -> Vec<f64> {
    let first = (lo / step).ceil() as i64;
    let last = (hi / step).floor() as i64;
    (first..=last).map(|k| k as f64 * step).collect()
}

/// A tick label with as many decimals as the step needs.
pub(crate) fn tick_label(value: f64, step: f64) -> String {
    let decimals = (-step.log10().floor()).max(0.0) as usize;
    let s = format!("{:.*}", decimals, value);
    // "-0.00" reads as a different number from "0.00".
    if s.starts_with('-') && s[1..].chars().all(|c| c == '0' || c == '.') {
        s[1..].to_string()
    } else {
        s
    }
}

/// Loads the shipped font into plotters, once.
pub(crate) fn register_font() {
    FONT_ONCE.call_once(|| {
        // The font is compiled in and known good; a failure here is a build defect.
        plotters::style::register_font(FONT_FAMILY, FontStyle::Normal, FONT)
            .unwrap_or_else(|_| panic!("the shipped font {FONT_FAMILY} does not load"));
    });
}

/// A plotters colour from 8-bit RGB.
pub(crate) fn rgb(c: (u8, u8, u8)) -> RGBColor {
    RGBColor(c.0, c.1, c.2)
}

/// The display colour of colour code `code` (1..=5 a straw's sections, 6..=8 a coin, a card and
/// its picture), as 8-bit RGB.
pub(crate) fn section_rgb8(code: u8) -> [u8; 3] {
    let c = COLOR_RGB[(code.clamp(1, COLOR_COUNT as u8) - 1) as usize];
    [
        (c[0] * 255.0).round() as u8,
        (c[1] * 255.0).round() as u8,
        (c[2] * 255.0).round() as u8,
    ]
}

/// A number in its shortest exact form, for captions.
pub(crate) fn num(v: f64) -> String {
    format!("{v}")
}

/// A point as `(x, y, z)` in the shortest exact form.
pub(crate) fn triple(p: Vec3) -> String {
    format!("({}, {}, {})", num(p.x), num(p.y), num(p.z))
}

/// Counts of points per section code 1..=5.
pub(crate) fn counts(points: &[ImagePoint]) -> [usize; SECTION_COUNT] {
    let mut n = [0; SECTION_COUNT];
    for p in points {
        if (1..=SECTION_COUNT as u8).contains(&p.color) {
            n[(p.color - 1) as usize] += 1;
        }
    }
    n
}

/// A drawing area on any backend (bitmap or SVG): the shared drawing code takes these.
pub(crate) type AreaOn<DB> = DrawingArea<DB, plotters::coord::Shift>;
/// What drawing on any backend returns.
pub(crate) type DrawResultOn<DB> =
    Result<(), DrawingAreaErrorKind<<DB as DrawingBackend>::ErrorType>>;

/// One panel: where it is and how it projects.
pub(crate) struct Panel {
    /// How the panel projects the scene.
    pub proj: Projection,
    /// The caption above the panel, one entry a line.
    pub caption: Vec<String>,
    /// Left edge (px).
    pub left: i32,
    /// Top edge (px).
    pub top: i32,
    /// Width (px).
    pub width: i32,
    /// Height (px).
    pub height: i32,
    /// The frame the box is fitted in, where the scales run: left, right, top, bottom (px).
    pub frame: [f64; 4],
}

impl Panel {
    /// The values of world axis `a` at the two ends of the frame along the screen direction it
    /// runs in (left to right, or bottom to top), in increasing order.
    fn frame_range(&self, a: usize) -> (f64, f64) {
        let p = &self.proj;
        let [l, r, t, b] = self.frame;
        let (h, _) = world_axis(p.right);
        let (ends, along) = if a == h {
            ([(l, p.origin.1), (r, p.origin.1)], p.right)
        } else {
            ([(p.origin.0, b), (p.origin.0, t)], p.up)
        };
        let value = |(x, y): (f64, f64)| {
            let d = (x - p.origin.0) * p.right - (y - p.origin.1) * p.up;
            p.centre[a] + d.dot(along) / p.scale * along[a].signum()
        };
        let (u, v) = (value(ends[0]), value(ends[1]));
        (u.min(v), u.max(v))
    }
}

/// Height of one caption line over a panel (px).
pub(crate) const CAPTION_LINE: i32 = 40;
/// Height of a cell of the three-view figure (px): caption, box, scales.
pub(crate) const CELL_HEIGHT: i32 = 600;
/// Room kept left of each panel's box for the vertical scale: tick labels and the axis's name.
pub(crate) const PAD_LEFT: f64 = 150.0;
/// Room kept right of each panel's box (the horizontal scale's last label sticks out).
pub(crate) const PAD_RIGHT: f64 = 40.0;
/// Room kept below each panel's box for the horizontal scale (labels never go on top).
pub(crate) const PAD_BOTTOM: f64 = 100.0;
/// Room kept above each panel's box, under the caption.
pub(crate) const PAD_TOP: f64 = 16.0;

/// Panels in a grid of `columns` cells of `cell_height`, row by row from `top`, each fitting the
/// whole box under a caption of `caption_lines` lines. Panels of the same view get the same scale.
pub(crate) fn grid(
    bx: &AxisBox,
    views: &[(ViewDirection, Vec<String>)],
    top: i32,
    columns: usize,
    cell_height: i32,
    caption_lines: usize,
) -> Vec<Panel> {
    let cell_w = FIGURE_WIDTH as i32 / columns as i32;
    let caption_band = caption_lines as i32 * CAPTION_LINE;
    let fit_w = cell_w as f64 - PAD_LEFT - PAD_RIGHT;
    let fit_h = (cell_height - caption_band) as f64 - PAD_TOP - PAD_BOTTOM;
    views
        .iter()
        .enumerate()
        .map(|(i, (v, caption))| {
            let left = (i % columns) as i32 * cell_w;
            let top = top + (i / columns) as i32 * cell_height;
            let origin = (
                left as f64 + PAD_LEFT + fit_w / 2.0,
                (top + caption_band) as f64 + PAD_TOP + fit_h / 2.0,
            );
            Panel {
                // Each panel has its own scale (a top view fits far more than a side view), but within
                // a panel one metre has the same length along both axes.
                proj: Projection::new(*v, bx.centre(), origin, fit_scale(bx, *v, fit_w, fit_h)),
                caption: caption.clone(),
                left,
                top,
                width: cell_w,
                height: cell_height,
                frame: [
                    left as f64 + PAD_LEFT,
                    left as f64 + PAD_LEFT + fit_w,
                    (top + caption_band) as f64 + PAD_TOP,
                    (top + caption_band) as f64 + PAD_TOP + fit_h,
                ],
            }
        })
        .collect()
}

/// The three panels of the classic figure in a 2 × 2 grid under the heading (the fourth cell holds
/// the legend).
pub(crate) fn layout(bx: &AxisBox, views: &[(ViewDirection, Vec<String>)], top: i32) -> Vec<Panel> {
    grid(bx, views, top, 2, CELL_HEIGHT, 2)
}

/// The legend's cell of the classic figure: (left, top, width, height).
pub(crate) fn legend_cell(top: i32) -> (i32, i32, i32, i32) {
    let w = FIGURE_WIDTH as i32 / 2;
    (w, top + CELL_HEIGHT, w, CELL_HEIGHT)
}

/// The size of the classic figure under `heading`.
pub(crate) fn three_view_size(heading: &Heading) -> (u32, u32) {
    (FIGURE_WIDTH, (heading.height() + 2 * CELL_HEIGHT) as u32)
}

/// Draws the classic three-view figure of `points` seen from `observer` into `path`: PNG, SVG or
/// PDF by its extension.
pub fn write_cloud_figure(
    path: &Path,
    scene: &Setup,
    observer: Vec3,
    points: &[ImagePoint],
    title: &str,
) -> Result {
    let bytes = render_cloud_figure(path, scene, observer, points, title)?;
    files::write_bytes(path, &bytes)
}

/// The classic figure as the bytes of its file (format by `path`'s extension).
pub(crate) fn render_cloud_figure(
    path: &Path,
    scene: &Setup,
    observer: Vec3,
    points: &[ImagePoint],
    title: &str,
) -> Result<Vec<u8>> {
    register_font();
    let heading = cloud_heading(observer, points.len(), title);
    let size = three_view_size(&heading);
    figure_bytes(
        path,
        FigureFormat::of(path)?,
        size,
        |root| draw_cloud_figure(root, scene, observer, points, &heading),
        |root| draw_cloud_figure(root, scene, observer, points, &heading),
    )
}

/// The heading of the classic figure: `title`, then the count, the observer's direction, the scale.
pub(crate) fn cloud_heading(observer: Vec3, n: usize, title: &str) -> Heading {
    let o = observer_direction(observer);
    Heading::new(
        title,
        &format!(
            "{n} image points · the observer looks from azimuth {}°, elevation {}° · lengths in \
             metres, one scale for both axes of a panel",
            whole(degrees(o.azimuth)),
            whole(o.elevation.to_degrees())
        ),
    )
}

/// The classic figure on any backend.
fn draw_cloud_figure<DB: DrawingBackend>(
    root: &AreaOn<DB>,
    scene: &Setup,
    observer: Vec3,
    points: &[ImagePoint],
    heading: &Heading,
) -> Result<(), String> {
    let e = |x: DrawingAreaErrorKind<DB::ErrorType>| x.to_string();
    root.fill(&WHITE).map_err(e)?;
    heading.draw(root).map_err(e)?;
    let bx = axis_box(scene, observer, points);
    let panels = layout(&bx, &figure_views(observer), heading.height());
    for p in &panels {
        // Back to front: panes, the far half of the water, the straw's outline, the points from far
        // to near, the near half of the water, the scales and the observer.
        draw_panes(root, p, &bx).map_err(e)?;
        draw_water(root, &p.proj, scene, false).map_err(e)?;
        draw_straw_outline(root, &p.proj, scene).map_err(e)?;
        let dots = visible_dots(p, &[], points);
        draw_dots(root, &dots).map_err(e)?;
        draw_water(root, &p.proj, scene, true).map_err(e)?;
        draw_axis_labels(root, p, &bx).map_err(e)?;
        draw_observer(root, p, &bx, observer, &dots).map_err(e)?;
    }
    let mut items: Vec<(LegendMark, String)>;
    if scene.assignment_numbers().is_some() {
        let n = counts(points);
        items = vec![(LegendMark::None, "image points by section:".to_string())];
        items.extend((0..SECTION_COUNT).map(|k| {
            (
                LegendMark::Swatch(section_rgb8(k as u8 + 1)),
                format!("{} {}: {}", k + 1, SECTION_NAMES[k], n[k]),
            )
        }));
        items.extend(common_legend(bx.observer_inside));
    } else {
        // The codes the points have: a straw's bands, coins, cards, pictures.
        let mut n = [0usize; COLOR_COUNT];
        for p in points {
            n[p.color as usize - 1] += 1;
        }
        items = vec![(LegendMark::None, "image points by colour:".to_string())];
        items.extend((0..COLOR_COUNT).filter(|&k| n[k] > 0).map(|k| {
            (
                LegendMark::Swatch(COLOR_RGB[k].map(|c| (c * 255.0).round() as u8)),
                format!("{} {}: {}", k + 1, COLOR_NAMES[k], n[k]),
            )
        }));
        let mut common = common_legend(bx.observer_inside);
        common[1].1 = "container and liquids (wireframe)".to_string();
        common[2].1 = "objects, true outlines".to_string();
        items.extend(common);
    }
    draw_legend_cell(root, legend_cell(heading.height()), &items).map_err(e)?;
    Ok(())
}

/// The colour code, name and heights of section `k` (0-based), for legends.
pub(crate) fn section_words(k: usize) -> String {
    format!(
        "{} {}, {:.2}–{:.2} m",
        k + 1,
        SECTION_NAMES[k],
        k as f64 * SECTION_HEIGHT,
        (k + 1) as f64 * SECTION_HEIGHT
    )
}

/// The legend's entries for the observer, the water and the straw's outline.
pub(crate) fn common_legend(observer_inside: bool) -> Vec<(LegendMark, String)> {
    vec![
        (
            LegendMark::Dot,
            if observer_inside {
                "observer".to_string()
            } else {
                "observer (far: arrow)".to_string()
            },
        ),
        (LegendMark::Line(WATER_RGB), "water (wireframe)".to_string()),
        (
            LegendMark::Dashed(STRAW_OUTLINE_RGB),
            "straw, true outline".to_string(),
        ),
    ]
}

/// The mark before a legend's entry.
#[derive(Clone, Copy, Debug)]
pub(crate) enum LegendMark {
    /// A filled square of this colour.
    Swatch([u8; 3]),
    /// Two half squares: a pale and a full colour.
    TwoSwatches([u8; 3], [u8; 3]),
    /// A black dot (the observer).
    Dot,
    /// A line of this colour.
    Line((u8, u8, u8)),
    /// A dashed line of this colour.
    Dashed((u8, u8, u8)),
    /// No mark: a line of text.
    None,
    /// No mark, but the room for one (the caller draws its own).
    Room,
}

/// Height of a legend's line (px).
pub(crate) const LEGEND_LINE: i32 = 44;

/// A legend as a column of entries in the cell `(left, top, width, height)`, each wrapped to the
/// cell's width; returns the row (px) of each entry's mark.
pub(crate) fn draw_legend_cell<DB: DrawingBackend>(
    root: &AreaOn<DB>,
    (left, top, width, _h): (i32, i32, i32, i32),
    items: &[(LegendMark, String)],
) -> Result<Vec<i32>, DrawingAreaErrorKind<DB::ErrorType>> {
    let x = left + 30;
    let mut y = top + CAPTION_LINE + LEGEND_LINE / 2;
    let mut rows = Vec::new();
    for (mark, text) in items {
        draw_legend_mark(root, *mark, x, y)?;
        rows.push(y);
        let indent = if matches!(mark, LegendMark::None) {
            0
        } else {
            44
        };
        for line in wrap(text, TEXT, width - 40 - indent) {
            root.draw(&Text::new(
                line,
                (x + indent, y),
                font(TEXT).pos(Pos::new(HPos::Left, VPos::Center)),
            ))?;
            y += (1.2 * TEXT) as i32;
        }
        y += LEGEND_LINE - (1.2 * TEXT) as i32;
    }
    Ok(rows)
}

/// A legend's mark, 32 px wide, starting at `x`, centred on `y`.
pub(crate) fn draw_legend_mark<DB: DrawingBackend>(
    root: &AreaOn<DB>,
    mark: LegendMark,
    x: i32,
    y: i32,
) -> DrawResultOn<DB> {
    let c = |c: [u8; 3]| RGBColor(c[0], c[1], c[2]);
    match mark {
        LegendMark::Swatch(s) => root.draw(&Rectangle::new(
            [(x + 4, y - 12), (x + 28, y + 12)],
            c(s).filled(),
        )),
        LegendMark::TwoSwatches(a, b) => {
            root.draw(&Rectangle::new(
                [(x + 4, y - 12), (x + 16, y + 12)],
                c(a).filled(),
            ))?;
            root.draw(&Rectangle::new(
                [(x + 16, y - 12), (x + 28, y + 12)],
                c(b).filled(),
            ))
        }
        LegendMark::Dot => root.draw(&Circle::new((x + 16, y), 8, BLACK.filled())),
        LegendMark::Line(l) => root.draw(&PathElement::new(
            vec![(x, y), (x + 32, y)],
            rgb(l).stroke_width(3),
        )),
        LegendMark::Dashed(l) => dashed(
            root,
            &[(x as f64, y as f64), (x as f64 + 32.0, y as f64)],
            rgb(l),
        ),
        LegendMark::None | LegendMark::Room => Ok(()),
    }
}

/// A figure's file format, by the file's extension.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FigureFormat {
    /// A bitmap (`.png`).
    Png,
    /// A vector drawing (`.svg`).
    Svg,
    /// A vector drawing for print (`.pdf`): the SVG, converted.
    Pdf,
}

/// The extensions a figure may have, as the output checks take them.
pub const FIGURE_EXTENSIONS: &[&str] = &["png", "svg", "pdf"];

impl FigureFormat {
    /// The format of `path` by its extension, or the one-line refusal naming the accepted ones.
    pub fn of(path: &Path) -> Result<FigureFormat> {
        match path
            .extension()
            .map(|e| e.to_string_lossy().to_ascii_lowercase())
            .as_deref()
        {
            Some("png") => Ok(FigureFormat::Png),
            Some("svg") => Ok(FigureFormat::Svg),
            Some("pdf") => Ok(FigureFormat::Pdf),
            _ => Err(Error::Refused(format!(
                "{}: a figure's file name must end in .png, .svg or .pdf",
                files::shown(path)
            ))),
        }
    }
}

/// A figure of `size` pixels as the bytes of its file, PNG, SVG or PDF: the one drawing code,
/// generic over the backend, is passed twice (`png_draw` and `svg_draw` call it on each backend;
/// a PDF is the SVG, converted); errors name `path`.
pub(crate) fn figure_bytes(
    path: &Path,
    format: FigureFormat,
    size: (u32, u32),
    png_draw: impl FnOnce(&DrawingArea<BitMapBackend, plotters::coord::Shift>) -> Result<(), String>,
    svg_draw: impl FnOnce(&DrawingArea<SVGBackend, plotters::coord::Shift>) -> Result<(), String>,
) -> Result<Vec<u8>> {
    register_font();
    let fail = |e: String| Error::Encode(format!("cannot draw {}: {e}", files::shown(path)));
    match format {
        FigureFormat::Svg | FigureFormat::Pdf => {
            let mut text = String::new();
            {
                let root = SVGBackend::with_string(&mut text, size).into_drawing_area();
                svg_draw(&root).map_err(fail)?;
                root.present().map_err(|e| fail(e.to_string()))?;
            }
            let text = merge_marks(&text);
            if format == FigureFormat::Pdf {
                svg_to_pdf(&text).map_err(fail)
            } else {
                Ok(text.into_bytes())
            }
        }
        FigureFormat::Png => {
            let mut buf = vec![255u8; (size.0 * size.1 * 3) as usize];
            {
                let root = BitMapBackend::with_buffer(&mut buf, size).into_drawing_area();
                png_draw(&root).map_err(fail)?;
                root.present().map_err(|e| fail(e.to_string()))?;
            }
            encode_png(&buf, size.0, size.1).map_err(fail)
        }
    }
}

/// How SVG is read for PDF: the shipped font loaded, and the family every text of ours names
/// (`sans-serif`) and the default family both mapped to it.
pub(crate) fn svg_options() -> Result<usvg::Options<'static>, String> {
    let mut opt = usvg::Options::default();
    let db = opt.fontdb_mut();
    db.load_font_data(FONT.to_vec());
    let family = db
        .faces()
        .next()
        .and_then(|f| f.families.first().map(|(name, _)| name.clone()))
        .ok_or("the shipped font does not load")?;
    db.set_sans_serif_family(family.clone());
    opt.font_family = family;
    Ok(opt)
}

/// Width of a PDF figure's page (cm): one column of a printed page, the width the text sizes
/// are chosen for.
pub const PDF_WIDTH_CM: f64 = 8.5;

/// The PDF of an SVG drawn by [`figure_bytes`], its page [`PDF_WIDTH_CM`] wide; the shipped font
/// is embedded (the SVG names it by its family only).
fn svg_to_pdf(svg: &str) -> Result<Vec<u8>, String> {
    let tree = usvg::Tree::from_str(svg, &svg_options()?).map_err(|e| e.to_string())?;
    // The page's width in points is the drawing's width in pixels × 72 / dpi.
    let dpi = tree.size().width() as f64 * 2.54 / PDF_WIDTH_CM;
    svg2pdf::to_pdf(
        &tree,
        svg2pdf::ConversionOptions::default(),
        svg2pdf::PageOptions { dpi: dpi as f32 },
    )
    .map_err(|e| e.to_string())
}

/// An RGB pixel buffer of `w` × `h` as PNG bytes.
pub(crate) fn encode_png(buf: &[u8], w: u32, h: u32) -> Result<Vec<u8>, String> {
    let mut png = Vec::new();
    image::codecs::png::PngEncoder::new(&mut png)
        .write_image(buf, w, h, image::ExtendedColorType::Rgb8)
        .map_err(|e| e.to_string())?;
    Ok(png)
}

/// The smallest text of every figure (px, the font's size proper, SVG's `font-size`): 3 % of the
/// figure's 1000 px, so printed 8.5 cm wide it is 7.2 pt.
pub const TEXT: f64 = 30.0;
/// Panel captions and axis names (px).
pub const CAPTION: f64 = 32.0;
/// Titles (px).
pub const TITLE: f64 = 40.0;
/// Plotters' sizes are 1.24 times the font's size proper (it draws a size `s` with an em of
/// `s / 1.24`, and writes `font-size = s / 1.24` into an SVG).
const PLOTTERS_SIZE_PER_EM: f64 = 1.24;

/// The figures' font at `size` px (the em, as SVG's `font-size`), black.
pub(crate) fn font(size: f64) -> TextStyle<'static> {
    (FONT_FAMILY, size * PLOTTERS_SIZE_PER_EM)
        .into_font()
        .color(&BLACK)
}

/// `text` broken at spaces into lines at most `max` px wide at `size` (a longer word stays whole).
pub(crate) fn wrap(text: &str, size: f64, max: i32) -> Vec<String> {
    let mut lines: Vec<String> = Vec::new();
    for word in text.split(' ').filter(|w| !w.is_empty()) {
        match lines.last_mut() {
            Some(l) if text_width(&format!("{l} {word}"), size) <= max => {
                l.push(' ');
                l.push_str(word);
            }
            _ => lines.push(word.to_string()),
        }
    }
    lines
}

/// A figure's heading: the title in large type, the subtitle below it, both wrapped to the width.
pub(crate) struct Heading {
    /// The lines with their sizes (px).
    lines: Vec<(String, f64)>,
}

impl Heading {
    /// The heading of `title` and `subtitle` (empty: none).
    pub fn new(title: &str, subtitle: &str) -> Heading {
        let max = FIGURE_WIDTH as i32 - 40;
        let mut lines: Vec<(String, f64)> = wrap(title, TITLE, max)
            .into_iter()
            .map(|l| (l, TITLE))
            .collect();
        lines.extend(wrap(subtitle, TEXT, max).into_iter().map(|l| (l, TEXT)));
        Heading { lines }
    }

    /// Its height (px), margins included.
    pub fn height(&self) -> i32 {
        16 + self
            .lines
            .iter()
            .map(|(_, s)| (1.3 * s).round() as i32)
            .sum::<i32>()
            + 10
    }

    /// Draws it at the top, centred.
    pub fn draw<DB: DrawingBackend>(&self, root: &AreaOn<DB>) -> DrawResultOn<DB> {
        let mut y = 16;
        for (line, size) in &self.lines {
            let color = if *size == TITLE {
                BLACK
            } else {
                RGBColor(60, 60, 60)
            };
            root.draw(&Text::new(
                line.clone(),
                (FIGURE_WIDTH as i32 / 2, y),
                font(*size)
                    .color(&color)
                    .pos(Pos::new(HPos::Center, VPos::Top)),
            ))?;
            y += (1.3 * size).round() as i32;
        }
        Ok(())
    }
}

/// The world axis (0, 1, 2 for x, y, z) along `d`, a screen direction of a view that looks along a
/// world axis, and whether it increases along `d` (`true`) or against it.
pub(crate) fn world_axis(d: Vec3) -> (usize, bool) {
    let a = (0..3)
        .max_by(|&i, &j| d[i].abs().total_cmp(&d[j].abs()))
        .unwrap_or(0);
    (a, d[a] > 0.0)
}

/// The step between ticks of world axis `a` in `panel`: a round number, at least `room` px apart.
fn panel_step(panel: &Panel, a: usize) -> f64 {
    let (h, _) = world_axis(panel.proj.right);
    let (lo, hi) = panel.frame_range(a);
    let mut step = tick_step(hi - lo, 5.0);
    for _ in 0..20 {
        let room = if a == h {
            // Across: the widest label and a gap.
            ticks(lo, hi, step)
                .iter()
                .map(|&v| text_width(&tick_label(v, step), TEXT))
                .max()
                .unwrap_or(0) as f64
                + 24.0
        } else {
            1.6 * TEXT
        };
        if step * panel.proj.scale >= room {
            break;
        }
        step = next_step(step);
    }
    step
}

/// The next round step after `step`: 1, 2, 5, 10, 20 …
fn next_step(step: f64) -> f64 {
    let power = 10f64.powf(step.log10().floor());
    let m = (step / power).round();
    if m < 2.0 {
        2.0 * power
    } else if m < 5.0 {
        5.0 * power
    } else {
        10.0 * power
    }
}

/// The panel's caption, and the pane of the box's far face, with grid lines at the scales' ticks.
pub(crate) fn draw_panes<DB: DrawingBackend>(
    root: &AreaOn<DB>,
    panel: &Panel,
    bx: &AxisBox,
) -> DrawResultOn<DB> {
    for (k, line) in panel.caption.iter().enumerate() {
        root.draw(&Text::new(
            line.clone(),
            (
                panel.left + panel.width / 2,
                panel.top + 6 + k as i32 * CAPTION_LINE,
            ),
            font(CAPTION).pos(Pos::new(HPos::Center, VPos::Top)),
        ))?;
    }
    // The frame: a pale pane with grid lines at the scales' ticks.
    let [l, r, t, b] = panel.frame;
    let px = |v: f64| v.round() as i32;
    root.draw(&Rectangle::new(
        [(px(l), px(t)), (px(r), px(b))],
        RGBColor(244, 244, 246).filled(),
    ))?;
    let grid = RGBColor(218, 218, 224);
    for (a, across) in [
        (world_axis(panel.proj.right).0, true),
        (world_axis(panel.proj.up).0, false),
    ] {
        let (lo, hi) = panel.frame_range(a);
        for v in ticks(lo, hi, panel_step(panel, a)) {
            let at = tick_pixel(panel, a, v);
            let seg = if across {
                vec![(px(at), px(t)), (px(at), px(b))]
            } else {
                vec![(px(l), px(at)), (px(r), px(at))]
            };
            root.draw(&PathElement::new(seg, grid))?;
        }
    }
    // The box's edges seen from here: where glass, straw and points lie.
    let mut outline: Vec<(i32, i32)> = {
        let (mut x0, mut x1, mut y0, mut y1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
        for k in bx.corners() {
            let (x, y) = panel.proj.pixel(k);
            x0 = x0.min(x);
            x1 = x1.max(x);
            y0 = y0.min(y);
            y1 = y1.max(y);
        }
        vec![
            (px(x0), px(y0)),
            (px(x1), px(y0)),
            (px(x1), px(y1)),
            (px(x0), px(y1)),
        ]
    };
    outline.push(outline[0]);
    root.draw(&PathElement::new(outline, RGBColor(200, 200, 208)))?;
    root.draw(&Rectangle::new(
        [(px(l), px(t)), (px(r), px(b))],
        RGBColor(170, 170, 178),
    ))?;
    Ok(())
}

/// Where value `v` of world axis `a` lands along the screen direction it runs in: a column for an
/// axis running across, a row for one running up (px).
fn tick_pixel(panel: &Panel, a: usize, v: f64) -> f64 {
    let mut p = panel.proj.centre;
    p[a] = v;
    let (x, y) = panel.proj.pixel(p);
    if world_axis(panel.proj.right).0 == a {
        x
    } else {
        y
    }
}

/// The water's wireframe segments on the near (`front`) or far side of the glass's axis.
pub(crate) fn draw_water<DB: DrawingBackend>(
    root: &AreaOn<DB>,
    proj: &Projection,
    scene: &Setup,
    front: bool,
) -> DrawResultOn<DB> {
    let (axis, segments) = scene.wireframe();
    let axis_depth = proj.nearness(axis);
    let color = if front {
        rgb(WATER_RGB).mix(0.75)
    } else {
        rgb(WATER_RGB).mix(0.45)
    };
    for [a, b] in segments {
        let mid = 0.5 * (a + b);
        if (proj.nearness(mid) > axis_depth) == front {
            root.draw(&PathElement::new(vec![proj.at(a), proj.at(b)], color))?;
        }
    }
    Ok(())
}

/// The straw's true outline, dashed: its section boundaries and its two silhouette lines.
pub(crate) fn draw_straw_outline<DB: DrawingBackend>(
    root: &AreaOn<DB>,
    proj: &Projection,
    scene: &Setup,
) -> DrawResultOn<DB> {
    let color = rgb(STRAW_OUTLINE_RGB);
    for line in scene.outlines(proj.right) {
        let px: Vec<(f64, f64)> = line.iter().map(|&p| proj.pixel(p)).collect();
        dashed(root, &px, color)?;
    }
    Ok(())
}

/// A dashed polyline through pixel positions: 5 px on, 4 px off.
pub(crate) fn dashed<DB: DrawingBackend>(
    root: &AreaOn<DB>,
    px: &[(f64, f64)],
    color: RGBColor,
) -> DrawResultOn<DB> {
    const ON: f64 = 5.0;
    const PERIOD: f64 = 9.0;
    let mut phase = 0.0f64;
    for w in px.windows(2) {
        let (a, b) = (w[0], w[1]);
        let len = (b.0 - a.0).hypot(b.1 - a.1);
        let mut s = 0.0;
        while s < len {
            let in_period = phase % PERIOD;
            let (seg, on) = if in_period < ON {
                (ON - in_period, true)
            } else {
                (PERIOD - in_period, false)
            };
            let e = (s + seg).min(len);
            if on && len > 0.0 {
                let p = |t: f64| {
                    let f = t / len;
                    (
                        (a.0 + f * (b.0 - a.0)).round() as i32,
                        (a.1 + f * (b.1 - a.1)).round() as i32,
                    )
                };
                root.draw(&PathElement::new(vec![p(s), p(e)], color))?;
            }
            phase += e - s;
            s = e;
        }
    }
    Ok(())
}

/// Side of the square dot of one image point, in pixels.
pub(crate) const DOT: i32 = 3;

/// One image point's dot: its top-left pixel and colour.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Dot {
    /// Left column (px).
    pub x: i32,
    /// Top row (px).
    pub y: i32,
    /// Width and height (px): [`DOT`], less what is clipped off at the panel's edge.
    pub size: (i32, i32),
    /// Colour.
    pub rgb: [u8; 3],
}

/// The dots of a panel that the picture shows, in drawing order: first `ghost` (pale, in the
/// given order), then `points` in their colours from far to near, each a [`DOT`]-pixel square
/// clipped to the panel. A dot whose every pixel a later dot covers is left out: the picture is
/// the same, and an SVG of a million points stays a few megabytes.
pub(crate) fn visible_dots(
    panel: &Panel,
    ghost: &[(ImagePoint, [u8; 3])],
    points: &[ImagePoint],
) -> Vec<Dot> {
    let proj = &panel.proj;
    let mut order: Vec<(f64, usize)> = points
        .iter()
        .enumerate()
        .filter(|(_, p)| p.position.is_finite())
        .map(|(i, p)| (proj.nearness(p.position), i))
        .collect();
    // Stable, so that equal depths keep the input order and the picture is reproducible.
    order.par_sort_by(|a, b| a.0.total_cmp(&b.0));
    let place = |p: &ImagePoint, rgb: [u8; 3]| {
        let (px, py) = proj.pixel(p.position);
        let half = DOT as f64 / 2.0;
        Dot {
            x: (px - half).round() as i32,
            y: (py - half).round() as i32,
            size: (DOT, DOT),
            rgb,
        }
    };
    let drawn: Vec<Dot> = ghost
        .iter()
        .filter(|(p, _)| p.position.is_finite())
        .map(|(p, c)| place(p, *c))
        .chain(
            order
                .iter()
                .map(|&(_, i)| place(&points[i], section_rgb8(points[i].color))),
        )
        .collect();
    // From the last drawn back: a dot shows if one of its pixels is not yet covered.
    let (w, h) = (panel.width.max(0) as usize, panel.height.max(0) as usize);
    let mut covered = vec![false; w * h];
    let mut kept: Vec<Dot> = Vec::new();
    for d in drawn.iter().rev() {
        let x0 = (d.x - panel.left).max(0);
        let y0 = (d.y - panel.top).max(0);
        let x1 = (d.x + DOT - panel.left).min(w as i32);
        let y1 = (d.y + DOT - panel.top).min(h as i32);
        let mut shows = false;
        for y in y0..y1 {
            for x in x0..x1 {
                let k = y as usize * w + x as usize;
                shows |= !covered[k];
                covered[k] = true;
            }
        }
        if shows && x1 > x0 && y1 > y0 {
            kept.push(Dot {
                x: x0 + panel.left,
                y: y0 + panel.top,
                size: (x1 - x0, y1 - y0),
                rgb: d.rgb,
            });
        }
    }
    kept.reverse();
    kept
}

/// The pixels `dots` cover, each in the colour of the last dot over it, as rectangles that do
/// not overlap, one colour after the other: pixel rows of one colour, rows of the same extent one
/// under the other joined. Drawn in any order they make the picture the dots make in theirs, and
/// an SVG writes each colour as one path.
pub(crate) fn covered_pixels(dots: &[Dot]) -> Vec<Dot> {
    let (Some(x0), Some(y0)) = (
        dots.iter().map(|d| d.x).min(),
        dots.iter().map(|d| d.y).min(),
    ) else {
        return Vec::new();
    };
    let x1 = dots.iter().map(|d| d.x + d.size.0).max().unwrap_or(x0);
    let y1 = dots.iter().map(|d| d.y + d.size.1).max().unwrap_or(y0);
    let (w, h) = ((x1 - x0) as usize, (y1 - y0) as usize);
    let mut colours: Vec<[u8; 3]> = dots.iter().map(|d| d.rgb).collect();
    colours.sort_unstable();
    colours.dedup();
    // Each pixel's colour (its index in `colours`, plus one; 0: uncovered).
    let mut grid = vec![0u16; w * h];
    for d in dots {
        let c = colours.binary_search(&d.rgb).expect("listed") as u16 + 1;
        for y in d.y..d.y + d.size.1 {
            let row = (y - y0) as usize * w;
            for x in d.x..d.x + d.size.0 {
                grid[row + (x - x0) as usize] = c;
            }
        }
    }
    let mut out = Vec::new();
    for (k, rgb) in colours.iter().enumerate() {
        let c = k as u16 + 1;
        // Rectangles still growing downwards, by their left column and width.
        let mut open: Vec<Dot> = Vec::new();
        for y in 0..=h {
            let mut runs: Vec<(i32, i32)> = Vec::new();
            if y < h {
                let row = &grid[y * w..(y + 1) * w];
                let mut x = 0;
                while x < w {
                    if row[x] == c {
                        let start = x;
                        while x < w && row[x] == c {
                            x += 1;
                        }
                        runs.push((x0 + start as i32, (x - start) as i32));
                    } else {
                        x += 1;
                    }
                }
            }
            let mut next = Vec::with_capacity(runs.len());
            for (x, len) in runs {
                match open.iter().position(|d| d.x == x && d.size.0 == len) {
                    Some(i) => {
                        let mut d = open.swap_remove(i);
                        d.size.1 += 1;
                        next.push(d);
                    }
                    None => next.push(Dot {
                        x,
                        y: y0 + y as i32,
                        size: (len, 1),
                        rgb: *rgb,
                    }),
                }
            }
            out.append(&mut open);
            open = next;
        }
    }
    out
}

/// Draws the pixels dots cover (see [`covered_pixels`]) as filled rectangles.
pub(crate) fn draw_dots<DB: DrawingBackend>(root: &AreaOn<DB>, dots: &[Dot]) -> DrawResultOn<DB> {
    for d in &covered_pixels(dots) {
        root.draw(&Rectangle::new(
            [(d.x, d.y), (d.x + d.size.0, d.y + d.size.1)],
            RGBColor(d.rgb[0], d.rgb[1], d.rgb[2]).filled(),
        ))?;
    }
    Ok(())
}

/// The name of world axis `a` with an arrow the way its values increase along the reading
/// direction (`increasing`: to the right, or up for a vertical name written bottom to top).
pub(crate) fn axis_name(a: usize, increasing: bool) -> String {
    let name = ["x", "y", "z"][a];
    if increasing {
        format!("{name} (m) →")
    } else {
        format!("← {name} (m)")
    }
}

/// The panel's two scales: the world axis running across the screen along the bottom of the frame,
/// the one running up the screen along its left side, each with ticks, labels and its name with an
/// arrow the way it increases. A view looks along a world axis, so each is one axis of the scene.
pub(crate) fn draw_axis_labels<DB: DrawingBackend>(
    root: &AreaOn<DB>,
    panel: &Panel,
    _bx: &AxisBox,
) -> DrawResultOn<DB> {
    let [x0, x1, y0, y1] = panel.frame;
    let tick_color = RGBColor(70, 70, 76);
    let r = |v: f64| v.round() as i32;
    // Across, along the bottom edge.
    let (h, h_up) = world_axis(panel.proj.right);
    let step = panel_step(panel, h);
    let (lo, hi) = panel.frame_range(h);
    for v in ticks(lo, hi, step) {
        let x = tick_pixel(panel, h, v);
        root.draw(&PathElement::new(
            vec![(r(x), r(y1)), (r(x), r(y1) + 7)],
            tick_color,
        ))?;
        root.draw(&Text::new(
            tick_label(v, step),
            (r(x), r(y1) + 10),
            font(TEXT)
                .color(&tick_color)
                .pos(Pos::new(HPos::Center, VPos::Top)),
        ))?;
    }
    root.draw(&Text::new(
        axis_name(h, h_up),
        (r(0.5 * (x0 + x1)), r(y1) + 12 + (1.3 * TEXT) as i32),
        font(CAPTION).pos(Pos::new(HPos::Center, VPos::Top)),
    ))?;
    // Up, along the left edge.
    let (v_axis, v_up) = world_axis(panel.proj.up);
    let step = panel_step(panel, v_axis);
    let (lo, hi) = panel.frame_range(v_axis);
    let mut widest = 0;
    for v in ticks(lo, hi, step) {
        let y = tick_pixel(panel, v_axis, v);
        let text = tick_label(v, step);
        widest = widest.max(text_width(&text, TEXT));
        root.draw(&PathElement::new(
            vec![(r(x0) - 7, r(y)), (r(x0), r(y))],
            tick_color,
        ))?;
        root.draw(&Text::new(
            text,
            (r(x0) - 10, r(y)),
            font(TEXT)
                .color(&tick_color)
                .pos(Pos::new(HPos::Right, VPos::Center)),
        ))?;
    }
    // Written bottom to top, so that its arrow points up when the axis increases upwards.
    root.draw(&Text::new(
        axis_name(v_axis, v_up),
        (
            r(x0) - 18 - widest - (1.25 * CAPTION) as i32,
            r(0.5 * (y0 + y1)),
        ),
        font(CAPTION)
            .transform(FontTransform::Rotate270)
            .pos(Pos::new(HPos::Center, VPos::Top)),
    ))?;
    Ok(())
}

/// A label beside a marker at `(x, y)`, on a pale backing, kept inside the frame: right of it,
/// left, above or below, wherever it hides the fewest of the panel's `dots`.
fn marker_label<DB: DrawingBackend>(
    root: &AreaOn<DB>,
    panel: &Panel,
    (x, y): (i32, i32),
    text: &str,
    dots: &[Dot],
) -> DrawResultOn<DB> {
    let tw = text_width(text, TEXT);
    let fit = |(l, cy): (i32, i32)| {
        (
            // Inside the frame, off the scales' labels (beyond its right edge if need be).
            l.clamp(
                panel.frame[0] as i32 + 4,
                (panel.frame[1] as i32 - tw - 6).max(panel.frame[0] as i32 + 4),
            ),
            cy.clamp(panel.frame[2] as i32 + 18, panel.frame[3] as i32 - 18),
        )
    };
    let candidates = [
        (x + 14, y),
        (x - 18 - tw, y),
        (x - tw / 2, y - 32),
        (x - tw / 2, y + 32),
    ]
    .map(fit);
    let hidden = |(l, cy): (i32, i32)| {
        // Never over the marker itself (a label pushed back into the panel might be).
        let on_marker = l < x + 9 && l + tw + 4 > x - 9 && cy - 18 < y + 9 && cy + 18 > y - 9;
        usize::from(on_marker) * usize::MAX / 2
            + dots
                .iter()
                .filter(|d| {
                    d.x < l + tw + 4
                        && d.x + d.size.0 > l - 2
                        && d.y < cy + 18
                        && d.y + d.size.1 > cy - 18
                })
                .count()
    };
    // The first of the least hiding, so that an empty neighbourhood keeps the label on the right.
    let (l, cy) = candidates
        .iter()
        .copied()
        .min_by_key(|&c| hidden(c))
        .unwrap_or(candidates[0]);
    root.draw(&Rectangle::new(
        [(l - 2, cy - 18), (l + tw + 4, cy + 18)],
        WHITE.mix(0.75).filled(),
    ))?;
    root.draw(&Text::new(
        text.to_string(),
        (l, cy),
        font(TEXT).pos(Pos::new(HPos::Left, VPos::Center)),
    ))
}

/// The observer as a black dot, or, when too far away to draw to scale, an arrow pointing to it;
/// its label placed where it hides the fewest of `dots`.
pub(crate) fn draw_observer<DB: DrawingBackend>(
    root: &AreaOn<DB>,
    panel: &Panel,
    bx: &AxisBox,
    observer: Vec3,
    dots: &[Dot],
) -> DrawResultOn<DB> {
    let proj = &panel.proj;
    if bx.observer_inside {
        let (x, y) = proj.at(observer);
        // Seen from about the observer's side the marker sits on the image: a ring hides less.
        let head_on = proj
            .toward
            .dot((observer - SCENE_CENTRE).normalize_or_zero())
            > 0.5f64.sqrt();
        if head_on {
            root.draw(&Circle::new((x, y), 8, BLACK.stroke_width(3)))?;
        } else {
            root.draw(&Circle::new((x, y), 8, BLACK.filled()))?;
        }
        return marker_label(root, panel, (x, y), "observer", dots);
    }
    let Some((tail, tip)) = bx.observer_arrow else {
        return Ok(());
    };
    let (tx, ty) = proj.pixel(tip);
    let (sx, sy) = proj.pixel(tail);
    let (dx, dy) = (tx - sx, ty - sy);
    let len = dx.hypot(dy);
    if len < 18.0 {
        // Seen end-on, the arrow would be a dot: a ring, and which way the observer is.
        let at = (sx.round() as i32, sy.round() as i32);
        root.draw(&Circle::new(at, 8, BLACK.stroke_width(3)))?;
        let words = if proj.nearness(observer) > 0.0 {
            "observer, far in front"
        } else {
            "observer, far behind"
        };
        return marker_label(root, panel, at, words, dots);
    }
    let (ux, uy) = (dx / len, dy / len);
    root.draw(&PathElement::new(
        vec![(sx as i32, sy as i32), (tx as i32, ty as i32)],
        BLACK.stroke_width(3),
    ))?;
    let (px, py) = (-uy, ux);
    let head = vec![
        (tx as i32, ty as i32),
        (
            (tx - 16.0 * ux + 7.0 * px) as i32,
            (ty - 16.0 * uy + 7.0 * py) as i32,
        ),
        (
            (tx - 16.0 * ux - 7.0 * px) as i32,
            (ty - 16.0 * uy - 7.0 * py) as i32,
        ),
    ];
    root.draw(&Polygon::new(head, BLACK.filled()))?;
    // "observer" beside the arrow's middle: above a level arrow, beside a steep one.
    let (mx, my) = (0.5 * (sx + tx), 0.5 * (sy + ty));
    if ux.abs() >= uy.abs() {
        root.draw(&Text::new(
            "observer",
            (mx as i32, my as i32 - 8),
            font(TEXT).pos(Pos::new(HPos::Center, VPos::Bottom)),
        ))
    } else {
        marker_label(root, panel, (mx as i32, my as i32), "observer", dots)
    }
}

/// Width of `s` in pixels at `size`.
pub(crate) fn text_width(s: &str, size: f64) -> i32 {
    font(size)
        .font
        .layout_box(s)
        .map(|((x0, _), (x1, _))| x1 - x0)
        .unwrap_or((s.len() as f64 * size * 0.6) as i32)
}

/// A short title naming the inputs, for figures.
pub fn simulation_title(scene: &Scene, observer: Vec3) -> String {
    format!(
        "observer ({}, {}, {}) m, straw ({}, {}) m, water {} m, n = {}",
        observer.x,
        observer.y,
        observer.z,
        scene.straw_x(),
        scene.straw_y(),
        scene.water_height(),
        scene.n_water()
    )
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use bentstraw_optics::sampling::sample_image;
    use bentstraw_optics::scene::{
        Scene, GLASS_HEIGHT, GLASS_RADIUS, REFERENCES, STRAW_HEIGHT, STRAW_RADIUS,
    };
    use bentstraw_optics::sketch::{water_segments, CIRCLE_SEGMENTS, WIRE_VERTICALS};

    /// A point of colour `color` at `position` (the other fields do not matter for drawing).
    pub(crate) fn point(position: Vec3, color: u8) -> ImagePoint {
        ImagePoint {
            position,
            color,
            direction: Vec3::X,
            path_length: 0.1,
            straw_point: position,
            events: 0,
        }
    }

    pub(crate) fn decode(png: &[u8]) -> image::RgbImage {
        image::load_from_memory_with_format(png, image::ImageFormat::Png)
            .expect("a valid PNG")
            .to_rgb8()
    }

    /// The panels of the classic figure of `points`, as drawn under its heading.
    fn panels_of(scene: &Setup, observer: Vec3, points: &[ImagePoint]) -> Vec<Panel> {
        let heading = cloud_heading(observer, points.len(), "t");
        layout(
            &axis_box(scene, observer, points),
            &figure_views(observer),
            heading.height(),
        )
    }

    /// Whether some pixel of the panels (not the heading or the legend) has exactly colour `c`.
    fn panels_have(img: &image::RgbImage, panels: &[Panel], c: [u8; 3]) -> bool {
        panels.iter().any(|p| {
            (p.top..p.top + p.height).any(|y| {
                (p.left..p.left + p.width).any(|x| img.get_pixel(x as u32, y as u32).0 == c)
            })
        })
    }

    fn png_of(scene: &Setup, observer: Vec3, points: &[ImagePoint]) -> image::RgbImage {
        decode(&render_cloud_figure(Path::new("f.png"), scene, observer, points, "t").unwrap())
    }

    #[test]
    fn figure_is_a_png_of_the_stated_size_showing_exactly_the_colours_present() {
        let scene = Setup::assignment(Scene::with_defaults(0.0, 0.0, 0.1).unwrap(), Vec3::ZERO);
        // Sections 1, 2 and 4 only, on the straw's surface.
        let points: Vec<ImagePoint> = (0..300)
            .map(|i| {
                let t = i as f64 * 0.1;
                let color = [1u8, 2, 4][i % 3];
                let z = (color as f64 - 0.5) * SECTION_HEIGHT;
                point(
                    Vec3::new(STRAW_RADIUS * t.cos(), STRAW_RADIUS * t.sin(), z),
                    color,
                )
            })
            .collect();
        let observer = Vec3::new(0.1, 0.0, 0.1);
        let img = png_of(&scene, observer, &points);
        let heading = cloud_heading(observer, points.len(), "t");
        assert_eq!(img.dimensions(), three_view_size(&heading));
        let panels = panels_of(&scene, observer, &points);
        for code in [1, 2, 4] {
            assert!(
                panels_have(&img, &panels, section_rgb8(code)),
                "colour {code} missing"
            );
        }
        for code in [3, 5] {
            assert!(
                !panels_have(&img, &panels, section_rgb8(code)),
                "colour {code} drawn without points"
            );
        }
    }

    #[test]
    fn reference_figure_is_written_and_shows_every_colour_seen() {
        let r = REFERENCES[1];
        let scene = Setup::assignment(r.scene(1.333), r.observer);
        let cloud = sample_image(&scene.world, r.observer, 2000, &|_| {});
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("ref.png");
        write_cloud_figure(&path, &scene, r.observer, &cloud.points, "Reference 2").unwrap();
        let img = decode(&std::fs::read(&path).unwrap());
        let panels = panels_of(&scene, r.observer, &cloud.points);
        let n = counts(&cloud.points);
        for code in 1..=5u8 {
            if n[(code - 1) as usize] > 0 {
                assert!(
                    panels_have(&img, &panels, section_rgb8(code)),
                    "colour {code} missing"
                );
            }
        }
        // Nothing else is left in the folder (the write is atomic).
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
        if let Ok(look) = std::env::var("BENTSTRAW_LOOK") {
            std::fs::copy(&path, Path::new(&look).join("cloud2.png")).unwrap();
        }
    }

    /// Leaving out the dots that later dots cover changes no pixel, and leaves out most of a
    /// dense cloud's dots.
    #[test]
    fn hidden_dots_left_out_change_no_pixel() {
        let r = REFERENCES[2];
        let scene = Setup::assignment(r.scene(1.333), r.observer);
        let cloud = sample_image(&scene.world, r.observer, 20_000, &|_| {});
        let panels = panels_of(&scene, r.observer, &cloud.points);
        let size = (FIGURE_WIDTH, 1400);
        for p in &panels {
            let ghost: Vec<(ImagePoint, [u8; 3])> = cloud.points[..500]
                .iter()
                .map(|q| (point(q.position + Vec3::new(0.003, 0.0, 0.0), 1), [9, 9, 9]))
                .collect();
            let kept = visible_dots(p, &ghost, &cloud.points);
            // Every dot drawn, far to near, straight into pixels, clipped to the panel.
            let mut all = vec![255u8; (size.0 * size.1 * 3) as usize];
            let mut order: Vec<(f64, usize)> = cloud
                .points
                .iter()
                .enumerate()
                .map(|(i, q)| (p.proj.nearness(q.position), i))
                .collect();
            order.sort_by(|a, b| a.0.total_cmp(&b.0));
            let squares = ghost
                .iter()
                .map(|(q, c)| (q.position, *c))
                .chain(order.iter().map(|&(_, i)| {
                    (
                        cloud.points[i].position,
                        section_rgb8(cloud.points[i].color),
                    )
                }));
            for (q, c) in squares {
                let (x, y) = p.proj.pixel(q);
                let (x, y) = ((x - 1.5).round() as i32, (y - 1.5).round() as i32);
                for yy in y.max(p.top)..(y + DOT).min(p.top + p.height) {
                    for xx in x.max(p.left)..(x + DOT).min(p.left + p.width) {
                        let k = ((yy as u32 * size.0 + xx as u32) * 3) as usize;
                        all[k..k + 3].copy_from_slice(&c);
                    }
                }
            }
            let mut some = vec![255u8; all.len()];
            for d in &kept {
                for yy in d.y..d.y + d.size.1 {
                    for xx in d.x..d.x + d.size.0 {
                        let k = ((yy as u32 * size.0 + xx as u32) * 3) as usize;
                        some[k..k + 3].copy_from_slice(&d.rgb);
                    }
                }
            }
            assert!(all == some, "the kept dots draw a different picture");
            assert!(
                kept.len() < (cloud.points.len() + ghost.len()) / 2,
                "{} of {} dots kept",
                kept.len(),
                cloud.points.len()
            );
        }
    }

    #[test]
    fn observer_is_a_black_dot_where_each_view_projects_it() {
        let scene = Setup::assignment(Scene::with_defaults(0.02, 0.01, 0.15).unwrap(), Vec3::ZERO);
        let observer = Vec3::new(-0.07, 0.06, 0.17);
        let img = png_of(&scene, observer, &[]);
        let bx = axis_box(&scene, observer, &[]);
        assert!(bx.observer_inside);
        for p in panels_of(&scene, observer, &[]) {
            let (x, y) = p.proj.pixel(observer);
            let (x, y) = (x.round() as i32, y.round() as i32);
            // A dot, or a ring in a view straight from the observer's direction: either way black
            // pixels all round within 8 px, left and right, above and below.
            let black = |dx: std::ops::RangeInclusive<i32>, dy: std::ops::RangeInclusive<i32>| {
                dx.clone().any(|i| {
                    dy.clone()
                        .any(|j| img.get_pixel((x + i) as u32, (y + j) as u32).0 == [0, 0, 0])
                })
            };
            assert!(
                black(-8..=-3, -1..=1) && black(3..=8, -1..=1),
                "no marker at ({x}, {y})"
            );
            assert!(
                black(-1..=1, -8..=-3) && black(-1..=1, 3..=8),
                "no marker at ({x}, {y})"
            );
        }
    }

    #[test]
    fn empty_glass_and_no_points_still_draw() {
        let scene = Setup::assignment(Scene::with_defaults(0.01, 0.0, 0.0).unwrap(), Vec3::ZERO);
        let observer = Vec3::new(0.0, -0.2, 0.3);
        let img = png_of(&scene, observer, &[]);
        assert_eq!(img.width(), FIGURE_WIDTH);
        assert_eq!(
            water_segments(scene.assignment_numbers().unwrap()).len(),
            2 * CIRCLE_SEGMENTS
        );
    }

    #[test]
    fn same_inputs_give_the_same_bytes() {
        let r = REFERENCES[2];
        let scene = Setup::assignment(r.scene(1.333), r.observer);
        let cloud = sample_image(&scene.world, r.observer, 3000, &|_| {});
        // (A PDF's objects come out in an order that varies from run to run: not compared.)
        for name in ["a.png", "a.svg"] {
            let f =
                || render_cloud_figure(Path::new(name), &scene, r.observer, &cloud.points, "again");
            assert!(
                f().unwrap() == f().unwrap(),
                "{name}: two renderings differ"
            );
        }
    }

    #[test]
    fn unwritable_path_is_an_error_not_a_panic() {
        let scene = Setup::assignment(Scene::with_defaults(0.0, 0.0, 0.1).unwrap(), Vec3::ZERO);
        let path = Path::new("/nonexistent-folder/fig.png");
        assert!(write_cloud_figure(path, &scene, Vec3::new(0.1, 0.0, 0.1), &[], "t").is_err());
    }

    #[test]
    fn figure_formats_by_extension() {
        for (name, want) in [
            ("a.PNG", Some(FigureFormat::Png)),
            ("a.svg", Some(FigureFormat::Svg)),
            ("b/a.Pdf", Some(FigureFormat::Pdf)),
            ("a.gif", None),
            ("a", None),
        ] {
            assert_eq!(FigureFormat::of(Path::new(name)).ok(), want, "{name}");
        }
        let e = FigureFormat::of(Path::new("x.gif"))
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("x.gif") && e.contains(".png, .svg or .pdf"),
            "{e}"
        );
    }

    #[test]
    fn long_text_wraps_within_the_width() {
        let text = "observer (0.1, 0, 0.1) m, straw (0.02, 0.01) m, water 0.15 m, n = 1.333, and more words";
        let lines = wrap(text, TEXT, 400);
        assert!(lines.len() >= 3, "{lines:?}");
        assert_eq!(lines.join(" "), text);
        for l in &lines {
            assert!(text_width(l, TEXT) <= 400, "{l}");
        }
    }

    #[test]
    fn axis_box_holds_glass_straw_points_and_a_near_observer() {
        let scene = Setup::assignment(Scene::with_defaults(0.02, 0.01, 0.15).unwrap(), Vec3::ZERO);
        let points = [
            point(Vec3::new(-0.2, 0.03, 0.12), 1),
            point(Vec3::new(0.01, 0.01, -0.05), 1),
        ];
        let observer = Vec3::new(0.0, 0.1, 0.4);
        let bx = axis_box(&scene, observer, &points);
        assert!(bx.observer_inside && bx.observer_arrow.is_none());
        assert!(bx.contains(observer));
        for p in &points {
            assert!(bx.contains(p.position));
        }
        for corner in [
            Vec3::new(GLASS_RADIUS, GLASS_RADIUS, GLASS_HEIGHT),
            Vec3::new(-GLASS_RADIUS, -GLASS_RADIUS, 0.0),
            Vec3::new(0.02, 0.01, STRAW_HEIGHT),
        ] {
            assert!(bx.contains(corner), "{corner} outside {bx:?}");
        }
    }

    #[test]
    fn far_observer_gets_an_arrow_pointing_at_it_inside_the_box() {
        let scene = Setup::assignment(Scene::with_defaults(0.0, 0.0, 0.15).unwrap(), Vec3::ZERO);
        let observer = Vec3::new(5.0, -2.0, 1.0);
        let bx = axis_box(&scene, observer, &[]);
        assert!(!bx.observer_inside);
        let (tail, tip) = bx.observer_arrow.unwrap();
        assert!(bx.contains(tail) && bx.contains(tip));
        // The box stays about the glass's size, not the observer's distance.
        assert!((bx.max - bx.min).max_element() < 0.5);
        let along = (tip - tail).normalize();
        let to_observer = (observer - tail).normalize();
        assert!(
            along.dot(to_observer) > 0.999,
            "arrow does not point at the observer"
        );
    }

    #[test]
    fn one_metre_has_the_same_length_on_screen_along_every_axis() {
        let c = Vec3::new(0.0, 0.0, 0.1);
        for az in [0.0, 0.4, 1.3, 2.9, -2.0] {
            // Level view: z and the horizontal axis across the screen are both true length.
            let level = Projection::new(
                ViewDirection {
                    azimuth: az,
                    elevation: 0.0,
                },
                c,
                (300.0, 200.0),
                1234.0,
            );
            let len = |proj: &Projection, d: Vec3| {
                let (a, b) = (proj.pixel(c), proj.pixel(c + d));
                (b.0 - a.0).hypot(b.1 - a.1)
            };
            assert!((len(&level, Vec3::Z * 0.1) - 123.4).abs() < 1e-9);
            assert!((len(&level, level.right * 0.1) - 123.4).abs() < 1e-9);
            // From above: x and y are both true length.
            let top = Projection::new(
                ViewDirection {
                    azimuth: az,
                    elevation: FRAC_PI_2,
                },
                c,
                (300.0, 200.0),
                1234.0,
            );
            assert!((len(&top, Vec3::X * 0.1) - 123.4).abs() < 1e-9);
            assert!((len(&top, Vec3::Y * 0.1) - 123.4).abs() < 1e-9);
        }
    }

    #[test]
    fn views_look_along_axes_unmirrored_with_z_up_and_the_observer_to_the_right_from_the_side() {
        for observer in [
            Vec3::new(0.0, 0.1, 0.1),
            Vec3::new(0.1, 0.0, -0.1),
            Vec3::new(-0.3, 0.2, 0.5),
            Vec3::new(0.05, -0.3, 0.1),
            Vec3::new(0.0, 0.0, 0.6),
        ] {
            let views = figure_views(observer);
            for (v, _) in &views {
                let (r, u, t) = (v.right(), v.up(), v.toward_viewer());
                // Screen right × screen up points at the viewer: a right-handed, unmirrored picture.
                assert!((r.cross(u) - t).length() < 1e-12);
                // Right and up each run along one axis of the scene: one scale each.
                for d in [r, u] {
                    let along = (0..3).filter(|&a| d[a].abs() > 1e-9).count();
                    assert_eq!(along, 1, "{observer}: {d} is not along an axis");
                }
                assert!(r.z == 0.0, "z must stay upright");
            }
            // Level views have z up; the top view x to the right and y up.
            for (v, _) in &views[..2] {
                assert_eq!(world_axis(v.up()), (2, true));
            }
            assert_eq!(world_axis(views[2].0.right()), (0, true));
            assert_eq!(world_axis(views[2].0.up()), (1, true));
            // The front view looks from the axis direction nearest the observer's.
            let d = observer - SCENE_CENTRE;
            let horizontal = Vec3::new(d.x, d.y, 0.0);
            if horizontal.length() > 1e-9 {
                let t = views[0].0.toward_viewer();
                for other in [Vec3::X, Vec3::Y, -Vec3::X, -Vec3::Y] {
                    assert!(
                        t.dot(horizontal) >= other.dot(horizontal) - 1e-12,
                        "{observer}"
                    );
                }
                // From the side the observer is to the right.
                assert!(views[1].0.right().dot(horizontal) > 0.0, "{observer}");
            }
        }
        assert_eq!(
            figure_views(Vec3::new(0.0, 0.1, 0.1))[1].1[0],
            "side view, from +x"
        );
    }

    #[test]
    fn every_panel_holds_its_whole_box_with_room_for_labels() {
        let far = Vec3::new(3.0, -1.0, 0.4);
        for (scene, observer) in REFERENCES
            .iter()
            .map(|r| (Setup::assignment(r.scene(1.333), r.observer), r.observer))
            .chain([(
                Setup::assignment(Scene::with_defaults(0.0, 0.0, 0.1).unwrap(), far),
                far,
            )])
        {
            let bx = axis_box(&scene, observer, &[]);
            let panels = panels_of(&scene, observer, &[]);
            assert_eq!(panels.len(), 3);
            for p in &panels {
                for k in bx.corners() {
                    let (x, y) = p.proj.pixel(k);
                    let (l, r) = (
                        p.left as f64 + PAD_LEFT,
                        (p.left + p.width) as f64 - PAD_RIGHT,
                    );
                    let (t, b) = (
                        (p.top + 2 * CAPTION_LINE) as f64 + PAD_TOP - 1e-6,
                        (p.top + p.height) as f64 - PAD_BOTTOM + 1e-6,
                    );
                    assert!(x >= l - 1e-6 && x <= r + 1e-6, "x {x} outside {l}..{r}");
                    assert!(y >= t && y <= b, "y {y} outside {t}..{b}");
                }
            }
        }
    }

    #[test]
    fn ticks_are_round_numbers_and_labels_have_no_negative_zero() {
        assert!((tick_step(0.25, 5.0) - 0.05).abs() < 1e-15);
        assert!((tick_step(0.09, 5.0) - 0.02).abs() < 1e-15);
        assert!((tick_step(3.0, 5.0) - 0.5).abs() < 1e-15);
        let t = ticks(-0.041, 0.26, 0.05);
        assert_eq!(t.len(), 6);
        assert_eq!(tick_label(t[0], 0.05), "0.00");
        assert_eq!(tick_label(-1e-17, 0.05), "0.00");
        assert_eq!(tick_label(-0.05, 0.05), "-0.05");
        assert_eq!(tick_label(0.1, 0.1), "0.1");
    }

    #[test]
    fn water_wireframe_has_two_circles_and_thirty_verticals() {
        let scene = Setup::assignment(Scene::with_defaults(0.0, 0.0, 0.15).unwrap(), Vec3::ZERO);
        let segs = water_segments(scene.assignment_numbers().unwrap());
        let verticals: Vec<_> = segs
            .iter()
            .filter(|[a, b]| a.x == b.x && a.y == b.y)
            .collect();
        assert_eq!(verticals.len(), WIRE_VERTICALS);
        assert_eq!(segs.len(), WIRE_VERTICALS + 2 * CIRCLE_SEGMENTS);
        for [a, b] in &segs {
            for p in [a, b] {
                assert!((p.x.hypot(p.y) - GLASS_RADIUS).abs() < 1e-12);
                assert!(p.z == 0.0 || p.z == 0.15);
            }
        }
    }
}
