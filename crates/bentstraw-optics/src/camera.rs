//! The observer's pinhole camera (see `docs/physics.md` in the repository).

use crate::geometry::Ray;
use crate::scene::{GLASS_RADIUS, STRAW_HEIGHT};
use crate::Vec3;

/// Relative margin left around the glass and straw by [`framing_fov`].
pub const FRAMING_MARGIN: f64 = 0.08;
/// Widest vertical field of view [`framing_fov`] returns (radians, 150°): used when the eye is
/// so close that no narrower view holds the whole glass (references 1 and 2 need about 148°).
pub const MAX_FRAMING_FOV: f64 = 150.0 * std::f64::consts::PI / 180.0;

/// A pinhole camera at the eye, aimed at a target, `width × height` pixels, vertical field `fov_y`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    /// The eye `E`.
    pub eye: Vec3,
    /// Unit forward `f = (T − E)/|T − E|`.
    pub forward: Vec3,
    /// Unit right `r`.
    pub right: Vec3,
    /// Unit up `u = r × f`.
    pub up: Vec3,
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// `tan(φ/2)`, half the image plane's height at unit distance.
    pub tan_half_fov: f64,
}

/// The camera's orthonormal basis looking along `direction`: forward `f`, right
/// `r = (f × ẑ)/|f × ẑ|` (`x̂` when looking straight up or down), up `u = r × f`.
pub fn view_basis(direction: Vec3) -> (Vec3, Vec3, Vec3) {
    let forward = direction.normalize();
    let c = forward.cross(Vec3::Z);
    let right = if c.length() < 1e-9 {
        Vec3::X
    } else {
        c.normalize()
    };
    (forward, right, right.cross(forward))
}

impl Camera {
    /// A pinhole camera at `eye`, aimed at `target`, with vertical field of view `fov_y`
    /// (radians).
    ///
    /// The caller guarantees `eye != target`, `width, height > 0` and `0 < fov_y < π`.
    pub fn new(eye: Vec3, target: Vec3, width: u32, height: u32, fov_y: f64) -> Camera {
        let (forward, right, up) = view_basis(target - eye);
        Camera {
            eye,
            forward,
            right,
            up,
            width,
            height,
            tan_half_fov: libm::tan(fov_y / 2.0),
        }
    }

    /// The (unnormalised) direction through the image point `(row, col)`, both continuous
    /// (pixel `(i, j)`'s centre is `(i + 0.5, j + 0.5)`).
    #[inline]
    pub fn direction_at(&self, row: f64, col: f64) -> Vec3 {
        let (w, h) = (self.width as f64, self.height as f64);
        let sx = (2.0 * col / w - 1.0) * self.tan_half_fov * (w / h);
        let sy = (1.0 - 2.0 * row / h) * self.tan_half_fov;
        self.forward + sx * self.right + sy * self.up
    }

    /// The ray through the centre of pixel row `i` (0 at the top), column `j` (0 at the left).
    #[inline]
    pub fn pixel_ray(&self, i: u32, j: u32) -> Ray {
        Ray::new(self.eye, self.direction_at(i as f64 + 0.5, j as f64 + 0.5))
    }

    /// Where the point `p` appears in the picture, as continuous `(row, col)`; `None` if behind the eye.
    #[inline]
    pub fn project(&self, p: Vec3) -> Option<(f64, f64)> {
        let v = p - self.eye;
        let z = v.dot(self.forward);
        if z <= 0.0 {
            return None;
        }
        let (w, h) = (self.width as f64, self.height as f64);
        let sx = v.dot(self.right) / z / (self.tan_half_fov * (w / h));
        let sy = v.dot(self.up) / z / self.tan_half_fov;
        Some(((1.0 - sy) * h / 2.0, (sx + 1.0) * w / 2.0))
    }
}

