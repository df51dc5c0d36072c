//! Pictures of one simulation for reports: the observer's picture (Fresnel mode) and the point
//! cloud seen through the same camera, side by side.

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

use bentstraw_optics::camera::{framing_fov, framing_target, Camera};
use bentstraw_optics::frame::{draw_frame, Frame, FrameRequest};
use bentstraw_optics::image::ImagePoint;
use bentstraw_optics::shading::{
    cloud_picture, splat_radius, Backdrop, RgbPicture, ShadingMode, ShadingOptions,
};
use bentstraw_optics::text::number_text;
use bentstraw_optics::view::{PictureSpec, DEFAULT_PRUNE, MAX_SAMPLES};
use bentstraw_optics::world::World;
use bentstraw_optics::Vec3;
use image::codecs::png::PngEncoder;
use image::{ExtendedColorType, ImageEncoder};

use crate::error::{Error, Result};
use crate::files;

/// Size of the report's observer pictures (pixels): what a page shows of them, half the screen
/// report's width, or a column of a printed A4 page at 300 dpi.
pub const REPORT_SIZE: (u32, u32) = (1000, 750);
/// Pruning threshold of the report's Fresnel pictures.
pub const REPORT_PRUNE: f64 = DEFAULT_PRUNE;

/// `samples` per pixel side if within 1..=[`MAX_SAMPLES`], else the message that refuses it.
pub fn checked_samples(samples: u32) -> std::result::Result<u32, String> {
    if (1..=MAX_SAMPLES).contains(&samples) {
        Ok(samples)
    } else {
        Err(format!(
            "--samples {samples} is not allowed: samples per pixel side must be between 1 and {MAX_SAMPLES}"
        ))
    }
}

/// The PNG encoding of `picture`.
pub fn png_bytes(picture: &RgbPicture) -> Result<Vec<u8>> {
    let mut bytes = Vec::new();
    PngEncoder::new(&mut bytes)
        .write_image(
            &picture.pixels,
            picture.width,
            picture.height,
            ExtendedColorType::Rgb8,
        )
        .map_err(|e| Error::Encode(format!("cannot encode the picture as PNG: {e}")))?;
    Ok(bytes)
}

/// The shading of a picture as asked for (Fresnel or the course's one colour per sample, the
/// pruning weight, a checker backdrop or none, samples per pixel side), or a refusal naming every
/// value outside its rule.
pub fn checked_shading(spec: &PictureSpec) -> Result<ShadingOptions> {
    let (prune, samples) = (spec.prune, spec.samples);
    let mut broken = Vec::new();
    if !prune.is_finite() || !(0.0..1.0).contains(&prune) {
        broken.push(format!(
            "--prune {} is not allowed: the pruning weight must satisfy 0 <= W < 1",
            number_text(prune)
        ));
    }
    if let Err(message) = checked_samples(samples) {
        broken.push(message);
    }
    if !broken.is_empty() {
        return Err(Error::Refused(broken.join("\n")));
    }
    Ok(spec.shading())
}

/// The picture `camera` takes of `world` with `shading`, drawn by the explorer's frame call
/// (picture only): what `render` writes, the page shows and the Python package returns.
pub fn picture(world: &World, camera: Camera, shading: ShadingOptions) -> RgbPicture {
    picture_until(world, camera, shading, &Arc::new(AtomicBool::new(false)))
        .expect("a picture nobody stops is whole")
}

/// [`picture`], given up row by row once `stop` is set (another thread's: a Python caller's
/// Ctrl-C): `None` then.
pub fn picture_until(
    world: &World,
    camera: Camera,
    shading: ShadingOptions,
    stop: &Arc<AtomicBool>,
) -> Option<RgbPicture> {
    let mut frame = Frame::with_stop_flag(Arc::clone(stop));
    let request = FrameRequest {
        camera,
        shading,
        min_points: 0,
    };
    draw_frame(world, &request, &mut frame);
    (!stop.load(Ordering::Relaxed)).then(|| std::mem::take(&mut frame.picture))
}

