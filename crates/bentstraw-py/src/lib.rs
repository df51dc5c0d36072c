//! `bentstraw._engine`: the compiled part of the Python package. Each call loads the scene the
//! way the command line does ([`ViewSpec::load`]), runs the same library calls as `simulate`,
//! `render`, `check` and the explorer's clicked ray, with the interpreter's lock released while
//! it works, and hands the results to Python as numpy arrays that take over the engine's own
//! buffers (no copy). The friendly functions, their defaults and documentation are in
//! `python/bentstraw/__init__.py`; the physics is explained in `docs/physics.md`.

#![warn(missing_docs)]

use std::collections::BTreeMap;
use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{mpsc, Arc};
use std::time::Duration;

use bentstraw_io::camera::{scene_camera, CameraSpec};
use bentstraw_io::gallery::GALLERY;
use bentstraw_io::grade as grading;
use bentstraw_io::pictures::{checked_shading, picture_until};
use bentstraw_io::scene_input::{parse_scene_text, read_scene_text, SceneFile};
use bentstraw_io::solution::{json_report, solution_of_points, CheckOptions, Solution};
use bentstraw_io::words::Lang;
use bentstraw_io::writers::{
    check_points_asked, raw_weight_count, write_points, ModelPoints, PointFormat, PointSet,
};
use bentstraw_io::{Error, ViewSpec};
use bentstraw_optics::apparent::{eye_model_points, stereo_points};
use bentstraw_optics::camera::Camera;
use bentstraw_optics::check::{check_solution, CheckReport};
use bentstraw_optics::image::ImagePoint;
use bentstraw_optics::light_path_type::LightPathType;
use bentstraw_optics::picture::{course_picture_exact, fresnel_picture_exact};
use bentstraw_optics::sampling::{light_path_types, sample_image_until};
use bentstraw_optics::setup::{SceneValues, Setup};
use bentstraw_optics::spectrum::{white_bands, WHITE_BANDS};
use bentstraw_optics::text::number_text;
use bentstraw_optics::text::refuse_choice;
use bentstraw_optics::view::PictureSpec;
use bentstraw_optics::world::{COLOR_NAMES, COLOR_RGB};
use bentstraw_optics::Vec3;
use numpy::{PyArray1, PyArrayMethods, PyReadonlyArray1, PyReadonlyArray2};
use pyo3::exceptions::{PyFileNotFoundError, PyOSError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// The Python exception for a library error: a broken rule is a `ValueError` with the command
/// line's message; a file that cannot be read, an `OSError`.
fn python_error(e: Error) -> PyErr {
    match &e {
        Error::Io { source, .. } if source.kind() == std::io::ErrorKind::NotFound => {
            PyFileNotFoundError::new_err(e.to_string())
        }
        Error::Io { .. } => PyOSError::new_err(e.to_string()),
        _ => PyValueError::new_err(e.to_string()),
    }
}

/// How often a computation's wait looks at the interpreter's signals (Ctrl-C, Jupyter's
/// interrupt): well within the 0.2 s a person notices.
const SIGNALS_EVERY: Duration = Duration::from_millis(40);

/// Runs `work` on a thread of its own while the interpreter's other threads run, and looks at
/// the interpreter's signals every [`SIGNALS_EVERY`]: on Ctrl-C (or Jupyter's "Interrupt
/// kernel") it sets the stop flag `work` is given, waits for `work` to give up (the engine looks
/// at the flag between rays and rows) and raises the signal's exception, `KeyboardInterrupt`, with
/// nothing left running. `work`'s result is `None` when it stopped.
fn interruptible<T: Send>(
    py: Python<'_>,
    work: impl FnOnce(&Arc<AtomicBool>) -> Option<T> + Send,
) -> PyResult<T> {
    let stop = Arc::new(AtomicBool::new(false));
    std::thread::scope(|s| {
        let (done, mut finished) = mpsc::channel();
        let flag = Arc::clone(&stop);
        let worker = s.spawn(move || {
            let out = work(&flag);
            // (The waiting side may have gone: a signal's exception is being raised.)
            let _ = done.send(());
            out
        });
        loop {
            // (The receiver goes to the waiting side and back: it may not be shared.)
            let over;
            (over, finished) =
                py.detach(move || (finished.recv_timeout(SIGNALS_EVERY).is_ok(), finished));
            if over {
                break;
            }
            if let Err(signal) = py.check_signals() {
                stop.store(true, Ordering::Relaxed);
                // It gives up at once; a panic in it is its own bug, said as such.
                let _ = py.detach(|| worker.join());
                return Err(signal);
            }
        }
        match worker.join() {
            Ok(Some(out)) => Ok(out),
            // Stopped without a signal to raise: cannot happen, the flag is only set above.
            Ok(None) => Err(PyValueError::new_err("the computation was stopped")),
            Err(panic) => std::panic::resume_unwind(panic),
        }
    })
}

/// A scene loaded and checked, with its observer: what every call traces.
#[pyclass(frozen, module = "bentstraw._engine")]
struct LoadedScene {
    loaded: Setup,
}

#[pymethods]
impl LoadedScene {
    /// The observer's eye (m).
    #[getter]
    fn observer(&self) -> [f64; 3] {
        self.loaded.observer.to_array()
    }

    /// The scene file's name, or `None` for the assignment's glass given by its numbers.
    #[getter]
    fn name(&self) -> Option<String> {
        self.loaded.name.clone()
    }

    /// Most events (refractions and total reflections) a ray may undergo.
    #[getter]
    fn max_events(&self) -> u32 {
        self.loaded.world.max_events()
    }

    /// The names of the colour codes the scene can show, code 1 first.
    #[getter]
    fn color_names(&self) -> Vec<&'static str> {
        self.loaded.colour_names().to_vec()
    }

    /// The scene file's hints: numbers that break no rule but look like a slip.
    #[getter]
    fn hints(&self) -> Vec<String> {
        match &self.loaded.name {
            Some(name) => self
                .loaded
                .description
                .hints()
                .iter()
                .map(|h| format!("{name}: {h}"))
                .collect(),
            None => Vec::new(),
        }
    }
}

