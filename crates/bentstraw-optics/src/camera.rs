//! The observer's pinhole camera (SPEC §6).

use crate::geometry::Ray;
use crate::Vec3;

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
