//! A solution's image points judged: read from a file (any common layout of `x y z color`),
//! checked against the true image, and reported in words for people or as one JSON object for
//! graders' scripts. The command line's `check` and the Python package's `check` both end here.

use std::fmt::Write as _;
use std::path::Path;

use bentstraw_optics::check::{worst_points, CheckReport, ClaimedPoint, Verdict};
use bentstraw_optics::check::{MissingRegion, VerdictKind, REACH_CELLS};
use bentstraw_optics::scene::SECTION_COUNT;
use bentstraw_optics::text::{clip_text, number_text};
use bentstraw_optics::world::COLOR_NAMES;
use bentstraw_optics::Vec3;
use serde_json::{json, Value};

use crate::error::{Error, Result};
use crate::files::{read_input, Unread};
use bentstraw_optics::record::InputValue;
use bentstraw_optics::setup::Setup;

/// How strictly a solution is judged, and how much of it the report lists.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CheckOptions {
    /// Largest error of a point's path length still judged correct (m).
    pub tolerance: f64,
    /// Smallest share of each colour's true image a complete solution covers.
    pub min_coverage: f64,
    /// How many of the worst points the report lists.
    pub worst: usize,
}

impl CheckOptions {
    /// The options, or a refusal naming each value outside its rule.
    pub fn validate(&self) -> Result<()> {
        let mut broken = Vec::new();
        if !(self.tolerance.is_finite() && self.tolerance > 0.0) {
            broken.push(format!(
                "--tolerance {} is not allowed: it must be a finite length > 0 (metres)",
                number_text(self.tolerance)
            ));
        }
        if !(0.0..=1.0).contains(&self.min_coverage) {
            broken.push(format!(
                "--min-coverage {} is not allowed: it must be a share between 0 and 1",
                number_text(self.min_coverage)
            ));
        }
        match broken.len() {
            0 => Ok(()),
            _ => Err(Error::Refused(broken.join("\n"))),
        }
    }
}

/// Most points a solution may have: more is not a reasonable image (a simulation makes 20 000 by
/// default); judging one costs about 200 bytes of memory, so at most ~400 MB.
pub const MAX_POINTS: usize = 2_000_000;
/// Largest solution file read (bytes, 128 MiB): two million points of generous width.
pub const MAX_FILE_BYTES: u64 = 128 << 20;
/// Most values on a line of a solution file (a header may name extra columns, such as the ones
/// `simulate` writes).
pub const MAX_FIELDS: usize = 64;
/// How many characters of a user's text an error quotes.
const QUOTE: usize = 40;

/// A solution read from a file: its points, and the line each came from.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Solution {
    /// The points, in the file's order.
    pub points: Vec<ClaimedPoint>,
    /// The 1-based line number of each point.
    pub lines: Vec<usize>,
    /// A note on how the header was read, if there was one.
    pub header: Option<String>,
    /// Most significant digits written in any coordinate (how precisely the file was saved).
    pub digits: usize,
    /// Largest coordinate's magnitude (m).
    pub largest: f64,
}

/// Fewest significant digits with which a micrometre tolerance is safe at the scene's size.
const SAFE_DIGITS: usize = 7;

/// The significant digits written in a number: `0.0012300` has 5, `1.5e2` has 2.
fn significant_digits(field: &str) -> usize {
    let mantissa = field.split(['e', 'E']).next().unwrap_or("");
    let digits: String = mantissa.chars().filter(char::is_ascii_digit).collect();
    digits.trim_start_matches('0').len()
}

/// How far rounding to `digits` significant digits can move a coordinate of magnitude `largest`.
fn rounding_error(digits: usize, largest: f64) -> f64 {
    if largest <= 0.0 || digits == 0 {
        return 0.0;
    }
    0.5 * 10f64.powf(largest.log10().floor() - digits as f64 + 1.0)
}

