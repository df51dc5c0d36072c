//! Apparent depth against the viewing angle: where one object point appears (the course's point,
//! the eye model's two focal lines, the stereo point) as the eye moves round the glass, or up and
//! down, at the same distance from the point it looks at.
//!
//! Each seat of a classroom sees the same straw point along its own light path: the angle at which
//! that light leaves the water changes, and with it how far the refraction lifts the point and how
//! far apart the two focal lines lie. The sweep puts the eye at `rows` seats on a circle about
//! the sweep's centre, keeps the eye's distance from it, and finds at each seat the ray that
//! reaches the object point:
//! - **round the glass** (`around`): the eye turns about the vertical line through the centre, at
//!   the same height and horizontal distance; the angle is the turn from the observer's seat
//!   (degrees, −180 to 180, positive anticlockwise seen from above);
//! - **up and down** (`updown`): the eye moves in the vertical plane through the centre and the
//!   observer, at the same distance from the centre; the angle is the eye's elevation above the
//!   centre's horizontal plane (degrees, −90 straight below to 90 straight above).
//!
//! The observer's own seat is always one of the rows (inserted if the grid misses it), placed
//! exactly at the observer, so that its row gives the numbers the observer's ray gives.
//!
//! The ray to the point at each seat is followed from the neighbouring seat's ray along the same
//! light path (re-aimed by Newton's method, see [`super`], "Re-aiming"), outwards from the
//! observer's seat both ways, so that one image is followed as long as it lasts. Where that path is
//! lost (the light would leave another face, or something is in the way), the point is searched
//! for afresh: rays in a cone around the straight line to it are traced and the ones that land
//! nearest it are re-aimed along their own light paths. A seat from which no ray reaches the
//! point is a row marked not seen; a seat inside the container, a liquid or an object is a row
//! marked so. Neither is a failure.
//!
//! What is plotted as the apparent depth is each model's point's height `z` (m): the depth under
//! the liquid's surface is that surface's height minus it, and the object point's own height is
//! the depth it would seem to have without refraction.

use std::sync::atomic::{AtomicBool, Ordering};

use super::reaim::Aim;
use super::{
    extend_sequence, pupil_axes, ApparentPoint, Focus, LightPath, StereoEyes, StereoPoint,
    EMPTY_SEQUENCE,
};
use crate::geometry::Ray;
use crate::image::ImagePoint;
use crate::light_path_type::LightPathType;
use crate::scene_file::Observer;
use crate::setup::Setup;
use crate::world::World;
use crate::Vec3;

/// Seats of a sweep when none is asked for: every 6° round the glass, every 3° up and down.
pub const DEFAULT_SWEEP_ROWS: usize = 61;
/// Most seats of one sweep (besides the observer's own): every degree round the glass.
pub const MAX_SWEEP_ROWS: usize = 361;
/// Fewest seats of one sweep: both ends of its range.
pub const MIN_SWEEP_ROWS: usize = 2;
/// How close to an object's surface the point swept must lie (m): the rays found must reach it
/// within [`super::REACH_TOLERANCE`], so a point off every surface would be seen from nowhere.
pub const SWEEP_POINT_TOLERANCE: f64 = 1e-6;
/// Half-angle of the cone of directions searched around the straight line from a seat to the
/// point (radians, 40°): refraction by a liquid of index up to about 2 turns the line of sight by
/// less where light can still leave it.
const SEARCH_HALF_ANGLE: f64 = 0.7;
/// Directions across each side of the searched cone (a `SEARCH_GRID`² grid, one trace each).
const SEARCH_GRID: usize = 17;
/// The searched rays that land nearest the point and are re-aimed at it, at most.
const SEARCH_TRIES: usize = 4;

/// How the eye moves.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SweepKind {
    /// Round the glass: about the vertical through the centre, at the same height and distance.
    Around,
    /// Up and down: in the vertical plane through the centre and the observer, at the same
    /// distance from the centre.
    UpDown,
}

impl SweepKind {
    /// Every kind's name, as the explorer's query and the files spell it.
    pub const NAMES: [&'static str; 2] = ["around", "updown"];

    /// The kind's name: `around` or `updown`.
    pub fn name(self) -> &'static str {
        match self {
            SweepKind::Around => "around",
            SweepKind::UpDown => "updown",
        }
    }

