//! The report as a PDF of A4 pages (`bentstraw table --pdf FILE`), laid out by the program from the
//! same [`Report`] as the page, the way the page's print stylesheet lays it out: figures a column
//! wide and side by side, tables and figures never cut, headings kept with what follows, the parts
//! that are not printed named in a note.
//!
//! No browser is needed: each page's text, tables and rules are drawn as an SVG in the shipped
//! font and converted (usvg and svg2pdf, which already write the PDF figures), the figures are
//! embedded once each as vector drawings (SVG) or pictures (PNG, deflated), and the pages are
//! assembled with pdf-writer. Text stays text: it can be searched and copied.

use std::collections::HashMap;
use std::fmt::Write as _;

use pdf_writer::{Content, Filter, Finish, Name, Pdf, Rect, Ref, TextStr};

use crate::error::{Error, Result};
use crate::escape::escape_html;
use crate::plot::{svg_options, FONT};
use crate::report::{colour_count, seconds, Check, Figure, Report, Section, SimulationEntry};
use crate::words::{self, Lang};

/// One typographic point in millimetres.
const PT: f64 = 25.4 / 72.0;
/// The A4 page (mm).
const PAGE_W: f64 = 210.0;
const PAGE_H: f64 = 297.0;
/// The margins (mm): the print stylesheet's.
const MARGIN_X: f64 = 12.0;
const MARGIN_Y: f64 = 11.0;
/// The width and height text and figures may take (mm).
const WIDTH: f64 = PAGE_W - 2.0 * MARGIN_X;
const HEIGHT: f64 = PAGE_H - 2.0 * MARGIN_Y - FOLIO_SPACE;
/// Room kept at the foot of each page for its number (mm).
const FOLIO_SPACE: f64 = 5.0;
/// Between two columns (mm).
const GAP: f64 = 7.0;
/// Between two blocks of a column (mm).
const SPACE: f64 = 1.6;
/// Line height as a multiple of the font size.
const LEADING: f64 = 1.3;

/// The type sizes (pt), as printed by the page's stylesheet.
const BODY: f64 = 9.0;
const TITLE: f64 = 16.0;
const H2: f64 = 13.0;
const H3: f64 = 11.0;
const H4: f64 = 9.5;
const SMALL: f64 = 8.0;
const CAPTION: f64 = 7.5;

/// Colours: the page's ink, muted text, rules and verdicts.
const INK: &str = "#1d2330";
const MUTED: &str = "#5b6475";
const LINE: &str = "#c9ced8";
const OK: (&str, &str) = ("#1d7a3a", "#e7f4ea");
const BAD: (&str, &str) = ("#b3261e", "#fbe9e7");

/// Largest heights of a figure (mm): alone, in a two-column part, in a pair to compare, and beside
/// an index check's numbers (the stylesheet's).
const FIGURE_MAX: f64 = 100.0;
const PART_MAX: f64 = 90.0;
const PAIR_MAX: f64 = 52.0;
const VARIANT_MAX: f64 = 58.0;

/// Writes the PDF of `report`, each figure's bytes given by `read` (by the figure's file name).
pub fn report_pdf(report: &Report, read: &dyn Fn(&str) -> Result<Vec<u8>>) -> Result<Vec<u8>> {
    let mut layout = Layout::new(read, report.lang)?;
    let blocks = layout.report(report);
    let pages = paginate(blocks);
    assemble(report, &layout, &pages)
}

/// What is drawn, in millimetres from the top left of its block (then of its page).
#[derive(Clone, Debug)]
enum Mark {
    /// A line of text, `y` its baseline, `size` in mm.
    Text {
        x: f64,
        y: f64,
        size: f64,
        colour: &'static str,
        text: String,
    },
    /// A filled rectangle (rules, verdicts' backgrounds, colour swatches).
    Fill {
        x: f64,
        y: f64,
        w: f64,
        h: f64,
        colour: String,
    },
    /// A figure file, fitted in the rectangle.
    Picture {
        x: f64,
        y: f64,
        w: f64,
        h: f64,
        file: String,
    },
}

impl Mark {
    /// The mark moved by `(dx, dy)`.
    fn shifted(mut self, dx: f64, dy: f64) -> Mark {
        match &mut self {
            Mark::Text { x, y, .. } | Mark::Fill { x, y, .. } | Mark::Picture { x, y, .. } => {
                *x += dx;
                *y += dy;
            }
        }
        self
    }
}

/// A piece that is never cut by a page's end.
#[derive(Clone, Debug, Default)]
struct Block {
    /// Its height (mm).
    h: f64,
    /// Its marks.
    marks: Vec<Mark>,
    /// Whether it goes on the page of the block after it (a heading).
    keep_with_next: bool,
}

impl Block {
    /// The blocks one under the other, as one block.
    fn stack(blocks: Vec<Block>) -> Block {
        let mut out = Block::default();
        for (k, b) in blocks.into_iter().enumerate() {
            if k > 0 {
                out.h += SPACE;
            }
            let dy = out.h;
            out.marks
                .extend(b.marks.into_iter().map(|m| m.shifted(0.0, dy)));
            out.h += b.h;
        }
        out
    }

    /// The blocks side by side, `widths` apart by [`GAP`], as one block.
    fn row(blocks: Vec<Block>, widths: &[f64]) -> Block {
        let mut out = Block::default();
        let mut x = 0.0;
        for (b, w) in blocks.into_iter().zip(widths) {
            out.h = out.h.max(b.h);
            out.marks
                .extend(b.marks.into_iter().map(|m| m.shifted(x, 0.0)));
            x += w + GAP;
        }
        out
    }
}

