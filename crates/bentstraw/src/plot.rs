//! The classic figure (SPEC §5) as a PNG: the image points in their section colours, the water as a
//! wireframe, the observer, equal axes, three views side by side.
//!
//! The views are orthographic projections computed here (not plotters' 3D charts), so that one metre
//! has the same length on screen along every axis and in every panel, and so that the drawing order
//! (back of the glass, points from far to near, front of the glass) is under our control.

use std::f64::consts::{FRAC_PI_2, PI};
use std::path::Path;
use std::sync::Once;

use bentstraw_optics::image::ImagePoint;
use bentstraw_optics::scene::{
    Scene, GLASS_HEIGHT, GLASS_RADIUS, SCENE_CENTRE, SECTION_COUNT, SECTION_HEIGHT, SECTION_NAMES,
    SECTION_RGB, STRAW_HEIGHT, STRAW_RADIUS,
};
use bentstraw_optics::Vec3;
use image::ImageEncoder;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use rayon::slice::ParallelSliceMut;

use crate::error::{CliError, CliResult};
use crate::files;

/// Width of the figure in pixels.
pub const FIGURE_WIDTH: u32 = 1800;
/// Height of the figure in pixels.
pub const FIGURE_HEIGHT: u32 = 650;

/// The font of every text in the figure, shipped with the program so pictures look the same anywhere.
static FONT: &[u8] = include_bytes!("../../../assets/DejaVuSans.ttf");
/// The family name the font is registered under.
const FONT_FAMILY: &str = "sans-serif";
static FONT_ONCE: Once = Once::new();

/// Number of vertical lines of the water's wireframe.
pub(crate) const WIRE_VERTICALS: usize = 30;
/// Segments per circle of the wireframes.
pub(crate) const CIRCLE_SEGMENTS: usize = 72;
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