/// Reads and parses the solution at `path` (refusing files too large to be an image), for a
/// scene whose colour codes go from 1 to `codes`.
pub fn read_solution_of(path: &Path, codes: usize) -> Result<Solution> {
    let name = clip_text(&path.display().to_string(), 80);
    let bytes =
        read_input(path, MAX_FILE_BYTES).map_err(|u| Error::Refused(unread_words(&name, u)))?;
    solution_from_bytes(&name, &bytes, codes)
}

/// Parses the bytes of the solution file `name` (see [`parse_solution_of`]); a refusal names it.
pub fn solution_from_bytes(name: &str, bytes: &[u8], codes: usize) -> Result<Solution> {
    parse_solution_of(bytes, codes).map_err(|e| Error::Refused(format!("{name}: {e}")))
}

/// Why the solution file `name` was not read, in words.
pub fn unread_words(name: &str, unread: Unread) -> String {
    match unread {
        Unread::Io(e) => format!("cannot read {name}: {e}"),
        Unread::NotAFile(why) => format!("cannot read {name}: {why}"),
        Unread::TooLarge(size) => format!(
            "{name} is {size}: larger than any reasonable image (at most {MAX_FILE_BYTES} \
             bytes, {MAX_POINTS} points), not read"
        ),
    }
}

/// The colour columns' accepted names.
const COLOUR_NAMES: [&str; 8] = [
    "color", "colour", "face", "couleur", "c", "code", "section", "col",
];

/// Parses a solution: columns `x y z color` (or as a header names them), one point a line.
#[cfg(test)]
pub fn parse_solution(bytes: &[u8]) -> Result<Solution, String> {
    parse_solution_of(bytes, SECTION_COUNT)
}

/// Parses a solution (columns `x y z color`, or as a header names them, one point a line) for a
/// scene whose colour codes go from 1 to `codes` (5: a straw's sections; 8 with a scene file's
/// coins, cards and pictures).
pub fn parse_solution_of(bytes: &[u8], codes: usize) -> Result<Solution, String> {
    let bytes = bytes.strip_prefix(b"\xEF\xBB\xBF").unwrap_or(bytes);
    let mut solution = Solution::default();
    // Column of x, y, z and the colour; None until the first line that is not a comment.
    let mut columns: Option<[usize; 4]> = None;
    let mut width = 4;
    for (k, raw) in bytes.split(|&b| b == b'\n').enumerate() {
        let line_no = k + 1;
        let line = std::str::from_utf8(raw)
            .map_err(|_| format!("line {line_no}: not text (not UTF-8)"))?
            .trim_end_matches('\r')
            .trim();
        if line.is_empty() || line.starts_with('#') || line.starts_with('%') {
            continue;
        }
        let fields = split_fields(line).map_err(|e| format!("line {line_no}: {e}"))?;
        if columns.is_none() {
            columns = Some([0, 1, 2, 3]);
            if fields.iter().all(|f| parse_number(f).is_none()) {
                let (cols, note) =
                    read_header(&fields).map_err(|e| format!("line {line_no}: {e}"))?;
                columns = Some(cols);
                width = fields.len();
                solution.header = Some(format!("line {line_no}: {note}"));
                continue;
            }
        }
        let cols = columns.unwrap_or([0, 1, 2, 3]);
        if fields.len() != width {
            return Err(format!(
                "line {line_no}: {} value(s), expected {width} ({}): '{}'",
                fields.len(),
                if solution.header.is_some() {
                    "as the header names"
                } else {
                    "x y z color"
                },
                clip_text(line, QUOTE)
            ));
        }
        let mut v = [0.0; 4];
        for (slot, &c) in v.iter_mut().zip(&cols) {
            let f = fields[c];
            let x = parse_number(f).ok_or_else(|| {
                format!(
                    "line {line_no}: '{}' is not a number (column {})",
                    clip_text(f, QUOTE),
                    c + 1
                )
            })?;
            *slot = x;
        }
        for &c in &cols[..3] {
            solution.digits = solution.digits.max(significant_digits(fields[c]));
        }
        solution.largest = v[..3].iter().fold(solution.largest, |m, x| m.max(x.abs()));
        let point = claimed_point(v, codes).map_err(|e| format!("line {line_no}: {e}"))?;
        if solution.points.len() == MAX_POINTS {
            return Err(format!(
                "more than {MAX_POINTS} points: too many to be a reasonable image (line {line_no})"
            ));
        }
        solution.points.push(point);
        solution.lines.push(line_no);
    }
    if solution.points.is_empty() {
        return Err(
            "no points: expected lines of x y z color (numbers in metres, colour codes 1 to 5)"
                .into(),
        );
    }
    Ok(solution)
}

