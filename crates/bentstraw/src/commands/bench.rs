//! `bentstraw bench`: how many primary rays per second the picture tracer traces.
//!
//! Each case renders one observer's picture (one ray per pixel centre, nothing written) a first
//! time to warm up, then `--repeat` times; the median time is reported, once in a one-thread rayon
//! pool and once in a pool of `--threads` (default: all cores).
//!
//! With `--models`, each view's image points ([`MODEL_POINTS`] of them, as `simulate` samples
//! them) are then timed beside the eye and the stereo model on those points, in the pool of
//! `--threads`: the best of [`MODEL_RUNS`] runs each, in nanoseconds per point.

use std::time::Instant;

use bentstraw_optics::apparent::{eye_model_points, stereo_points};
use bentstraw_optics::camera::Camera;
use bentstraw_optics::frame::{draw_frame, Frame, FrameRequest};
use bentstraw_optics::picture::{course_picture_into, fresnel_picture_into};
use bentstraw_optics::sampling::sample_image;
use bentstraw_optics::scene::SECTION_COUNT;
use bentstraw_optics::scene::{Scene, REFERENCES, WATER_INDEX};
use bentstraw_optics::shading::{Backdrop, ShadingMode, ShadingOptions};
use bentstraw_optics::world::{World, COLOR_COUNT};
use bentstraw_optics::Vec3;

use crate::cli::{BenchArgs, ModeArg};
use crate::error::{fail, CliError, CliResult};
use bentstraw_io::camera;

/// Vertical field of view of the benchmark views (degrees).
const BENCH_FOV_DEG: f64 = 50.0;
/// Picture size of the benchmark views.
const BENCH_SIZE: (u32, u32) = (1024, 768);
/// Most timed pictures per case.
const MAX_REPEAT: usize = 1000;
/// Most primary rays one case may trace, warm-up included: about a minute in fresnel mode on one
/// thread at the measured 16–17 M rays/s, so that no `--repeat` and `--size` run for hours.
const MAX_RAYS_PER_CASE: u64 = 1_000_000_000;
/// Image points per view on which `--models` times the models.
const MODEL_POINTS: usize = 50_000;
/// Timed runs of each model per view (the best is reported), after one warm-up run.
const MODEL_RUNS: usize = 3;
/// Fresnel branches lighter than this are abandoned (the same default as `render --prune`).
const BENCH_PRUNE: f64 = 1e-4;

/// One view to time.
struct View {
    /// Reference simulation number, or `None` for a view given on the command line.
    simulation: Option<u32>,
    world: World,
    camera: Camera,
}

/// One timed case.
struct Measure {
    simulation: Option<u32>,
    mode: ModeArg,
    threads: usize,
    width: u32,
    height: u32,
    seconds: f64,
}

impl Measure {
    fn rays(&self) -> u64 {
        self.width as u64 * self.height as u64
    }
}

