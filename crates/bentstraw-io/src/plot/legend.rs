//! Legends: the mark before each entry, the words for the straw's sections and the entries
//! every figure of the scene has, and a column of entries wrapped to its cell.

use bentstraw_optics::image::ImagePoint;
use bentstraw_optics::scene::{SECTION_HEIGHT, SECTION_NAMES};
use bentstraw_optics::setup::Setup;
use bentstraw_optics::spectrum::{wavelength_rgb8, white_bands, WHITE_BANDS};
use bentstraw_optics::world::COLOR_COUNT;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use super::colours::{rgb, section_rgb8, STRAW_OUTLINE_RGB, WATER_RGB};
use super::figure::{AreaOn, DrawResultOn};
use super::panel::CAPTION_LINE;
use super::text::{font, wrap, TEXT};
use super::wireframe::dashed;

/// One line of a legend of image points: what a colour of points stands for.
pub(crate) struct LegendEntry {
    /// The key the points of this colour carry ([`legend_key`]).
    pub(crate) code: u8,
    /// Its short name (the colour's, or the band's wavelength).
    pub(crate) label: String,
    /// Its name in a legend: the colour code and name, or the band's wavelength.
    pub(crate) name: String,
    /// The heights of the straw a section spans (`, z 0.00–0.05 m`), or nothing.
    pub(crate) span: String,
    /// Its colour.
    pub(crate) rgb: [u8; 3],
    /// The points of this colour.
    pub(crate) count: usize,
}

/// Legend keys, 0 unused: colour codes 1..=8, or white light's bands 1..=8.
const LEGEND_KEYS: usize = 1 + if COLOR_COUNT > WHITE_BANDS {
    COLOR_COUNT
} else {
    WHITE_BANDS
};
// The 3D view's script keeps a colour per key, 0..=8.
const _: () = assert!(LEGEND_KEYS <= 9);

/// The key a point is coloured by: its colour code in light of one wavelength, its band (from 1,
/// violet) in white light, where each point is seen in its wavelength's colour.
pub(crate) fn legend_key(p: &ImagePoint) -> u8 {
    p.band.map_or(p.color, |k| k + 1)
}

/// The legend's lines: every colour code the scene lists (every section of the straw; a scene
/// file's where seen), or in white light every band of the spectrum seen.
pub(crate) fn legend_entries(scene: &Setup, points: &[ImagePoint]) -> Vec<LegendEntry> {
    let mut n = [0usize; LEGEND_KEYS];
    for p in points {
        n[legend_key(p) as usize] += 1;
    }
    if points.iter().any(|p| p.band.is_some()) {
        return white_bands()
            .iter()
            .enumerate()
            .filter(|&(k, _)| n[k + 1] > 0)
            .map(|(k, band)| LegendEntry {
                code: k as u8 + 1,
                label: format!("{} nm", band.nm),
                name: format!("{} nm", band.nm),
                span: String::new(),
                rgb: wavelength_rgb8(band.nm),
                count: n[k + 1],
            })
            .collect();
    }
    (1..=scene.colour_names().len() as u8)
        .filter(|&c| n[c as usize] > 0 || scene.lists_unseen_colours())
        .map(|c| {
            let name = scene.colour_names()[c as usize - 1];
            // A section of the straw says which heights it spans.
            let span = scene
                .code_heights(c)
                .map_or(String::new(), |(lo, hi)| format!(", z {lo:.2}–{hi:.2} m"));
            LegendEntry {
                code: c,
                label: name.to_string(),
                name: format!("{c} {name}"),
                span,
                rgb: section_rgb8(c),
                count: n[c as usize],
            }
        })
        .collect()
}

/// Counts of points per section code 1..=5.
#[cfg(test)]
pub(crate) fn counts(
    points: &[bentstraw_optics::image::ImagePoint],
) -> [usize; bentstraw_optics::scene::SECTION_COUNT] {
    use bentstraw_optics::scene::SECTION_COUNT;
    let mut n = [0; SECTION_COUNT];
    for p in points {
        if (1..=SECTION_COUNT as u8).contains(&p.color) {
            n[(p.color - 1) as usize] += 1;
        }
    }
    n
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
pub(crate) fn common_legend(scene: &Setup, observer_inside: bool) -> Vec<(LegendMark, String)> {
    let words = scene.sketch_words();
    vec![
        (
            LegendMark::Dot,
            if observer_inside {
                "observer".to_string()
            } else {
                "observer (far: arrow)".to_string()
            },
        ),
        (LegendMark::Line(WATER_RGB), words.wireframe.to_string()),
        (
            LegendMark::Dashed(STRAW_OUTLINE_RGB),
            words.outlines.to_string(),
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