/// Loads the scene as the command line's flags give it: a scene file's path or a gallery name
/// (`path`), or a scene file's text (`text` = (name, text)), or the assignment's numbers; the
/// other values override the file's where given.
#[pyfunction]
#[pyo3(signature = (path, text, observer, straw, water_height, n_water, max_events, wavelength))]
#[allow(clippy::too_many_arguments)] // the command line's flags, one by one
fn load(
    path: Option<PathBuf>,
    text: Option<(String, String)>,
    observer: Option<[f64; 3]>,
    straw: Option<[f64; 2]>,
    water_height: Option<f64>,
    n_water: Option<f64>,
    max_events: u32,
    wavelength: Option<f64>,
) -> PyResult<LoadedScene> {
    let scene = match text {
        Some((name, text)) => Some(SceneFile { name, text }),
        None => path
            .as_deref()
            .map(SceneFile::read)
            .transpose()
            .map_err(python_error)?,
    };
    let view = ViewSpec {
        scene,
        values: SceneValues {
            observer,
            straw,
            water_height,
            n_water,
            max_events,
            wavelength,
        },
        ..ViewSpec::default()
    };
    Ok(LoadedScene {
        loaded: view.load().map_err(python_error)?,
    })
}

/// The text of the scene file at `path`, read (at most 1 MB, UTF-8) and checked by the scene
/// file's rules, with its name as messages show it.
#[pyfunction]
fn read_scene(path: PathBuf) -> PyResult<(String, String)> {
    let text = read_scene_text(&path).map_err(python_error)?;
    let name = bentstraw_io::files::shown(&path);
    parse_scene_text(&name, &text).map_err(python_error)?;
    Ok((name, text))
}

/// Checks the scene file text `text` named `name` by the scene file's rules.
#[pyfunction]
fn check_scene(name: &str, text: &str) -> PyResult<()> {
    parse_scene_text(name, text).map_err(python_error)?;
    Ok(())
}

/// The gallery's scenes: (name, text of the scene file), in the gallery's order.
#[pyfunction]
fn gallery() -> Vec<(&'static str, &'static str)> {
    GALLERY.to_vec()
}

/// Why `name` is no gallery scene, as the command line says it: the names it may be a slip for.
#[pyfunction]
fn gallery_miss(name: &str) -> String {
    bentstraw_io::scene_input::gallery_miss(name)
}

/// A column of numbers as a numpy array that owns `values` (no copy).
fn column<'py, T: numpy::Element>(py: Python<'py>, values: Vec<T>) -> Bound<'py, PyArray1<T>> {
    PyArray1::from_vec(py, values)
}

/// Whether `light` (one of the picture's lights, as Python names it) is white light, or the
/// refusal naming it.
fn white_light(light: &str) -> PyResult<bool> {
    let spec = PictureSpec::default().with_light("light", light);
    Ok(spec.map_err(PyValueError::new_err)?.white)
}