/// Runs `bench`.
pub fn run(args: &BenchArgs) -> CliResult {
    if args.repeat == 0 {
        return fail("--repeat 0 is not allowed: it must be at least 1");
    }
    if args.repeat > MAX_REPEAT {
        return fail(format!(
            "--repeat {} is not allowed: at most {MAX_REPEAT} timed pictures per case",
            args.repeat
        ));
    }
    let all_cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    let threads = args.threads.unwrap_or(all_cores);
    if threads == 0 || threads > 1024 {
        return fail(format!(
            "--threads {threads} is not allowed: it must be between 1 and 1024"
        ));
    }
    let views = views(args)?;
    if let Some(v) = views.first() {
        let rays = v.camera.width as u64 * v.camera.height as u64 * (args.repeat as u64 + 1);
        if rays > MAX_RAYS_PER_CASE {
            return fail(format!(
                "--repeat {} at {}x{} pixels is too much: a case may trace at most {MAX_RAYS_PER_CASE} \
                 rays (pixels × (repeats + 1), about a minute); use fewer repeats or a smaller --size",
                args.repeat, v.camera.width, v.camera.height
            ));
        }
    }
    let modes: Vec<ModeArg> = match args.mode {
        Some(m) => vec![m],
        None => vec![ModeArg::Course, ModeArg::Fresnel],
    };
    let mut counts = vec![1];
    if threads != 1 {
        counts.push(threads);
    }
    let pools = counts
        .iter()
        .map(|&n| {
            rayon::ThreadPoolBuilder::new()
                .num_threads(n)
                .build()
                .map_err(|e| CliError(format!("cannot start {n} worker threads: {e}")))
        })
        .collect::<CliResult<Vec<_>>>()?;

    if !args.json {
        print_line(&format!(
            "{:<10} {:<8} {:>7} {:>10} {:>11} {:>12} {:>14}",
            "view", "mode", "threads", "size", "ms/picture", "Mrays/s", "Mpixels/s"
        ))?;
    }
    let mut measures = Vec::new();
    for view in &views {
        for &mode in &modes {
            for (&n, pool) in counts.iter().zip(&pools) {
                let seconds = pool.install(|| {
                    if args.frame {
                        time_frame(view, mode, args.repeat)
                    } else {
                        time_picture(view, mode, args.repeat)
                    }
                });
                let m = Measure {
                    simulation: view.simulation,
                    mode,
                    threads: n,
                    width: view.camera.width,
                    height: view.camera.height,
                    seconds,
                };
                print_measure(&m, args.json)?;
                measures.push(m);
            }
        }
    }
    print_averages(&measures, &modes, &counts, args.json)?;
    if args.models {
        let (&n, pool) = counts
            .iter()
            .zip(&pools)
            .next_back()
            .expect("one pool at least");
        if !args.json {
            print_line(&format!(
                "{:<10} {:>7} {:>8} {:>16} {:>14} {:>7} {:>14} {:>7}",
                "view",
                "threads",
                "points",
                "image ns/point",
                "eye ns/point",
                "ratio",
                "stereo ns/point",
                "ratio"
            ))?;
        }
        for view in &views {
            let costs = pool.install(|| time_models(view));
            print_model_costs(view.simulation, n, &costs, args.json)?;
        }
    }
    Ok(())
}

/// What one view's image points and models cost.
struct ModelCosts {
    /// Image points sampled.
    points: usize,
    /// Best time (s) of sampling the image points, of the eye model and of the stereo model.
    image: f64,
    eye: f64,
    stereo: f64,
}

/// Times the image points of `view`'s observer and both models on them (best of [`MODEL_RUNS`],
/// after a warm-up).
fn time_models(view: &View) -> ModelCosts {
    let (world, observer) = (&view.world, view.camera.eye);
    let best = |work: &dyn Fn()| {
        work();
        (0..MODEL_RUNS)
            .map(|_| {
                let start = Instant::now();
                work();
                start.elapsed().as_secs_f64()
            })
            .fold(f64::INFINITY, f64::min)
    };
    let cloud = sample_image(world, observer, MODEL_POINTS, &|_| {});
    let points = &cloud.points;
    ModelCosts {
        points: points.len(),
        image: best(&|| {
            std::hint::black_box(sample_image(world, observer, MODEL_POINTS, &|_| {}));
        }),
        eye: best(&|| {
            std::hint::black_box(eye_model_points(world, observer, points));
        }),
        stereo: best(&|| {
            std::hint::black_box(stereo_points(world, observer, points));
        }),
    }
}

fn print_model_costs(
    simulation: Option<u32>,
    threads: usize,
    c: &ModelCosts,
    json: bool,
) -> CliResult {
    let per_point = |s: f64| 1e9 * s / c.points.max(1) as f64;
    if json {
        let line = serde_json::json!({
            "simulation": simulation,
            "models": true,
            "threads": threads,
            "points": c.points,
            "image_ns_per_point": per_point(c.image),
            "eye_ns_per_point": per_point(c.eye),
            "eye_ratio": c.eye / c.image,
            "stereo_ns_per_point": per_point(c.stereo),
            "stereo_ratio": c.stereo / c.image,
        });
        print_line(&line.to_string())
    } else {
        let view = simulation.map_or_else(|| "given".to_string(), |n| format!("sim {n}"));
        print_line(&format!(
            "{:<10} {:>7} {:>8} {:>16.0} {:>14.0} {:>7.2} {:>14.0} {:>7.2}",
            view,
            threads,
            c.points,
            per_point(c.image),
            per_point(c.eye),
            c.eye / c.image,
            per_point(c.stereo),
            c.stereo / c.image
        ))
    }
}