/// What the pages are made of, in reading order.
#[derive(Clone, Debug)]
enum Flow {
    /// A block the page's width.
    One(Block),
    /// Two columns, each flowing on from page to page on its own (blocks half the width).
    Two(Vec<Block>, Vec<Block>),
}

impl From<Block> for Flow {
    fn from(b: Block) -> Flow {
        Flow::One(b)
    }
}

/// The blocks of the parts `parts` in two columns, each put in the column that is shorter so far.
fn balanced(parts: Vec<Vec<Block>>) -> Flow {
    let (mut left, mut right) = (Vec::new(), Vec::new());
    let height = |c: &Vec<Block>| c.iter().map(|b| b.h + SPACE).sum::<f64>();
    for part in parts {
        if height(&left) <= height(&right) {
            left.extend(part);
        } else {
            right.extend(part);
        }
    }
    Flow::Two(left, right)
}

/// Widths of text in the shipped font.
struct Metrics {
    face: ttf_parser::Face<'static>,
}

impl Metrics {
    fn new() -> Result<Metrics> {
        let face = ttf_parser::Face::parse(FONT, 0)
            .map_err(|e| Error::Refused(format!("the shipped font does not load ({e})")))?;
        Ok(Metrics { face })
    }

    /// Width (mm) of `text` at `size` pt.
    fn width(&self, text: &str, size: f64) -> f64 {
        let em = self.face.units_per_em() as f64;
        let units: f64 = text
            .chars()
            .map(|c| {
                self.face
                    .glyph_index(c)
                    .and_then(|g| self.face.glyph_hor_advance(g))
                    .map_or(em * 0.6, f64::from)
            })
            .sum();
        units / em * size * PT
    }

    /// `text` broken into lines at most `width` mm wide at `size` pt (a word longer than a line is
    /// cut where it must be).
    fn lines(&self, text: &str, width: f64, size: f64) -> Vec<String> {
        let mut lines = Vec::new();
        let mut line = String::new();
        for word in text.split_whitespace() {
            let tried = if line.is_empty() {
                word.to_string()
            } else {
                format!("{line} {word}")
            };
            if self.width(&tried, size) <= width {
                line = tried;
                continue;
            }
            if !line.is_empty() {
                lines.push(std::mem::take(&mut line));
            }
            for c in word.chars() {
                line.push(c);
                if self.width(&line, size) > width && line.chars().count() > 1 {
                    line.pop();
                    lines.push(std::mem::replace(&mut line, c.to_string()));
                }
            }
        }
        if !line.is_empty() {
            lines.push(line);
        }
        lines
    }
}

/// A figure file as read for the PDF.
enum Picture {
    /// A vector drawing.
    Drawing(Box<usvg::Tree>),
    /// A picture's pixels (RGB, 8 bits), its width and height.
    Pixels(Vec<u8>, u32, u32),
    /// Why it could not be read.
    Unread(String),
}

impl Picture {
    /// Width over height, or why the file could not be read.
    fn aspect(&self) -> std::result::Result<f64, &str> {
        match self {
            Picture::Drawing(t) => Ok((t.size().width() / t.size().height()) as f64),
            Picture::Pixels(_, w, h) => Ok(*w as f64 / *h as f64),
            Picture::Unread(e) => Err(e),
        }
    }
}

/// The report laid out as blocks, its figures read as they are placed.
struct Layout<'a> {
    metrics: Metrics,
    read: &'a dyn Fn(&str) -> Result<Vec<u8>>,
    /// Each figure file placed, read once.
    pictures: HashMap<String, Picture>,
    /// The files in the order first placed (the PDF embeds them in this order).
    order: Vec<String>,
    lang: Lang,
    /// How SVG is read (the shipped font loaded): made once for the figures and the pages.
    options: usvg::Options<'static>,
}

