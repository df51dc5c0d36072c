//! The `index.html` report of `bentstraw table`: one self-contained page (embedded CSS, no external
//! resource) with every simulation's inputs, statistics, checks and figures.
//!
//! The page is built from plain data: a [`Report`] holds [`SimulationEntry`]s, each with a list of
//! [`Section`]s holding [`Figure`]s. Later kinds of result (the observer's pictures, other
//! apparent-position models) are added as more sections of a simulation, with no change here.

use std::fmt::Write as _;
use std::path::Path;
use std::time::Duration;

use bentstraw_optics::scene::SECTION_COUNT;

use crate::error::Result;
use crate::escape::escape_html;
use crate::files::write_bytes;
use crate::words::{self, Lang, Text};
use crate::writers::section_rgb8;

/// The whole report.
#[derive(Clone, Debug)]
pub struct Report {
    /// Page title.
    pub title: String,
    /// One-sentence description under the title.
    pub subtitle: String,
    /// Sections before the simulations: the effect at a glance, the method.
    pub intro: Vec<Section>,
    /// The simulations, in order; consecutive ones with the same reference are grouped.
    pub simulations: Vec<SimulationEntry>,
    /// Sections after the simulations: the validation, the limits.
    pub closing: Vec<Section>,
    /// Wall-clock time of the whole run.
    pub total: Duration,
    /// The language of the page's own words (the rest is written in it by the caller).
    pub lang: Lang,
    /// The conventions at the foot of the page (a template: the colours' names, the version and
    /// the time fill it): the assignment's glass, or any scene's.
    pub footer: Text,
}

/// One simulation: its inputs, numbers, check and sections of figures.
#[derive(Clone, Debug)]
pub struct SimulationEntry {
    /// Anchor and file stem, e.g. `sim1_n1`.
    pub id: String,
    /// Number of the reference simulation (or the observer) it belongs to.
    pub reference: u32,
    /// The heading of its group (consecutive entries of the same reference), e.g. "Reference
    /// simulation 1".
    pub group: String,
    /// Heading, e.g. "Simulation 1, check n_water = 1".
    pub heading: String,
    /// Inputs as label/value rows.
    pub inputs: Vec<(String, String)>,
    /// Refractive index of the water.
    pub n_water: f64,
    /// Rays traced.
    pub rays: u64,
    /// Image points kept.
    pub points: usize,
    /// Image points per colour code, from 1 (the straw's five sections, then a scene's coins,
    /// cards and their pictures).
    pub counts: Vec<usize>,
    /// Fraction of the traced rays that reached the straw.
    pub hit_ratio: f64,
    /// Where the time went.
    pub timings: Vec<Timing>,
    /// A built-in check and its verdict, if this simulation has one.
    pub check: Option<Check>,
    /// What `bentstraw check` says of these image points, as it would of a student's.
    pub solution_check: Option<Check>,
    /// The results, one section per kind.
    pub sections: Vec<Section>,
}

/// A named duration.
#[derive(Clone, Debug)]
pub struct Timing {
    /// What was timed.
    pub label: String,
    /// How long it took.
    pub duration: Duration,
}

impl Timing {
    /// A timing named `label`.
    pub fn new(label: &str, duration: Duration) -> Self {
        Timing {
            label: label.into(),
            duration,
        }
    }
}

/// A verdict of a built-in check.
#[derive(Clone, Debug)]
pub struct Check {
    /// Whether it passed.
    pub passed: bool,
    /// One line saying what was checked, the measured value and the verdict.
    pub text: String,
    /// A few words for tables, e.g. "on the straw (max 3e-16 m): pass".
    pub short: String,
}

/// A titled group of figures within a simulation.
#[derive(Clone, Debug)]
pub struct Section {
    /// Heading.
    pub title: String,
    /// The figures.
    pub figures: Vec<Figure>,
    /// Paragraphs of explanation under the figures.
    pub notes: Vec<String>,
    /// Whether the figures are shown side by side (pictures meant to be compared), not stacked.
    pub side_by_side: bool,
    /// Whether the section is printed: one that is not is named, on paper, in a note saying where
    /// to find it.
    pub printed: bool,
    /// A table of numbers under the figures: a header row, then data rows.
    pub table: Vec<Vec<String>>,
}