/// Traces the image points of `scene` as `simulate` does: at least `points` of them in `light`
/// (`mono` or `white`), placed by `image_model` (`course`, `eye` or `stereo`), with each one's
/// ray (see [`light_paths`] for the kind of light path of each) and, in white light, its
/// band's wavelength.
#[pyfunction]
fn simulate<'py>(
    py: Python<'py>,
    scene: &LoadedScene,
    points: usize,
    image_model: &str,
    light: &str,
) -> PyResult<Bound<'py, PyDict>> {
    if !matches!(image_model, "course" | "eye" | "stereo") {
        return Err(PyValueError::new_err(refuse_choice(
            "image_model",
            image_model,
            &["course", "eye", "stereo"],
        )));
    }
    let white = white_light(light)?;
    check_points_asked(points, image_model).map_err(python_error)?;
    let loaded = &scene.loaded;
    let (world, observer) = (&loaded.world, loaded.observer);
    // The traced points, one row per point the model writes: for the course and the eye model
    // every image point; for the stereo model, those both eyes see. The columns are made while
    // other Python threads run; numpy then takes them over as they are.
    let (stats, columns, extra) = interruptible(py, |stop| {
        let mut cloud = sample_image_until(world, observer, points, white, &|_| {}, stop)?;
        let stats = (
            cloud.rays_traced,
            cloud.spacing,
            cloud.hit_ratio(),
            cloud.points.len(),
        );
        let (placed, images, extra): (Option<Vec<Option<Vec3>>>, Vec<ImagePoint>, ModelColumns) =
            match image_model {
                "eye" => {
                    let eye = eye_model_points(world, observer, &cloud.points);
                    let columns = ModelColumns::Eye {
                        s_h: eye
                            .iter()
                            .map(|p| nan_if_none(p.s_h.signed_distance()))
                            .collect(),
                        s_v: eye
                            .iter()
                            .map(|p| nan_if_none(p.s_v.signed_distance()))
                            .collect(),
                        s_h_kind: eye.iter().map(|p| p.s_h.kind()).collect(),
                        s_v_kind: eye.iter().map(|p| p.s_v.kind()).collect(),
                        gap: eye.iter().map(|p| nan_if_none(p.gap_to_course())).collect(),
                    };
                    let placed = eye.iter().map(|p| p.position).collect();
                    (Some(placed), eye.iter().map(|p| p.image).collect(), columns)
                }
                "stereo" => {
                    let stereo = stereo_points(world, observer, &cloud.points);
                    let s = &stereo.points;
                    let columns = ModelColumns::Stereo {
                        disparity: s.iter().map(|p| p.disparity).collect(),
                        vertical_disparity: s.iter().map(|p| p.vertical_disparity).collect(),
                        miss_distance: s.iter().map(|p| p.miss_distance).collect(),
                        gap: s.iter().map(|p| nan_if_none(p.gap_to_course())).collect(),
                        skipped: stereo.skipped,
                    };
                    let placed = s.iter().map(|p| p.position).collect();
                    (Some(placed), s.iter().map(|p| p.image).collect(), columns)
                }
                // The course's points are the image points themselves.
                _ => (
                    None,
                    std::mem::take(&mut cloud.points),
                    ModelColumns::Course,
                ),
            };
        let bands: Vec<Option<u8>> = images.iter().map(|p| p.band).collect();
        Some((
            stats,
            Columns::of(placed.as_deref(), images),
            (extra, bands),
        ))
    })?;
    let (extra, bands) = extra;

    let out = PyDict::new(py);
    let n = columns.color.len();
    let rows = |flat: Vec<f64>| -> PyResult<Bound<'py, PyAny>> {
        Ok(PyArray1::from_vec(py, flat).reshape([n, 3])?.into_any())
    };
    let image_xyz = rows(columns.image_xyz)?;
    match columns.xyz {
        Some(xyz) => out.set_item("xyz", rows(xyz)?)?,
        // The course's points are where its image points are: one array under both names.
        None => out.set_item("xyz", &image_xyz)?,
    }
    out.set_item("image_xyz", image_xyz)?;
    out.set_item("color", column(py, columns.color))?;
    out.set_item("direction", rows(columns.direction)?)?;
    out.set_item("path_length", column(py, columns.path_length))?;
    out.set_item("object_point", rows(columns.object_point)?)?;
    out.set_item("events", column(py, columns.events))?;
    if white {
        let nms = white_bands().map(|b| b.nm);
        let nm = |b: &Option<u8>| b.map_or(f64::NAN, |k| nms[k as usize]);
        out.set_item("wavelength", column(py, bands.iter().map(nm).collect()))?;
        let band = |b: &Option<u8>| b.map_or(-1, |k| k as i64);
        out.set_item("_band", column(py, bands.iter().map(band).collect()))?;
    }
    match extra {
        ModelColumns::Course => {}
        ModelColumns::Eye {
            s_h,
            s_v,
            s_h_kind,
            s_v_kind,
            gap,
        } => {
            out.set_item("s_h", column(py, s_h))?;
            out.set_item("s_v", column(py, s_v))?;
            out.set_item("s_h_kind", s_h_kind)?;
            out.set_item("s_v_kind", s_v_kind)?;
            out.set_item("gap", column(py, gap))?;
        }
        ModelColumns::Stereo {
            disparity,
            vertical_disparity,
            miss_distance,
            gap,
            skipped,
        } => {
            out.set_item("disparity", column(py, disparity))?;
            out.set_item("vertical_disparity", column(py, vertical_disparity))?;
            out.set_item("miss_distance", column(py, miss_distance))?;
            out.set_item("gap", column(py, gap))?;
            out.set_item("skipped", skipped)?;
        }
    }
    let (rays_traced, spacing, hit_ratio, image_points) = stats;
    out.set_item("rays_traced", rays_traced)?;
    out.set_item("spacing", spacing)?;
    out.set_item("hit_ratio", hit_ratio)?;
    out.set_item("image_points", image_points)?;
    Ok(out)
}