/// The point `x y z color` of a solution, or the rule it breaks: coordinates finite, the colour
/// a whole number from 1 to `codes`.
fn claimed_point(v: [f64; 4], codes: usize) -> Result<ClaimedPoint, String> {
    for (name, x) in ["x", "y", "z", "color"].iter().zip(v) {
        if !x.is_finite() {
            return Err(format!(
                "{name} = {} is not a finite number",
                number_text(x)
            ));
        }
    }
    let c = v[3];
    if c.fract() != 0.0 || !(1.0..=codes as f64).contains(&c) {
        return Err(if codes == SECTION_COUNT {
            format!(
                "colour {} is not a colour code: expected a whole number from 1 (red) to 5 (blue)",
                number_text(c)
            )
        } else {
            format!(
                "colour {} is not a colour code: expected a whole number from 1 to {codes} \
                 (1 red … 5 blue a straw's sections, 6 a coin, 7 a card, 8 the arrow on it)",
                number_text(c)
            )
        });
    }
    Ok(ClaimedPoint {
        position: Vec3::new(v[0], v[1], v[2]),
        color: c as u8,
    })
}

/// A solution given as numbers rather than a file (a program's own points): point `k` is
/// `xyz[k]` with colour `colors[k]`, and its "line" is `k + 1`; refused as a file's points are,
/// each message naming the point by its index `k`.
pub fn solution_of_points(
    xyz: &[[f64; 3]],
    colors: &[f64],
    codes: usize,
) -> Result<Solution, String> {
    if xyz.len() != colors.len() {
        return Err(format!(
            "{} points but {} colours: give one colour code per point",
            xyz.len(),
            colors.len()
        ));
    }
    if xyz.is_empty() {
        return Err("no points: give at least one point x y z with its colour code".into());
    }
    if xyz.len() > MAX_POINTS {
        return Err(format!(
            "{} points: more than {MAX_POINTS}, too many to be a reasonable image",
            xyz.len()
        ));
    }
    let mut solution = Solution {
        // Binary numbers carry every digit: no rounding to warn about.
        digits: 17,
        ..Solution::default()
    };
    for (k, (p, &c)) in xyz.iter().zip(colors).enumerate() {
        let point =
            claimed_point([p[0], p[1], p[2], c], codes).map_err(|e| format!("point {k}: {e}"))?;
        solution.largest = p.iter().fold(solution.largest, |m, x| m.max(x.abs()));
        solution.points.push(point);
        solution.lines.push(k + 1);
    }
    Ok(solution)
}

/// The fields of a data or header line: split at commas, at semicolons, or at runs of spaces and tabs.
fn split_fields(line: &str) -> Result<Vec<&str>, String> {
    // At most one field past the limit is collected: a line of millions of fields costs no more
    // memory than a short one.
    let fields: Vec<&str> = if line.contains(';') {
        line.split(';')
            .map(str::trim)
            .take(MAX_FIELDS + 1)
            .collect()
    } else if line.contains(',') {
        line.split(',')
            .map(str::trim)
            .take(MAX_FIELDS + 1)
            .collect()
    } else {
        line.split_whitespace().take(MAX_FIELDS + 1).collect()
    };
    if fields.len() > MAX_FIELDS {
        return Err(format!(
            "more than {MAX_FIELDS} values: a solution's line holds x y z color (and a few other \
             columns at most): '{}'",
            clip_text(line, QUOTE)
        ));
    }
    if let Some(n) = fields.iter().position(|f| f.is_empty()) {
        return Err(format!(
            "empty value in column {}: '{}'",
            n + 1,
            clip_text(line, QUOTE)
        ));
    }
    Ok(fields)
}

