//! Command-line arguments (clap), and parsers for the value forms they use (`X,Y,Z`, `WxH`).

use std::path::{Path, PathBuf};

use bentstraw_io::camera::CameraSpec;
use bentstraw_io::parse::{parse_size, parse_vec2, parse_vec3};
use bentstraw_io::view_spec::{SceneFile, ViewSpec};
use bentstraw_optics::scene::DEFAULT_MAX_EVENTS;
use bentstraw_optics::setup::{SceneValues, Setup};
use bentstraw_optics::view::{PictureSpec, DEFAULT_POINTS, DEFAULT_PRUNE, DEFAULT_SAMPLES};
use clap::{Args, Parser, Subcommand, ValueEnum};

/// bentstraw: what refraction does to a straw in a glass of water.
///
/// With no command, runs `table`: the four reference simulations and their checks, into out/.
#[derive(Parser, Debug)]
#[command(name = "bentstraw", version, about, long_about = None)]
pub struct Cli {
    /// What to do (default: table).
    #[command(subcommand)]
    pub command: Option<Command>,
}

/// The commands.
#[derive(Subcommand, Debug)]
pub enum Command {
    /// Trace rays from an observer and write the straw's virtual image points.
    #[command(
        after_help = "Example:\n  bentstraw simulate --observer 0,0.1,0.1 --straw 0.02,0.01 --water-height 0.15 \\\n      --output sim1.csv --plot sim1.png --html sim1.html"
    )]
    Simulate(SimulateArgs),
    /// Run the four reference simulations and their checks, and write a report (index.html).
    #[command(
        after_help = "The report prints from the browser on at most 16 A4 pages (the gallery and the \
3D views stay on screen; the printout says where). The folder holds about 20 MB: figures as SVG, \
pictures as PNG, image points as gzip-compressed CSV. With --lang fr the report is in French \
(headings, captions, tables, notes, the validation figure, the gap plots and the ray diagrams; \
numbers keep their decimal point).\n\nExamples:\n  bentstraw table --out out/      # then open out/index.html in a web browser\n  \
bentstraw table --lang fr --out rapport/"
    )]
    Table(TableArgs),
    /// Render the picture the observer's eye sees (pinhole camera).
    #[command(
        after_help = "Examples:\n  # the classic broken straw, seen from 30 cm away\n  bentstraw render --observer 0.3,0,0.22 --straw -0.02,0.02 --water-height 0.15 --output view.png\n  bentstraw render --observer 0.1,0,0.1 --straw 0.02,0.01 --water-height 0.15 \\\n      --mode fresnel --output view.png --raw view.csv"
    )]
    Render(RenderArgs),
    /// Measure the tracer's speed in rays per second.
    #[command(
        after_help = "Example:\n  bentstraw bench            # the four reference views, both modes\n  bentstraw bench --json --threads 2"
    )]
    Bench(BenchArgs),
    /// Check a solution's image points: which are right, which are wrong, and what is missing.
    #[command(
        after_help = "Reads columns x y z color (a header may name them in another order; separators: \
comma, semicolon, tab or spaces; lines starting with # or % are comments). Exit code 0: pass, \
1: fail, 2: bad input.\n\nExample:\n  bentstraw check mine.csv --observer 0.1,0,0.1 --straw 0.02,0.01 \
--water-height 0.15 --plot check.png\n  bentstraw check mine.txt --observer 0.1,0,0.1 --straw 0.02,0.01 \
--water-height 0.15 --json"
    )]
    Check(CheckArgs),
    /// Grade a class: every student's solution files checked, a gradebook and Gradescope's results.
    #[command(
        after_help = "CLASS holds one folder per student (Moodle's \"download all submissions\" \
folders, Name_Id_assignsubmission_file_, give the name). Each student hands in sim1 … sim4 (.csv, \
.txt or .dat), the four reference simulations, 25 points each: a pass scores them, a fail the \
share of right points times the coverage over the coverage asked for, a missing or unreadable file \
none. Writes DIR/grades.csv, the class at a glance (DIR/index.html), and for each student the \
feedback page (DIR/<student>/index.html) and Gradescope's results (DIR/<student>/results.json). \
Exit code 0 when the class is graded, 2 for bad input. --assignment FILE.toml grades other cases: scenes, \
observers, files and points of your own.\n\nExample:\n  bentstraw grade submissions/ --out grades/\n  bentstraw grade submissions/ --out grades/ --assignment prism-lab.toml --lang fr"
    )]
    Grade(GradeArgs),
    /// Explore live in the browser: drag the eye around the glass, click to see the light's path.
    #[command(
        after_help = "Example:\n  bentstraw explore                       # opens http://127.0.0.1:8157/\n  bentstraw explore --port 0 --no-open --observer 0.3,0,0.1 --straw 0,0 --water-height 0.15"
    )]
    Explore(ExploreArgs),
}