/// The kind of light path of each ray from the scene's observer along `direction` (n × 3, unit
/// vectors such as a simulation's `u0`): `path_index` (n) into `path_keys` and `path_words`,
/// the kinds present, sorted (direct first, then by entry face and total reflections).
#[pyfunction]
#[pyo3(signature = (scene, direction, band=None))]
fn light_paths<'py>(
    py: Python<'py>,
    scene: &LoadedScene,
    direction: PyReadonlyArray2<'_, f64>,
    band: Option<PyReadonlyArray1<'_, i64>>,
) -> PyResult<Bound<'py, PyDict>> {
    let direction = direction.as_array();
    if direction.ncols() != 3 {
        return Err(PyValueError::new_err(format!(
            "direction has {} columns: it must be an (n, 3) array of unit vectors",
            direction.ncols()
        )));
    }
    // Each ray's band of white light (from 0, violet), or none.
    let bands: Vec<Option<u8>> = match &band {
        None => vec![None; direction.nrows()],
        Some(b) => {
            let b = b.as_array();
            if b.len() != direction.nrows()
                || b.iter().any(|&k| !(0..WHITE_BANDS as i64).contains(&k))
            {
                return Err(PyValueError::new_err(format!(
                    "band must give each of the {} rays a band of white light, 0 to {}",
                    direction.nrows(),
                    WHITE_BANDS - 1
                )));
            }
            b.iter().map(|&k| Some(k as u8)).collect()
        }
    };
    let directions: Vec<(Vec3, Option<u8>)> = direction
        .rows()
        .into_iter()
        .zip(bands)
        .map(|(r, b)| (Vec3::new(r[0], r[1], r[2]), b))
        .collect();
    let loaded = &scene.loaded;
    let paths = interruptible(py, |stop| {
        let mut paths = Vec::new();
        light_path_types(
            &loaded.world,
            loaded.observer,
            &directions,
            |d| *d,
            &mut paths,
            stop,
        );
        (!stop.load(Ordering::Relaxed)).then_some(paths)
    })?;
    let out = PyDict::new(py);
    // The kinds of light path as small integers into a list of their names (sorted: direct
    // first, then by entry face and number of total reflections).
    let kinds: BTreeMap<LightPathType, usize> = paths.iter().map(|k| (*k, 0)).collect();
    let index: BTreeMap<LightPathType, usize> =
        kinds.keys().enumerate().map(|(i, k)| (*k, i)).collect();
    out.set_item(
        "path_index",
        column(py, paths.iter().map(|k| index[k] as i64).collect()),
    )?;
    out.set_item(
        "path_keys",
        index.keys().map(|k| k.key()).collect::<Vec<_>>(),
    )?;
    out.set_item(
        "path_words",
        index.keys().map(|k| k.to_string()).collect::<Vec<_>>(),
    )?;
    Ok(out)
}

/// The columns every model gives each point, flat (three numbers a row for vectors).
struct Columns {
    /// Where the model places each point (NaN where it places none); `None` for the course's
    /// convention, whose points are the image points.
    xyz: Option<Vec<f64>>,
    /// The course's image point `O + L·u0`.
    image_xyz: Vec<f64>,
    /// The colour code of the object reached.
    color: Vec<i64>,
    /// The ray's first direction `u0`.
    direction: Vec<f64>,
    /// The broken path's length `L`.
    path_length: Vec<f64>,
    /// The object's point reached.
    object_point: Vec<f64>,
    /// Refractions and total reflections on the way.
    events: Vec<i64>,
}

