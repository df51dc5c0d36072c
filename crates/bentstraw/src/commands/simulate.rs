//! `bentstraw simulate`: trace rays from one observer, write the image points, optionally draw them.
//!
//! Everything is checked before any ray is traced (the scene, the point count, every output path),
//! so a mistake costs nothing and leaves no file behind.

use std::fmt::Write as _;
use std::path::Path;
use std::time::{Duration, Instant};

use bentstraw_optics::sampling::{sample_image, ImageCloud};
use bentstraw_optics::scene::{Scene, SECTION_NAMES};
use bentstraw_optics::Vec3;
use clap::ValueEnum;

use crate::cli::{ImageModelArg, SimulateArgs};
use crate::error::{fail, CliError, CliResult};
use crate::files::check_writable;
use crate::writers::{write_points, PointFormat, PointSet};
use crate::{html, plot, progress};

/// Runs `simulate`.
pub fn run(args: &SimulateArgs) -> CliResult {
    // 1. Validate everything, trace nothing yet.
    let (scene, observer) = args.scene.scene_and_observer()?;
    if args.points == 0 {
        return fail("--points 0 is not allowed: ask for at least 1 image point");
    }
    check_image_model(args.image_model)?;
    let format = PointFormat::from_path(&args.output)?;
    if let Some(p) = &args.plot {
        require_extension(p, "--plot", &["png"])?;
    }
    if let Some(h) = &args.html {
        require_extension(h, "--html", &["html", "htm"])?;
    }
    for path in std::iter::once(&args.output)
        .chain(&args.plot)
        .chain(&args.html)
    {
        check_writable(path)?;
    }

    // 2. Trace.
    let started = Instant::now();
    let cloud = trace_with_spinner(&scene, observer, args.points);
    let traced = started.elapsed();

    // 3. Write.
    let model = model_name(args.image_model);
    let set = PointSet {
        scene: &scene,
        observer,
        min_points: args.points,
        image_model: &model,
        cloud: &cloud,
    };
    write_points(&args.output, format, &set)?;
    let title = simulation_title(&scene, observer);
    if let Some(p) = &args.plot {
        plot::write_cloud_figure(p, &scene, observer, &cloud.points, &title)?;
    }
    if let Some(h) = &args.html {
        html::write_cloud_viewer(h, &scene, observer, &cloud.points, &title)?;
    }
    let total = started.elapsed();

    let mut written = vec![format!(
        "{} ({} points)",
        args.output.display(),
        format.name()
    )];
    if let Some(p) = &args.plot {
        written.push(format!("{} (figure, three views)", p.display()));
    }
    if let Some(h) = &args.html {
        written.push(format!("{} (rotatable 3D view)", h.display()));
    }
    eprint!("{}", summary(&set, traced, total, &written));
    Ok(())
}

// ---- Apparent-position models ---------------------------------------------------------------
// The course's convention (SPEC §4, P = O + L·u0) is what `sample_image` returns. The other models
// (`eye`, `stereo`) are being built separately: they plug in here, as a function turning the traced
// rays into their own points, and `check_image_model` then lets them through.

/// Refuses, before tracing, the image models that do not exist yet.
fn check_image_model(model: ImageModelArg) -> CliResult {
    match model {
        ImageModelArg::Course => Ok(()),
        ImageModelArg::Eye | ImageModelArg::Stereo => fail(format!(
            "--image-model {} is not implemented yet: use --image-model course (the default)",
            model_name(model)
        )),
    }
}

/// The model's name as typed on the command line.
fn model_name(model: ImageModelArg) -> String {
    model
        .to_possible_value()
        .map(|v| v.get_name().to_string())
        .unwrap_or_else(|| format!("{model:?}").to_lowercase())
}

// ---------------------------------------------------------------------------------------------

/// Samples the straw's image, with a spinner counting rays when it takes a while.
pub fn trace_with_spinner(scene: &Scene, observer: Vec3, min_points: usize) -> ImageCloud {
    progress::with_progress(
        None,
        "{spinner} tracing rays: {human_pos} so far  [{elapsed}]",
        |bar| sample_image(scene, observer, min_points, &|rays| bar.set_position(rays)),
    )
}

/// Checks that `path` ends in one of `allowed` (lower-case, without dot).
fn require_extension(path: &Path, flag: &str, allowed: &[&str]) -> CliResult {
    let ext = path
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase());
    if ext.as_deref().is_some_and(|e| allowed.contains(&e)) {
        return Ok(());
    }
    let expected = allowed
        .iter()
        .map(|a| format!(".{a}"))
        .collect::<Vec<_>>()
        .join(" or ");
    Err(CliError(format!(
        "{flag} {}: the file name must end in {expected}",
        path.display()
    )))
}

/// A short title naming the inputs, for figures.
pub fn simulation_title(scene: &Scene, observer: Vec3) -> String {
    format!(
        "observer ({}, {}, {}) m, straw ({}, {}) m, water {} m, n = {}",
        observer.x,
        observer.y,
        observer.z,
        scene.straw_x,
        scene.straw_y,
        scene.water_height,
        scene.n_water
    )
}

/// The one-screen summary printed on stderr; `written` names the files written, one a line.
pub fn summary(set: &PointSet, traced: Duration, total: Duration, written: &[String]) -> String {
    let (s, o, cloud) = (set.scene, set.observer, set.cloud);
    let mut t = String::new();
    let _ = writeln!(
        t,
        "bentstraw simulate: the straw's virtual image ({} model)",
        set.image_model
    );
    let _ = writeln!(t, "  observer        ({}, {}, {}) m", o.x, o.y, o.z);
    let _ = writeln!(t, "  straw axis      ({}, {}) m", s.straw_x, s.straw_y);
    let _ = writeln!(
        t,
        "  water           height {} m, index {}",
        s.water_height, s.n_water
    );
    let _ = writeln!(t, "  event limit     {}", s.max_events);
    let _ = writeln!(t, "  rays traced     {}", cloud.rays_traced);
    let _ = writeln!(
        t,
        "  image points    {} (asked for at least {})",
        cloud.points.len(),
        set.min_points
    );
    for (k, n) in cloud.counts_per_color().iter().enumerate() {
        let _ = writeln!(t, "    {} {:<8} {:>8}", k + 1, SECTION_NAMES[k], n);
    }
    let _ = writeln!(
        t,
        "  hit ratio       {:.1} % of the rays reached the straw",
        100.0 * cloud.hit_ratio()
    );
    let _ = writeln!(
        t,
        "  time            {:.3} s tracing, {:.3} s in all",
        traced.as_secs_f64(),
        total.as_secs_f64()
    );
    if let Some((first, rest)) = written.split_first() {
        let _ = writeln!(t, "  wrote           {first}");
        for w in rest {
            let _ = writeln!(t, "                  {w}");
        }
    }
    if cloud.points.len() < set.min_points {
        let _ = writeln!(
            t,
            "  note            fewer points than asked: the straw is all but invisible from here"
        );
    }
    t
}