/// The views to time: the one given by the scene flags, or the four reference views.
fn views(args: &BenchArgs) -> CliResult<Vec<View>> {
    // The same rules as `render`'s camera, with the benchmark's defaults.
    let (w, h) = camera::checked_size(args.camera.size.unwrap_or(BENCH_SIZE))?;
    let fov_deg = camera::checked_fov_deg(args.camera.fov.unwrap_or(BENCH_FOV_DEG))?;
    let target_flag = args.camera.target.map(camera::checked_target).transpose()?;
    let camera_for = |eye: Vec3, target: Vec3| -> CliResult<Camera> {
        camera::check_target_away(target, eye)?;
        Ok(Camera::new(eye, target, w, h, fov_deg.to_radians()))
    };
    let given = [
        args.view.observer.is_some(),
        args.view.straw.is_some(),
        args.view.water_height.is_some(),
    ];
    if args.view.scene.is_some() || given.iter().any(|&g| g) {
        if args.view.scene.is_none() && !given.iter().all(|&g| g) {
            return fail(
                "a single view needs all three of --observer, --straw and --water-height, or a --scene file (give none to time the four reference views)",
            );
        }
        let loaded = crate::cli::load_scene(&args.view.view()?)?;
        let target = target_flag.unwrap_or(loaded.default_target());
        let (world, observer) = (loaded.world, loaded.observer);
        let camera = camera_for(observer, target)?;
        return Ok(vec![View {
            simulation: None,
            world,
            camera,
        }]);
    }
    REFERENCES
        .iter()
        .map(|r| {
            let scene = Scene::new(
                r.straw.0,
                r.straw.1,
                r.water_height,
                args.view.n_water.unwrap_or(WATER_INDEX),
                args.view.max_events,
            )?;
            // Zoomed on the straw where it enters the water (the bottom, for an observer below).
            let camera = camera_for(r.observer, target_flag.unwrap_or(r.zoom_target()))?;
            Ok(View {
                simulation: Some(r.number),
                world: World::assignment(&scene),
                camera,
            })
        })
        .collect()
}

/// Median time (s) of `repeat` pictures of `view` in `mode`, after one warm-up picture.
///
/// The picture goes into one buffer reused from run to run, as an interactive view would: the time
/// is the tracing's, not the allocator's.
fn time_picture(view: &View, mode: ModeArg, repeat: usize) -> f64 {
    let pixels = view.camera.width as usize * view.camera.height as usize;
    // Only the mode's buffer: at the largest size the weights alone take 1 GB.
    // The weights of the colour codes the world can show: a straw's five bands, or all eight.
    let straws_only = view.world.color_codes() <= SECTION_COUNT;
    let (mut codes, mut weights, mut all_weights) = match mode {
        ModeArg::Course => (vec![0u8; pixels], Vec::new(), Vec::new()),
        ModeArg::Fresnel if straws_only => {
            (Vec::new(), vec![[0.0; SECTION_COUNT]; pixels], Vec::new())
        }
        ModeArg::Fresnel => (Vec::new(), Vec::new(), vec![[0.0; COLOR_COUNT]; pixels]),
    };
    let world = &view.world;
    let mut once = || -> f64 {
        let start = Instant::now();
        match mode {
            ModeArg::Course => course_picture_into(world, &view.camera, &mut codes),
            ModeArg::Fresnel if straws_only => {
                fresnel_picture_into(world, &view.camera, BENCH_PRUNE, &mut weights)
            }
            ModeArg::Fresnel => {
                fresnel_picture_into(world, &view.camera, BENCH_PRUNE, &mut all_weights)
            }
        }
        std::hint::black_box((&codes, &weights, &all_weights));
        start.elapsed().as_secs_f64()
    };
    once();
    median((0..repeat).map(|_| once()).collect())
}

