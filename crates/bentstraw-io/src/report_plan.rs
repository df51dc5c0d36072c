//! The report's plan: which simulations it holds (the four references and their index checks,
//! or a scene file seen from four observers), the files each writes, and the sections they make;
//! the command line's `table` reserves the files, shows the progress and puts them in place.

use std::fmt::Write as _;
use std::path::Path;
use std::time::{Duration, Instant};

use bentstraw_optics::apparent::{
    default_sweep_point, eye_model_points, stereo_points, sweep_apparent, Sweep, SweepKind,
    DEFAULT_SWEEP_ROWS,
};
use bentstraw_optics::camera::Camera;
use bentstraw_optics::check::{
    check_solution, ClaimedPoint, DEFAULT_MIN_COVERAGE, DEFAULT_TOLERANCE,
};
use bentstraw_optics::image::ImagePoint;
use bentstraw_optics::record::InputValue;
use bentstraw_optics::sampling::{sample_image, ImageCloud};
use bentstraw_optics::scene::{Reference, Scene, REFERENCES, SECTION_NAMES, WATER_INDEX};
use bentstraw_optics::setup::{SceneValues, Setup};
use bentstraw_optics::text::number_text;
use bentstraw_optics::view::{
    CLASSIC_OBSERVER, CLASSIC_STRAW, CLASSIC_WATER_HEIGHT, DEFAULT_POINTS,
};
use bentstraw_optics::Vec3;
use rayon::prelude::*;

use crate::camera::{scene_camera, CameraSpec};
use crate::error::{fail, Result};
use crate::gallery::{lesson_notes, opening_comment, GALLERY};
use crate::gallery_report::{gallery_files, gallery_sections, write_picture};
use crate::model_plots::{
    eye_gap_samples, stereo_gap_samples, write_gap_plot, write_model_comparison, GapSeries,
    ModelCloud, MODEL_NAMES,
};
use crate::ray_diagram::{write_ray_diagram, Diagram};
use crate::report::{Check, Figure, Link, Report, Section, SimulationEntry, Timing};
use crate::solution::region_words;
use crate::validation::{self, write_validation_figure, ValidationSeries};
use crate::words::{self, Lang};
use crate::writers::{write_csv_gz, ModelPoints, PointSet};
use crate::{html, pictures, plot};

/// Most image points per simulation: the table traces twelve, and runs the eye and stereo models
/// on four (measured on two cores: 16 s and 270 MB for 100 000 points, 35–80 s and 490 MB for
/// 200 000, depending on the load).
pub const MAX_POINTS: usize = 200_000;

/// The report's file name in the folder.
pub const REPORT_FILE: &str = "index.html";

/// Largest distance (m) from the straw's surface an `n_water = 1` image point may have.
pub const ON_STRAW_TOLERANCE: f64 = 1e-9;

/// The water indices of each reference: the real one, then the two checks, with file suffixes.
const VARIANTS: [(f64, &str); 3] = [(WATER_INDEX, ""), (1.0, "_n1"), (1.05, "_n1.05")];

/// What a report's work tells while it runs: the stage it is at, and each step done (a
/// simulation, a gallery scene, the closing sections).
pub trait Progress: Sync {
    /// Work on `stage` begins.
    fn stage(&self, stage: &str);
    /// One more step is done.
    fn step(&self);
}

/// A report planned: its simulations chosen and their scenes checked, before anything is written.
pub struct ReportPlan {
    /// Image points per simulation.
    points: usize,
    /// The report's language.
    lang: Lang,
    /// The reference simulations' jobs, or a scene file's observers.
    kind: Kind,
}

/// The two kinds of report.
enum Kind {
    /// The four reference simulations, each with its two index checks.
    References(Vec<Job>),
    /// A scene file seen from four observers.
    Scene(ScenePlan),
}

/// `points` if a report may trace that many image points per simulation, else why not.
pub fn checked_points(points: usize) -> Result<usize> {
    if points == 0 {
        return fail("--points 0 is not allowed: ask for at least 1 image point per simulation");
    }
    if points > MAX_POINTS {
        return fail(format!(
            "--points {points} is too many for the table: at most {MAX_POINTS} image points per \
             simulation (twelve simulations, four with the eye and stereo models: about 500 MB and \
             a minute at the limit); use simulate for one large simulation"
        ));
    }
    Ok(points)
}

impl ReportPlan {
    /// The report of the four reference simulations and their index checks, with at least
    /// `points` image points each, in `lang`.
    pub fn references(points: usize, lang: Lang) -> Result<ReportPlan> {
        let jobs = REFERENCES
            .iter()
            .flat_map(|r| {
                VARIANTS
                    .iter()
                    .map(move |&(n, suffix)| Job::reference(r, n, suffix, lang))
            })
            .collect();
        Ok(ReportPlan {
            points: checked_points(points)?,
            lang,
            kind: Kind::References(jobs),
        })
    }

    /// The report of the scene file `name` whose text is `text`, seen from its observer (or
    /// `observer`) and three more turned about the vertical through its target, at `wavelength`
    /// (nm; the d line when none) where an index depends on it.
    pub fn scene(
        name: String,
        text: &str,
        observer: Option<[f64; 3]>,
        wavelength: Option<f64>,
        points: usize,
        lang: Lang,
    ) -> Result<ReportPlan> {
        let points = checked_points(points)?;
        Ok(ReportPlan {
            points,
            lang,
            kind: Kind::Scene(ScenePlan::new(name, text, observer, wavelength, lang)?),
        })
    }

