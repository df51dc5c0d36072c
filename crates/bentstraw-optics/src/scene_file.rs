//! Scene files: a scene written as data (TOML), read into a plain description and checked against
//! every rule before anything is traced.
//!
//! The format (lengths in metres, angles in degrees): a `[container]` (a glass, an upright
//! cylinder, or a tank, a rectangular box), `[[liquid]]` layers bottom first, `[[straw]]`s,
//! `[[coin]]`s lying on the floor, upright `[[card]]`s, and an optional `[observer]`. The module
//! takes the file's text and does no I/O. Every refusal names the key as a TOML path (`straw[2].tilt`,
//! counting from 1 as the file lists them), the value, and the rule.

use std::fmt;

use crate::dispersion::Dispersion;
use crate::profile::{self, Piece};
use crate::rule::{self, number, point, Param, Params, Rule};
use crate::scene::{
    is_physical_index, Scene, DEFAULT_MAX_EVENTS, GLASS_HEIGHT, GLASS_RADIUS, STRAW_HEIGHT,
    STRAW_RADIUS, WATER_INDEX,
};
use crate::text::number_text;
use crate::Vec3;

#[cfg(feature = "scene-file")]
mod format;
#[cfg(feature = "scene-file")]
pub use format::SceneForm;

/// A container's index when the file gives none (ordinary glass).
pub const DEFAULT_CONTAINER_INDEX: f64 = 1.5;
/// A coin's radius when the file gives none (a one-euro coin).
pub const DEFAULT_COIN_RADIUS: f64 = 0.0115;
/// A coin's thickness when the file gives none.
pub const DEFAULT_COIN_THICKNESS: f64 = 0.0019;
/// The largest size (m) of a container, straw or coin that does not look like centimetres
/// written as metres ([`SceneDescription::hints`]): bigger than any tabletop demonstration.
pub const LARGEST_LIKELY_SIZE: f64 = 1.0;
/// Most liquid layers a file may list: every ray is tested against each layer's faces, so this
/// bounds the time a picture takes.
pub const MAX_LIQUIDS: usize = 32;
/// Most objects (straws, coins and cards together) a file may list: every ray is tested against
/// each, and the overlap checks compare pairs, so this bounds the time a file takes to check and
/// to trace (seconds, not hours).
pub const MAX_OBJECTS: usize = 100;
/// Smallest size (m) of anything in a scene, a micrometre: below it, squared sizes lose their
/// precision and objects vanish from the rays that should meet them.
pub const MIN_SIZE: f64 = 1e-6;
pub use crate::scene::MAX_LENGTH;
/// Smallest tilt (degrees) of a leaning straw: a straw tilted less is upright to within a
/// nanometre over its length, and is written `tilt = 0`.
pub const MIN_TILT_DEG: f64 = 1e-6;
/// Points around a tilted straw's circumference where its extent is measured: the extent found
/// is short of the true one by at most `radius·(1 − cos(π/N))`, about 1.5 nm for a 5 mm straw.
const RIM_SAMPLES: usize = 4096;

/// Why a scene file is not valid: every rule it breaks, each a line naming the key, the value
/// and the rule (the rules that do not depend on one another are all checked, so that a file is
/// mended in one go). Each is data too: the [`Rule`] (its stable code), the key, the value and
/// the rule's parameters, so that a page can say it in its own language. The checks return it
/// boxed: a refusal is large, and a `Result` carrying it whole would be as large when it passes.
#[derive(Clone, Debug, PartialEq)]
pub struct SceneFileError {
    /// The first broken rule's key as a TOML path (`straw[2].tilt`), empty when the text is not
    /// TOML at all.
    pub key: String,
    /// The line of the file where TOML's parser stopped, for errors of syntax and type.
    pub line: Option<usize>,
    /// The first broken rule's message.
    pub message: String,
    /// The first broken rule.
    pub rule: Rule,
    /// The value refused, as the message quotes it, when the rule is about one number.
    pub value: Option<String>,
    /// The rule's parameters (its bounds, the positions and sizes it compares).
    pub params: Params,
    /// The other broken rules, in the file's order.
    pub more: Vec<SceneFileError>,
}

impl SceneFileError {
    /// Every broken rule, the first included.
    pub fn rules(&self) -> impl Iterator<Item = &SceneFileError> {
        std::iter::once(self).chain(&self.more)
    }

    /// One error of the broken rules `all` (at least one).
    fn all(mut all: Vec<SceneFileError>) -> Option<Box<SceneFileError>> {
        if all.is_empty() {
            return None;
        }
        let more: Vec<SceneFileError> = all.drain(1..).flat_map(|e| e.into_rules()).collect();
        let mut first = all.pop()?;
        first.more.extend(more);
        Some(Box::new(first))
    }

    /// The broken rules, each on its own.
    fn into_rules(mut self) -> Vec<SceneFileError> {
        let more = std::mem::take(&mut self.more);
        std::iter::once(self).chain(more).collect()
    }
}

/// The broken rules found by checks that do not depend on one another.
#[derive(Default)]
struct Broken(Vec<SceneFileError>);

impl Broken {
    /// Keeps `check`'s refusal, if any; says whether it passed.
    fn check(&mut self, check: Result<(), Box<SceneFileError>>) -> bool {
        match check {
            Ok(()) => true,
            Err(e) => {
                self.0.push(*e);
                false
            }
        }
    }

    /// `Ok` when nothing is broken, else every broken rule.
    fn done(self) -> Result<(), Box<SceneFileError>> {
        SceneFileError::all(self.0).map_or(Ok(()), Err)
    }
}

impl fmt::Display for SceneFileError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.more.is_empty() {
            return f.write_str(&self.message);
        }
        write!(f, "{} rules are broken:", 1 + self.more.len())?;
        for e in self.rules() {
            write!(f, "\n  {}", e.message)?;
        }
        Ok(())
    }
}

impl std::error::Error for SceneFileError {}

impl SceneFileError {
    /// The refusal of `key` (of value `value`, if the rule is about one number) by `rule` with
    /// its parameters `params`, its message the rule's English line.
    pub fn new(key: &str, value: Option<f64>, rule: Rule, params: Params) -> SceneFileError {
        let value = value.map(number_text);
        SceneFileError {
            key: key.to_string(),
            line: None,
            message: rule::line(rule, key, value.as_deref(), &params),
            rule,
            value,
            params,
            more: Vec::new(),
        }
    }
}

/// The refusal of `key = value` by `rule`.
fn refuse(key: &str, value: f64, rule: Rule, params: Params) -> Box<SceneFileError> {
    Box::new(SceneFileError::new(key, Some(value), rule, params))
}

/// The refusal of `key` without a single number to quote.
fn refuse_key(key: &str, rule: Rule, params: Params) -> Box<SceneFileError> {
    Box::new(SceneFileError::new(key, None, rule, params))
}

/// A parameter of words quoted as they are.
fn words(text: impl Into<String>) -> Param {
    Param::Text(text.into())
}

/// A bound written as the messages always wrote it (`{}`: `0.000001`, not `1e-6`).
fn bound(x: f64) -> Param {
    Param::Number(x.to_string())
}

/// The container: a glass, a tank or a container of revolution.
#[derive(Clone, Debug, PartialEq)]
pub enum Container {
    /// An upright cylinder.
    Glass(Glass),
    /// A rectangular box with walls of zero thickness.
    Tank(Tank),
    /// A glass of any profile turned about the `z` axis (a tapered tumbler, a wine glass).
    Revolution(Revolution),
}

/// A glass of revolution about the `z` axis, standing with its base on `z = 0`: its wall between
/// two profiles `[r, z]`, each smooth through its points (see [`crate::profile`]).
#[derive(Clone, Debug, PartialEq)]
pub struct Revolution {
    /// The outer profile, from the base (`z = 0`) to the rim, `z` rising (m).
    pub outer: Vec<[f64; 2]>,
    /// The inner profile, from the floor to the rim, `z` rising (m).
    pub inner: Vec<[f64; 2]>,
    /// Refractive index of the glass itself.
    pub index: f64,
}

/// Most points a profile may have: each makes one or two faces every ray is tested against.
pub const MAX_PROFILE_POINTS: usize = 32;

impl Revolution {
    /// The outer surface's pieces.
    pub fn outer_pieces(&self) -> Vec<Piece> {
        profile::pieces(&self.outer)
    }

    /// The inner surface's pieces.
    pub fn inner_pieces(&self) -> Vec<Piece> {
        profile::pieces(&self.inner)
    }

    /// The greatest outer radius (m): the cylinder about the axis that holds it.
    pub fn reach(&self) -> f64 {
        profile::radius_range(&self.outer_pieces(), f64::NEG_INFINITY, f64::INFINITY)
            .map_or(0.0, |(_, most)| most)
    }

    /// The least inner radius between heights `lo` and `hi` (the part of them below the rim):
    /// what an object spanning them must fit in.
    fn narrowest(&self, lo: f64, hi: f64) -> f64 {
        let rim = self.outer.last().map_or(0.0, |p| p[1]);
        if lo > rim {
            return f64::INFINITY;
        }
        profile::radius_range(&self.inner_pieces(), lo, hi.min(rim)).map_or(0.0, |(least, _)| least)
    }
}

/// An upright cylindrical glass standing with its outer base on `z = 0`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Glass {
    /// Outer radius (m).
    pub radius: f64,
    /// The walls' height above the outer base (m).
    pub height: f64,
    /// Wall thickness (m).
    pub wall: f64,
    /// Bottom thickness (m): the floor inside is at `z = bottom`.
    pub bottom: f64,
    /// Refractive index of the glass itself.
    pub index: f64,
}

/// A rectangular tank centred on the `z` axis, its floor on `z = 0`, walls of zero thickness.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Tank {
    /// Half width along `x` (m).
    pub half_x: f64,
    /// Half width along `y` (m).
    pub half_y: f64,
    /// The walls' height (m).
    pub height: f64,
}

impl Container {
    /// Height of the floor inside, where liquids start and objects rest (m).
    pub fn floor(&self) -> f64 {
        match self {
            Container::Glass(g) => g.bottom,
            Container::Tank(_) => 0.0,
            Container::Revolution(v) => v.inner.first().map_or(0.0, |p| p[1]),
        }
    }

    /// The walls' height (m).
    pub fn height(&self) -> f64 {
        match self {
            Container::Glass(g) => g.height,
            Container::Tank(t) => t.height,
            Container::Revolution(v) => v.outer.last().map_or(0.0, |p| p[1]),
        }
    }

    /// The radius of the cylinder about the `z` axis that holds the container (for a tank, the
    /// one through its corners).
    pub fn reach(&self) -> f64 {
        match self {
            Container::Glass(g) => g.radius,
            Container::Tank(t) => libm::hypot(t.half_x, t.half_y),
            Container::Revolution(v) => v.reach(),
        }
    }

