//! What a figure draws of a scene besides the points, as lines in space: the assignment's water
//! as a wireframe, a scene file's container and liquids (from the world's own boundaries) and
//! the objects' true outlines. Geometry only: the figures project and draw it.

use std::f64::consts::PI;

use crate::scene::{
    Scene, GLASS_RADIUS, SECTION_COUNT, SECTION_HEIGHT, STRAW_HEIGHT, STRAW_RADIUS,
};
use crate::world::{Boundary, Object, Region, Shape, World};
use crate::Vec3;

/// Number of vertical lines of the water's wireframe.
pub const WIRE_VERTICALS: usize = 30;
/// Segments per circle of the wireframes.
pub const CIRCLE_SEGMENTS: usize = 72;

/// Points around the horizontal circle of radius `r` centred on `(cx, cy)` at height `z`.
pub fn circle(cx: f64, cy: f64, r: f64, z: f64) -> Vec<Vec3> {
    (0..=CIRCLE_SEGMENTS)
        .map(|k| {
            let t = 2.0 * PI * k as f64 / CIRCLE_SEGMENTS as f64;
            Vec3::new(cx + r * t.cos(), cy + r * t.sin(), z)
        })
        .collect()
}

/// The water's wireframe as segments: top and bottom circles and [`WIRE_VERTICALS`] vertical lines.
pub fn water_segments(scene: &Scene) -> Vec<[Vec3; 2]> {
    let he = scene.water_height();
    let mut segs = Vec::new();
    for z in [0.0, he] {
        let c = circle(0.0, 0.0, GLASS_RADIUS, z);
        segs.extend(c.windows(2).map(|w| [w[0], w[1]]));
    }
    if he > 0.0 {
        for k in 0..WIRE_VERTICALS {
            let t = 2.0 * PI * k as f64 / WIRE_VERTICALS as f64;
            let (x, y) = (GLASS_RADIUS * t.cos(), GLASS_RADIUS * t.sin());
            segs.push([Vec3::new(x, y, 0.0), Vec3::new(x, y, he)]);
        }
    }
    segs
}

/// A ring of [`CIRCLE_SEGMENTS`] points around `centre` in the plane of unit `e1`, `e2`.
fn ring(centre: Vec3, e1: Vec3, e2: Vec3, r: f64) -> Vec<Vec3> {
    (0..=CIRCLE_SEGMENTS)
        .map(|k| {
            let t = 2.0 * PI * k as f64 / CIRCLE_SEGMENTS as f64;
            centre + r * (t.cos() * e1 + t.sin() * e2)
        })
        .collect()
}

/// Consecutive pairs of a polyline.
fn pairs(line: &[Vec3]) -> impl Iterator<Item = [Vec3; 2]> + '_ {
    line.windows(2).map(|w| [w[0], w[1]])
}

/// The wireframe of one boundary: its circles, rectangles and a few vertical lines.
fn boundary_segments(b: &Boundary, out: &mut Vec<[Vec3; 2]>) {
    match b.shape {
        Shape::Horizontal { z, region } => match region {
            Region::Disk { cx, cy, radius } => out.extend(pairs(&circle(cx, cy, radius, z))),
            Region::Annulus { inner2, outer2 } => {
                out.extend(pairs(&circle(0.0, 0.0, inner2.sqrt(), z)));
                out.extend(pairs(&circle(0.0, 0.0, outer2.sqrt(), z)));
            }
            Region::Rectangle { half_x, half_y } => {
                let c = [
                    Vec3::new(-half_x, -half_y, z),
                    Vec3::new(half_x, -half_y, z),
                    Vec3::new(half_x, half_y, z),
                    Vec3::new(-half_x, half_y, z),
                    Vec3::new(-half_x, -half_y, z),
                ];
                out.extend(pairs(&c));
            }
        },
        Shape::Upright {
            cx,
            cy,
            radius,
            z_min,
            z_max,
        } => {
            for k in 0..WIRE_VERTICALS {
                let t = 2.0 * PI * k as f64 / WIRE_VERTICALS as f64;
                let (x, y) = (cx + radius * t.cos(), cy + radius * t.sin());
                out.push([Vec3::new(x, y, z_min), Vec3::new(x, y, z_max)]);
            }
        }
        Shape::Vertical {
            axis,
            at,
            half,
            z_min,
            z_max,
        } => {
            let corner = |s: f64, z: f64| {
                let mut p = Vec3::new(0.0, 0.0, z);
                p[axis] = at;
                p[1 - axis] = s * half;
                p
            };
            out.push([corner(-1.0, z_min), corner(-1.0, z_max)]);
            out.push([corner(1.0, z_min), corner(1.0, z_max)]);
        }
    }
}