impl<'a> Layout<'a> {
    /// A layout in `lang` whose figures are read by `read`.
    fn new(read: &'a dyn Fn(&str) -> Result<Vec<u8>>, lang: Lang) -> Result<Layout<'a>> {
        let options = svg_options().map_err(|e| Error::Refused(format!("the PDF's font: {e}")))?;
        Ok(Layout {
            metrics: Metrics::new()?,
            read,
            pictures: HashMap::new(),
            order: Vec::new(),
            lang,
            options,
        })
    }

    /// The whole report: the header, the intro two columns wide, the overview, the simulations,
    /// the closing sections and the conventions.
    fn report(&mut self, report: &Report) -> Vec<Flow> {
        let lang = self.lang;
        let mut flows: Vec<Flow> = vec![
            self.text(&report.title, WIDTH, TITLE, INK).into(),
            self.text(&report.subtitle, WIDTH, BODY, INK).into(),
            rule(WIDTH, 0.5, INK).into(),
            self.text(lang.of(words::PRINTED_FROM), WIDTH, SMALL, MUTED)
                .into(),
        ];
        flows.extend(self.top_sections(&report.intro, true));
        flows.extend(self.overview(report).into_iter().map(Flow::from));
        let mut k = 0;
        while k < report.simulations.len() {
            let reference = report.simulations[k].reference;
            flows.push(self.heading(&report.simulations[k].group, H2, WIDTH).into());
            let mut first = true;
            while k < report.simulations.len() && report.simulations[k].reference == reference {
                flows.extend(self.simulation(&report.simulations[k], !first));
                first = false;
                k += 1;
            }
        }
        flows.extend(self.top_sections(&report.closing, false));
        flows.extend(self.footer(report).into_iter().map(Flow::from));
        flows
    }

    /// Wrapped text as one block.
    fn text(&self, text: &str, width: f64, size: f64, colour: &'static str) -> Block {
        let lines = self.metrics.lines(text, width, size);
        let step = size * PT * LEADING;
        let count = lines.len();
        let marks = lines
            .into_iter()
            .enumerate()
            .map(|(k, line)| Mark::Text {
                x: 0.0,
                y: step * (k as f64 + 0.8),
                size: size * PT,
                colour,
                text: line,
            })
            .collect();
        Block {
            h: step * count as f64,
            marks,
            keep_with_next: false,
        }
    }

    /// A heading kept with what follows; `H2` ones underlined.
    fn heading(&self, text: &str, size: f64, width: f64) -> Block {
        let colour = if size < H3 { MUTED } else { INK };
        let mut b = self.text(text, width, size, colour);
        b.h += 0.6;
        if size >= H2 {
            b.marks.push(Mark::Fill {
                x: 0.0,
                y: b.h,
                w: width,
                h: 0.35,
                colour: LINE.into(),
            });
            b.h += 1.0;
        }
        b.keep_with_next = true;
        b
    }

    /// Sections with their own heading; on paper those that are not printed are named in a note.
    /// `two_columns`: side by side in pairs (the intro), else one under the other.
    fn top_sections(&mut self, sections: &[Section], two_columns: bool) -> Vec<Flow> {
        let mut flows: Vec<Flow> = Vec::new();
        let half = (WIDTH - GAP) / 2.0;
        let mut k = 0;
        while k < sections.len() {
            if !sections[k].printed {
                let names: Vec<&str> = sections[k..]
                    .iter()
                    .take_while(|s| !s.printed)
                    .map(|s| s.title.as_str())
                    .collect();
                k += names.len();
                let note = self.lang.fill(words::NOT_PRINTED, &[&names.join(" · ")]);
                flows.push(self.text(&note, WIDTH, SMALL, MUTED).into());
                continue;
            }
            let run = sections[k..].iter().take_while(|s| s.printed).count();
            if two_columns && run > 1 {
                let parts = sections[k..k + run]
                    .iter()
                    .map(|s| {
                        let mut part = vec![self.heading(&s.title, H2, half)];
                        part.extend(self.body(s, half, PART_MAX));
                        part
                    })
                    .collect();
                flows.push(balanced(parts));
                k += run;
                continue;
            }
            flows.push(self.heading(&sections[k].title, H2, WIDTH).into());
            let body = self.body(&sections[k], WIDTH, FIGURE_MAX);
            flows.extend(body.into_iter().map(Flow::from));
            k += 1;
        }
        flows
    }

    /// A section's figures, notes and table, `width` wide.
    fn body(&mut self, sec: &Section, width: f64, max_h: f64) -> Vec<Block> {
        let mut blocks = Vec::new();
        if sec.side_by_side && sec.figures.len() > 1 {
            let half = (width - GAP) / 2.0;
            for pair in sec.figures.chunks(2) {
                let figs = pair
                    .iter()
                    .map(|f| self.figure(f, half, PAIR_MAX))
                    .collect();
                blocks.push(Block::row(figs, &[half, half]));
            }
        } else {
            for f in &sec.figures {
                blocks.push(self.figure(f, width, max_h));
            }
        }
        for n in &sec.notes {
            blocks.push(self.text(n, width, BODY, INK));
        }
        if !sec.table.is_empty() {
            blocks.push(self.table(&sec.table, width, true));
        }
        blocks
    }

    /// A figure fitted in `width` × `max_h`, centred, its caption under it (with its companion
    /// files' names, as printed).
    fn figure(&mut self, f: &Figure, width: f64, max_h: f64) -> Block {
        let mut caption = f.caption.clone();
        let links: Vec<String> = f
            .links
            .iter()
            .map(|l| match &l.error {
                None => format!("{} ({})", l.label, l.file),
                Some(e) => self.lang.fill(words::NOT_WRITTEN_LINK, &[&l.label, e]),
            })
            .collect();
        if !links.is_empty() {
            caption = format!("{caption} — {}", links.join(" · "));
        }
        let shown = match &f.error {
            Some(e) => Err(e.clone()),
            None => self.picture(&f.file).aspect().map_err(str::to_string),
        };
        let mut parts = Vec::new();
        match shown {
            Err(e) => {
                let text = self.lang.fill(words::NOT_WRITTEN_FIGURE, &[&f.file, &e]);
                parts.push(self.verdict(&text, false, width));
            }
            Ok(aspect) => {
                let w = width.min(max_h * aspect);
                let h = w / aspect;
                parts.push(Block {
                    h,
                    marks: vec![Mark::Picture {
                        x: (width - w) / 2.0,
                        y: 0.0,
                        w,
                        h,
                        file: f.file.clone(),
                    }],
                    keep_with_next: false,
                });
            }
        }
        parts.push(self.text(&caption, width, CAPTION, MUTED));
        Block::stack(parts)
    }

    /// The figure file `file`, read the first time it is placed.
    fn picture(&mut self, file: &str) -> &Picture {
        if !self.pictures.contains_key(file) {
            let picture = match (self.read)(file) {
                Err(e) => Picture::Unread(e.to_string()),
                Ok(bytes) if file.ends_with(".svg") => {
                    match usvg::Tree::from_data(&bytes, &self.options) {
                        Ok(tree) => Picture::Drawing(Box::new(tree)),
                        Err(e) => Picture::Unread(e.to_string()),
                    }
                }
                Ok(bytes) => match image::load_from_memory(&bytes) {
                    Ok(img) => {
                        let rgb = img.to_rgb8();
                        let (w, h) = rgb.dimensions();
                        Picture::Pixels(rgb.into_raw(), w, h)
                    }
                    Err(e) => Picture::Unread(e.to_string()),
                },
            };
            self.order.push(file.to_string());
            self.pictures.insert(file.to_string(), picture);
        }
        &self.pictures[file]
    }

    /// A verdict's line on its green or red ground.
    fn verdict(&self, text: &str, passed: bool, width: f64) -> Block {
        let (ink, ground) = if passed { OK } else { BAD };
        let pad = 1.2;
        let lines = self.metrics.lines(text, width - 2.0 * pad, SMALL);
        let step = SMALL * PT * LEADING;
        let h = step * lines.len() as f64 + 2.0 * pad;
        let mut marks = vec![Mark::Fill {
            x: 0.0,
            y: 0.0,
            w: width,
            h,
            colour: ground.into(),
        }];
        marks.extend(lines.into_iter().enumerate().map(|(k, line)| Mark::Text {
            x: pad,
            y: pad + step * (k as f64 + 0.8),
            size: SMALL * PT,
            colour: ink,
            text: line,
        }));
        Block {
            h,
            marks,
            keep_with_next: false,
        }
    }

    /// A table of text cells (the first row a header when `header`), shrunk to `width` if it is
    /// wider; numbers right-aligned, the first column left-aligned.
    fn table(&self, rows: &[Vec<String>], width: f64, header: bool) -> Block {
        let pad = 1.6;
        let columns = rows.iter().map(Vec::len).max().unwrap_or(0);
        let natural = |size: f64| -> Vec<f64> {
            (0..columns)
                .map(|c| {
                    rows.iter()
                        .filter_map(|r| r.get(c))
                        .map(|t| self.metrics.width(t, size))
                        .fold(0.0, f64::max)
                        + 2.0 * pad
                })
                .collect()
        };
        let mut size = SMALL;
        let total: f64 = natural(size).iter().sum();
        if total > width {
            size *= width / total;
        }
        let widths = natural(size);
        let step = size * PT * 1.45;
        let mut marks = Vec::new();
        let mut y = 0.0;
        for (r, row) in rows.iter().enumerate() {
            let mut x = 0.0;
            for (c, cell) in row.iter().enumerate() {
                let w = self.metrics.width(cell, size);
                let left = c == 0 || !looks_numeric(cell);
                marks.push(Mark::Text {
                    x: if left {
                        x + pad
                    } else {
                        x + widths[c] - pad - w
                    },
                    y: y + step * 0.75,
                    size: size * PT,
                    colour: if header && r == 0 { MUTED } else { INK },
                    text: cell.clone(),
                });
                x += widths[c];
            }
            y += step;
            marks.push(Mark::Fill {
                x: 0.0,
                y,
                w: widths.iter().sum(),
                h: if header && r == 0 { 0.3 } else { 0.15 },
                colour: LINE.into(),
            });
        }
        Block {
            h: y + 0.5,
            marks,
            keep_with_next: false,
        }
    }

    /// The overview table: one row per simulation.
    fn overview(&self, report: &Report) -> Vec<Block> {
        let lang = self.lang;
        let colours = colour_count(report);
        let mut head: Vec<String> = words::OVERVIEW_HEAD
            .iter()
            .map(|t| lang.of(*t).to_string())
            .collect();
        head.extend((0..colours).map(|k| lang.colour_name(k).to_string()));
        head.extend(words::OVERVIEW_TAIL.iter().map(|t| lang.of(*t).to_string()));
        let mut rows = vec![head];
        for s in &report.simulations {
            let mut row = vec![
                s.id.clone(),
                s.n_water.to_string(),
                s.rays.to_string(),
                s.points.to_string(),
                format!("{:.1} %", 100.0 * s.hit_ratio),
            ];
            row.extend((0..colours).map(|k| s.counts.get(k).copied().unwrap_or(0).to_string()));
            let total: std::time::Duration = s.timings.iter().map(|t| t.duration).sum();
            row.push(seconds(total));
            row.push(
                s.check
                    .as_ref()
                    .map(|c| c.short.clone())
                    .unwrap_or_default(),
            );
            rows.push(row);
        }
        vec![
            self.heading(lang.of(words::OVERVIEW), H2, WIDTH),
            self.table(&rows, WIDTH, true),
        ]
    }

    /// One simulation: its heading, numbers and checks, then its parts two columns wide (the
    /// pictures to compare across the page, last). An index check (`variant`): numbers and
    /// checks beside its parts.
    fn simulation(&mut self, s: &SimulationEntry, variant: bool) -> Vec<Flow> {
        let lang = self.lang;
        let facts = words::FACTS.map(|t| lang.of(t).to_string());
        let inputs: Vec<Vec<String>> = s
            .inputs
            .iter()
            .map(|(l, v)| vec![l.clone(), v.clone()])
            .collect();
        let numbers = vec![
            vec![facts[0].clone(), s.rays.to_string()],
            vec![facts[1].clone(), s.points.to_string()],
            vec![facts[2].clone(), format!("{:.1} %", 100.0 * s.hit_ratio)],
        ];
        let counts: Vec<Vec<String>> = s
            .counts
            .iter()
            .enumerate()
            .map(|(k, c)| vec![format!("{} {}", k + 1, lang.colour_name(k)), c.to_string()])
            .collect();
        let checks = |me: &Self, width: f64| -> Vec<Block> {
            let mut out = Vec::new();
            if let Some(c) = &s.check {
                out.push(me.verdict(&c.text, c.passed, width));
            }
            if let Some(c) = &s.solution_check {
                out.push(me.solution_verdict(c, width));
            }
            out
        };
        let mut flows: Vec<Flow> = vec![self.heading(&s.heading, H3, WIDTH).into()];
        let half = (WIDTH - GAP) / 2.0;
        if variant {
            let mut left = vec![
                self.table(&inputs, half, false),
                self.table(&numbers, half, false),
                self.table(&counts, half, false),
            ];
            left.extend(checks(self, half));
            let mut right = Vec::new();
            for sec in &s.sections {
                right.push(self.heading(&sec.title, H4, half));
                right.extend(self.body(sec, half, VARIANT_MAX));
            }
            flows.push(Flow::Two(left, right));
            return flows;
        }
        let tables = [
            self.table(&inputs, WIDTH, false),
            self.table(&numbers, WIDTH, false),
            self.table(&counts, WIDTH, false),
        ];
        let widths: Vec<f64> = tables.iter().map(table_width).collect();
        if widths.iter().sum::<f64>() + 2.0 * GAP <= WIDTH {
            flows.push(Block::row(tables.to_vec(), &widths).into());
        } else {
            flows.extend(tables.into_iter().map(Flow::from));
        }
        flows.extend(checks(self, WIDTH).into_iter().map(Flow::from));
        let (wide, narrow): (Vec<&Section>, Vec<&Section>) =
            s.sections.iter().partition(|sec| sec.side_by_side);
        let parts = narrow
            .iter()
            .map(|sec| {
                let mut part = vec![self.heading(&sec.title, H4, half)];
                part.extend(self.body(sec, half, PART_MAX));
                part
            })
            .collect();
        flows.push(balanced(parts));
        for sec in wide {
            flows.push(self.heading(&sec.title, H4, WIDTH).into());
            let body = self.body(sec, WIDTH, PAIR_MAX);
            flows.extend(body.into_iter().map(Flow::from));
        }
        flows
    }

    /// What `bentstraw check` says of a simulation's points.
    fn solution_verdict(&self, c: &Check, width: f64) -> Block {
        // The words end in a space that `plain` does not keep.
        let text = format!(
            "{} {}",
            plain(self.lang.of(words::CHECKED_AS_SOLUTION)),
            c.text
        );
        self.verdict(&text, c.passed, width)
    }

    /// The conventions at the foot (the footer's headings and paragraphs, as text).
    fn footer(&self, report: &Report) -> Vec<Block> {
        let lang = self.lang;
        let names = (0..colour_count(report))
            .map(|k| format!("{} {}", k + 1, lang.colour_name(k)))
            .collect::<Vec<_>>()
            .join(", ");
        let html = lang.fill(
            report.footer,
            &[&names, &env!("CARGO_PKG_VERSION"), &seconds(report.total)],
        );
        // Each `<h2>` or `<p>` starts a block; inline elements (`<code>`) stay in theirs.
        let mut pieces: Vec<(bool, String)> = Vec::new();
        for piece in html.split('<').skip(1) {
            let Some((tag, text)) = piece.split_once('>') else {
                continue;
            };
            match tag.split_whitespace().next() {
                Some(kind @ ("h2" | "p")) => pieces.push((kind == "h2", text.to_string())),
                _ => {
                    if let Some((_, last)) = pieces.last_mut() {
                        last.push_str(text);
                    }
                }
            }
        }
        let mut blocks = Vec::new();
        for (heading, text) in pieces {
            let text = plain(&text);
            if text.is_empty() {
                continue;
            }
            blocks.push(if heading {
                self.heading(&text, H2, WIDTH)
            } else {
                self.text(&text, WIDTH, SMALL, INK)
            });
        }
        blocks
    }
}

/// The text of a block made by [`Layout::text`], its lines joined.
#[cfg(test)]
fn block_text(b: &Block) -> String {
    b.marks
        .iter()
        .filter_map(|m| match m {
            Mark::Text { text, .. } => Some(text.as_str()),
            _ => None,
        })
        .collect::<Vec<_>>()
        .join(" ")
}

/// The width a table block takes (its widest rule).
fn table_width(b: &Block) -> f64 {
    b.marks
        .iter()
        .map(|m| match m {
            Mark::Fill { x, w, .. } => x + w,
            _ => 0.0,
        })
        .fold(0.0, f64::max)
}

/// Whether a cell reads as a number (right-aligned): it starts with a digit, a sign or a point.
fn looks_numeric(cell: &str) -> bool {
    cell.trim_start()
        .chars()
        .next()
        .is_some_and(|c| c.is_ascii_digit() || "+-−.".contains(c))
}

/// A horizontal rule `thick` mm thick.
fn rule(width: f64, thick: f64, colour: &str) -> Block {
    Block {
        h: thick + 1.0,
        marks: vec![Mark::Fill {
            x: 0.0,
            y: 0.5,
            w: width,
            h: thick,
            colour: colour.into(),
        }],
        keep_with_next: false,
    }
}

/// Text of a piece of our own HTML: tags dropped, entities decoded.
fn plain(html: &str) -> String {
    let mut out = String::with_capacity(html.len());
    let mut in_tag = false;
    for c in html.chars() {
        match c {
            '<' => in_tag = true,
            '>' if in_tag => in_tag = false,
            c if !in_tag => out.push(c),
            _ => {}
        }
    }
    out.replace("&lt;", "<")
        .replace("&gt;", ">")
        .replace("&quot;", "\"")
        .replace("&#39;", "'")
        .replace("&amp;", "&")
        .split_whitespace()
        .collect::<Vec<_>>()
        .join(" ")
}

/// The flows placed on pages: a block that does not fit in what is left of a page (or of its
/// column) starts the next, and so does a heading whose next block would not fit with it.
fn paginate(flows: Vec<Flow>) -> Vec<Vec<Mark>> {
    let mut pages: Vec<Vec<Mark>> = vec![Vec::new()];
    let mut y = 0.0;
    let half = (WIDTH - GAP) / 2.0;
    for (k, flow) in flows.iter().enumerate() {
        match flow {
            Flow::One(b) => {
                let next = flows.get(k + 1).map_or(0.0, first_height);
                let need = b.h + if b.keep_with_next { SPACE + next } else { 0.0 };
                if y > 0.0 && y + need.min(HEIGHT) > HEIGHT {
                    pages.push(Vec::new());
                    y = 0.0;
                }
                place(pages.last_mut().expect("a page"), b, MARGIN_X, y);
                y += b.h + SPACE;
            }
            Flow::Two(left, right) => {
                let (mut l, mut r) = (0, 0);
                let mut top = y;
                loop {
                    let page = pages.last_mut().expect("a page");
                    let yl = fill_column(page, left, &mut l, top, MARGIN_X);
                    let yr = fill_column(page, right, &mut r, top, MARGIN_X + half + GAP);
                    if l == left.len() && r == right.len() {
                        y = yl.max(yr);
                        break;
                    }
                    pages.push(Vec::new());
                    top = 0.0;
                }
            }
        }
    }
    pages
}

/// Height of the first block of `flow` (what a heading before it must fit with).
fn first_height(flow: &Flow) -> f64 {
    match flow {
        Flow::One(b) => b.h,
        Flow::Two(l, r) => {
            let h = |c: &Vec<Block>| c.first().map_or(0.0, |b| b.h);
            h(l).max(h(r))
        }
    }
}

/// Places the blocks of `column` from `*next` at `x`, from `top` down while they fit on the page
/// (at least one when `top` is the page's top); returns where the column ends.
fn fill_column(page: &mut Vec<Mark>, column: &[Block], next: &mut usize, top: f64, x: f64) -> f64 {
    let mut y = top;
    while let Some(b) = column.get(*next) {
        let after = column.get(*next + 1).map_or(0.0, |n| SPACE + n.h);
        let need = b.h + if b.keep_with_next { after } else { 0.0 };
        if y > 0.0 && y + need.min(HEIGHT) > HEIGHT {
            break;
        }
        place(page, b, x, y);
        y += b.h + SPACE;
        *next += 1;
    }
    y
}

/// The marks of `b` put on `page` with its top left at `(x, y)` of the text area.
fn place(page: &mut Vec<Mark>, b: &Block, x: f64, y: f64) {
    page.extend(b.marks.iter().cloned().map(|m| m.shifted(x, MARGIN_Y + y)));
}

/// The PDF: each page's text and rules as one drawing, its figures drawn over it from the
/// objects embedded once.
fn assemble(report: &Report, layout: &Layout, pages: &[Vec<Mark>]) -> Result<Vec<u8>> {
    let fail = |what: &str, e: String| Error::Refused(format!("the PDF's {what}: {e}"));
    let mut alloc = Ref::new(1);
    let catalog = alloc.bump();
    let tree = alloc.bump();
    let info = alloc.bump();
    let mut pdf = Pdf::new();

    let mut embedded: HashMap<&str, Ref> = HashMap::new();
    for file in &layout.order {
        let id = match &layout.pictures[file] {
            Picture::Drawing(t) => {
                let (chunk, id) = svg2pdf::to_chunk(t, svg2pdf::ConversionOptions::default())
                    .map_err(|e| fail(file, e.to_string()))?;
                embed(&mut pdf, &chunk, id, &mut alloc)
            }
            Picture::Pixels(rgb, w, h) => {
                let id = alloc.bump();
                let data = deflate(rgb).map_err(|e| fail(file, e.to_string()))?;
                let mut image = pdf.image_xobject(id, &data);
                image.filter(Filter::FlateDecode);
                image.width(*w as i32);
                image.height(*h as i32);
                image.color_space().device_rgb();
                image.bits_per_component(8);
                image.finish();
                id
            }
            Picture::Unread(_) => continue,
        };
        embedded.insert(file.as_str(), id);
    }

    let scale = |mm: f64| (mm / PT) as f32;
    let count = pages.len();
    let mut page_ids = Vec::with_capacity(count);
    for (n, marks) in pages.iter().enumerate() {
        let svg = page_svg(marks, &format!("{} / {count}", n + 1));
        let drawing =
            usvg::Tree::from_str(&svg, &layout.options).map_err(|e| fail("page", e.to_string()))?;
        let (chunk, id) = svg2pdf::to_chunk(&drawing, svg2pdf::ConversionOptions::default())
            .map_err(|e| fail("page", e.to_string()))?;
        let drawing = embed(&mut pdf, &chunk, id, &mut alloc);

        let mut names: Vec<(String, Ref)> = vec![("P".into(), drawing)];
        let mut content = Content::new();
        content.save_state();
        content.transform([scale(PAGE_W), 0.0, 0.0, scale(PAGE_H), 0.0, 0.0]);
        content.x_object(Name(b"P"));
        content.restore_state();
        for m in marks {
            if let Mark::Picture { x, y, w, h, file } = m {
                let Some(&id) = embedded.get(file.as_str()) else {
                    continue;
                };
                let name = format!("I{}", names.len());
                content.save_state();
                content.transform([
                    scale(*w),
                    0.0,
                    0.0,
                    scale(*h),
                    scale(*x),
                    scale(PAGE_H - y - h),
                ]);
                content.x_object(Name(name.as_bytes()));
                content.restore_state();
                names.push((name, id));
            }
        }
        let content_id = alloc.bump();
        pdf.stream(content_id, &content.finish());
        let page_id = alloc.bump();
        let mut page = pdf.page(page_id);
        page.media_box(Rect::new(0.0, 0.0, scale(PAGE_W), scale(PAGE_H)));
        page.parent(tree);
        page.contents(content_id);
        let mut resources = page.resources();
        let mut objects = resources.x_objects();
        for (name, id) in &names {
            objects.pair(Name(name.as_bytes()), *id);
        }
        objects.finish();
        resources.finish();
        page.finish();
        page_ids.push(page_id);
    }
    pdf.pages(tree).kids(page_ids).count(count as i32);
    pdf.catalog(catalog)
        .pages(tree)
        .lang(TextStr(report.lang.code()));
    pdf.document_info(info)
        .title(TextStr(&report.title))
        .creator(TextStr(concat!("bentstraw ", env!("CARGO_PKG_VERSION"))));
    Ok(pdf.finish())
}

/// `chunk` put into `pdf` with fresh object numbers; the new number of its object `id`.
fn embed(pdf: &mut Pdf, chunk: &pdf_writer::Chunk, id: Ref, alloc: &mut Ref) -> Ref {
    let mut map = HashMap::new();
    let renumbered = chunk.renumber(|old| *map.entry(old).or_insert_with(|| alloc.bump()));
    pdf.extend(&renumbered);
    map[&id]
}

/// `bytes` compressed for a PDF stream's `FlateDecode`.
fn deflate(bytes: &[u8]) -> std::io::Result<Vec<u8>> {
    use std::io::Write as _;
    let mut z = flate2::write::ZlibEncoder::new(Vec::new(), flate2::Compression::new(6));
    z.write_all(bytes)?;
    z.finish()
}

/// One page's text and rules (not its figures) as an SVG in millimetres, its number at the foot.
fn page_svg(marks: &[Mark], folio: &str) -> String {
    let mut s = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{PAGE_W}\" height=\"{PAGE_H}\" \
         viewBox=\"0 0 {PAGE_W} {PAGE_H}\" font-family=\"sans-serif\">\n"
    );
    for m in marks {
        match m {
            Mark::Text {
                x,
                y,
                size,
                colour,
                text,
            } => {
                let _ = writeln!(
                    s,
                    "<text x=\"{x:.3}\" y=\"{y:.3}\" font-size=\"{size:.3}\" fill=\"{colour}\">{}</text>",
                    escape_html(text)
                );
            }
            Mark::Fill { x, y, w, h, colour } => {
                let _ = writeln!(
                    s,
                    "<rect x=\"{x:.3}\" y=\"{y:.3}\" width=\"{w:.3}\" height=\"{h:.3}\" fill=\"{colour}\"/>"
                );
            }
            Mark::Picture { .. } => {}
        }
    }
    let _ = writeln!(
        s,
        "<text x=\"{:.3}\" y=\"{:.3}\" font-size=\"{:.3}\" fill=\"{MUTED}\" text-anchor=\"end\">{}</text>",
        PAGE_W - MARGIN_X,
        PAGE_H - MARGIN_Y + 1.0,
        SMALL * PT,
        escape_html(folio)
    );
    s.push_str("</svg>\n");
    s
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::report::{Link, Timing};
    use std::time::Duration;

