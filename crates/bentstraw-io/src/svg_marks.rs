//! Leaner SVG figures: the plotting crate writes one element per mark (a `rect` per image point, a
//! `circle` per gap sample, a `line` per stroke of a cross), about 80 bytes each. A run of marks of
//! one style drawn one after the other becomes one `path` of the same style, each mark a short
//! sub-path, and a mark drawn twice at the same place in that run is kept once: the same picture
//! in a third of the bytes. A marker (a circle, a stroke of a cross) whose place is within
//! [`MARKER_CELL`] pixels of one already drawn in its run is left out: the two overlap on paper
//! (a figure is printed at about 300 pixels an inch), and most of a gap plot's samples do.

use std::collections::HashSet;
use std::fmt::Write as _;

/// Fewest consecutive marks of one style merged into a path: shorter runs (frames, legend marks,
/// the observer) stay as they are, so that their elements can still be found by name.
const MIN_RUN: usize = 16;

/// Side (px) of the cells of a grid: a marker in a cell that holds one of its run already adds
/// nothing that shows.
const MARKER_CELL: f64 = 2.0;

/// One mark: its style (the element's name and every attribute but its geometry) and its geometry
/// as path data.
struct Mark {
    /// Element name and non-geometric attributes, as written.
    style: String,
    /// The same shape as SVG path data.
    path: String,
    /// Marks of one run with the same key look the same: the path of a rectangle or polyline, the
    /// grid cells of a marker's coordinates.
    key: String,
}

/// The attributes of one self-closing element line `<name a="v" …/>`, if it is one.
fn attributes(line: &str) -> Option<(&str, Vec<(&str, &str)>)> {
    let body = line.trim().strip_prefix('<')?.strip_suffix("/>")?;
    let (name, mut rest) = body.split_once(' ')?;
    let mut attrs = Vec::new();
    loop {
        rest = rest.trim_start();
        if rest.is_empty() {
            return Some((name, attrs));
        }
        let (key, after) = rest.split_once("=\"")?;
        let (value, after) = after.split_once('"')?;
        attrs.push((key, value));
        rest = after;
    }
}

/// The mark a line draws, if it is a rectangle, circle, line or polyline of the plotting crate.
fn mark(line: &str) -> Option<Mark> {
    let (name, attrs) = attributes(line)?;
    let geometric: &[&str] = match name {
        "rect" => &["x", "y", "width", "height"],
        "circle" => &["cx", "cy", "r"],
        "line" => &["x1", "y1", "x2", "y2"],
        "polyline" => &["points"],
        _ => return None,
    };
    let get = |k: &str| -> Option<f64> {
        attrs
            .iter()
            .find(|(key, _)| *key == k)
            .and_then(|(_, v)| v.parse().ok())
    };
    let mut style = String::from(name);
    for (k, v) in &attrs {
        if !geometric.contains(k) {
            let _ = write!(style, " {k}=\"{v}\"");
        }
    }
    let path = match name {
        "rect" => {
            let (x, y, w, h) = (get("x")?, get("y")?, get("width")?, get("height")?);
            format!("M{x} {y}h{w}v{h}h{}z", -w)
        }
        "circle" => {
            let (cx, cy, r) = (get("cx")?, get("cy")?, get("r")?);
            format!(
                "M{} {cy}a{r} {r} 0 1 0 {} 0a{r} {r} 0 1 0 {} 0z",
                cx - r,
                2.0 * r,
                -2.0 * r
            )
        }
        "line" => {
            let (x1, y1, x2, y2) = (get("x1")?, get("y1")?, get("x2")?, get("y2")?);
            format!("M{x1} {y1}L{x2} {y2}")
        }
        _ => {
            let points = attrs.iter().find(|(k, _)| *k == "points")?.1;
            let mut d = String::new();
            for (k, p) in points.split_whitespace().enumerate() {
                let (x, y) = p.split_once(',')?;
                let _ = write!(d, "{}{x} {y}", if k == 0 { 'M' } else { 'L' });
            }
            if d.is_empty() {
                return None;
            }
            d
        }
    };
    let key = match name {
        "circle" | "line" => geometric
            .iter()
            .filter_map(|k| get(k))
            .map(|v| format!("{} ", (v / MARKER_CELL).floor()))
            .collect(),
        _ => path.clone(),
    };
    // A line or polyline is stroked only: a path is filled unless told not to be.
    if matches!(name, "line" | "polyline") && !style.contains(" fill=") {
        style.push_str(" fill=\"none\"");
    }
    Some(Mark { style, path, key })
}

