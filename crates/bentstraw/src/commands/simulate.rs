//! `bentstraw simulate`: trace rays from one observer, write the image points, optionally draw them.
//!
//! Everything is checked before any ray is traced (the scene, the point count, every output path),
//! so a mistake costs nothing and leaves no file behind.

use std::time::Instant;

use bentstraw_optics::apparent::{eye_model_points, stereo_points, ApparentPoint, StereoImage};
use bentstraw_optics::sampling::{sample_image_until, ImageCloud};
use std::sync::atomic::AtomicBool;

use crate::cli::{ImageModelArg, SimulateArgs};
use crate::error::CliResult;
use crate::progress;
use bentstraw_io::files::{Output, OutputSet};
use bentstraw_io::model_plots::{
    eye_gap_samples, stereo_gap_samples, write_gap_plot, write_model_comparison, GapSeries,
    ModelCloud, MODEL_NAMES,
};
use bentstraw_io::summary::{model_summary, summary};
use bentstraw_io::words::Lang;
use bentstraw_io::writers::{check_points_asked, write_points, ModelPoints, PointFormat, PointSet};
use bentstraw_io::{html, plot, ray_diagram};
use bentstraw_optics::setup::Setup;

/// Runs `simulate`: the same steps for the assignment's glass (traced by its fast tracers) and
/// for a scene file's world.
pub fn run(args: &SimulateArgs) -> CliResult {
    // 1. Validate everything, trace nothing yet.
    let view = args.view()?;
    let loaded = crate::cli::load_scene(&view)?;
    let (scene, observer) = (&loaded, loaded.observer);
    // The model comparison and the gap plot need both the eye and the stereo model.
    let both_models = args.models_plot.is_some() || args.gap_plot.is_some();
    let models = match args.image_model {
        _ if both_models => "eye and stereo (--models-plot, --gap-plot)",
        ImageModelArg::Course => "course",
        ImageModelArg::Eye => "eye",
        ImageModelArg::Stereo => "stereo",
    };
    check_points_asked(view.points, models)?;
    let format = PointFormat::from_path(&args.output)?;
    let mut outputs = vec![Output {
        flag: "--output",
        path: &args.output,
        extensions: &[],
    }];
    let figures = [
        ("--plot", &args.plot),
        ("--html", &args.html),
        ("--rays", &args.rays),
        ("--models-plot", &args.models_plot),
        ("--gap-plot", &args.gap_plot),
    ];
    for (flag, path) in figures {
        if let Some(path) = path {
            let extensions = if flag == "--html" {
                &["html", "htm"][..]
            } else {
                plot::FIGURE_EXTENSIONS
            };
            outputs.push(Output {
                flag,
                path,
                extensions,
            });
        }
    }
    // The previous files stay until every new one is complete.
    let outputs = OutputSet::reserve(&outputs)?;

    // 2. Trace.
    let started = Instant::now();
    let cloud = trace_with_spinner(scene, view.points, view.picture.white);
    let traced = started.elapsed();

    // 3. The apparent-position model, if not the course's.
    let modelled = Instant::now();
    let eye = (both_models || args.image_model == ImageModelArg::Eye).then(|| {
        with_spinner("eye model", || {
            eye_model_points(&scene.world, observer, &cloud.points)
        })
    });
    let stereo = (both_models || args.image_model == ImageModelArg::Stereo).then(|| {
        with_spinner("stereo model", || {
            stereo_points(&scene.world, observer, &cloud.points)
        })
    });
    let model = match (args.image_model, &eye, &stereo) {
        (ImageModelArg::Eye, Some(eye), _) => ModelPoints::Eye(eye),
        (ImageModelArg::Stereo, _, Some(stereo)) => ModelPoints::Stereo(stereo),
        _ => ModelPoints::Course,
    };
    let modelled = modelled.elapsed();

    // 4. Write.
    let set = PointSet {
        scene,
        min_points: view.points,
        model,
        cloud: &cloud,
    };
    let title = format!("{} ({} model)", inputs_title(scene), model.name());
    write_points(&args.output, format, &set)?;
    if args.plot.is_some() || args.html.is_some() {
        let placed = set.placed_points();
        if let Some(p) = &args.plot {
            plot::write_cloud_figure(p, scene, observer, &placed, &title)?;
        }
        if let Some(h) = &args.html {
            html::write_cloud_viewer(h, scene, observer, &placed, &title)?;
        }
    }
    if let Some(r) = &args.rays {
        let diagram = ray_diagram::Diagram::new(&scene.world, observer, &cloud.points);
        let title = format!("Ray diagram: {}", inputs_title(scene));
        ray_diagram::write_ray_diagram(r, scene, &diagram, &title, Lang::En)?;
    }
    if let (Some(eye), Some(stereo)) = (&eye, &stereo) {
        write_model_figures(args, &set, eye, stereo)?;
    }
    outputs.commit()?;
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
    if let Some(r) = &args.rays {
        written.push(format!("{} (ray diagram)", r.display()));
    }
    if let Some(m) = &args.models_plot {
        written.push(format!("{} (the three models compared)", m.display()));
    }
    if let Some(g) = &args.gap_plot {
        written.push(format!("{} (gap to the course's points)", g.display()));
    }
    progress::tell(&summary(&set, traced, total, &written));
    if !matches!(model, ModelPoints::Course) {
        progress::tell(&model_summary(&set, modelled));
    }
    Ok(())
}