/// A number in C's notation (`1e-3`, `.5`, `-0.`, `+1.5E+2`, `nan`, `inf`), or with a decimal comma
/// (as spreadsheets write beside semicolons), quotes around it allowed.
fn parse_number(field: &str) -> Option<f64> {
    let f = field.trim_matches('"').trim();
    if let Ok(x) = f.parse::<f64>() {
        return Some(x);
    }
    if f.matches(',').count() == 1 && !f.contains('.') {
        return f.replace(',', ".").parse().ok();
    }
    None
}

/// Reads a header: which columns hold x, y, z and the colour, and a note saying how it was read.
fn read_header(fields: &[&str]) -> Result<([usize; 4], String), String> {
    let names: Vec<String> = fields.iter().map(|f| column_name(f)).collect();
    let find = |wanted: &[&str]| names.iter().position(|n| wanted.contains(&n.as_str()));
    let found = [
        find(&["x"]),
        find(&["y"]),
        find(&["z"]),
        find(&COLOUR_NAMES),
    ];
    let quoted = fields
        .iter()
        .map(|f| clip_text(f, 16))
        .collect::<Vec<_>>()
        .join(", ");
    if found.iter().all(Option::is_none) && fields.len() == 4 {
        // Names of no meaning (Var1 … Var4, as MATLAB's writetable writes): the usual order.
        return Ok((
            [0, 1, 2, 3],
            format!("header ({quoted}) names no known column: read as x y z color"),
        ));
    }
    match found {
        [Some(x), Some(y), Some(z), Some(c)] => Ok(([x, y, z, c], format!("header ({quoted})"))),
        _ => {
            let missing: Vec<&str> = ["x", "y", "z", "color"]
                .iter()
                .zip(&found)
                .filter(|(_, f)| f.is_none())
                .map(|(n, _)| *n)
                .collect();
            Err(format!(
                "header ({}) has no column {}: expected x, y, z and color (or colour, face, couleur)",
                clip_text(&quoted, 60),
                missing.join(", ")
            ))
        }
    }
}

/// A header name, lower case, without quotes or a unit: `"X (m)"` → `x`.
fn column_name(field: &str) -> String {
    let f = field.trim_matches('"').trim_matches('\'').trim();
    let cut = f.find([' ', '(', '[']).unwrap_or(f.len());
    let n = f[..cut].to_lowercase();
    n.strip_suffix("_m").map(str::to_string).unwrap_or(n)
}

/// A colour code with its name: `2 (orange)`.
fn colour_words(code: u8) -> String {
    match COLOR_NAMES.get(code as usize - 1) {
        Some(n) => format!("{code} ({n})"),
        None => code.to_string(),
    }
}

/// A length in metres in the unit a person reads best: µm below a millimetre, else mm.
fn length_words(m: f64) -> String {
    if m.abs() < 1e-3 {
        format!("{:.1} µm", 1e6 * m)
    } else {
        format!("{:.2} mm", 1e3 * m)
    }
}

