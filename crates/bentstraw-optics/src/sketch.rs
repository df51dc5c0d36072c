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

/// The wireframe of one boundary: its circles, rectangles and a few vertical lines (a prism's
/// top and bottom are drawn by its sides' edges).
fn boundary_segments(b: &Boundary, out: &mut Vec<[Vec3; 2]>) {
    if b.solid && matches!(b.shape, Shape::Horizontal { .. }) {
        return;
    }
    // A lens's face cut by a liquid's surface: each piece draws the part between its heights.
    if let Shape::Cap { z_min, z_max, .. }
    | Shape::Disk { z_min, z_max, .. }
    | Shape::Tube { z_min, z_max, .. } = b.shape
    {
        let mut all = Vec::new();
        shape_segments(b, &mut all);
        let inside = |p: Vec3| (z_min..=z_max).contains(&p.z);
        out.extend(all.into_iter().filter(|[a, c]| inside(*a) && inside(*c)));
        return;
    }
    shape_segments(b, out);
}

/// [`boundary_segments`] of any boundary, whole.
fn shape_segments(b: &Boundary, out: &mut Vec<[Vec3; 2]>) {
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
        Shape::Revolution {
            zc,
            c,
            z_min,
            z_max,
            ..
        } => {
            // Its meridians, as upright sides have their vertical lines.
            let piece = crate::profile::Piece {
                zc,
                c,
                z0: z_min,
                z1: z_max,
            };
            let radius = |z: f64| piece.r2(z).max(0.0).sqrt();
            for k in 0..WIRE_VERTICALS {
                let t = 2.0 * PI * k as f64 / WIRE_VERTICALS as f64;
                let line: Vec<Vec3> = (0..=8)
                    .map(|j| {
                        let z = z_min + (z_max - z_min) * j as f64 / 8.0;
                        let r = radius(z);
                        Vec3::new(r * t.cos(), r * t.sin(), z)
                    })
                    .collect();
                out.extend(pairs(&line));
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
        Shape::Face {
            ax,
            ay,
            ux,
            uy,
            length,
            z_min,
            z_max,
        } => {
            // Its vertical edges, top and bottom.
            let (a, b) = (
                Vec3::new(ax, ay, 0.0),
                Vec3::new(ax + length * ux, ay + length * uy, 0.0),
            );
            let at = |p: Vec3, z: f64| Vec3::new(p.x, p.y, z);
            out.push([at(a, z_min), at(a, z_max)]);
            out.push([at(b, z_min), at(b, z_max)]);
            out.push([at(a, z_min), at(b, z_min)]);
            out.push([at(a, z_max), at(b, z_max)]);
        }
        Shape::Cap {
            centre,
            radius,
            toward,
            rho2,
            ..
        } => {
            // Its rim, and two arcs across it through its vertex.
            let (r, rim) = (radius.abs(), rho2.sqrt());
            let (e1, e2) = toward.any_orthonormal_pair();
            out.extend(pairs(&ring(
                centre + (r * r - rho2).max(0.0).sqrt() * toward,
                e1,
                e2,
                rim,
            )));
            let half = (rim / r).min(1.0).asin();
            for e in [e1, e2] {
                let arc: Vec<Vec3> = (0..=24)
                    .map(|k| {
                        let a = -half + 2.0 * half * k as f64 / 24.0;
                        centre + r * (a.cos() * toward + a.sin() * e)
                    })
                    .collect();
                out.extend(pairs(&arc));
            }
        }
        Shape::Disk {
            centre, normal, r2, ..
        } => {
            let (e1, e2) = normal.any_orthonormal_pair();
            out.extend(pairs(&ring(centre, e1, e2, r2.sqrt())));
        }
        Shape::Tube {
            centre,
            axis,
            r2,
            w_min,
            w_max,
            ..
        } => {
            // Its two circles and four lines along it.
            let (e1, e2) = axis.any_orthonormal_pair();
            let r = r2.sqrt();
            for w in [w_min, w_max] {
                out.extend(pairs(&ring(centre + w * axis, e1, e2, r)));
            }
            for e in [e1, -e1, e2, -e2] {
                out.push([centre + w_min * axis + r * e, centre + w_max * axis + r * e]);
            }
        }
        Shape::Sphere {
            centre,
            radius,
            z_min,
            z_max,
        } => {
            // Its equator and two meridians, within the heights it spans.
            let c = centre;
            let mut rings = vec![ring(c, Vec3::X, Vec3::Y, radius)];
            rings.push(ring(c, Vec3::X, Vec3::Z, radius));
            rings.push(ring(c, Vec3::Y, Vec3::Z, radius));
            for line in rings {
                out.extend(
                    pairs(&line).filter(|[a, b]| {
                        a.z >= z_min && a.z <= z_max && b.z >= z_min && b.z <= z_max
                    }),
                );
            }
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

/// A scene drawn as lines in space: its boundaries' edges and its objects' true outlines.
#[derive(Clone, Debug, PartialEq)]
pub struct SceneLines {
    /// The boundaries' edges, as segments.
    pub edges: Vec<[Vec3; 2]>,
    /// The objects' outlines, as polylines.
    pub outlines: Vec<Vec<Vec3>>,
}

/// A panel of a schematic drawing: a side view along a horizontal unit axis (the distance along
/// it to the right, the height up), or the view from above (x to the right, y up).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Panel {
    /// Side view along this horizontal unit vector.
    Side(Vec3),
    /// Top view.
    Top,
}

impl Panel {
    /// Where the point `p` lands on the panel's plane (m).
    pub fn project(self, p: Vec3) -> (f64, f64) {
        match self {
            Panel::Side(e) => (p.x * e.x + p.y * e.y, p.z),
            Panel::Top => (p.x, p.y),
        }
    }
}

/// A shape of a schematic, in the panel's coordinates (m).
#[derive(Clone, Debug, PartialEq)]
pub enum Figure {
    /// An upright rectangle by two opposite corners.
    Rect([(f64, f64); 2]),
    /// A closed polygon.
    Polygon(Vec<(f64, f64)>),
    /// An open polyline.
    Line(Vec<(f64, f64)>),
}

/// What a mark of a schematic shows: it sets how the mark is drawn.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Part {
    /// A liquid's body, filled.
    Liquid,
    /// A container's wall, a thick line.
    Wall,
    /// A part of an object in its colour code, filled.
    Band(u8),
    /// An object seen from above, filled grey.
    Footprint,
    /// A boundary's edge, a thin line.
    Edge,
    /// An object's true outline.
    Outline,
}

/// One mark of a schematic: what it shows and its shape.
#[derive(Clone, Debug, PartialEq)]
pub struct Mark {
    /// What it shows.
    pub part: Part,
    /// Its shape on the panel.
    pub figure: Figure,
}

/// Points around the circle of radius `r` centred on `(cx, cy)` of a schematic's top view (96
/// segments, closed).
fn flat_circle(cx: f64, cy: f64, r: f64) -> Vec<(f64, f64)> {
    (0..=96)
        .map(|k| {
            let a = std::f64::consts::TAU * k as f64 / 96.0;
            (cx + r * a.cos(), cy + r * a.sin())
        })
        .collect()
}

/// The schematic of the assignment's glass in `panel`, back to front: the water, the glass's
/// wall, the straw (its five bands from the side, its footprint from above).
pub fn straw_schematic(scene: &Scene, panel: Panel) -> Vec<Mark> {
    let mark = |part, figure| Mark { part, figure };
    let rv = GLASS_RADIUS;
    let mut marks = Vec::new();
    match panel {
        Panel::Side(axis) => {
            if scene.has_water() {
                marks.push(mark(
                    Part::Liquid,
                    Figure::Rect([(-rv, 0.0), (rv, scene.water_height())]),
                ));
            }
            marks.push(mark(
                Part::Wall,
                Figure::Line(vec![
                    (-rv, crate::scene::GLASS_HEIGHT),
                    (-rv, 0.0),
                    (rv, 0.0),
                    (rv, crate::scene::GLASS_HEIGHT),
                ]),
            ));
            let c = scene.straw_x() * axis.x + scene.straw_y() * axis.y;
            for k in 0..SECTION_COUNT {
                marks.push(mark(
                    Part::Band(k as u8 + 1),
                    Figure::Rect([
                        (c - STRAW_RADIUS, k as f64 * SECTION_HEIGHT),
                        (c + STRAW_RADIUS, (k + 1) as f64 * SECTION_HEIGHT),
                    ]),
                ));
            }
        }
        Panel::Top => {
            if scene.has_water() {
                marks.push(mark(
                    Part::Liquid,
                    Figure::Polygon(flat_circle(0.0, 0.0, rv)),
                ));
            }
            marks.push(mark(Part::Wall, Figure::Line(flat_circle(0.0, 0.0, rv))));
            marks.push(mark(
                Part::Footprint,
                Figure::Polygon(flat_circle(scene.straw_x(), scene.straw_y(), STRAW_RADIUS)),
            ));
        }
    }
    marks
}

/// The schematic of a scene file's world in `panel`: every boundary's edges, then the objects'
/// true outlines.
pub fn world_schematic(world: &World, panel: Panel) -> Vec<Mark> {
    let edges = world_wireframe(world).into_iter().map(|[a, b]| Mark {
        part: Part::Edge,
        figure: Figure::Line(vec![panel.project(a), panel.project(b)]),
    });
    let outlines = object_outlines(world).into_iter().map(|line| Mark {
        part: Part::Outline,
        figure: Figure::Line(line.iter().map(|p| panel.project(*p)).collect()),
    });
    edges.chain(outlines).collect()
}

/// The points a schematic of the assignment's glass must hold: the glass's square at the floor
/// and at the straw's top, and the straw's foot.
pub fn straw_schematic_extent(scene: &Scene) -> Vec<Vec3> {
    let mut pts = Vec::new();
    for z in [0.0, STRAW_HEIGHT] {
        for (x, y) in [(-1.0, -1.0), (1.0, 1.0), (-1.0, 1.0), (1.0, -1.0)] {
            pts.push(Vec3::new(x * GLASS_RADIUS, y * GLASS_RADIUS, z));
        }
    }
    pts.push(Vec3::new(scene.straw_x(), scene.straw_y(), 0.0));
    pts
}

/// The points a schematic of a world must hold: the corners of the box holding everything.
pub fn world_schematic_extent(world: &World) -> Vec<Vec3> {
    let (lo, hi) = world.bounds();
    (0..8)
        .map(|k| {
            let pick = |bit: i32, a: f64, b: f64| if k & bit == 0 { a } else { b };
            Vec3::new(
                pick(1, lo.x, hi.x),
                pick(2, lo.y, hi.y),
                pick(4, lo.z, hi.z),
            )
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_glass_from_the_side_is_its_water_its_wall_and_five_bands_on_the_straws_axis() {
        let scene = Scene::with_defaults(0.02, 0.01, 0.15).unwrap();
        let axis = Vec3::new(0.6, 0.8, 0.0);
        let marks = straw_schematic(&scene, Panel::Side(axis));
        let parts: Vec<Part> = marks.iter().map(|m| m.part).collect();
        assert_eq!(
            parts,
            [
                Part::Liquid,
                Part::Wall,
                Part::Band(1),
                Part::Band(2),
                Part::Band(3),
                Part::Band(4),
                Part::Band(5)
            ]
        );
        assert_eq!(
            marks[0].figure,
            Figure::Rect([(-GLASS_RADIUS, 0.0), (GLASS_RADIUS, 0.15)])
        );
        // The bands stand on the straw's axis as the panel projects it, one section high each.
        let c = 0.02 * 0.6 + 0.01 * 0.8;
        assert_eq!(
            Panel::Side(axis).project(Vec3::new(0.02, 0.01, 0.3)),
            (c, 0.3)
        );
        let Figure::Rect([(x0, z0), (x1, z1)]) = marks[4].figure else {
            panic!("a band is a rectangle")
        };
        assert!((x0 - (c - STRAW_RADIUS)).abs() < 1e-15 && (x1 - (c + STRAW_RADIUS)).abs() < 1e-15);
        assert!(
            (z0 - 2.0 * SECTION_HEIGHT).abs() < 1e-15 && (z1 - 3.0 * SECTION_HEIGHT).abs() < 1e-15
        );
        // An empty glass has no water to fill.
        let empty = Scene::with_defaults(0.0, 0.0, 0.0).unwrap();
        assert!(straw_schematic(&empty, Panel::Top)
            .iter()
            .all(|m| m.part != Part::Liquid));
    }

    #[test]
    fn a_worlds_schematic_is_its_wireframe_then_its_outlines() {
        let scene = Scene::with_defaults(0.0, 0.0, 0.1).unwrap();
        let world = World::assignment(&scene);
        let marks = world_schematic(&world, Panel::Top);
        let (edges, outlines) = (world_wireframe(&world).len(), object_outlines(&world).len());
        assert_eq!(marks.len(), edges + outlines);
        assert!(marks[..edges].iter().all(|m| m.part == Part::Edge));
        assert!(marks[edges..].iter().all(|m| m.part == Part::Outline));
        // The box's eight corners hold every boundary.
        let corners = world_schematic_extent(&world);
        assert_eq!(corners.len(), 8);
        let (lo, hi) = world.bounds();
        assert!(corners
            .iter()
            .all(|p| p.cmpge(lo).all() && p.cmple(hi).all()));
    }
}