/// The scene and observer flags of `simulate`, `render` and `check`: the values, or a scene file
/// that the values override.
#[derive(Args, Debug, Clone)]
pub struct SceneFlags {
    /// A scene file (TOML, see scenes/), or a gallery scene or the assignment's own (spec) by
    /// name from any folder (e.g. leaning-straw): the observer it names is used when --observer
    /// is absent, and --straw, --water-height and --n-water change its one straw and one liquid
    #[arg(long, value_name = "FILE.toml")]
    pub scene: Option<PathBuf>,
    /// Observer position X,Y,Z in metres, e.g. 0,0.1,0.1
    #[arg(long, value_name = "X,Y,Z", value_parser = parse_vec3, allow_hyphen_values = true, required_unless_present = "scene")]
    pub observer: Option<[f64; 3]>,
    /// Straw axis XP,YP in metres, e.g. 0.02,0.01
    #[arg(long, value_name = "XP,YP", value_parser = parse_vec2, allow_hyphen_values = true, required_unless_present = "scene")]
    pub straw: Option<[f64; 2]>,
    /// Water height in metres, 0 <= H <= 0.2
    #[arg(
        long,
        value_name = "H",
        allow_hyphen_values = true,
        required_unless_present = "scene"
    )]
    pub water_height: Option<f64>,
    /// Refractive index of the water (>= 1) [default: 1.333, or the scene file's]
    #[arg(long, value_name = "N", allow_hyphen_values = true)]
    pub n_water: Option<f64>,
    /// Wavelength of the light in nanometres, 380..=780, where an index depends on it (a scene
    /// file's cauchy, sellmeier or material) [default: 587.56, the d line]
    #[arg(long, value_name = "NM", allow_hyphen_values = true)]
    pub wavelength: Option<f64>,
    /// Most events (refractions and total reflections) a ray may undergo, 1..=1000
    #[arg(
        long,
        value_name = "N",
        default_value_t = DEFAULT_MAX_EVENTS,
        allow_hyphen_values = true
    )]
    pub max_events: u32,
}

/// The scene flags of a command that has its own view when they are absent (`bench`, `explore`):
/// every one optional.
#[derive(Args, Debug, Clone)]
pub struct OptionalSceneFlags {
    /// A scene file (TOML, see scenes/), or a gallery scene or the assignment's own (spec) by
    /// name from any folder (e.g. leaning-straw): the observer it names is used when --observer
    /// is absent, and --straw, --water-height and --n-water change its one straw and one liquid
    #[arg(long, value_name = "FILE.toml")]
    pub scene: Option<PathBuf>,
    /// Observer position X,Y,Z in metres [default: the scene file's; without one, reference 2 in explore, the four reference views in bench]
    #[arg(long, value_name = "X,Y,Z", value_parser = parse_vec3, allow_hyphen_values = true)]
    pub observer: Option<[f64; 3]>,
    /// Straw axis XP,YP in metres [default: the scene file's; without one, reference 2 in explore, the four reference views in bench]
    #[arg(long, value_name = "XP,YP", value_parser = parse_vec2, allow_hyphen_values = true)]
    pub straw: Option<[f64; 2]>,
    /// Water height in metres, 0 <= H <= 0.2 [default: the scene file's; without one, reference 2
    /// in explore, the four reference views in bench]
    #[arg(long, value_name = "H", allow_hyphen_values = true)]
    pub water_height: Option<f64>,
    /// Refractive index of the water (>= 1) [default: 1.333, or the scene file's]
    #[arg(long, value_name = "N", allow_hyphen_values = true)]
    pub n_water: Option<f64>,
    /// Wavelength of the light in nanometres, 380..=780, where an index depends on it (a scene
    /// file's cauchy, sellmeier or material) [default: 587.56, the d line]
    #[arg(long, value_name = "NM", allow_hyphen_values = true)]
    pub wavelength: Option<f64>,
    /// Most events (refractions and total reflections) a ray may undergo, 1..=1000
    #[arg(
        long,
        value_name = "N",
        default_value_t = DEFAULT_MAX_EVENTS,
        allow_hyphen_values = true
    )]
    pub max_events: u32,
}