    /// A small report: two reference simulations (one with an index check), a side-by-side
    /// section, a section that is not printed, an SVG and a PNG figure and one that is missing.
    fn report() -> Report {
        let section = |title: &str, figures: Vec<Figure>, side_by_side: bool, printed: bool| {
            Section {
                title: title.into(),
                figures,
                notes: vec![format!("A note on {title}, long enough to wrap onto a second line of the column it is set in, and then a third one.")],
                side_by_side,
                printed,
                table: Vec::new(),
            }
        };
        let mut drawing = Figure::image("cloud.svg", "Image points <three views>");
        drawing.links = vec![Link::new("cloud.html", "3D view", None)];
        let entry = |id: &str, reference: u32| SimulationEntry {
            id: id.into(),
            reference,
            group: format!("Reference simulation {reference}"),
            heading: format!("Simulation {id}"),
            inputs: vec![("observer".into(), "(0, 0.1, 0.1) m".into())],
            n_water: 1.333,
            rays: 4000,
            points: 1234,
            counts: vec![1, 2, 3, 4, 1224],
            hit_ratio: 0.3085,
            timings: vec![Timing::new("tracing", Duration::from_millis(250))],
            check: Some(Check {
                passed: id != "sim2",
                text: format!("verdict of {id}"),
                short: "pass".into(),
            }),
            solution_check: None,
            sections: vec![
                section("Image points", vec![drawing.clone()], false, true),
                section(
                    "Pictures",
                    vec![
                        Figure::image("view.png", "What the observer sees"),
                        Figure::image("missing.png", "Not there"),
                    ],
                    true,
                    true,
                ),
            ],
        };
        Report {
            title: "The title".into(),
            subtitle: "The subtitle".into(),
            intro: vec![
                section("Method", vec![], false, true),
                section("Effect", vec![], false, true),
            ],
            simulations: vec![entry("sim1", 1), entry("sim1_n1", 1), entry("sim2", 2)],
            closing: vec![
                section("Gallery: a", vec![], false, false),
                section("Limits", vec![], false, true),
            ],
            total: Duration::from_secs(3),
            lang: Lang::En,
            footer: words::FOOTER,
        }
    }