/// The report's camera at `observer`: [`REPORT_SIZE`], aimed at the glass (not at its box's
/// centre, which close observers see off-centre), the field of view framing glass and straw.
pub fn report_camera(observer: Vec3) -> Camera {
    let (w, h) = REPORT_SIZE;
    let target = framing_target(observer);
    let fov = framing_fov(observer, target, w as f64 / h as f64);
    Camera::new(observer, target, w, h, fov)
}

/// What `camera` sees of `scene` (Fresnel mode, checker backdrop) as PNG bytes, through the
/// explorer's frame call (picture only).
fn seen_png(world: &World, camera: Camera) -> Result<Vec<u8>> {
    let options = ShadingOptions {
        mode: ShadingMode::Fresnel {
            prune_below: REPORT_PRUNE,
        },
        backdrop: Backdrop::Checker,
        samples: 3,
        adaptive: true,
        outline: true,
        white: false,
    };
    png_bytes(&picture(world, camera, options))
}

/// Writes `path`: what `observer` sees through the report's camera.
pub fn write_view_picture(path: &Path, world: &World, observer: Vec3) -> Result {
    files::write_bytes(path, &seen_png(world, report_camera(observer))?)
}

/// Writes `<dir>/<stem>_observer.png` (what `camera` sees, Fresnel mode: the
/// [`report_camera`] for the assignment's glass) and `<dir>/<stem>_cloud.png` (the image
/// `points`, seen through the same camera); returns their paths in that order.
pub fn write_observer_pictures(
    dir: &Path,
    stem: &str,
    world: &World,
    camera: Camera,
    points: &[ImagePoint],
) -> Result<(PathBuf, PathBuf)> {
    let view = dir.join(format!("{stem}_observer.png"));
    let cloud = dir.join(format!("{stem}_cloud.png"));
    files::check_writable(&view)?;
    files::check_writable(&cloud)?;
    let seen = seen_png(world, camera)?;
    let splat = png_bytes(&cloud_picture(
        world,
        &camera,
        points,
        splat_radius(&camera, points),
    ))?;
    files::write_bytes(&view, &seen)?;
    files::write_bytes(&cloud, &splat)?;
    Ok((view, cloud))
}

#[cfg(test)]
mod tests {
    use super::*;
    use bentstraw_optics::sampling::sample_image;
    use bentstraw_optics::scene::{REFERENCES, WATER_INDEX};

    /// Both pictures of a reference are written, as PNGs of the report's size, and differ (one
    /// is the rendered view, the other the splatted cloud).
    #[test]
    fn observer_pictures_are_written_for_a_reference() {
        let dir = tempfile::tempdir().unwrap();
        // BENTSTRAW_PICTURES_DIR keeps the pictures somewhere to look at them.
        let keep = std::env::var_os("BENTSTRAW_PICTURES_DIR").map(PathBuf::from);
        for r in REFERENCES {
            let scene = r.scene(WATER_INDEX);
            let cloud = sample_image(&World::assignment(&scene), r.observer, 20000, &|_| {});
            let out = keep.clone().unwrap_or_else(|| dir.path().to_path_buf());
            let stem = format!("sim{}", r.number);
            let (view, splat) = write_observer_pictures(
                &out,
                &stem,
                &World::assignment(&scene),
                report_camera(r.observer),
                &cloud.points,
            )
            .unwrap();
            assert_eq!(view, out.join(format!("sim{}_observer.png", r.number)));
            assert_eq!(splat, out.join(format!("sim{}_cloud.png", r.number)));
            let a = image::open(&view).unwrap().to_rgb8();
            let b = image::open(&splat).unwrap().to_rgb8();
            assert_eq!(a.dimensions(), REPORT_SIZE);
            assert_eq!(b.dimensions(), REPORT_SIZE);
            assert_ne!(a.as_raw(), b.as_raw());
        }
    }
}