/// Median time (s) of `repeat` frames of `view` in `mode` as `render` draws them (the frame call,
/// picture only: shaded, checkerboard backdrop, 3x3 samples at edges), after one warm-up, into
/// one frame reused from run to run as the explorer does.
fn time_frame(view: &View, mode: ModeArg, repeat: usize) -> f64 {
    let request = FrameRequest {
        camera: view.camera,
        shading: ShadingOptions {
            mode: match mode {
                ModeArg::Course => ShadingMode::Course,
                ModeArg::Fresnel => ShadingMode::Fresnel {
                    prune_below: BENCH_PRUNE,
                },
            },
            backdrop: Backdrop::Checker,
            samples: 3,
            adaptive: true,
            outline: true,
            white: false,
        },
        min_points: 0,
    };
    let mut frame = Frame::default();
    let mut once = || -> f64 {
        let start = Instant::now();
        draw_frame(&view.world, &request, &mut frame);
        std::hint::black_box(&frame.picture);
        start.elapsed().as_secs_f64()
    };
    once();
    median((0..repeat).map(|_| once()).collect())
}

/// The median of `times`.
fn median(mut times: Vec<f64>) -> f64 {
    times.sort_by(f64::total_cmp);
    let mid = times.len() / 2;
    if times.len() % 2 == 1 {
        times[mid]
    } else {
        0.5 * (times[mid - 1] + times[mid])
    }
}

fn mode_name(mode: ModeArg) -> &'static str {
    match mode {
        ModeArg::Course => "course",
        ModeArg::Fresnel => "fresnel",
    }
}

/// Writes one line to stdout; a closed or full stdout ends the run with a message, not a panic.
fn print_line(line: &str) -> CliResult {
    use std::io::Write;
    writeln!(std::io::stdout().lock(), "{line}")
        .map_err(|e| CliError(format!("cannot write to standard output: {e}")))
}

fn print_measure(m: &Measure, json: bool) -> CliResult {
    let rays = m.rays() as f64;
    if json {
        let line = serde_json::json!({
            "simulation": m.simulation,
            "mode": mode_name(m.mode),
            "threads": m.threads,
            "width": m.width,
            "height": m.height,
            "rays": m.rays(),
            "seconds": m.seconds,
            "rays_per_s": rays / m.seconds,
            "pixels_per_s": rays / m.seconds,
        });
        print_line(&line.to_string())
    } else {
        let view = m
            .simulation
            .map_or_else(|| "given".to_string(), |n| format!("sim {n}"));
        print_line(&format!(
            "{:<10} {:<8} {:>7} {:>10} {:>11.3} {:>12.2} {:>14.2}",
            view,
            mode_name(m.mode),
            m.threads,
            format!("{}x{}", m.width, m.height),
            1e3 * m.seconds,
            rays / m.seconds / 1e6,
            rays / m.seconds / 1e6
        ))
    }
}

/// Per mode and thread count: all rays over all time (the mean time per picture).
fn print_averages(
    measures: &[Measure],
    modes: &[ModeArg],
    counts: &[usize],
    json: bool,
) -> CliResult {
    let mut parts = Vec::new();
    for &mode in modes {
        for &n in counts {
            let sel: Vec<&Measure> = measures
                .iter()
                .filter(|m| m.mode == mode && m.threads == n)
                .collect();
            let rays: u64 = sel.iter().map(|m| m.rays()).sum();
            let seconds: f64 = sel.iter().map(|m| m.seconds).sum();
            let per_s = rays as f64 / seconds;
            let per_picture = seconds / sel.len() as f64;
            if json {
                let line = serde_json::json!({
                    "simulation": "average",
                    "mode": mode_name(mode),
                    "threads": n,
                    "pictures": sel.len(),
                    "rays": rays,
                    "seconds": seconds,
                    "seconds_per_picture": per_picture,
                    "rays_per_s": per_s,
                    "pixels_per_s": per_s,
                });
                print_line(&line.to_string())?;
            } else {
                parts.push(format!(
                    "{} {}T {:.2} Mrays/s {:.3} ms/picture",
                    mode_name(mode),
                    n,
                    per_s / 1e6,
                    1e3 * per_picture
                ));
            }
        }
    }
    if !json {
        print_line(&format!("average: {}", parts.join("; ")))?;
    }
    Ok(())
}