/// A picture file shown in the page, with links to companion files.
#[derive(Clone, Debug)]
pub struct Figure {
    /// The image's file name, relative to the report.
    pub file: String,
    /// What the figure shows.
    pub caption: String,
    /// Companion files (3D view, data).
    pub links: Vec<Link>,
    /// Why the image could not be written, if it could not.
    pub error: Option<String>,
}

impl Figure {
    /// A figure of the image `file` with `caption`, no links, no error.
    pub fn image(file: &str, caption: &str) -> Self {
        Figure {
            file: file.into(),
            caption: caption.into(),
            links: Vec::new(),
            error: None,
        }
    }
}

/// A link to a file written beside the report.
#[derive(Clone, Debug)]
pub struct Link {
    /// File name, relative to the report.
    pub file: String,
    /// Link text.
    pub label: String,
    /// Why the file could not be written, if it could not.
    pub error: Option<String>,
}

impl Link {
    /// A link to `file` labelled `label`, or the reason it is missing.
    pub fn new(file: &str, label: &str, error: Option<String>) -> Self {
        Link {
            file: file.into(),
            label: label.into(),
            error,
        }
    }
}

/// Writes the report to `path`, all-or-nothing.
pub fn write_report(path: &Path, report: &Report) -> Result {
    write_bytes(path, render(report).as_bytes())
}

