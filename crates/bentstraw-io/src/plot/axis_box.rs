//! The axis box: the part of the scene every panel of a figure shows, one scale for all axes.

use bentstraw_optics::image::ImagePoint;
use bentstraw_optics::setup::Setup;
use bentstraw_optics::Vec3;

/// An observer farther out than this many times the scene's size is shown by an arrow, not to scale.
pub(crate) const FAR_OBSERVER_FACTOR: f64 = 2.5;

/// The axis ranges of a figure: one box holding the glass, the straw, every image point and (when not
/// too far) the observer. Drawn with one scale for all axes, so the ranges may differ in length.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct AxisBox {
    /// Lower corner (m).
    pub min: Vec3,
    /// Upper corner (m).
    pub max: Vec3,
    /// Whether the observer is inside the box (drawn to scale), or too far and drawn as an arrow.
    pub observer_inside: bool,
    /// For a far observer: tail and tip of an arrow pointing to it, in room left for it in the box.
    pub observer_arrow: Option<(Vec3, Vec3)>,
}

impl AxisBox {
    /// Centre of the box.
    pub fn centre(&self) -> Vec3 {
        0.5 * (self.min + self.max)
    }

    /// The eight corners, corner `i` taking `max` on axis `a` when bit `a` of `i` is set.
    pub fn corners(&self) -> [Vec3; 8] {
        std::array::from_fn(|i| {
            Vec3::new(
                if i & 1 != 0 { self.max.x } else { self.min.x },
                if i & 2 != 0 { self.max.y } else { self.min.y },
                if i & 4 != 0 { self.max.z } else { self.min.z },
            )
        })
    }

    /// Whether `p` lies in the box.
    #[cfg(test)]
    pub fn contains(&self, p: Vec3) -> bool {
        p.cmpge(self.min).all() && p.cmple(self.max).all()
    }
}

/// The axis box of a figure: tight around the scene (glass and straw, or a world's container and
/// objects) and the points, with a margin; the observer is included unless that would make the
/// box more than [`FAR_OBSERVER_FACTOR`] times larger.
pub(crate) fn axis_box(scene: &Setup, observer: Vec3, points: &[ImagePoint]) -> AxisBox {
    let (mut lo, mut hi, centre) = scene.frame();
    for p in points {
        if p.position.is_finite() {
            lo = lo.min(p.position);
            hi = hi.max(p.position);
        }
    }
    let size = (hi - lo).max_element();
    let (with_lo, with_hi) = (lo.min(observer), hi.max(observer));
    let observer_inside = (with_hi - with_lo).max_element() <= FAR_OBSERVER_FACTOR * size;
    let mut observer_arrow = None;
    if observer_inside {
        lo = with_lo;
        hi = with_hi;
    } else {
        // Widen the box a little towards the observer and put an arrow pointing to it there.
        let c = centre;
        let d = (observer - c).normalize();
        let exit = (0..3)
            .filter(|&a| d[a].abs() > 1e-12)
            .map(|a| ((if d[a] > 0.0 { hi[a] } else { lo[a] }) - c[a]) / d[a])
            .fold(f64::INFINITY, f64::min);
        let tail = c + (exit + 0.04 * size) * d;
        let tip = c + (exit + 0.3 * size) * d;
        lo = lo.min(tip);
        hi = hi.max(tip);
        observer_arrow = Some((tail, tip));
    }
    // One margin for all axes, so the observer's marker and the outermost points are not on the edge.
    let margin = 0.04 * (hi - lo).max_element();
    AxisBox {
        min: lo - Vec3::splat(margin),
        max: hi + Vec3::splat(margin),
        observer_inside,
        observer_arrow,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::plot::tests::point;
    use bentstraw_optics::scene::{Scene, GLASS_HEIGHT, GLASS_RADIUS, STRAW_HEIGHT};

    #[test]
    fn axis_box_holds_glass_straw_points_and_a_near_observer() {
        let scene = Setup::assignment(Scene::with_defaults(0.02, 0.01, 0.15).unwrap(), Vec3::ZERO);
        let points = [
            point(Vec3::new(-0.2, 0.03, 0.12), 1),
            point(Vec3::new(0.01, 0.01, -0.05), 1),
        ];
        let observer = Vec3::new(0.0, 0.1, 0.4);
        let bx = axis_box(&scene, observer, &points);
        assert!(bx.observer_inside && bx.observer_arrow.is_none());
        assert!(bx.contains(observer));
        for p in &points {
            assert!(bx.contains(p.position));
        }
        for corner in [
            Vec3::new(GLASS_RADIUS, GLASS_RADIUS, GLASS_HEIGHT),
            Vec3::new(-GLASS_RADIUS, -GLASS_RADIUS, 0.0),
            Vec3::new(0.02, 0.01, STRAW_HEIGHT),
        ] {
            assert!(bx.contains(corner), "{corner} outside {bx:?}");
        }
    }

    #[test]
    fn far_observer_gets_an_arrow_pointing_at_it_inside_the_box() {
        let scene = Setup::assignment(Scene::with_defaults(0.0, 0.0, 0.15).unwrap(), Vec3::ZERO);
        let observer = Vec3::new(5.0, -2.0, 1.0);
        let bx = axis_box(&scene, observer, &[]);
        assert!(!bx.observer_inside);
        let (tail, tip) = bx.observer_arrow.unwrap();
        assert!(bx.contains(tail) && bx.contains(tip));
        // The box stays about the glass's size, not the observer's distance.
        assert!((bx.max - bx.min).max_element() < 0.5);
        let along = (tip - tail).normalize();
        let to_observer = (observer - tail).normalize();
        assert!(
            along.dot(to_observer) > 0.999,
            "arrow does not point at the observer"
        );
    }
}
