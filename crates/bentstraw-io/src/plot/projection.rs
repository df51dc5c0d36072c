//! The orthographic projection of the scene into a panel: one metre has the same length on
//! screen along every axis, and depth says what is drawn over what.

use bentstraw_optics::Vec3;

use super::axis_box::AxisBox;
use super::views::ViewDirection;

/// An orthographic projection of the scene into one panel of the figure.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Projection {
    pub(super) right: Vec3,
    pub(super) up: Vec3,
    pub(super) toward: Vec3,
    pub(super) centre: Vec3,
    /// Pixel where `centre` lands.
    pub(super) origin: (f64, f64),
    /// Pixels per metre, the same along every axis.
    pub scale: f64,
}

impl Projection {
    /// A projection of `view` putting `centre` at pixel `origin`, `scale` pixels per metre.
    pub fn new(view: ViewDirection, centre: Vec3, origin: (f64, f64), scale: f64) -> Self {
        Projection {
            right: view.right(),
            up: view.up(),
            toward: view.toward_viewer(),
            centre,
            origin,
            scale,
        }
    }

    /// Pixel coordinates of `p` (x to the right, y down).
    pub fn pixel(&self, p: Vec3) -> (f64, f64) {
        let d = p - self.centre;
        (
            self.origin.0 + self.scale * d.dot(self.right),
            self.origin.1 - self.scale * d.dot(self.up),
        )
    }

    /// Pixel coordinates rounded for drawing.
    pub fn at(&self, p: Vec3) -> (i32, i32) {
        let (x, y) = self.pixel(p);
        (x.round() as i32, y.round() as i32)
    }

    /// How near `p` is to the viewer (larger is nearer).
    pub fn nearness(&self, p: Vec3) -> f64 {
        (p - self.centre).dot(self.toward)
    }
}

/// Pixels per metre that fit the box, seen from `view`, in a `width` × `height` area.
pub(crate) fn fit_scale(bx: &AxisBox, view: ViewDirection, width: f64, height: f64) -> f64 {
    let c = bx.centre();
    let (r, u) = (view.right(), view.up());
    let (mut hw, mut hh) = (0f64, 0f64);
    for k in bx.corners() {
        hw = hw.max((k - c).dot(r).abs());
        hh = hh.max((k - c).dot(u).abs());
    }
    (width / (2.0 * hw.max(1e-9))).min(height / (2.0 * hh.max(1e-9)))
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::FRAC_PI_2;

    #[test]
    fn one_metre_has_the_same_length_on_screen_along_every_axis() {
        let c = Vec3::new(0.0, 0.0, 0.1);
        for az in [0.0, 0.4, 1.3, 2.9, -2.0] {
            // Level view: z and the horizontal axis across the screen are both true length.
            let level = Projection::new(
                ViewDirection {
                    azimuth: az,
                    elevation: 0.0,
                },
                c,
                (300.0, 200.0),
                1234.0,
            );
            let len = |proj: &Projection, d: Vec3| {
                let (a, b) = (proj.pixel(c), proj.pixel(c + d));
                (b.0 - a.0).hypot(b.1 - a.1)
            };
            assert!((len(&level, Vec3::Z * 0.1) - 123.4).abs() < 1e-9);
            assert!((len(&level, level.right * 0.1) - 123.4).abs() < 1e-9);
            // From above: x and y are both true length.
            let top = Projection::new(
                ViewDirection {
                    azimuth: az,
                    elevation: FRAC_PI_2,
                },
                c,
                (300.0, 200.0),
                1234.0,
            );
            assert!((len(&top, Vec3::X * 0.1) - 123.4).abs() < 1e-9);
            assert!((len(&top, Vec3::Y * 0.1) - 123.4).abs() < 1e-9);
        }
    }
}