    /// The files of [`report`]: a drawing 4:3, a picture 2:1, nothing else.
    fn read(file: &str) -> Result<Vec<u8>> {
        match file {
            "cloud.svg" => Ok(br##"<svg xmlns="http://www.w3.org/2000/svg" width="400" height="300"><rect width="400" height="300" fill="#fff"/><circle cx="200" cy="150" r="100" fill="#c00"/><text x="10" y="30" font-size="20">front view</text></svg>"##.to_vec()),
            "view.png" => {
                let mut png = Vec::new();
                image::RgbImage::from_pixel(40, 20, image::Rgb([10, 200, 30]))
                    .write_to(&mut std::io::Cursor::new(&mut png), image::ImageFormat::Png)
                    .unwrap();
                Ok(png)
            }
            other => Err(Error::Refused(format!("{other}: no such file"))),
        }
    }

    fn texts(pages: &[Vec<Mark>]) -> Vec<Vec<String>> {
        pages
            .iter()
            .map(|p| {
                p.iter()
                    .filter_map(|m| match m {
                        Mark::Text { text, .. } => Some(text.clone()),
                        _ => None,
                    })
                    .collect()
            })
            .collect()
    }

    #[test]
    fn every_mark_lies_inside_its_pages_margins() {
        let r = report();
        let mut layout = Layout::new(&read, r.lang).unwrap();
        let pages = paginate(layout.report(&r));
        assert!(pages.len() >= 2, "{} pages", pages.len());
        for (n, page) in pages.iter().enumerate() {
            for m in page {
                let (x, y, w, h) = match m {
                    Mark::Text {
                        x, y, size, text, ..
                    } => (*x, *y - size, layout.metrics.width(text, size / PT), *size),
                    Mark::Fill { x, y, w, h, .. } | Mark::Picture { x, y, w, h, .. } => {
                        (*x, *y, *w, *h)
                    }
                };
                assert!(
                    x >= MARGIN_X - 1e-9
                        && x + w <= PAGE_W - MARGIN_X + 1e-6
                        && y >= MARGIN_Y - 2.0
                        && y + h <= PAGE_H - MARGIN_Y + 1e-6,
                    "page {}: {m:?} leaves the page's text area",
                    n + 1
                );
            }
        }
    }

    #[test]
    fn headings_are_never_last_on_a_page_and_what_is_not_printed_is_named() {
        let r = report();
        let mut layout = Layout::new(&read, r.lang).unwrap();
        let flows = layout.report(&r);
        let headings: Vec<String> = flows
            .iter()
            .flat_map(|f| match f {
                Flow::One(b) => vec![b.clone()],
                Flow::Two(l, r) => l.iter().chain(r).cloned().collect(),
            })
            .filter(|b| b.keep_with_next)
            .map(|b| block_text(&b))
            .collect();
        let placed = paginate(flows);
        // No page (nor column: a heading is the lowest text of its column) ends on a heading.
        for page in &placed {
            for column in [MARGIN_X, MARGIN_X + (WIDTH + GAP) / 2.0] {
                let lowest = page
                    .iter()
                    .filter_map(|m| match m {
                        Mark::Text { x, y, text, .. }
                            if *x >= column - 1e-9 && *x < column + (WIDTH - GAP) / 2.0 =>
                        {
                            Some((*y, text.clone()))
                        }
                        _ => None,
                    })
                    .max_by(|a, b| a.0.total_cmp(&b.0));
                if let Some((_, text)) = lowest {
                    assert!(
                        !headings.contains(&text),
                        "a page ends with heading {text:?}"
                    );
                }
            }
        }
        let pages = texts(&placed);
        let all: Vec<&String> = pages.iter().flatten().collect();
        assert!(all
            .iter()
            .any(|t| t.contains("Not printed") && t.contains("Gallery: a")));
        assert!(!all.iter().any(|t| t.as_str() == "Gallery: a"));
        // The missing figure is said, the companion file named, the verdicts there.
        let joined = all.iter().map(|s| s.as_str()).collect::<Vec<_>>().join(" ");
        assert!(
            joined.contains("missing.png could not be written"),
            "{joined}"
        );
        assert!(joined.contains("3D view (cloud.html)"));
        assert!(joined.contains("verdict of sim2"));
        // The same drawing is read once, however often it is placed.
        assert_eq!(layout.order.iter().filter(|f| *f == "cloud.svg").count(), 1);
    }

    #[test]
    fn the_pdf_has_its_pages_text_and_figures() {
        let pdf = report_pdf(&report(), &read).unwrap();
        assert!(pdf.starts_with(b"%PDF-"));
        let text = String::from_utf8_lossy(&pdf);
        let pages = text.matches("/Type /Page").count() - text.matches("/Type /Pages").count();
        assert!(pages >= 2, "{pages} pages");
        assert!(text.contains("/Lang (en)"));
        // The picture's pixels are embedded once, deflated, as RGB.
        assert_eq!(text.matches("/Width 40").count(), 1);
        assert!(text.contains("/FlateDecode"));
    }

    #[test]
    fn lines_fit_their_width_and_keep_every_word() {
        let m = Metrics::new().unwrap();
        let text = "Snell's law bends every ray that crosses the water's surface towards the \
                    normal, a_very_long_identifier_that_must_be_cut_somewhere_inside_it";
        for width in [20.0, 45.0, 90.0] {
            let lines = m.lines(text, width, BODY);
            for l in &lines {
                assert!(m.width(l, BODY) <= width + 1e-9, "{l:?} wider than {width}");
            }
            assert_eq!(
                lines.concat().replace(' ', ""),
                text.replace(' ', ""),
                "a word was lost at width {width}"
            );
        }
        assert!(m.width("mm", BODY) > m.width("ii", BODY));
    }

    #[test]
    fn our_html_reads_as_plain_text() {
        assert_eq!(
            plain("Checked (<code>bentstraw check</code>): a &amp; b &#39;c&#39;"),
            "Checked (bentstraw check): a & b 'c'"
        );
    }
}
