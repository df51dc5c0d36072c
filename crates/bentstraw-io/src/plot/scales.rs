//! A panel's frame and scales: round tick steps, the pale pane with grid lines at the ticks,
//! and along its edges the tick labels and each axis's name with an arrow the way it increases.

use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use plotters::style::FontTransform;

use super::axis_box::AxisBox;
use super::figure::{AreaOn, DrawResultOn};
use super::panel::{Panel, CAPTION_LINE};
use super::text::{font, text_width, CAPTION, TEXT};
use super::views::world_axis;

/// A step between axis ticks giving about `count` ticks over `span`: 1, 2 or 5 times a power of ten.
pub(crate) fn tick_step(span: f64, count: f64) -> f64 {
    let raw = (span / count).max(1e-12);
    let power = 10f64.powf(raw.log10().floor());
    let m = raw / power;
    let nice = if m < 1.5 {
        1.0
    } else if m < 3.5 {
        2.0
    } else if m < 7.5 {
        5.0
    } else {
        10.0
    };
    nice * power
}

/// The tick values within `[lo, hi]` for `step`.
pub(crate) fn ticks(lo: f64, hi: f64, step: f64) -> Vec<f64> {
    let first = (lo / step).ceil() as i64;
    let last = (hi / step).floor() as i64;
    (first..=last).map(|k| k as f64 * step).collect()
}

/// A tick label with as many decimals as the step needs.
pub(crate) fn tick_label(value: f64, step: f64) -> String {
    let decimals = (-step.log10().floor()).max(0.0) as usize;
    let s = format!("{:.*}", decimals, value);
    // "-0.00" reads as a different number from "0.00".
    if s.starts_with('-') && s[1..].chars().all(|c| c == '0' || c == '.') {
        s[1..].to_string()
    } else {
        s
    }
}

/// The step between ticks of world axis `a` in `panel`: a round number, at least `room` px apart.
fn panel_step(panel: &Panel, a: usize) -> f64 {
    let (h, _) = world_axis(panel.proj.right);
    let (lo, hi) = panel.frame_range(a);
    let mut step = tick_step(hi - lo, 5.0);
    for _ in 0..20 {
        let room = if a == h {
            // Across: the widest label and a gap.
            ticks(lo, hi, step)
                .iter()
                .map(|&v| text_width(&tick_label(v, step), TEXT))
                .max()
                .unwrap_or(0) as f64
                + 24.0
        } else {
            1.6 * TEXT
        };
        if step * panel.proj.scale >= room {
            break;
        }
        step = next_step(step);
    }
    step
}

/// The next round step after `step`: 1, 2, 5, 10, 20 …
fn next_step(step: f64) -> f64 {
    let power = 10f64.powf(step.log10().floor());
    let m = (step / power).round();
    if m < 2.0 {
        2.0 * power
    } else if m < 5.0 {
        5.0 * power
    } else {
        10.0 * power
    }
}

/// Where value `v` of world axis `a` lands along the screen direction it runs in: a column for an
/// axis running across, a row for one running up (px).
fn tick_pixel(panel: &Panel, a: usize, v: f64) -> f64 {
    let mut p = panel.proj.centre;
    p[a] = v;
    let (x, y) = panel.proj.pixel(p);
    if world_axis(panel.proj.right).0 == a {
        x
    } else {
        y
    }
}

/// The name of world axis `a` with an arrow the way its values increase along the reading
/// direction (`increasing`: to the right, or up for a vertical name written bottom to top).
pub(crate) fn axis_name(a: usize, increasing: bool) -> String {
    let name = ["x", "y", "z"][a];
    if increasing {
        format!("{name} (m) →")
    } else {
        format!("← {name} (m)")
    }
}

