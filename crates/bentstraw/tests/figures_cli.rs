//! Every figure read back from its file: SVGs parse and say what they show (titles, views, axes
//! and which way they run), their text is legible printed 8.5 cm wide, each panel has one
//! horizontal and one vertical scale, the ray diagram's paths are the traced light paths, PDFs open
//! and render at the figure's shape, and an unknown extension is refused before any work.

use std::fs;
use std::path::Path;
use std::process::{Command, Output};

use bentstraw_optics::geometry::Ray;
use bentstraw_optics::ray_diagram::diagram_rays;
use bentstraw_optics::sampling::sample_image;
use bentstraw_optics::scene::{REFERENCES, SECTION_RGB};
use bentstraw_optics::world::World;
use bentstraw_optics::Vec3;

use crate::test_support::require_tool;

/// Runs the binary in `dir` with `args`.
fn bentstraw(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_bentstraw"))
        .current_dir(dir)
        .args(args)
        .output()
        .expect("the binary runs")
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// `simulate` of reference simulation `k` (1..=4) with `points` and `extra` arguments; must succeed.
fn simulate(dir: &Path, k: usize, points: usize, extra: &[&str]) {
    let r = &REFERENCES[k - 1];
    let o = r.observer;
    let observer = format!("{},{},{}", o.x, o.y, o.z);
    let straw = format!("{},{}", r.straw.0, r.straw.1);
    let he = format!("{}", r.water_height);
    let n = points.to_string();
    let mut args = vec![
        "simulate",
        "--observer",
        &observer,
        "--straw",
        &straw,
        "--water-height",
        &he,
        "--points",
        &n,
        "--output",
        "points.csv",
    ];
    args.extend_from_slice(extra);
    let out = bentstraw(dir, &args);
    assert!(out.status.success(), "{args:?}: {}", stderr(&out));
}

/// The smallest font size allowed, as a share of the figure's width: 7 pt when printed 8.5 cm
/// wide (7/72 inch = 0.247 cm).
const MIN_TEXT_SHARE: f64 = 7.0 / 72.0 * 2.54 / 8.5;

/// A parsed SVG figure: its size, and its texts with their font size and whether rotated.
struct Svg {
    width: f64,
    height: f64,
    texts: Vec<(String, f64, bool)>,
    source: String,
}

fn read_svg(path: &Path) -> Svg {
    let source = fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let doc = roxmltree::Document::parse(&source)
        .unwrap_or_else(|e| panic!("{} is not well-formed XML: {e}", path.display()));
    let root = doc.root_element();
    assert_eq!(root.tag_name().name(), "svg");
    let num = |n: roxmltree::Node, a: &str| -> f64 {
        n.attribute(a)
            .unwrap_or_else(|| panic!("{}: no {a}", path.display()))
            .parse()
            .unwrap()
    };
    let (width, height) = (num(root, "width"), num(root, "height"));
    let texts = doc
        .descendants()
        .filter(|n| n.has_tag_name("text"))
        .map(|n| {
            (
                n.text().unwrap_or("").trim().to_string(),
                num(n, "font-size"),
                n.attribute("transform")
                    .is_some_and(|t| t.contains("rotate")),
            )
        })
        .collect();
    Svg {
        width,
        height,
        texts,
        source,
    }
}

impl Svg {
    /// Every text is at least 7 pt when the figure is printed 8.5 cm wide; the title is larger.
    fn assert_legible(&self, name: &str) {
        let least = MIN_TEXT_SHARE * self.width;
        assert!(!self.texts.is_empty(), "{name}: no text");
        for (t, size, _) in &self.texts {
            assert!(
                *size >= least,
                "{name}: '{t}' is {size} px, under 7 pt at 8.5 cm ({least:.1} px of {})",
                self.width
            );
        }
        let largest = self.texts.iter().map(|t| t.1).fold(0.0, f64::max);
        let smallest = self.texts.iter().map(|t| t.1).fold(f64::MAX, f64::min);
        assert!(largest > smallest, "{name}: the title is not larger");
    }

    fn has(&self, want: &str) -> bool {
        self.texts.iter().any(|t| t.0.contains(want))
    }

    fn assert_has(&self, name: &str, wants: &[&str]) {
        for w in wants {
            assert!(self.has(w), "{name}: no text '{w}' in {:?}", self.texts);
        }
    }

    /// The axis names ("x (m) →", "← y (m)", …): (text, rotated).
    fn axis_names(&self) -> Vec<(String, bool)> {
        self.texts
            .iter()
            .filter(|(t, _, _)| {
                ["x", "y", "z"]
                    .iter()
                    .any(|a| *t == format!("{a} (m) →") || *t == format!("← {a} (m)"))
            })
            .map(|(t, _, r)| (t.clone(), *r))
            .collect()
    }
}

/// The three-view figure of a steep observer (simulation 4, elevation −66°): one horizontal and
/// one vertical scale per panel, named with the way they run, up is up, the observer marked.
#[test]
fn cloud_figure_svg_has_one_scale_each_way_per_panel_and_legible_text() {
    let dir = tempfile::tempdir().unwrap();
    simulate(dir.path(), 4, 3000, &["--plot", "fig.svg"]);
    let svg = read_svg(&dir.path().join("fig.svg"));
    svg.assert_legible("fig.svg");
    svg.assert_has(
        "fig.svg",
        &[
            "observer (0.1, 0, -0.1) m",
            "front view, from +x",
            "side view, from −y",
            "top view, from above",
            "observer",
            "1 red",
            "5 blue",
            "water (wireframe)",
        ],
    );
    let names = svg.axis_names();
    // Three panels: three names across, three up (written bottom to top), no more.
    assert_eq!(names.len(), 6, "{names:?}");
    let up: Vec<&String> = names.iter().filter(|n| n.1).map(|n| &n.0).collect();
    let across: Vec<&String> = names.iter().filter(|n| !n.1).map(|n| &n.0).collect();
    assert_eq!(up.len(), 3, "{names:?}");
    // Up is up: z in the front and side views, y from above, all increasing upwards.
    assert_eq!(up, ["z (m) →", "z (m) →", "y (m) →"]);
    // Seen from +x, y runs to the right; from −y, x runs to the right; from above, x.
    assert_eq!(across, ["y (m) →", "x (m) →", "x (m) →"]);
    // The points are drawn: squares in the colours of the sections seen.
    let csv = fs::read_to_string(dir.path().join("points.csv")).unwrap();
    for (k, rgb) in SECTION_RGB.iter().enumerate() {
        let code = format!(",{}", k + 1);
        let seen = csv.lines().skip(1).any(|l| l.ends_with(&code));
        let [r, g, b] = rgb.map(|v| (v * 255.0).round() as u8);
        let fill = format!("fill=\"#{r:02X}{g:02X}{b:02X}\"");
        let drawn = svg
            .source
            .lines()
            .filter(|l| l.contains(&fill))
            .map(|l| {
                if l.starts_with("<rect") {
                    1
                } else if l.starts_with("<path") {
                    // Many rectangles of one colour are one path, a sub-path each.
                    l.matches('M').count()
                } else {
                    0
                }
            })
            .sum::<usize>();
        // The legend's swatch is one; points make many.
        assert_eq!(drawn > 20, seen, "colour {}: {drawn} rectangles", k + 1);
    }
}

/// A front view from +y: x increases to the left, and its name says so.
#[test]
fn an_axis_running_left_says_so() {
    let dir = tempfile::tempdir().unwrap();
    let args = [
        "simulate",
        "--observer",
        "0.02,0.2,0.1",
        "--straw",
        "0,0",
        "--water-height",
        "0.1",
        "--points",
        "500",
        "--output",
        "p.csv",
        "--plot",
        "f.svg",
    ];
    let out = bentstraw(dir.path(), &args);
    assert!(out.status.success(), "{}", stderr(&out));
    let svg = read_svg(&dir.path().join("f.svg"));
    let across: Vec<String> = svg
        .axis_names()
        .into_iter()
        .filter(|n| !n.1)
        .map(|n| n.0)
        .collect();
    assert_eq!(across, ["← x (m)", "y (m) →", "x (m) →"]);
}

/// Each solid path of the ray diagram is a traced ray: its vertices, mapped back from pixels with
/// one scale per panel (the same across and up), are the eye, the ray's events as the library
/// traces them, and the straw point, within the pixel's rounding.
#[test]
fn ray_diagram_paths_are_the_traced_light_paths() {
    let dir = tempfile::tempdir().unwrap();
    let points = 4000;
    simulate(dir.path(), 3, points, &["--rays", "rays.svg"]);
    let svg = read_svg(&dir.path().join("rays.svg"));
    svg.assert_legible("rays.svg");
    svg.assert_has("rays.svg", &["side view", "top view", "eye", "refraction"]);
    // The rays simulate drew: the library's choice among the same points.
    let r = &REFERENCES[2];
    let scene = r.scene(1.333);
    let cloud = sample_image(&World::assignment(&scene), r.observer, points, &|_| {});
    let rays = diagram_rays(&World::assignment(&scene), r.observer, &cloud.points, 40);
    assert!(rays.len() >= 30, "{} rays", rays.len());
    // Traced again here, independently of what the diagram kept.
    let paths: Vec<Vec<Vec3>> = rays
        .iter()
        .map(|ray| {
            let mut v = vec![r.observer];
            World::assignment(&scene).trace_with(
                Ray {
                    origin: r.observer,
                    direction: ray.image.direction,
                },
                |e| v.push(e.point),
            );
            v.push(ray.image.straw_point);
            v
        })
        .collect();
    // The solid paths: width-3 polylines, not the glass's grey outline; side view first, then top.
    let doc = roxmltree::Document::parse(&svg.source).unwrap();
    let polylines: Vec<Vec<(f64, f64)>> = doc
        .descendants()
        .filter(|n| {
            n.has_tag_name("polyline")
                && n.attribute("stroke-width") == Some("3")
                && n.attribute("stroke") != Some("#787878")
        })
        .map(|n| {
            n.attribute("points")
                .unwrap()
                .split_whitespace()
                .map(|p| {
                    let (x, y) = p.split_once(',').unwrap();
                    (x.parse().unwrap(), y.parse().unwrap())
                })
                .collect()
        })
        .collect();
    assert_eq!(polylines.len(), 2 * rays.len(), "one path per ray and view");
    let o = r.observer;
    let e = Vec3::new(o.x, o.y, 0.0).normalize();
    let side = |p: Vec3| (p.x * e.x + p.y * e.y, p.z);
    let top = |p: Vec3| (p.x, p.y);
    for (view, drawn) in [
        (
            &side as &dyn Fn(Vec3) -> (f64, f64),
            &polylines[..rays.len()],
        ),
        (&top, &polylines[rays.len()..]),
    ] {
        // Pairs of (world (u, v), pixel (x, y)), for a fit x = a + s·u, y = b − s·v.
        let mut pairs: Vec<Pair> = Vec::new();
        for (path, line) in paths.iter().zip(drawn) {
            assert_eq!(path.len(), line.len(), "a path's vertex count");
            for (p, q) in path.iter().zip(line) {
                pairs.push((view(*p), *q));
            }
        }
        let n = pairs.len() as f64;
        let mean = |f: &dyn Fn(&Pair) -> f64| pairs.iter().map(f).sum::<f64>() / n;
        let (mu, mv) = (mean(&|p| p.0 .0), mean(&|p| p.0 .1));
        let (mx, my) = (mean(&|p| p.1 .0), mean(&|p| p.1 .1));
        let num: f64 = pairs
            .iter()
            .map(|((u, v), (x, y))| (u - mu) * (x - mx) - (v - mv) * (y - my))
            .sum();
        let den: f64 = pairs
            .iter()
            .map(|((u, v), _)| (u - mu).powi(2) + (v - mv).powi(2))
            .sum();
        let s = num / den;
        assert!(s > 100.0, "scale {s} px/m");
        let worst = pairs
            .iter()
            .map(|((u, v), (x, y))| {
                let (fx, fy) = (mx + s * (u - mu), my - s * (v - mv));
                (fx - x).hypot(fy - y)
            })
            .fold(0.0, f64::max);
        assert!(
            worst <= 1.5,
            "a vertex is {worst:.2} px from its traced event"
        );
    }
}

/// A point's world coordinates in a view and its pixel in the figure.
type Pair = ((f64, f64), (f64, f64));

/// The figures and ray diagrams of reference 2 written as PDF and as SVG into `dir`
/// (`fig.pdf`, `rays.pdf`, `fig.svg`, `rays.svg`); the PDFs start as PDFs.
fn pdf_and_svg_figures(dir: &tempfile::TempDir) {
    simulate(
        dir.path(),
        2,
        2000,
        &["--plot", "fig.pdf", "--rays", "rays.pdf"],
    );
    simulate(
        dir.path(),
        2,
        2000,
        &["--plot", "fig.svg", "--rays", "rays.svg"],
    );
    for stem in ["fig", "rays"] {
        let pdf = fs::read(dir.path().join(format!("{stem}.pdf"))).unwrap();
        assert!(pdf.starts_with(b"%PDF"), "{stem}.pdf is not a PDF");
    }
}

/// PDFs of the figures: they start as PDFs (their rendering: `pdf_figures_open_at_the_figures_shape`).
#[test]
fn pdf_figures_are_pdfs() {
    pdf_and_svg_figures(&tempfile::tempdir().unwrap());
}

/// PDFs of the figures render with poppler's tools at the SVG's shape, 8.5 cm wide, with their
/// text as text (without poppler-utils, the test fails).
#[test]
#[ignore = "needs poppler's pdftoppm and pdftotext to render and read the PDFs"]
fn pdf_figures_open_at_the_figures_shape() {
    let dir = tempfile::tempdir().unwrap();
    pdf_and_svg_figures(&dir);
    let (pdftoppm, pdftotext) = (require_tool("pdftoppm"), require_tool("pdftotext"));
    for stem in ["fig", "rays"] {
        let svg = read_svg(&dir.path().join(format!("{stem}.svg")));
        // 254 dpi: a page 8.5 cm wide is 850 px.
        let out = Command::new(&pdftoppm)
            .args(["-png", "-r", "254", "-singlefile"])
            .arg(dir.path().join(format!("{stem}.pdf")))
            .arg(dir.path().join(format!("{stem}-page")))
            .output()
            .unwrap();
        assert!(out.status.success(), "pdftoppm: {}", stderr(&out));
        let png = image::open(dir.path().join(format!("{stem}-page.png"))).unwrap();
        assert!(
            png.width().abs_diff(850) <= 1,
            "{stem}.pdf is {} px wide at 254 dpi, not 8.5 cm",
            png.width()
        );
        let (want, got) = (
            svg.height / svg.width,
            png.height() as f64 / png.width() as f64,
        );
        assert!(
            (want - got).abs() < 0.01,
            "{stem}.pdf: aspect {got}, the figure's {want}"
        );
        // Not blank: a good part of the page is drawn.
        let rgb = png.to_rgb8();
        let inked = rgb
            .pixels()
            .filter(|p| p.0.iter().any(|&c| c < 200))
            .count();
        assert!(inked * 50 > rgb.len() / 3, "{stem}.pdf looks blank");
        // The text is text, in the shipped font.
        let text = Command::new(&pdftotext)
            .arg(dir.path().join(format!("{stem}.pdf")))
            .arg("-")
            .output()
            .unwrap();
        let text = String::from_utf8_lossy(&text.stdout);
        let want = if stem == "fig" {
            "front view"
        } else {
            "side view"
        };
        assert!(text.contains(want), "{stem}.pdf: no '{want}' in {text}");
    }
}

/// A figure with an extension that is no figure format: one line naming the file and the formats,
/// exit code 2, nothing written, the previous file kept.
#[test]
fn unknown_figure_extensions_are_refused_before_any_work() {
    for flag in ["--plot", "--rays", "--models-plot", "--gap-plot"] {
        let dir = tempfile::tempdir().unwrap();
        fs::write(dir.path().join("points.csv"), "old").unwrap();
        let r = &REFERENCES[1];
        let o = r.observer;
        let out = bentstraw(
            dir.path(),
            &[
                "simulate",
                "--observer",
                &format!("{},{},{}", o.x, o.y, o.z),
                "--straw",
                &format!("{},{}", r.straw.0, r.straw.1),
                "--water-height",
                &format!("{}", r.water_height),
                "--output",
                "points.csv",
                flag,
                "fig.gif",
            ],
        );
        let err = stderr(&out);
        assert_eq!(out.status.code(), Some(2), "{err}");
        assert_eq!(err.trim_end().lines().count(), 1, "{err}");
        assert!(
            err.contains(&format!("{flag} fig.gif")) && err.contains(".png, .svg or .pdf"),
            "{err}"
        );
        assert_eq!(
            fs::read_to_string(dir.path().join("points.csv")).unwrap(),
            "old"
        );
        assert_eq!(fs::read_dir(dir.path()).unwrap().count(), 1);
    }
}

/// The report's figures: each PNG figure has its SVG beside it, linked from the page, and every
/// SVG of the folder (model comparison, gap plot, ray diagrams, validation) parses, says what it
/// shows and is legible at 8.5 cm. `folder` is the report job's (run once by the test
/// `the_report_job` in `main.rs`).
pub fn the_reports_figures_come_as_svg_too_and_are_legible(folder: &Path) {
    let index = fs::read_to_string(folder.join("index.html")).unwrap();
    let mut svgs: Vec<String> = fs::read_dir(folder)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".svg"))
        .collect();
    svgs.sort();
    // The figures are SVG only (no PNG copy); the PNGs are the pictures.
    for name in fs::read_dir(folder)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".png"))
    {
        assert!(
            name.ends_with("_observer.png")
                || name.ends_with("_cloud.png")
                || name == "classic_view.png",
            "{name}: a figure is drawn as SVG"
        );
    }
    for svg in &svgs {
        assert!(index.contains(&format!("src=\"{svg}\"")), "{svg} not shown");
    }
    // 12 classic figures, 4 comparisons, 4 gap plots, 5 ray diagrams, the validation, and the
    // points and ray diagram of each gallery scene.
    let gallery = bentstraw_io::gallery::GALLERY.len();
    assert_eq!(svgs.len(), 12 + 4 + 4 + 5 + 1 + 2 * gallery, "{svgs:?}");
    for name in &svgs {
        let svg = read_svg(&folder.join(name));
        svg.assert_legible(name);
        let wants: &[&str] = if name.ends_with("_models.svg") {
            &["course", "eye", "stereo", "side view", "top view"]
        } else if name.ends_with("_gap.svg") {
            &["height z of the straw point (m) →", "eye model"]
        } else if name.ends_with("_rays.svg") {
            &["side view", "top view", "eye", "refraction"]
        } else if name == "validation.svg" {
            &["index of the water n →", "simulation 1"]
        } else if name.starts_with("gallery_") {
            &[
                "front view",
                "side view",
                "top view",
                "image points by colour",
            ]
        } else {
            &["front view", "side view", "top view", "Simulation"]
        };
        svg.assert_has(name, wants);
        if name.ends_with("_models.svg") {
            // Six panels, each with one scale across and one up.
            let names = svg.axis_names();
            assert_eq!(names.iter().filter(|n| n.1).count(), 6, "{name}: {names:?}");
            assert_eq!(
                names.iter().filter(|n| !n.1).count(),
                6,
                "{name}: {names:?}"
            );
        }
    }
}