    /// Whether the point `(x, y, z)` lies on or inside the walls' inner face.
    fn holds(&self, x: f64, y: f64, z: f64) -> bool {
        self.holds_disk(x, y, 0.0, z, z)
    }

    /// Whether the segment from `a` to `b` lies on or inside the walls' inner face: its ends for
    /// a glass or a tank (whose inside is convex); points along it every 1/64 of its length
    /// for a container of revolution, whose inner face may bend inwards.
    fn holds_line(&self, a: Vec3, b: Vec3) -> bool {
        let steps = if matches!(self, Container::Revolution(_)) {
            64
        } else {
            1
        };
        (0..=steps).all(|k| {
            let p = a.lerp(b, k as f64 / steps as f64);
            self.holds(p.x, p.y, p.z)
        })
    }

    /// Whether the ball of `centre` and `radius` lies inside the walls' inner face: its
    /// horizontal circle at each of 129 heights across it for a container of revolution (a
    /// marble resting in a cone touches the wall above its lowest point), its widest circle
    /// for a glass or a tank.
    fn holds_ball(&self, centre: Vec3, radius: f64) -> bool {
        let Container::Revolution(v) = self else {
            return self.holds_disk(centre.x, centre.y, radius, centre.z, centre.z);
        };
        let (inner, rim, off) = (
            v.inner_pieces(),
            self.height(),
            libm::hypot(centre.x, centre.y),
        );
        (0..=128).all(|k| {
            let s = -1.0 + 2.0 * k as f64 / 128.0;
            let z = centre.z + s * radius;
            let half = radius * (1.0 - s * s).max(0.0).sqrt();
            // (A ball resting on the floor may reach a hair below it by rounding.)
            let z = z.max(v.inner[0][1]);
            z > rim || profile::radius_at(&inner, z).is_some_and(|r| off + half <= r)
        })
    }

    /// Whether a horizontal disk of `radius` about `(x, y)`, at every height from `lo` to `hi`,
    /// lies inside the walls' inner face.
    fn holds_disk(&self, x: f64, y: f64, radius: f64, lo: f64, hi: f64) -> bool {
        match self {
            // Computed as the assignment's scene computes its straw's fit, so that the two
            // agree to the last bit on its glass.
            Container::Glass(g) => (x * x + y * y).sqrt() + radius <= g.radius - g.wall,
            Container::Tank(t) => x.abs() + radius <= t.half_x && y.abs() + radius <= t.half_y,
            Container::Revolution(v) => libm::hypot(x, y) + radius <= v.narrowest(lo, hi),
        }
    }

    /// Whether the point `p` is inside or on the container's outer surface.
    fn encloses(&self, p: Vec3) -> bool {
        let within_height = (0.0..=self.height()).contains(&p.z);
        within_height
            && match self {
                Container::Glass(g) => p.x * p.x + p.y * p.y <= g.radius * g.radius,
                Container::Tank(t) => p.x.abs() <= t.half_x && p.y.abs() <= t.half_y,
                Container::Revolution(v) => profile::radius_at(&v.outer_pieces(), p.z)
                    .is_some_and(|r| libm::hypot(p.x, p.y) <= r),
            }
    }

    /// Distance (m) from `p` to the container's solid (its walls, floor and the space they
    /// enclose, up to the rim): 0 inside it.
    fn distance_to(&self, p: Vec3) -> f64 {
        let dz = (-p.z).max(p.z - self.height()).max(0.0);
        let across = match self {
            // A container of revolution is taken as the cylinder that holds it.
            Container::Glass(_) | Container::Revolution(_) => {
                (libm::hypot(p.x, p.y) - self.reach()).max(0.0)
            }
            Container::Tank(t) => libm::hypot(
                (p.x.abs() - t.half_x).max(0.0),
                (p.y.abs() - t.half_y).max(0.0),
            ),
        };
        libm::hypot(across, dz)
    }

    /// Whether prism `p` stays clear of the container's solid (its walls, floor and the space
    /// they enclose, up to the rim): apart in height, or apart seen from above.
    fn distance_to_prism(&self, p: &Prism) -> f64 {
        let above_or_below = (p.bottom - self.height()).max(-p.top);
        if above_or_below > 0.0 {
            return above_or_below;
        }
        let c = p.counterclockwise();
        match self {
            Container::Glass(_) | Container::Revolution(_) => {
                let radius = self.reach();
                if convex_contains(&c, (0.0, 0.0)) {
                    -radius
                } else {
                    let hull: Vec<(f64, f64)> = c.iter().map(|q| (q[0], q[1])).collect();
                    distance_to_hull((0.0, 0.0), &hull) - radius
                }
            }
            Container::Tank(t) => {
                let rect = [
                    [-t.half_x, -t.half_y],
                    [t.half_x, -t.half_y],
                    [t.half_x, t.half_y],
                    [-t.half_x, t.half_y],
                ];
                convex_gap(&c, &rect)
            }
        }
    }

    /// Whether the horizontal segment from `a` to `b` passes through the container's outline
    /// seen from above (touching it is allowed).
    fn crossed_by(&self, a: (f64, f64), b: (f64, f64)) -> bool {
        match self {
            Container::Glass(_) | Container::Revolution(_) => {
                segment_distance_to_origin(a, b) < self.reach()
            }
            Container::Tank(t) => segment_enters_box(a, b, t.half_x, t.half_y),
        }
    }
}

/// Distance (m) from `p` to the segment `a`–`b` of positive length.
fn point_segment_distance(p: Vec3, a: Vec3, b: Vec3) -> f64 {
    let d = b - a;
    let s = ((p - a).dot(d) / d.length_squared()).clamp(0.0, 1.0);
    (a + s * d - p).length()
}

/// Distance (m) from `p` to coin `c` lying on the floor at `floor` (a solid disk): 0 inside it.
fn distance_to_disk_solid(p: Vec3, c: &Coin, floor: f64) -> f64 {
    let across = (libm::hypot(p.x - c.x, p.y - c.y) - c.radius).max(0.0);
    let up = (floor - p.z).max(p.z - (floor + c.thickness)).max(0.0);
    libm::hypot(across, up)
}

/// Distance (m) from `p` to the flat rectangle of `corners` (in order round it): 0 on it.
fn distance_to_rectangle(p: Vec3, corners: &[Vec3; 4]) -> f64 {
    let (o, u, v) = (corners[0], corners[1] - corners[0], corners[3] - corners[0]);
    let w = p - o;
    let s = (w.dot(u) / u.length_squared()).clamp(0.0, 1.0);
    let t = (w.dot(v) / v.length_squared()).clamp(0.0, 1.0);
    (o + s * u + t * v - p).length()
}

