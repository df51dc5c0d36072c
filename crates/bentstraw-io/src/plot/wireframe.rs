//! The scene's lines: the water's wireframe, its near half drawn over the points and its far
//! half under them, and the straw's true outline, dashed.

use bentstraw_optics::setup::Setup;
use plotters::prelude::*;

use super::colours::{rgb, STRAW_OUTLINE_RGB, WATER_RGB};
use super::figure::{AreaOn, DrawResultOn};
use super::projection::Projection;

/// The water's wireframe segments on the near (`front`) or far side of the glass's axis.
pub(crate) fn draw_water<DB: DrawingBackend>(
    root: &AreaOn<DB>,
    proj: &Projection,
    scene: &Setup,
    front: bool,
) -> DrawResultOn<DB> {
    let (axis, segments) = scene.wireframe();
    let axis_depth = proj.nearness(axis);
    let color = if front {
        rgb(WATER_RGB).mix(0.75)
    } else {
        rgb(WATER_RGB).mix(0.45)
    };
    for [a, b] in segments {
        let mid = 0.5 * (a + b);
        if (proj.nearness(mid) > axis_depth) == front {
            root.draw(&PathElement::new(vec![proj.at(a), proj.at(b)], color))?;
        }
    }
    Ok(())
}

/// The straw's true outline, dashed: its section boundaries and its two silhouette lines.
pub(crate) fn draw_straw_outline<DB: DrawingBackend>(
    root: &AreaOn<DB>,
    proj: &Projection,
    scene: &Setup,
) -> DrawResultOn<DB> {
    let color = rgb(STRAW_OUTLINE_RGB);
    for line in scene.outlines(proj.right) {
        let px: Vec<(f64, f64)> = line.iter().map(|&p| proj.pixel(p)).collect();
        dashed(root, &px, color)?;
    }
    Ok(())
}

/// A dashed polyline through pixel positions: 5 px on, 4 px off.
pub(crate) fn dashed<DB: DrawingBackend>(
    root: &AreaOn<DB>,
    px: &[(f64, f64)],
    color: RGBColor,
) -> DrawResultOn<DB> {
    const ON: f64 = 5.0;
    const PERIOD: f64 = 9.0;
    let mut phase = 0.0f64;
    for w in px.windows(2) {
        let (a, b) = (w[0], w[1]);
        let len = (b.0 - a.0).hypot(b.1 - a.1);
        let mut s = 0.0;
        while s < len {
            let in_period = phase % PERIOD;
            let (seg, on) = if in_period < ON {
                (ON - in_period, true)
            } else {
                (PERIOD - in_period, false)
            };
            let e = (s + seg).min(len);
            if on && len > 0.0 {
                let p = |t: f64| {
                    let f = t / len;
                    (
                        (a.0 + f * (b.0 - a.0)).round() as i32,
                        (a.1 + f * (b.1 - a.1)).round() as i32,
                    )
                };
                root.draw(&PathElement::new(vec![p(s), p(e)], color))?;
            }
            phase += e - s;
            s = e;
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use bentstraw_optics::scene::{Scene, GLASS_RADIUS};
    use bentstraw_optics::setup::Setup;
    use bentstraw_optics::sketch::{CIRCLE_SEGMENTS, WIRE_VERTICALS};
    use bentstraw_optics::Vec3;

    #[test]
    fn water_wireframe_has_two_circles_and_thirty_verticals() {
        let scene = Setup::assignment(Scene::with_defaults(0.0, 0.0, 0.15).unwrap(), Vec3::ZERO);
        let segs = scene.wireframe().1;
        let verticals: Vec<_> = segs
            .iter()
            .filter(|[a, b]| a.x == b.x && a.y == b.y)
            .collect();
        assert_eq!(verticals.len(), WIRE_VERTICALS);
        assert_eq!(segs.len(), WIRE_VERTICALS + 2 * CIRCLE_SEGMENTS);
        for [a, b] in &segs {
            for p in [a, b] {
                assert!((p.x.hypot(p.y) - GLASS_RADIUS).abs() < 1e-12);
                assert!(p.z == 0.0 || p.z == 0.15);
            }
        }
    }
}