/// How an image point's position is judged.
#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum ImageModelArg {
    /// The course's convention: the point straight ahead along the first ray, as far as the light travelled (P = O + L·u0).
    #[default]
    Course,
    /// A small pupil: the astigmatic foci of the bundle reaching the eye.
    Eye,
    /// Two eyes 65 mm apart: triangulated lines of sight.
    Stereo,
}

/// Arguments of `simulate`.
#[derive(Args, Debug)]
pub struct SimulateArgs {
    /// The scene and the observer.
    #[command(flatten)]
    pub scene: SceneFlags,
    /// At least this many image points (at most 10000000; 2000000 with the eye or stereo model)
    #[arg(
        long,
        value_name = "N",
        default_value_t = DEFAULT_POINTS,
        allow_hyphen_values = true
    )]
    pub points: usize,
    /// Where to write the points: .csv, .json or .ply (by extension)
    #[arg(long, value_name = "FILE")]
    pub output: PathBuf,
    /// Also draw the classic figure (front, side and top views) into this file: .png, .svg or
    /// .pdf (by extension)
    #[arg(long, value_name = "FILE.png|.svg|.pdf")]
    pub plot: Option<PathBuf>,
    /// Also write a self-contained, rotatable 3D view into this HTML file
    #[arg(long, value_name = "FILE.html")]
    pub html: Option<PathBuf>,
    /// Also draw a ray diagram (side and top views of about 40 broken light paths, coloured by
    /// path type) into this file: .svg, .png or .pdf (by extension)
    #[arg(long, value_name = "FILE.svg|.png|.pdf")]
    pub rays: Option<PathBuf>,
    /// How the apparent position is judged
    #[arg(long, value_enum, default_value_t = ImageModelArg::Course)]
    pub image_model: ImageModelArg,
    /// Also draw the course's, the eye's and the stereo image one above the other, same views and
    /// scales, into this file: .png, .svg or .pdf (runs the eye and stereo models)
    #[arg(long, value_name = "FILE.png|.svg|.pdf")]
    pub models_plot: Option<PathBuf>,
    /// Also plot the gap from each course point to the eye's and the stereo model's point against
    /// the straw point's height, into this file: .png, .svg or .pdf (runs both models)
    #[arg(long, value_name = "FILE.png|.svg|.pdf")]
    pub gap_plot: Option<PathBuf>,
    /// The light the rays carry: white gives each ray one band of the spectrum in turn (as many
    /// points, an eighth in each band), writes each point's wavelength in a `wavelength` column
    /// and colours the figures by it
    #[arg(long, value_enum, default_value_t = LightArg::Mono)]
    pub light: LightArg,
}

/// Arguments of `table`.
#[derive(Args, Debug, Default)]
pub struct TableArgs {
    /// Folder to write into
    #[arg(long, value_name = "DIR", default_value = "out")]
    pub out: PathBuf,
    /// At least this many image points per simulation (at most 200000)
    #[arg(
        long,
        value_name = "N",
        default_value_t = DEFAULT_POINTS,
        allow_hyphen_values = true
    )]
    pub points: usize,
    /// The report's language: headings, captions, tables and figure text
    #[arg(long, value_enum, default_value_t = LangArg::En)]
    pub lang: LangArg,
    /// The report of this scene instead of the reference simulations: a scene file (TOML, see
    /// scenes/) or a gallery scene by name (e.g. leaning-straw), seen from the observer it names
    /// and three more observers turned about the vertical through its target
    #[arg(long, value_name = "FILE.toml")]
    pub scene: Option<PathBuf>,
    /// Also write the report as a PDF of A4 pages into this file, laid out as the page prints
    /// (no browser needed)
    #[arg(long, value_name = "FILE.pdf")]
    pub pdf: Option<PathBuf>,
    /// With --scene: the first observer X,Y,Z in metres, instead of the file's own observer
    #[arg(long, value_name = "X,Y,Z", value_parser = parse_vec3, allow_hyphen_values = true, requires = "scene")]
    pub observer: Option<[f64; 3]>,
    /// With --scene: the wavelength of the light in nanometres, 380..=780, where an index
    /// depends on it [default: 587.56, the d line]
    #[arg(
        long,
        value_name = "NM",
        allow_hyphen_values = true,
        requires = "scene"
    )]
    pub wavelength: Option<f64>,
}

