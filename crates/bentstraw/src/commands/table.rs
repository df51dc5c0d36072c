//! `bentstraw table` (and `bentstraw` alone): the four reference simulations, each also
//! with `n_water = 1` (whose image points must lie on the straw) and `n_water = 1.05`, written as
//! CSV, PNG and HTML into one folder with an `index.html` report.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use bentstraw_optics::apparent::{eye_model_points, stereo_points};
use bentstraw_optics::sampling::{sample_image, ImageCloud};
use bentstraw_optics::scene::{Reference, Scene, REFERENCES, SECTION_NAMES, WATER_INDEX};

use bentstraw_optics::world::World;
use bentstraw_optics::Vec3;
use rayon::prelude::*;

use crate::cli::TableArgs;
use crate::commands::simulate::simulation_title;
use crate::error::{fail, CliResult};
use crate::progress;
use bentstraw_outputs::files::{self, Output, OutputSet};
use bentstraw_outputs::gallery::GALLERY;
use bentstraw_outputs::gallery_report::{gallery_files, gallery_sections};
use bentstraw_outputs::model_plots::{
    eye_gap_samples, stereo_gap_samples, write_gap_plot, write_model_comparison, GapSeries,
    ModelCloud, MODEL_NAMES,
};
use bentstraw_outputs::ray_diagram::{write_ray_diagram, Diagram};
use bentstraw_outputs::report::{
    self, Check, Figure, Link, Report, Section, SimulationEntry, Timing,
};
use bentstraw_outputs::scene_input::Loaded;
use bentstraw_outputs::validation::{self, write_validation_figure, ValidationSeries};
use bentstraw_outputs::writers::{write_csv_gz, ModelPoints, PointSet};
use bentstraw_outputs::{html, pictures, plot};

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
                             and the observer (black dot): a front view from the observer's side, \
                             a side view with the observer to the right, and the view from above.";

/// One simulation of the table.
struct Job {
    /// The reference it belongs to.
    reference: Reference,
    /// Its scene (reference geometry with this variant's index).
    scene: Scene,
    /// That scene seen from the reference's observer, built once for tracing and drawing.
    loaded: Loaded,
    /// File stem, e.g. `sim1_n1.05`.
    stem: String,
}