/// The container's and liquids' wireframe: every boundary between media of different index.
pub fn world_wireframe(world: &World) -> Vec<[Vec3; 2]> {
    let mut out = Vec::new();
    for b in world.boundaries() {
        boundary_segments(b, &mut out);
    }
    out
}

/// The objects' true outlines as polylines: a straw's band edges and four lines along it, a
/// coin's two rims, a card's edge and its arrow.
pub fn object_outlines(world: &World) -> Vec<Vec<Vec3>> {
    let mut out = Vec::new();
    for o in world.objects() {
        match o {
            Object::Straw { solid, edges } => {
                for h in [0.0, edges[0], edges[1], edges[2], edges[3], solid.length] {
                    out.push(ring(
                        solid.base + h * solid.axis,
                        solid.e1,
                        solid.e2,
                        solid.radius,
                    ));
                }
                for side in [solid.e1, -solid.e1, solid.e2, -solid.e2] {
                    let a = solid.base + solid.radius * side;
                    out.push(vec![a, a + solid.length * solid.axis]);
                }
            }
            Object::Coin(solid) => {
                for h in [0.0, solid.length] {
                    out.push(ring(
                        solid.base + h * solid.axis,
                        solid.e1,
                        solid.e2,
                        solid.radius,
                    ));
                }
            }
            Object::Card {
                centre,
                right,
                width,
                height,
                arrow,
                ..
            } => {
                let at = |u: f64, v: f64| *centre + u * *right + Vec3::new(0.0, 0.0, v);
                let (w, h) = (*width, *height);
                out.push(vec![
                    at(-w / 2.0, -h / 2.0),
                    at(w / 2.0, -h / 2.0),
                    at(w / 2.0, h / 2.0),
                    at(-w / 2.0, h / 2.0),
                    at(-w / 2.0, -h / 2.0),
                ]);
                if *arrow {
                    // The arrow's outline (see the scene format): shaft, then head.
                    out.push(vec![
                        at(-0.35 * w, -0.1 * h),
                        at(0.1 * w, -0.1 * h),
                        at(0.1 * w, -0.3 * h),
                        at(0.4 * w, 0.0),
                        at(0.1 * w, 0.3 * h),
                        at(0.1 * w, 0.1 * h),
                        at(-0.35 * w, 0.1 * h),
                        at(-0.35 * w, -0.1 * h),
                    ]);
                }
            }
        }
    }
    out
}

/// The assignment's straw's true outline for a view whose rightward direction is `right`: the
/// circles between its sections (and its caps), and its two silhouette lines.
pub fn straw_outline(scene: &Scene, right: Vec3) -> Vec<Vec<Vec3>> {
    let (x, y) = (scene.straw_x(), scene.straw_y());
    let mut out: Vec<Vec<Vec3>> = (0..=SECTION_COUNT)
        .map(|k| circle(x, y, STRAW_RADIUS, k as f64 * SECTION_HEIGHT))
        .collect();
    let side = STRAW_RADIUS * right;
    let axis = Vec3::new(x, y, 0.0);
    for s in [-1.0, 1.0] {
        let a = axis + s * side;
        out.push(vec![a, a + Vec3::new(0.0, 0.0, STRAW_HEIGHT)]);
    }
    out
}