/// The language of the report.
#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum LangArg {
    /// English.
    #[default]
    En,
    /// French (the explorer's French words).
    Fr,
}

impl From<LangArg> for bentstraw_io::words::Lang {
    fn from(a: LangArg) -> Self {
        match a {
            LangArg::En => Self::En,
            LangArg::Fr => Self::Fr,
        }
    }
}

/// The observer's picture mode: the course's single ray, or Fresnel-weighted branches.
#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum ModeArg {
    /// One ray per sample, the colour code it hits.
    Course,
    /// Fresnel reflection and refraction, weights per section.
    Fresnel,
}

impl ModeArg {
    /// The mode of a picture as the engine's defaults draw it.
    pub fn default_picture() -> ModeArg {
        if PictureSpec::default().fresnel {
            ModeArg::Fresnel
        } else {
            ModeArg::Course
        }
    }
}

/// The light a picture is drawn in, or image points are traced in.
#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum LightArg {
    /// Light of one wavelength, --wavelength's (the d line by default).
    #[default]
    Mono,
    /// White light: eight bands of the spectrum, each traced at its own wavelength and seen in
    /// its colour (where a scene's index depends on the wavelength, colour fringes appear).
    White,
}

/// Where a rendered picture takes its samples.
#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum SamplingArg {
    /// Every pixel's centre, then the samples only where a pixel's centre and a neighbour's
    /// differ (an edge): the same picture within a few levels where nothing is finer than a
    /// pixel (see docs/physics.md).
    #[default]
    Adaptive,
    /// The samples at every pixel.
    Full,
}

/// What lies behind the glass in a rendered picture.
#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum BackdropArg {
    /// A plain light background.
    None,
    /// A checkerboard wall and floor.
    Checker,
}

impl BackdropArg {
    /// The backdrop of a picture as the engine's defaults draw it.
    pub fn default_picture() -> BackdropArg {
        if PictureSpec::default().checker {
            BackdropArg::Checker
        } else {
            BackdropArg::None
        }
    }
}

/// Camera options shared by `render` and `bench`.
#[derive(Args, Debug, Clone)]
pub struct CameraArgs {
    /// Point the camera looks at (default: the scene file's target, else 0,0,0.125)
    #[arg(long, value_name = "X,Y,Z", value_parser = parse_vec3, allow_hyphen_values = true)]
    pub target: Option<[f64; 3]>,
    /// Vertical field of view in degrees, 0 < FOV < 180 (default: frames the glass and straw)
    #[arg(long, value_name = "DEG", allow_hyphen_values = true)]
    pub fov: Option<f64>,
    /// Picture size in pixels [default: 800x600]
    #[arg(long, value_name = "WxH", value_parser = parse_size)]
    pub size: Option<(u32, u32)>,
}

/// Arguments of `render`.
#[derive(Args, Debug)]
pub struct RenderArgs {
    /// The scene and the observer.
    #[command(flatten)]
    pub scene: SceneFlags,
    /// The camera.
    #[command(flatten)]
    pub camera: CameraArgs,
    /// Course (colour codes) or fresnel (weights)
    #[arg(long, value_enum, default_value_t = ModeArg::default_picture())]
    pub mode: ModeArg,
    /// Backdrop behind the glass
    #[arg(long, value_enum, default_value_t = BackdropArg::default_picture())]
    pub backdrop: BackdropArg,
    /// The light the picture is drawn in (white light costs a picture per band where an index
    /// depends on the wavelength; --raw stays at the one wavelength)
    #[arg(long, value_enum, default_value_t = LightArg::Mono)]
    pub light: LightArg,
    /// Fresnel branches lighter than this are abandoned, 0 <= W < 1
    ///
    /// Pruning only takes weight away: a pixel loses at most the weight of the branches it
    /// abandons (each lighter than W, but there may be several; with the default, at most 1.5e-4
    /// on the assignment's views). See docs/physics.md.
    #[arg(
        long,
        value_name = "W",
        default_value_t = DEFAULT_PRUNE,
        allow_hyphen_values = true
    )]
    pub prune: f64,
    /// Samples per pixel side for anti-aliasing (N×N rays in pixels at an edge), 1..=16
    #[arg(long, value_name = "N", default_value_t = DEFAULT_SAMPLES)]
    pub samples: u32,
    /// Where the N×N samples are taken: at edges only, or at every pixel
    #[arg(long, value_enum, default_value_t = SamplingArg::Adaptive)]
    pub sampling: SamplingArg,
    /// The picture (PNG)
    #[arg(long, value_name = "FILE.png")]
    pub output: PathBuf,
    /// Also write one ray per pixel centre as CSV
    #[arg(long, value_name = "FILE.csv")]
    pub raw: Option<PathBuf>,
}