impl Job {
    /// The names of every file this simulation writes, so that all are reserved before the work.
    fn outputs(&self) -> Vec<String> {
        let stem = &self.stem;
        let mut names = vec![format!("{stem}.csv.gz"), format!("{stem}.svg")];
        if self.scene.n_water() == WATER_INDEX {
            for suffix in [
                ".html",
                "_observer.png",
                "_cloud.png",
                "_models.svg",
                "_gap.svg",
                "_rays.svg",
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
                loaded: Loaded::assignment(r.scene(n), r.observer),
                stem: format!("sim{}{suffix}", r.number),
            })
        })
        .collect();
    let paths: Vec<PathBuf> = jobs
        .iter()
        .flat_map(|job| job.outputs())
        .chain(INTRO_FILES.iter().map(|f| f.to_string()))
        .chain(gallery_files())
        .chain([VALIDATION_FILE.to_string(), REPORT_FILE.to_string()])
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
    // One bar over the whole job: the simulations, the gallery's scenes, then the rest.
    let steps = (jobs.len() + GALLERY.len() + 1) as u64;
    let (entries, intro, closing) = progress::with_progress(
        Some(steps),
        "{msg:22} {bar:30} {pos}/{len}  [{elapsed}, about {eta} left]",
        |bar| {
            bar.set_message("simulations");
            // In parallel: the figures are drawn on one thread each, so this is where cores help.
            let entries: Vec<SimulationEntry> = jobs
                .par_iter()
                .map(|job| {
                    let entry = run_job(job, out, args.points);
                    bar.inc(1);
                    entry
                })
                .collect();
            bar.set_message("gallery");
            let mut closing = gallery_sections(out, &|| bar.inc(1));
            bar.set_message("method and validation");
            let intro = intro_sections(out, args.points);
            closing.extend(closing_sections(out));
            bar.inc(1);
            (entries, intro, closing)
        },
    );
    let elapsed = started.elapsed();

    let report = Report {
        title: "bentstraw: why a straw in a glass of water looks broken".into(),
        subtitle: format!(
            "A short lab report. Rays are traced from the observer's eye through the water \
             (Snell–Descartes refraction and total reflection) to a five-colour straw, and each \
             ray that reaches it gives an image point: where the observer believes that piece of \
             straw is. Four reference simulations, each also with water of index 1 (the image must \
             then lie on the straw) and 1.05; at least {} image points each.",
            args.points
        ),
        intro,
        simulations: entries,
        closing,
        total: elapsed,
    };
    report::write_report(&out.join(REPORT_FILE), &report)?;

    // Any file that could not be written: nothing is replaced, the previous table stays whole.
    let failed: Vec<(&str, &str)> = report
        .simulations
        .iter()
        .flat_map(|s| &s.sections)
        .chain(&report.intro)
        .chain(&report.closing)
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
    let cloud = sample_image(&job.loaded.world, observer, points, &|_| {});
    let traced = t0.elapsed();

    let t1 = Instant::now();
    let title = format!(
        "{}: {}",
        simulation_heading(job),
        simulation_title(scene, observer)
    );
    let csv = format!("{}.csv.gz", job.stem);
    let svg = format!("{}.svg", job.stem);
    let data_error = write_csv_gz(&out.join(&csv), &cloud.points).err();
    // A vector drawing, sharp on screen and on paper.
    let plot_error = plot::write_cloud_figure(
        &out.join(&svg),
        &job.loaded,
        observer,
        &cloud.points,
        &title,
    )
    .err();
    let mut figure = Figure::image(&svg, CLOUD_CAPTION);
    figure.error = plot_error.map(|e| e.to_string());
    // The rotatable view of the reference simulations (the checks' points differ little from it).
    if scene.n_water() == WATER_INDEX {
        let page = format!("{}.html", job.stem);
        let page_error = html::write_cloud_viewer(
            &out.join(&page),
            &job.loaded,
            observer,
            &cloud.points,
            &title,
        )
        .err();
        figure.links.push(Link::new(
            &page,
            "rotatable 3D view",
            page_error.map(|e| e.to_string()),
        ));
    }
    figure.links.push(Link::new(
        &csv,
        "points (CSV, gzip)",
        data_error.map(|e| e.to_string()),
    ));
    let written = t1.elapsed();

    let mut timings = vec![
        Timing::new("tracing", traced),
        Timing::new("writing files", written),
    ];
    let mut sections = vec![Section {
        title: "Virtual image points (course convention, P = O + L·u0)".into(),
        figures: vec![figure],
        notes: vec![distance_note(scene, &cloud)],
        side_by_side: false,
        printed: true,
        table: Vec::new(),
    }];
    // The reference simulations proper (not the index checks) also get the observer's picture and
    // the apparent-position models.
    if scene.n_water() == WATER_INDEX {
        let t = Instant::now();
        sections.push(observer_section(job, out, &cloud));
        timings.push(Timing::new("observer's picture", t.elapsed()));
        let t = Instant::now();
        sections.push(rays_section(job, out, &cloud));
        timings.push(Timing::new("ray diagram", t.elapsed()));
        let t = Instant::now();
        sections.push(models_section(job, out, &cloud));
        timings.push(Timing::new("eye and stereo models", t.elapsed()));
    }

    SimulationEntry {
        id: job.stem.clone(),
        reference: job.reference.number,
        heading: simulation_heading(job),
        inputs: inputs(scene, observer),
        n_water: scene.n_water(),
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

/// What the observer's eye sees (fresnel mode) beside the image points through the same camera.
fn observer_section(job: &Job, out: &Path, cloud: &ImageCloud) -> Section {
    let observer = job.reference.observer;
    let seen = format!("{}_observer.png", job.stem);
    let splat = format!("{}_cloud.png", job.stem);
    let error = pictures::write_observer_pictures(
        out,
        &job.stem,
        &job.loaded.world,
        observer,
        &cloud.points,
    )
    .err()
    .map(|e| e.to_string());
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
        printed: true,
        table: Vec::new(),
    }
}

