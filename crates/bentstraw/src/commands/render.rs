//! `bentstraw render`: the observer's picture as a PNG for people, and optionally one ray
//! per pixel centre as CSV.

use std::path::Path;
use std::time::Instant;

use bentstraw_optics::camera::{framing_fov, framing_fov_box, Camera};
use bentstraw_optics::frame::{draw_frame, Frame, FrameRequest};
use bentstraw_optics::picture::{course_picture_exact, fresnel_picture_exact};
use bentstraw_optics::scene::{number_text, SCENE_CENTRE, SECTION_COUNT};
use bentstraw_optics::shading::{Backdrop, ShadingMode, ShadingOptions};
use bentstraw_optics::world::World;
use bentstraw_optics::Vec3;

use crate::cli::{BackdropArg, CameraArgs, ModeArg, RenderArgs};
use crate::error::{fail, CliResult};
use crate::files::{self, Output, OutputSet};
use crate::pictures::png_bytes;
use crate::progress;
use crate::scene_input::{AnyScene, FileWorld};

/// Picture size when `--size` is not given.
pub const DEFAULT_SIZE: (u32, u32) = (800, 600);
/// Most samples per pixel side accepted by `--samples`.
pub const MAX_SAMPLES: u32 = 16;
/// Most pixels in a picture (the renderer keeps a few dozen bytes per pixel in memory).
pub const MAX_PIXELS: u64 = 25_000_000;

