//! `bentstraw table` (and `bentstraw` alone): the four reference simulations of SPEC §5, each also
//! with `n_water = 1` (whose image points must lie on the straw) and `n_water = 1.05`, written as
//! CSV, PNG and HTML into one folder with an `index.html` report.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use bentstraw_optics::apparent::{eye_model_points, stereo_points};
use bentstraw_optics::sampling::{sample_image, ImageCloud};
use bentstraw_optics::scene::{Reference, Scene, REFERENCES, SECTION_NAMES, WATER_INDEX};
use bentstraw_optics::Vec3;
use rayon::prelude::*;

use crate::cli::TableArgs;
use crate::commands::simulate::simulation_title;
use crate::error::{fail, CliResult};
use crate::files::{self, Output, OutputSet};
use crate::model_plots::{write_gap_plot, write_model_comparison, GapSeries, ModelCloud};
use crate::report::{self, Check, Figure, Link, Report, Section, SimulationEntry, Timing};
use crate::writers::{write_points, ModelPoints, PointFormat, PointSet};
use crate::{html, pictures, plot, progress};

/// Most image points per simulation: the table traces twelve, and runs the eye and stereo models
/// on four (measured on two cores: 16 s and 270 MB for 100 000 points, 35–80 s and 490 MB for
/// 200 000, depending on the load).
pub const MAX_POINTS: usize = 200_000;

/// The report's file name in the folder.
const REPORT_FILE: &str = "index.html";

/// Largest distance (m) from the straw's surface an `n_water = 1` image point may have.
pub const ON_STRAW_TOLERANCE: f64 = 1e-9;

/// The water indices of each reference: the real one, then the two checks, with file suffixes.
const VARIANTS: [(f64, &str); 3] = [(WATER_INDEX, ""), (1.0, "_n1"), (1.05, "_n1.05")];

/// What the classic figure shows.
const CLOUD_CAPTION: &str = "The image points in their section colours, the water as a wireframe \
                             and the observer (black circle), seen from three sides.";

/// One simulation of the table.
struct Job {
    /// The reference it belongs to.
    reference: Reference,
    /// Its scene (reference geometry with this variant's index).
    scene: Scene,
    /// File stem, e.g. `sim1_n1.05`.
    stem: String,
}

impl Job {
    /// The names of every file this simulation writes, so that all are reserved before the work.
    fn outputs(&self) -> Vec<String> {
        let stem = &self.stem;
        let mut names = vec![
            format!("{stem}.csv"),
            format!("{stem}.png"),
            format!("{stem}.html"),
        ];
        if self.scene.n_water == WATER_INDEX {
            for suffix in [
                "_observer.png",
                "_cloud.png",
                "_eye.csv",
                "_eye.html",
                "_stereo.csv",
                "_stereo.html",
                "_models.png",
                "_gap.png",
            ] {
                names.push(format!("{stem}{suffix}"));
            }
        }
        names
    }
}

/// Runs `table`.
pub fn run(args: &TableArgs) -> CliResult {
    if args.points == 0 {
        return fail("--points 0 is not allowed: ask for at least 1 image point per simulation");
    }
    if args.points > MAX_POINTS {
        return fail(format!(
            "--points {} is too many for the table: at most {MAX_POINTS} image points per \
             simulation (twelve simulations, four with the eye and stereo models: about 500 MB and \
             a minute at the limit); use simulate for one large simulation",
            args.points
        ));
    }
    let out = &args.out;
    if out.exists() && !out.is_dir() {
        return fail(format!(
            "--out {}: it exists and is not a folder",
            files::shown(out)
        ));
    }
    let made = files::make_folder(out)?;
    let result = run_into(args, out);
    if result.is_err() {
        // A failed run leaves no folder it made (the set removed its temporaries).
        files::remove_made_folders(&made);
    }
    result
}

