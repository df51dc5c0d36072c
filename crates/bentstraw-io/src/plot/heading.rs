//! A figure's heading (title and subtitle, wrapped and centred), and the title naming a
//! simulation's inputs.

use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use super::figure::{AreaOn, DrawResultOn, FIGURE_WIDTH};
use super::text::{font, wrap, TEXT, TITLE};

/// A figure's heading: the title in large type, the subtitle below it, both wrapped to the width.
pub(crate) struct Heading {
    /// The lines with their sizes (px).
    lines: Vec<(String, f64)>,
}

impl Heading {
    /// The heading of `title` and `subtitle` (empty: none).
    pub fn new(title: &str, subtitle: &str) -> Heading {
        let max = FIGURE_WIDTH as i32 - 40;
        let mut lines: Vec<(String, f64)> = wrap(title, TITLE, max)
            .into_iter()
            .map(|l| (l, TITLE))
            .collect();
        lines.extend(wrap(subtitle, TEXT, max).into_iter().map(|l| (l, TEXT)));
        Heading { lines }
    }

    /// Its height (px), margins included.
    pub fn height(&self) -> i32 {
        16 + self
            .lines
            .iter()
            .map(|(_, s)| (1.3 * s).round() as i32)
            .sum::<i32>()
            + 10
    }

    /// Draws it at the top, centred.
    pub fn draw<DB: DrawingBackend>(&self, root: &AreaOn<DB>) -> DrawResultOn<DB> {
        let mut y = 16;
        for (line, size) in &self.lines {
            let color = if *size == TITLE {
                BLACK
            } else {
                RGBColor(60, 60, 60)
            };
            root.draw(&Text::new(
                line.clone(),
                (FIGURE_WIDTH as i32 / 2, y),
                font(*size)
                    .color(&color)
                    .pos(Pos::new(HPos::Center, VPos::Top)),
            ))?;
            y += (1.3 * size).round() as i32;
        }
        Ok(())
    }
}