/// The ray diagram of one simulation: which light paths make which pieces of its image.
fn rays_section(job: &Job, out: &Path, cloud: &ImageCloud) -> Section {
    let (scene, observer) = (&job.scene, job.reference.observer);
    let file = format!("{}_rays.svg", job.stem);
    let diagram = Diagram::new(&job.loaded.world, observer, &cloud.points);
    let title = format!(
        "{} ray diagram: {}",
        simulation_heading(job),
        simulation_title(scene, observer)
    );
    let mut figure = Figure::image(
        &file,
        "About forty of the rays, each drawn as its broken path from the eye (black dot) through \
         the water's faces to the straw, coloured by the kind of light path; rings mark \
         refractions, crosses total reflections, and the dashed line runs from the eye straight \
         to the ray's image point. Side view in the vertical plane through the glass's axis and \
         the observer (the observer to the right), and top view.",
    );
    figure.error = write_ray_diagram(&out.join(&file), &job.loaded, &diagram, &title)
        .err()
        .map(|e| e.to_string());
    let total: usize = diagram.counts.iter().map(|c| c.1).sum::<usize>().max(1);
    let shares: Vec<String> = diagram
        .counts
        .iter()
        .map(|(kind, n)| format!("{kind}: {:.1} %", 100.0 * *n as f64 / total as f64))
        .collect();
    Section {
        title: "Which light path makes which piece (ray diagram)".into(),
        figures: vec![figure],
        notes: vec![format!(
            "Image points by light path: {}. Pieces of the image far from the straw, even \
             outside the glass, come from light totally reflected inside the water: the eye, \
             looking along the first straight piece of the ray, places the straw as far away as \
             the light really travelled.",
            shares.join("; ")
        )],
        side_by_side: false,
        printed: true,
        table: Vec::new(),
    }
}

/// The files of the report's opening sections.
const INTRO_FILES: [&str; 2] = ["classic_view.png", "classic_rays.svg"];
/// The validation figure's file.
const VALIDATION_FILE: &str = "validation.svg";
/// The classic view: an observer 30 cm away, a little above the water, the straw off the axis.
const CLASSIC_OBSERVER: Vec3 = Vec3::new(0.3, 0.0, 0.25);
/// The straw of the classic view.
const CLASSIC_STRAW: (f64, f64) = (0.0, 0.03);
/// Water height of the classic view.
const CLASSIC_WATER: f64 = 0.15;

