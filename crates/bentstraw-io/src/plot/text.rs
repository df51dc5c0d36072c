//! Text in figures: the shipped font, the sizes chosen to be legible printed 8.5 cm wide, and
//! text measured and wrapped to a width.

use std::sync::Once;

use plotters::prelude::*;

/// The font of every text in the figure, shipped with the program so pictures look the same anywhere.
pub(crate) static FONT: &[u8] = include_bytes!("../../assets/DejaVuSans.ttf");
/// The family name the font is registered under.
const FONT_FAMILY: &str = "sans-serif";
static FONT_ONCE: Once = Once::new();

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

/// The figures' font at `size` px (the em, as SVG's `font-size`), black. The shipped font is
/// registered first: text measured before it (to wrap a caption, to size a figure) would
/// otherwise be measured in another font than the one drawn, and the first figure of a process
/// would be laid out unlike the next.
pub(crate) fn font(size: f64) -> TextStyle<'static> {
    register_font();
    (FONT_FAMILY, size * PLOTTERS_SIZE_PER_EM)
        .into_font()
        .color(&BLACK)
}

/// Width of `s` in pixels at `size`.
pub(crate) fn text_width(s: &str, size: f64) -> i32 {
    font(size)
        .font
        .layout_box(s)
        .map(|((x0, _), (x1, _))| x1 - x0)
        .unwrap_or((s.len() as f64 * size * 0.6) as i32)
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

/// Loads the shipped font into plotters, once.
pub(crate) fn register_font() {
    FONT_ONCE.call_once(|| {
        // The font is compiled in and known good; a failure here is a build defect.
        plotters::style::register_font(FONT_FAMILY, FontStyle::Normal, FONT)
            .unwrap_or_else(|_| panic!("the shipped font {FONT_FAMILY} does not load"));
    });
}

#[cfg(test)]
mod tests {
    use super::*;

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
}
