//! The observer in a panel: a dot (a ring when seen head-on) where it is, or an arrow pointing
//! to it when too far to draw to scale, labelled where the label hides the fewest dots.

use bentstraw_optics::scene::SCENE_CENTRE;
use bentstraw_optics::Vec3;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use super::axis_box::AxisBox;
use super::dots::Dot;
use super::figure::{AreaOn, DrawResultOn};
use super::panel::Panel;
use super::text::{font, text_width, TEXT};

/// A label beside a marker at `(x, y)`, on a pale backing, kept inside the frame: right of it,
/// left, above or below, wherever it hides the fewest of the panel's `dots`.
fn marker_label<DB: DrawingBackend>(
    root: &AreaOn<DB>,
    panel: &Panel,
    (x, y): (i32, i32),
    text: &str,
    dots: &[Dot],
) -> DrawResultOn<DB> {
    let tw = text_width(text, TEXT);
    let fit = |(l, cy): (i32, i32)| {
        (
            // Inside the frame, off the scales' labels (beyond its right edge if need be).
            l.clamp(
                panel.frame[0] as i32 + 4,
                (panel.frame[1] as i32 - tw - 6).max(panel.frame[0] as i32 + 4),
            ),
            cy.clamp(panel.frame[2] as i32 + 18, panel.frame[3] as i32 - 18),
        )
    };
    let candidates = [
        (x + 14, y),
        (x - 18 - tw, y),
        (x - tw / 2, y - 32),
        (x - tw / 2, y + 32),
    ]
    .map(fit);
    let hidden = |(l, cy): (i32, i32)| {
        // Never over the marker itself (a label pushed back into the panel might be).
        let on_marker = l < x + 9 && l + tw + 4 > x - 9 && cy - 18 < y + 9 && cy + 18 > y - 9;
        usize::from(on_marker) * usize::MAX / 2
            + dots
                .iter()
                .filter(|d| {
                    d.x < l + tw + 4
                        && d.x + d.size.0 > l - 2
                        && d.y < cy + 18
                        && d.y + d.size.1 > cy - 18
                })
                .count()
    };
    // The first of the least hiding, so that an empty neighbourhood keeps the label on the right.
    let (l, cy) = candidates
        .iter()
        .copied()
        .min_by_key(|&c| hidden(c))
        .unwrap_or(candidates[0]);
    root.draw(&Rectangle::new(
        [(l - 2, cy - 18), (l + tw + 4, cy + 18)],
        WHITE.mix(0.75).filled(),
    ))?;
    root.draw(&Text::new(
        text.to_string(),
        (l, cy),
        font(TEXT).pos(Pos::new(HPos::Left, VPos::Center)),
    ))
}

/// The observer as a black dot, or, when too far away to draw to scale, an arrow pointing to it;
/// its label placed where it hides the fewest of `dots`.
pub(crate) fn draw_observer<DB: DrawingBackend>(
    root: &AreaOn<DB>,
    panel: &Panel,
    bx: &AxisBox,
    observer: Vec3,
    dots: &[Dot],
) -> DrawResultOn<DB> {
    let proj = &panel.proj;
    if bx.observer_inside {
        let (x, y) = proj.at(observer);
        // Seen from about the observer's side the marker sits on the image: a ring hides less.
        let head_on = proj
            .toward
            .dot((observer - SCENE_CENTRE).normalize_or_zero())
            > 0.5f64.sqrt();
        if head_on {
            root.draw(&Circle::new((x, y), 8, BLACK.stroke_width(3)))?;
        } else {
            root.draw(&Circle::new((x, y), 8, BLACK.filled()))?;
        }
        return marker_label(root, panel, (x, y), "observer", dots);
    }
    let Some((tail, tip)) = bx.observer_arrow else {
        return Ok(());
    };
    let (tx, ty) = proj.pixel(tip);
    let (sx, sy) = proj.pixel(tail);
    let (dx, dy) = (tx - sx, ty - sy);
    let len = dx.hypot(dy);
    if len < 18.0 {
        // Seen end-on, the arrow would be a dot: a ring, and which way the observer is.
        let at = (sx.round() as i32, sy.round() as i32);
        root.draw(&Circle::new(at, 8, BLACK.stroke_width(3)))?;
        let words = if proj.nearness(observer) > 0.0 {
            "observer, far in front"
        } else {
            "observer, far behind"
        };
        return marker_label(root, panel, at, words, dots);
    }
    let (ux, uy) = (dx / len, dy / len);
    root.draw(&PathElement::new(
        vec![(sx as i32, sy as i32), (tx as i32, ty as i32)],
        BLACK.stroke_width(3),
    ))?;
    let (px, py) = (-uy, ux);
    let head = vec![
        (tx as i32, ty as i32),
        (
            (tx - 16.0 * ux + 7.0 * px) as i32,
            (ty - 16.0 * uy + 7.0 * py) as i32,
        ),
        (
            (tx - 16.0 * ux - 7.0 * px) as i32,
            (ty - 16.0 * uy - 7.0 * py) as i32,
        ),
    ];
    root.draw(&Polygon::new(head, BLACK.filled()))?;
    // "observer" beside the arrow's middle: above a level arrow, beside a steep one.
    let (mx, my) = (0.5 * (sx + tx), 0.5 * (sy + ty));
    if ux.abs() >= uy.abs() {
        root.draw(&Text::new(
            "observer",
            (mx as i32, my as i32 - 8),
            font(TEXT).pos(Pos::new(HPos::Center, VPos::Bottom)),
        ))
    } else {
        marker_label(root, panel, (mx as i32, my as i32), "observer", dots)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::plot::axis_box::axis_box;
    use crate::plot::tests::{panels_of, png_of};
    use bentstraw_optics::scene::Scene;
    use bentstraw_optics::setup::Setup;

    #[test]
    fn observer_is_a_black_dot_where_each_view_projects_it() {
        let scene = Setup::assignment(Scene::with_defaults(0.02, 0.01, 0.15).unwrap(), Vec3::ZERO);
        let observer = Vec3::new(-0.07, 0.06, 0.17);
        let img = png_of(&scene, observer, &[]);
        let bx = axis_box(&scene, observer, &[]);
        assert!(bx.observer_inside);
        for p in panels_of(&scene, observer, &[]) {
            let (x, y) = p.proj.pixel(observer);
            let (x, y) = (x.round() as i32, y.round() as i32);
            // A dot, or a ring in a view straight from the observer's direction: either way black
            // pixels all round within 8 px, left and right, above and below.
            let black = |dx: std::ops::RangeInclusive<i32>, dy: std::ops::RangeInclusive<i32>| {
                dx.clone().any(|i| {
                    dy.clone()
                        .any(|j| img.get_pixel((x + i) as u32, (y + j) as u32).0 == [0, 0, 0])
                })
            };
            assert!(
                black(-8..=-3, -1..=1) && black(3..=8, -1..=1),
                "no marker at ({x}, {y})"
            );
            assert!(
                black(-1..=1, -8..=-3) && black(-1..=1, 3..=8),
                "no marker at ({x}, {y})"
            );
        }
    }
}