/// One wrong point in words, without its line number.
fn point_words(p: &ClaimedPoint, v: &Verdict, path: &str) -> String {
    let at = format!(
        "({}, {}, {}) colour {}",
        p.position.x, p.position.y, p.position.z, p.color
    );
    match v {
        Verdict::Correct { .. } => format!("{at}: correct"),
        Verdict::WrongColour { actual } => format!(
            "{at}: wrong colour, the ray meets {}, seen {path}",
            colour_words(*actual)
        ),
        Verdict::WrongLength { length_error } => format!(
            "{at}: wrong length, {} too {}, seen {path}",
            length_words(length_error.abs()),
            if *length_error > 0.0 { "far" } else { "near" }
        ),
        Verdict::NoStraw => format!("{at}: no straw in that direction (the ray escapes)"),
        Verdict::TooManyEvents { events, actual } => format!(
            "{at}: the ray meets {} only after {events} events, seen {path}",
            colour_words(*actual)
        ),
    }
}

/// A missing region in words a student understands.
pub fn region_words(m: &MissingRegion) -> String {
    let name = COLOR_NAMES[m.color as usize - 1];
    let (z0, z1) = m.straw_z;
    format!(
        "{name} ({}): {:.1} % of its image, {:.0} mm of straw {} (z = {:.0}–{:.0} mm), seen {}",
        m.color,
        100.0 * m.share_of_colour,
        1e3 * (z1 - z0),
        m.place.words(),
        1e3 * z0,
        1e3 * z1,
        m.path
    )
}

/// The library's hints, and one about the file's precision when points have wrong lengths and the
/// file was written with too few digits for the tolerance.
fn all_hints(solution: &Solution, r: &CheckReport) -> Vec<String> {
    let mut hints: Vec<String> = r.hints.iter().map(|h| h.to_string()).collect();
    if r.tally.wrong_length > 0 && solution.digits < SAFE_DIGITS {
        hints.push(format!(
            "the file's coordinates have at most {} significant digits: rounding alone moves a point \
             by up to {} m; save with more digits (writematrix, or dlmwrite with 'precision', '%.15g') \
             or widen --tolerance",
            solution.digits,
            number_text(rounding_error(solution.digits, solution.largest))
        ));
    }
    hints
}