impl Columns {
    /// The columns of `images`, placed at `placed` by a model (or where they are).
    ///
    /// The points are taken from the last, each row written as its point is let go, and the
    /// list of points is shrunk as it empties: the columns' pages are only used once written
    /// (they start as untouched zero pages), so the points and their columns are never all held
    /// at once, and a point costs in all about what its columns do.
    fn of(placed: Option<&[Option<Vec3>]>, mut images: Vec<ImagePoint>) -> Columns {
        let n = images.len();
        let mut c = Columns {
            xyz: placed.map(|placed| {
                let mut xyz = Vec::with_capacity(3 * n);
                for p in placed {
                    xyz.extend_from_slice(&p.unwrap_or(Vec3::NAN).to_array());
                }
                xyz
            }),
            image_xyz: vec![0.0; 3 * n],
            color: vec![0; n],
            direction: vec![0.0; 3 * n],
            path_length: vec![0.0; n],
            object_point: vec![0.0; 3 * n],
            events: vec![0; n],
        };
        let put =
            |v: &mut [f64], k: usize, p: Vec3| v[3 * k..3 * k + 3].copy_from_slice(&p.to_array());
        // Shrunk every sixteenth of the way (a shrink gives the freed pages back).
        let step = (n / 16).max(1 << 16);
        while let Some(p) = images.pop() {
            let k = images.len();
            put(&mut c.image_xyz, k, p.position);
            c.color[k] = i64::from(p.color);
            put(&mut c.direction, k, p.direction);
            c.path_length[k] = p.path_length;
            put(&mut c.object_point, k, p.straw_point);
            c.events[k] = i64::from(p.events);
            if k % step == 0 {
                images.shrink_to_fit();
            }
        }
        c
    }
}

/// The columns an apparent-position model adds to each point.
enum ModelColumns {
    /// The course's convention adds none.
    Course,
    /// The eye model's foci (m; NaN where not defined) and their kinds, and the gap to the
    /// course's point.
    Eye {
        s_h: Vec<f64>,
        s_v: Vec<f64>,
        s_h_kind: Vec<&'static str>,
        s_v_kind: Vec<&'static str>,
        gap: Vec<f64>,
    },
    /// The stereo model's disparities (rad), the lines of sight's miss distance (m) and the gap
    /// to the course's point, and how many points one eye only sees.
    Stereo {
        disparity: Vec<f64>,
        vertical_disparity: Vec<f64>,
        miss_distance: Vec<f64>,
        gap: Vec<f64>,
        skipped: usize,
    },
}

/// A number, or NaN where it is not defined.
fn nan_if_none(v: Option<f64>) -> f64 {
    v.unwrap_or(f64::NAN)
}