/// Arguments of `bench`.
#[derive(Args, Debug)]
pub struct BenchArgs {
    /// Threads for the multi-threaded runs (default: all cores)
    #[arg(long, value_name = "N")]
    pub threads: Option<usize>,
    /// Timed repeats per case (the median is reported)
    #[arg(long, value_name = "N", default_value_t = 20)]
    pub repeat: usize,
    /// One JSON object per line instead of a table
    #[arg(long)]
    pub json: bool,
    /// A single view to time (the four reference views when none is given).
    #[command(flatten)]
    pub view: OptionalSceneFlags,
    /// The camera of a single view.
    #[command(flatten)]
    pub camera: CameraArgs,
    /// Mode of a single view (default: both)
    #[arg(long, value_enum)]
    pub mode: Option<ModeArg>,
    /// Time the pictures as render and the explorer draw them (shaded, checkerboard backdrop,
    /// 3x3 samples at edges, through the frame call) instead of one ray per pixel centre
    #[arg(long)]
    pub frame: bool,
    /// Also time the apparent-position models on each view's image points (ns per point for the
    /// image points, the eye model and the stereo model, and each model's ratio to the points)
    #[arg(long)]
    pub models: bool,
}

/// Arguments of `check`.
#[derive(Args, Debug)]
pub struct CheckArgs {
    /// The solution's image points: columns x y z color, in metres and colour codes 1..5
    #[arg(value_name = "FILE")]
    pub file: PathBuf,
    /// The scene and the observer the solution was computed for.
    #[command(flatten)]
    pub scene: SceneFlags,
    /// Largest allowed difference between a point's distance from the observer and its ray's path
    /// length, in metres (> 0)
    #[arg(
        long,
        value_name = "M",
        default_value_t = bentstraw_optics::check::DEFAULT_TOLERANCE,
        allow_hyphen_values = true
    )]
    pub tolerance: f64,
    /// Share of each colour's true image (by solid angle) the points must cover to be complete, 0..=1
    #[arg(
        long,
        value_name = "SHARE",
        default_value_t = bentstraw_optics::check::DEFAULT_MIN_COVERAGE,
        allow_hyphen_values = true
    )]
    pub min_coverage: f64,
    /// Print one JSON object (for graders' scripts) instead of the summary
    #[arg(long)]
    pub json: bool,
    /// Also draw a figure: the true image, the solution's points and what is missing (.png, .svg
    /// or .pdf)
    #[arg(long, value_name = "FILE.png|.svg|.pdf")]
    pub plot: Option<PathBuf>,
    /// How many of the worst points to list
    #[arg(long, value_name = "N", default_value_t = 10)]
    pub worst: usize,
}

/// Arguments of `grade`.
#[derive(Args, Debug)]
pub struct GradeArgs {
    /// The class: a folder with one sub-folder per student
    #[arg(value_name = "CLASS")]
    pub class: PathBuf,
    /// Folder for the gradebook (grades.csv), the class's page (index.html) and each student's
    /// feedback page and Gradescope results (STUDENT/index.html, STUDENT/results.json)
    #[arg(long, value_name = "DIR")]
    pub out: PathBuf,
    /// The cases to grade (TOML, one table per case, see docs/usage.md) instead of the four
    /// reference simulations
    #[arg(long, value_name = "FILE.toml")]
    pub assignment: Option<PathBuf>,
    /// The language of the feedback pages
    #[arg(long, value_enum, default_value_t = LangArg::En)]
    pub lang: LangArg,
}