/// The panel's caption, and the pane of the box's far face, with grid lines at the scales' ticks.
pub(crate) fn draw_panes<DB: DrawingBackend>(
    root: &AreaOn<DB>,
    panel: &Panel,
    bx: &AxisBox,
) -> DrawResultOn<DB> {
    for (k, line) in panel.caption.iter().enumerate() {
        root.draw(&Text::new(
            line.clone(),
            (
                panel.left + panel.width / 2,
                panel.top + 6 + k as i32 * CAPTION_LINE,
            ),
            font(CAPTION).pos(Pos::new(HPos::Center, VPos::Top)),
        ))?;
    }
    // The frame: a pale pane with grid lines at the scales' ticks.
    let [l, r, t, b] = panel.frame;
    let px = |v: f64| v.round() as i32;
    root.draw(&Rectangle::new(
        [(px(l), px(t)), (px(r), px(b))],
        RGBColor(244, 244, 246).filled(),
    ))?;
    let grid = RGBColor(218, 218, 224);
    for (a, across) in [
        (world_axis(panel.proj.right).0, true),
        (world_axis(panel.proj.up).0, false),
    ] {
        let (lo, hi) = panel.frame_range(a);
        for v in ticks(lo, hi, panel_step(panel, a)) {
            let at = tick_pixel(panel, a, v);
            let seg = if across {
                vec![(px(at), px(t)), (px(at), px(b))]
            } else {
                vec![(px(l), px(at)), (px(r), px(at))]
            };
            root.draw(&PathElement::new(seg, grid))?;
        }
    }
    // The box's edges seen from here: where glass, straw and points lie.
    let mut outline: Vec<(i32, i32)> = {
        let (mut x0, mut x1, mut y0, mut y1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
        for k in bx.corners() {
            let (x, y) = panel.proj.pixel(k);
            x0 = x0.min(x);
            x1 = x1.max(x);
            y0 = y0.min(y);
            y1 = y1.max(y);
        }
        vec![
            (px(x0), px(y0)),
            (px(x1), px(y0)),
            (px(x1), px(y1)),
            (px(x0), px(y1)),
        ]
    };
    outline.push(outline[0]);
    root.draw(&PathElement::new(outline, RGBColor(200, 200, 208)))?;
    root.draw(&Rectangle::new(
        [(px(l), px(t)), (px(r), px(b))],
        RGBColor(170, 170, 178),
    ))?;
    Ok(())
}

/// The panel's two scales: the world axis running across the screen along the bottom of the frame,
/// the one running up the screen along its left side, each with ticks, labels and its name with an
/// arrow the way it increases. A view looks along a world axis, so each is one axis of the scene.
pub(crate) fn draw_axis_labels<DB: DrawingBackend>(
    root: &AreaOn<DB>,
    panel: &Panel,
    _bx: &AxisBox,
) -> DrawResultOn<DB> {
    let [x0, x1, y0, y1] = panel.frame;
    let tick_color = RGBColor(70, 70, 76);
    let r = |v: f64| v.round() as i32;
    // Across, along the bottom edge.
    let (h, h_up) = world_axis(panel.proj.right);
    let step = panel_step(panel, h);
    let (lo, hi) = panel.frame_range(h);
    for v in ticks(lo, hi, step) {
        let x = tick_pixel(panel, h, v);
        root.draw(&PathElement::new(
            vec![(r(x), r(y1)), (r(x), r(y1) + 7)],
            tick_color,
        ))?;
        root.draw(&Text::new(
            tick_label(v, step),
            (r(x), r(y1) + 10),
            font(TEXT)
                .color(&tick_color)
                .pos(Pos::new(HPos::Center, VPos::Top)),
        ))?;
    }
    root.draw(&Text::new(
        axis_name(h, h_up),
        (r(0.5 * (x0 + x1)), r(y1) + 12 + (1.3 * TEXT) as i32),
        font(CAPTION).pos(Pos::new(HPos::Center, VPos::Top)),
    ))?;
    // Up, along the left edge.
    let (v_axis, v_up) = world_axis(panel.proj.up);
    let step = panel_step(panel, v_axis);
    let (lo, hi) = panel.frame_range(v_axis);
    let mut widest = 0;
    for v in ticks(lo, hi, step) {
        let y = tick_pixel(panel, v_axis, v);
        let text = tick_label(v, step);
        widest = widest.max(text_width(&text, TEXT));
        root.draw(&PathElement::new(
            vec![(r(x0) - 7, r(y)), (r(x0), r(y))],
            tick_color,
        ))?;
        root.draw(&Text::new(
            text,
            (r(x0) - 10, r(y)),
            font(TEXT)
                .color(&tick_color)
                .pos(Pos::new(HPos::Right, VPos::Center)),
        ))?;
    }
    // Written bottom to top, so that its arrow points up when the axis increases upwards.
    root.draw(&Text::new(
        axis_name(v_axis, v_up),
        (
            r(x0) - 18 - widest - (1.25 * CAPTION) as i32,
            r(0.5 * (y0 + y1)),
        ),
        font(CAPTION)
            .transform(FontTransform::Rotate270)
            .pos(Pos::new(HPos::Center, VPos::Top)),
    ))?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ticks_are_round_numbers_and_labels_have_no_negative_zero() {
        assert!((tick_step(0.25, 5.0) - 0.05).abs() < 1e-15);
        assert!((tick_step(0.09, 5.0) - 0.02).abs() < 1e-15);
        assert!((tick_step(3.0, 5.0) - 0.5).abs() < 1e-15);
        let t = ticks(-0.041, 0.26, 0.05);
        assert_eq!(t.len(), 6);
        assert_eq!(tick_label(t[0], 0.05), "0.00");
        assert_eq!(tick_label(-1e-17, 0.05), "0.00");
        assert_eq!(tick_label(-0.05, 0.05), "-0.05");
        assert_eq!(tick_label(0.1, 0.1), "0.1");
    }
}
