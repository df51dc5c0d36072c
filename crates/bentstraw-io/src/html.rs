//! A self-contained, offline, rotatable and zoomable 3D view of the image points (one HTML file).
//!
//! The page embeds its script and style (from `assets/viewer.js` and `assets/viewer.css`) and its data
//! as JSON: the points as base64 little-endian `f32` offsets from the centre of the axis box (compact,
//! and exact to about 1e-8 m at these sizes) and their colour codes as base64 bytes (in white
//! light, their bands: each point is shown in its wavelength's colour).

use std::path::Path;

use bentstraw_optics::image::ImagePoint;
use bentstraw_optics::record::InputValue;
use bentstraw_optics::scene::{GLASS_RADIUS, SECTION_HEIGHT, STRAW_HEIGHT, STRAW_RADIUS};
use bentstraw_optics::Vec3;
use serde_json::json;

use crate::error::Result;
use crate::escape::escape_html;
use crate::files;
use crate::plot::{
    axis_box, degrees, figure_views, legend_entries, legend_key, observer_direction, whole,
    AxisBox, LegendEntry,
};
use bentstraw_optics::setup::Setup;
use bentstraw_optics::sketch::WIRE_VERTICALS;

/// The viewer's script, kept in its own file so it stays readable and lintable.
const VIEWER_JS: &str = include_str!("../assets/viewer.js");
/// The viewer's style sheet.
const VIEWER_CSS: &str = include_str!("../assets/viewer.css");

/// Writes an interactive 3D view of `points`, the scene's wireframe and outlines and the observer
/// to `path`.
pub fn write_cloud_viewer(
    path: &Path,
    scene: &Setup,
    observer: Vec3,
    points: &[ImagePoint],
    title: &str,
) -> Result {
    let stem = path
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default();
    let page = viewer_page(scene, observer, points, title, &stem);
    files::write_bytes(path, page.as_bytes())
}

/// The whole HTML page: the facts, the legend of the colours the scene lists, and the data the
/// script draws.
fn viewer_page(
    scene: &Setup,
    observer: Vec3,
    points: &[ImagePoint],
    title: &str,
    file_stem: &str,
) -> String {
    let bx = axis_box(scene, observer, points);
    let entries = legend_entries(scene, points);
    let data = viewer_data(scene, &bx, observer, points, &entries, title, file_stem);
    // In a <script> element only "</" could end the element early; JSON allows "<" as \u003c.
    let data = data.to_string().replace('<', "\\u003c");
    let mut legend = String::new();
    for e in &entries {
        let [r, g, b] = e.rgb;
        legend.push_str(&format!(
            "<li data-code=\"{code}\" title=\"click to hide or show\"><span class=\"swatch\" style=\"background:rgb({r},{g},{b})\"></span>{name}{span}<span class=\"count\">{count}</span></li>\n",
            code = e.code,
            name = e.name,
            span = e.span,
            count = e.count,
        ));
    }
    let observer_note = if bx.observer_inside {
        "observer"
    } else {
        "observer (far: arrow points to it)"
    };
    // The facts under the title: where the eye is, the scene's values (or its file), the count.
    let (mut place, mut tally) = (Vec::new(), Vec::new());
    for input in scene.inputs() {
        match input.key {
            "scene_file" => place.push(format!("scene {}", escape_html(scene.name()))),
            "n_water" => tally.extend(input.heading_phrase()),
            _ => place.extend(input.heading_phrase()),
        }
    }
    tally.push(format!("{} image points", points.len()));
    if points.iter().any(|p| p.band.is_some()) {
        tally.push("white light".to_string());
    }
    let pictured = scene.subject().map_or("the image points".to_string(), |s| {
        format!("{s}'s image points")
    });
    let words = scene.sketch_words();
    format!(
        r#"<!DOCTYPE html>
<html lang="en">
<head>
<meta charset="utf-8">
<meta name="viewport" content="width=device-width, initial-scale=1">
<meta name="generator" content="bentstraw">
<title>{title_html}</title>
<style>
{css}
</style>
</head>
<body>
<canvas id="view" aria-label="3D view of {pictured}"></canvas>
<noscript><p style="position:absolute;right:20px;top:20px">This page draws its 3D view with JavaScript: please allow scripts for this file.</p></noscript>
<div id="panel">
<h1>{title_html}</h1>
<div class="facts">
<div>observer ({ox}, {oy}, {oz}) m</div>
<div>{place}</div>
<div>{tally}</div>
</div>
<ul id="legend">
{legend}<li class="static"><span class="swatch dot"></span>{observer_note}</li>
<li class="static"><span class="swatch line"></span>{wireframe}</li>
<li class="static"><span class="swatch dash"></span>{outlines}</li>
</ul>
<div class="buttons" id="buttons"></div>
<div class="toggles">
<label><input type="checkbox" id="show-water" checked> {wireframe_switch}</label>
<label><input type="checkbox" id="show-straw" checked> {outlines_switch}</label>
<label><input type="checkbox" id="show-axes" checked> axes</label>
</div>
<div id="status"></div>
<div class="hint">drag or arrow keys: rotate · wheel, pinch or +/−: zoom · shift-drag, right-drag or two fingers: pan · double-click or R: reset · click a colour to hide it · lengths in metres, one scale on every axis</div>
</div>
<script id="bentstraw-data" type="application/json">{data}</script>
<script>
{js}
</script>
</body>
</html>
"#,
        title_html = escape_html(title),
        css = VIEWER_CSS,
        js = VIEWER_JS,
        ox = observer.x,
        oy = observer.y,
        oz = observer.z,
        place = place.join(" · "),
        tally = tally.join(" · "),
        wireframe = words.wireframe,
        outlines = words.outlines,
        wireframe_switch = words.wireframe_switch,
        outlines_switch = words.outlines_switch,
    )
}