/// The observer's picture of `scene` as `render` draws it: `(height, width, 3)` bytes, the PNG's
/// pixels; with `raw`, also one ray per pixel centre as `render --raw` writes it: the colour code
/// met (course mode) or the weight of each colour code (Fresnel mode).
#[pyfunction]
#[pyo3(signature = (scene, size, target, fov, mode, prune, backdrop, samples, raw, light, sampling))]
#[allow(clippy::too_many_arguments)]
fn render<'py>(
    py: Python<'py>,
    scene: &LoadedScene,
    size: Option<(u32, u32)>,
    target: Option<[f64; 3]>,
    fov: Option<f64>,
    mode: &str,
    prune: f64,
    backdrop: &str,
    samples: u32,
    raw: bool,
    light: &str,
    sampling: &str,
) -> PyResult<Bound<'py, PyDict>> {
    let asked = PictureSpec {
        prune,
        samples,
        ..PictureSpec::default()
    };
    let (with_mode, with_backdrop, with_light, with_sampling) = (
        asked.with_mode("mode", mode),
        asked.with_backdrop("backdrop", backdrop),
        asked.with_light("light", light),
        asked.with_sampling("sampling", sampling),
    );
    let broken: Vec<String> = [&with_mode, &with_backdrop, &with_light, &with_sampling]
        .iter()
        .filter_map(|r| r.as_ref().err().cloned())
        .collect();
    if !broken.is_empty() {
        return Err(PyValueError::new_err(broken.join("\n")));
    }
    let spec = PictureSpec {
        checker: with_backdrop.map_err(PyValueError::new_err)?.checker,
        white: with_light.map_err(PyValueError::new_err)?.white,
        adaptive: with_sampling.map_err(PyValueError::new_err)?.adaptive,
        ..with_mode.map_err(PyValueError::new_err)?
    };
    let loaded = &scene.loaded;
    let camera_spec = CameraSpec { target, fov, size };
    let camera = scene_camera(loaded, &camera_spec).map_err(python_error)?;
    let fresnel = spec.fresnel;
    let shading = checked_shading(&spec).map_err(python_error)?;
    let world = &loaded.world;
    let (image, codes, weights) = interruptible(py, |stop| {
        let image = picture_until(world, camera, shading, stop)?;
        let (codes, weights) = match (raw, fresnel) {
            (false, _) => (None, None),
            (true, false) => (Some(course_picture_exact(world, &camera)), None),
            (true, true) => (None, Some(fresnel_picture_exact(world, &camera, prune))),
        };
        Some((image, codes, weights))
    })?;
    let (w, h) = (image.width as usize, image.height as usize);
    let out = PyDict::new(py);
    out.set_item(
        "pixels",
        PyArray1::from_vec(py, image.pixels).reshape([h, w, 3])?,
    )?;
    if let Some(codes) = codes {
        out.set_item("codes", PyArray1::from_vec(py, codes).reshape([h, w])?)?;
    }
    if let Some(weights) = weights {
        // As many weights per pixel as `render --raw` writes.
        let k = raw_weight_count(world);
        let flat: Vec<f64> = weights
            .iter()
            .flat_map(|p| p[..k].iter().copied())
            .collect();
        out.set_item("weights", PyArray1::from_vec(py, flat).reshape([h, w, k])?)?;
    }
    out.set_item("fov_deg", 2.0 * camera.tan_half_fov.atan().to_degrees())?;
    // The camera, so that a pixel maps to the direction its ray leaves the eye in.
    out.set_item("eye", camera.eye.to_array())?;
    out.set_item("forward", camera.forward.to_array())?;
    out.set_item("right", camera.right.to_array())?;
    out.set_item("up", camera.up.to_array())?;
    out.set_item("tan_half_fov", camera.tan_half_fov)?;
    Ok(out)
}

/// The colour the figures show light of wavelength `nm` in: sRGB display values, 0 to 1.
#[pyfunction]
fn wavelength_rgb(nm: f64) -> [f64; 3] {
    bentstraw_optics::spectrum::wavelength_rgb(nm)
}

/// Writes to `path` the points file `bentstraw simulate --output PATH` writes for the same scene,
/// number of points, light and model (CSV, JSON or PLY by the name's extension), all or nothing: the
/// points are traced again (tracing is deterministic: they are the simulation's own) and written
/// by the command line's writers.
#[pyfunction]
fn save_points(
    py: Python<'_>,
    scene: &LoadedScene,
    points: usize,
    image_model: &str,
    light: &str,
    path: PathBuf,
) -> PyResult<()> {
    let white = white_light(light)?;
    check_points_asked(points, image_model).map_err(python_error)?;
    let format = PointFormat::from_path(&path).map_err(python_error)?;
    let setup = &scene.loaded;
    let (world, observer) = (&setup.world, setup.observer);
    let written = interruptible(py, |stop| {
        let cloud = sample_image_until(world, observer, points, white, &|_| {}, stop)?;
        let eye = (image_model == "eye").then(|| eye_model_points(world, observer, &cloud.points));
        let stereo =
            (image_model == "stereo").then(|| stereo_points(world, observer, &cloud.points));
        let model = match (&eye, &stereo) {
            (Some(eye), _) => ModelPoints::Eye(eye),
            (_, Some(stereo)) => ModelPoints::Stereo(stereo),
            _ => ModelPoints::Course,
        };
        let set = PointSet {
            scene: setup,
            min_points: points,
            model,
            cloud: &cloud,
        };
        Some(write_points(&path, format, &set))
    })?;
    written.map_err(python_error)
}

/// The unit direction of the ray through the centre of pixel `(row, col)` of a picture whose
/// camera `render` gave (`forward`, `right`, `up`, `tan_half_fov`, `size` as `(w, h)`): the
/// camera's own rule, so that the direction is the one the picture's pixel was traced along.
#[pyfunction]
#[allow(clippy::too_many_arguments)]
fn pixel_direction(
    forward: [f64; 3],
    right: [f64; 3],
    up: [f64; 3],
    tan_half_fov: f64,
    size: (u32, u32),
    row: f64,
    col: f64,
) -> [f64; 3] {
    let camera = Camera {
        eye: Vec3::ZERO,
        forward: Vec3::from_array(forward),
        right: Vec3::from_array(right),
        up: Vec3::from_array(up),
        width: size.0,
        height: size.1,
        tan_half_fov,
    };
    camera
        .direction_at(row + 0.5, col + 0.5)
        .normalize()
        .to_array()
}