/// The SVG text `svg` with every run of at least [`MIN_RUN`] consecutive marks of one style
/// written as one `path` (marks that look the same as one before them in the run left out).
pub(crate) fn merge_marks(svg: &str) -> String {
    let mut out = String::with_capacity(svg.len() / 2);
    let lines: Vec<&str> = svg.lines().collect();
    let marks: Vec<Option<Mark>> = lines.iter().map(|l| mark(l)).collect();
    let mut k = 0;
    while k < lines.len() {
        let run = match &marks[k] {
            Some(first) => marks[k..]
                .iter()
                .take_while(|m| m.as_ref().is_some_and(|m| m.style == first.style))
                .count(),
            None => 0,
        };
        if run >= MIN_RUN {
            let style = &marks[k].as_ref().expect("a run starts with a mark").style;
            let attrs = style.split_once(' ').map_or("", |s| s.1);
            let mut seen = HashSet::new();
            let _ = write!(out, "<path {attrs} d=\"");
            for m in marks[k..k + run].iter().flatten() {
                if seen.insert(m.key.as_str()) {
                    out.push_str(&m.path);
                }
            }
            out.push_str("\"/>\n");
            k += run;
        } else {
            out.push_str(lines[k]);
            out.push('\n');
            k += 1;
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn runs_of_one_style_become_one_path_and_short_runs_stay() {
        let mut svg = String::from("<svg width=\"10\" height=\"10\">\n");
        svg.push_str("<rect x=\"0\" y=\"0\" width=\"10\" height=\"10\" opacity=\"1\" fill=\"#FFFFFF\" stroke=\"none\"/>\n");
        for k in 0..20 {
            // Every point twice: kept once.
            for _ in 0..2 {
                let _ = writeln!(
                    svg,
                    "<rect x=\"{k}\" y=\"2\" width=\"3\" height=\"3\" opacity=\"1\" fill=\"#FF0000\" stroke=\"none\"/>"
                );
            }
        }
        // Strokes 3 px apart are kept; one 1 px beside another is not (the same cell of the grid).
        for x in (0..16).map(|k| 3 * k).chain([1]) {
            let _ = writeln!(
                svg,
                "<line opacity=\"1\" stroke=\"#000000\" stroke-width=\"1\" x1=\"{x}\" y1=\"0\" x2=\"{x}\" y2=\"5\"/>"
            );
        }
        svg.push_str("<circle cx=\"5\" cy=\"5\" r=\"8\" opacity=\"1\" fill=\"#000000\" stroke=\"none\"/>\n</svg>\n");
        let merged = merge_marks(&svg);
        let doc = roxmltree::Document::parse(&merged).expect("still SVG");
        let paths: Vec<roxmltree::Node> = doc
            .descendants()
            .filter(|n| n.has_tag_name("path"))
            .collect();
        assert_eq!(paths.len(), 2, "{merged}");
        assert_eq!(paths[0].attribute("fill"), Some("#FF0000"));
        assert_eq!(paths[0].attribute("d").unwrap().matches('M').count(), 20);
        assert!(paths[0].attribute("d").unwrap().starts_with("M0 2h3v3h-3z"));
        assert_eq!(paths[1].attribute("fill"), Some("none"));
        assert_eq!(paths[1].attribute("stroke"), Some("#000000"));
        assert_eq!(paths[1].attribute("d").unwrap().matches('L').count(), 16);
        // The background and the lone circle are untouched.
        assert_eq!(
            doc.descendants().filter(|n| n.has_tag_name("rect")).count(),
            1
        );
        assert_eq!(
            doc.descendants()
                .filter(|n| n.has_tag_name("circle"))
                .count(),
            1
        );
    }
}
