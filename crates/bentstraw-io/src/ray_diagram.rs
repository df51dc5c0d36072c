//! The ray diagram: side and top views of a sample of rays, each drawn as its broken path from the
//! eye through the water's faces to the straw, with its events marked (a ring for a refraction, a
//! cross for a total reflection) and the dashed straight line from the eye to its image point; the
//! glass, the water and the straw to scale; the kinds of light path coloured and named in a legend
//! with the share of the image points each makes. PNG, SVG or PDF, by the file's extension.
//!
//! Sized for print: the figure is 1000 px wide and every text at least 30 px (the font's size
//! proper), so printed 8.5 cm wide (a report's column) the smallest text is 7.2 pt.

use std::path::Path;

use bentstraw_optics::image::ImagePoint;
use bentstraw_optics::light_path_type::LightPathType;
use bentstraw_optics::ray_diagram::{diagram_rays, path_type_counts, DiagramRay};
use bentstraw_optics::world::World;
use bentstraw_optics::world::COLOR_RGB;
use bentstraw_optics::Vec3;
use plotters::coord::types::RangedCoordf64;
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use crate::error::Result;
use crate::files;
use crate::plot::{figure_bytes, font, wrap, FigureFormat, CAPTION, CAPTION_LINE, TEXT, TITLE};
use crate::words::{self, Lang};
use bentstraw_optics::setup::Setup;
use bentstraw_optics::sketch::{Figure, Panel, Part};

/// Width of the diagram (px).
pub const DIAGRAM_WIDTH: u32 = 1000;
/// Height of the diagram (px).
pub const DIAGRAM_HEIGHT: u32 = 1160;
/// Rays drawn, about.
pub const DIAGRAM_RAYS: usize = 40;
/// Size of the smallest text (px): 7.2 pt when the figure is printed 8.5 cm wide.
const SMALL_TEXT: f64 = TEXT;
/// Height of a line of the legend (px).
const LEGEND_LINE: i32 = 42;

/// What a diagram shows: the rays drawn, and the image points per kind of light path.
pub struct Diagram {
    /// The observer.
    pub observer: Vec3,
    /// The rays drawn.
    pub rays: Vec<DiagramRay>,
    /// Image points per kind of light path, most common first.
    pub counts: Vec<(LightPathType, usize)>,
}

impl Diagram {
    /// The diagram of `points` (an image seen from `observer`): about [`DIAGRAM_RAYS`] rays.
    pub fn new(world: &World, observer: Vec3, points: &[ImagePoint]) -> Diagram {
        Diagram {
            observer,
            rays: diagram_rays(world, observer, points, DIAGRAM_RAYS),
            counts: path_type_counts(world, observer, points),
        }
    }

    /// The colour of kind `k`: the same in every figure (see [`LightPathType::rgb`]).
    fn color_of(&self, kind: LightPathType) -> RGBColor {
        let [r, g, b] = kind.rgb();
        RGBColor(r, g, b)
    }
}

/// Writes the diagram to `path`, `.png`, `.svg` or `.pdf` by its extension.
pub fn write_ray_diagram(
    path: &Path,
    scene: &Setup,
    diagram: &Diagram,
    title: &str,
    lang: Lang,
) -> Result {
    let bytes = render(path, scene, diagram, title, lang)?;
    files::write_bytes(path, &bytes)
}

/// The diagram as the bytes of a PNG, SVG or PDF file, by `path`'s extension.
pub fn render(
    path: &Path,
    scene: &Setup,
    diagram: &Diagram,
    title: &str,
    lang: Lang,
) -> Result<Vec<u8>> {
    figure_bytes(
        path,
        FigureFormat::of(path)?,
        (DIAGRAM_WIDTH, DIAGRAM_HEIGHT),
        |root| draw(root, scene, diagram, title, lang),
        |root| draw(root, scene, diagram, title, lang),
    )
}

/// The horizontal unit vector from the glass's axis towards the observer (the side view's axis).
fn side_axis(observer: Vec3) -> Vec3 {
    let h = Vec3::new(observer.x, observer.y, 0.0);
    if h.length() < 1e-9 {
        Vec3::X
    } else {
        h.normalize()
    }
}

