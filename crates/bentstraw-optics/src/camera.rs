//! The observer's pinhole camera (SPEC §6).

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

impl Camera {
    /// The camera of SPEC §6 at `eye`, aimed at `target`, with vertical field of view `fov_y` (radians).
    ///
    /// The caller guarantees `eye != target`, `width, height > 0` and `0 < fov_y < π`.
    pub fn new(eye: Vec3, target: Vec3, width: u32, height: u32, fov_y: f64) -> Camera {
        let forward = (target - eye).normalize();
        let c = forward.cross(Vec3::Z);
        let right = if c.length() < 1e-9 {
            Vec3::X
        } else {
            c.normalize()
        };
        let up = right.cross(forward);
        Camera {
            eye,
            forward,
            right,
            up,
            width,
            height,
            tan_half_fov: (fov_y / 2.0).tan(),
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

/// The vertical field of view (radians) that just frames the glass and the straw, with a margin of
/// [`FRAMING_MARGIN`], for a camera at `eye` aimed at `target` with `aspect = width / height`.
///
/// Glass and straw (wherever it stands) lie in the cylinder of radius `Rv` from `z = 0` to `Hp`; a
/// pinhole picture of a cylinder is bounded by the pictures of its two end circles, so the field is
/// the smallest that holds those circles. Capped at [`MAX_FRAMING_FOV`] (also when part of the
/// cylinder is behind the eye).
pub fn framing_fov(eye: Vec3, target: Vec3, aspect: f64) -> f64 {
    // A 1×1 camera with a 90° field measures image-plane coordinates at unit distance.
    let cam = Camera::new(eye, target, 1, 1, std::f64::consts::FRAC_PI_2);
    let mut half = 0.0f64; // the largest tan(φ/2) needed
    const STEPS: usize = 1440;
    for k in 0..STEPS {
        let a = k as f64 * std::f64::consts::TAU / STEPS as f64;
        for z in [0.0, STRAW_HEIGHT] {
            let v = Vec3::new(GLASS_RADIUS * a.cos(), GLASS_RADIUS * a.sin(), z) - eye;
            let depth = v.dot(cam.forward);
            if depth <= 1e-9 {
                return MAX_FRAMING_FOV;
            }
            let x = v.dot(cam.right) / depth;
            let y = v.dot(cam.up) / depth;
            half = half.max(y.abs()).max(x.abs() / aspect);
        }
    }
    (2.0 * (half * (1.0 + FRAMING_MARGIN)).atan()).min(MAX_FRAMING_FOV)
}