/// The report's opening: the effect at a glance (a realistic view), and the method with its ray
/// diagram.
fn intro_sections(out: &Path, points: usize) -> Vec<Section> {
    let scene = Scene::with_defaults(CLASSIC_STRAW.0, CLASSIC_STRAW.1, CLASSIC_WATER)
        .expect("the classic view is valid");
    let observer = CLASSIC_OBSERVER;
    let loaded = Loaded::assignment(scene, observer);
    let world = &loaded.world;
    let mut view = Figure::image(
        INTRO_FILES[0],
        "What an eye 30 cm from the glass sees (bentstraw render --observer 0.3,0,0.25 --straw \
         0,0.03 --water-height 0.15): below the water's surface the straw is shifted sideways and \
         looks wider; above it, it is seen straight.",
    );
    view.error = pictures::write_view_picture(&out.join(INTRO_FILES[0]), world, observer)
        .err()
        .map(|e| e.to_string());
    let cloud = sample_image(world, observer, points.min(20_000), &|_| {});
    let diagram = Diagram::new(world, observer, &cloud.points);
    let mut rays = Figure::image(
        INTRO_FILES[1],
        "The same view as a ray diagram: each ray's broken path from the eye to the straw, and \
         the dashed straight line along which the eye looks. The eye places each piece of straw \
         on that line, as far away as the light travelled.",
    );
    rays.error = write_ray_diagram(
        &out.join(INTRO_FILES[1]),
        &loaded,
        &diagram,
        &format!("Ray diagram: {}", simulation_title(&scene, observer)),
    )
    .err()
    .map(|e| e.to_string());
    vec![
        Section {
            title: "The broken straw".into(),
            figures: vec![view],
            notes: vec![],
            side_by_side: false,
            printed: true,
            table: Vec::new(),
        },
        Section {
            title: "Method".into(),
            figures: vec![rays],
            notes: vec![
                "A ray leaves the observer's eye O with direction u0 and goes straight until it \
                 meets a face of the water (its side, its surface, its bottom) or the straw. At a \
                 water face it is refracted by Snell–Descartes, n1 sin θ1 = n2 sin θ2, or totally \
                 reflected when no refracted ray exists (from water to air beyond 48.6°); at most \
                 ten such events. A ray that meets the opaque straw stops there and takes the \
                 colour of that section. Its image point is P = O + L·u0, with L the length of its \
                 broken path: where the eye, looking along u0, believes the light came from. \
                 Rays are spread evenly over the directions in which the straw can be seen."
                    .into(),
                "Every image point is checked: with water of index 1 the points must lie on the \
                 straw; and every simulation's points are re-traced one by one by bentstraw check, \
                 the tool a student uses on their own program's output."
                    .into(),
            ],
            side_by_side: false,
            printed: true,
            table: Vec::new(),
        },
    ]
}

/// The report's closing: the validation as the index grows, and the limits of the model.
fn closing_sections(out: &Path) -> Vec<Section> {
    let series: Vec<ValidationSeries> = REFERENCES
        .par_iter()
        .map(|r| {
            validation::series(
                &format!("simulation {}", r.number),
                &r.scene(WATER_INDEX),
                r.observer,
            )
        })
        .collect();
    let mut figure = Figure::image(
        VALIDATION_FILE,
        "For the image points seen through the water, the largest (solid) and median (dashed) \
         distance from the straw's surface, as the water's index goes from 1 to 1.333, log scale.",
    );
    figure.error = write_validation_figure(&out.join(VALIDATION_FILE), &series)
        .err()
        .map(|e| e.to_string());
    let mut table = vec![{
        let mut head = vec!["n_water".to_string()];
        for s in &series {
            head.push(format!("{}: largest (m)", s.label));
            head.push(format!("{}: median (m)", s.label));
        }
        head
    }];
    for (k, n) in validation::indices().into_iter().enumerate() {
        let mut row = vec![format!("{n:.4}")];
        for s in &series {
            row.push(format!("{:.2e}", s.rows[k].1));
            row.push(format!("{:.2e}", s.rows[k].2));
        }
        table.push(row);
    }
    vec![
        Section {
            title: "Validation".into(),
            figures: vec![figure],
            notes: vec![format!(
                "With index 1 the water bends nothing, and every image point lies on the straw to \
                 rounding (about 1e-16 m); as soon as the index grows, the points seen through the \
                 water leave the straw, by millimetres at first and by centimetres at 1.333. The \
                 points seen straight through air are left out: they lie on the straw whatever the \
                 water. {} image points per simulation and index.",
                validation::VALIDATION_POINTS
            )],
            side_by_side: false,
            printed: true,
            table,
        },
        Section {
            title: "Limits".into(),
            figures: vec![],
            notes: vec![
                "The image point P = O + L·u0 is the course's convention, not what an eye measures: \
                 the eye and stereo models above say where one eye with a small pupil, and two \
                 eyes, see each point. The glass has walls of no thickness and the index of air; \
                 the straw is opaque and its surface does not reflect; light is traced for one \
                 colour (no dispersion). The pictures' Fresnel mode follows at most 2048 ray \
                 segments per ray from the eye."
                    .into(),
            ],
            side_by_side: false,
            printed: true,
            table: Vec::new(),
        },
    ]
}

