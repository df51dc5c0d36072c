//! `bentstraw render`: the observer's picture as a PNG for people, and optionally one ray
//! per pixel centre as CSV.

use std::path::Path;
use std::time::Instant;

use bentstraw_optics::camera::Camera;
use bentstraw_optics::frame::{draw_frame, Frame, FrameRequest};
use bentstraw_optics::picture::{course_picture_exact, fresnel_picture_exact};
use bentstraw_optics::scene::SECTION_COUNT;
use bentstraw_optics::shading::ShadingOptions;
use bentstraw_optics::view::PictureSpec;
use bentstraw_optics::world::World;

use crate::cli::{ModeArg, RenderArgs};
use crate::error::CliResult;
use crate::progress;
use bentstraw_io::camera::scene_camera;
use bentstraw_io::files::{self, Output, OutputSet};
use bentstraw_io::pictures::{checked_shading, png_bytes};
use bentstraw_io::writers::{raw_weight_count, write_raw_codes, write_raw_weights};

/// Runs `render`.
pub fn run(args: &RenderArgs) -> CliResult {
    let start = Instant::now();
    // Everything is checked before any work, so bad input leaves no file.
    let view = args.view()?;
    let loaded = crate::cli::load_scene(&view)?;
    let camera = scene_camera(&loaded, &view.camera)?;
    let world = loaded.world;
    let (options, outputs) = shading_and_outputs(args, &view.picture)?;
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

/// The shading options of `picture`, checked, and the outputs of `args` reserved (the previous
/// picture and raw file stay until both new ones are complete).
fn shading_and_outputs(
    args: &RenderArgs,
    picture: &PictureSpec,
) -> CliResult<(ShadingOptions, OutputSet)> {
    let options = checked_shading(picture)?;
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
    Ok((options, outputs))
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
fn write_raw(
    path: &Path,
    world: &World,
    camera: &Camera,
    mode: ModeArg,
    prune: f64,
) -> bentstraw_io::Result {
    match mode {
        ModeArg::Course => write_raw_codes(path, camera, &course_picture_exact(world, camera)),
        ModeArg::Fresnel if raw_weight_count(world) == SECTION_COUNT => {
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