/// Distance from the origin to the segment `a`–`b` in the plane.
fn segment_distance_to_origin(a: (f64, f64), b: (f64, f64)) -> f64 {
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    let len2 = dx * dx + dy * dy;
    let s = if len2 > 0.0 {
        (-(a.0 * dx + a.1 * dy) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    libm::hypot(a.0 + s * dx, a.1 + s * dy)
}

/// Whether the segment `a`–`b` has points strictly inside `|x| < hx, |y| < hy` (Liang–Barsky).
fn segment_enters_box(a: (f64, f64), b: (f64, f64), hx: f64, hy: f64) -> bool {
    let (mut t0, mut t1) = (0.0f64, 1.0f64);
    for (p, d, h) in [(a.0, b.0 - a.0, hx), (a.1, b.1 - a.1, hy)] {
        if d == 0.0 {
            if p.abs() >= h {
                return false;
            }
        } else {
            let (u, v) = ((-h - p) / d, (h - p) / d);
            t0 = t0.max(u.min(v));
            t1 = t1.min(u.max(v));
        }
    }
    t0 < t1
}

/// The shortest distance between the segments `p1`–`q1` and `p2`–`q2`, both of positive length
/// (the closest points' parameters, clamped to the segments in turn).
fn segment_distance(p1: Vec3, q1: Vec3, p2: Vec3, q2: Vec3) -> f64 {
    let (d1, d2, r) = (q1 - p1, q2 - p2, p1 - p2);
    let (a, b, c) = (d1.dot(d1), d1.dot(d2), d1.dot(r));
    let (e, f) = (d2.dot(d2), d2.dot(r));
    let denom = a * e - b * b;
    // Parallel axes: any point of the first will do before the clamping below.
    let mut s = if denom > 0.0 {
        ((b * f - c * e) / denom).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let mut t = (b * s + f) / e;
    if t < 0.0 {
        t = 0.0;
        s = (-c / a).clamp(0.0, 1.0);
    } else if t > 1.0 {
        t = 1.0;
        s = ((b - c) / a).clamp(0.0, 1.0);
    }
    ((p1 + s * d1) - (p2 + t * d2)).length()
}

/// Distance from `p` to the convex hull of `points` in the plane (0 inside it).
fn distance_to_hull(p: (f64, f64), points: &[(f64, f64)]) -> f64 {
    let cross = |o: (f64, f64), a: (f64, f64), b: (f64, f64)| {
        (a.0 - o.0) * (b.1 - o.1) - (a.1 - o.1) * (b.0 - o.0)
    };
    // Andrew's monotone chain: the hull counter-clockwise.
    let mut sorted = points.to_vec();
    sorted.sort_by(|a, b| a.partial_cmp(b).expect("finite points"));
    sorted.dedup();
    if sorted.is_empty() {
        return f64::INFINITY;
    }
    let mut hull: Vec<(f64, f64)> = Vec::with_capacity(sorted.len() + 1);
    for pass in 0..2 {
        let start = hull.len();
        let ordered: Box<dyn Iterator<Item = &(f64, f64)>> = if pass == 0 {
            Box::new(sorted.iter())
        } else {
            Box::new(sorted.iter().rev())
        };
        for &q in ordered {
            while hull.len() >= start + 2
                && cross(hull[hull.len() - 2], hull[hull.len() - 1], q) <= 0.0
            {
                hull.pop();
            }
            hull.push(q);
        }
        hull.pop();
    }
    if hull.is_empty() {
        hull.push(sorted[0]);
    }
    let n = hull.len();
    let edge = |k: usize| (hull[k], hull[(k + 1) % n]);
    if n >= 3
        && (0..n).all(|k| {
            let (a, b) = edge(k);
            cross(a, b, p) >= 0.0
        })
    {
        return 0.0;
    }
    (0..n)
        .map(|k| {
            let (a, b) = edge(k);
            segment_distance_to_origin((a.0 - p.0, a.1 - p.1), (b.0 - p.0, b.1 - p.1))
        })
        .fold(f64::INFINITY, f64::min)
}

/// One layer of liquid, filling the inside from the layer below (or the floor) up to `top`.
#[derive(Clone, Debug, PartialEq)]
pub struct Liquid {
    /// What it is, for people ("water", "oil").
    pub name: String,
    /// Its refractive index.
    pub index: f64,
    /// Height of its free surface above `z = 0` (m).
    pub top: f64,
    /// The colour white light takes through [`TINT_DEPTH`] of it (sRGB), or `None` for a clear
    /// liquid: light is absorbed along its path inside by the Beer–Lambert law.
    pub tint: Option<[u8; 3]>,
}

/// The depth of liquid through which white light takes a liquid's tint (m).
pub const TINT_DEPTH: f64 = 0.10;

impl Liquid {
    /// Its absorption coefficient per metre in each of the red, green and blue channels (linear
    /// light): white light through a depth `L` keeps `exp(−α·L)` of each channel, so that
    /// [`TINT_DEPTH`] gives its tint. A channel written 0 absorbs all but a millionth per tint depth.
    pub fn absorption(&self) -> Option<[f64; 3]> {
        self.tint.map(|rgb| {
            rgb.map(|c| {
                let kept = crate::shading::srgb_to_linear(c as f64 / 255.0).max(1e-6);
                -kept.ln() / TINT_DEPTH
            })
        })
    }
}

/// A five-colour straw resting on the floor, possibly leaning.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Straw {
    /// Its bottom cap's centre stands above this `x` (m).
    pub x: f64,
    /// Its bottom cap's centre stands above this `y` (m).
    pub y: f64,
    /// Angle of its axis from the vertical (degrees).
    pub tilt_deg: f64,
    /// Direction its top leans toward, from `+x` towards `+y` (degrees).
    pub azimuth_deg: f64,
    /// Radius (m).
    pub radius: f64,
    /// Length along its axis (m).
    pub length: f64,
}

impl Straw {
    /// Unit vector along its axis, bottom to top: `(sin t cos a, sin t sin a, cos t)`.
    pub fn axis(&self) -> Vec3 {
        let (t, a) = (self.tilt_deg.to_radians(), self.azimuth_deg.to_radians());
        Vec3::new(
            libm::sin(t) * libm::cos(a),
            libm::sin(t) * libm::sin(a),
            libm::cos(t),
        )
    }

    /// Its bottom cap's centre when it rests on a floor at height `floor`: the cap's rim touches
    /// the floor at its lowest point, so the centre is `radius·sin(tilt)` above it.
    pub fn bottom_centre(&self, floor: f64) -> Vec3 {
        let t = self.tilt_deg.to_radians();
        Vec3::new(self.x, self.y, floor + self.radius * libm::sin(t))
    }

    /// The unit vector in the bottom cap's plane pointing most steeply down (towards the lean).
    fn downhill(&self) -> Vec3 {
        let (t, a) = (self.tilt_deg.to_radians(), self.azimuth_deg.to_radians());
        Vec3::new(
            libm::cos(t) * libm::cos(a),
            libm::cos(t) * libm::sin(a),
            -libm::sin(t),
        )
    }

    /// The point where it touches the floor: the lowest point of its bottom cap's rim.
    pub fn foot(&self, floor: f64) -> Vec3 {
        self.bottom_centre(floor) + self.radius * self.downhill()
    }

    /// The lines of its side, around its circumference, between the floor and the height
    /// `z_top`: from the bottom cap's rim to where the line reaches `z_top` or the top cap's
    /// rim. Along each the horizontal position moves linearly, so any convex measure of extent
    /// (a distance from the glass's axis, a coordinate) is largest at its ends.
    fn outline_below(&self, floor: f64, z_top: f64) -> impl Iterator<Item = [Vec3; 2]> + '_ {
        let c = self.bottom_centre(floor);
        let axis = self.axis();
        let e1 = self.downhill();
        let e2 = Vec3::new(
            -libm::sin(self.azimuth_deg.to_radians()),
            libm::cos(self.azimuth_deg.to_radians()),
            0.0,
        );
        (0..RIM_SAMPLES).filter_map(move |k| {
            let phi = std::f64::consts::TAU * k as f64 / RIM_SAMPLES as f64;
            let rim = c + self.radius * (libm::cos(phi) * e1 + libm::sin(phi) * e2);
            let s_top = ((z_top - rim.z) / axis.z).min(self.length);
            (rim.z <= z_top).then(|| [rim, rim + s_top * axis])
        })
    }

    /// Whether the point `p` is inside or on the straw resting on `floor`.
    fn contains(&self, floor: f64, p: Vec3) -> bool {
        let d = p - self.bottom_centre(floor);
        let s = d.dot(self.axis());
        (0.0..=self.length).contains(&s) && (d - s * self.axis()).length() <= self.radius
    }
}

/// A coin lying flat on the floor (colour code 6).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Coin {
    /// Centre, `x` (m).
    pub x: f64,
    /// Centre, `y` (m).
    pub y: f64,
    /// Radius (m).
    pub radius: f64,
    /// Thickness (m).
    pub thickness: f64,
}

/// What is drawn on a card's front.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Picture {
    /// An arrow pointing to the card's right (colour code 8).
    Arrow,
    /// Nothing: a plain card.
    None,
}

impl Picture {
    /// The word the file uses for it.
    pub fn word(&self) -> &'static str {
        match self {
            Picture::Arrow => "arrow",
            Picture::None => "none",
        }
    }
}

/// An upright opaque card (colour code 7), a rectangle in a vertical plane.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Card {
    /// Its centre (m).
    pub center: Vec3,
    /// Azimuth of the direction its front faces (degrees).
    pub facing_deg: f64,
    /// Width (m).
    pub width: f64,
    /// Height (m).
    pub height: f64,
    /// What its front shows.
    pub picture: Picture,
}

impl Card {
    /// Whether the point `p` lies on the card (within a nanometre of its plane, inside its
    /// edges): an eye there would see from inside the card.
    fn touches(&self, p: Vec3) -> bool {
        let f = self.facing_deg.to_radians();
        let (front, right) = (
            Vec3::new(libm::cos(f), libm::sin(f), 0.0),
            Vec3::new(-libm::sin(f), libm::cos(f), 0.0),
        );
        let d = p - self.center;
        d.dot(front).abs() <= 1e-9
            && d.dot(right).abs() <= self.width / 2.0
            && d.z.abs() <= self.height / 2.0
    }

    /// The horizontal ends of its bottom edge: left and right as seen from its front.
    /// Its four corners, in order round it.
    fn corners(&self) -> [Vec3; 4] {
        let ((ax, ay), (bx, by)) = self.ends();
        let (lo, hi) = (
            self.center.z - self.height / 2.0,
            self.center.z + self.height / 2.0,
        );
        [
            Vec3::new(ax, ay, lo),
            Vec3::new(bx, by, lo),
            Vec3::new(bx, by, hi),
            Vec3::new(ax, ay, hi),
        ]
    }

    fn ends(&self) -> ((f64, f64), (f64, f64)) {
        let f = self.facing_deg.to_radians();
        // To the right of someone facing the card's front, who looks along −(cos f, sin f).
        let (ux, uy) = (-libm::sin(f), libm::cos(f));
        let h = self.width / 2.0;
        (
            (self.center.x - h * ux, self.center.y - h * uy),
            (self.center.x + h * ux, self.center.y + h * uy),
        )
    }
}

/// A transparent ball of its own index: a marble, a bowl of water, a drop. Light refracts where
/// it enters and leaves; what is around it is whatever fills that place without it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sphere {
    /// Its centre (m).
    pub center: Vec3,
    /// Its radius (m).
    pub radius: f64,
    /// Its refractive index.
    pub index: f64,
}

impl Sphere {
    /// Whether it stands inside `container`, above the floor (a valid sphere that does not
    /// stands wholly outside it).
    pub fn inside(&self, container: &Container) -> bool {
        let c = self.center;
        // A ball resting on the floor, its centre written as floor + radius, may land a hair
        // below by rounding: it still rests on it.
        let rounding = 8.0 * f64::EPSILON * (c.z.abs() + self.radius);
        container.holds_ball(c, self.radius) && c.z - self.radius >= container.floor() - rounding
    }

    /// The corners of a box holding it.
    pub fn bounds(&self) -> (Vec3, Vec3) {
        (
            self.center - Vec3::splat(self.radius),
            self.center + Vec3::splat(self.radius),
        )
    }
}

/// A transparent upright prism or block of its own index: a convex polygon seen from above,
/// between two heights (a 60° prism, a glass block).
#[derive(Clone, Debug, PartialEq)]
pub struct Prism {
    /// Its corners seen from above, `(x, y)` in metres, in either order round it as the file
    /// gives them ([`Prism::counterclockwise`] puts them in one order).
    pub corners: Vec<[f64; 2]>,
    /// Height of its bottom face (m).
    pub bottom: f64,
    /// Height of its top face (m).
    pub top: f64,
    /// Its refractive index.
    pub index: f64,
}

/// A lens of its own index: two faces, each a sphere's cap (or flat), about its optical axis,
/// and a rim of its diameter between them. Light along `+axis` meets face 1 first.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Lens {
    /// The middle of its axis between the two vertices (m).
    pub center: Vec3,
    /// Its optical axis, as the file gives it (any length but 0).
    pub axis: Vec3,
    /// Face 1's radius of curvature, signed: positive when its centre of curvature lies on the
    /// `+axis` side of its vertex; 0 for a flat face (m).
    pub radius1: f64,
    /// Face 2's radius of curvature, signed the same way (m).
    pub radius2: f64,
    /// Its thickness on the axis, vertex to vertex (m).
    pub thickness: f64,
    /// Its diameter (m).
    pub diameter: f64,
    /// Its refractive index.
    pub index: f64,
}

impl Lens {
    /// Its axis as a unit vector.
    pub fn unit_axis(&self) -> Vec3 {
        self.axis.normalize()
    }

    /// How far along the axis a face of radius `r` lies at distance `rho` from it, from its
    /// vertex (its sag; 0 for a flat face).
    pub fn sag(r: f64, rho: f64) -> f64 {
        if r == 0.0 {
            0.0
        } else {
            r - r.signum() * (r * r - rho * rho).max(0.0).sqrt()
        }
    }

    /// The axial coordinates (from the centre) of face 1 and face 2 at distance `rho` from the
    /// axis.
    pub fn faces_at(&self, rho: f64) -> (f64, f64) {
        (
            -self.thickness / 2.0 + Lens::sag(self.radius1, rho),
            self.thickness / 2.0 + Lens::sag(self.radius2, rho),
        )
    }

    /// The radius of a sphere about its centre holding it.
    pub fn reach(&self) -> f64 {
        let (f1, f2) = self.faces_at(self.diameter / 2.0);
        let along = (self.thickness / 2.0).max(f1.abs()).max(f2.abs());
        libm::hypot(self.diameter / 2.0, along)
    }

    /// Whether the point `p` is in the lens (its faces and rim included).
    pub fn contains(&self, p: Vec3) -> bool {
        let a = self.unit_axis();
        let q = p - self.center;
        let w = q.dot(a);
        let rho = (q - w * a).length();
        let (f1, f2) = self.faces_at(rho);
        rho <= self.diameter / 2.0 && w >= f1 && w <= f2
    }