    /// The kind named `name`, if any.
    pub fn from_name(name: &str) -> Option<SweepKind> {
        match name {
            "around" => Some(SweepKind::Around),
            "updown" => Some(SweepKind::UpDown),
            _ => None,
        }
    }

    /// The range of the angle (degrees): the turn from the observer's seat, or the elevation.
    pub fn range(self) -> (f64, f64) {
        match self {
            SweepKind::Around => (-180.0, 180.0),
            SweepKind::UpDown => (-90.0, 90.0),
        }
    }
}

/// A sweep as asked for: how the eye moves, about which point, in how many seats.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sweep {
    /// How the eye moves.
    pub kind: SweepKind,
    /// The point the eye keeps its distance from (the vertical through it is the axis of turn):
    /// where the camera looks, the glass's axis for the assignment.
    pub centre: Vec3,
    /// Seats on the grid over the kind's range, ends included ([`MIN_SWEEP_ROWS`] to
    /// [`MAX_SWEEP_ROWS`]; clamped), besides the observer's own if the grid misses it.
    pub rows: usize,
}

/// What one seat sees of the point, when it sees it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SweepSight {
    /// The kind of light path the point is seen along.
    pub path: LightPathType,
    /// The eye model's answer, with the course's image point of the same ray (`image`).
    pub apparent: ApparentPoint,
    /// The stereo model's point (two eyes around the seat), if both eyes see it along that path.
    pub stereo: Option<StereoPoint>,
}

impl SweepSight {
    /// The course's image point `O + L·u0`.
    pub fn course_point(&self) -> Vec3 {
        self.apparent.image.position
    }

    /// The horizontal focal line's point on the line of sight (`E + s_h·u0`), if in front.
    pub fn horizontal_focus(&self, eye: Vec3) -> Option<Vec3> {
        focal_point(eye, self.apparent.image.direction, self.apparent.s_h)
    }

    /// The vertical focal line's point on the line of sight (`E + s_v·u0`), if in front.
    pub fn vertical_focus(&self, eye: Vec3) -> Option<Vec3> {
        focal_point(eye, self.apparent.image.direction, self.apparent.s_v)
    }

    /// The stereo point, if the two lines of sight converge.
    pub fn stereo_point(&self) -> Option<Vec3> {
        self.stereo.and_then(|s| s.position)
    }
}

/// The point of focus `f` on the line of sight from `eye` along `u0`, if it is in front.
fn focal_point(eye: Vec3, u0: Vec3, f: Focus) -> Option<Vec3> {
    Some(eye + f.distance()? * u0)
}

/// What a seat sees of the point.
#[derive(Clone, Copy, Debug, PartialEq)]
#[allow(clippy::large_enum_variant)] // a few hundred rows at most, each made once
pub enum Sight {
    /// The point is seen: along which path, and where each model puts it.
    Seen(SweepSight),
    /// No ray from this seat reaches the point (it is hidden, or out of every light path's reach).
    NotSeen,
    /// The seat lies inside the container, a liquid or an object: no eye can be there.
    EyeInside,
}

/// One seat of a sweep.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SweepRow {
    /// The angle (degrees): the turn from the observer's seat (`around`), or the elevation
    /// (`updown`).
    pub angle: f64,
    /// The eye's position.
    pub eye: Vec3,
    /// Whether this is the observer's own seat.
    pub current: bool,
    /// What it sees.
    pub sight: Sight,
}

impl SweepRow {
    /// What it sees, if it sees the point.
    pub fn seen(&self) -> Option<&SweepSight> {
        match &self.sight {
            Sight::Seen(s) => Some(s),
            _ => None,
        }
    }
}