const CSS: &str = r#"
:root { --ink:#1d2330; --muted:#5b6475; --line:#e2e6ee; --bg:#f6f7fb; --card:#fff; --accent:#2456a6; --ok:#1d7a3a; --bad:#b3261e; }
* { box-sizing: border-box; }
body { margin:0; background:var(--bg); color:var(--ink); font:15px/1.5 system-ui,-apple-system,"Segoe UI",Roboto,Helvetica,Arial,sans-serif; }
header { background:#1f2a44; color:#fff; padding:28px 40px 22px; }
header h1 { margin:0 0 6px; font-size:26px; font-weight:600; }
header p { margin:0; color:#c9d3e8; max-width:900px; }
nav { padding:10px 40px; background:#fff; border-bottom:1px solid var(--line); position:sticky; top:0; z-index:1; }
nav a { margin-right:18px; }
main { max-width:1280px; margin:0 auto; padding:24px 40px 40px; }
a { color:var(--accent); text-decoration:none; } a:hover { text-decoration:underline; }
h2 { font-size:21px; margin:34px 0 12px; padding-bottom:6px; border-bottom:2px solid var(--line); }
h3 { font-size:17px; margin:0 0 10px; }
h4 { font-size:15px; margin:16px 0 8px; color:var(--muted); font-weight:600; }
table { border-collapse:collapse; font-variant-numeric:tabular-nums; }
th, td { padding:4px 10px; text-align:right; border-bottom:1px solid var(--line); white-space:nowrap; }
th { font-weight:600; color:var(--muted); font-size:13px; }
td.l, th.l { text-align:left; }
.overview { background:var(--card); border:1px solid var(--line); border-radius:8px; padding:12px 16px; overflow-x:auto; }
.sim { background:var(--card); border:1px solid var(--line); border-radius:8px; padding:18px 20px; margin:16px 0; }
.facts { display:flex; flex-wrap:wrap; gap:28px; align-items:flex-start; }
.facts table td:first-child { text-align:left; color:var(--muted); }
.sw { display:inline-block; width:11px; height:11px; border-radius:2px; margin-right:5px; vertical-align:-1px; border:1px solid rgba(0,0,0,.15); }
.check { margin:12px 0 0; padding:6px 10px; border-radius:6px; font-size:14px; }
.check.pass { background:#e7f4ea; color:var(--ok); } .check.fail { background:#fbe9e7; color:var(--bad); }
.badge { font-size:12px; padding:1px 7px; border-radius:10px; }
.badge.pass { background:#e7f4ea; color:var(--ok); } .badge.fail { background:#fbe9e7; color:var(--bad); }
.timing { color:var(--muted); font-size:13px; margin-top:8px; }
figure { margin:8px 0 0; }
.figs.pair { display:grid; grid-template-columns:repeat(auto-fit, minmax(min(380px, 100%), 1fr)); gap:12px; }
.facts > table { max-width:100%; overflow-x:auto; display:block; }
main p { max-width:900px; }
@media (max-width: 700px) {
  header, nav, main, footer { padding-left:14px; padding-right:14px; }
  nav { position:static; }
  nav a { display:inline-block; margin:2px 12px 2px 0; }
  .sim { padding:12px; }
  th, td { padding:3px 6px; }
  body { overflow-wrap:anywhere; }
}
figure img { max-width:100%; height:auto; border:1px solid var(--line); border-radius:4px; background:#fff; }
figcaption { color:var(--muted); font-size:13px; margin-top:4px; }
.missing { padding:18px; border:1px dashed var(--bad); color:var(--bad); border-radius:6px; background:#fff8f7; }
.legend { margin-top:10px; color:var(--muted); font-size:13px; }
footer { max-width:1280px; margin:0 auto; padding:0 40px 40px; color:var(--muted); font-size:13px; }
.print-only { display:none; }
@page { size: A4; margin: 11mm 12mm; }
@media print {
  /* On paper: no screen furniture, figures a column wide and side by side, nothing cut. */
  body { background:#fff; font-size:9pt; line-height:1.35; }
  nav, .screen-only, .timing { display:none; }
  .print-only { display:block; }
  header { background:none; color:var(--ink); padding:0 0 4mm; border-bottom:2px solid var(--ink); }
  header h1 { font-size:16pt; }
  header p { color:var(--ink); max-width:none; }
  main, footer { max-width:none; padding:0; }
  main p { max-width:none; margin:1.5mm 0; }
  h2 { font-size:13pt; margin:5mm 0 2mm; }
  h2, h3, h4 { break-after:avoid; page-break-after:avoid; }
  h4 { margin:2mm 0 1mm; }
  table, .facts, .check, figure, .overview { break-inside:avoid; page-break-inside:avoid; }
  th, td { padding:1px 5px; font-size:8pt; }
  .overview, .sim { border:none; padding:0; margin:0; overflow:visible; }
  .sim { margin:3mm 0; }
  .facts { gap:6mm; }
  .facts > table { display:table; }
  .check { margin:1mm 0 0; padding:1mm 2mm; font-size:8pt; }
  figure img { border:none; max-height:11.5cm; width:auto; margin:0 auto; display:block; }
  figcaption { font-size:7.5pt; line-height:1.25; }
  figcaption a::after { content:" (" attr(href) ")"; }
  a { color:var(--ink); }
  .parts { display:grid; grid-template-columns:1fr 1fr; gap:3mm 7mm; align-items:start; }
  .part { break-inside:avoid; page-break-inside:avoid; }
  .parts figure img { max-height:11cm; }
  .parts > .part.wide { grid-column:1 / -1; order:9; }
  .parts .pair figure img { max-height:6cm; }
  .figs.pair { grid-template-columns:1fr 1fr; gap:3mm; }
  .intro { display:grid; grid-template-columns:1fr 1fr; gap:7mm; align-items:start; }
  .sim.variant { display:grid; grid-template-columns:1fr 1fr; gap:0 7mm; break-inside:avoid; }
  .sim.variant > .parts { grid-column:2; grid-row:1 / span 5; display:block; }
  .sim.variant .facts { flex-direction:column; gap:2mm; }
  .sim.variant .part figure img { max-height:7.5cm; }
  .not-printed { display:none; }
  .print-note { color:var(--muted); font-style:italic; }
}
"#;

/// A small square in the section's colour.
fn swatch(code: usize) -> String {
    let [r, g, b] = section_rgb8(code as u8);
    format!("<span class=\"sw\" style=\"background:rgb({r},{g},{b})\"></span>")
}

/// A duration in seconds, two decimals: `0.84 s`.
pub(crate) fn seconds(d: Duration) -> String {
    format!("{:.2} s", d.as_secs_f64())
}

/// The report as one HTML page.
pub fn render(report: &Report) -> String {
    let mut h = String::with_capacity(32 * 1024);
    let _ = write!(
        h,
        "<!DOCTYPE html>\n<html lang=\"{}\">\n<head>\n<meta charset=\"utf-8\">\n\
         <meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n\
         <title>{}</title>\n<style>{CSS}</style>\n</head>\n<body>\n",
        report.lang.code(),
        escape_html(&report.title)
    );
    let _ = write!(
        h,
        "<header>\n<h1>{}</h1>\n<p>{}</p>\n</header>\n",
        escape_html(&report.title),
        escape_html(&report.subtitle)
    );

    // Consecutive simulations of the same reference form one group.
    let mut groups: Vec<(u32, Vec<&SimulationEntry>)> = Vec::new();
    for s in &report.simulations {
        match groups.last_mut() {
            Some((r, list)) if *r == s.reference => list.push(s),
            _ => groups.push((s.reference, vec![s])),
        }
    }
    h.push_str("<nav>");
    for (k, sec) in report.intro.iter().enumerate() {
        let _ = write!(h, "<a href=\"#intro{k}\">{}</a>", escape_html(&sec.title));
    }
    let lang = report.lang;
    let _ = write!(h, "<a href=\"#overview\">{}</a>", lang.of(words::OVERVIEW));
    for (r, _) in &groups {
        let _ = write!(
            h,
            "<a href=\"#reference{r}\">{}</a>",
            lang.fill(words::NAV_SIMULATION, &[r])
        );
    }
    for (k, sec) in report.closing.iter().enumerate() {
        let _ = write!(h, "<a href=\"#closing{k}\">{}</a>", escape_html(&sec.title));
    }
    let _ = write!(
        h,
        "<a href=\"#conventions\">{}</a></nav>\n<main>\n",
        lang.of(words::CONVENTIONS)
    );
    let _ = writeln!(
        h,
        "<p class=\"print-only print-note\">{}</p>",
        lang.of(words::PRINTED_FROM)
    );

    h.push_str("<div class=\"intro\">\n");
    render_top_sections(&mut h, lang, "intro", &report.intro);
    h.push_str("</div>\n");
    render_overview(&mut h, report);
    for (r, list) in &groups {
        let _ = writeln!(
            h,
            "<h2 id=\"reference{r}\">{}</h2>",
            escape_html(&list[0].group)
        );
        for (k, s) in list.iter().enumerate() {
            // The first of a group is the reference, the others its index checks.
            render_simulation(&mut h, lang, s, k > 0);
        }
    }
    render_top_sections(&mut h, lang, "closing", &report.closing);
    h.push_str("</main>\n");
    let names = (0..colour_count(report))
        .map(|k| format!("{}{} {}", swatch(k + 1), k + 1, lang.colour_name(k)))
        .collect::<Vec<_>>()
        .join(", ");
    h.push_str(&lang.fill(
        report.footer,
        &[&names, &env!("CARGO_PKG_VERSION"), &seconds(report.total)],
    ));
    h
}

/// Sections with their own `h2`, anchored `{anchor}{k}`; before each run of sections that are not
/// printed, a note (on paper only) naming them and where to find them.
fn render_top_sections(h: &mut String, lang: Lang, anchor: &str, sections: &[Section]) {
    for (k, sec) in sections.iter().enumerate() {
        let starts_run = !sec.printed && (k == 0 || sections[k - 1].printed);
        if starts_run {
            let names: Vec<String> = sections[k..]
                .iter()
                .take_while(|s| !s.printed)
                .map(|s| escape_html(&s.title))
                .collect();
            let _ = writeln!(
                h,
                "<p class=\"print-only print-note\">{}</p>",
                lang.fill(words::NOT_PRINTED, &[&names.join(" · ")])
            );
        }
        let class = if sec.printed { "part" } else { "not-printed" };
        let _ = writeln!(
            h,
            "<section class=\"{class}\">\n<h2 id=\"{anchor}{k}\">{}</h2>",
            escape_html(&sec.title)
        );
        render_section_body(h, lang, sec);
        h.push_str("</section>\n");
    }
}

/// How many colour codes the report counts: the straw's five sections at least.
pub(crate) fn colour_count(report: &Report) -> usize {
    report
        .simulations
        .iter()
        .map(|s| s.counts.len())
        .fold(SECTION_COUNT, usize::max)
}

fn render_overview(h: &mut String, report: &Report) {
    let lang = report.lang;
    let head = words::OVERVIEW_HEAD.map(|t| lang.of(t));
    let _ = write!(
        h,
        "<h2 id=\"overview\">{}</h2>\n<div class=\"overview\"><table>\n<tr><th class=\"l\">{}</th><th>{}</th><th>{}</th><th>{}</th><th>{}</th>",
        lang.of(words::OVERVIEW),
        head[0],
        head[1],
        head[2],
        head[3],
        head[4]
    );
    let colours = colour_count(report);
    for k in 0..colours {
        let _ = write!(h, "<th>{}{}</th>", swatch(k + 1), lang.colour_name(k));
    }
    let tail = words::OVERVIEW_TAIL.map(|t| lang.of(t));
    let _ = writeln!(
        h,
        "<th>{}</th><th class=\"l\">{}</th></tr>",
        tail[0], tail[1]
    );
    for s in &report.simulations {
        let _ = write!(
            h,
            "<tr><td class=\"l\"><a href=\"#{id}\">{id}</a></td><td>{}</td><td>{}</td><td>{}</td><td>{:.1} %</td>",
            s.n_water,
            s.rays,
            s.points,
            100.0 * s.hit_ratio,
            id = escape_html(&s.id)
        );
        for k in 0..colours {
            let _ = write!(h, "<td>{}</td>", s.counts.get(k).copied().unwrap_or(0));
        }
        let total: Duration = s.timings.iter().map(|t| t.duration).sum();
        let verdict = match &s.check {
            Some(c) => format!(
                "<span class=\"badge {}\">{}</span>",
                if c.passed { "pass" } else { "fail" },
                escape_html(&c.short)
            ),
            None => String::new(),
        };
        let _ = writeln!(
            h,
            "<td>{}</td><td class=\"l\">{verdict}</td></tr>",
            seconds(total)
        );
    }
    h.push_str("</table></div>\n");
}

/// One simulation's article; `variant`: an index check of the reference before it.
fn render_simulation(h: &mut String, lang: Lang, s: &SimulationEntry, variant: bool) {
    let _ = write!(
        h,
        "<article class=\"sim{}\" id=\"{}\">\n<h3>{}</h3>\n<div class=\"facts\">\n<table>",
        if variant { " variant" } else { "" },
        escape_html(&s.id),
        escape_html(&s.heading)
    );
    for (label, value) in &s.inputs {
        let _ = write!(
            h,
            "<tr><td>{}</td><td>{}</td></tr>",
            escape_html(label),
            escape_html(value)
        );
    }
    let facts = words::FACTS.map(|t| lang.of(t));
    let _ = write!(
        h,
        "</table>\n<table><tr><td>{}</td><td>{}</td></tr><tr><td>{}</td><td>{}</td></tr>\
         <tr><td>{}</td><td>{:.1} %</td></tr></table>\n<table>",
        facts[0],
        s.rays,
        facts[1],
        s.points,
        facts[2],
        100.0 * s.hit_ratio
    );
    for (k, c) in s.counts.iter().enumerate() {
        let _ = write!(
            h,
            "<tr><td>{}{} {}</td><td>{c}</td></tr>",
            swatch(k + 1),
            k + 1,
            lang.colour_name(k)
        );
    }
    h.push_str("</table>\n</div>\n");
    if let Some(c) = &s.check {
        let _ = writeln!(
            h,
            "<p class=\"check {}\">{}</p>",
            if c.passed { "pass" } else { "fail" },
            escape_html(&c.text)
        );
    }
    if let Some(c) = &s.solution_check {
        let _ = writeln!(
            h,
            "<p class=\"check {} solution\">{}{}</p>",
            if c.passed { "pass" } else { "fail" },
            lang.of(words::CHECKED_AS_SOLUTION),
            escape_html(&c.text)
        );
    }
    let timings: Vec<String> = s
        .timings
        .iter()
        .map(|t| format!("{} {}", escape_html(&t.label), seconds(t.duration)))
        .collect();
    let _ = writeln!(
        h,
        "<p class=\"timing\">{}{}</p>",
        lang.of(words::TIME),
        timings.join(" · ")
    );
    h.push_str("<div class=\"parts\">\n");
    for sec in &s.sections {
        // Pictures to compare take the printed page's width, after the other parts.
        let _ = writeln!(
            h,
            "<section class=\"part{}\">\n<h4>{}</h4>",
            if sec.side_by_side { " wide" } else { "" },
            escape_html(&sec.title)
        );
        render_section_body(h, lang, sec);
        h.push_str("</section>\n");
    }
    h.push_str("</div>\n</article>\n");
}

/// A section's figures, notes and table (its heading is the caller's).
fn render_section_body(h: &mut String, lang: Lang, sec: &Section) {
    let class = if sec.side_by_side {
        "figs pair"
    } else {
        "figs"
    };
    if !sec.figures.is_empty() {
        let _ = writeln!(h, "<div class=\"{class}\">");
        for f in &sec.figures {
            render_figure(h, lang, f);
        }
        h.push_str("</div>\n");
    }
    for n in &sec.notes {
        let _ = writeln!(h, "<p>{}</p>", escape_html(n));
    }
    if let Some((head, rows)) = sec.table.split_first() {
        h.push_str("<div class=\"overview\"><table>\n<tr>");
        for c in head {
            let _ = write!(h, "<th>{}</th>", escape_html(c));
        }
        h.push_str("</tr>\n");
        for row in rows {
            h.push_str("<tr>");
            for c in row {
                let _ = write!(h, "<td>{}</td>", escape_html(c));
            }
            h.push_str("</tr>\n");
        }
        h.push_str("</table></div>\n");
    }
}

fn render_figure(h: &mut String, lang: Lang, f: &Figure) {
    h.push_str("<figure>\n");
    match &f.error {
        None => {
            let img = format!(
                "<img src=\"{}\" alt=\"{}\" loading=\"lazy\">",
                escape_html(&f.file),
                escape_html(&f.caption)
            );
            // Clicking the picture opens its first companion (the rotatable 3D view).
            match f.links.iter().find(|l| l.error.is_none()) {
                Some(l) => {
                    let _ = writeln!(h, "<a href=\"{}\">{img}</a>", escape_html(&l.file));
                }
                None => {
                    let _ = writeln!(h, "{img}");
                }
            }
        }
        Some(e) => {
            let _ = writeln!(
                h,
                "<div class=\"missing\">{}</div>",
                lang.fill(
                    words::NOT_WRITTEN_FIGURE,
                    &[&escape_html(&f.file), &escape_html(e)]
                )
            );
        }
    }
    let links: Vec<String> = f
        .links
        .iter()
        .map(|l| match &l.error {
            None => format!(
                "<a href=\"{}\">{}</a>",
                escape_html(&l.file),
                escape_html(&l.label)
            ),
            Some(e) => lang.fill(
                words::NOT_WRITTEN_LINK,
                &[&escape_html(&l.label), &escape_html(e)],
            ),
        })
        .collect();
    let _ = write!(h, "<figcaption>{}", escape_html(&f.caption));
    if !links.is_empty() {
        let _ = write!(h, " — {}", links.join(" · "));
    }
    h.push_str("</figcaption>\n</figure>\n");
}

#[cfg(test)]
mod tests {
    use super::*;

    fn entry(
        id: &str,
        reference: u32,
        check: Option<Check>,
        error: Option<String>,
    ) -> SimulationEntry {
        let mut figure = Figure::image(&format!("{id}.png"), "cloud <three views>");
        figure.links = vec![Link::new(&format!("{id}.html"), "3D view", None)];
        figure.error = error;
        SimulationEntry {
            id: id.into(),
            reference,
            group: format!("Reference simulation {reference}"),
            heading: format!("Simulation {reference}"),
            inputs: vec![("observer".into(), "(0, 0.1, 0.1) m".into())],
            n_water: 1.0,
            rays: 4000,
            points: 1234,
            counts: vec![1, 2, 3, 4, 1224],
            hit_ratio: 0.3085,
            timings: vec![Timing::new("tracing", Duration::from_millis(250))],
            check,
            solution_check: Some(Check {
                passed: true,
                text: format!("pass: 1234 of 1234 points correct <{id}>"),
                short: "pass".into(),
            }),
            sections: vec![Section {
                title: "Image points".into(),
                figures: vec![figure],
                notes: vec!["a & b".into()],
                side_by_side: false,
                printed: true,
                table: Vec::new(),
            }],
        }
    }

    fn report() -> Report {
        Report {
            title: "T".into(),
            subtitle: "S".into(),
            intro: Vec::new(),
            closing: Vec::new(),
            simulations: vec![
                entry("sim1", 1, None, None),
                entry(
                    "sim1_n1",
                    1,
                    Some(Check {
                        passed: true,
                        text: "on the straw, at most 1e-17 m".into(),
                        short: "max 1e-17 m: pass".into(),
                    }),
                    None,
                ),
                entry(
                    "sim2",
                    2,
                    Some(Check {
                        passed: false,
                        text: "off".into(),
                        short: "max 1 m: FAIL".into(),
                    }),
                    Some("disk full".into()),
                ),
            ],
            total: Duration::from_secs(3),
            lang: Lang::En,
            footer: words::FOOTER,
        }
    }

    #[test]
    fn every_figure_check_and_number_is_shown() {
        let html = render(&report());
        assert!(html.contains("<a href=\"sim1.html\"><img src=\"sim1.png\""));
        assert!(html.contains("<img src=\"sim1_n1.png\""));
        assert!(html.contains("<a href=\"sim1_n1.html\">3D view</a>"));
        assert!(html.contains("sim2.png could not be written: disk full"));
        assert!(!html.contains("<img src=\"sim2.png\""));
        assert!(html.contains("on the straw, at most 1e-17 m"));
        assert!(html.contains("class=\"check fail\">off"));
        assert!(html.contains("max 1e-17 m: pass") && html.contains("max 1 m: FAIL"));
        assert!(html.contains("<td>1224</td>") && html.contains("30.9 %"));
        assert!(html.contains("id=\"reference1\"") && html.contains("id=\"reference2\""));
        // One group per reference, not per simulation.
        assert_eq!(html.matches("<h2 id=\"reference").count(), 2);
        // Each simulation's points checked as a solution, escaped.
        assert!(html.contains(
            "(<code>bentstraw check</code>): pass: 1234 of 1234 points correct &lt;sim2&gt;</p>"
        ));
    }

    #[test]
    fn print_keeps_tables_and_headings_whole_and_names_what_it_leaves_out() {
        let mut r = report();
        let section = |title: &str, printed: bool| Section {
            title: title.into(),
            figures: vec![],
            notes: vec![],
            side_by_side: false,
            printed,
            table: vec![],
        };
        r.closing = vec![
            section("Gallery: a", false),
            section("Gallery: b", false),
            section("Limits", true),
        ];
        let html = render(&r);
        assert!(html.contains("@media print"));
        assert!(html.contains("break-inside:avoid") && html.contains("break-after:avoid"));
        // One note for the run of sections left out, naming each.
        assert_eq!(html.matches("Not printed").count(), 1);
        assert!(html.contains(
            "Not printed (in the report on screen, index.html): Gallery: a · Gallery: b."
        ));
        assert_eq!(html.matches("class=\"not-printed\"").count(), 2);
        // The index checks are laid out as variants of their reference.
        assert!(html.contains("<article class=\"sim variant\" id=\"sim1_n1\">"));
        assert!(html.contains("<article class=\"sim\" id=\"sim1\">"));
    }

    #[test]
    fn text_is_escaped_and_nothing_is_fetched() {
        let html = render(&report());
        assert!(html.contains("cloud &lt;three views&gt;"));
        assert!(html.contains("a &amp; b"));
        assert!(!html.contains("http://") && !html.contains("https://"));
        assert!(!html.contains("<script") && !html.contains("<link"));
    }
}