fn draw<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    scene: &Setup,
    diagram: &Diagram,
    title: &str,
    lang: Lang,
) -> Result<(), String> {
    let e = |x: DrawingAreaErrorKind<DB::ErrorType>| x.to_string();
    root.fill(&WHITE).map_err(e)?;
    let (w, h) = (DIAGRAM_WIDTH as i32, DIAGRAM_HEIGHT as i32);
    // The title's first part in large type, the rest (the inputs) wrapped below it.
    let (head, rest) = title.split_once(": ").unwrap_or((title, ""));
    root.draw(&Text::new(head.to_string(), (20, 10), font(TITLE)))
        .map_err(e)?;
    let mut top = 64;
    for line in wrap(rest, SMALL_TEXT, w - 40) {
        root.draw(&Text::new(line, (20, top), font(SMALL_TEXT)))
            .map_err(e)?;
        top += 40;
    }
    let legend_h = 2 * LEGEND_LINE + 24 + LEGEND_LINE * diagram.counts.len().min(6) as i32;
    let panels_area = root.margin(top + 6, legend_h, 0, 0);
    let (left, right) = panels_area.split_horizontally(w / 2);
    let e_side = side_axis(diagram.observer);
    draw_panel(
        &left,
        scene,
        diagram,
        Panel::Side(e_side),
        words::DIAGRAM_SIDE.map(|t| lang.of(t)),
        lang.of(words::TOWARDS_OBSERVER),
        "z (m) →",
    )?;
    draw_panel(
        &right,
        scene,
        diagram,
        Panel::Top,
        words::DIAGRAM_TOP.map(|t| lang.of(t)),
        "x (m) →",
        "y (m) →",
    )?;
    // Legend: one line per kind of path, with its share of the image points.
    let total: usize = diagram.counts.iter().map(|c| c.1).sum::<usize>().max(1);
    let mut y = h - legend_h + 14;
    for line in words::DIAGRAM_KEY.map(|t| lang.of(t)) {
        root.draw(&Text::new(line.to_string(), (20, y), font(SMALL_TEXT)))
            .map_err(e)?;
        y += LEGEND_LINE;
    }
    y -= LEGEND_LINE;
    for (kind, n) in diagram.counts.iter().take(6) {
        y += LEGEND_LINE;
        let c = diagram.color_of(*kind);
        root.draw(&PathElement::new(
            vec![(20, y + 15), (70, y + 15)],
            c.stroke_width(5),
        ))
        .map_err(e)?;
        root.draw(&Text::new(
            format!(
                "{:4.1} %  {}",
                100.0 * *n as f64 / total as f64,
                lang.light_path(kind)
            ),
            (85, y),
            font(SMALL_TEXT),
        ))
        .map_err(e)?;
    }
    Ok(())
}