    /// The scene file's hints (numbers that break no rule but look like a slip), each naming the
    /// file.
    pub fn hints(&self) -> &[String] {
        match &self.kind {
            Kind::References(_) => &[],
            Kind::Scene(plan) => &plan.hints,
        }
    }

    /// The names of every file the report writes into its folder (its page last).
    pub fn files(&self) -> Vec<String> {
        match &self.kind {
            Kind::References(jobs) => jobs
                .iter()
                .flat_map(|job| job.outputs())
                .chain(INTRO_FILES.iter().map(|f| f.to_string()))
                .chain(gallery_files())
                .chain([VALIDATION_FILE.to_string(), REPORT_FILE.to_string()])
                .collect(),
            Kind::Scene(plan) => {
                let validated = plan.jobs[0].n_water != 1.0;
                plan.jobs
                    .iter()
                    .flat_map(|job| job.outputs())
                    .chain(sweep_files())
                    .chain([SCENE_PICTURE_FILE.to_string(), REPORT_FILE.to_string()])
                    .chain(plan.has_rainbow().then(|| RAINBOW_FILE.to_string()))
                    .chain(validated.then(|| VALIDATION_FILE.to_string()))
                    .collect()
            }
        }
    }

    /// How many steps [`ReportPlan::write`] tells [`Progress`] of.
    pub fn steps(&self) -> u64 {
        match &self.kind {
            Kind::References(jobs) => (jobs.len() + GALLERY.len() + 1) as u64,
            Kind::Scene(plan) => (plan.jobs.len() + 1) as u64,
        }
    }

    /// Traces every simulation and writes every figure into the folder `out` (through the
    /// outputs reserved there), then the report's page; the report, whose figures say which
    /// could not be written.
    pub fn write(&self, out: &Path, progress: &dyn Progress) -> Result<Report> {
        let (points, lang) = (self.points, self.lang);
        let started = Instant::now();
        let simulations = |jobs: &[Job]| -> Vec<SimulationEntry> {
            // In parallel: the figures are drawn on one thread each, so this is where cores help.
            jobs.par_iter()
                .map(|job| {
                    let entry = run_job(job, out, points, lang);
                    progress.step();
                    entry
                })
                .collect()
        };
        let report = match &self.kind {
            Kind::References(jobs) => {
                progress.stage("simulations");
                let entries = simulations(jobs);
                progress.stage("gallery");
                let mut closing = gallery_sections(out, lang, &|| progress.step());
                progress.stage("method and validation");
                let intro = intro_sections(out, points, lang);
                closing.extend(closing_sections(out, lang));
                progress.step();
                Report {
                    title: lang.of(words::TITLE).into(),
                    subtitle: lang.fill(words::SUBTITLE, &[&points]),
                    intro,
                    simulations: entries,
                    closing,
                    total: started.elapsed(),
                    lang,
                    footer: words::FOOTER,
                }
            }
            Kind::Scene(plan) => {
                progress.stage("observers");
                let entries = simulations(&plan.jobs);
                progress.stage("picture and validation");
                let (intro, closing) = rayon::join(
                    || scene_intro(plan, out, lang),
                    || scene_closing(plan, out, lang),
                );
                progress.step();
                let mut closing = closing?;
                closing.insert(0, sweep_section(plan, out, lang));
                if plan.has_rainbow() {
                    closing.insert(0, rainbow_section(plan, out, lang));
                }
                Report {
                    title: lang.fill(words::SCENE_TITLE, &[&plan.name]),
                    subtitle: lang.fill(words::SCENE_SUBTITLE, &[&plan.comment, &points]),
                    intro,
                    simulations: entries,
                    closing,
                    total: started.elapsed(),
                    lang,
                    footer: words::SCENE_FOOTER,
                }
            }
        };
        crate::report::write_report(&out.join(REPORT_FILE), &report)?;
        Ok(report)
    }
}

/// The first file of `report` that could not be written, and how many there are, as the message
/// that says nothing was replaced in `out`.
pub fn unwritten(report: &Report, out: &Path) -> Option<String> {
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
    let (file, error) = failed.first()?;
    Some(format!(
        "{} file(s) could not be written (first: {file}: {error}); no file in {} was replaced",
        failed.len(),
        crate::files::shown(out)
    ))
}

/// The first failed check of `report`'s simulations, and how many failed, as one message.
pub fn failed_checks(report: &Report) -> Option<String> {
    let off: Vec<&SimulationEntry> = report
        .simulations
        .iter()
        .filter(|s| s.check.as_ref().is_some_and(|c| !c.passed))
        .collect();
    let first = off.first()?;
    Some(format!(
        "check failed: {} ({} check(s) failed in all)",
        first
            .check
            .as_ref()
            .map(|c| c.text.as_str())
            .unwrap_or_default(),
        off.len()
    ))
}

/// One simulation of the table: a reference (or one of its index checks), or a scene file seen
/// from one of its observers.
struct Job {
    /// Number of the reference (or of the observer) it belongs to.
    number: u32,
    /// The scene seen from the job's observer, built once for tracing and drawing.
    loaded: Setup,
    /// File stem, e.g. `sim1_n1.05`.
    stem: String,
    /// Heading, e.g. "Simulation 1, check n_water = 1".
    heading: String,
    /// The heading of its group, e.g. "Reference simulation 1".
    group: String,
    /// The scene and observer in a line, for the figures' titles.
    title: String,
    /// The index of the water (or of the scene's first liquid).
    n_water: f64,
    /// Whether it gets every figure (the observer's pictures, the rays, the models), not only its
    /// points: the references proper, not their index checks.
    full: bool,
    /// The camera of the observer's pictures.
    camera: Camera,
}