/// The data the script draws: the box, the views, the points compactly encoded, the colours
/// listed, and what to draw of the scene: its lines, or the glass's water and straw from their
/// values.
fn viewer_data(
    scene: &Setup,
    bx: &AxisBox,
    observer: Vec3,
    points: &[ImagePoint],
    entries: &[LegendEntry],
    title: &str,
    file_stem: &str,
) -> serde_json::Value {
    let origin = bx.centre();
    let (xyz, colors) = encoded_points(points, origin);
    let v3 = |v: Vec3| [v.x, v.y, v.z];
    let mut data = json!({
        "title": title,
        "fileStem": file_stem,
        "n": points.len(),
        "origin": v3(origin),
        "box": { "min": v3(bx.min), "max": v3(bx.max) },
        "xyz": base64(&xyz),
        "color": base64(&colors),
        "observer": v3(observer),
        "sceneCentre": v3(scene.frame().2),
        "observerInside": bx.observer_inside,
        "arrow": bx.observer_arrow.map(|(a, b)| [v3(a), v3(b)]),
        "sections": entries.iter().map(|e| json!({
            "code": e.code,
            "name": e.label,
            "rgb": e.rgb,
            "count": e.count,
        })).collect::<Vec<_>>(),
        "views": views_json(observer),
    });
    match scene.page_lines() {
        Some(lines) => {
            data["wire"] = lines.edges.iter().map(|s| [v3(s[0]), v3(s[1])]).collect();
            data["outlines"] = lines
                .outlines
                .iter()
                .map(|l| l.iter().map(|&p| v3(p)).collect::<Vec<_>>())
                .collect();
        }
        // The page draws the glass's water and the straw from their values.
        None => {
            for input in scene.inputs() {
                match (input.key, input.value) {
                    ("straw", InputValue::Pair([x, y])) => {
                        data["straw"] = json!({
                            "x": x,
                            "y": y,
                            "radius": STRAW_RADIUS,
                            "height": STRAW_HEIGHT,
                            "sectionHeight": SECTION_HEIGHT,
                        })
                    }
                    ("water_height", InputValue::Length(h)) => {
                        data["water"] = json!({
                            "radius": GLASS_RADIUS,
                            "height": h,
                            "verticals": WIRE_VERTICALS,
                        })
                    }
                    ("n_water", InputValue::Number(index)) => data["nWater"] = json!(index),
                    _ => {}
                }
            }
        }
    }
    data
}