    /// The corners of a box holding it.
    pub fn bounds(&self) -> (Vec3, Vec3) {
        let r = Vec3::splat(self.reach());
        (self.center - r, self.center + r)
    }

    /// Whether it stands inside `container`, above the floor (a valid lens that does not
    /// stands wholly outside it).
    pub fn inside(&self, container: &Container) -> bool {
        let (c, r) = (self.center, self.reach());
        container.holds_disk(c.x, c.y, r, c.z - r, c.z + r) && c.z - r >= container.floor()
    }
}

/// Most corners a prism may have: each is a face every ray is tested against.
pub const MAX_PRISM_CORNERS: usize = 16;

impl Prism {
    /// Its corners, counterclockwise seen from above (the file may list them either way).
    pub fn counterclockwise(&self) -> Vec<[f64; 2]> {
        let mut c = self.corners.clone();
        if polygon_area(&c) < 0.0 {
            c.reverse();
        }
        c
    }

    /// The distance (m) from `p` to the prism's solid: 0 inside it.
    pub fn distance(&self, p: Vec3) -> f64 {
        let c = self.counterclockwise();
        let inside = convex_contains(&c, (p.x, p.y));
        let across = if inside {
            0.0
        } else {
            distance_to_hull(
                (p.x, p.y),
                &c.iter().map(|q| (q[0], q[1])).collect::<Vec<_>>(),
            )
        };
        let up = (self.bottom - p.z).max(p.z - self.top).max(0.0);
        libm::hypot(across, up)
    }

    /// Whether it stands inside `container`, above the floor (a valid prism that does not
    /// stands wholly outside it).
    pub fn inside(&self, container: &Container) -> bool {
        self.bottom >= container.floor()
            && self
                .corners
                .iter()
                .all(|q| container.holds_disk(q[0], q[1], 0.0, self.bottom, self.top))
    }

    /// The corners of a box holding it.
    pub fn bounds(&self) -> (Vec3, Vec3) {
        let (mut lo, mut hi) = (Vec3::splat(f64::INFINITY), Vec3::splat(f64::NEG_INFINITY));
        for q in &self.corners {
            lo = lo.min(Vec3::new(q[0], q[1], self.bottom));
            hi = hi.max(Vec3::new(q[0], q[1], self.top));
        }
        (lo, hi)
    }
}

/// Twice the signed area of the polygon `c` (positive counterclockwise).
fn polygon_area(c: &[[f64; 2]]) -> f64 {
    (0..c.len())
        .map(|k| {
            let (a, b) = (c[k], c[(k + 1) % c.len()]);
            a[0] * b[1] - a[1] * b[0]
        })
        .sum()
}

/// A profile's own rules (`key` names it): 2 to [`MAX_PROFILE_POINTS`] points of finite
/// lengths, `z` rising, every radius positive (but the first, on the axis, for an `inner`
/// profile's round bottom). The smooth wall between them then keeps off the axis (its radius
/// stays between its points').
fn validate_profile(
    key: &str,
    points: &[[f64; 2]],
    inner: bool,
) -> Result<(), Box<SceneFileError>> {
    if !(2..=MAX_PROFILE_POINTS).contains(&points.len()) {
        return Err(refuse_key(
            key,
            Rule::ProfilePoints,
            vec![
                ("max", number(MAX_PROFILE_POINTS as f64)),
                ("count", number(points.len() as f64)),
            ],
        ));
    }
    for (k, &[r, z]) in points.iter().enumerate() {
        let at = format!("{key}[{}]", k + 1);
        length(&at, r)?;
        length(&at, z)?;
        if r < 0.0 || (r == 0.0 && !(inner && k == 0)) {
            return Err(refuse_key(
                &at,
                Rule::ProfileRadius,
                vec![("k", number((k + 1) as f64)), ("r", number(r))],
            ));
        }
        if k > 0 && z <= points[k - 1][1] {
            return Err(refuse_key(
                &at,
                Rule::ProfileRise,
                vec![
                    ("k", number((k + 1) as f64)),
                    ("z", number(z)),
                    ("below", number(points[k - 1][1])),
                ],
            ));
        }
    }
    Ok(())
}

/// Whether the inner surface (`inner`'s pieces) lies inside the outer one below the rim (at
/// `rim`, where they may meet): the difference of their squared radii, a quadratic on each
/// span where both are one piece, is positive there.
fn wall_between(outer: &[Piece], inner: &[Piece], rim: f64) -> Result<(), Box<SceneFileError>> {
    let mut cuts: Vec<f64> = outer
        .iter()
        .chain(inner)
        .flat_map(|p| [p.z0, p.z1])
        .filter(|&z| z >= inner[0].z0)
        .collect();
    cuts.sort_by(f64::total_cmp);
    cuts.dedup();
    for w in cuts.windows(2) {
        let (lo, hi) = (w[0], w[1]);
        let mid = 0.5 * (lo + hi);
        let (Some(o), Some(i)) = (
            outer.iter().find(|p| p.z0 <= mid && mid <= p.z1),
            inner.iter().find(|p| p.z0 <= mid && mid <= p.z1),
        ) else {
            continue;
        };
        // o.r2 − i.r2 as one quadratic about `lo`.
        let gap = Piece {
            zc: lo,
            c: [
                o.r2(lo) - i.r2(lo),
                o.slope(lo) - i.slope(lo),
                o.c[2] - i.c[2],
            ],
            z0: lo,
            z1: hi,
        };
        let top = if hi >= rim { hi - 1e-9 * (hi - lo) } else { hi };
        let (least, _) = gap.r2_range(lo, top);
        if least <= 0.0 {
            let z = [lo, top, mid]
                .into_iter()
                .min_by(|a, b| gap.r2(*a).total_cmp(&gap.r2(*b)))
                .unwrap_or(mid);
            return Err(refuse_key(
                "container.inner",
                Rule::ProfileInside,
                vec![
                    ("z", number(z)),
                    ("inner", number(i.r2(z).max(0.0).sqrt())),
                    ("outer", number(o.r2(z).max(0.0).sqrt())),
                ],
            ));
        }
    }
    Ok(())
}

/// Whether the counterclockwise convex polygon `c` holds `p` (its edges included).
fn convex_contains(c: &[[f64; 2]], p: (f64, f64)) -> bool {
    (0..c.len()).all(|k| {
        let (a, b) = (c[k], c[(k + 1) % c.len()]);
        (b[0] - a[0]) * (p.1 - a[1]) - (b[1] - a[1]) * (p.0 - a[0]) >= 0.0
    })
}

/// How far apart the counterclockwise convex polygons `a` and `b` are along the axis that
/// separates them best (the separating axis theorem): positive when apart, 0 or less when they
/// touch or overlap.
fn convex_gap(a: &[[f64; 2]], b: &[[f64; 2]]) -> f64 {
    let mut gap = f64::NEG_INFINITY;
    for poly in [a, b] {
        for k in 0..poly.len() {
            let (p, q) = (poly[k], poly[(k + 1) % poly.len()]);
            let (nx, ny) = (q[1] - p[1], p[0] - q[0]);
            let len = libm::hypot(nx, ny);
            let project = |c: &[[f64; 2]]| {
                c.iter()
                    .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
                        let t = (v[0] * nx + v[1] * ny) / len;
                        (lo.min(t), hi.max(t))
                    })
            };
            let ((alo, ahi), (blo, bhi)) = (project(a), project(b));
            gap = gap.max((blo - ahi).max(alo - bhi));
        }
    }
    gap
}

/// Whether the segment `a`–`b` has a point in the counterclockwise convex polygon `c`
/// (Cyrus–Beck clipping against its edges).
fn segment_meets_convex(a: (f64, f64), b: (f64, f64), c: &[[f64; 2]]) -> bool {
    let (mut t0, mut t1) = (0.0f64, 1.0f64);
    let d = (b.0 - a.0, b.1 - a.1);
    for k in 0..c.len() {
        let (p, q) = (c[k], c[(k + 1) % c.len()]);
        // Inside the edge: (q − p) × (x − p) >= 0, linear in t along the segment.
        let e = (q[0] - p[0], q[1] - p[1]);
        let f0 = e.0 * (a.1 - p[1]) - e.1 * (a.0 - p[0]);
        let df = e.0 * d.1 - e.1 * d.0;
        if df == 0.0 {
            if f0 < 0.0 {
                return false;
            }
        } else if df > 0.0 {
            t0 = t0.max(-f0 / df);
        } else {
            t1 = t1.min(-f0 / df);
        }
    }
    t0 <= t1
}

/// Whether the polygon `c` (either order, at least 3 corners) is strictly convex: every turn
/// the same way, none straight, and it goes round once.
fn strictly_convex(c: &[[f64; 2]]) -> bool {
    let n = c.len();
    let turns: Vec<f64> = (0..n)
        .map(|k| {
            let (a, b, d) = (c[k], c[(k + 1) % n], c[(k + 2) % n]);
            (b[0] - a[0]) * (d[1] - b[1]) - (b[1] - a[1]) * (d[0] - b[0])
        })
        .collect();
    let all_left = turns.iter().all(|&t| t > 0.0);
    let all_right = turns.iter().all(|&t| t < 0.0);
    if !(all_left || all_right) {
        return false;
    }
    // The edges' directions turn through one full circle, not more (no star).
    let mut total = 0.0;
    for k in 0..n {
        let (a, b, d) = (c[k], c[(k + 1) % n], c[(k + 2) % n]);
        let (u, v) = ((b[0] - a[0], b[1] - a[1]), (d[0] - b[0], d[1] - b[1]));
        total += libm::atan2(u.0 * v.1 - u.1 * v.0, u.0 * v.0 + u.1 * v.1);
    }
    (total.abs() - std::f64::consts::TAU).abs() < 1e-6
}

/// The sun's rule: its direction a direction.
fn validate_sun(sun: &Sun) -> Result<(), Box<SceneFileError>> {
    for v in sun.direction.to_array() {
        finite("sun.direction", v)?;
    }
    let length = sun.direction.length();
    if length == 0.0 || !length.is_finite() {
        return Err(refuse_key("sun.direction", Rule::SunDirection, vec![]));
    }
    Ok(())
}