/// Judges the points `xyz` (n × 3, m) of colour codes `color` (n) as `check --json` does a
/// solution file, seen from the scene's observer: the report as JSON text.
#[pyfunction]
fn check(
    py: Python<'_>,
    scene: &LoadedScene,
    xyz: PyReadonlyArray2<'_, f64>,
    color: PyReadonlyArray1<'_, f64>,
    tolerance: f64,
    min_coverage: f64,
    worst: usize,
) -> PyResult<String> {
    let options = CheckOptions {
        tolerance,
        min_coverage,
        worst,
    };
    let started = std::time::Instant::now();
    let (solution, report) = judged_points(py, scene, xyz, color, &options)?;
    let seconds = started.elapsed().as_secs_f64();
    let v = json_report(
        "(arrays)",
        &scene.loaded,
        &solution,
        &report,
        &options,
        seconds,
    );
    Ok(v.to_string())
}

/// The points `xyz` (n × 3, m) of colour codes `color` (n) as a solution, and their judgement
/// from the scene's observer with `options` (checked first; the interpreter's lock released
/// while it works).
fn judged_points(
    py: Python<'_>,
    scene: &LoadedScene,
    xyz: PyReadonlyArray2<'_, f64>,
    color: PyReadonlyArray1<'_, f64>,
    options: &CheckOptions,
) -> PyResult<(Solution, CheckReport)> {
    options.validate().map_err(python_error)?;
    let CheckOptions {
        tolerance,
        min_coverage,
        ..
    } = *options;
    let loaded = &scene.loaded;
    let xyz = xyz.as_array();
    if xyz.ncols() != 3 {
        return Err(PyValueError::new_err(format!(
            "xyz has {} columns: it must be an (n, 3) array of points x, y, z in metres",
            xyz.ncols()
        )));
    }
    let points: Vec<[f64; 3]> = xyz.rows().into_iter().map(|r| [r[0], r[1], r[2]]).collect();
    let colors: Vec<f64> = color.as_array().iter().copied().collect();
    let solution = solution_of_points(&points, &colors, loaded.colour_names().len())
        .map_err(PyValueError::new_err)?;
    let report = py.detach(|| {
        check_solution(
            &loaded.world,
            loaded.observer,
            &solution.points,
            tolerance,
            min_coverage,
        )
    });
    Ok((solution, report))
}

/// Grades the class `class_dir` (a folder or zip of students' folders) as `bentstraw grade` does,
/// on the assignment file's cases or the four reference simulations, writing its files into
/// `out` (in `lang`): the gradebook's rows as JSON text.
#[pyfunction]
#[pyo3(signature = (class_dir, out, assignment, lang))]
fn grade(
    py: Python<'_>,
    class_dir: PathBuf,
    out: PathBuf,
    assignment: Option<PathBuf>,
    lang: &str,
) -> PyResult<String> {
    let lang = Lang::from_code(lang).map_err(PyValueError::new_err)?;
    let cases = grading::assignment(assignment.as_deref()).map_err(python_error)?;
    let graded = py
        .detach(|| grading::grade_class(&class_dir, &cases, &out, lang, &|_, _| {}))
        .map_err(python_error)?;
    let rows: Vec<grading::CaseGrade> = graded.rows.into_iter().flatten().collect();
    Ok(grading::rows_json(&rows, lang).to_string())
}

/// Grades the points `xyz` (n × 3, m) of colour codes `color` (n) as one case worth
/// `max_score` is graded (the verdict `check` gives, and the same partial score): its row as
/// JSON text, the note and the missing parts in `lang`.
#[pyfunction]
#[allow(clippy::too_many_arguments)]
fn grade_points(
    py: Python<'_>,
    scene: &LoadedScene,
    xyz: PyReadonlyArray2<'_, f64>,
    color: PyReadonlyArray1<'_, f64>,
    tolerance: f64,
    min_coverage: f64,
    max_score: f64,
    lang: &str,
) -> PyResult<String> {
    let lang = Lang::from_code(lang).map_err(PyValueError::new_err)?;
    if !(max_score.is_finite() && max_score >= 0.0) {
        return Err(PyValueError::new_err(format!(
            "points {max_score} is not allowed: a case is worth a finite number >= 0 of points"
        )));
    }
    let options = CheckOptions {
        tolerance,
        min_coverage,
        worst: 0,
    };
    let (_, report) = judged_points(py, scene, xyz, color, &options)?;
    let row = grading::CaseGrade::judged("", "solution", (max_score, min_coverage), "xyz", &report);
    Ok(grading::rows_json(&[row], lang)[0].to_string())
}