/// The preset views of a page: a three-quarter view first (shown on opening, so the page looks
/// 3D at once), then the observer's own direction and the figure's side and top views.
fn views_json(observer: Vec3) -> Vec<serde_json::Value> {
    let o = observer_direction(observer);
    let [_, side, top] = figure_views(observer);
    // First, and shown on opening: a three-quarter view that makes the page look 3D at once.
    let three_quarter = json!({
        "name": "3D view",
        "caption": "three-quarter view: 35° round from the observer's azimuth, 20° from above",
        "az": o.azimuth.to_degrees() - 35.0,
        "el": 20.0,
    });
    // Then the observer's own direction, and the figure's side and top views.
    let observer_view = (
        o,
        format!(
            "from the observer's direction (azimuth {}°, elevation {}°)",
            whole(degrees(o.azimuth)),
            whole(o.elevation.to_degrees())
        ),
    );
    std::iter::once(three_quarter)
        .chain(
            [
                observer_view,
                (side.0, side.1.join(" ")),
                (top.0, top.1.join(" ")),
            ]
            .iter()
            .zip(["observer", "side", "top"])
            .map(|((v, caption), name)| {
                json!({
                    "name": format!("{name} view"),
                    "caption": caption,
                    "az": v.azimuth.to_degrees(),
                    "el": v.elevation.to_degrees(),
                })
            }),
        )
        .collect()
}

/// The points as little-endian `f32` offsets from `origin`, and their legend keys.
fn encoded_points(points: &[ImagePoint], origin: Vec3) -> (Vec<u8>, Vec<u8>) {
    let mut xyz = Vec::with_capacity(points.len() * 12);
    let mut colors = Vec::with_capacity(points.len());
    for p in points {
        let d = p.position - origin;
        for v in [d.x, d.y, d.z] {
            xyz.extend_from_slice(&(v as f32).to_le_bytes());
        }
        colors.push(legend_key(p));
    }
    (xyz, colors)
}