/// A lesson's lengths: a title of 1 to [`LESSON_TITLE_MAX`] characters, a text of at most
/// [`LESSON_TEXT_MAX`], at most [`LESSON_QUESTIONS_MAX`] questions of at most
/// [`LESSON_QUESTION_MAX`] each (what a page has room for).
fn validate_lesson(lang: &str, l: &LessonText) -> Result<(), Box<SceneFileError>> {
    let long = |s: &String, max: usize| s.chars().count() > max;
    let key = if l.title.trim().is_empty() || long(&l.title, LESSON_TITLE_MAX) {
        Some("title")
    } else if long(&l.text, LESSON_TEXT_MAX) {
        Some("text")
    } else if l.questions.len() > LESSON_QUESTIONS_MAX
        || l.questions.iter().any(|q| long(q, LESSON_QUESTION_MAX))
    {
        Some("questions")
    } else {
        None
    };
    match key {
        None => Ok(()),
        Some(k) => Err(refuse_key(
            &format!("lesson.{lang}.{k}"),
            Rule::LessonLength,
            vec![
                ("title", bound(LESSON_TITLE_MAX as f64)),
                ("text", bound(LESSON_TEXT_MAX as f64)),
                ("questions", bound(LESSON_QUESTIONS_MAX as f64)),
                ("question", bound(LESSON_QUESTION_MAX as f64)),
            ],
        )),
    }
}

/// Longest lesson title, in characters (a heading on a phone).
pub const LESSON_TITLE_MAX: usize = 80;
/// Longest lesson text, in characters (a paragraph beside the picture).
pub const LESSON_TEXT_MAX: usize = 600;
/// Most questions a lesson asks.
pub const LESSON_QUESTIONS_MAX: usize = 3;
/// Longest question, in characters.
pub const LESSON_QUESTION_MAX: usize = 240;

/// What a scene teaches, in words: a title, a few sentences and guiding questions, in English
/// and in French (either may be missing; the page shows its own language's, else the other).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Lesson {
    /// In English.
    pub en: Option<LessonText>,
    /// In French.
    pub fr: Option<LessonText>,
}

/// A lesson in one language.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct LessonText {
    /// Its title.
    pub title: String,
    /// What the scene shows, and why.
    pub text: String,
    /// Questions to ask the class.
    pub questions: Vec<String>,
}

impl Lesson {
    /// The lesson in `lang` ("en" or "fr"), else in the other language.
    pub fn in_language(&self, lang: &str) -> Option<&LessonText> {
        let (first, second) = if lang == "fr" {
            (&self.fr, &self.en)
        } else {
            (&self.en, &self.fr)
        };
        first.as_ref().or(second.as_ref())
    }
}

/// The view a scene is meant for.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Observer {
    /// The eye (m).
    pub position: Vec3,
    /// The point it looks at (m).
    pub target: Vec3,
}

/// The sun of a scene seen outdoors: a scene with a sun is seen against a dark sky (no wall, no
/// floor) in which the sun is a bright disc of the sun's angular size, so that light that left
/// the sun and came to the eye through the scene shows (a water drop's rainbow).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sun {
    /// The direction towards the sun (any length but zero).
    pub direction: Vec3,
}

/// A whole scene as a file describes it, defaults applied.
#[derive(Clone, Debug, PartialEq)]
pub struct SceneDescription {
    /// The glass or the tank.
    pub container: Container,
    /// The liquid layers, bottom first (none: an empty container).
    pub liquids: Vec<Liquid>,
    /// The straws.
    pub straws: Vec<Straw>,
    /// The coins.
    pub coins: Vec<Coin>,
    /// The cards.
    pub cards: Vec<Card>,
    /// The transparent spheres.
    pub spheres: Vec<Sphere>,
    /// The transparent prisms and blocks.
    pub prisms: Vec<Prism>,
    /// The lenses.
    pub lenses: Vec<Lens>,
    /// The view it is meant for, if the file gives one.
    pub observer: Option<Observer>,
    /// The sun, for a scene seen outdoors against the sky.
    pub sun: Option<Sun>,
    /// What it teaches, if the file says.
    pub lesson: Option<Lesson>,
    /// The media whose index depends on the wavelength, each with its law; every other medium
    /// has its one index at all wavelengths. Each such medium's `index` is its law's value at
    /// the wavelength the description is at ([`SceneDescription::at_wavelength`]).
    pub dispersion: Vec<Dispersive>,
}

/// A medium of a scene, as a law of dispersion names it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Medium {
    /// The glass of the container.
    Container,
    /// The liquid layer of this number (from 0, bottom first).
    Liquid(usize),
    /// The transparent sphere of this number.
    Sphere(usize),
    /// The prism or block of this number.
    Prism(usize),
    /// The lens of this number.
    Lens(usize),
}

/// A medium whose index depends on the wavelength, and its law.
#[derive(Clone, Debug, PartialEq)]
pub struct Dispersive {
    /// Which medium.
    pub medium: Medium,
    /// Its law.
    pub law: Dispersion,
}

impl SceneDescription {
    /// The index of `medium`, to read or set (`None` for a medium the scene does not have, or a
    /// tank, whose walls have no index).
    pub fn index_mut(&mut self, medium: Medium) -> Option<&mut f64> {
        match medium {
            Medium::Container => match &mut self.container {
                Container::Glass(g) => Some(&mut g.index),
                Container::Revolution(v) => Some(&mut v.index),
                Container::Tank(_) => None,
            },
            Medium::Liquid(i) => self.liquids.get_mut(i).map(|l| &mut l.index),
            Medium::Sphere(i) => self.spheres.get_mut(i).map(|b| &mut b.index),
            Medium::Prism(i) => self.prisms.get_mut(i).map(|p| &mut p.index),
            Medium::Lens(i) => self.lenses.get_mut(i).map(|l| &mut l.index),
        }
    }

    /// The law of `medium`, if its index depends on the wavelength.
    pub fn law(&self, medium: Medium) -> Option<&Dispersion> {
        self.dispersion
            .iter()
            .find(|d| d.medium == medium)
            .map(|d| &d.law)
    }

    /// Whether some medium's index depends on the wavelength.
    pub fn disperses(&self) -> bool {
        !self.dispersion.is_empty()
    }

    /// The description at the wavelength `nm` (nanometres): each dispersive medium's index set
    /// to its law's value there, every other value as it is. The law stays, so it can be
    /// evaluated at another wavelength.
    pub fn at_wavelength(mut self, nm: f64) -> SceneDescription {
        let laws = std::mem::take(&mut self.dispersion);
        for d in &laws {
            if let Some(index) = self.index_mut(d.medium) {
                *index = d.law.index_at(nm);
            }
        }
        self.dispersion = laws;
        self
    }

    /// Checks every rule of a scene: finite numbers, positive sizes, liquids stacked inside the
    /// walls, straws and coins on the floor inside the walls and not overlapping, cards clear of
    /// the container, the observer outside the container and the objects.
    ///
    /// Every rule that does not depend on another is checked, and all that are broken are
    /// reported at once: each object's own rules, object by object; the container first (the
    /// other rules are about fitting in it), the overlaps and the observer once every object is
    /// valid.
    pub fn validate(&self) -> Result<(), Box<SceneFileError>> {
        self.validate_container()?;
        let mut broken = Broken::default();
        let objects = self.straws.len() + self.coins.len() + self.cards.len() + self.spheres.len();
        if self.liquids.len() > MAX_LIQUIDS {
            broken.check(Err(refuse_key(
                "liquid",
                Rule::TooManyLiquids,
                vec![
                    ("count", bound(self.liquids.len() as f64)),
                    ("max", bound(MAX_LIQUIDS as f64)),
                ],
            )));
        }
        if objects > MAX_OBJECTS {
            broken.check(Err(refuse_key(
                "straw, coin, card, sphere, prism, lens",
                Rule::TooManyObjects,
                vec![
                    ("count", bound(objects as f64)),
                    ("max", bound(MAX_OBJECTS as f64)),
                ],
            )));
        }
        // Too many entries: checking them one by one is what the bound is there to prevent.
        if !broken.0.is_empty() {
            return broken.done();
        }
        self.validate_liquids(&mut broken);
        for (i, s) in self.straws.iter().enumerate() {
            broken.check(self.validate_straw(i, s));
        }
        for (i, c) in self.coins.iter().enumerate() {
            broken.check(self.validate_coin(i, c));
        }
        for (i, c) in self.cards.iter().enumerate() {
            broken.check(self.validate_card(i, c));
        }
        for (i, b) in self.spheres.iter().enumerate() {
            broken.check(self.validate_sphere(i, b));
        }
        for (i, p) in self.prisms.iter().enumerate() {
            broken.check(self.validate_prism(i, p));
        }
        for (i, l) in self.lenses.iter().enumerate() {
            broken.check(self.validate_lens(i, l));
        }
        if let Some(sun) = &self.sun {
            broken.check(validate_sun(sun));
        }
        if broken.0.is_empty() {
            broken.check(self.validate_sphere_overlaps());
            broken.check(self.validate_prism_overlaps());
            broken.check(self.validate_lens_overlaps());
            broken.check(self.validate_overlaps());
            broken.check(self.validate_observer());
        }
        if let Some(lesson) = &self.lesson {
            for (lang, text) in [("en", &lesson.en), ("fr", &lesson.fr)] {
                if let Some(text) = text {
                    broken.check(validate_lesson(lang, text));
                }
            }
        }
        broken.done()
    }

    fn validate_container(&self) -> Result<(), Box<SceneFileError>> {
        match &self.container {
            Container::Glass(g) => {
                positive("container.radius", g.radius)?;
                positive("container.height", g.height)?;
                at_least_zero("container.wall", g.wall)?;
                at_least_zero("container.bottom", g.bottom)?;
                finite("container.index", g.index)?;
                if g.wall >= g.radius {
                    return Err(refuse(
                        "container.wall",
                        g.wall,
                        Rule::WallThinner,
                        vec![("radius", number(g.radius))],
                    ));
                }
                if g.bottom >= g.height {
                    return Err(refuse(
                        "container.bottom",
                        g.bottom,
                        Rule::BottomThinner,
                        vec![("height", number(g.height))],
                    ));
                }
                if !is_physical_index(g.index) {
                    return Err(refuse("container.index", g.index, Rule::IndexRange, vec![]));
                }
            }
            Container::Tank(t) => {
                positive("container.half_x", t.half_x)?;
                positive("container.half_y", t.half_y)?;
                positive("container.height", t.height)?;
            }
            Container::Revolution(v) => {
                validate_profile("container.outer", &v.outer, false)?;
                validate_profile("container.inner", &v.inner, true)?;
                finite("container.index", v.index)?;
                if !is_physical_index(v.index) {
                    return Err(refuse("container.index", v.index, Rule::IndexRange, vec![]));
                }
                let base = v.outer[0][1];
                if base != 0.0 {
                    return Err(refuse_key(
                        "container.outer[1]",
                        Rule::ProfileBase,
                        vec![("z", number(base))],
                    ));
                }
                let floor = v.inner[0][1];
                if floor < 0.0 {
                    return Err(refuse_key(
                        "container.inner[1]",
                        Rule::ProfileFloor,
                        vec![("z", number(floor))],
                    ));
                }
                let (rim, end) = (self.container.height(), v.inner[v.inner.len() - 1][1]);
                if end != rim {
                    return Err(refuse_key(
                        &format!("container.inner[{}]", v.inner.len()),
                        Rule::ProfileRim,
                        vec![("height", number(rim)), ("z", number(end))],
                    ));
                }
                wall_between(&v.outer_pieces(), &v.inner_pieces(), rim)?;
            }
        }
        Ok(())
    }