/// The eye positions and angles of `sweep` around `observer`, sorted by angle, and the index of
/// the observer's own seat (placed exactly at `observer`).
pub fn sweep_seats(observer: Vec3, sweep: &Sweep) -> (Vec<(f64, Vec3)>, usize) {
    let rows = sweep.rows.clamp(MIN_SWEEP_ROWS, MAX_SWEEP_ROWS);
    let c = sweep.centre;
    let v = observer - c;
    let level = Vec3::new(v.x, v.y, 0.0);
    let across = level.length();
    // The horizontal direction from the centre towards the observer (x̂ straight above or below).
    let out = if across < 1e-12 {
        Vec3::X
    } else {
        level / across
    };
    let (lo, hi) = sweep.kind.range();
    let own = match sweep.kind {
        SweepKind::Around => 0.0,
        SweepKind::UpDown => libm::atan2(v.z, across).to_degrees(),
    };
    let place = |angle: f64| -> Vec3 {
        let a = angle.to_radians();
        match sweep.kind {
            SweepKind::Around => {
                let (s, co) = (libm::sin(a), libm::cos(a));
                c + Vec3::new(co * v.x - s * v.y, s * v.x + co * v.y, v.z)
            }
            SweepKind::UpDown => c + v.length() * (libm::cos(a) * out + libm::sin(a) * Vec3::Z),
        }
    };
    let step = (hi - lo) / (rows - 1) as f64;
    let mut seats: Vec<(f64, Vec3)> = Vec::with_capacity(rows + 1);
    let mut current = None;
    for k in 0..rows {
        let angle = if k + 1 == rows {
            hi
        } else {
            lo + k as f64 * step
        };
        if current.is_none() && (angle - own).abs() < 1e-9 {
            current = Some(seats.len());
            seats.push((own, observer));
        } else {
            if current.is_none() && angle > own {
                current = Some(seats.len());
                seats.push((own, observer));
            }
            seats.push((angle, place(angle)));
        }
    }
    let current = current.unwrap_or_else(|| {
        seats.push((own, observer));
        seats.len() - 1
    });
    (seats, current)
}

/// Where `point` (on an object's surface, within [`SWEEP_POINT_TOLERANCE`]) appears from every
/// seat of `sweep` around `observer`, by each model; `seen_along`, the direction in which the
/// observer sees it if known (the picked ray's), chooses the light path followed from the
/// observer's seat. `None` if `stop` is set on the way.
pub fn sweep_apparent_until(
    setup: &Setup,
    observer: Vec3,
    point: Vec3,
    seen_along: Option<Vec3>,
    sweep: &Sweep,
    stop: &AtomicBool,
) -> Option<Vec<SweepRow>> {
    let world = &setup.world;
    let (seats, current) = sweep_seats(observer, sweep);
    let mut rows: Vec<Option<SweepRow>> = vec![None; seats.len()];
    let in_air = |eye: Vec3| {
        setup
            .description
            .check_observer(&Observer {
                position: eye,
                target: if eye == sweep.centre {
                    eye + Vec3::Z
                } else {
                    sweep.centre
                },
            })
            .is_ok()
    };
    // Outwards from the observer's seat, each way: each seat continues its neighbour's ray.
    let order = std::iter::once((current, None))
        .chain((current + 1..seats.len()).map(|k| (k, Some(k - 1))))
        .chain((0..current).rev().map(|k| (k, Some(k + 1))));
    for (k, before) in order {
        if stop.load(Ordering::Relaxed) {
            return None;
        }
        let (angle, eye) = seats[k];
        let sight = if !in_air(eye) {
            Sight::EyeInside
        } else {
            let previous = before
                .and_then(|b| rows[b].as_ref())
                .and_then(|r| Some((r.eye, r.seen()?.apparent.image.direction)));
            let hint = if k == current { seen_along } else { None };
            match find_ray(world, eye, point, previous, hint) {
                Some(u) => see(world, eye, u).map_or(Sight::NotSeen, Sight::Seen),
                None => Sight::NotSeen,
            }
        };
        rows[k] = Some(SweepRow {
            angle,
            eye,
            current: k == current,
            sight,
        });
    }
    Some(rows.into_iter().flatten().collect())
}

/// [`sweep_apparent_until`], never stopped.
pub fn sweep_apparent(
    setup: &Setup,
    observer: Vec3,
    point: Vec3,
    seen_along: Option<Vec3>,
    sweep: &Sweep,
) -> Vec<SweepRow> {
    sweep_apparent_until(
        setup,
        observer,
        point,
        seen_along,
        sweep,
        &AtomicBool::new(false),
    )
    .expect("never stopped")
}