/// The light path of one ray from the scene's observer, along `direction` or toward the point
/// `toward`, as the explorer shows a clicked ray: JSON text.
#[pyfunction]
#[pyo3(signature = (scene, direction, toward))]
fn trace(
    scene: &LoadedScene,
    direction: Option<[f64; 3]>,
    toward: Option<[f64; 3]>,
) -> PyResult<String> {
    let eye = scene.loaded.observer;
    let u = match (direction, toward) {
        (Some(d), None) => Vec3::from_array(d),
        (None, Some(p)) => Vec3::from_array(p) - eye,
        _ => {
            return Err(PyValueError::new_err(
                "give the ray's direction or a point toward which it goes (toward), not both",
            ))
        }
    };
    let what = if direction.is_some() {
        "direction"
    } else {
        "toward: the point"
    };
    if !u.is_finite() || u.length() == 0.0 || !u.length().is_finite() {
        let v = direction.or(toward).unwrap_or_default();
        return Err(PyValueError::new_err(format!(
            "{what} ({}, {}, {}) gives no direction: it must be finite and away from the eye",
            number_text(v[0]),
            number_text(v[1]),
            number_text(v[2])
        )));
    }
    // A direction already of unit length (to rounding), such as an image point's `u0`, is used
    // as given, so that its ray is traced exactly as it was.
    let u0 = if (u.length_squared() - 1.0).abs() <= 4.0 * f64::EPSILON {
        u
    } else {
        u.normalize()
    };
    let v = bentstraw_explore::ray_json(&scene.loaded.world, eye, u0);
    Ok(v.to_string())
}

/// The compiled part of the `bentstraw` package.
#[pymodule]
fn _engine(m: &Bound<'_, PyModule>) -> PyResult<()> {
    // numpy's C interface is fetched now, not at the first array a call returns: fetching it runs
    // Python code, where a Ctrl-C that came as the work ended would otherwise be a panic.
    numpy::PyArray1::<f64>::zeros(m.py(), 0, false);
    m.add_class::<LoadedScene>()?;
    m.add_function(wrap_pyfunction!(load, m)?)?;
    m.add_function(wrap_pyfunction!(read_scene, m)?)?;
    m.add_function(wrap_pyfunction!(check_scene, m)?)?;
    m.add_function(wrap_pyfunction!(gallery, m)?)?;
    m.add_function(wrap_pyfunction!(gallery_miss, m)?)?;
    m.add_function(wrap_pyfunction!(simulate, m)?)?;
    m.add_function(wrap_pyfunction!(light_paths, m)?)?;
    m.add_function(wrap_pyfunction!(save_points, m)?)?;
    m.add_function(wrap_pyfunction!(wavelength_rgb, m)?)?;
    m.add_function(wrap_pyfunction!(render, m)?)?;
    m.add_function(wrap_pyfunction!(pixel_direction, m)?)?;
    m.add_function(wrap_pyfunction!(check, m)?)?;
    m.add_function(wrap_pyfunction!(grade, m)?)?;
    m.add_function(wrap_pyfunction!(grade_points, m)?)?;
    m.add_function(wrap_pyfunction!(trace, m)?)?;
    m.add("VERSION", env!("CARGO_PKG_VERSION"))?;
    m.add("WATER_INDEX", bentstraw_optics::scene::WATER_INDEX)?;
    m.add(
        "DEFAULT_MAX_EVENTS",
        bentstraw_optics::scene::DEFAULT_MAX_EVENTS,
    )?;
    m.add(
        "DEFAULT_TOLERANCE",
        bentstraw_optics::check::DEFAULT_TOLERANCE,
    )?;
    m.add(
        "DEFAULT_MIN_COVERAGE",
        bentstraw_optics::check::DEFAULT_MIN_COVERAGE,
    )?;
    m.add("DEFAULT_POINTS", bentstraw_optics::view::DEFAULT_POINTS)?;
    m.add("DEFAULT_PRUNE", bentstraw_optics::view::DEFAULT_PRUNE)?;
    m.add("DEFAULT_SAMPLES", bentstraw_optics::view::DEFAULT_SAMPLES)?;
    m.add("DEFAULT_SIZE", bentstraw_optics::view::DEFAULT_SIZE)?;
    m.add("DEFAULT_MODE", PictureSpec::default().mode())?;
    m.add("DEFAULT_BACKDROP", PictureSpec::default().backdrop())?;
    m.add("COLOR_NAMES", COLOR_NAMES.to_vec())?;
    m.add("COLOR_RGB", COLOR_RGB.to_vec())?;
    Ok(())
}