/// Standard base64 with padding (RFC 4648), as the browser's `atob` reads it.
pub(crate) fn base64(bytes: &[u8]) -> String {
    const ALPHABET: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut out = String::with_capacity(bytes.len().div_ceil(3) * 4);
    for chunk in bytes.chunks(3) {
        let b = [
            chunk[0],
            chunk.get(1).copied().unwrap_or(0),
            chunk.get(2).copied().unwrap_or(0),
        ];
        let v = (b[0] as u32) << 16 | (b[1] as u32) << 8 | b[2] as u32;
        for k in 0..4 {
            if k <= chunk.len() {
                out.push(ALPHABET[(v >> (18 - 6 * k) & 63) as usize] as char);
            } else {
                out.push('=');
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::plot::{counts, section_rgb8};
    use bentstraw_optics::sampling::sample_image;
    use bentstraw_optics::scene::{Scene, REFERENCES};
    use bentstraw_optics::sketch::{object_outlines, world_wireframe};
    use bentstraw_optics::world::World;

    fn reference_page(title: &str) -> (Vec<ImagePoint>, String) {
        let r = REFERENCES[0];
        let scene = Setup::assignment(r.scene(1.333), r.observer);
        let cloud = sample_image(&scene.world, r.observer, 1500, &|_| {});
        let page = viewer_page(&scene, r.observer, &cloud.points, title, "ref1");
        (cloud.points, page)
    }

    /// The JSON embedded in the page.
    fn embedded_data(page: &str) -> serde_json::Value {
        let open = r#"<script id="bentstraw-data" type="application/json">"#;
        let start = page.find(open).expect("data element") + open.len();
        let end = start + page[start..].find("</script>").expect("end of data");
        serde_json::from_str(&page[start..end]).expect("valid JSON")
    }

    /// Base64 decoding written independently of the encoder: each character's place in the alphabet.
    fn unbase64(text: &str) -> Vec<u8> {
        let alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
        let mut bits = 0u32;
        let mut count = 0;
        let mut out = Vec::new();
        for c in text.chars().filter(|&c| c != '=') {
            bits = bits << 6 | alphabet.find(c).expect("base64 character") as u32;
            count += 6;
            if count >= 8 {
                count -= 8;
                out.push((bits >> count) as u8);
                bits &= (1 << count) - 1;
            }
        }
        out
    }

    #[test]
    fn base64_matches_the_rfc_4648_examples() {
        for (plain, coded) in [
            ("", ""),
            ("f", "Zg=="),
            ("fo", "Zm8="),
            ("foo", "Zm9v"),
            ("foob", "Zm9vYg=="),
            ("fooba", "Zm9vYmE="),
            ("foobar", "Zm9vYmFy"),
        ] {
            assert_eq!(base64(plain.as_bytes()), coded);
            assert_eq!(unbase64(coded), plain.as_bytes());
        }
        let all: Vec<u8> = (0..=255).collect();
        assert_eq!(unbase64(&base64(&all)), all);
    }

    #[test]
    fn page_is_self_contained_and_offline() {
        let (_, page) = reference_page("Reference 1");
        for banned in [
            "http://",
            "https://",
            "src=\"//",
            "href=\"//",
            "src='//",
            "<link",
            "<script src",
            "@import",
            "url(",
        ] {
            assert!(!page.contains(banned), "page contains {banned:?}");
        }
        // Exactly our two scripts, both inline.
        assert_eq!(page.matches("<script").count(), 2);
        assert!(!VIEWER_JS.contains("</script") && !VIEWER_CSS.contains("</style"));
    }

    #[test]
    fn page_embeds_the_points_exactly_to_f32_precision() {
        let (points, page) = reference_page("Reference 1");
        assert!(page.contains(&format!("{} image points", points.len())));
        let data = embedded_data(&page);
        assert_eq!(data["n"].as_u64().unwrap() as usize, points.len());
        let origin: Vec<f64> = data["origin"]
            .as_array()
            .unwrap()
            .iter()
            .map(|v| v.as_f64().unwrap())
            .collect();
        let xyz = unbase64(data["xyz"].as_str().unwrap());
        let colors = unbase64(data["color"].as_str().unwrap());
        assert_eq!(xyz.len(), 12 * points.len());
        assert_eq!(colors.len(), points.len());
        for (i, p) in points.iter().enumerate() {
            for a in 0..3 {
                let b = &xyz[12 * i + 4 * a..12 * i + 4 * a + 4];
                let v = origin[a] + f32::from_le_bytes([b[0], b[1], b[2], b[3]]) as f64;
                // f32 offsets of at most a few tenths of a metre are exact to ~3e-8 m.
                assert!(
                    (v - p.position[a]).abs() < 1e-7,
                    "point {i} axis {a}: {v} vs {}",
                    p.position[a]
                );
            }
            assert_eq!(colors[i], p.color);
        }
        // The legend counts agree with the points.
        let n = counts(&points);
        for (k, s) in data["sections"].as_array().unwrap().iter().enumerate() {
            assert_eq!(s["count"].as_u64().unwrap() as usize, n[k]);
            assert_eq!(s["code"].as_u64().unwrap() as usize, k + 1);
        }
    }

    #[test]
    fn title_cannot_break_out_of_the_page() {
        let evil = "</script><script>alert(1)</script> & \"quotes\"";
        let (_, page) = reference_page(evil);
        assert!(!page.contains("<script>alert"));
        assert!(page.contains(
            "&lt;/script&gt;&lt;script&gt;alert(1)&lt;/script&gt; &amp; &quot;quotes&quot;"
        ));
        assert_eq!(embedded_data(&page)["title"].as_str().unwrap(), evil);
    }

    #[test]
    fn empty_cloud_still_gives_a_valid_page() {
        let scene = Setup::assignment(Scene::with_defaults(0.0, 0.0, 0.1).unwrap(), Vec3::ZERO);
        let page = viewer_page(&scene, Vec3::new(0.1, 0.0, 0.1), &[], "none", "x");
        let data = embedded_data(&page);
        assert_eq!(data["n"], 0);
        assert_eq!(data["xyz"], "");
    }

    #[test]
    fn preset_views_are_the_figure_views() {
        let observer = Vec3::new(0.1, -0.05, 0.3);
        let scene = Setup::assignment(Scene::with_defaults(0.0, 0.0, 0.1).unwrap(), Vec3::ZERO);
        let data = embedded_data(&viewer_page(&scene, observer, &[], "v", "x"));
        let views = data["views"].as_array().unwrap();
        assert_eq!(views.len(), 4);
        let [_, side, top] = figure_views(observer);
        let o = observer_direction(observer);
        for (v, page) in [o, side.0, top.0].iter().zip(&views[1..]) {
            assert!((page["az"].as_f64().unwrap() - v.azimuth.to_degrees()).abs() < 1e-9);
            assert!((page["el"].as_f64().unwrap() - v.elevation.to_degrees()).abs() < 1e-9);
        }
        assert_eq!(views[1]["name"], "observer view");
    }

    #[test]
    fn far_observer_page_carries_the_arrow() {
        let scene = Setup::assignment(Scene::with_defaults(0.0, 0.0, 0.1).unwrap(), Vec3::ZERO);
        let page = viewer_page(&scene, Vec3::new(3.0, 1.0, 0.5), &[], "far", "x");
        let data = embedded_data(&page);
        assert_eq!(data["observerInside"], false);
        assert_eq!(data["arrow"].as_array().unwrap().len(), 2);
    }

    #[test]
    fn written_file_is_the_page() {
        let scene = Setup::assignment(Scene::with_defaults(0.0, 0.0, 0.1).unwrap(), Vec3::ZERO);
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("view.html");
        write_cloud_viewer(&path, &scene, Vec3::new(0.1, 0.0, 0.1), &[], "t").unwrap();
        let text = std::fs::read_to_string(&path).unwrap();
        assert!(text.starts_with("<!DOCTYPE html>") && text.trim_end().ends_with("</html>"));
        assert!(write_cloud_viewer(
            Path::new("/nonexistent-dir/v.html"),
            &scene,
            Vec3::X,
            &[],
            "t"
        )
        .is_err());
    }

    /// The page's own script decodes the same points (run under node; without node it fails).
    #[test]
    #[ignore = "needs Node.js (`node`) to run the viewer's script"]
    fn viewer_script_decodes_the_embedded_points() {
        let node = crate::test_support::require_tool("node");
        let (points, page) = reference_page("Reference 1");
        let dir = tempfile::tempdir().unwrap();
        let js = dir.path().join("viewer.js");
        std::fs::write(&js, VIEWER_JS).unwrap();
        let html = dir.path().join("page.html");
        std::fs::write(&html, &page).unwrap();
        let check = format!(
            r#"globalThis.atob = (s) => Buffer.from(s, "base64").toString("latin1");
const v = require({js:?});
const page = require("fs").readFileSync({html:?}, "utf8");
const m = page.match(/<script id="bentstraw-data" type="application\/json">([\s\S]*?)<\/script>/);
const data = JSON.parse(m[1]);
const p = v.decodePoints(data);
const out = [];
for (let i = 0; i < data.n; i++) out.push([data.origin[0] + p.xyz[3 * i], data.origin[1] + p.xyz[3 * i + 1], data.origin[2] + p.xyz[3 * i + 2], p.color[i]]);
const a = v.viewAxes(30, 20);
console.log(JSON.stringify({{ points: out, right: a.right, up: a.up, toward: a.toward }}));"#,
            js = js.to_str().unwrap(),
            html = html.to_str().unwrap(),
        );
        let output = std::process::Command::new(node)
            .arg("-e")
            .arg(check)
            .output()
            .unwrap();
        assert!(
            output.status.success(),
            "{}",
            String::from_utf8_lossy(&output.stderr)
        );
        let got: serde_json::Value = serde_json::from_slice(&output.stdout).unwrap();
        let got_points = got["points"].as_array().unwrap();
        assert_eq!(got_points.len(), points.len());
        for (g, p) in got_points.iter().zip(&points) {
            for a in 0..3 {
                assert!((g[a].as_f64().unwrap() - p.position[a]).abs() < 1e-7);
            }
            assert_eq!(g[3].as_u64().unwrap(), p.color as u64);
        }
        // The script's view axes are the figure's (same picture, not a mirror image).
        let v = crate::plot::ViewDirection {
            azimuth: 30f64.to_radians(),
            elevation: 20f64.to_radians(),
        };
        for (key, want) in [
            ("right", v.right()),
            ("up", v.up()),
            ("toward", v.toward_viewer()),
        ] {
            for a in 0..3 {
                assert!(
                    (got[key][a].as_f64().unwrap() - want[a]).abs() < 1e-12,
                    "{key}"
                );
            }
        }
    }

    /// Whether `p` is section colour `c` shaded by depth as the viewer does (factor 0.72 to 1).
    fn is_shade_of(p: [u8; 3], c: [u8; 3]) -> bool {
        let k = (0..3).max_by_key(|&i| c[i]).unwrap();
        let f = p[k] as f64 / c[k] as f64;
        (0.70..=1.01).contains(&f) && (0..3).all(|i| (p[i] as f64 - f * c[i] as f64).abs() <= 3.0)
    }

    /// Opens the page in headless Chromium and checks that the script ran to the end and drew every
    /// colour present (without Chromium it fails).
    #[test]
    #[ignore = "needs Chromium (headless) to draw the page"]
    fn chromium_draws_the_page() {
        let (points, page) = reference_page("Smoke test");
        draws_in_chromium(&page, &points);
    }

    /// A gallery scene's world, its points from its own observer, and its page.
    fn world_page(name: &str) -> (World, Vec<ImagePoint>, String) {
        let path = Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../../scenes")
            .join(name);
        let text = std::fs::read_to_string(path).unwrap();
        let values = bentstraw_optics::setup::SceneValues::default();
        let loaded = Setup::from_text(name, &text, &values).expect("a valid scene");
        let observer = loaded.observer;
        let points = sample_image(&loaded.world, observer, 3000, &|_| {}).points;
        let page = viewer_page(&loaded, observer, &points, name, "w");
        (loaded.world, points, page)
    }

    /// A scene file's page carries its points exactly, a legend of the codes present with their
    /// counts, the world's wireframe and its objects' outlines (the browser draws it:
    /// `chromium_draws_a_scene_files_page`).
    #[test]
    fn a_scene_files_page_shows_its_world() {
        let (world, points, page) = world_page("reversing-arrow.toml");
        let data = embedded_data(&page);
        assert_eq!(data["n"].as_u64().unwrap() as usize, points.len());
        let colors = unbase64(data["color"].as_str().unwrap());
        assert_eq!(colors, points.iter().map(|p| p.color).collect::<Vec<_>>());
        let sections = data["sections"].as_array().unwrap();
        let codes: Vec<u64> = sections
            .iter()
            .map(|s| s["code"].as_u64().unwrap())
            .collect();
        assert_eq!(codes, [7, 8], "the card and its arrow");
        for s in sections {
            let code = s["code"].as_u64().unwrap() as u8;
            let n = points.iter().filter(|p| p.color == code).count();
            assert_eq!(s["count"].as_u64().unwrap() as usize, n);
        }
        assert_eq!(
            data["wire"].as_array().unwrap().len(),
            world_wireframe(&world).len()
        );
        assert_eq!(
            data["outlines"].as_array().unwrap().len(),
            object_outlines(&world).len()
        );
        assert!(data.get("water").is_none() && data.get("straw").is_none());
    }

    /// Headless Chromium draws a scene file's page, every colour present.
    #[test]
    #[ignore = "needs Chromium (headless) to draw the page"]
    fn chromium_draws_a_scene_files_page() {
        let (_, points, page) = world_page("tank-pencil.toml");
        draws_in_chromium(&page, &points);
    }

    /// Opens `page` in headless Chromium and checks that the script ran to the end and drew every
    /// straw colour among `points`. Where Chromium is missing or cannot start, the test fails.
    fn draws_in_chromium(page: &str, points: &[ImagePoint]) {
        let chromium = crate::test_support::require_tool("chromium");
        let dir = tempfile::tempdir().unwrap();
        let html = dir.path().join("page.html");
        std::fs::write(&html, page).unwrap();
        let shot = dir.path().join("shot.png");
        let mut child = std::process::Command::new(chromium)
            .args([
                "--headless",
                "--no-sandbox",
                "--disable-gpu",
                "--hide-scrollbars",
                "--window-size=1200,800",
                "--virtual-time-budget=5000",
            ])
            .arg(format!(
                "--user-data-dir={}",
                dir.path().join("profile").display()
            ))
            .arg(format!("--screenshot={}", shot.display()))
            .arg("--dump-dom")
            .arg(format!("file://{}", html.display()))
            .stdout(std::process::Stdio::piped())
            .stderr(std::process::Stdio::null())
            .spawn()
            .unwrap();
        // Read the page dump while the browser runs, so that a full pipe cannot stall it; its end
        // (the browser closed its output) is the event waited for.
        let mut stdout = child.stdout.take().unwrap();
        let (sent, dumped) = std::sync::mpsc::channel();
        std::thread::spawn(move || {
            let mut dom = String::new();
            let _ = std::io::Read::read_to_string(&mut stdout, &mut dom);
            let _ = sent.send(dom);
        });
        // A deadline only so that a browser that hangs cannot hang the test suite.
        let dom = match dumped.recv_timeout(std::time::Duration::from_secs(90)) {
            Ok(dom) => dom,
            Err(_) => {
                let _ = child.kill();
                let _ = child.wait();
                panic!("chromium did not finish in 90 s");
            }
        };
        child.wait().unwrap();
        if !shot.exists() && dom.is_empty() {
            // The browser could not start here (no display stack, sandbox rules...).
            crate::test_support::unavailable(
                "chromium produced nothing (it could not start here)",
                "run `chromium --headless --no-sandbox --screenshot about:blank` to see why",
            );
        }
        // The status line is written at the end of each frame: the script ran without an error.
        assert!(dom.contains("drawn in"), "the viewer did not draw a frame");
        let img = image::open(&shot).expect("a screenshot").to_rgb8();
        let n = counts(points);
        for code in 1..=5u8 {
            if n[(code - 1) as usize] == 0 {
                continue;
            }
            let c = section_rgb8(code);
            // Pixels right of the panel only (the legend has swatches in every colour).
            let hits = img
                .enumerate_pixels()
                .filter(|(x, _, p)| *x > 400 && is_shade_of(p.0, c))
                .count();
            assert!(hits >= 20, "colour {code}: {hits} pixels");
        }
    }
}