/// The unit direction from `eye` whose ray reaches `q`: along the light path of the neighbouring
/// seat's ray (`previous`: its eye and direction) or of the ray along `hint`, else searched for.
fn find_ray(
    world: &World,
    eye: Vec3,
    q: Vec3,
    previous: Option<(Vec3, Vec3)>,
    hint: Option<Vec3>,
) -> Option<Vec3> {
    if let Some((from, u)) = previous {
        if let Some(path) = path_to(world, from, u, q) {
            let (e_h, e_v) = pupil_axes(u);
            let aim = Aim::new(world, path, u, e_h, e_v);
            if let Some(x) = aim.predict_and_follow(from, eye, [0.0; 2], [0.0; 2]) {
                return Some(aim.direction(x));
            }
        }
    }
    if let Some(u) = hint {
        // Kept as given when already unit: its numbers must be the readout's, to the bit.
        let u = if (u.length() - 1.0).abs() < 1e-12 {
            u
        } else {
            u.normalize()
        };
        // The picked ray itself, if it reaches the point: its numbers are the readout's.
        if world
            .light_path(eye, u)
            .is_some_and(|p| p.straw_point.distance(q) <= super::REACH_TOLERANCE)
        {
            return Some(u);
        }
        if let Some(found) = path_to(world, eye, u, q).and_then(|p| aim_along(world, eye, u, p)) {
            return Some(found);
        }
    }
    search(world, eye, q)
}

/// The light path of the ray from `eye` along `u`, re-targeted at `q`, if the ray reaches an
/// object (its sequence of faces is what matters: Newton's method then aims it at `q`).
fn path_to(world: &World, eye: Vec3, u: Vec3, q: Vec3) -> Option<LightPath> {
    let path = world.light_path(eye, u)?;
    Some(LightPath {
        straw_point: q,
        ..path
    })
}

/// The direction from `eye` that reaches `path`'s point along its faces, by Newton's method from
/// `u`, checked by tracing.
fn aim_along(world: &World, eye: Vec3, u: Vec3, path: LightPath) -> Option<Vec3> {
    let (e_h, e_v) = pupil_axes(u);
    let aim = Aim::new(world, path, u, e_h, e_v);
    let x = aim.solve(eye, [0.0; 2], &mut None)?;
    Some(aim.direction(x))
}

/// A ray from `eye` that reaches `q`, searched afresh: a grid of directions in a cone around the
/// straight line to `q` traced, and the [`SEARCH_TRIES`] whose straight pieces pass nearest `q`
/// re-aimed at it along their light paths up to that piece (the nearest first). A piece need not
/// end on an object: Newton's method only needs the faces met before it.
fn search(world: &World, eye: Vec3, q: Vec3) -> Option<Vec3> {
    let d0 = (q - eye).normalize();
    let (right, up) = pupil_axes(d0);
    let span = libm::tan(SEARCH_HALF_ANGLE);
    let mut best: [Option<(f64, Vec3, LightPath)>; SEARCH_TRIES] = [None; SEARCH_TRIES];
    for i in 0..SEARCH_GRID {
        for j in 0..SEARCH_GRID {
            let a = span * (2.0 * i as f64 / (SEARCH_GRID - 1) as f64 - 1.0);
            let b = span * (2.0 * j as f64 / (SEARCH_GRID - 1) as f64 - 1.0);
            let u = (d0 + a * right + b * up).normalize();
            let Some((miss, path)) = nearest_piece(world, eye, u, q) else {
                continue;
            };
            // Keep the nearest few, one per light path (the same path re-aimed gives one ray).
            let same = best
                .iter()
                .position(|c| matches!(c, Some((_, _, p)) if p.sequence == path.sequence && p.events == path.events));
            let slot = match same {
                Some(k) => best[k].is_some_and(|c| miss < c.0).then_some(k),
                None => best.iter().position(|c| c.is_none()).or_else(|| {
                    let (worst, m) = best
                        .iter()
                        .enumerate()
                        .map(|(k, c)| (k, c.map_or(f64::INFINITY, |c| c.0)))
                        .fold((0, f64::NEG_INFINITY), |a, b| if b.1 > a.1 { b } else { a });
                    (miss < m).then_some(worst)
                }),
            };
            if let Some(k) = slot {
                best[k] = Some((miss, u, path));
            }
        }
    }
    best.sort_by(|a, b| {
        let key = |c: &Option<(f64, Vec3, LightPath)>| c.map_or(f64::INFINITY, |c| c.0);
        key(a).total_cmp(&key(b))
    });
    best.iter()
        .flatten()
        .find_map(|&(_, u, path)| aim_along(world, eye, u, path))
}