/// Runs the table into the existing folder `out`; every file is replaced, or none.
fn run_into(args: &TableArgs, out: &Path) -> CliResult {
    let jobs: Vec<Job> = REFERENCES
        .iter()
        .flat_map(|r| {
            VARIANTS.iter().map(move |&(n, suffix)| Job {
                reference: *r,
                scene: r.scene(n),
                stem: format!("sim{}{suffix}", r.number),
            })
        })
        .collect();
    let paths: Vec<PathBuf> = jobs
        .iter()
        .flat_map(|job| job.outputs())
        .chain([REPORT_FILE.to_string()])
        .map(|name| out.join(name))
        .collect();
    let outputs: Vec<Output> = paths
        .iter()
        .map(|path| Output {
            flag: "--out",
            path,
            extensions: &[],
        })
        .collect();
    let outputs = OutputSet::reserve_folder(out, &outputs)?;

    let started = Instant::now();
    let entries: Vec<SimulationEntry> = progress::with_progress(
        Some(jobs.len() as u64),
        "simulating {bar:30} {pos}/{len}  [{elapsed}, about {eta} left]",
        |bar| {
            // In parallel: the figures are drawn on one thread each, so this is where cores help.
            jobs.par_iter()
                .map(|job| {
                    let entry = run_job(job, out, args.points);
                    bar.inc(1);
                    entry
                })
                .collect()
        },
    );
    let elapsed = started.elapsed();

    let report = Report {
        title: "bentstraw: the straw's virtual image".into(),
        subtitle: format!(
            "The four reference simulations of the straw in a glass of water, each also with water of \
             index 1 (the image must then lie on the straw) and 1.05; at least {} image points each.",
            args.points
        ),
        simulations: entries,
        total: elapsed,
    };
    report::write_report(&out.join(REPORT_FILE), &report)?;

    // Any file that could not be written: nothing is replaced, the previous table stays whole.
    let failed: Vec<(&str, &str)> = report
        .simulations
        .iter()
        .flat_map(|s| &s.sections)
        .flat_map(|s| &s.figures)
        .flat_map(|f| {
            let own = f.error.as_deref().map(|e| (f.file.as_str(), e));
            let links = f
                .links
                .iter()
                .filter_map(|l| l.error.as_deref().map(|e| (l.file.as_str(), e)));
            own.into_iter().chain(links)
        })
        .collect();
    if let Some((file, error)) = failed.first() {
        return fail(format!(
            "{} file(s) could not be written (first: {file}: {error}); no file in {} was replaced",
            failed.len(),
            files::shown(out)
        ));
    }
    outputs.commit()?;
    progress::tell(&summary(&report, out));

    // A failed check is reported after the files are in place, so that the report shows it.
    let off: Vec<&SimulationEntry> = report
        .simulations
        .iter()
        .filter(|s| s.check.as_ref().is_some_and(|c| !c.passed))
        .collect();
    if let Some(first) = off.first() {
        return fail(format!(
            "check failed: {} ({} check(s) failed in all)",
            first
                .check
                .as_ref()
                .map(|c| c.text.as_str())
                .unwrap_or_default(),
            off.len()
        ));
    }
    Ok(())
}