/// The model comparison and the gap plot, if asked for: the course's, the eye's and the stereo
/// points of `set`'s cloud.
fn write_model_figures(
    args: &SimulateArgs,
    set: &PointSet,
    eye: &[ApparentPoint],
    stereo: &StereoImage,
) -> CliResult {
    let inputs = inputs_title(set.scene);
    if let Some(path) = &args.models_plot {
        let placed = [
            ModelPoints::Course,
            ModelPoints::Eye(eye),
            ModelPoints::Stereo(stereo),
        ]
        .map(|model| PointSet { model, ..*set }.placed_points());
        let clouds: Vec<ModelCloud> = MODEL_NAMES
            .iter()
            .zip(&placed)
            .map(|(name, points)| ModelCloud { name, points })
            .collect();
        let what = match set.scene.subject() {
            Some(subject) => format!("{subject} appears"),
            None => "the objects appear".to_string(),
        };
        let title = format!("Where {what}: {inputs}");
        write_model_comparison(path, set.scene, set.scene.observer, &clouds, &title)?;
    }
    if let Some(path) = &args.gap_plot {
        let (eye_gaps, stereo_gaps) = (eye_gap_samples(eye), stereo_gap_samples(stereo));
        let series = GapSeries::of_models(&eye_gaps, &stereo_gaps, Lang::En);
        let title =
            format!("Gap from the course's point to the eye's and the stereo point: {inputs}");
        write_gap_plot(path, &series, &title, Lang::En)?;
    }
    Ok(())
}

/// Runs `work` with a spinner on stderr if it takes a while.
fn with_spinner<T>(what: &str, work: impl FnOnce() -> T) -> T {
    progress::with_progress(None, &format!("{{spinner}} {what}  [{{elapsed}}]"), |_| {
        work()
    })
}

/// Samples the image of the scene's objects (in white light if `white`), with a spinner counting
/// rays when it takes a while.
fn trace_with_spinner(scene: &Setup, min_points: usize, white: bool) -> ImageCloud {
    progress::with_progress(
        None,
        "{spinner} tracing rays: {human_pos} so far  [{elapsed}]",
        |bar| {
            let progress = |rays| bar.set_position(rays);
            let never = AtomicBool::new(false);
            sample_image_until(
                &scene.world,
                scene.observer,
                min_points,
                white,
                &progress,
                &never,
            )
            .expect("a stop flag never set does not stop the sampling")
        },
    )
}

/// The inputs in words, for figures' titles: the assignment's values, or a scene file's name and
/// the observer.
fn inputs_title(scene: &Setup) -> String {
    scene.inputs_line(false)
}