/// The course's, the eye's and the stereo image side by side, and how far apart they are.
fn models_section(job: &Job, out: &Path, cloud: &ImageCloud) -> Section {
    let (scene, observer) = (&job.scene, job.reference.observer);
    let eye = eye_model_points(&job.loaded.world, observer, &cloud.points);
    let stereo = stereo_points(&job.loaded.world, observer, &cloud.points);
    let placed: Vec<Vec<_>> = [
        ModelPoints::Course,
        ModelPoints::Eye(&eye),
        ModelPoints::Stereo(&stereo),
    ]
    .into_iter()
    .map(|model| {
        PointSet {
            scene: &job.loaded,
            min_points: cloud.points.len(),
            model,
            cloud,
        }
        .placed_points()
    })
    .collect();
    let clouds: Vec<ModelCloud> = MODEL_NAMES
        .iter()
        .zip(&placed)
        .map(|(name, points)| ModelCloud { name, points })
        .collect();
    let compare = format!("{}_models.svg", job.stem);
    let title = format!("{}: where the straw appears", simulation_heading(job));
    let mut figure = Figure::image(
        &compare,
        "The same straw points placed by the three models, seen from the same side and scale.",
    );
    figure.error =
        write_model_comparison(&out.join(&compare), &job.loaded, observer, &clouds, &title)
            .err()
            .map(|e| e.to_string());
    let mut figures = vec![figure];

    let eye_gaps = eye_gap_samples(&eye);
    let stereo_gaps = stereo_gap_samples(&stereo);
    let gap = format!("{}_gap.svg", job.stem);
    let series = GapSeries::of_models(&eye_gaps, &stereo_gaps);
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
        .map(|e| e.to_string());
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
            format!(
                "Each model's points, as a file: bentstraw simulate {} --image-model eye (or \
                 stereo) --output points.csv.",
                simulate_flags(scene, observer)
            ),
        ],
        side_by_side: false,
        printed: true,
        table: Vec::new(),
    }
}

/// "Simulation 1", "Simulation 1, check n_water = 1", …
fn simulation_heading(job: &Job) -> String {
    let n = job.scene.n_water();
    if n == WATER_INDEX {
        format!("Simulation {}", job.reference.number)
    } else {
        format!("Simulation {}, check n_water = {n}", job.reference.number)
    }
}

/// The flags of `bentstraw simulate` that give `scene` seen from `o`.
fn simulate_flags(scene: &Scene, o: Vec3) -> String {
    format!(
        "--observer {},{},{} --straw {},{} --water-height {} --n-water {}",
        o.x,
        o.y,
        o.z,
        scene.straw_x(),
        scene.straw_y(),
        scene.water_height(),
        scene.n_water()
    )
}

/// The inputs as label/value rows.
fn inputs(scene: &Scene, o: Vec3) -> Vec<(String, String)> {
    vec![
        ("observer".into(), format!("({}, {}, {}) m", o.x, o.y, o.z)),
        (
            "straw axis".into(),
            format!("({}, {}) m", scene.straw_x(), scene.straw_y()),
        ),
        ("water height".into(), format!("{} m", scene.water_height())),
        ("water index".into(), format!("{}", scene.n_water())),
        ("event limit".into(), format!("{}", scene.max_events())),
    ]
}

/// The built-in check for `n_water = 1`: every image point lies on the straw.
fn check(scene: &Scene, cloud: &ImageCloud) -> Option<Check> {
    if scene.n_water() != 1.0 {
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
        scene.n_water()
    )
}

/// Largest distance (m) of an image point from the straw's surface.
fn max_distance_to_straw(scene: &Scene, cloud: &ImageCloud) -> f64 {
    let world = World::assignment(scene);
    cloud
        .points
        .iter()
        .map(|p| world.distance_to_objects(p.position))
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