/// `simulate` draws the model comparison and the gap plot too, in any of the formats; they need
/// both models, so their point limit applies.
#[test]
fn simulate_draws_the_model_comparison_and_the_gap_plot() {
    let dir = tempfile::tempdir().unwrap();
    simulate(
        dir.path(),
        1,
        1500,
        &["--models-plot", "m.svg", "--gap-plot", "g.svg"],
    );
    let m = read_svg(&dir.path().join("m.svg"));
    m.assert_legible("m.svg");
    m.assert_has(
        "m.svg",
        &[
            "Where the straw appears",
            "course",
            "eye (small pupil)",
            "stereo",
            "top view",
        ],
    );
    let names = m.axis_names();
    assert_eq!(names.iter().filter(|n| n.1).count(), 6, "{names:?}");
    assert_eq!(names.iter().filter(|n| !n.1).count(), 6, "{names:?}");
    let g = read_svg(&dir.path().join("g.svg"));
    g.assert_legible("g.svg");
    g.assert_has(
        "g.svg",
        &[
            "eye model",
            "stereo model",
            "height z of the straw point (m) →",
        ],
    );
    simulate(
        dir.path(),
        1,
        500,
        &["--models-plot", "m.pdf", "--gap-plot", "g.png"],
    );
    assert!(fs::read(dir.path().join("m.pdf"))
        .unwrap()
        .starts_with(b"%PDF"));
    assert!(fs::read(dir.path().join("g.png"))
        .unwrap()
        .starts_with(b"\x89PNG"));
    // Over the models' limit: refused before any work, nothing written.
    let before = fs::read_dir(dir.path()).unwrap().count();
    let out = bentstraw(
        dir.path(),
        &[
            "simulate",
            "--observer",
            "0,0.1,0.1",
            "--straw",
            "0.02,0.01",
            "--water-height",
            "0.15",
            "--points",
            "3000000",
            "--output",
            "big.csv",
            "--gap-plot",
            "big.svg",
        ],
    );
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    assert!(
        stderr(&out).contains("--points 3000000"),
        "{}",
        stderr(&out)
    );
    assert_eq!(fs::read_dir(dir.path()).unwrap().count(), before);
}