impl Job {
    /// The job of reference `r` with water of index `n` (`suffix` names the index checks' files).
    fn reference(r: &Reference, n: f64, suffix: &str, lang: Lang) -> Job {
        let scene = r.scene(n);
        let heading = if n == WATER_INDEX {
            lang.fill(words::SIMULATION, &[&r.number])
        } else {
            lang.fill(words::SIMULATION_CHECK, &[&r.number, &n])
        };
        let loaded = Setup::assignment(scene, r.observer);
        Job {
            number: r.number,
            title: loaded.inputs_line(false),
            loaded,
            stem: format!("sim{}{suffix}", r.number),
            heading,
            group: lang.fill(words::REFERENCE_SIMULATION, &[&r.number]),
            n_water: n,
            full: n == WATER_INDEX,
            camera: pictures::report_camera(r.observer),
        }
    }

    /// The names of every file this simulation writes, so that all are reserved before the work.
    fn outputs(&self) -> Vec<String> {
        let stem = &self.stem;
        let mut names = vec![format!("{stem}.csv.gz"), format!("{stem}.svg")];
        if self.full {
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

/// The turns (degrees) about the vertical through the target that give a scene report's three
/// more observers, in the order they are tried: a turn that puts the eye in the container, an
/// object or a card is left for the next.
const TURNS: [f64; 7] = [45.0, -45.0, 90.0, -90.0, 135.0, -135.0, 180.0];
/// How many observers a scene report has.
const SCENE_OBSERVERS: usize = 4;
/// The scene's picture, from the file's observer.
const SCENE_PICTURE_FILE: &str = "scene_view.png";
/// The rainbow's figure, for a scene with a sun and a drop.
const RAINBOW_FILE: &str = "rainbow.svg";

/// `table --scene`: the scene read and checked, its observers chosen, before anything is written.
struct ScenePlan {
    /// The scene's name as messages show it (`scenes/leaning-straw.toml`, `leaning-straw`).
    name: String,
    /// The file's opening comment: what the scene shows.
    comment: String,
    /// Its lesson's title and notes (text, questions) in the report's language, if it has one.
    lesson: Option<(String, Vec<String>)>,
    /// One simulation per observer: the file's first.
    jobs: Vec<Job>,
    /// The turns taken, in degrees, and the ones refused with why.
    turns: Vec<f64>,
    /// Turns refused before three were found: the angle and the reason.
    refused: Vec<(f64, String)>,
    /// The scene file's hints: numbers that break no rule but look like a slip.
    hints: Vec<String>,
    /// The point the observers look at: the other observers turn about the vertical through it,
    /// and so does the eye in the sweep round the glass.
    target: Vec3,
}

impl ScenePlan {
    /// Whether the scene has a sun and a sphere: its report then draws the first sphere's
    /// rainbow.
    fn has_rainbow(&self) -> bool {
        let d = &self.jobs[0].loaded.description;
        d.sun.is_some() && !d.spheres.is_empty()
    }

    /// The scene file `name` whose text is `text`, seen from its observer (or `observer`), and
    /// the observers turned about the vertical through its target, at `wavelength`.
    fn new(
        name: String,
        text: &str,
        observer: Option<[f64; 3]>,
        wavelength: Option<f64>,
        lang: Lang,
    ) -> Result<ScenePlan> {
        // Each observer's scene made from the one text.
        let load = |observer: Option<[f64; 3]>| {
            let values = SceneValues {
                observer,
                wavelength,
                ..SceneValues::default()
            };
            Setup::from_text(&name, text, &values).map_err(crate::Error::from)
        };
        let first = load(observer)?;
        let hints = match &first.name {
            Some(name) => first
                .description
                .hints()
                .iter()
                .map(|h| format!("{name}: {h}"))
                .collect(),
            None => Vec::new(),
        };
        let target = first.target.unwrap_or_else(|| {
            let (lo, hi) = first.world.bounds();
            0.5 * (lo + hi)
        });
        let o = first.observer;
        let mut jobs = vec![Job::scene(
            first,
            1,
            lang.fill(words::OBSERVER_OF_FILE, &[&1]),
            lang,
        )?];
        let (mut turns, mut refused) = (Vec::new(), Vec::new());
        for turn in TURNS {
            if jobs.len() == SCENE_OBSERVERS {
                break;
            }
            let turned = turned_about_vertical(o, target, turn);
            match load(Some(turned.to_array())) {
                Ok(loaded) => {
                    let k = jobs.len() as u32 + 1;
                    let group = lang.fill(words::OBSERVER_TURNED, &[&k, &signed(turn)]);
                    jobs.push(Job::scene(loaded, k, group, lang)?);
                    turns.push(turn);
                }
                Err(e) => refused.push((turn, e.to_string())),
            }
        }
        Ok(ScenePlan {
            name,
            comment: opening_comment(text),
            lesson: lesson_notes(text, lang),
            hints,
            jobs,
            turns,
            refused,
            target,
        })
    }
}

/// An angle with its sign, the minus sign typeset: `+45`, `−45`.
fn signed(degrees: f64) -> String {
    format!("{degrees:+}").replace('-', "−")
}

/// `o` turned by `degrees` about the vertical line through `target` (from `+x` towards `+y`).
fn turned_about_vertical(o: Vec3, target: Vec3, degrees: f64) -> Vec3 {
    let (sin, cos) = degrees.to_radians().sin_cos();
    let (dx, dy) = (o.x - target.x, o.y - target.y);
    // To the micrometre: the report prints the position, and `simulate --observer` given the
    // printed numbers sees exactly the same.
    let micrometres = |v: f64| (v * 1e6).round() / 1e6 + 0.0; // + 0.0: no "-0"
    Vec3::new(
        micrometres(target.x + cos * dx - sin * dy),
        micrometres(target.y + sin * dx + cos * dy),
        o.z,
    )
}

impl Job {
    /// The job of a scene file seen from its observer number `number`, under the heading `group`.
    fn scene(loaded: Setup, number: u32, group: String, lang: Lang) -> Result<Job> {
        let camera = scene_camera(
            &loaded,
            &CameraSpec {
                size: Some(pictures::REPORT_SIZE),
                ..CameraSpec::default()
            },
        )?;
        let o = loaded.observer;
        // The index the report names: the straw's water's (even an empty glass has one), else
        // the first liquid's.
        let n_water = match loaded.input("n_water") {
            Some(InputValue::Number(n)) => n,
            _ => loaded.description.liquids.first().map_or(1.0, |l| l.index),
        };
        Ok(Job {
            number,
            title: format!("observer ({}, {}, {}) m, {}", o.x, o.y, o.z, loaded.name()),
            loaded,
            stem: format!("obs{number}"),
            heading: lang.fill(words::OBSERVER_N, &[&number]),
            group,
            n_water,
            full: true,
            camera,
        })
    }
}

/// The scene report's opening: the picture from the file's observer, what the scene shows and
/// how the observers were chosen; and the method.
fn scene_intro(plan: &ScenePlan, out: &Path, lang: Lang) -> Vec<Section> {
    let mut picture = Figure::image(
        SCENE_PICTURE_FILE,
        &lang.fill(words::SCENE_PICTURE, &[&plan.name]),
    );
    picture.error = write_picture(&out.join(SCENE_PICTURE_FILE), &plan.jobs[0].loaded)
        .err()
        .map(|e| e.to_string());
    let turns: Vec<String> = plan
        .turns
        .iter()
        .map(|t| format!("{}°", signed(*t)))
        .collect();
    let mut notes = vec![plan.comment.clone()];
    // What the scene teaches, when its file says.
    if let Some((title, lesson)) = &plan.lesson {
        notes.push(title.clone());
        notes.extend(lesson.iter().cloned());
    }
    notes.push(lang.fill(words::OBSERVERS_NOTE, &[&turns.join(", ")]));
    for (turn, why) in &plan.refused {
        notes.push(lang.fill(words::TURN_REFUSED, &[&signed(*turn), why]));
    }
    vec![
        Section {
            title: lang.of(words::THE_SCENE).into(),
            figures: vec![picture],
            notes,
            side_by_side: false,
            printed: true,
            table: Vec::new(),
        },
        Section {
            title: lang.of(words::METHOD).into(),
            figures: vec![],
            notes: words::METHOD_NOTES
                .iter()
                .map(|t| lang.of(*t).to_string())
                .collect(),
            side_by_side: false,
            printed: true,
            table: Vec::new(),
        },
    ]
}

/// The sweeps' kinds, in the report's order.
const SWEEPS: [SweepKind; 2] = [SweepKind::Around, SweepKind::UpDown];
/// Image points of the file's observer among which the sweeps' point is chosen.
const SWEEP_CLOUD_POINTS: usize = 2000;

/// A sweep's files: its figure and its CSV.
fn sweep_file(kind: SweepKind, extension: &str) -> String {
    format!("sweep_{}.{extension}", kind.name())
}

/// Every sweep's files.
fn sweep_files() -> impl Iterator<Item = String> {
    SWEEPS
        .into_iter()
        .flat_map(|k| [sweep_file(k, "svg"), sweep_file(k, "csv")])
}

/// Apparent depth against the viewing angle: one point the file's observer sees (the middle one,
/// by height, of its lowest colour code: under water for a straw), followed as the eye moves
/// round the glass and up and down; a figure and a CSV file each.
fn sweep_section(plan: &ScenePlan, out: &Path, lang: Lang) -> Section {
    let first = &plan.jobs[0].loaded;
    let cloud = sample_image(&first.world, first.observer, SWEEP_CLOUD_POINTS, &|_| {});
    let picked = default_sweep_point(&cloud.points);
    let figures = SWEEPS
        .iter()
        .map(|&kind| {
            let rows = picked.map_or_else(Vec::new, |p| {
                let sweep = Sweep {
                    kind,
                    centre: plan.target,
                    rows: DEFAULT_SWEEP_ROWS,
                };
                sweep_apparent(
                    first,
                    first.observer,
                    p.straw_point,
                    Some(p.direction),
                    &sweep,
                )
            });
            let point = picked.map_or(plan.target, |p| p.straw_point);
            let caption = match kind {
                SweepKind::Around => {
                    let mm = |v: f64| number_text((v * 1e4).round() / 1e4);
                    lang.fill(
                        words::SWEEP_AROUND_CAPTION,
                        &[&mm(point.x), &mm(point.y), &mm(point.z)],
                    )
                }
                SweepKind::UpDown => lang.of(words::SWEEP_UPDOWN_CAPTION).into(),
            };
            let (svg, csv) = (sweep_file(kind, "svg"), sweep_file(kind, "csv"));
            let mut figure = Figure::image(&svg, &caption);
            figure.error = crate::sweep::write_sweep_plot(
                &out.join(&svg),
                kind,
                &rows,
                point,
                crate::sweep::shown_heights(point),
                &caption_title(kind, lang),
                lang,
            )
            .err()
            .map(|e| e.to_string());
            let written = crate::files::write_atomically(&out.join(&csv), |w| {
                crate::sweep::write_sweep_csv(w, &rows)
            });
            figure.links.push(Link::new(
                &csv,
                lang.of(words::SWEEP_CSV),
                written.err().map(|e| e.to_string()),
            ));
            figure
        })
        .collect();
    let mut notes = vec![lang.of(words::SWEEP_NOTE).to_string()];
    if picked.is_none() {
        notes.push(lang.of(words::SWEEP_NONE).into());
    }
    Section {
        title: lang.of(words::SWEEP).into(),
        figures,
        notes,
        side_by_side: false,
        printed: true,
        table: Vec::new(),
    }
}

/// The rainbow of the scene's first sphere in the sun: Descartes' construction traced at each
/// band of white light, as a figure and a table of the bows' angles.
fn rainbow_section(plan: &ScenePlan, out: &Path, lang: Lang) -> Section {
    let description = &plan.jobs[0].loaded.description;
    let nms = bentstraw_optics::spectrum::white_bands().map(|b| b.nm);
    let bow = |k| bentstraw_optics::rainbow::deviation_curves(description, 0, k, &nms);
    let (traced, (first, second)) = match bow(1).and_then(|first| Ok((first, bow(2)?))) {
        Ok(bows) => (None, bows),
        Err(e) => (Some(e.to_string()), Default::default()),
    };
    let caption = lang.of(words::RAINBOW_CAPTION);
    let mut figure = Figure::image(RAINBOW_FILE, caption);
    let drawn = crate::rainbow_plot::write_rainbow_plot(
        &out.join(RAINBOW_FILE),
        &[first.as_slice(), second.as_slice()].concat(),
        lang.of(words::RAINBOW),
        lang,
    );
    figure.error = traced.or(drawn.err().map(|e| e.to_string()));
    let degrees = |a: f64| format!("{}°", number_text((a * 100.0).round() / 100.0));
    let mut table = vec![words::RAINBOW_HEAD
        .iter()
        .map(|&h| lang.of(h).to_string())
        .collect::<Vec<_>>()];
    for (a, b) in first.iter().zip(&second) {
        table.push(vec![
            number_text(a.nm),
            number_text((a.index * 1e5).round() / 1e5),
            degrees(a.bow[1]),
            degrees(b.bow[1]),
        ]);
    }
    Section {
        title: lang.of(words::RAINBOW).into(),
        figures: vec![figure],
        notes: vec![lang.of(words::RAINBOW_NOTE).to_string()],
        side_by_side: false,
        printed: true,
        table,
    }
}

/// A sweep figure's title: the section's heading and how the eye moves.
fn caption_title(kind: SweepKind, lang: Lang) -> String {
    let how = match kind {
        SweepKind::Around => words::SWEEP_KINDS[0],
        SweepKind::UpDown => words::SWEEP_KINDS[1],
    };
    let colon = if lang == Lang::Fr { " : " } else { ": " };
    format!("{}{colon}{}", lang.of(words::SWEEP), lang.of(how))
}

/// The scene report's closing: the validation over the index of its bottom liquid, seen by every
/// observer, and the limits.
fn scene_closing(plan: &ScenePlan, out: &Path, lang: Lang) -> Result<Vec<Section>> {
    let series: Vec<Option<ValidationSeries>> = plan
        .jobs
        .par_iter()
        .map(|job| {
            validation::liquid_series(
                &lang.fill(words::OBSERVER_SERIES, &[&job.number]),
                &job.loaded,
            )
        })
        .collect::<Result<_>>()?;
    let series: Vec<ValidationSeries> = series.into_iter().flatten().collect();
    let first = &plan.jobs[0].loaded;
    let liquid = first.description.liquids.first().map(|l| l.name.clone());
    let validation = match liquid {
        Some(liquid) if !series.is_empty() => {
            let mut figure = Figure::image(
                VALIDATION_FILE,
                &lang.fill(
                    words::SCENE_VALIDATION_CAPTION,
                    &[&liquid, &plan.jobs[0].n_water],
                ),
            );
            figure.error = write_validation_figure(
                &out.join(VALIDATION_FILE),
                &series,
                words::LIQUID_INDEX_AXIS,
                lang,
            )
            .err()
            .map(|e| e.to_string());
            Section {
                title: lang.of(words::VALIDATION).into(),
                figures: vec![figure],
                notes: vec![lang.fill(
                    words::SCENE_VALIDATION_NOTE,
                    &[&validation::VALIDATION_POINTS],
                )],
                side_by_side: false,
                printed: true,
                table: validation_table(&series, lang),
            }
        }
        liquid => Section {
            title: lang.of(words::VALIDATION).into(),
            figures: vec![],
            notes: vec![lang.fill(
                words::NO_VALIDATION,
                &[&lang.of(match liquid {
                    Some(_) => words::INDEX_ONE,
                    None => words::NO_LIQUID,
                })],
            )],
            side_by_side: false,
            printed: true,
            table: Vec::new(),
        },
    };
    Ok(vec![
        validation,
        Section {
            title: lang.of(words::LIMITS).into(),
            figures: vec![],
            notes: vec![lang.of(words::SCENE_LIMITS_NOTE).into()],
            side_by_side: false,
            printed: true,
            table: Vec::new(),
        },
    ])
}

/// The validation's numbers: a row per index, the largest and median distance of each series.
fn validation_table(series: &[ValidationSeries], lang: Lang) -> Vec<Vec<String>> {
    let mut table = vec![{
        let mut head = vec!["n".to_string()];
        for s in series {
            head.push(lang.fill(words::LARGEST_M, &[&s.label]));
            head.push(lang.fill(words::MEDIAN_M, &[&s.label]));
        }
        head
    }];
    for k in 0..series.first().map_or(0, |s| s.rows.len()) {
        let mut row = vec![format!("{:.4}", series[0].rows[k].0)];
        for s in series {
            row.push(format!("{:.2e}", s.rows[k].1));
            row.push(format!("{:.2e}", s.rows[k].2));
        }
        table.push(row);
    }
    table
}

/// Traces one simulation, writes its files, and describes it for the report.
fn run_job(job: &Job, out: &Path, points: usize, lang: Lang) -> SimulationEntry {
    let observer = job.loaded.observer;
    let t0 = Instant::now();
    let cloud = sample_image(&job.loaded.world, observer, points, &|_| {});
    let traced = t0.elapsed();

    let t1 = Instant::now();
    let title = format!("{}: {}", job.heading, job.title);
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
    let mut figure = Figure::image(&svg, lang.of(words::CLOUD_CAPTION));
    figure.error = plot_error.map(|e| e.to_string());
    // The rotatable view of the reference simulations (the checks' points differ little from it).
    if job.full {
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
            lang.of(words::ROTATABLE_VIEW),
            page_error.map(|e| e.to_string()),
        ));
    }
    figure.links.push(Link::new(
        &csv,
        lang.of(words::POINTS_FILE),
        data_error.map(|e| e.to_string()),
    ));
    let written = t1.elapsed();

    let mut timings = vec![
        Timing::new(lang.of(words::TRACING), traced),
        Timing::new(lang.of(words::WRITING_FILES), written),
    ];
    let mut sections = vec![Section {
        title: lang.of(words::IMAGE_POINTS_SECTION).into(),
        figures: vec![figure],
        notes: vec![distance_note(job, &cloud, lang)],
        side_by_side: false,
        printed: true,
        table: Vec::new(),
    }];
    // The reference simulations proper (not the index checks) also get the observer's picture and
    // the apparent-position models.
    if job.full {
        let t = Instant::now();
        sections.push(observer_section(job, out, &cloud, lang));
        timings.push(Timing::new(lang.of(words::OBSERVERS_PICTURE), t.elapsed()));
        let t = Instant::now();
        sections.push(rays_section(job, out, &cloud, lang));
        timings.push(Timing::new(lang.of(words::RAY_DIAGRAM), t.elapsed()));
        let t = Instant::now();
        sections.push(models_section(job, out, &cloud, lang));
        timings.push(Timing::new(lang.of(words::EYE_AND_STEREO), t.elapsed()));
    }

    let counts = cloud.counts_per_code()[..job.loaded.colour_names().len()].to_vec();
    SimulationEntry {
        id: job.stem.clone(),
        reference: job.number,
        group: job.group.clone(),
        heading: job.heading.clone(),
        inputs: inputs(&job.loaded, lang),
        n_water: job.n_water,
        rays: cloud.rays_traced,
        points: cloud.points.len(),
        counts,
        hit_ratio: cloud.hit_ratio(),
        timings,
        check: check(job, &cloud, lang),
        solution_check: Some(own_points_check(&job.loaded, &cloud.points)),
        sections,
    }
}

/// What the observer's eye sees (fresnel mode) beside the image points through the same camera.
fn observer_section(job: &Job, out: &Path, cloud: &ImageCloud, lang: Lang) -> Section {
    let seen = format!("{}_observer.png", job.stem);
    let splat = format!("{}_cloud.png", job.stem);
    let error = pictures::write_observer_pictures(
        out,
        &job.stem,
        &job.loaded.world,
        job.camera,
        &cloud.points,
    )
    .err()
    .map(|e| e.to_string());
    let mut picture = Figure::image(&seen, lang.of(words::OBSERVER_CAPTION));
    picture.error = error.clone();
    let mut points = Figure::image(&splat, lang.of(words::SPLAT_CAPTION));
    points.error = error;
    Section {
        title: lang.of(words::OBSERVER_SECTION).into(),
        figures: vec![picture, points],
        notes: vec![],
        side_by_side: true,
        printed: true,
        table: Vec::new(),
    }
}

/// The ray diagram of one simulation: which light paths make which pieces of its image.
fn rays_section(job: &Job, out: &Path, cloud: &ImageCloud, lang: Lang) -> Section {
    let observer = job.loaded.observer;
    let file = format!("{}_rays.svg", job.stem);
    let diagram = Diagram::new(&job.loaded.world, observer, &cloud.points);
    let title = lang.fill(words::RAY_DIAGRAM_TITLE, &[&job.heading, &job.title]);
    let mut figure = Figure::image(&file, lang.of(words::RAYS_CAPTION));
    figure.error = write_ray_diagram(&out.join(&file), &job.loaded, &diagram, &title, lang)
        .err()
        .map(|e| e.to_string());
    let total: usize = diagram.counts.iter().map(|c| c.1).sum::<usize>().max(1);
    let shares: Vec<String> = diagram
        .counts
        .iter()
        .map(|(kind, n)| {
            format!(
                "{}: {:.1} %",
                lang.light_path(kind),
                100.0 * *n as f64 / total as f64
            )
        })
        .collect();
    Section {
        title: lang.of(words::RAYS_SECTION).into(),
        figures: vec![figure],
        notes: vec![lang.fill(words::RAYS_NOTE, &[&shares.join("; ")])],
        side_by_side: false,
        printed: true,
        table: Vec::new(),
    }
}

/// The files of the report's opening sections.
const INTRO_FILES: [&str; 2] = ["classic_view.png", "classic_rays.svg"];
/// The validation figure's file.
const VALIDATION_FILE: &str = "validation.svg";

/// The report's opening: the effect at a glance (a realistic view), and the method with its ray
/// diagram.
fn intro_sections(out: &Path, points: usize, lang: Lang) -> Vec<Section> {
    let [x, y] = CLASSIC_STRAW;
    let scene =
        Scene::with_defaults(x, y, CLASSIC_WATER_HEIGHT).expect("the classic view is valid");
    let observer = Vec3::from_array(CLASSIC_OBSERVER);
    let loaded = Setup::assignment(scene, observer);
    let world = &loaded.world;
    let mut view = Figure::image(INTRO_FILES[0], lang.of(words::VIEW_CAPTION));
    view.error = pictures::write_view_picture(&out.join(INTRO_FILES[0]), world, observer)
        .err()
        .map(|e| e.to_string());
    let cloud = sample_image(world, observer, points.min(DEFAULT_POINTS), &|_| {});
    let diagram = Diagram::new(world, observer, &cloud.points);
    let mut rays = Figure::image(INTRO_FILES[1], lang.of(words::INTRO_RAYS_CAPTION));
    rays.error = write_ray_diagram(
        &out.join(INTRO_FILES[1]),
        &loaded,
        &diagram,
        &lang.fill(words::RAY_DIAGRAM_OF, &[&loaded.inputs_line(false)]),
        lang,
    )
    .err()
    .map(|e| e.to_string());
    vec![
        Section {
            title: lang.of(words::BROKEN_STRAW).into(),
            figures: vec![view],
            notes: vec![],
            side_by_side: false,
            printed: true,
            table: Vec::new(),
        },
        Section {
            title: lang.of(words::METHOD).into(),
            figures: vec![rays],
            notes: words::METHOD_NOTES
                .iter()
                .map(|t| lang.of(*t).to_string())
                .collect(),
            side_by_side: false,
            printed: true,
            table: Vec::new(),
        },
    ]
}

/// The report's closing: the validation as the index grows, and the limits of the model.
fn closing_sections(out: &Path, lang: Lang) -> Vec<Section> {
    let series: Vec<ValidationSeries> = REFERENCES
        .par_iter()
        .map(|r| {
            validation::series(
                &lang.fill(words::VALIDATION_SERIES, &[&r.number]),
                &r.scene(WATER_INDEX),
                r.observer,
            )
        })
        .collect();
    let mut figure = Figure::image(VALIDATION_FILE, lang.of(words::VALIDATION_CAPTION));
    figure.error =
        write_validation_figure(&out.join(VALIDATION_FILE), &series, words::INDEX_AXIS, lang)
            .err()
            .map(|e| e.to_string());
    let mut table = validation_table(&series, lang);
    table[0][0] = "n_water".to_string();
    vec![
        Section {
            title: lang.of(words::VALIDATION).into(),
            figures: vec![figure],
            notes: vec![lang.fill(words::VALIDATION_NOTE, &[&validation::VALIDATION_POINTS])],
            side_by_side: false,
            printed: true,
            table,
        },
        Section {
            title: lang.of(words::LIMITS).into(),
            figures: vec![],
            notes: vec![lang.of(words::LIMITS_NOTE).into()],
            side_by_side: false,
            printed: true,
            table: Vec::new(),
        },
    ]
}

/// The course's, the eye's and the stereo image side by side, and how far apart they are.
fn models_section(job: &Job, out: &Path, cloud: &ImageCloud, lang: Lang) -> Section {
    let observer = job.loaded.observer;
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
    let title = lang.fill(words::WHERE_IT_APPEARS, &[&job.heading]);
    let mut figure = Figure::image(&compare, lang.of(words::MODELS_CAPTION));
    figure.error =
        write_model_comparison(&out.join(&compare), &job.loaded, observer, &clouds, &title)
            .err()
            .map(|e| e.to_string());
    let mut figures = vec![figure];

    let eye_gaps = eye_gap_samples(&eye);
    let stereo_gaps = stereo_gap_samples(&stereo);
    let gap = format!("{}_gap.svg", job.stem);
    let series = GapSeries::of_models(&eye_gaps, &stereo_gaps, lang);
    let mut figure = Figure::image(&gap, lang.of(words::GAP_CAPTION));
    let gap_title = lang.fill(words::GAP_TITLE, &[&job.heading]);
    figure.error = write_gap_plot(&out.join(&gap), &series, &gap_title, lang)
        .err()
        .map(|e| e.to_string());
    figures.push(figure);

    let unplaced = eye.iter().filter(|p| p.position.is_none()).count();
    let max_gap = eye_gaps.iter().map(|g| g.1).fold(0.0, f64::max);
    let mut sorted: Vec<f64> = eye_gaps.iter().map(|g| g.1).collect();
    sorted.sort_by(f64::total_cmp);
    let median = sorted.get(sorted.len() / 2).copied().unwrap_or(0.0);
    Section {
        title: lang.of(words::MODELS_SECTION).into(),
        figures,
        notes: vec![
            lang.fill(
                words::EYE_NOTE,
                &[
                    &(eye.len() - unplaced),
                    &eye.len(),
                    &unplaced,
                    &format!("{:.2}", 1e3 * median),
                    &format!("{:.2}", 1e3 * max_gap),
                ],
            ),
            lang.fill(words::STEREO_NOTE, &[&stereo.points.len(), &stereo.skipped]),
            lang.fill(words::MODELS_FILE_NOTE, &[&simulate_flags(&job.loaded)]),
        ],
        side_by_side: false,
        printed: true,
        table: Vec::new(),
    }
}

/// The flags of `bentstraw simulate` that give the job's scene seen from its observer.
fn simulate_flags(loaded: &Setup) -> String {
    loaded.flags().join(" ")
}

/// The inputs as label/value rows.
fn inputs(loaded: &Setup, lang: Lang) -> Vec<(String, String)> {
    let mut inputs = loaded.inputs();
    // The observer first, then the scene's values in their order.
    inputs.sort_by_key(|i| i.key != "observer");
    let mut rows = Vec::new();
    for input in inputs {
        let label = match input.key {
            "observer" => words::INPUTS[0],
            "straw" => words::INPUTS[1],
            "water_height" => words::INPUTS[2],
            "n_water" => words::INPUTS[3],
            "max_events" => words::INPUTS[4],
            "scene_file" => words::SCENE_FILE,
            // The scene file's text, summed up: its liquids and how many objects of each kind.
            _ => {
                let d = &loaded.description;
                for l in &d.liquids {
                    rows.push((
                        lang.fill(words::LIQUID_ROW, &[&l.name]),
                        lang.fill(words::LIQUID_VALUE, &[&l.top, &l.index]),
                    ));
                }
                let mut objects = lang.fill(
                    words::OBJECTS_VALUE,
                    &[&d.straws.len(), &d.coins.len(), &d.cards.len()],
                );
                let solids = [d.spheres.len(), d.prisms.len(), d.lenses.len()];
                if solids.iter().any(|&n| n > 0) {
                    objects +=
                        &lang.fill(words::SOLIDS_VALUE, &[&solids[0], &solids[1], &solids[2]]);
                }
                rows.push((lang.of(words::OBJECTS).to_string(), objects));
                continue;
            }
        };
        rows.push((lang.of(label).to_string(), input.value.to_string()));
    }
    rows
}

/// The built-in check where nothing bends light (`n_water = 1` and nothing else refracting):
/// every image point lies on the straw.
fn check(job: &Job, cloud: &ImageCloud, lang: Lang) -> Option<Check> {
    // A thick glass or a solid bends light whatever the liquid's index: no check there.
    if job.n_water != 1.0 || job.loaded.world.refracts() {
        return None;
    }
    let max = max_distance_to_objects(&job.loaded, cloud);
    let passed = !cloud.points.is_empty() && max < ON_STRAW_TOLERANCE;
    let verdict = lang.of(if passed { words::PASS } else { words::FAIL });
    let text = if cloud.points.is_empty() {
        lang.of(words::NO_POINTS_TO_CHECK).to_string()
    } else {
        lang.fill(
            words::ON_STRAW_CHECK,
            &[
                &cloud.points.len(),
                &format!("{max:.3e}"),
                &format!("{ON_STRAW_TOLERANCE:e}"),
                &verdict,
            ],
        )
    };
    let short = lang.fill(words::ON_STRAW_SHORT, &[&format!("{max:.1e}"), &verdict]);
    Some(Check {
        passed,
        text,
        short,
    })
}

/// How far the image lies from the real straw: zero for `n_water = 1`, growing with the index.
fn distance_note(job: &Job, cloud: &ImageCloud, lang: Lang) -> String {
    if cloud.points.is_empty() {
        return lang.of(words::NOT_SEEN).into();
    }
    let mm = format!("{:.3}", 1e3 * max_distance_to_objects(&job.loaded, cloud));
    // The note on the index applies where the scene has one index of its own to name.
    match job.loaded.input("n_water") {
        Some(n) => lang.fill(words::DISTANCE_NOTE, &[&mm, &n]),
        None => lang.fill(words::SCENE_DISTANCE_NOTE, &[&mm]),
    }
}

/// Largest distance (m) of an image point from the surface of the object it shows.
fn max_distance_to_objects(loaded: &Setup, cloud: &ImageCloud) -> f64 {
    cloud
        .points
        .iter()
        .map(|p| loaded.world.distance_to_objects(p.position))
        .fold(0.0, f64::max)
}

/// The table printed at the end: each simulation's counts, time and check.
pub fn summary(report: &Report, out: &Path) -> String {
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
        for c in s.counts.iter().take(SECTION_NAMES.len()) {
            let _ = write!(t, " {c:>7}");
        }
        let secs: Duration = s.timings.iter().map(|t| t.duration).sum();
        let check = s.check.as_ref().map(|c| c.short.as_str()).unwrap_or("");
        let _ = writeln!(t, " {:>8.2}  {check}", secs.as_secs_f64());
    }
    let _ = writeln!(t, "  report: {}", out.join(REPORT_FILE).display());
    t
}

