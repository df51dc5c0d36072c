//! The camera of a picture: where it looks, how wide and how large, checked; plain values that
//! the command line's flags and the explorer's queries both give.

use bentstraw_optics::camera::{framing_fov, Camera};
use bentstraw_optics::scene::SCENE_CENTRE;
use bentstraw_optics::text::number_text;
use bentstraw_optics::view::DEFAULT_SIZE;
use bentstraw_optics::Vec3;

use crate::error::{fail, Result};
use bentstraw_optics::setup::Setup;

/// A camera as asked for: each value optional, a default chosen from the scene when absent.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct CameraSpec {
    /// The point looked at.
    pub target: Option<[f64; 3]>,
    /// Vertical field of view in degrees.
    pub fov: Option<f64>,
    /// Picture size in pixels.
    pub size: Option<(u32, u32)>,
}

/// Most pixels on a side of a picture.
pub const MAX_SIDE: u32 = 16384;
/// Most pixels in a picture (the renderer keeps a few dozen bytes per pixel in memory).
pub const MAX_PIXELS: u64 = 25_000_000;

/// The validated camera of `args` at `observer`: target (default the scene's centre) finite and
/// away from the observer, field of view in (0°, 180°) (default: framing the glass and straw).
pub fn camera_from_args(args: &CameraSpec, observer: Vec3) -> Result<Camera> {
    let target = match args.target {
        Some(t) => checked_target(t)?,
        None => SCENE_CENTRE,
    };
    check_target_away(target, observer)?;
    let (width, height) = checked_size(args.size.unwrap_or(DEFAULT_SIZE))?;
    let fov = match args.fov {
        Some(deg) => checked_fov_deg(deg)?.to_radians(),
        None => framing_fov(observer, target, width as f64 / height as f64),
    };
    Ok(Camera::new(observer, target, width, height, fov))
}

/// `--target` as a point, if every coordinate is finite.
pub fn checked_target(t: [f64; 3]) -> Result<Vec3> {
    for (name, v) in ["X", "Y", "Z"].iter().zip(t) {
        if !v.is_finite() {
            return fail(format!(
                "--target {name} = {} is not a finite number",
                number_text(v)
            ));
        }
    }
    Ok(Vec3::from_array(t))
}

/// Refuses a camera target at the observer's position (the camera would look nowhere).
pub fn check_target_away(target: Vec3, observer: Vec3) -> Result {
    if (target - observer).length() < 1e-9 {
        return fail(format!(
            "--target ({}, {}, {}) is the observer's position: the camera must look somewhere else",
            number_text(target.x),
            number_text(target.y),
            number_text(target.z)
        ));
    }
    Ok(())
}

/// A picture size within [`MAX_PIXELS`] (the sides are checked by the `WxH` parser).
pub fn checked_size((width, height): (u32, u32)) -> Result<(u32, u32)> {
    if !(1..=MAX_SIDE).contains(&width) || !(1..=MAX_SIDE).contains(&height) {
        return fail(format!(
            "--size {width}x{height} is not allowed: each side must be between 1 and {MAX_SIDE} pixels"
        ));
    }
    if width as u64 * height as u64 > MAX_PIXELS {
        return fail(format!(
            "--size {width}x{height} is too large: a picture may have at most {MAX_PIXELS} pixels (e.g. 6000x4000)"
        ));
    }
    Ok((width, height))
}

/// A vertical field of view in degrees, `0 < FOV < 180`.
pub fn checked_fov_deg(deg: f64) -> Result<f64> {
    if !deg.is_finite() || deg <= 0.0 || deg >= 180.0 {
        return fail(format!(
            "--fov {} is not allowed: the field of view must be a number of degrees with 0 < FOV < 180",
            number_text(deg)
        ));
    }
    Ok(deg)
}

/// The camera of `spec` for the scene at its observer: aimed at the target given, else the scene
/// file's, else the scene's centre; framing the scene ([`Setup::framing_fov`]) unless a field of
/// view is given. Every picture is asked for through it.
pub fn scene_camera(loaded: &Setup, spec: &CameraSpec) -> Result<Camera> {
    let observer = loaded.observer;
    let target = match spec.target {
        Some(t) => checked_target(t)?,
        None => loaded.default_target(),
    };
    check_target_away(target, observer)?;
    let (width, height) = checked_size(spec.size.unwrap_or(DEFAULT_SIZE))?;
    let fov = match spec.fov {
        Some(deg) => checked_fov_deg(deg)?.to_radians(),
        None => loaded.framing_fov(observer, target, width as f64 / height as f64),
    };
    Ok(Camera::new(observer, target, width, height, fov))
}