/// Range of a panel: the glass, the straw, the observer, every ray vertex and image point, with a
/// margin; widened so that one metre is as long across as up.
fn ranges(scene: &Setup, diagram: &Diagram, view: Panel, aspect: f64) -> ((f64, f64), (f64, f64)) {
    let mut pts: Vec<(f64, f64)> = scene
        .schematic_extent()
        .into_iter()
        .map(|p| view.project(p))
        .collect();
    pts.push(view.project(diagram.observer));
    for r in &diagram.rays {
        pts.push(view.project(r.image.position));
        for v in r.vertices(diagram.observer) {
            pts.push(view.project(v));
        }
    }
    let (mut x0, mut x1, mut y0, mut y1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
    for (x, y) in pts {
        x0 = x0.min(x);
        x1 = x1.max(x);
        y0 = y0.min(y);
        y1 = y1.max(y);
    }
    let pad = 0.06 * (x1 - x0).max(y1 - y0);
    let (mut x0, mut x1, mut y0, mut y1) = (x0 - pad, x1 + pad, y0 - pad, y1 + pad);
    // Equal scales: widen the narrower side to the panel's aspect (width / height in pixels).
    let (dx, dy) = (x1 - x0, y1 - y0);
    if dx / dy < aspect {
        let grow = (dy * aspect - dx) / 2.0;
        x0 -= grow;
        x1 += grow;
    } else {
        let grow = (dx / aspect - dy) / 2.0;
        y0 -= grow;
        y1 += grow;
    }
    ((x0, x1), (y0, y1))
}

#[allow(clippy::too_many_arguments)]
fn draw_panel<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    scene: &Setup,
    diagram: &Diagram,
    view: Panel,
    caption: [&str; 2],
    x_label: &str,
    y_label: &str,
) -> Result<(), String> {
    let e = |x: DrawingAreaErrorKind<DB::ErrorType>| x.to_string();
    let (pw, ph) = area.dim_in_pixel();
    for (k, line) in caption.iter().enumerate() {
        area.draw(&Text::new(
            line.to_string(),
            (pw as i32 / 2, k as i32 * CAPTION_LINE),
            font(CAPTION).pos(Pos::new(HPos::Center, VPos::Top)),
        ))
        .map_err(e)?;
    }
    let caption_h = 2 * CAPTION_LINE + 10;
    let area = area.margin(caption_h, 0, 0, 0);
    // The plotting area's size once labels take their room (as set below).
    let (plot_w, plot_h) = (
        pw as f64 - 150.0 - 40.0,
        ph as f64 - caption_h as f64 - 110.0,
    );
    let ((x0, x1), (y0, y1)) = ranges(scene, diagram, view, plot_w / plot_h);
    let mut chart = ChartBuilder::on(&area)
        .margin_right(40)
        .x_label_area_size(110)
        .y_label_area_size(150)
        .build_cartesian_2d(x0..x1, y0..y1)
        .map_err(e)?;
    chart
        .configure_mesh()
        .disable_mesh()
        .x_labels(4)
        .y_labels(5)
        .label_style(font(SMALL_TEXT))
        .axis_desc_style(font(SMALL_TEXT))
        .x_desc(x_label)
        .y_desc(y_label)
        .x_label_formatter(&|v| tick(*v))
        .y_label_formatter(&|v| tick(*v))
        .draw()
        .map_err(e)?;

    // The scene's schematic, back to front, each part in its style.
    let (water, glass, grey) = (
        RGBColor(200, 225, 250),
        RGBColor(120, 120, 120),
        RGBColor(150, 150, 150),
    );
    for mark in scene.schematic(view) {
        let style = match mark.part {
            Part::Liquid => water.filled(),
            Part::Wall => glass.stroke_width(3),
            Part::Band(code) => {
                let [r, g, b] = COLOR_RGB[code as usize - 1].map(|v| (v * 255.0).round() as u8);
                RGBColor(r, g, b).mix(0.55).filled()
            }
            Part::Footprint => grey.mix(0.6).filled(),
            Part::Edge => glass.mix(0.5).into(),
            Part::Outline => grey.stroke_width(2),
        };
        match mark.figure {
            Figure::Rect(corners) => {
                chart.draw_series(std::iter::once(Rectangle::new(corners, style)))
            }
            Figure::Polygon(points) => {
                chart.draw_series(std::iter::once(Polygon::new(points, style)))
            }
            Figure::Line(points) => {
                chart.draw_series(std::iter::once(PathElement::new(points, style)))
            }
        }
        .map_err(e)?;
    }
    draw_rays(&mut chart, diagram, view)
}

/// The rays of a panel: the dashed line of sight to the image point, the broken path, the
/// events, the image point; then the observer.
fn draw_rays<DB: DrawingBackend>(
    chart: &mut ChartContext<DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>,
    diagram: &Diagram,
    view: Panel,
) -> Result<(), String> {
    let e = |x: DrawingAreaErrorKind<DB::ErrorType>| x.to_string();
    for r in &diagram.rays {
        let color = diagram.color_of(r.kind);
        let eye = view.project(diagram.observer);
        let image = view.project(r.image.position);
        chart
            .draw_series(DashedLineSeries::new(
                vec![eye, image],
                8,
                6,
                color.mix(0.7).stroke_width(2),
            ))
            .map_err(e)?;
        chart
            .draw_series(std::iter::once(PathElement::new(
                r.vertices(diagram.observer)
                    .into_iter()
                    .map(|v| view.project(v))
                    .collect::<Vec<_>>(),
                color.stroke_width(3),
            )))
            .map_err(e)?;
        for ev in &r.events {
            let p = view.project(ev.point);
            if ev.totally_reflected {
                chart
                    .draw_series(std::iter::once(Cross::new(p, 7, color.stroke_width(3))))
                    .map_err(e)?;
            } else {
                chart
                    .draw_series(std::iter::once(Circle::new(p, 5, color.stroke_width(2))))
                    .map_err(e)?;
            }
        }
        let [cr, cg, cb] = COLOR_RGB[r.image.color as usize - 1].map(|v| (v * 255.0).round() as u8);
        chart
            .draw_series(std::iter::once(Circle::new(
                image,
                5,
                RGBColor(cr, cg, cb).filled(),
            )))
            .map_err(e)?;
    }
    // The observer.
    let eye = view.project(diagram.observer);
    chart
        .draw_series(std::iter::once(Circle::new(eye, 8, BLACK.filled())))
        .map_err(e)?;
    let label = EmptyElement::at(eye) + Text::new("eye", (-20, 12), font(SMALL_TEXT));
    chart.draw_series(std::iter::once(label)).map_err(e)?;
    Ok(())
}