/// The straight piece of the ray from `eye` along `u` that passes nearest `q` (with `q` beside
/// it, between its ends): how near (m), and the light path up to it, aimed at `q`.
fn nearest_piece(world: &World, eye: Vec3, u: Vec3, q: Vec3) -> Option<(f64, LightPath)> {
    let mut nearest: Option<(f64, LightPath)> = None;
    let mut consider = |from: Vec3, d: Vec3, length: f64, events: u32, sequence: u64| {
        let v = q - from;
        let along = v.dot(d);
        if along <= 0.0 || along > length {
            return;
        }
        let miss = (v - along * d).length();
        if nearest.as_ref().is_none_or(|n| miss < n.0) {
            nearest = Some((
                miss,
                LightPath {
                    straw_point: q,
                    events,
                    final_direction: d,
                    sequence,
                },
            ));
        }
    };
    let (mut from, mut d, mut events, mut sequence) = (eye, u, 0u32, EMPTY_SEQUENCE);
    let end = world.follow_events(
        Ray {
            origin: eye,
            direction: u,
        },
        |e| {
            consider(from, d, from.distance(e.point), events, sequence);
            sequence = extend_sequence(sequence, e.face, e.totally_reflected);
            events += 1;
            (from, d) = (e.point, e.outgoing);
        },
    );
    let length = end.map_or(f64::INFINITY, |(point, _)| from.distance(point));
    consider(from, d, length, events, sequence);
    nearest
}

/// What `eye` sees along `u` (a ray found to reach the point): the kind of path and each
/// model's point.
fn see(world: &World, eye: Vec3, u: Vec3) -> Option<SweepSight> {
    let ray = Ray {
        origin: eye,
        direction: u,
    };
    let (outcome, path) = world.trace_path_type(ray);
    let image: ImagePoint = outcome.image_point(eye, u)?;
    let apparent = world.apparent_point(eye, &image);
    let stereo = world.stereo_point(&StereoEyes::around(eye), eye, &image);
    Some(SweepSight {
        path,
        apparent,
        stereo,
    })
}