/// The one-screen summary of the judgement of `solution` (read from `file`) of `checked`'s
/// image from its observer.
pub fn summary(
    file: &str,
    checked: &Setup,
    solution: &Solution,
    r: &CheckReport,
    options: &CheckOptions,
    seconds: f64,
) -> String {
    let mut t = String::new();
    let t_ = &r.tally;
    let _ = writeln!(t, "bentstraw check: {file}");
    let _ = writeln!(t, "  scene           {}", checked.inputs_line(true));
    let names = checked.colour_names();
    if let Some(h) = &solution.header {
        let _ = writeln!(t, "  read            {h}");
    }
    let wrong = t_.points - t_.correct;
    let incomplete: Vec<String> = (0..names.len())
        .filter(|&k| r.coverage.per_colour[k].share() < options.min_coverage)
        .map(|k| names[k].to_string())
        .collect();
    let _ = writeln!(
        t,
        "  verdict         {}: {}; {}",
        if r.passes() { "PASS" } else { "FAIL" },
        if wrong == 0 {
            "every point correct".to_string()
        } else {
            format!("{wrong} point(s) wrong")
        },
        if r.complete {
            format!(
                "coverage complete (every colour >= {} %)",
                100.0 * options.min_coverage
            )
        } else {
            format!(
                "incomplete: {} below {} %",
                incomplete.join(", "),
                100.0 * options.min_coverage
            )
        }
    );
    let _ = writeln!(
        t,
        "  points          {} ({:.2} % correct, path lengths to within {} m)",
        t_.points,
        100.0 * t_.share_correct(),
        number_text(options.tolerance)
    );
    let max_len = r
        .judged
        .iter()
        .filter_map(|j| match j.verdict {
            Verdict::WrongLength { length_error } => Some(length_error.abs()),
            _ => None,
        })
        .fold(0.0, f64::max);
    for kind in VerdictKind::ALL {
        let n = t_.count(kind);
        let extra = if kind == VerdictKind::WrongLength && n > 0 {
            format!(" (by up to {})", length_words(max_len))
        } else {
            String::new()
        };
        let _ = writeln!(t, "    {:<32} {n:>9}{extra}", kind.words());
    }
    let _ = writeln!(t);
    let _ = writeln!(
        t,
        "  {:<11} {:>8} {:>8} {:>8} {:>8} {:>8} {:>8}  {:>8}",
        "colour", "points", "correct", "colour?", "length?", "no straw", "events?", "coverage"
    );
    for (k, name) in names.iter().enumerate() {
        let c = &r.per_colour[k];
        let cov = &r.coverage.per_colour[k];
        // A scene file's colours neither claimed nor seen are left out (a card has no red).
        if !checked.lists_unseen_colours() && c.points == 0 && cov.true_samples == 0 {
            continue;
        }
        let cov_text = if cov.true_samples == 0 {
            "not seen".to_string()
        } else {
            format!("{:.1} %", 100.0 * cov.share())
        };
        let _ = writeln!(
            t,
            "  {:<11} {:>8} {:>8} {:>8} {:>8} {:>8} {:>8}  {:>8}",
            format!("{} {name}", k + 1),
            c.points,
            c.correct,
            c.wrong_colour,
            c.wrong_length,
            c.no_straw,
            c.too_many_events,
            cov_text
        );
    }
    for h in all_hints(solution, r) {
        let _ = writeln!(t);
        let _ = writeln!(t, "  hint            {h}");
    }
    let worst = worst_points(&r.judged, options.worst);
    if !worst.is_empty() {
        let _ = writeln!(t);
        let _ = writeln!(t, "  worst points");
        for i in worst {
            let j = &r.judged[i];
            let _ = writeln!(
                t,
                "    line {}: {}",
                solution.lines[i],
                point_words(&solution.points[i], &j.verdict, &j.path.to_string())
            );
        }
    }
    if !r.coverage.missing.is_empty() {
        let _ = writeln!(t);
        let _ = writeln!(
            t,
            "  missing from the image (compared with the true image seen from the same eye)"
        );
        for m in r.coverage.missing.iter().take(12) {
            let _ = writeln!(t, "    {}", region_words(m));
        }
        if r.coverage.missing.len() > 12 {
            let _ = writeln!(
                t,
                "    … and {} smaller regions",
                r.coverage.missing.len() - 12
            );
        }
    }
    let _ = writeln!(t);
    let _ = writeln!(
        t,
        "  how           each point's ray from the eye towards it is traced; coverage: {} samples of the true \
         image, each reached when a point of its colour that really meets that colour lies within {} of \
         the solution's point spacings ({:.2} mrad)",
        r.truth.points.len(),
        REACH_CELLS,
        1e3 * r.coverage.reach
    );
    let _ = writeln!(t, "  time          {seconds:.3} s");
    t
}