/// Arguments of `explore`.
#[derive(Args, Debug)]
pub struct ExploreArgs {
    /// Port to listen on (0: any free port)
    #[arg(long, value_name = "N", default_value_t = 8157)]
    pub port: u16,
    /// Address to listen on; only 127.0.0.1 (this machine) unless you give another (then a
    /// random token in the printed address is asked for on every request)
    #[arg(long, value_name = "ADDR", default_value = "127.0.0.1")]
    pub host: String,
    /// Another name of this machine to answer to (a classroom machine's, as the other machines
    /// write it); may be given more than once
    #[arg(long, value_name = "NAME")]
    pub allow_host: Vec<String>,
    /// Do not open a browser (print the address only)
    #[arg(long)]
    pub no_open: bool,
    /// The view to start with (reference 2 when none is given).
    #[command(flatten)]
    pub view: OptionalSceneFlags,
    /// At least this many image points in the 3D view
    #[arg(
        long,
        value_name = "N",
        default_value_t = DEFAULT_POINTS,
        allow_hyphen_values = true
    )]
    pub points: usize,
    /// The picture's mode to start with
    #[arg(long, value_enum, default_value_t = ModeArg::default_picture())]
    pub mode: ModeArg,
}

/// The scene of `view`, loaded, with a hint on standard error for each number of its scene
/// file that breaks no rule but looks like a slip (centimetres written as metres).
pub fn load_scene(view: &ViewSpec) -> bentstraw_io::Result<Setup> {
    view.load().map(with_hints)
}

/// `loaded`, after its scene file's hints (numbers that look like centimetres) on stderr.
pub fn with_hints(loaded: Setup) -> Setup {
    if let Some(name) = &loaded.name {
        for hint in loaded.description.hints() {
            eprintln!("hint: {name}: {hint}");
        }
    }
    loaded
}

/// The view of a scene as flags give it, its file (`--scene`) read but nothing checked yet: the
/// file and the values; the camera, the picture and the points as by default.
fn scene_view(file: Option<&Path>, values: SceneValues) -> bentstraw_io::Result<ViewSpec> {
    Ok(ViewSpec {
        scene: file.map(SceneFile::read).transpose()?,
        values,
        ..ViewSpec::default()
    })
}

impl SceneFlags {
    /// The view of these flags' scene (see [`scene_view`]).
    pub fn view(&self) -> bentstraw_io::Result<ViewSpec> {
        let values = SceneValues {
            observer: self.observer,
            straw: self.straw,
            water_height: self.water_height,
            n_water: self.n_water,
            max_events: self.max_events,
            wavelength: self.wavelength,
        };
        scene_view(self.scene.as_deref(), values)
    }
}

impl OptionalSceneFlags {
    /// The view of these flags' scene (see [`scene_view`]): only the values given.
    pub fn view(&self) -> bentstraw_io::Result<ViewSpec> {
        let values = SceneValues {
            observer: self.observer,
            straw: self.straw,
            water_height: self.water_height,
            n_water: self.n_water,
            max_events: self.max_events,
            wavelength: self.wavelength,
        };
        scene_view(self.scene.as_deref(), values)
    }
}

impl From<&CameraArgs> for CameraSpec {
    fn from(a: &CameraArgs) -> Self {
        CameraSpec {
            target: a.target,
            fov: a.fov,
            size: a.size,
        }
    }
}

impl SimulateArgs {
    /// The view these flags ask for (the scene and the points), its scene file read but nothing
    /// checked yet.
    pub fn view(&self) -> bentstraw_io::Result<ViewSpec> {
        Ok(ViewSpec {
            points: self.points,
            picture: PictureSpec {
                white: self.light == LightArg::White,
                ..PictureSpec::default()
            },
            ..self.scene.view()?
        })
    }
}

impl RenderArgs {
    /// The view these flags ask for (the scene, the camera and the picture), its scene file read
    /// but nothing checked yet.
    pub fn view(&self) -> bentstraw_io::Result<ViewSpec> {
        Ok(ViewSpec {
            camera: (&self.camera).into(),
            picture: self.picture(),
            ..self.scene.view()?
        })
    }

