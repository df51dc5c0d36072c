//! The panels of a figure: cells in a grid, each with a caption, a frame the axis box is fitted
//! in, room for the scales around it, and the projection that fits it.

use super::axis_box::AxisBox;
use super::figure::FIGURE_WIDTH;
use super::projection::{fit_scale, Projection};
use super::views::{world_axis, ViewDirection};

/// One panel: where it is and how it projects.
pub(crate) struct Panel {
    /// How the panel projects the scene.
    pub proj: Projection,
    /// The caption above the panel, one entry a line.
    pub caption: Vec<String>,
    /// Left edge (px).
    pub left: i32,
    /// Top edge (px).
    pub top: i32,
    /// Width (px).
    pub width: i32,
    /// Height (px).
    pub height: i32,
    /// The frame the box is fitted in, where the scales run: left, right, top, bottom (px).
    pub frame: [f64; 4],
}

impl Panel {
    /// The values of world axis `a` at the two ends of the frame along the screen direction it
    /// runs in (left to right, or bottom to top), in increasing order.
    pub(super) fn frame_range(&self, a: usize) -> (f64, f64) {
        let p = &self.proj;
        let [l, r, t, b] = self.frame;
        let (h, _) = world_axis(p.right);
        let (ends, along) = if a == h {
            ([(l, p.origin.1), (r, p.origin.1)], p.right)
        } else {
            ([(p.origin.0, b), (p.origin.0, t)], p.up)
        };
        let value = |(x, y): (f64, f64)| {
            let d = (x - p.origin.0) * p.right - (y - p.origin.1) * p.up;
            p.centre[a] + d.dot(along) / p.scale * along[a].signum()
        };
        let (u, v) = (value(ends[0]), value(ends[1]));
        (u.min(v), u.max(v))
    }
}

/// Height of one caption line over a panel (px).
pub(crate) const CAPTION_LINE: i32 = 40;

/// Room kept left of each panel's box for the vertical scale: tick labels and the axis's name.
pub(crate) const PAD_LEFT: f64 = 150.0;
/// Room kept right of each panel's box (the horizontal scale's last label sticks out).
pub(crate) const PAD_RIGHT: f64 = 40.0;
/// Room kept below each panel's box for the horizontal scale (labels never go on top).
pub(crate) const PAD_BOTTOM: f64 = 100.0;
/// Room kept above each panel's box, under the caption.
pub(crate) const PAD_TOP: f64 = 16.0;

/// Panels in a grid of `columns` cells of `cell_height`, row by row from `top`, each fitting the
/// whole box under a caption of `caption_lines` lines. Panels of the same view get the same scale.
pub(crate) fn grid(
    bx: &AxisBox,
    views: &[(ViewDirection, Vec<String>)],
    top: i32,
    columns: usize,
    cell_height: i32,
    caption_lines: usize,
) -> Vec<Panel> {
    let cell_w = FIGURE_WIDTH as i32 / columns as i32;
    let caption_band = caption_lines as i32 * CAPTION_LINE;
    let fit_w = cell_w as f64 - PAD_LEFT - PAD_RIGHT;
    let fit_h = (cell_height - caption_band) as f64 - PAD_TOP - PAD_BOTTOM;
    views
        .iter()
        .enumerate()
        .map(|(i, (v, caption))| {
            let left = (i % columns) as i32 * cell_w;
            let top = top + (i / columns) as i32 * cell_height;
            let origin = (
                left as f64 + PAD_LEFT + fit_w / 2.0,
                (top + caption_band) as f64 + PAD_TOP + fit_h / 2.0,
            );
            Panel {
                // Each panel has its own scale (a top view fits far more than a side view), but within
                // a panel one metre has the same length along both axes.
                proj: Projection::new(*v, bx.centre(), origin, fit_scale(bx, *v, fit_w, fit_h)),
                caption: caption.clone(),
                left,
                top,
                width: cell_w,
                height: cell_height,
                frame: [
                    left as f64 + PAD_LEFT,
                    left as f64 + PAD_LEFT + fit_w,
                    (top + caption_band) as f64 + PAD_TOP,
                    (top + caption_band) as f64 + PAD_TOP + fit_h,
                ],
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::plot::axis_box::axis_box;
    use crate::plot::tests::panels_of;
    use bentstraw_optics::scene::{Scene, REFERENCES};
    use bentstraw_optics::setup::Setup;
    use bentstraw_optics::Vec3;

    #[test]
    fn every_panel_holds_its_whole_box_with_room_for_labels() {
        let far = Vec3::new(3.0, -1.0, 0.4);
        for (scene, observer) in REFERENCES
            .iter()
            .map(|r| (Setup::assignment(r.scene(1.333), r.observer), r.observer))
            .chain([(
                Setup::assignment(Scene::with_defaults(0.0, 0.0, 0.1).unwrap(), far),
                far,
            )])
        {
            let bx = axis_box(&scene, observer, &[]);
            let panels = panels_of(&scene, observer, &[]);
            assert_eq!(panels.len(), 3);
            for p in &panels {
                for k in bx.corners() {
                    let (x, y) = p.proj.pixel(k);
                    let (l, r) = (
                        p.left as f64 + PAD_LEFT,
                        (p.left + p.width) as f64 - PAD_RIGHT,
                    );
                    let (t, b) = (
                        (p.top + 2 * CAPTION_LINE) as f64 + PAD_TOP - 1e-6,
                        (p.top + p.height) as f64 - PAD_BOTTOM + 1e-6,
                    );
                    assert!(x >= l - 1e-6 && x <= r + 1e-6, "x {x} outside {l}..{r}");
                    assert!(y >= t && y <= b, "y {y} outside {t}..{b}");
                }
            }
        }
    }
}
