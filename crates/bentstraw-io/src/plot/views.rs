//! The directions the figures look from: the observer's, and the classic figure's three views,
//! each along an axis of the scene so that a panel's two scales are two of x, y and z.

use std::f64::consts::FRAC_PI_2;

use bentstraw_optics::scene::SCENE_CENTRE;
use bentstraw_optics::Vec3;

/// A direction to look at the scene from: azimuth from +x towards +y, elevation above the horizon.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct ViewDirection {
    /// Azimuth of the viewer as seen from the scene (rad).
    pub azimuth: f64,
    /// Elevation of the viewer above the horizontal plane (rad).
    pub elevation: f64,
}

impl ViewDirection {
    /// Unit vector from the scene towards the viewer.
    pub fn toward_viewer(&self) -> Vec3 {
        let (se, ce) = self.elevation.sin_cos();
        let (sa, ca) = self.azimuth.sin_cos();
        Vec3::new(ce * ca, ce * sa, se)
    }

    /// Unit vector pointing right on the screen (always horizontal, so `z` stays upright).
    pub fn right(&self) -> Vec3 {
        let (sa, ca) = self.azimuth.sin_cos();
        Vec3::new(-sa, ca, 0.0)
    }

    /// Unit vector pointing up on the screen.
    pub fn up(&self) -> Vec3 {
        self.toward_viewer().cross(self.right())
    }
}

/// The observer's direction as seen from the scene's centre (straight down or up: azimuth −90°).
pub(crate) fn observer_direction(observer: Vec3) -> ViewDirection {
    let d = observer - SCENE_CENTRE;
    let horizontal = d.x.hypot(d.y);
    let azimuth = if horizontal < 1e-12 {
        -FRAC_PI_2
    } else {
        d.y.atan2(d.x)
    };
    ViewDirection {
        azimuth,
        elevation: d.z.atan2(horizontal),
    }
}

/// The name of the direction a level view looks from, e.g. "+x".
fn from_words(azimuth: f64) -> &'static str {
    let quarter = ((azimuth / FRAC_PI_2).round() as i64).rem_euclid(4);
    ["+x", "+y", "−x", "−y"][quarter as usize]
}

/// The three views of the figure with their captions (one entry a line): a level front view from
/// the axis direction nearest the observer's azimuth, a level side view a quarter turn from it with
/// the observer's side on the right, and the view from above, x to the right and y up. Each looks
/// along an axis of the scene, so that a panel's scales are two of x, y and z; z is always up.
pub(crate) fn figure_views(observer: Vec3) -> [(ViewDirection, Vec<String>); 3] {
    let o = observer_direction(observer);
    let front = (o.azimuth / FRAC_PI_2).round() * FRAC_PI_2;
    let side = front - FRAC_PI_2;
    let level = |azimuth| ViewDirection {
        azimuth,
        elevation: 0.0,
    };
    [
        (
            level(front),
            vec![
                format!("front view, from {}", from_words(front)),
                "(the observer's side)".to_string(),
            ],
        ),
        (
            level(side),
            vec![
                format!("side view, from {}", from_words(side)),
                "(observer to the right)".to_string(),
            ],
        ),
        (
            ViewDirection {
                azimuth: -FRAC_PI_2,
                elevation: FRAC_PI_2,
            },
            vec!["top view, from above".to_string(), "(x →, y ↑)".to_string()],
        ),
    ]
}

/// The world axis (0, 1, 2 for x, y, z) along `d`, a screen direction of a view that looks along a
/// world axis, and whether it increases along `d` (`true`) or against it.
pub(crate) fn world_axis(d: Vec3) -> (usize, bool) {
    let a = (0..3)
        .max_by(|&i, &j| d[i].abs().total_cmp(&d[j].abs()))
        .unwrap_or(0);
    (a, d[a] > 0.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn views_look_along_axes_unmirrored_with_z_up_and_the_observer_to_the_right_from_the_side() {
        for observer in [
            Vec3::new(0.0, 0.1, 0.1),
            Vec3::new(0.1, 0.0, -0.1),
            Vec3::new(-0.3, 0.2, 0.5),
            Vec3::new(0.05, -0.3, 0.1),
            Vec3::new(0.0, 0.0, 0.6),
        ] {
            let views = figure_views(observer);
            for (v, _) in &views {
                let (r, u, t) = (v.right(), v.up(), v.toward_viewer());
                // Screen right × screen up points at the viewer: a right-handed, unmirrored picture.
                assert!((r.cross(u) - t).length() < 1e-12);
                // Right and up each run along one axis of the scene: one scale each.
                for d in [r, u] {
                    let along = (0..3).filter(|&a| d[a].abs() > 1e-9).count();
                    assert_eq!(along, 1, "{observer}: {d} is not along an axis");
                }
                assert!(r.z == 0.0, "z must stay upright");
            }
            // Level views have z up; the top view x to the right and y up.
            for (v, _) in &views[..2] {
                assert_eq!(world_axis(v.up()), (2, true));
            }
            assert_eq!(world_axis(views[2].0.right()), (0, true));
            assert_eq!(world_axis(views[2].0.up()), (1, true));
            // The front view looks from the axis direction nearest the observer's.
            let d = observer - SCENE_CENTRE;
            let horizontal = Vec3::new(d.x, d.y, 0.0);
            if horizontal.length() > 1e-9 {
                let t = views[0].0.toward_viewer();
                for other in [Vec3::X, Vec3::Y, -Vec3::X, -Vec3::Y] {
                    assert!(
                        t.dot(horizontal) >= other.dot(horizontal) - 1e-12,
                        "{observer}"
                    );
                }
                // From the side the observer is to the right.
                assert!(views[1].0.right().dot(horizontal) > 0.0, "{observer}");
            }
        }
        assert_eq!(
            figure_views(Vec3::new(0.0, 0.1, 0.1))[1].1[0],
            "side view, from +x"
        );
    }
}