    /// Each liquid's rules; a layer that breaks one is left out of the next layer's "above the
    /// layer below" rule, which then compares with the last good one.
    fn validate_liquids(&self, broken: &mut Broken) {
        let floor = self.container.floor();
        let mut below = floor;
        for (i, l) in self.liquids.iter().enumerate() {
            if broken.check(self.validate_liquid(i, l, below)) {
                below = l.top;
            }
        }
    }

    /// Liquid `i`'s rules, with the top of the last good layer below it at `below`.
    fn validate_liquid(&self, i: usize, l: &Liquid, below: f64) -> Result<(), Box<SceneFileError>> {
        let floor = self.container.floor();
        let height = self.container.height();
        {
            let key = |k: &str| format!("liquid[{}].{k}", i + 1);
            finite(&key("index"), l.index)?;
            if !is_physical_index(l.index) {
                return Err(refuse(&key("index"), l.index, Rule::IndexRange, vec![]));
            }
            length(&key("top"), l.top)?;
            if l.top <= below {
                let (rule, params) = if i == 0 {
                    (Rule::LiquidAboveFloor, vec![("floor", number(floor))])
                } else {
                    (Rule::LiquidAboveLayer, vec![("below", number(below))])
                };
                return Err(refuse(&key("top"), l.top, rule, params));
            }
            if l.top > height {
                return Err(refuse(
                    &key("top"),
                    l.top,
                    Rule::LiquidBelowRim,
                    vec![("height", number(height))],
                ));
            }
        }
        Ok(())
    }

    /// Straw `i`'s own rules.
    fn validate_straw(&self, i: usize, s: &Straw) -> Result<(), Box<SceneFileError>> {
        let floor = self.container.floor();
        {
            let key = |k: &str| format!("straw[{}].{k}", i + 1);
            length(&key("x"), s.x)?;
            length(&key("y"), s.y)?;
            finite(&key("tilt"), s.tilt_deg)?;
            finite(&key("azimuth"), s.azimuth_deg)?;
            positive(&key("radius"), s.radius)?;
            positive(&key("length"), s.length)?;
            if !(0.0..90.0).contains(&s.tilt_deg) {
                return Err(refuse(&key("tilt"), s.tilt_deg, Rule::TiltRange, vec![]));
            }
            if s.tilt_deg > 0.0 && s.tilt_deg < MIN_TILT_DEG {
                return Err(refuse(
                    &key("tilt"),
                    s.tilt_deg,
                    Rule::TiltTiny,
                    vec![("min", bound(MIN_TILT_DEG))],
                ));
            }
            // Upright, it stands on its whole cap: the cap's centre must be on the floor (its
            // rim's fit is the wall's rule below); leaning, on the one lowest point of the rim.
            let foot = if s.tilt_deg == 0.0 {
                s.bottom_centre(floor)
            } else {
                s.foot(floor)
            };
            if !self.container.holds(foot.x, foot.y, floor) {
                return Err(refuse_key(
                    &format!("straw[{}]", i + 1),
                    Rule::StrawFoot,
                    vec![("x", number(foot.x)), ("y", number(foot.y))],
                ));
            }
            let inside = if s.tilt_deg == 0.0 {
                // Upright: its cross-section is its own disk at every height.
                self.container
                    .holds_disk(s.x, s.y, s.radius, floor, floor + s.length)
            } else {
                s.outline_below(floor, self.container.height())
                    .all(|[a, b]| self.container.holds_line(a, b))
            };
            if !inside {
                return Err(refuse_key(
                    &format!("straw[{}]", i + 1),
                    Rule::StrawPierces,
                    vec![
                        ("x", number(s.x)),
                        ("y", number(s.y)),
                        ("radius", number(s.radius)),
                        ("tilt", number(s.tilt_deg)),
                    ],
                ));
            }
        }
        Ok(())
    }

    /// Coin `i`'s own rules.
    fn validate_coin(&self, i: usize, c: &Coin) -> Result<(), Box<SceneFileError>> {
        let floor = self.container.floor();
        {
            let key = |k: &str| format!("coin[{}].{k}", i + 1);
            length(&key("x"), c.x)?;
            length(&key("y"), c.y)?;
            positive(&key("radius"), c.radius)?;
            positive(&key("thickness"), c.thickness)?;
            if !self
                .container
                .holds_disk(c.x, c.y, c.radius, floor, floor + c.thickness)
            {
                return Err(refuse_key(
                    &format!("coin[{}]", i + 1),
                    Rule::CoinOutside,
                    vec![
                        ("x", number(c.x)),
                        ("y", number(c.y)),
                        ("radius", number(c.radius)),
                    ],
                ));
            }
            if floor + c.thickness > self.container.height() {
                return Err(refuse(
                    &key("thickness"),
                    c.thickness,
                    Rule::CoinBelowRim,
                    vec![],
                ));
            }
        }
        Ok(())
    }

    /// Card `i`'s own rules.
    fn validate_card(&self, i: usize, c: &Card) -> Result<(), Box<SceneFileError>> {
        {
            let key = |k: &str| format!("card[{}].{k}", i + 1);
            for v in c.center.to_array() {
                length(&key("center"), v)?;
            }
            finite(&key("facing"), c.facing_deg)?;
            positive(&key("width"), c.width)?;
            positive(&key("height"), c.height)?;
            let (low, high) = (c.center.z - c.height / 2.0, c.center.z + c.height / 2.0);
            let (a, b) = c.ends();
            if high > 0.0 && low < self.container.height() && self.container.crossed_by(a, b) {
                let mut params = point(c.center);
                params.extend([("width", number(c.width)), ("height", number(c.height))]);
                return Err(refuse_key(
                    &format!("card[{}]", i + 1),
                    Rule::CardCuts,
                    params,
                ));
            }
        }
        Ok(())
    }

    /// Sphere `i`'s own rules: its numbers, and its place: inside the container above the floor
    /// (through any liquid's surface), or wholly outside the container.
    fn validate_sphere(&self, i: usize, b: &Sphere) -> Result<(), Box<SceneFileError>> {
        let key = |k: &str| format!("sphere[{}].{k}", i + 1);
        for v in b.center.to_array() {
            length(&key("center"), v)?;
        }
        positive(&key("radius"), b.radius)?;
        finite(&key("index"), b.index)?;
        if !is_physical_index(b.index) {
            return Err(refuse(&key("index"), b.index, Rule::IndexRange, vec![]));
        }
        let c = b.center;
        let mut params = point(c);
        params.push(("radius", number(b.radius)));
        if !b.inside(&self.container) && self.container.distance_to(c) < b.radius {
            return Err(refuse_key(
                &format!("sphere[{}]", i + 1),
                Rule::SphereContainer,
                params,
            ));
        }
        Ok(())
    }

    /// Prism `i`'s own rules: its numbers, a convex polygon of at most [`MAX_PRISM_CORNERS`]
    /// corners, its bottom below its top, and its place: inside the container above the floor
    /// (through any liquid's surface), or wholly outside the container.
    fn validate_prism(&self, i: usize, p: &Prism) -> Result<(), Box<SceneFileError>> {
        let key = |k: &str| format!("prism[{}].{k}", i + 1);
        for q in &p.corners {
            for &v in q {
                length(&key("corners"), v)?;
            }
        }
        length(&key("bottom"), p.bottom)?;
        length(&key("top"), p.top)?;
        finite(&key("index"), p.index)?;
        if !is_physical_index(p.index) {
            return Err(refuse(&key("index"), p.index, Rule::IndexRange, vec![]));
        }
        let n = p.corners.len();
        if !(3..=MAX_PRISM_CORNERS).contains(&n) || !strictly_convex(&p.corners) {
            return Err(refuse_key(
                &key("corners"),
                Rule::PrismConvex,
                vec![
                    ("count", bound(n as f64)),
                    ("max", bound(MAX_PRISM_CORNERS as f64)),
                ],
            ));
        }
        if p.top - p.bottom < MIN_SIZE {
            return Err(refuse(
                &key("top"),
                p.top,
                Rule::PrismTop,
                vec![("bottom", number(p.bottom))],
            ));
        }
        if !p.inside(&self.container) && self.container.distance_to_prism(p) <= 0.0 {
            return Err(refuse_key(
                &format!("prism[{}]", i + 1),
                Rule::PrismContainer,
                vec![],
            ));
        }
        Ok(())
    }

    /// Lens `i`'s own rules: its numbers, its axis not zero, each curved face's radius at least
    /// half its diameter, its faces apart across the whole diameter, and its place: inside the
    /// container above the floor and wholly in one layer (or above them all), or wholly outside
    /// it (taken with the sphere about its centre that holds it).
    fn validate_lens(&self, i: usize, l: &Lens) -> Result<(), Box<SceneFileError>> {
        let key = |k: &str| format!("lens[{}].{k}", i + 1);
        for v in l.center.to_array() {
            length(&key("center"), v)?;
        }
        for v in l.axis.to_array() {
            finite(&key("axis"), v)?;
        }
        if l.axis.length() == 0.0 || !l.axis.length().is_finite() {
            return Err(refuse_key(&key("axis"), Rule::LensAxis, vec![]));
        }
        positive(&key("thickness"), l.thickness)?;
        positive(&key("diameter"), l.diameter)?;
        finite(&key("index"), l.index)?;
        if !is_physical_index(l.index) {
            return Err(refuse(&key("index"), l.index, Rule::IndexRange, vec![]));
        }
        for (name, r) in [("radius1", l.radius1), ("radius2", l.radius2)] {
            if r != 0.0 {
                length(&key(name), r)?;
                if r.abs() < l.diameter / 2.0 {
                    return Err(refuse(
                        &key(name),
                        r,
                        Rule::LensRadius,
                        vec![("half", number(l.diameter / 2.0))],
                    ));
                }
            }
        }
        // The faces may not meet or cross anywhere within the diameter.
        for k in 0..=64 {
            let rho = l.diameter / 2.0 * k as f64 / 64.0;
            let (f1, f2) = l.faces_at(rho);
            if f2 - f1 < 0.0 {
                return Err(refuse_key(
                    &format!("lens[{}]", i + 1),
                    Rule::LensFaces,
                    vec![("rho", number(rho)), ("gap", number(f2 - f1))],
                ));
            }
        }
        let (c, reach) = (l.center, l.reach());
        let mut params = point(c);
        params.push(("radius", number(reach)));
        // Inside, it may lie across any liquid's surface (a lens half dipped in water).
        let inside = l.inside(&self.container);
        if !inside && self.container.distance_to(c) < reach {
            return Err(refuse_key(
                &format!("lens[{}]", i + 1),
                Rule::LensPlace,
                params,
            ));
        }
        Ok(())
    }