/// Traces one simulation, writes its files, and describes it for the report.
fn run_job(job: &Job, out: &Path, points: usize) -> SimulationEntry {
    let (scene, observer) = (&job.scene, job.reference.observer);
    let t0 = Instant::now();
    let cloud = sample_image(scene, observer, points, &|_| {});
    let traced = t0.elapsed();

    let t1 = Instant::now();
    let set = PointSet {
        scene,
        observer,
        min_points: points,
        model: ModelPoints::Course,
        cloud: &cloud,
    };
    let title = format!(
        "{}: {}",
        simulation_heading(job),
        simulation_title(scene, observer)
    );
    let csv = format!("{}.csv", job.stem);
    let png = format!("{}.png", job.stem);
    let page = format!("{}.html", job.stem);
    let data_error = write_points(&out.join(&csv), PointFormat::Csv, &set).err();
    let plot_error =
        plot::write_cloud_figure(&out.join(&png), scene, observer, &cloud.points, &title).err();
    let page_error =
        html::write_cloud_viewer(&out.join(&page), scene, observer, &cloud.points, &title).err();
    let written = t1.elapsed();

    let mut figure = Figure::image(&png, CLOUD_CAPTION);
    figure.error = plot_error.map(|e| e.0);
    figure.links = vec![
        Link::new(&page, "rotatable 3D view", page_error.map(|e| e.0)),
        Link::new(&csv, "points (CSV)", data_error.map(|e| e.0)),
    ];

    let mut timings = vec![
        Timing::new("tracing", traced),
        Timing::new("writing files", written),
    ];
    let mut sections = vec![Section {
        title: "Virtual image points (course convention, P = O + L·u0)".into(),
        figures: vec![figure],
        notes: vec![distance_note(scene, &cloud)],
        side_by_side: false,
    }];
    // The reference simulations proper (not the index checks) also get the observer's picture and
    // the apparent-position models.
    if scene.n_water == WATER_INDEX {
        let t = Instant::now();
        sections.push(observer_section(job, out, &cloud));
        timings.push(Timing::new("observer's picture", t.elapsed()));
        let t = Instant::now();
        sections.push(models_section(job, out, &cloud));
        timings.push(Timing::new("eye and stereo models", t.elapsed()));
    }

    SimulationEntry {
        id: job.stem.clone(),
        reference: job.reference.number,
        heading: simulation_heading(job),
        inputs: inputs(scene, observer),
        n_water: scene.n_water,
        rays: cloud.rays_traced,
        points: cloud.points.len(),
        counts: cloud.counts_per_color(),
        hit_ratio: cloud.hit_ratio(),
        timings,
        check: check(scene, &cloud),
        solution_check: Some(crate::commands::check::own_points_check(
            scene,
            observer,
            &cloud.points,
        )),
        sections,
    }
}

/// What the observer's eye sees (SPEC §6, fresnel mode) beside the image points through the same camera.
fn observer_section(job: &Job, out: &Path, cloud: &ImageCloud) -> Section {
    let (scene, observer) = (&job.scene, job.reference.observer);
    let seen = format!("{}_observer.png", job.stem);
    let splat = format!("{}_cloud.png", job.stem);
    let error = pictures::write_observer_pictures(out, &job.stem, scene, observer, &cloud.points)
        .err()
        .map(|e| e.0);
    let mut picture = Figure::image(
        &seen,
        "What the observer sees: a pinhole camera at the observer, Fresnel reflection and \
         refraction at every water face, a checkerboard wall and floor behind the glass.",
    );
    picture.error = error.clone();
    let mut points = Figure::image(
        &splat,
        "The course's image points seen through the same camera: each lies on the ray that \
         shows it, so the two pictures agree on where each colour appears.",
    );
    points.error = error;
    Section {
        title: "What the observer sees (Fresnel picture)".into(),
        figures: vec![picture, points],
        notes: vec![],
        side_by_side: true,
    }
}