/// A tick label in metres, two decimals, without a minus sign on zero.
fn tick(v: f64) -> String {
    let t = format!("{v:.2}");
    if t == "-0.00" {
        "0.00".into()
    } else {
        t
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use bentstraw_optics::sampling::sample_image;
    use bentstraw_optics::scene::{GLASS_RADIUS, REFERENCES};

    fn diagram_of(number: usize) -> (Setup, Diagram) {
        let r = REFERENCES[number - 1];
        let scene = Setup::assignment(r.scene(1.333), r.observer);
        let cloud = sample_image(&scene.world, r.observer, 5000, &|_| {});
        let d = Diagram::new(&scene.world, r.observer, &cloud.points);
        (scene, d)
    }

    /// The rays drawn are the library's: each vertex is a traced event, in order.
    #[test]
    fn the_rays_drawn_are_the_traced_paths() {
        let (scene, d) = diagram_of(3);
        assert!((30..=60).contains(&d.rays.len()), "{} rays", d.rays.len());
        for r in &d.rays {
            let mut points = vec![d.observer];
            let outcome = scene.world.trace_with(
                bentstraw_optics::geometry::Ray {
                    origin: d.observer,
                    direction: r.image.direction,
                },
                |e| points.push(e.point),
            );
            points.push(r.image.straw_point);
            assert_eq!(r.vertices(d.observer), points);
            assert_eq!(outcome.color(), r.image.color);
        }
        // Simulation 3 has pieces of the image outside the glass: the diagram draws the light
        // paths that make them, and they are totally reflected at least once.
        let outside: Vec<_> = d
            .rays
            .iter()
            .filter(|r| r.image.position.truncate().length() > GLASS_RADIUS)
            .collect();
        assert!(
            !outside.is_empty(),
            "no ray to the pieces outside the glass"
        );
        assert!(outside.iter().any(|r| r.kind.total_reflections > 0));
    }

    /// The SVG is well-formed XML, names every kind of path in its legend, and holds one solid
    /// path per ray drawn in each view.
    #[test]
    fn the_svg_names_the_paths_and_draws_every_ray() {
        let (scene, d) = diagram_of(3);
        let svg = render(Path::new("d.svg"), &scene, &d, "simulation 3", Lang::En).unwrap();
        let text = String::from_utf8(svg).unwrap();
        let doc = roxmltree::Document::parse(&text).expect("well-formed SVG");
        let texts: Vec<String> = doc
            .descendants()
            .filter(|n| n.has_tag_name("text"))
            .map(|n| n.text().unwrap_or("").to_string())
            .collect();
        for (kind, _) in &d.counts[..d.counts.len().min(6)] {
            let want = kind.to_string();
            assert!(
                texts.iter().any(|t| t.contains(&want)),
                "legend lacks {want}"
            );
        }
        assert!(texts.iter().any(|t| t.contains("side view")));
        assert!(texts.iter().any(|t| t.contains("top view")));
        // Solid ray paths: width 3 polylines in a kind's colour, one per ray and view.
        let colours: Vec<String> = d
            .counts
            .iter()
            .map(|(k, _)| k.hex().to_uppercase())
            .collect();
        let solid = doc
            .descendants()
            .filter(|n| {
                n.has_tag_name("polyline")
                    && n.attribute("stroke-width") == Some("3")
                    && n.attribute("stroke")
                        .is_some_and(|s| colours.iter().any(|c| c == s))
            })
            .count();
        assert_eq!(solid, 2 * d.rays.len());
    }

    #[test]
    fn png_and_view_for_the_eye() {
        let (scene, d) = diagram_of(3);
        let png = render(Path::new("d.png"), &scene, &d, "simulation 3", Lang::En).unwrap();
        let img = image::load_from_memory(&png).unwrap();
        assert_eq!((img.width(), img.height()), (DIAGRAM_WIDTH, DIAGRAM_HEIGHT));
        if let Ok(dir) = std::env::var("BENTSTRAW_LOOK") {
            std::fs::write(Path::new(&dir).join("diagram3.png"), &png).unwrap();
            let svg = render(Path::new("d.svg"), &scene, &d, "simulation 3", Lang::En).unwrap();
            std::fs::write(Path::new(&dir).join("diagram3.svg"), &svg).unwrap();
        }
    }
}