    /// Lenses stand clear of the other objects, each taken as the sphere about its centre that
    /// holds it; the eye outside them is checked with the observer.
    fn validate_lens_overlaps(&self) -> Result<(), Box<SceneFileError>> {
        let floor = self.container.floor();
        for (j, l) in self.lenses.iter().enumerate() {
            let (c, r) = (l.center, l.reach());
            let overlap = |other: String, gap: f64, sum: f64| {
                refuse_key(
                    &format!("lens[{}]", j + 1),
                    Rule::SolidOverlap,
                    vec![
                        ("other", words(other)),
                        ("gap", number(gap)),
                        ("sum", number(sum)),
                    ],
                )
            };
            for (i, m) in self.lenses[..j].iter().enumerate() {
                let gap = (m.center - c).length();
                if gap < r + m.reach() {
                    return Err(overlap(format!("lens[{}]", i + 1), gap, r + m.reach()));
                }
            }
            for (i, b) in self.spheres.iter().enumerate() {
                let gap = (b.center - c).length();
                if gap < r + b.radius {
                    return Err(overlap(format!("sphere[{}]", i + 1), gap, r + b.radius));
                }
            }
            for (i, p) in self.prisms.iter().enumerate() {
                let gap = p.distance(c);
                if gap < r {
                    return Err(overlap(format!("prism[{}]", i + 1), gap, r));
                }
            }
            for (i, s) in self.straws.iter().enumerate() {
                let foot = s.bottom_centre(floor);
                let gap = point_segment_distance(c, foot, foot + s.length * s.axis());
                if gap < r + s.radius {
                    return Err(overlap(format!("straw[{}]", i + 1), gap, r + s.radius));
                }
            }
            for (i, coin) in self.coins.iter().enumerate() {
                let gap = distance_to_disk_solid(c, coin, floor);
                if gap < r {
                    return Err(overlap(format!("coin[{}]", i + 1), gap, r));
                }
            }
            for (i, card) in self.cards.iter().enumerate() {
                if distance_to_rectangle(c, &card.corners()) < r {
                    return Err(refuse_key(
                        &format!("lens[{}]", j + 1),
                        Rule::SolidCard,
                        vec![("other", words(format!("card[{}]", i + 1)))],
                    ));
                }
            }
        }
        Ok(())
    }

    /// Spheres stand clear of one another, of the straws (of the capsule about each straw's
    /// axis, a slightly larger body) and of the coins; a card lies wholly inside a sphere or
    /// wholly outside it.
    fn validate_sphere_overlaps(&self) -> Result<(), Box<SceneFileError>> {
        let floor = self.container.floor();
        let overlap = |j: usize, other: String, gap: f64, sum: f64| {
            refuse_key(
                &format!("sphere[{}]", j + 1),
                Rule::SolidOverlap,
                vec![
                    ("other", words(other)),
                    ("gap", number(gap)),
                    ("sum", number(sum)),
                ],
            )
        };
        for (j, b) in self.spheres.iter().enumerate() {
            for (i, a) in self.spheres[..j].iter().enumerate() {
                let gap = (a.center - b.center).length();
                if gap < a.radius + b.radius {
                    return Err(overlap(
                        j,
                        format!("sphere[{}]", i + 1),
                        gap,
                        a.radius + b.radius,
                    ));
                }
            }
            for (i, s) in self.straws.iter().enumerate() {
                let foot = s.bottom_centre(floor);
                let gap = point_segment_distance(b.center, foot, foot + s.length * s.axis());
                if gap < b.radius + s.radius {
                    return Err(overlap(
                        j,
                        format!("straw[{}]", i + 1),
                        gap,
                        b.radius + s.radius,
                    ));
                }
            }
            for (i, c) in self.coins.iter().enumerate() {
                let gap = distance_to_disk_solid(b.center, c, floor);
                if gap < b.radius {
                    return Err(overlap(j, format!("coin[{}]", i + 1), gap, b.radius));
                }
            }
            for (i, card) in self.cards.iter().enumerate() {
                let corners = card.corners();
                let inside = corners.iter().all(|p| (*p - b.center).length() < b.radius);
                let outside = distance_to_rectangle(b.center, &corners) > b.radius;
                if !inside && !outside {
                    return Err(refuse_key(
                        &format!("sphere[{}]", j + 1),
                        Rule::SolidCard,
                        vec![("other", words(format!("card[{}]", i + 1)))],
                    ));
                }
            }
        }
        Ok(())
    }

    /// Prisms stand clear of one another, of the spheres, the straws (each taken at points along
    /// its axis closer than half its radius) and the coins; a card lies wholly inside a prism or
    /// wholly outside it.
    fn validate_prism_overlaps(&self) -> Result<(), Box<SceneFileError>> {
        let floor = self.container.floor();
        let overlap = |j: usize, other: String, gap: f64, sum: f64| {
            refuse_key(
                &format!("prism[{}]", j + 1),
                Rule::SolidOverlap,
                vec![
                    ("other", words(other)),
                    ("gap", number(gap)),
                    ("sum", number(sum)),
                ],
            )
        };
        let ccw: Vec<Vec<[f64; 2]>> = self.prisms.iter().map(Prism::counterclockwise).collect();
        for (j, p) in self.prisms.iter().enumerate() {
            for (i, q) in self.prisms[..j].iter().enumerate() {
                let apart_z = (p.bottom - q.top).max(q.bottom - p.top);
                let gap = apart_z.max(convex_gap(&ccw[i], &ccw[j]));
                if gap <= 0.0 {
                    return Err(overlap(j, format!("prism[{}]", i + 1), gap.max(0.0), 0.0));
                }
            }
            for (i, b) in self.spheres.iter().enumerate() {
                let gap = p.distance(b.center);
                if gap < b.radius {
                    return Err(overlap(j, format!("sphere[{}]", i + 1), gap, b.radius));
                }
            }
            for (i, s) in self.straws.iter().enumerate() {
                let foot = s.bottom_centre(floor);
                let steps = (2.0 * s.length / s.radius).ceil().min(1e5) as usize;
                let gap = (0..=steps)
                    .map(|k| p.distance(foot + (k as f64 / steps as f64) * s.length * s.axis()))
                    .fold(f64::INFINITY, f64::min);
                if gap < s.radius {
                    return Err(overlap(j, format!("straw[{}]", i + 1), gap, s.radius));
                }
            }
            for (i, c) in self.coins.iter().enumerate() {
                let apart_z = (p.bottom - (floor + c.thickness)).max(floor - p.top);
                let across = if convex_contains(&ccw[j], (c.x, c.y)) {
                    0.0
                } else {
                    let hull: Vec<(f64, f64)> = ccw[j].iter().map(|q| (q[0], q[1])).collect();
                    distance_to_hull((c.x, c.y), &hull)
                };
                if apart_z <= 0.0 && across < c.radius {
                    return Err(overlap(j, format!("coin[{}]", i + 1), across, c.radius));
                }
            }
            for (i, card) in self.cards.iter().enumerate() {
                let inside = card.corners().iter().all(|q| p.distance(*q) == 0.0);
                let (lo, hi) = (
                    card.center.z - card.height / 2.0,
                    card.center.z + card.height / 2.0,
                );
                let (a, b) = card.ends();
                let meets = lo < p.top && hi > p.bottom && segment_meets_convex(a, b, &ccw[j]);
                if !inside && meets {
                    return Err(refuse_key(
                        &format!("prism[{}]", j + 1),
                        Rule::SolidCard,
                        vec![("other", words(format!("card[{}]", i + 1)))],
                    ));
                }
            }
        }
        Ok(())
    }

    /// Straws and coins may not share floor, a leaning straw may not lie on a coin, and straws
    /// may not cross. A straw's footprint is taken as the disk of its radius about the point
    /// below its bottom cap's centre, which holds the cap's shadow (an ellipse
    /// `radius·cos(tilt)` by `radius`) whatever its tilt.
    fn validate_overlaps(&self) -> Result<(), Box<SceneFileError>> {
        let footprints: Vec<(String, f64, f64, f64)> = self
            .straws
            .iter()
            .enumerate()
            .map(|(i, s)| (format!("straw[{}]", i + 1), s.x, s.y, s.radius))
            .chain(
                self.coins
                    .iter()
                    .enumerate()
                    .map(|(i, c)| (format!("coin[{}]", i + 1), c.x, c.y, c.radius)),
            )
            .collect();
        for (j, b) in footprints.iter().enumerate() {
            for a in &footprints[..j] {
                let gap = libm::hypot(a.1 - b.1, a.2 - b.2);
                if gap < a.3 + b.3 {
                    return Err(refuse_key(
                        &b.0,
                        Rule::FloorOverlap,
                        vec![
                            ("other", words(a.0.clone())),
                            ("gap", number(gap)),
                            ("sum", number(a.3 + b.3)),
                        ],
                    ));
                }
            }
        }
        // A leaning straw's body, low near its foot, may also lie over a coin beside its cap:
        // within the coin's height the coin holds every point above its disk, so they overlap
        // exactly when the coin's disk meets the shadow of the straw's part below the coin's top.
        for (j, c) in self.coins.iter().enumerate() {
            for (i, s) in self.straws.iter().enumerate() {
                if s.tilt_deg == 0.0 {
                    continue; // upright, its shadow is its footprint, checked above
                }
                // Far apart, they cannot meet: the straw's part below the coin's top lies within
                // `reach` of the point below its bottom cap's centre. Only near pairs pay for
                // the exact test, so a scene of many objects is checked in near-linear time.
                let (sin, cos) = libm::sincos(s.tilt_deg.to_radians());
                let reach = s.radius + sin * s.length.min((c.thickness + s.radius) / cos);
                let foot = s.bottom_centre(self.container.floor());
                if libm::hypot(c.x - foot.x, c.y - foot.y) > (reach + c.radius) * (1.0 + 1e-9) {
                    continue;
                }
                let low: Vec<(f64, f64)> = s
                    .outline_below(self.container.floor(), self.container.floor() + c.thickness)
                    .flat_map(|[a, b]| [(a.x, a.y), (b.x, b.y)])
                    .collect();
                let gap = distance_to_hull((c.x, c.y), &low);
                if gap < c.radius {
                    return Err(refuse_key(
                        &format!("coin[{}]", j + 1),
                        Rule::CoinLeanedOn,
                        vec![
                            ("other", words(format!("straw[{}]", i + 1))),
                            ("gap", number(gap)),
                            ("radius", number(c.radius)),
                        ],
                    ));
                }
            }
        }
        // Leaning straws can also cross above the floor: each is kept within the capsule about
        // its axis (a slightly larger body than the straw, rounded past its caps), so two whose
        // axes pass closer than their radii's sum are refused.
        let floor = self.container.floor();
        let axis_of = |s: &Straw| {
            let c = s.bottom_centre(floor);
            (c, c + s.length * s.axis())
        };
        for (j, b) in self.straws.iter().enumerate() {
            for (i, a) in self.straws[..j].iter().enumerate() {
                let ((a0, a1), (b0, b1)) = (axis_of(a), axis_of(b));
                let gap = segment_distance(a0, a1, b0, b1);
                if gap < a.radius + b.radius {
                    return Err(refuse_key(
                        &format!("straw[{}]", j + 1),
                        Rule::StrawsCross,
                        vec![
                            ("other", words(format!("straw[{}]", i + 1))),
                            ("gap", number(gap)),
                            ("sum", number(a.radius + b.radius)),
                        ],
                    ));
                }
            }
        }
        Ok(())
    }