/// The extent `(x_min, x_max, y_min, y_max)` of the glass-and-straw cylinder (radius `Rv`, `z` from
/// 0 to `Hp`) on the image plane at unit distance of a camera at `eye` looking at `target`, or
/// `None` if part of it is behind the eye.
///
/// A pinhole picture of a cylinder is bounded by the pictures of its two end circles.
fn scene_extent(eye: Vec3, target: Vec3) -> Option<(f64, f64, f64, f64)> {
    let cam = Camera::new(eye, target, 1, 1, std::f64::consts::FRAC_PI_2);
    let mut e = (
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
    );
    const STEPS: usize = 1440;
    for k in 0..STEPS {
        let a = k as f64 * std::f64::consts::TAU / STEPS as f64;
        for z in [0.0, STRAW_HEIGHT] {
            let v = Vec3::new(GLASS_RADIUS * libm::cos(a), GLASS_RADIUS * libm::sin(a), z) - eye;
            let depth = v.dot(cam.forward);
            if depth <= 1e-9 {
                return None;
            }
            let (x, y) = (v.dot(cam.right) / depth, v.dot(cam.up) / depth);
            e = (e.0.min(x), e.1.max(x), e.2.min(y), e.3.max(y));
        }
    }
    Some(e)
}

/// The vertical field of view (radians) that just frames the glass and the straw, with a margin of
/// [`FRAMING_MARGIN`], for a camera at `eye` aimed at `target` with `aspect = width / height`.
///
/// Glass and straw (wherever it stands) lie in the cylinder of radius `Rv` from `z = 0` to `Hp`;
/// the field is the smallest that holds its picture. Capped at [`MAX_FRAMING_FOV`] (also when part
/// of the cylinder is behind the eye).
pub fn framing_fov(eye: Vec3, target: Vec3, aspect: f64) -> f64 {
    let Some((x0, x1, y0, y1)) = scene_extent(eye, target) else {
        return MAX_FRAMING_FOV;
    };
    let half = y0.abs().max(y1.abs()).max(x0.abs().max(x1.abs()) / aspect);
    (2.0 * libm::atan(half * (1.0 + FRAMING_MARGIN))).min(MAX_FRAMING_FOV)
}

/// The vertical field of view (radians) that frames the box of corners `lo`, `hi` (its eight
/// corners' picture, with the margin of [`framing_fov`]) for a camera at `eye` aimed at `target`
/// with `aspect = width / height`; [`MAX_FRAMING_FOV`] at most, and when a corner is behind the eye.
pub fn framing_fov_box(eye: Vec3, target: Vec3, (lo, hi): (Vec3, Vec3), aspect: f64) -> f64 {
    let cam = Camera::new(eye, target, 1, 1, std::f64::consts::FRAC_PI_2);
    let mut half: f64 = 0.0;
    for k in 0..8 {
        let corner = Vec3::new(
            if k & 1 == 0 { lo.x } else { hi.x },
            if k & 2 == 0 { lo.y } else { hi.y },
            if k & 4 == 0 { lo.z } else { hi.z },
        );
        let v = corner - eye;
        let depth = v.dot(cam.forward);
        if depth <= 0.0 {
            return MAX_FRAMING_FOV;
        }
        half = half
            .max((v.dot(cam.up) / depth).abs())
            .max((v.dot(cam.right) / depth).abs() / aspect);
    }
    (2.0 * libm::atan(half * (1.0 + FRAMING_MARGIN))).min(MAX_FRAMING_FOV)
}

/// A target for a camera at `eye` that centres the picture of the glass and the straw (rather than
/// aiming at the centre of their box, which a close observer sees off-centre), at the distance of
/// [`crate::scene::SCENE_CENTRE`]; that centre itself if the glass is partly behind the eye.
pub fn framing_target(eye: Vec3) -> Vec3 {
    let centre = crate::scene::SCENE_CENTRE;
    let mut target = centre;
    // Re-aim at the angular middle of the picture's extent; a few rounds converge (each moves
    // the aim less). Should a round put part of the glass behind the eye, keep the last aim.
    for _ in 0..12 {
        let Some((x0, x1, y0, y1)) = scene_extent(eye, target) else {
            break;
        };
        let cam = Camera::new(eye, target, 1, 1, std::f64::consts::FRAC_PI_2);
        let mid = |a: f64, b: f64| libm::tan(0.5 * (libm::atan(a) + libm::atan(b)));
        let forward = (cam.forward + mid(x0, x1) * cam.right + mid(y0, y1) * cam.up).normalize();
        let next = eye + (centre - eye).length() * forward;
        if scene_extent(eye, next).is_none() {
            break;
        }
        target = next;
    }
    target
}