    /// The picture as these flags ask for it.
    pub fn picture(&self) -> PictureSpec {
        PictureSpec {
            fresnel: self.mode == ModeArg::Fresnel,
            checker: self.backdrop == BackdropArg::Checker,
            prune: self.prune,
            samples: self.samples,
            adaptive: self.sampling == SamplingArg::Adaptive,
            white: self.light == LightArg::White,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use bentstraw_io::view_spec::{ImageModel, Verb};
    use bentstraw_optics::view::DEFAULT_SIZE;

    /// The command `args` (as `ViewSpec::args` writes them), then `--output out`, parsed by clap.
    fn parsed(args: &[String], out: &str) -> Command {
        let line = ["bentstraw"]
            .into_iter()
            .chain(args.iter().map(String::as_str))
            .chain(["--output", out]);
        match Cli::try_parse_from(line) {
            Ok(cli) => cli.command.expect("a command"),
            Err(e) => panic!("{}: {e}", args.join(" ")),
        }
    }

    /// The views the round trip is tried on: the assignment's values, a gallery scene by name
    /// seen from an observer, a scene file by its path, a picture asked for in full, a camera.
    fn views(file: &Path) -> Vec<ViewSpec> {
        let glass = ViewSpec {
            values: SceneValues {
                observer: Some([0.1, 0.0, 0.1]),
                straw: Some([0.02, -0.01]),
                water_height: Some(0.15),
                n_water: Some(1.4),
                max_events: 7,
                wavelength: Some(486.13),
            },
            points: 1500,
            ..ViewSpec::default()
        };
        let gallery = ViewSpec {
            scene: SceneFile::gallery("reversing-arrow"),
            values: SceneValues {
                observer: Some([0.3, 0.0, 0.1]),
                ..SceneValues::default()
            },
            ..ViewSpec::default()
        };
        let on_disk = ViewSpec {
            scene: Some(SceneFile::read(file).unwrap()),
            values: SceneValues {
                n_water: Some(1.5),
                ..gallery.values
            },
            ..ViewSpec::default()
        };
        let picture = ViewSpec {
            picture: PictureSpec {
                fresnel: true,
                checker: true,
                prune: 1e-3,
                samples: 5,
                adaptive: false,
                white: true,
            },
            ..glass.clone()
        };
        let course = ViewSpec {
            picture: PictureSpec {
                fresnel: false,
                checker: false,
                ..PictureSpec::default()
            },
            points: 0,
            ..ViewSpec::default()
        };
        let camera = ViewSpec {
            camera: CameraSpec {
                target: Some([0.0, 0.01, -0.125]),
                fov: Some(40.5),
                size: Some((40, 30)),
            },
            ..gallery.clone()
        };
        vec![
            ViewSpec::default(),
            glass,
            gallery,
            on_disk,
            picture,
            course,
            camera,
        ]
    }

    /// A view written as `render`'s and `simulate`'s arguments (`ViewSpec::args`) reads back, by
    /// clap and `RenderArgs::view` / `SimulateArgs::view`, as itself: all of it that the verb's
    /// command carries (render: all but the points, its size always; simulate: the scene and
    /// the points, at least one, and the image model).
    #[test]
    fn a_views_command_lines_read_back_as_the_view() {
        let file = std::env::temp_dir().join(format!("bentstraw-cli-{}.toml", std::process::id()));
        let text = SceneFile::gallery("tank-pencil").unwrap().text;
        std::fs::write(&file, text.replace("0.10", "0.11")).unwrap();
        for view in views(&file) {
            let args = view.args(Verb::Render);
            let Command::Render(render) = parsed(&args, "view.png") else {
                panic!("not render: {args:?}");
            };
            let expected = ViewSpec {
                camera: CameraSpec {
                    size: Some(view.camera.size.unwrap_or(DEFAULT_SIZE)),
                    ..view.camera
                },
                points: DEFAULT_POINTS,
                ..view.clone()
            };
            assert_eq!(render.view().unwrap(), expected, "{}", args.join(" "));

            for model in [ImageModel::Course, ImageModel::Eye, ImageModel::Stereo] {
                let args = view.args(Verb::Simulate(model));
                let Command::Simulate(simulate) = parsed(&args, "points.csv") else {
                    panic!("not simulate: {args:?}");
                };
                let expected = ViewSpec {
                    camera: CameraSpec::default(),
                    picture: PictureSpec {
                        white: view.picture.white,
                        ..PictureSpec::default()
                    },
                    points: view.points.max(1),
                    ..view.clone()
                };
                assert_eq!(simulate.view().unwrap(), expected, "{}", args.join(" "));
                let name = simulate.image_model.to_possible_value().unwrap();
                assert_eq!(name.get_name(), model.name(), "{}", args.join(" "));
            }
        }
        std::fs::remove_file(&file).unwrap();
    }
}