/// The course's, the eye's and the stereo image side by side, and how far apart they are.
fn models_section(job: &Job, out: &Path, cloud: &ImageCloud) -> Section {
    let (scene, observer) = (&job.scene, job.reference.observer);
    let eye = eye_model_points(scene, observer, &cloud.points);
    let stereo = stereo_points(scene, observer, &cloud.points);
    let mut figures = Vec::new();
    let mut placed = Vec::new();
    let mut links = Vec::new();
    for model in [
        ModelPoints::Course,
        ModelPoints::Eye(&eye),
        ModelPoints::Stereo(&stereo),
    ] {
        let set = PointSet {
            scene,
            observer,
            min_points: cloud.points.len(),
            model,
            cloud,
        };
        let points = set.placed_points();
        if !matches!(model, ModelPoints::Course) {
            let csv = format!("{}_{}.csv", job.stem, model.name());
            let page = format!("{}_{}.html", job.stem, model.name());
            let title = format!(
                "{} ({} model)",
                simulation_title(scene, observer),
                model.name()
            );
            let data_error = write_points(&out.join(&csv), PointFormat::Csv, &set).err();
            let page_error =
                html::write_cloud_viewer(&out.join(&page), scene, observer, &points, &title).err();
            links.push(Link::new(
                &page,
                &format!("{} model, 3D view", model.name()),
                page_error.map(|e| e.0),
            ));
            links.push(Link::new(
                &csv,
                &format!("{} model, points (CSV)", model.name()),
                data_error.map(|e| e.0),
            ));
        }
        placed.push(points);
    }
    let names = [
        "course (P = O + L·u0)",
        "eye (small pupil)",
        "stereo (two eyes, 65 mm)",
    ];
    let clouds: Vec<ModelCloud> = names
        .iter()
        .zip(&placed)
        .map(|(name, points)| ModelCloud { name, points })
        .collect();
    let compare = format!("{}_models.png", job.stem);
    let title = format!("{}: where the straw appears", simulation_heading(job));
    let mut figure = Figure::image(
        &compare,
        "The same straw points placed by the three models, seen from the same side and scale.",
    );
    figure.error = write_model_comparison(&out.join(&compare), scene, observer, &clouds, &title)
        .err()
        .map(|e| e.0);
    figure.links = links;
    figures.push(figure);

    let eye_gaps: Vec<(f64, f64, u8)> = eye
        .iter()
        .filter_map(|p| Some((p.image.straw_point.z, p.gap_to_course()?, p.image.color)))
        .collect();
    let stereo_gaps: Vec<(f64, f64, u8)> = stereo
        .points
        .iter()
        .filter_map(|p| Some((p.image.straw_point.z, p.gap_to_course()?, p.image.color)))
        .collect();
    let gap = format!("{}_gap.png", job.stem);
    let series = [
        GapSeries {
            name: "eye model",
            samples: &eye_gaps,
        },
        GapSeries {
            name: "stereo model",
            samples: &stereo_gaps,
        },
    ];
    let mut figure = Figure::image(
        &gap,
        "Distance between the course's image point and the eye model's (and the stereo model's) \
         point of the same straw point, against the height of that straw point.",
    );
    let gap_title = format!(
        "{}: distance from the course's image point to the eye's and the stereo point",
        simulation_heading(job)
    );
    figure.error = write_gap_plot(&out.join(&gap), &series, &gap_title)
        .err()
        .map(|e| e.0);
    figures.push(figure);

    let unplaced = eye.iter().filter(|p| p.position.is_none()).count();
    let max_gap = eye_gaps.iter().map(|g| g.1).fold(0.0, f64::max);
    let mut sorted: Vec<f64> = eye_gaps.iter().map(|g| g.1).collect();
    sorted.sort_by(f64::total_cmp);
    let median = sorted.get(sorted.len() / 2).copied().unwrap_or(0.0);
    Section {
        title: "Where the straw really appears: course, eye and stereo models".into(),
        figures,
        notes: vec![
            format!(
                "Eye model: {} of {} points placed at (s_h + s_v)/2 along their ray; {unplaced} without a \
                 position (a focus unresolved, at infinity or behind the eye). Gap to the course's point: \
                 median {:.2} mm, largest {:.2} mm.",
                eye.len() - unplaced,
                eye.len(),
                1e3 * median,
                1e3 * max_gap
            ),
            format!(
                "Stereo model: {} points seen by both eyes and triangulated, {} seen by one eye only.",
                stereo.points.len(),
                stereo.skipped
            ),
        ],
        side_by_side: false,
    }
}