    fn validate_observer(&self) -> Result<(), Box<SceneFileError>> {
        match &self.observer {
            Some(o) => self.check_observer(o),
            None => Ok(()),
        }
    }

    /// Checks `o` by the rules an `[observer]` of this scene obeys (finite, outside the container
    /// and the straws, its target away from its eye), as if the file gave it.
    pub fn check_observer(&self, o: &Observer) -> Result<(), Box<SceneFileError>> {
        for (name, p) in [("position", o.position), ("target", o.target)] {
            for v in p.to_array() {
                length(&format!("observer.{name}"), v)?;
            }
        }
        let p = o.position;
        let at = |more: Option<String>| {
            let mut params = point(p);
            params.extend(more.map(|m| ("other", words(m))));
            params
        };
        if self.container.encloses(p) {
            return Err(refuse_key(
                "observer.position",
                Rule::EyeInContainer,
                at(None),
            ));
        }
        let floor = self.container.floor();
        if let Some(i) = self.straws.iter().position(|s| s.contains(floor, p)) {
            return Err(refuse_key(
                "observer.position",
                Rule::EyeInStraw,
                at(Some(format!("straw[{}]", i + 1))),
            ));
        }
        if let Some(i) = self
            .spheres
            .iter()
            .position(|b| (p - b.center).length() <= b.radius)
        {
            return Err(refuse_key(
                "observer.position",
                Rule::EyeInSolid,
                at(Some(format!("sphere[{}]", i + 1))),
            ));
        }
        if let Some(i) = self.lenses.iter().position(|l| l.contains(p)) {
            return Err(refuse_key(
                "observer.position",
                Rule::EyeInSolid,
                at(Some(format!("lens[{}]", i + 1))),
            ));
        }
        if let Some(i) = self.prisms.iter().position(|q| q.distance(p) == 0.0) {
            return Err(refuse_key(
                "observer.position",
                Rule::EyeInSolid,
                at(Some(format!("prism[{}]", i + 1))),
            ));
        }
        if let Some(i) = self.cards.iter().position(|c| c.touches(p)) {
            return Err(refuse_key(
                "observer.position",
                Rule::EyeOnCard,
                at(Some(format!("card[{}]", i + 1))),
            ));
        }
        if o.target == p {
            return Err(refuse_key("observer.target", Rule::TargetAtEye, at(None)));
        }
        Ok(())
    }

    /// Numbers that break no rule but look like a slip, each with what the file probably meant:
    /// a size above [`LARGEST_LIKELY_SIZE`] reads like centimetres written as metres (`radius =
    /// 4` is a glass 8 m wide, its straw a speck in it). Empty when nothing looks wrong.
    pub fn hints(&self) -> Vec<String> {
        self.size_hints()
            .into_iter()
            .map(|(key, v)| {
                format!(
                    "{key} = {}: lengths are in metres, so this is {} m; if you meant {} cm, write {}",
                    number_text(v),
                    number_text(v),
                    number_text(v),
                    number_text(v / 100.0)
                )
            })
            .collect()
    }

    /// The sizes [`SceneDescription::hints`] speaks of: each key with its value (m), for a page
    /// to say in its own language.
    pub fn size_hints(&self) -> Vec<(String, f64)> {
        let mut sizes: Vec<(String, f64)> = Vec::new();
        match &self.container {
            Container::Glass(g) => {
                sizes.push(("container.radius".into(), g.radius));
                sizes.push(("container.height".into(), g.height));
            }
            Container::Tank(t) => {
                sizes.push(("container.half_x".into(), t.half_x));
                sizes.push(("container.half_y".into(), t.half_y));
                sizes.push(("container.height".into(), t.height));
            }
            Container::Revolution(v) => {
                sizes.push(("container.outer".into(), v.reach()));
                sizes.push(("container.outer".into(), self.container.height()));
            }
        }
        for (i, s) in self.straws.iter().enumerate() {
            sizes.push((format!("straw[{}].radius", i + 1), s.radius));
            sizes.push((format!("straw[{}].length", i + 1), s.length));
        }
        for (i, c) in self.coins.iter().enumerate() {
            sizes.push((format!("coin[{}].radius", i + 1), c.radius));
        }
        sizes.retain(|&(_, v)| v > LARGEST_LIKELY_SIZE);
        sizes
    }

    /// What this scene has that the assignment's scene has not, in words ("a straw tilted 15°"),
    /// each said once; empty when it is exactly the assignment's kind.
    pub fn unsupported(&self) -> Vec<String> {
        let mut out = Vec::new();
        let m = |x: f64| format!("{} m", number_text(x));
        match &self.container {
            Container::Tank(_) => out.push("a rectangular tank".to_string()),
            Container::Revolution(_) => out.push("a glass of revolution".to_string()),
            Container::Glass(g) => {
                if g.radius != GLASS_RADIUS {
                    out.push(format!("a glass of radius {}", m(g.radius)));
                }
                if g.height != GLASS_HEIGHT {
                    out.push(format!("a glass {} high", m(g.height)));
                }
                if g.wall != 0.0 {
                    out.push(format!("walls {} thick", m(g.wall)));
                }
                if g.bottom != 0.0 {
                    out.push(format!("a bottom {} thick", m(g.bottom)));
                }
            }
        }
        if self.liquids.len() > 1 {
            out.push(format!("{} liquid layers", self.liquids.len()));
        }
        match self.straws.len() {
            0 => out.push("no straw".to_string()),
            1 => {}
            n => out.push(format!("{n} straws")),
        }
        for s in &self.straws {
            if s.tilt_deg != 0.0 {
                out.push(format!("a straw tilted {}°", number_text(s.tilt_deg)));
            }
            if s.radius != STRAW_RADIUS {
                out.push(format!("a straw of radius {}", m(s.radius)));
            }
            if s.length != STRAW_HEIGHT {
                out.push(format!("a straw {} long", m(s.length)));
            }
        }
        match self.coins.len() {
            0 => {}
            1 => out.push("a coin".to_string()),
            n => out.push(format!("{n} coins")),
        }
        match self.cards.len() {
            0 => {}
            1 => out.push("a card".to_string()),
            n => out.push(format!("{n} cards")),
        }
        // Many straws alike are one reason, said once.
        let mut seen = std::collections::HashSet::new();
        out.retain(|w| seen.insert(w.clone()));
        out
    }

    /// The assignment's scene written as a description: the glass of radius 0.04 m and height
    /// 0.2 m with walls and bottom of no thickness, its water (none when its height is 0), the
    /// upright straw of radius 0.005 m and length 0.25 m; no observer.
    pub fn assignment(scene: &Scene) -> SceneDescription {
        SceneDescription {
            container: Container::Glass(Glass {
                radius: GLASS_RADIUS,
                height: GLASS_HEIGHT,
                wall: 0.0,
                bottom: 0.0,
                index: DEFAULT_CONTAINER_INDEX,
            }),
            liquids: if scene.has_water() {
                vec![Liquid {
                    name: "water".to_string(),
                    index: scene.n_water(),
                    top: scene.water_height(),
                    tint: None,
                }]
            } else {
                vec![]
            },
            straws: vec![Straw {
                x: scene.straw_x(),
                y: scene.straw_y(),
                tilt_deg: 0.0,
                azimuth_deg: 0.0,
                radius: STRAW_RADIUS,
                length: STRAW_HEIGHT,
            }],
            coins: vec![],
            cards: vec![],
            spheres: vec![],
            prisms: vec![],
            lenses: vec![],
            observer: None,
            sun: None,
            lesson: None,
            dispersion: vec![],
        }
    }

    /// The assignment's scene when this is exactly its kind (a glass of radius 0.04 m and height
    /// 0.2 m with zero-thickness walls and bottom, at most one liquid, one upright straw of radius
    /// 0.005 m and length 0.25 m, no coin, no card), with the default event limit; else `None`.
    /// An empty glass is water of height 0.
    pub fn spec_scene(&self) -> Option<Scene> {
        if !self.unsupported().is_empty() {
            return None;
        }
        let straw = self.straws.first()?;
        let (top, index) = match self.liquids.first() {
            Some(l) => (l.top, l.index),
            None => (0.0, WATER_INDEX),
        };
        Scene::new(straw.x, straw.y, top, index, DEFAULT_MAX_EVENTS).ok()
    }
}

/// Checks that `value` is finite.
fn finite(key: &str, value: f64) -> Result<(), Box<SceneFileError>> {
    if value.is_finite() {
        Ok(())
    } else {
        Err(refuse(key, value, Rule::Finite, vec![]))
    }
}

/// Checks that a length or coordinate is finite and at most [`MAX_LENGTH`] in size.
fn length(key: &str, value: f64) -> Result<(), Box<SceneFileError>> {
    finite(key, value)?;
    if value.abs() <= MAX_LENGTH {
        Ok(())
    } else {
        Err(refuse(
            key,
            value,
            Rule::LengthMax,
            vec![("max", bound(MAX_LENGTH))],
        ))
    }
}

/// Checks that a size is finite, at least [`MIN_SIZE`] and at most [`MAX_LENGTH`].
fn positive(key: &str, value: f64) -> Result<(), Box<SceneFileError>> {
    finite(key, value)?;
    if (MIN_SIZE..=MAX_LENGTH).contains(&value) {
        Ok(())
    } else if value > 0.0 {
        Err(refuse(
            key,
            value,
            Rule::SizeRange,
            vec![("min", bound(MIN_SIZE)), ("max", bound(MAX_LENGTH))],
        ))
    } else {
        Err(refuse(key, value, Rule::SizePositive, vec![]))
    }
}

/// Checks that a thickness is finite and 0, or a size between [`MIN_SIZE`] and [`MAX_LENGTH`].
fn at_least_zero(key: &str, value: f64) -> Result<(), Box<SceneFileError>> {
    finite(key, value)?;
    if value < 0.0 {
        Err(refuse(key, value, Rule::ThicknessPositive, vec![]))
    } else if value == 0.0 || (MIN_SIZE..=MAX_LENGTH).contains(&value) {
        Ok(())
    } else {
        Err(refuse(
            key,
            value,
            Rule::ThicknessRange,
            vec![("min", bound(MIN_SIZE)), ("max", bound(MAX_LENGTH))],
        ))
    }
}

#[cfg(test)]
mod tests;