/// `bentstraw check` of a simulation's own image points (of the scene `loaded`, seen from its
/// observer) with the default tolerance and minimum coverage, for the report: its verdict in one
/// line.
pub fn own_points_check(loaded: &Setup, points: &[ImagePoint]) -> Check {
    let claimed: Vec<ClaimedPoint> = points
        .iter()
        .map(|p| ClaimedPoint {
            position: p.position,
            color: p.color,
        })
        .collect();
    let r = check_solution(
        &loaded.world,
        loaded.observer,
        &claimed,
        DEFAULT_TOLERANCE,
        DEFAULT_MIN_COVERAGE,
    );
    let colours = loaded.colour_names().len();
    let passed = r.passes();
    let verdict = if passed { "pass" } else { "fail" };
    let coverage: Vec<String> = r
        .coverage
        .per_colour
        .iter()
        .take(colours)
        .map(|c| format!("{:.1} %", 100.0 * c.share()))
        .collect();
    let mut text = format!(
        "{verdict}: {} of {} points correct (path lengths within {} m), coverage per colour 1–{colours}: {}",
        r.tally.correct,
        r.tally.points,
        number_text(DEFAULT_TOLERANCE),
        coverage.join(", ")
    );
    if let Some(m) = r.coverage.missing.first() {
        let _ = write!(text, "; largest missing region: {}", region_words(m));
    }
    Check {
        passed,
        text,
        short: format!("check: {verdict}"),
    }
}