/// "Simulation 1", "Simulation 1, check n_water = 1", …
fn simulation_heading(job: &Job) -> String {
    let n = job.scene.n_water;
    if n == WATER_INDEX {
        format!("Simulation {}", job.reference.number)
    } else {
        format!("Simulation {}, check n_water = {n}", job.reference.number)
    }
}

/// The inputs as label/value rows.
fn inputs(scene: &Scene, o: Vec3) -> Vec<(String, String)> {
    vec![
        ("observer".into(), format!("({}, {}, {}) m", o.x, o.y, o.z)),
        (
            "straw axis".into(),
            format!("({}, {}) m", scene.straw_x, scene.straw_y),
        ),
        ("water height".into(), format!("{} m", scene.water_height)),
        ("water index".into(), format!("{}", scene.n_water)),
        ("event limit".into(), format!("{}", scene.max_events)),
    ]
}

/// The built-in check of SPEC §4 for `n_water = 1`: every image point lies on the straw.
fn check(scene: &Scene, cloud: &ImageCloud) -> Option<Check> {
    if scene.n_water != 1.0 {
        return None;
    }
    let max = max_distance_to_straw(scene, cloud);
    let passed = !cloud.points.is_empty() && max < ON_STRAW_TOLERANCE;
    let text = if cloud.points.is_empty() {
        "n_water = 1: no image points to check".to_string()
    } else {
        format!(
            "n_water = 1: the {} image points lie on the straw, at most {max:.3e} m from its surface \
             (limit {ON_STRAW_TOLERANCE:e} m): {}",
            cloud.points.len(),
            if passed { "pass" } else { "FAIL" }
        )
    };
    let short = format!(
        "on the straw, max {max:.1e} m: {}",
        if passed { "pass" } else { "FAIL" }
    );
    Some(Check {
        passed,
        text,
        short,
    })
}

/// How far the image lies from the real straw: zero for `n_water = 1`, growing with the index.
fn distance_note(scene: &Scene, cloud: &ImageCloud) -> String {
    if cloud.points.is_empty() {
        return "No image point: the straw is not seen from here.".into();
    }
    format!(
        "The image points lie up to {:.3} mm from the straw's surface (n_water = {}; with \
         n_water = 1 they would lie on it).",
        1e3 * max_distance_to_straw(scene, cloud),
        scene.n_water
    )
}

/// Largest distance (m) of an image point from the straw's surface.
fn max_distance_to_straw(scene: &Scene, cloud: &ImageCloud) -> f64 {
    cloud
        .points
        .iter()
        .map(|p| scene.distance_to_straw_surface(p.position))
        .fold(0.0, f64::max)
}

/// The table printed on stderr at the end.
fn summary(report: &Report, out: &Path) -> String {
    let mut t = String::new();
    let _ = writeln!(
        t,
        "bentstraw table: {} simulations in {:.2} s, written to {}",
        report.simulations.len(),
        report.total.as_secs_f64(),
        out.display()
    );
    let _ = write!(
        t,
        "  {:<11} {:>7} {:>9} {:>8} {:>6}",
        "simulation", "n_water", "rays", "points", "hit %"
    );
    for name in SECTION_NAMES {
        let _ = write!(t, " {name:>7}");
    }
    let _ = writeln!(t, " {:>8}  check", "time s");
    for s in &report.simulations {
        let _ = write!(
            t,
            "  {:<11} {:>7} {:>9} {:>8} {:>6.1}",
            s.id,
            s.n_water,
            s.rays,
            s.points,
            100.0 * s.hit_ratio
        );
        for c in s.counts {
            let _ = write!(t, " {c:>7}");
        }
        let secs: Duration = s.timings.iter().map(|t| t.duration).sum();
        let check = s.check.as_ref().map(|c| c.short.as_str()).unwrap_or("");
        let _ = writeln!(t, " {:>8.2}  {check}", secs.as_secs_f64());
    }
    let _ = writeln!(t, "  report: {}", out.join(REPORT_FILE).display());
    t
}