/// A value read off a scale: the tick labels along one edge, fitted as value = a + b·pixel.
struct Scale {
    a: f64,
    b: f64,
}

impl Scale {
    /// The fit of `(pixel, value)` pairs; every label must lie on it within a pixel.
    fn fit(ticks: &[(f64, f64)], what: &str) -> Scale {
        assert!(ticks.len() >= 2, "{what}: {} tick labels", ticks.len());
        let n = ticks.len() as f64;
        let (mp, mv) = (
            ticks.iter().map(|t| t.0).sum::<f64>() / n,
            ticks.iter().map(|t| t.1).sum::<f64>() / n,
        );
        let b = ticks.iter().map(|t| (t.0 - mp) * (t.1 - mv)).sum::<f64>()
            / ticks.iter().map(|t| (t.0 - mp).powi(2)).sum::<f64>();
        let a = mv - b * mp;
        for &(p, v) in ticks {
            assert!(
                ((a + b * p - v) / b).abs() <= 1.0,
                "{what}: the label {v} is off its place ({p} px)"
            );
        }
        Scale { a, b }
    }

    fn at(&self, pixel: f64) -> f64 {
        self.a + self.b * pixel
    }
}

/// The scales of the front and side views are true: labels evenly placed, one metre as long
/// across as up, values increasing to the right and upwards, and the observer's marker where its
/// coordinates are.
#[test]
fn the_scales_read_the_observers_coordinates_at_its_marker() {
    let dir = tempfile::tempdir().unwrap();
    simulate(dir.path(), 2, 1000, &["--plot", "fig.svg"]);
    let svg = read_svg(&dir.path().join("fig.svg"));
    let doc = roxmltree::Document::parse(&svg.source).unwrap();
    let attr = |n: &roxmltree::Node, a: &str| -> f64 { n.attribute(a).unwrap().parse().unwrap() };
    // Tick labels: numbers in the scales' grey.
    let labels: Vec<(f64, f64, f64, bool)> = doc
        .descendants()
        .filter(|n| n.has_tag_name("text") && n.attribute("fill") == Some("#46464C"))
        .filter_map(|n| {
            let v: f64 = n.text()?.trim().parse().ok()?;
            let across = n.attribute("text-anchor") == Some("middle");
            Some((attr(&n, "x"), attr(&n, "y"), v, across))
        })
        .collect();
    let markers: Vec<(f64, f64)> = doc
        .descendants()
        .filter(|n| n.has_tag_name("circle") && n.attribute("r") == Some("8"))
        .map(|n| (attr(&n, "cx"), attr(&n, "cy")))
        .collect();
    let o = REFERENCES[1].observer;
    // Front view from +x: y across, z up; side view from −y: x across, z up.
    for (col, across_value) in [(0.0, o.y), (1.0, o.x)] {
        let in_col = |x: f64| x >= 500.0 * col && x < 500.0 * (col + 1.0);
        // The top row's labels across: the highest row of them in this column.
        let row_y = labels
            .iter()
            .filter(|l| l.3 && in_col(l.0))
            .map(|l| l.1)
            .fold(f64::MAX, f64::min);
        let across: Vec<(f64, f64)> = labels
            .iter()
            .filter(|l| l.3 && in_col(l.0) && l.1 == row_y)
            .map(|l| (l.0, l.2))
            .collect();
        let up: Vec<(f64, f64)> = labels
            .iter()
            .filter(|l| !l.3 && in_col(l.0) && l.1 < row_y)
            .map(|l| (l.1, l.2))
            .collect();
        let (h, v) = (Scale::fit(&across, "across"), Scale::fit(&up, "up"));
        assert!(h.b > 0.0, "column {col}: values must increase to the right");
        assert!(v.b < 0.0, "column {col}: values must increase upwards");
        assert!(
            (h.b + v.b).abs() < 0.01 * h.b,
            "column {col}: {} m per px across, {} up",
            h.b,
            -v.b
        );
        let (mx, my) = *markers
            .iter()
            .find(|m| in_col(m.0) && m.1 < row_y)
            .expect("the observer's marker");
        let px_m = 1.0 / h.b;
        assert!(
            (h.at(mx) - across_value).abs() * px_m <= 1.5,
            "column {col}: the marker reads {} across",
            h.at(mx)
        );
        assert!(
            (v.at(my) - o.z).abs() * px_m <= 1.5,
            "column {col}: the marker reads {} up",
            v.at(my)
        );
    }
}