/// The validated camera of `args` at `observer`: target (default the scene's centre) finite and
/// away from the observer, field of view in (0°, 180°) (default: framing the glass and straw).
pub fn camera_from_args(args: &CameraArgs, observer: Vec3) -> CliResult<Camera> {
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
pub fn checked_target(t: [f64; 3]) -> CliResult<Vec3> {
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
pub fn check_target_away(target: Vec3, observer: Vec3) -> CliResult {
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
pub fn checked_size((width, height): (u32, u32)) -> CliResult<(u32, u32)> {
    if width as u64 * height as u64 > MAX_PIXELS {
        return fail(format!(
            "--size {width}x{height} is too large: a picture may have at most {MAX_PIXELS} pixels (e.g. 6000x4000)"
        ));
    }
    Ok((width, height))
}

/// A vertical field of view in degrees, `0 < FOV < 180`.
pub fn checked_fov_deg(deg: f64) -> CliResult<f64> {
    if !deg.is_finite() || deg <= 0.0 || deg >= 180.0 {
        return fail(format!(
            "--fov {} is not allowed: the field of view must be a number of degrees with 0 < FOV < 180",
            number_text(deg)
        ));
    }
    Ok(deg)
}

/// Runs `render`.
pub fn run(args: &RenderArgs) -> CliResult {
    let start = Instant::now();
    // Everything is checked before any work, so bad input leaves no file.
    let (world, camera) = match args.scene.source().resolve_any()? {
        AnyScene::Spec(resolved) => {
            // A scene file's target stands in for an absent --target.
            let camera_args = CameraArgs {
                target: args.camera.target.or(resolved.target.map(|t| t.to_array())),
                ..args.camera.clone()
            };
            let camera = camera_from_args(&camera_args, resolved.observer)?;
            (World::assignment(&resolved.scene), camera)
        }
        AnyScene::File(file) => {
            let camera = world_camera(&file, &args.camera)?;
            (file.world, camera)
        }
    };
    let (options, outputs) = shading_and_outputs(args)?;
    // The explorer's frame call, picture only: the command line draws as fast as the live view,
    // with a bar (after a second) whose estimate follows the rows drawn.
    let mut frame = Frame::default();
    let rows = frame.picture_progress();
    let total = 2 * camera.height as u64;
    let picture = progress::with_progress(
        Some(total),
        "rendering {bar:30} {percent}%  [{elapsed}, about {eta} left]",
        |bar| {
            let done = std::sync::atomic::AtomicBool::new(false);
            std::thread::scope(|s| {
                let watcher = s.spawn(|| {
                    while !done.load(std::sync::atomic::Ordering::Relaxed) {
                        bar.set_position(rows.load(std::sync::atomic::Ordering::Relaxed));
                        // Woken at once when the picture is done (a sleep would add its rest).
                        std::thread::park_timeout(std::time::Duration::from_millis(100));
                    }
                });
                let request = FrameRequest {
                    camera,
                    shading: options,
                    min_points: 0,
                };
                draw_frame(&world, &request, &mut frame);
                done.store(true, std::sync::atomic::Ordering::Relaxed);
                watcher.thread().unpark();
            });
            std::mem::take(&mut frame.picture)
        },
    );
    let png = png_bytes(&picture)?;
    files::write_bytes(&args.output, &png)?;
    if let Some(raw) = &args.raw {
        write_raw(raw, &world, &camera, args.mode, args.prune)?;
    }
    outputs.commit()?;
    tell_rendered(args, &camera, start);
    Ok(())
}

/// The shading options of `args`, checked, and its outputs reserved (the previous picture and raw
/// file stay until both new ones are complete).
fn shading_and_outputs(args: &RenderArgs) -> CliResult<(ShadingOptions, OutputSet)> {
    if !args.prune.is_finite() || !(0.0..1.0).contains(&args.prune) {
        return fail(format!(
            "--prune {} is not allowed: the pruning weight must satisfy 0 <= W < 1",
            number_text(args.prune)
        ));
    }
    if !(1..=MAX_SAMPLES).contains(&args.samples) {
        return fail(format!(
            "--samples {} is not allowed: samples per pixel side must be between 1 and {MAX_SAMPLES}",
            args.samples
        ));
    }
    let mut outputs = vec![Output {
        flag: "--output",
        path: &args.output,
        extensions: &["png"],
    }];
    if let Some(raw) = &args.raw {
        outputs.push(Output {
            flag: "--raw",
            path: raw,
            extensions: &["csv"],
        });
    }
    let outputs = OutputSet::reserve(&outputs)?;
    let mode = match args.mode {
        ModeArg::Course => ShadingMode::Course,
        ModeArg::Fresnel => ShadingMode::Fresnel {
            prune_below: args.prune,
        },
    };
    let options = ShadingOptions {
        mode,
        backdrop: match args.backdrop {
            BackdropArg::None => Backdrop::Plain,
            BackdropArg::Checker => Backdrop::Checker,
        },
        samples: args.samples,
        outline: true,
    };
    Ok((options, outputs))
}

/// The camera of `camera_args` for a scene file's world: aimed at `--target`, else the file's
/// target, else the middle of the scene; framing the whole scene unless `--fov` is given.
pub fn world_camera(world: &FileWorld, camera_args: &CameraArgs) -> CliResult<Camera> {
    let (lo, hi) = world.world.bounds();
    let target = camera_args
        .target
        .or(world.target.map(|t| t.to_array()))
        .unwrap_or((0.5 * (lo + hi)).to_array());
    let mut camera = camera_from_args(
        &CameraArgs {
            target: Some(target),
            ..camera_args.clone()
        },
        world.observer,
    )?;
    if camera_args.fov.is_none() {
        let aspect = camera.width as f64 / camera.height as f64;
        let fov = framing_fov_box(world.observer, Vec3::from_array(target), (lo, hi), aspect);
        camera.tan_half_fov = (fov / 2.0).tan();
    }
    Ok(camera)
}

/// The one line `render` says when done.
fn tell_rendered(args: &RenderArgs, camera: &Camera, start: Instant) {
    let fov_deg = 2.0 * camera.tan_half_fov.atan().to_degrees();
    progress::tell(&format!(
        "render: {} mode, {}x{} pixels, {n}x{n} samples per pixel, fov {fov_deg:.2}°: wrote {}{} in {:.2} s\n",
        match args.mode {
            ModeArg::Course => "course",
            ModeArg::Fresnel => "fresnel",
        },
        camera.width,
        camera.height,
        args.output.display(),
        args.raw
            .as_ref()
            .map(|r| format!(" and {}", r.display()))
            .unwrap_or_default(),
        start.elapsed().as_secs_f64(),
        n = args.samples,
    ));
}

/// Writes one ray per pixel centre, row-major: `row,col,color` (course) or `row,col,w1..w5`
/// (fresnel, each weight in the shortest form that reads back as the same `f64`; exact zeros as `0`).
///
/// Traced in double precision: a data file is for checking, where the last edge pixel matters
/// more than the milliseconds the single-precision picture path saves.
fn write_raw(path: &Path, world: &World, camera: &Camera, mode: ModeArg, prune: f64) -> CliResult {
    match mode {
        ModeArg::Course => write_raw_codes(path, camera, &course_picture_exact(world, camera)),
        // Straws alone show five colours (their bands); coins and cards, eight codes in all.
        ModeArg::Fresnel if world.color_codes() <= SECTION_COUNT => {
            let all = fresnel_picture_exact(world, camera, prune);
            let sections: Vec<[f64; SECTION_COUNT]> =
                all.iter().map(|w| std::array::from_fn(|k| w[k])).collect();
            write_raw_weights(path, camera, &sections)
        }
        ModeArg::Fresnel => {
            write_raw_weights(path, camera, &fresnel_picture_exact(world, camera, prune))
        }
    }
}

/// Writes one colour code per pixel centre, row-major: `row,col,color`.
fn write_raw_codes(path: &Path, camera: &Camera, codes: &[u8]) -> CliResult {
    let w = camera.width as usize;
    files::write_atomically(path, |out| {
        writeln!(out, "row,col,color")?;
        for (k, code) in codes.iter().enumerate() {
            writeln!(out, "{},{},{code}", k / w, k % w)?;
        }
        Ok(())
    })
}

/// Writes the weights of each pixel centre's ray on each colour code, row-major:
/// `row,col,w1,…,wN`, each in the shortest form that reads back as the same `f64` (zeros as `0`).
fn write_raw_weights<const N: usize>(
    path: &Path,
    camera: &Camera,
    weights: &[[f64; N]],
) -> CliResult {
    let w = camera.width as usize;
    let mut digits = ryu::Buffer::new();
    files::write_atomically(path, |out| {
        write!(out, "row,col")?;
        for k in 1..=N {
            write!(out, ",w{k}")?;
        }
        writeln!(out)?;
        for (k, px) in weights.iter().enumerate() {
            write!(out, "{},{}", k / w, k % w)?;
            for v in px {
                if *v == 0.0 {
                    write!(out, ",0")?;
                } else {
                    write!(out, ",{}", digits.format_finite(*v))?;
                }
            }
            writeln!(out)?;
        }
        Ok(())
    })
}