/// The judgement as one JSON object (`check --json`): the verdict, the counts per kind and
/// colour, the coverage, the missing regions, the worst points and hints.
pub fn json_report(
    file: &str,
    checked: &Setup,
    solution: &Solution,
    r: &CheckReport,
    options: &CheckOptions,
    seconds: f64,
) -> Value {
    let o = checked.observer;
    let t = &r.tally;
    let mut coverage = serde_json::Map::new();
    let mut per_colour = Vec::new();
    for (k, name) in checked.colour_names().iter().enumerate() {
        let cov = &r.coverage.per_colour[k];
        coverage.insert((k + 1).to_string(), json!(cov.share()));
        let c = &r.per_colour[k];
        per_colour.push(json!({
            "color": k + 1,
            "name": name,
            "points": c.points,
            "correct": c.correct,
            "wrong_colour": c.wrong_colour,
            "wrong_length": c.wrong_length,
            "no_straw": c.no_straw,
            "too_many_events": c.too_many_events,
            "coverage": cov.share(),
            "seen": cov.true_samples > 0,
            "solid_angle_sr": cov.solid_angle,
        }));
    }
    let missing: Vec<Value> = r
        .coverage
        .missing
        .iter()
        .map(|m| {
            json!({
                "color": m.color,
                "path": m.path.key(),
                "share_of_colour": m.share_of_colour,
                "solid_angle_sr": m.solid_angle,
                "straw_z_m": [m.straw_z.0, m.straw_z.1],
                "place": format!("{:?}", m.place).to_lowercase(),
                "words": region_words(m),
            })
        })
        .collect();
    let worst: Vec<Value> = worst_points(&r.judged, options.worst)
        .into_iter()
        .map(|i| {
            let j = &r.judged[i];
            let p = &solution.points[i];
            let mut v = json!({
                "line": solution.lines[i],
                "kind": j.verdict.kind().key(),
                "position": [p.position.x, p.position.y, p.position.z],
                "color": p.color,
                "path": j.path.key(),
            });
            match j.verdict {
                Verdict::WrongColour { actual } => v["actual_color"] = json!(actual),
                Verdict::WrongLength { length_error } => v["length_error_m"] = json!(length_error),
                Verdict::TooManyEvents { events, actual } => {
                    v["events"] = json!(events);
                    v["actual_color"] = json!(actual);
                }
                _ => {}
            }
            v
        })
        .collect();
    let mut v = json!({
        "file": file,
        "observer": [o.x, o.y, o.z],
        "tolerance": options.tolerance,
        "min_coverage": options.min_coverage,
        "points": t.points,
        "correct": t.correct,
        "wrong_colour": t.wrong_colour,
        "wrong_length": t.wrong_length,
        "no_straw": t.no_straw,
        "too_many_events": t.too_many_events,
        "share_correct": t.share_correct(),
        "coverage": coverage,
        "complete": r.complete,
        "verdict": if r.passes() { "pass" } else { "fail" },
        "per_colour": per_colour,
        "missing": missing,
        "worst": worst,
        "hints": all_hints(solution, r),
        "digits": solution.digits,
        "true_samples": r.truth.points.len(),
        "seconds": seconds,
    });
    // The scene's inputs under their documented names (its whole text is the scene file's).
    for input in checked.inputs() {
        if !matches!(input.value, InputValue::Text(_)) {
            v[input.key] = crate::writers::input_json(&input.value);
        }
    }
    v
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(s: &str) -> Result<Solution, String> {
        parse_solution(s.as_bytes())
    }

    #[test]
    fn a_line_of_too_many_values_is_refused_before_they_are_collected() {
        // A header of five million names: refused, quoting its start only.
        let wide = vec!["x"; 5_000_000].join(",");
        let e = parse(&wide).unwrap_err();
        assert!(e.starts_with("line 1: more than 64 values"), "{e}");
        assert!(e.len() < 300, "{} bytes", e.len());
        let row = vec!["0.5"; 65].join(" ");
        assert!(parse(&format!("0 0 0 1\n{row}\n"))
            .unwrap_err()
            .starts_with("line 2: more than 64 values"));
        // Sixty-four are read (a header naming its columns).
        let mut names: Vec<String> = (4..64).map(|k| format!("extra{k}")).collect();
        names.splice(0..0, ["x", "y", "z", "color"].map(String::from));
        let mut line: Vec<&str> = vec!["0.5", "0.5", "0.5", "1"];
        line.extend(vec!["7"; 60]);
        let ok = format!("{}\n{}\n", names.join(","), line.join(","));
        assert_eq!(parse(&ok).unwrap().points.len(), 1);
    }

    #[test]
    fn every_separator_and_float_notation_reads_the_same() {
        let want = vec![
            ClaimedPoint {
                position: Vec3::new(0.001, 0.5, -0.0),
                color: 3,
            },
            ClaimedPoint {
                position: Vec3::new(150.0, -2.5, 1e-7),
                color: 1,
            },
        ];
        for text in [
            "1e-3,.5,-0.,3\n+1.5E+2,-2.5,1e-7,1\n",
            "x,y,z,color\r\n1e-3,.5,-0.,3\r\n+1.5E+2,-2.5,1e-7,1\r\n",
            "1e-3 .5 -0. 3\n  +1.5E+2   -2.5 1e-7  1",
            "1e-3\t.5\t-0.\t3\n+1.5E+2\t-2.5\t1e-7\t1\n",
            "1e-3;.5;-0.;3\n+1.5E+2;-2.5;1e-7;1\n",
            "x;y;z;couleur\n0,001;0,5;-0.;3\n+1.5E+2;-2,5;1e-7;1\n",
            "# Created by Octave\n% a comment\n 1.00000000e-03 5.0e-01 -0 3.00000000e+00\n\n1.5e2 -2.5 1e-7 1\n",
            "color,z,x,y\n3,-0.,1e-3,.5\n1,1e-7,150,-2.5\n",
            "\"Face\",\"X (m)\",\"y\",\"Z\"\n3,0.001,0.5,-0\n1,150,-2.5,1e-7\n",
            "Var1,Var2,Var3,Var4\n0.001,0.5,0,3\n150,-2.5,1e-7,1\n",
        ] {
            let s = parse(text).unwrap_or_else(|e| panic!("{text:?}: {e}"));
            assert_eq!(s.points, want, "{text:?}");
        }
        let s = parse("# c\nx y z color\n1 2 3 4\n").unwrap();
        assert_eq!(s.lines, vec![3]);
    }

    #[test]
    fn digits_written_are_counted() {
        assert_eq!(significant_digits("0.0012300"), 5);
        assert_eq!(significant_digits("-1.5e2"), 2);
        assert_eq!(significant_digits("1.00000000e-03"), 9);
        assert_eq!(significant_digits("0.1"), 1);
        assert_eq!(significant_digits("0"), 0);
        let s = parse("0.12346 -0.0012 1e-3 1\n0.1 0.2 0.3 2\n").unwrap();
        assert_eq!((s.digits, s.largest), (5, 0.3));
        // Five digits at 0.1 m: up to 5e-6 m.
        assert!((rounding_error(5, 0.3) - 5e-6).abs() < 1e-18);
    }

    #[test]
    fn malformed_lines_are_refused_with_their_number() {
        for (text, want) in [
            ("1,2,3,1\n1,2,1\n", "line 2: 3 value(s), expected 4"),
            (
                "1,2,3,1\n1,2,abc,1\n",
                "line 2: 'abc' is not a number (column 3)",
            ),
            ("1,2,3,1\n\n1,,3,1\n", "line 3: empty value in column 2"),
            ("1,2,3,6\n", "line 1: colour 6 is not a colour code"),
            ("1,2,3,2.5\n", "line 1: colour 2.5 is not a colour code"),
            ("1,2,3,0\n", "line 1: colour 0 is not a colour code"),
            (
                "NaN NaN NaN NaN\n",
                "line 1: x = NaN is not a finite number",
            ),
            ("1 2 inf 1\n", "line 1: z = inf is not a finite number"),
            (
                "a,b,d\n",
                "line 1: header (a, b, d) has no column x, y, z, color",
            ),
            (
                "x,y,z\n1,2,3\n",
                "line 1: header (x, y, z) has no column color",
            ),
            ("", "no points"),
            ("# only a comment\n\n", "no points"),
            ("x,y,z,color\n", "no points"),
        ] {
            let e = parse(text).unwrap_err();
            assert!(e.starts_with(want), "{text:?}: {e}");
        }
        let e = parse_solution(b"1,2,3,1\n\xff\xfe,1\n").unwrap_err();
        assert!(e.starts_with("line 2: not text"), "{e}");
    }
}