/// The point a sweep follows when none is picked, among `points` (image points of one view): the
/// middle one by height of those on the lowest colour code seen (for the assignment's glass, half
/// way up the part of the bottom section the observer sees, under water); `None` if there are none.
pub fn default_sweep_point(points: &[ImagePoint]) -> Option<ImagePoint> {
    let lowest = points.iter().map(|p| p.color).min()?;
    let mut on: Vec<&ImagePoint> = points.iter().filter(|p| p.color == lowest).collect();
    on.sort_by(|a, b| a.straw_point.z.total_cmp(&b.straw_point.z));
    on.get(on.len() / 2).map(|p| **p)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{REFERENCES, WATER_INDEX};
    use crate::setup::SceneValues;

    const N: f64 = WATER_INDEX;

    /// The coin in the glass: a coin on the glass's bottom, on its axis, under 10 cm of water.
    fn coin_in_glass() -> Setup {
        Setup::from_text(
            "coin-in-glass",
            include_str!("../../../../scenes/coin-in-glass.toml"),
            &SceneValues::default(),
        )
        .unwrap()
    }

    /// The middle of the coin's top face, and the water's height.
    fn coin_top(setup: &Setup) -> (Vec3, f64) {
        let coin = &setup.description.coins[0];
        let top = setup.description.liquids[0].top;
        let q = Vec3::new(coin.x, coin.y, coin.thickness);
        assert!(setup.world.distance_to_objects(q) < 1e-12);
        (q, top)
    }

    /// Seats: the grid's ends, the observer's own seat exactly once and exactly at the observer,
    /// every seat at the same distance from the centre (and, round the glass, at the same height).
    #[test]
    fn seats_keep_their_distance_and_hold_the_observer() {
        let observer = Vec3::new(0.1, 0.05, 0.3);
        let centre = Vec3::new(0.0, 0.0, 0.125);
        for kind in [SweepKind::Around, SweepKind::UpDown] {
            for rows in [2, 7, 61, 360] {
                let sweep = Sweep { kind, centre, rows };
                let (seats, k) = sweep_seats(observer, &sweep);
                assert_eq!(seats[k].1, observer);
                let (lo, hi) = kind.range();
                assert_eq!(seats[0].0, lo);
                assert_eq!(seats[seats.len() - 1].0, hi);
                assert!(seats.len() == rows || seats.len() == rows + 1);
                assert!(seats.windows(2).all(|w| w[0].0 < w[1].0));
                let r = observer.distance(centre);
                for (angle, eye) in &seats {
                    assert!((eye.distance(centre) - r).abs() < 1e-12, "{angle}");
                    if kind == SweepKind::Around {
                        assert!((eye.z - observer.z).abs() < 1e-15);
                    } else {
                        let up = libm::asin((eye.z - centre.z) / r).to_degrees();
                        assert!((up - angle).abs() < 1e-9, "{up} vs {angle}");
                    }
                }
            }
        }
    }

    /// A point on the glass's axis looks the same from every seat round the glass (the scene is
    /// a body of revolution about that axis): the same heights, foci and kind of path.
    #[test]
    fn a_point_on_the_axis_looks_the_same_from_every_seat_round_the_glass() {
        let setup = coin_in_glass();
        let (q, _) = coin_top(&setup);
        let sweep = Sweep {
            kind: SweepKind::Around,
            centre: Vec3::new(0.0, 0.0, 0.0),
            rows: 25,
        };
        let rows = sweep_apparent(&setup, setup.observer, q, None, &sweep);
        let own = rows.iter().find(|r| r.current).unwrap().seen().unwrap();
        for r in &rows {
            let s = r.seen().expect("seen from every seat");
            assert_eq!(s.path, own.path);
            let h = |s: &SweepSight, eye| s.horizontal_focus(eye).unwrap().z;
            let v = |s: &SweepSight, eye| s.vertical_focus(eye).unwrap().z;
            let o = setup.observer;
            assert!((s.course_point().z - own.course_point().z).abs() < 1e-9);
            assert!((h(s, r.eye) - h(own, o)).abs() < 1e-9);
            assert!((v(s, r.eye) - v(own, o)).abs() < 1e-9);
            assert!((s.stereo_point().unwrap().z - own.stereo_point().unwrap().z).abs() < 1e-6);
        }
    }

    /// Up and down over the coin: wherever the coin is seen through the flat surface, the
    /// course's point and the eye model's two foci are the closed forms of refraction at a plane
    /// (the point at depth `d`, the line of sight at `θ` in air, `θ'` in the water, `L` from the
    /// eye to the surface): course `L + d/cos θ'`, horizontal (sagittal) `L + d/(n cos θ')`,
    /// vertical (tangential) `L + d cos²θ/(n cos³θ')`; straight above, all three models give the
    /// apparent depth `d/n`. The lines of sight obey Snell's law, checked here independently.
    #[test]
    fn over_a_flat_surface_the_foci_are_the_closed_forms_and_straight_above_d_over_n() {
        let setup = coin_in_glass();
        let (q, top) = coin_top(&setup);
        let d = top - q.z;
        let sweep = Sweep {
            kind: SweepKind::UpDown,
            centre: q,
            rows: 61,
        };
        // From straight above (the coin is also seen through the wall, by another path: the
        // sweep follows the one it starts on).
        let above = q + setup.observer.distance(q) * Vec3::Z;
        let rows = sweep_apparent(&setup, above, q, None, &sweep);
        let mut through_surface = 0;
        for r in &rows {
            let Some(s) = r.seen() else { continue };
            if s.path.key() != "top" {
                continue;
            }
            through_surface += 1;
            let u = s.apparent.image.direction;
            let cos_air = -u.z;
            let sin_air = (1.0 - cos_air * cos_air).max(0.0).sqrt();
            let sin_w = sin_air / N;
            let cos_w = (1.0 - sin_w * sin_w).sqrt();
            let l = (r.eye.z - top) / cos_air;
            // The ray through the surface point, refracted by Snell's law, reaches q.
            let exit = r.eye + l * u;
            let horizontal = Vec3::new(u.x, u.y, 0.0).normalize_or_zero();
            let under = exit + (d / cos_w) * (sin_w * horizontal - cos_w * Vec3::Z);
            assert!(under.distance(q) < 1e-9, "{}: {under:?}", r.angle);
            let course = l + d / cos_w;
            let sagittal = l + d / (N * cos_w);
            let tangential = l + d * cos_air * cos_air / (N * cos_w.powi(3));
            let im = &s.apparent.image;
            assert!((im.path_length - course).abs() < 1e-9, "{}", r.angle);
            let sh = s.apparent.s_h.distance().unwrap();
            let sv = s.apparent.s_v.distance().unwrap();
            assert!(
                (sh - sagittal).abs() < 1e-9,
                "{}: {sh} vs {sagittal}",
                r.angle
            );
            assert!(
                (sv - tangential).abs() < 1e-9,
                "{}: {sv} vs {tangential}",
                r.angle
            );
            if r.angle == 90.0 {
                let depth = top - d / N;
                assert!(
                    (s.course_point().z - q.z).abs() < 1e-12,
                    "course: the real depth"
                );
                assert!((s.horizontal_focus(r.eye).unwrap().z - depth).abs() < 1e-12);
                assert!((s.vertical_focus(r.eye).unwrap().z - depth).abs() < 1e-12);
                let stereo = s.stereo_point().unwrap().z;
                // Paraxial: the eyes 6.5 cm apart see it at a small angle.
                assert!((stereo - depth).abs() < 2e-3 * d, "{stereo} vs {depth}");
            }
        }
        // Over the rim of the glass only: from about 68° up (every 3°).
        assert!(through_surface >= 7, "{through_surface}");
        assert!(rows
            .iter()
            .any(|r| r.seen().is_some_and(|s| s.path.key() == "wall")));
        assert!(rows.iter().any(|r| r.angle == 90.0 && r.seen().is_some()));
        // Straight below, the coin hides its own top: not seen, not a failure.
        assert!(rows[0].seen().is_none());
    }

    /// From a seat inside the glass no eye can look: such a row says so.
    #[test]
    fn seats_inside_the_glass_are_marked_and_not_seen_points_are_rows() {
        let r = REFERENCES[1];
        let setup = Setup::assignment(r.scene(N), r.observer);
        let image = setup
            .world
            .image_point(
                r.observer,
                (Vec3::new(0.02, 0.01, 0.05) - r.observer).normalize(),
            )
            .unwrap();
        // Turning about a centre beside the glass carries the eye through it.
        let sweep = Sweep {
            kind: SweepKind::Around,
            centre: Vec3::new(0.06, 0.0, 0.1),
            rows: 37,
        };
        let rows = sweep_apparent(
            &setup,
            r.observer,
            image.straw_point,
            Some(image.direction),
            &sweep,
        );
        assert!(rows.iter().any(|r| r.sight == Sight::EyeInside));
        let own = rows.iter().find(|r| r.current).unwrap();
        // The observer's seat gives the picked ray's numbers.
        let s = own.seen().unwrap();
        assert_eq!(s.apparent.image, image);
        assert_eq!(s.apparent, setup.world.apparent_point(r.observer, &image));
    }

    /// The observer's seat, with the picked ray's direction, gives that ray's own numbers; the
    /// seats near it see the point too, along the same path; a stopped sweep gives nothing.
    #[test]
    fn the_observers_seat_gives_the_picked_rays_numbers() {
        for r in REFERENCES {
            let setup = Setup::assignment(r.scene(N), r.observer);
            let cloud = crate::sampling::sample_image(&setup.world, r.observer, 400, &|_| {});
            let p = default_sweep_point(&cloud.points).unwrap();
            for kind in [SweepKind::Around, SweepKind::UpDown] {
                let sweep = Sweep {
                    kind,
                    centre: crate::scene::SCENE_CENTRE,
                    rows: 61,
                };
                let rows =
                    sweep_apparent(&setup, r.observer, p.straw_point, Some(p.direction), &sweep);
                let k = rows.iter().position(|r| r.current).unwrap();
                let s = rows[k].seen().unwrap();
                assert_eq!(s.apparent.image, p, "reference {}", r.number);
                let seen = rows.iter().filter(|r| r.seen().is_some()).count();
                assert!(seen >= 5, "reference {} {kind:?}: {seen}", r.number);
                for row in rows.iter().filter_map(|r| r.seen()) {
                    assert!(row.apparent.image.straw_point.distance(p.straw_point) < 1e-9);
                }
                let stop = AtomicBool::new(true);
                assert!(sweep_apparent_until(
                    &setup,
                    r.observer,
                    p.straw_point,
                    None,
                    &sweep,
                    &stop
                )
                .is_none());
            }
        }
    }
}