/// The axis box of a figure: tight around glass, straw and points, with a margin; the observer is
/// included unless that would make the box more than [`FAR_OBSERVER_FACTOR`] times larger.
pub(crate) fn axis_box(scene: &Scene, observer: Vec3, points: &[ImagePoint]) -> AxisBox {
    let mut lo = Vec3::new(-GLASS_RADIUS, -GLASS_RADIUS, 0.0);
    let mut hi = Vec3::new(GLASS_RADIUS, GLASS_RADIUS, GLASS_HEIGHT);
    let straw = Vec3::new(scene.straw_x, scene.straw_y, 0.0);
    lo = lo.min(straw - Vec3::new(STRAW_RADIUS, STRAW_RADIUS, 0.0));
    hi = hi.max(straw + Vec3::new(STRAW_RADIUS, STRAW_RADIUS, STRAW_HEIGHT));
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
        let c = SCENE_CENTRE;
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

/// The three views of the figure with their captions: from the observer's direction, from the side
/// (90° to the left of it, level, so heights read true) and from straight above (observer at the bottom); when
/// the observer is itself almost straight above or below, the third is a level view from its azimuth.
pub(crate) fn figure_views(observer: Vec3) -> [(ViewDirection, String); 3] {
    let o = observer_direction(observer);
    let side = ViewDirection {
        azimuth: o.azimuth + FRAC_PI_2,
        elevation: 0.0,
    };
    let third = if o.elevation.abs() > 75f64.to_radians() {
        (
            ViewDirection {
                azimuth: o.azimuth,
                elevation: 0.0,
            },
            "level view from the observer's side".to_string(),
        )
    } else {
        (
            // Turned by a multiple of 90° so that the axes run along the panel's sides.
            ViewDirection {
                azimuth: (o.azimuth / FRAC_PI_2).round() * FRAC_PI_2,
                elevation: FRAC_PI_2,
            },
            "from above (observer's side at the bottom)".to_string(),
        )
    };
    [
        (
            o,
            format!(
                "from the observer's direction (azimuth {}°, elevation {}°)",
                whole(degrees(o.azimuth)),
                whole(o.elevation.to_degrees())
            ),
        ),
        (
            side,
            format!(
                "from the side (azimuth {}°, elevation {}°)",
                whole(degrees(side.azimuth)),
                whole(side.elevation.to_degrees())
            ),
        ),
        third,
    ]
}

/// A number rounded to a whole, never written "-0".
fn whole(v: f64) -> String {
    let r = v.round();
    if r == 0.0 {
        "0".to_string()
    } else {
        format!("{r:.0}")
    }
}

/// An angle in degrees in (−180, 180].
fn degrees(angle: f64) -> f64 {
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

/// Points around the horizontal circle of radius `r` centred on `(cx, cy)` at height `z`.
pub(crate) fn circle(cx: f64, cy: f64, r: f64, z: f64) -> Vec<Vec3> {
    (0..=CIRCLE_SEGMENTS)
        .map(|k| {
            let t = 2.0 * PI * k as f64 / CIRCLE_SEGMENTS as f64;
            Vec3::new(cx + r * t.cos(), cy + r * t.sin(), z)
        })
        .collect()
}

/// The water's wireframe as segments: top and bottom circles and [`WIRE_VERTICALS`] vertical lines.
pub(crate) fn water_segments(scene: &Scene) -> Vec<[Vec3; 2]> {
    let he = scene.water_height;
    let mut segs = Vec::new();
    for z in [0.0, he] {
        let c = circle(0.0, 0.0, GLASS_RADIUS, z);
        segs.extend(c.windows(2).map(|w| [w[0], w[1]]));
    }
    if he > 0.0 {
        for k in 0..WIRE_VERTICALS {
            let t = 2.0 * PI * k as f64 / WIRE_VERTICALS as f64;
            let (x, y) = (GLASS_RADIUS * t.cos(), GLASS_RADIUS * t.sin());
            segs.push([Vec3::new(x, y, 0.0), Vec3::new(x, y, he)]);
        }
    }
    segs
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

/// The display colour of section code `code` (1..=5), as 8-bit RGB.
pub(crate) fn section_rgb8(code: u8) -> [u8; 3] {
    let c = SECTION_RGB[(code.clamp(1, SECTION_COUNT as u8) - 1) as usize];
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

/// A drawing area on a bitmap.
pub(crate) type Area<'a> = DrawingArea<BitMapBackend<'a>, plotters::coord::Shift>;
/// A drawing area on any backend (bitmap or SVG): the shared drawing code takes these.
pub(crate) type AreaOn<DB> = DrawingArea<DB, plotters::coord::Shift>;
/// What drawing on any backend returns.
pub(crate) type DrawResultOn<DB> =
    Result<(), DrawingAreaErrorKind<<DB as DrawingBackend>::ErrorType>>;

/// Turns a drawing error into the message naming the file.
pub(crate) fn draw_err<E: std::fmt::Display>(path: &Path) -> impl Fn(E) -> CliError + '_ {
    move |e| CliError(format!("cannot draw {}: {e}", path.display()))
}

/// One panel: where it is and how it projects.
pub(crate) struct Panel {
    /// How the panel projects the scene.
    pub proj: Projection,
    /// The caption above the panel.
    pub caption: String,
    /// Left edge (px).
    pub left: i32,
    /// Top edge (px).
    pub top: i32,
    /// Width (px).
    pub width: i32,
    /// Height (px).
    pub height: i32,
}

/// Height of the band holding the title and subtitle (px).
pub(crate) const TITLE_BAND: i32 = 58;
/// Height of the band holding the legend (px).
pub(crate) const LEGEND_BAND: i32 = 40;
/// Height of a panel's caption (px).
pub(crate) const CAPTION_BAND: i32 = 24;
/// Room kept left and right of each panel's box for tick labels and axis names.
pub(crate) const PAD_SIDE: f64 = 58.0;
/// Room kept below each panel's box for tick labels and axis names (labels never go on top).
pub(crate) const PAD_BOTTOM: f64 = 50.0;
/// Room kept above each panel's box, under the caption; more when a note about a far observer goes there.
pub(crate) const PAD_TOP: f64 = 14.0;
pub(crate) const PAD_TOP_NOTE: f64 = 30.0;

/// The three panels side by side, each fitting the whole box.
pub(crate) fn layout(bx: &AxisBox, views: &[(ViewDirection, String)]) -> Vec<Panel> {
    let panel_w = FIGURE_WIDTH as i32 / views.len() as i32;
    let panel_h = FIGURE_HEIGHT as i32 - TITLE_BAND - LEGEND_BAND;
    let pad_top = if bx.observer_inside {
        PAD_TOP
    } else {
        PAD_TOP_NOTE
    };
    let fit_w = panel_w as f64 - 2.0 * PAD_SIDE;
    let fit_h = (panel_h - CAPTION_BAND) as f64 - pad_top - PAD_BOTTOM;
    views
        .iter()
        .enumerate()
        .map(|(i, (v, caption))| {
            let left = i as i32 * panel_w;
            let top = TITLE_BAND;
            let origin = (
                left as f64 + panel_w as f64 / 2.0,
                (top + CAPTION_BAND) as f64 + pad_top + fit_h / 2.0,
            );
            Panel {
                // Each panel has its own scale (a top view fits far more than a side view), but within
                // a panel one metre has the same length along every axis.
                proj: Projection::new(*v, bx.centre(), origin, fit_scale(bx, *v, fit_w, fit_h)),
                caption: caption.clone(),
                left,
                top,
                width: panel_w,
                height: panel_h,
            }
        })
        .collect()
}

/// Draws the classic three-view figure of `points` seen from `observer` into the PNG at `path`.
pub fn write_cloud_figure(
    path: &Path,
    scene: &Scene,
    observer: Vec3,
    points: &[ImagePoint],
    title: &str,
) -> CliResult {
    let png = render_cloud_figure(scene, observer, points, title).map_err(draw_err(path))?;
    files::write_bytes(path, &png)
}

/// The figure as PNG bytes.
fn render_cloud_figure(
    scene: &Scene,
    observer: Vec3,
    points: &[ImagePoint],
    title: &str,
) -> Result<Vec<u8>, String> {
    register_font();
    let (w, h) = (FIGURE_WIDTH, FIGURE_HEIGHT);
    let mut buf = vec![255u8; (w * h * 3) as usize];
    let bx = axis_box(scene, observer, points);
    let panels = layout(&bx, &figure_views(observer));

    // Back layer: titles, axis panes, the far half of the water, the straw's outline.
    {
        let root = BitMapBackend::with_buffer(&mut buf, (w, h)).into_drawing_area();
        draw_titles(&root, scene, observer, points.len(), title).map_err(|e| e.to_string())?;
        for p in &panels {
            draw_panes(&root, p, &bx).map_err(|e| e.to_string())?;
            draw_water(&root, &p.proj, scene, false).map_err(|e| e.to_string())?;
            draw_straw_outline(&root, &p.proj, scene).map_err(|e| e.to_string())?;
        }
        root.present().map_err(|e| e.to_string())?;
    }
    // Points, far to near, straight into the pixels (fast even for a million points).
    for p in &panels {
        draw_points(&mut buf, w, h, p, points);
    }
    // Front layer: the near half of the water, the observer, the axes' labels, the legend.
    {
        let root = BitMapBackend::with_buffer(&mut buf, (w, h)).into_drawing_area();
        for p in &panels {
            draw_water(&root, &p.proj, scene, true).map_err(|e| e.to_string())?;
            draw_axis_labels(&root, p, &bx).map_err(|e| e.to_string())?;
            draw_observer(&root, p, &bx, observer).map_err(|e| e.to_string())?;
        }
        draw_legend(&root, points, bx.observer_inside).map_err(|e| e.to_string())?;
        root.present().map_err(|e| e.to_string())?;
    }
    encode_png(&buf, w, h)
}

/// Whether `path` names an SVG file (by its extension); figures are PNG otherwise.
pub(crate) fn is_svg(path: &Path) -> bool {
    path.extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("svg"))
}

/// A figure of `size` pixels as the bytes of its file, SVG or PNG: the one drawing code, generic
/// over the backend, is passed twice (`png` and `svg` call it on each backend); errors name `path`.
pub(crate) fn figure_bytes(
    path: &Path,
    svg: bool,
    size: (u32, u32),
    png_draw: impl FnOnce(&DrawingArea<BitMapBackend, plotters::coord::Shift>) -> Result<(), String>,
    svg_draw: impl FnOnce(&DrawingArea<SVGBackend, plotters::coord::Shift>) -> Result<(), String>,
) -> CliResult<Vec<u8>> {
    register_font();
    let fail = |e: String| CliError(format!("cannot draw {}: {e}", files::shown(path)));
    if svg {
        let mut text = String::new();
        {
            let root = SVGBackend::with_string(&mut text, size).into_drawing_area();
            svg_draw(&root).map_err(fail)?;
            root.present().map_err(|e| fail(e.to_string()))?;
        }
        Ok(text.into_bytes())
    } else {
        let mut buf = vec![255u8; (size.0 * size.1 * 3) as usize];
        {
            let root = BitMapBackend::with_buffer(&mut buf, size).into_drawing_area();
            png_draw(&root).map_err(fail)?;
            root.present().map_err(|e| fail(e.to_string()))?;
        }
        encode_png(&buf, size.0, size.1).map_err(fail)
    }
}

/// An RGB pixel buffer of `w` × `h` as PNG bytes.
pub(crate) fn encode_png(buf: &[u8], w: u32, h: u32) -> Result<Vec<u8>, String> {
    let mut png = Vec::new();
    image::codecs::png::PngEncoder::new(&mut png)
        .write_image(buf, w, h, image::ExtendedColorType::Rgb8)
        .map_err(|e| e.to_string())?;
    Ok(png)
}

/// The figures' font at `size` px, black.
pub(crate) fn font(size: f64) -> TextStyle<'static> {
    (FONT_FAMILY, size).into_font().color(&BLACK)
}

/// What drawing on a bitmap returns.
pub(crate) type DrawResult =
    Result<(), DrawingAreaErrorKind<<BitMapBackend<'static> as DrawingBackend>::ErrorType>>;

fn draw_titles(root: &Area, scene: &Scene, observer: Vec3, n: usize, title: &str) -> DrawResult {
    let w = FIGURE_WIDTH as i32;
    root.draw(&Text::new(
        title.to_string(),
        (w / 2, 20),
        font(24.0).pos(Pos::new(HPos::Center, VPos::Center)),
    ))?;
    let sub = format!(
        "observer {} m · straw axis ({}, {}) m · water height {} m · n_water = {} · {} image points · lengths in metres, same scale on every axis",
        triple(observer),
        num(scene.straw_x),
        num(scene.straw_y),
        num(scene.water_height),
        num(scene.n_water),
        n
    );
    root.draw(&Text::new(
        sub,
        (w / 2, 48),
        font(15.0)
            .color(&RGBColor(60, 60, 60))
            .pos(Pos::new(HPos::Center, VPos::Center)),
    ))?;
    Ok(())
}

/// The panes of the box's three far faces, with grid lines at the ticks, and the panel's caption.
pub(crate) fn draw_panes<DB: DrawingBackend>(
    root: &AreaOn<DB>,
    panel: &Panel,
    bx: &AxisBox,
) -> DrawResultOn<DB> {
    root.draw(&Text::new(
        panel.caption.clone(),
        (
            panel.left + panel.width / 2,
            panel.top + CAPTION_BAND / 2 + 2,
        ),
        font(16.0).pos(Pos::new(HPos::Center, VPos::Center)),
    ))?;
    let proj = &panel.proj;
    let pane = RGBColor(244, 244, 246);
    let grid = RGBColor(218, 218, 224);
    let edge = RGBColor(170, 170, 178);
    for a in 0..3 {
        let t = proj.toward[a];
        if t.abs() < 1e-6 {
            continue;
        }
        // The far face along axis a: the viewer is on the other side.
        let at = if t > 0.0 { bx.min[a] } else { bx.max[a] };
        let (b, c) = ((a + 1) % 3, (a + 2) % 3);
        let corner = |vb: f64, vc: f64| {
            let mut p = Vec3::ZERO;
            p[a] = at;
            p[b] = vb;
            p[c] = vc;
            p
        };
        let quad = [
            corner(bx.min[b], bx.min[c]),
            corner(bx.max[b], bx.min[c]),
            corner(bx.max[b], bx.max[c]),
            corner(bx.min[b], bx.max[c]),
        ];
        root.draw(&Polygon::new(
            quad.iter().map(|&q| proj.at(q)).collect::<Vec<_>>(),
            pane.filled(),
        ))?;
        // On a pane seen at a grazing angle the grid lines would only be a smudge.
        if t.abs() >= 0.3 {
            for v in ticks(bx.min[b], bx.max[b], axis_step(bx, b)) {
                line(root, proj, corner(v, bx.min[c]), corner(v, bx.max[c]), grid)?;
            }
            for v in ticks(bx.min[c], bx.max[c], axis_step(bx, c)) {
                line(root, proj, corner(bx.min[b], v), corner(bx.max[b], v), grid)?;
            }
        }
        let mut outline: Vec<(i32, i32)> = quad.iter().map(|&q| proj.at(q)).collect();
        outline.push(outline[0]);
        root.draw(&PathElement::new(outline, edge))?;
    }
    Ok(())
}

/// The tick step of axis `a`: about five ticks over its range, however short.
fn axis_step(bx: &AxisBox, a: usize) -> f64 {
    tick_step(bx.max[a] - bx.min[a], 5.0)
}

fn line<DB: DrawingBackend>(
    root: &AreaOn<DB>,
    proj: &Projection,
    a: Vec3,
    b: Vec3,
    color: RGBColor,
) -> DrawResultOn<DB> {
    root.draw(&PathElement::new(vec![proj.at(a), proj.at(b)], color))
}

/// The water's wireframe segments on the near (`front`) or far side of the glass's axis.
pub(crate) fn draw_water<DB: DrawingBackend>(
    root: &AreaOn<DB>,
    proj: &Projection,
    scene: &Scene,
    front: bool,
) -> DrawResultOn<DB> {
    let axis_depth = proj.nearness(Vec3::new(0.0, 0.0, scene.water_height / 2.0));
    let color = if front {
        rgb(WATER_RGB).mix(0.75)
    } else {
        rgb(WATER_RGB).mix(0.45)
    };
    for [a, b] in water_segments(scene) {
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
    scene: &Scene,
) -> DrawResultOn<DB> {
    let color = rgb(STRAW_OUTLINE_RGB);
    for k in 0..=SECTION_COUNT {
        let c = circle(
            scene.straw_x,
            scene.straw_y,
            STRAW_RADIUS,
            k as f64 * SECTION_HEIGHT,
        );
        let px: Vec<(f64, f64)> = c.iter().map(|&p| proj.pixel(p)).collect();
        dashed(root, &px, color)?;
    }
    let side = STRAW_RADIUS * proj.right;
    let axis = Vec3::new(scene.straw_x, scene.straw_y, 0.0);
    for s in [-1.0, 1.0] {
        let a = axis + s * side;
        let b = a + Vec3::new(0.0, 0.0, STRAW_HEIGHT);
        dashed(root, &[proj.pixel(a), proj.pixel(b)], color)?;
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

/// Image points as small squares in their section colours, drawn from far to near.
pub(crate) fn draw_points(buf: &mut [u8], w: u32, h: u32, panel: &Panel, points: &[ImagePoint]) {
    let proj = &panel.proj;
    let mut order: Vec<(f64, usize)> = points
        .iter()
        .enumerate()
        .filter(|(_, p)| p.position.is_finite())
        .map(|(i, p)| (proj.nearness(p.position), i))
        .collect();
    // Stable, so that equal depths keep the input order and the picture is reproducible.
    order.par_sort_by(|a, b| a.0.total_cmp(&b.0));
    let (x0, y0) = (panel.left.max(0), panel.top.max(0));
    let x1 = (panel.left + panel.width).min(w as i32);
    let y1 = (panel.top + panel.height).min(h as i32);
    for (_, i) in order {
        let p = &points[i];
        let (px, py) = proj.pixel(p.position);
        let c = section_rgb8(p.color);
        let (cx, cy) = (
            (px - DOT as f64 / 2.0).round() as i32,
            (py - DOT as f64 / 2.0).round() as i32,
        );
        for y in cy.max(y0)..(cy + DOT).min(y1) {
            for x in cx.max(x0)..(cx + DOT).min(x1) {
                let k = ((y as u32 * w + x as u32) * 3) as usize;
                buf[k..k + 3].copy_from_slice(&c);
            }
        }
    }
}

/// Tick labels and axis names along three outer edges of the box.
pub(crate) fn draw_axis_labels<DB: DrawingBackend>(
    root: &AreaOn<DB>,
    panel: &Panel,
    bx: &AxisBox,
) -> DrawResultOn<DB> {
    let proj = &panel.proj;
    let (ox, oy) = proj.pixel(bx.centre());
    let names = ["x (m)", "y (m)", "z (m)"];
    for a in 0..3 {
        let dir = {
            let mut d = Vec3::ZERO;
            d[a] = 1.0;
            d
        };
        // An axis seen end-on has no readable labels.
        let on_screen = (dir.dot(proj.right)).hypot(dir.dot(proj.up));
        if on_screen < 0.3 {
            continue;
        }
        let step = axis_step(bx, a);
        let (b, c) = ((a + 1) % 3, (a + 2) % 3);
        // Of the four edges along this axis, the one farthest out on screen: bottom-most for an axis
        // running across the screen, else left-most for z and right-most for x and y (so that two
        // axes never share a side); ties go to the edge farther from the viewer, where the grid lines
        // of the far panes meet it.
        let (ex, ey) = (dir.dot(proj.right), -dir.dot(proj.up));
        let across = ex.abs() >= ey.abs();
        let mut best: Option<(f64, Vec3)> = None;
        for (vb, vc) in [
            (bx.min[b], bx.min[c]),
            (bx.max[b], bx.min[c]),
            (bx.min[b], bx.max[c]),
            (bx.max[b], bx.max[c]),
        ] {
            let mut base = Vec3::ZERO;
            base[b] = vb;
            base[c] = vc;
            base[a] = 0.5 * (bx.min[a] + bx.max[a]);
            let (mx, my) = proj.pixel(base);
            let outwards = if across {
                my
            } else if a == 2 {
                -mx
            } else {
                mx
            };
            let score = outwards - 1e-3 * proj.nearness(base) * proj.scale;
            if best.is_none_or(|(s, _)| score > s + 1e-6) {
                best = Some((score, base));
            }
        }
        let Some((_, mid)) = best else { continue };
        let (mx, my) = proj.pixel(mid);
        let (mut lo, mut hi) = (mid, mid);
        lo[a] = bx.min[a];
        hi[a] = bx.max[a];
        line(root, proj, lo, hi, RGBColor(120, 120, 128))?;
        // Labels go outwards, perpendicular to the edge on screen.
        let (mut nx, mut ny) = (-ey, ex);
        let len = nx.hypot(ny).max(1e-9);
        nx /= len;
        ny /= len;
        if nx * (mx - ox) + ny * (my - oy) < 0.0 {
            nx = -nx;
            ny = -ny;
        }
        let tick_color = RGBColor(90, 90, 96);
        // Foreshortened axes get a label every `every` ticks, so that labels never overlap.
        let gap = step * proj.scale * on_screen;
        let room = if across { 44.0 } else { 17.0 };
        let every = (room / gap.max(1e-9)).ceil().max(1.0) as i64;
        // A text's centre goes this far out along the normal so that its box clears `gap` pixels.
        let reach = |text: &str, size: f64| {
            let (tw, th) = (text_width(text, size) as f64, size);
            nx.abs() * tw / 2.0 + ny.abs() * th / 2.0
        };
        let mut widest = 0f64;
        for v in ticks(bx.min[a], bx.max[a], step) {
            let mut p = mid;
            p[a] = v;
            let (tx, ty) = proj.pixel(p);
            root.draw(&PathElement::new(
                vec![
                    (tx.round() as i32, ty.round() as i32),
                    (
                        (tx + 5.0 * nx).round() as i32,
                        (ty + 5.0 * ny).round() as i32,
                    ),
                ],
                tick_color,
            ))?;
            if ((v / step).round() as i64).rem_euclid(every) != 0 {
                continue;
            }
            let text = tick_label(v, step);
            let r = reach(&text, 12.0);
            widest = widest.max(2.0 * r);
            let d = 8.0 + r;
            root.draw(&Text::new(
                text,
                ((tx + d * nx).round() as i32, (ty + d * ny).round() as i32),
                font(12.0)
                    .color(&tick_color)
                    .pos(Pos::new(HPos::Center, VPos::Center)),
            ))?;
        }
        let d = 8.0 + widest + 8.0 + reach(names[a], 14.0);
        root.draw(&Text::new(
            names[a],
            ((mx + d * nx).round() as i32, (my + d * ny).round() as i32),
            font(14.0).pos(Pos::new(HPos::Center, VPos::Center)),
        ))?;
    }
    Ok(())
}

/// The observer as a black dot, or, when too far away to draw to scale, an arrow pointing to it.
pub(crate) fn draw_observer<DB: DrawingBackend>(
    root: &AreaOn<DB>,
    panel: &Panel,
    bx: &AxisBox,
    observer: Vec3,
) -> DrawResultOn<DB> {
    let proj = &panel.proj;
    if bx.observer_inside {
        let (x, y) = proj.at(observer);
        // Seen from the observer's own direction the marker sits on the image: a ring hides less.
        let head_on = proj
            .toward
            .dot((observer - SCENE_CENTRE).normalize_or_zero())
            > 0.999;
        if head_on {
            root.draw(&Circle::new((x, y), 5, BLACK.stroke_width(2)))?;
        } else {
            root.draw(&Circle::new((x, y), 5, BLACK.filled()))?;
        }
        // A pale backing keeps the label readable over the points.
        let tw = text_width("observer", 13.0);
        root.draw(&Rectangle::new(
            [(x + 7, y - 9), (x + 11 + tw, y + 9)],
            WHITE.mix(0.75).filled(),
        ))?;
        root.draw(&Text::new(
            "observer",
            (x + 9, y),
            font(13.0).pos(Pos::new(HPos::Left, VPos::Center)),
        ))?;
        return Ok(());
    }
    let Some((tail, tip)) = bx.observer_arrow else {
        return Ok(());
    };
    let (tx, ty) = proj.pixel(tip);
    let (sx, sy) = proj.pixel(tail);
    let (dx, dy) = (tx - sx, ty - sy);
    let len = dx.hypot(dy);
    let note_at = (panel.left + panel.width / 2, panel.top + CAPTION_BAND + 10);
    let note = format!("observer at {} m, off the frame", triple(observer));
    let note_style = font(13.0).pos(Pos::new(HPos::Center, VPos::Center));
    if len < 18.0 {
        // Seen end-on, the arrow would be a dot: say where the observer is instead.
        let s = format!(
            "{note}, {}",
            if proj.nearness(observer) > 0.0 {
                "towards you"
            } else {
                "away from you, behind the glass"
            }
        );
        return root.draw(&Text::new(s, note_at, note_style));
    }
    root.draw(&Text::new(format!("{note} (arrow)"), note_at, note_style))?;
    let (ux, uy) = (dx / len, dy / len);
    root.draw(&PathElement::new(
        vec![(sx as i32, sy as i32), (tx as i32, ty as i32)],
        BLACK.stroke_width(2),
    ))?;
    let (px, py) = (-uy, ux);
    let head = vec![
        (tx as i32, ty as i32),
        (
            (tx - 11.0 * ux + 5.0 * px) as i32,
            (ty - 11.0 * uy + 5.0 * py) as i32,
        ),
        (
            (tx - 11.0 * ux - 5.0 * px) as i32,
            (ty - 11.0 * uy - 5.0 * py) as i32,
        ),
    ];
    root.draw(&Polygon::new(head, BLACK.filled()))?;
    // "observer" beside the arrow's middle: above a level arrow, right of a steep one.
    let (mx, my) = (0.5 * (sx + tx), 0.5 * (sy + ty));
    let (at, pos) = if ux.abs() >= uy.abs() {
        (
            (mx as i32, my as i32 - 6),
            Pos::new(HPos::Center, VPos::Bottom),
        )
    } else {
        (
            (mx as i32 + 9, my as i32),
            Pos::new(HPos::Left, VPos::Center),
        )
    };
    root.draw(&Text::new("observer", at, font(13.0).pos(pos)))
}

/// The colour codes with their heights and point counts, the observer, the wireframes.
fn draw_legend(root: &Area, points: &[ImagePoint], observer_inside: bool) -> DrawResult {
    let n = counts(points);
    let y = FIGURE_HEIGHT as i32 - LEGEND_BAND / 2;
    let mut x = 24;
    let style = font(14.0).pos(Pos::new(HPos::Left, VPos::Center));
    for (k, count) in n.iter().enumerate() {
        let c = section_rgb8(k as u8 + 1);
        root.draw(&Rectangle::new(
            [(x, y - 7), (x + 14, y + 7)],
            RGBColor(c[0], c[1], c[2]).filled(),
        ))?;
        let s = format!(
            "{} {}, z {:.2}–{:.2} m: {}",
            k + 1,
            SECTION_NAMES[k],
            k as f64 * SECTION_HEIGHT,
            (k + 1) as f64 * SECTION_HEIGHT,
            count
        );
        root.draw(&Text::new(s.clone(), (x + 20, y), style.clone()))?;
        x += 20 + text_width(&s, 14.0) + 22;
    }
    root.draw(&Circle::new((x + 6, y), 5, BLACK.filled()))?;
    let who = if observer_inside {
        "observer"
    } else {
        "observer (far: arrow)"
    };
    root.draw(&Text::new(who, (x + 16, y), style.clone()))?;
    x += 16 + text_width(who, 14.0) + 22;
    root.draw(&PathElement::new(
        vec![(x, y), (x + 24, y)],
        rgb(WATER_RGB).stroke_width(2),
    ))?;
    root.draw(&Text::new("water (wireframe)", (x + 30, y), style.clone()))?;
    x += 30 + text_width("water (wireframe)", 14.0) + 22;
    dashed(
        root,
        &[(x as f64, y as f64), (x as f64 + 24.0, y as f64)],
        rgb(STRAW_OUTLINE_RGB),
    )?;
    root.draw(&Text::new("straw, true outline", (x + 30, y), style))?;
    Ok(())
}

/// Width of `s` in pixels at `size`.
pub(crate) fn text_width(s: &str, size: f64) -> i32 {
    font(size)
        .font
        .layout_box(s)
        .map(|((x0, _), (x1, _))| x1 - x0)
        .unwrap_or((s.len() as f64 * size * 0.6) as i32)
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use bentstraw_optics::sampling::sample_image;
    use bentstraw_optics::scene::REFERENCES;

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

    /// Whether some pixel of the panels (not the legend) has exactly colour `c`.
    fn panels_have(img: &image::RgbImage, c: [u8; 3]) -> bool {
        img.enumerate_pixels().any(|(_, y, p)| {
            (y as i32) > TITLE_BAND && (y as i32) < FIGURE_HEIGHT as i32 - LEGEND_BAND && p.0 == c
        })
    }

    #[test]
    fn figure_is_a_png_of_the_stated_size_showing_exactly_the_colours_present() {
        let scene = Scene::with_defaults(0.0, 0.0, 0.1).unwrap();
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
        let png = render_cloud_figure(&scene, Vec3::new(0.1, 0.0, 0.1), &points, "test").unwrap();
        let img = decode(&png);
        assert_eq!(img.dimensions(), (FIGURE_WIDTH, FIGURE_HEIGHT));
        for code in [1, 2, 4] {
            assert!(
                panels_have(&img, section_rgb8(code)),
                "colour {code} missing"
            );
        }
        for code in [3, 5] {
            assert!(
                !panels_have(&img, section_rgb8(code)),
                "colour {code} drawn without points"
            );
        }
    }

    #[test]
    fn reference_figure_is_written_and_shows_every_colour_seen() {
        let r = REFERENCES[1];
        let scene = r.scene(1.333);
        let cloud = sample_image(&scene, r.observer, 2000, &|_| {});
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("ref.png");
        write_cloud_figure(&path, &scene, r.observer, &cloud.points, "Reference 2").unwrap();
        let img = decode(&std::fs::read(&path).unwrap());
        assert_eq!(img.dimensions(), (FIGURE_WIDTH, FIGURE_HEIGHT));
        let n = counts(&cloud.points);
        for code in 1..=5u8 {
            if n[(code - 1) as usize] > 0 {
                assert!(
                    panels_have(&img, section_rgb8(code)),
                    "colour {code} missing"
                );
            }
        }
        // Nothing else is left in the folder (the write is atomic).
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
    }

    #[test]
    fn observer_is_a_black_dot_where_each_view_projects_it() {
        let scene = Scene::with_defaults(0.02, 0.01, 0.15).unwrap();
        let observer = Vec3::new(-0.07, 0.06, 0.17);
        let png = render_cloud_figure(&scene, observer, &[], "observer").unwrap();
        let img = decode(&png);
        let bx = axis_box(&scene, observer, &[]);
        assert!(bx.observer_inside);
        for p in layout(&bx, &figure_views(observer)) {
            let (x, y) = p.proj.pixel(observer);
            let (x, y) = (x.round() as i32, y.round() as i32);
            // A dot, or a ring in the view from the observer's own direction: either way black
            // pixels all round within 6 px, left and right, above and below.
            let black = |dx: std::ops::RangeInclusive<i32>, dy: std::ops::RangeInclusive<i32>| {
                dx.clone().any(|i| {
                    dy.clone()
                        .any(|j| img.get_pixel((x + i) as u32, (y + j) as u32).0 == [0, 0, 0])
                })
            };
            assert!(
                black(-6..=-3, -1..=1) && black(3..=6, -1..=1),
                "no marker at ({x}, {y})"
            );
            assert!(
                black(-1..=1, -6..=-3) && black(-1..=1, 3..=6),
                "no marker at ({x}, {y})"
            );
        }
    }

    #[test]
    fn empty_glass_and_no_points_still_draw() {
        let scene = Scene::with_defaults(0.01, 0.0, 0.0).unwrap();
        let png = render_cloud_figure(&scene, Vec3::new(0.0, -0.2, 0.3), &[], "empty").unwrap();
        assert_eq!(decode(&png).dimensions(), (FIGURE_WIDTH, FIGURE_HEIGHT));
        assert_eq!(water_segments(&scene).len(), 2 * CIRCLE_SEGMENTS);
    }

    #[test]
    fn same_inputs_give_the_same_bytes() {
        let r = REFERENCES[2];
        let scene = r.scene(1.333);
        let cloud = sample_image(&scene, r.observer, 3000, &|_| {});
        let a = render_cloud_figure(&scene, r.observer, &cloud.points, "again").unwrap();
        let b = render_cloud_figure(&scene, r.observer, &cloud.points, "again").unwrap();
        assert!(a == b, "two renderings differ");
    }

    #[test]
    fn unwritable_path_is_an_error_not_a_panic() {
        let scene = Scene::with_defaults(0.0, 0.0, 0.1).unwrap();
        let path = Path::new("/nonexistent-folder/fig.png");
        assert!(write_cloud_figure(path, &scene, Vec3::new(0.1, 0.0, 0.1), &[], "t").is_err());
    }

    #[test]
    fn axis_box_holds_glass_straw_points_and_a_near_observer() {
        let scene = Scene::with_defaults(0.02, 0.01, 0.15).unwrap();
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
        let scene = Scene::with_defaults(0.0, 0.0, 0.15).unwrap();
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
    fn views_are_not_mirrored_and_the_first_looks_from_the_observer() {
        for observer in [
            Vec3::new(0.0, 0.1, 0.1),
            Vec3::new(0.1, 0.0, -0.1),
            Vec3::new(-0.3, 0.2, 0.5),
            Vec3::new(0.0, 0.0, 0.6),
        ] {
            let views = figure_views(observer);
            for (v, _) in &views {
                let (r, u, t) = (v.right(), v.up(), v.toward_viewer());
                // Screen right × screen up points at the viewer: a right-handed, unmirrored picture.
                assert!((r.cross(u) - t).length() < 1e-12);
                assert!(r.dot(u).abs() < 1e-12 && (u.length() - 1.0).abs() < 1e-12);
                assert!(r.z == 0.0, "z must stay upright");
            }
            let to_observer = (observer - SCENE_CENTRE).normalize();
            assert!((views[0].0.toward_viewer() - to_observer).length() < 1e-12);
        }
        // Level views say "elevation 0°", not "-0°".
        let (_, caption) = &figure_views(Vec3::new(1.0, 0.0, SCENE_CENTRE.z - 1e-12))[0];
        assert!(caption.contains("elevation 0°"), "{caption}");
    }

    #[test]
    fn every_panel_holds_its_whole_box_with_room_for_labels() {
        let far = Vec3::new(3.0, -1.0, 0.4);
        for (scene, observer) in REFERENCES
            .iter()
            .map(|r| (r.scene(1.333), r.observer))
            .chain([(Scene::with_defaults(0.0, 0.0, 0.1).unwrap(), far)])
        {
            let bx = axis_box(&scene, observer, &[]);
            let panels = layout(&bx, &figure_views(observer));
            assert_eq!(panels.len(), 3);
            for p in &panels {
                for k in bx.corners() {
                    let (x, y) = p.proj.pixel(k);
                    let (l, r) = (
                        p.left as f64 + PAD_SIDE,
                        (p.left + p.width) as f64 - PAD_SIDE,
                    );
                    let (t, b) = (
                        (p.top + CAPTION_BAND) as f64 + PAD_TOP - 1e-6,
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
        let scene = Scene::with_defaults(0.0, 0.0, 0.15).unwrap();
        let segs = water_segments(&scene);
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
