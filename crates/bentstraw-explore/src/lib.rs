//! `bentstraw-explore`: the live explorer's API, a request's address in, a response out.
//!
//! Every value is read and checked as the command line reads and checks it (the same parsers, the
//! same scene rules, the same camera rules), so the page shows the command line's messages. The
//! physics is the library's: this crate only turns numbers into bytes.

#![warn(missing_docs)]

use std::collections::HashMap;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};

use bentstraw_optics::apparent::{
    eye_model_points_until, stereo_point_each_until, stereo_points, stereo_points_until, Focus,
};
use bentstraw_optics::camera::Camera;
use bentstraw_optics::frame::{draw_frame, Frame, FrameRequest};
use bentstraw_optics::geometry::Ray;
use bentstraw_optics::image::ImagePoint;
use bentstraw_optics::light_path_type::LightPathType;
use bentstraw_optics::rule::{Param, Rule};
use bentstraw_optics::sampling::{sample_image_until, ImageCloud};
use bentstraw_optics::scene::{DEFAULT_MAX_EVENTS, WATER_INDEX};
use bentstraw_optics::scene_file::{
    Container, Lesson, LessonText, Observer, SceneForm, DEFAULT_COIN_RADIUS,
};
use bentstraw_optics::shading::{RgbPicture, ShadingOptions};
use bentstraw_optics::spectrum::{wavelength_rgb8, white_bands, WHITE_BANDS};
use bentstraw_optics::text::{clip_text, css_hex};
use bentstraw_optics::world::{Outcome, World, COLOR_NAMES};
use bentstraw_optics::Vec3;
use serde_json::{json, Value};

pub mod aim;
pub mod page;
pub mod sweep;

// The query's codec and the page's scene file's name, where the view as asked for is read.
pub use bentstraw_io::view_spec::{parse_query, query_value, PAGE_SCENE_FILE};

use bentstraw_io::camera::scene_camera;
use bentstraw_io::gallery::{opening_comment, GALLERY};
use bentstraw_io::pictures::checked_shading;
use bentstraw_io::pictures::png_bytes;
use bentstraw_io::scene_input::{gallery_setup, parse_scene_text};
use bentstraw_io::view_spec::{number, required, ImageModel, SceneFile, Verb, ViewSpec};
use bentstraw_io::writers::{write_csv, write_model_csv, write_ply, ModelPoints, PointSet};
use bentstraw_optics::scene::{GLASS_HEIGHT, GLASS_RADIUS, REFERENCES, STRAW_HEIGHT, STRAW_RADIUS};
use bentstraw_optics::setup::{Setup, MAX_SCENE_FILE_BYTES};
use bentstraw_optics::sketch::{object_outlines, world_wireframe};
use bentstraw_optics::text::{number_text, refuse_choice};
use bentstraw_optics::view::{
    PictureSpec, BACKDROPS, CLASSIC_OBSERVER, CLASSIC_STRAW, CLASSIC_WATER_HEIGHT, DEFAULT_POINTS,
    DEFAULT_SIZE, MAX_SAMPLES, MODES,
};

/// Most image points one request may ask for (a million take about half a second).
pub const MAX_POINTS: usize = 1_000_000;
/// Most pixels of a picture the explorer draws (4K); the command line allows more, but a page
/// never shows more than its screen.
pub const MAX_PICTURE_PIXELS: u64 = 3840 * 2160;
/// Most work one request may ask for, in ray-surface tests at worst ([`View::work`]): a 4K
/// picture with 16×16 samples of the classic glass and its 1000 events fits; a hundred straws under
/// 32 layers drawn so does not (it would hold a worker for minutes).
pub const MAX_WORK: f64 = 2e13;
/// Work beyond which a request is heavy ([`View::work`]): the explorer computes one heavy request
/// at a time, so that the page's frames (about a hundredth of this) never wait behind them.
pub const HEAVY_WORK: f64 = 1e10;
/// Longest request address accepted (bytes): room for a scene file of a few kilobytes, which
/// travels in the address (`scene-file`).
pub const MAX_URL: usize = 16 * 1024;

/// A finished answer to a request.
#[derive(Debug, Clone, PartialEq)]
pub struct Reply {
    /// HTTP status.
    pub status: u16,
    /// `Content-Type`.
    pub content_type: &'static str,
    /// The body.
    pub body: Vec<u8>,
    /// A file name for downloads (`Content-Disposition: attachment`).
    pub file_name: Option<String>,
    /// Whether a model's answer started from the last frame's course points instead of tracing
    /// them again (sent as `X-Points: reused`, so that the page and its tests can tell).
    pub reused_points: bool,
}

impl Reply {
    /// A plain-text reply (errors: one line naming the value and the rule).
    pub fn text(status: u16, message: impl Into<String>) -> Reply {
        Reply {
            status,
            content_type: "text/plain; charset=utf-8",
            body: message.into().into_bytes(),
            file_name: None,
            reused_points: false,
        }
    }

    fn json(value: &Value) -> Reply {
        Reply {
            status: 200,
            content_type: "application/json",
            body: value.to_string().into_bytes(),
            file_name: None,
            reused_points: false,
        }
    }

    /// A success: `body`, of `content_type`.
    pub fn bytes(content_type: &'static str, body: Vec<u8>) -> Reply {
        Reply {
            status: 200,
            content_type,
            body,
            file_name: None,
            reused_points: false,
        }
    }
}

/// A refusal of a request: the command line's message, and, when a rule of scenes is broken,
/// every broken rule as data (its code, key, value and parameters) for the page to say in its
/// own language.
#[derive(Debug, Clone, PartialEq)]
pub struct Refused {
    /// The command line's message (English).
    pub message: String,
    /// The broken rules as JSON (`{file, flagged, rules: [{code, key, value, line, params}]}`),
    /// when they are scene rules.
    pub rules: Option<Value>,
}

impl From<String> for Refused {
    fn from(message: String) -> Refused {
        Refused {
            message,
            rules: None,
        }
    }
}

impl From<&str> for Refused {
    fn from(message: &str) -> Refused {
        Refused::from(message.to_string())
    }
}

/// One broken rule as the page reads it.
fn rule_json(
    rule: Rule,
    key: &str,
    value: Option<&str>,
    line: Option<usize>,
    params: &[(&'static str, Param)],
) -> Value {
    let params: serde_json::Map<String, Value> = params
        .iter()
        .map(|(name, p)| {
            let v = match p {
                Param::Number(t) => json!(t),
                Param::Text(t) => json!({ "text": t }),
            };
            (name.to_string(), v)
        })
        .collect();
    json!({"code": rule.code(), "key": key, "value": value, "line": line, "params": params})
}

impl From<bentstraw_io::error::Error> for Refused {
    fn from(e: bentstraw_io::error::Error) -> Refused {
        use bentstraw_io::error::Error;
        let rules = match &e {
            Error::SceneFile {
                name,
                flagged,
                error,
            } => {
                let rules: Vec<Value> = error
                    .rules()
                    .map(|r| rule_json(r.rule, &r.key, r.value.as_deref(), r.line, &r.params))
                    .collect();
                Some(json!({"file": name, "flagged": flagged, "rules": rules}))
            }
            Error::Scene(error) => {
                let (rule, params) = error.rule();
                Some(
                    json!({"file": null, "flagged": false, "rules": [rule_json(rule, "", None, None, &params)]}),
                )
            }
            _ => None,
        };
        Refused {
            message: e.to_string(),
            rules,
        }
    }
}

impl Refused {
    /// The answer refusing the request (400): the message as text, or, with the broken rules,
    /// JSON holding both.
    pub fn reply(self) -> Reply {
        match self.rules {
            None => Reply::text(400, self.message),
            Some(mut rules) => {
                rules["message"] = json!(self.message);
                Reply {
                    status: 400,
                    ..Reply::json(&rules)
                }
            }
        }
    }
}

/// Everything that defines a view, checked: the view as asked for, and its scene and camera.
#[derive(Debug, Clone)]
pub struct View {
    /// The view as asked for (names and values as the command line's flags).
    pub spec: ViewSpec,
    /// The scene (validated): the assignment's glass, a gallery scene or the page's scene file.
    pub scene: Arc<Setup>,
    /// The observer (validated).
    pub observer: Vec3,
    /// The camera (validated).
    pub camera: Camera,
}

/// `GET /api/sketch?scene=NAME` (or `scene-file=TEXT`): what the page draws of a scene besides
/// its points, asked once per scene (not with every frame): the container's and liquids'
/// wireframe as `[x, y, z, x, y, z]` segments, the objects' outlines as flat polylines, the box
/// holding them, and the file's own observer.
pub fn sketch_reply(q: &HashMap<String, String>) -> Result<Reply, Refused> {
    let Some(SceneFile { name, text }) = SceneFile::from_query(q)? else {
        return Err("missing required parameter 'scene'".into());
    };
    let description = parse_scene_text(&name, &text)?;
    let world = World::new(&description, DEFAULT_MAX_EVENTS).map_err(|error| {
        bentstraw_io::error::Error::SceneFile {
            name: name.clone(),
            flagged: false,
            error,
        }
    })?;
    let w = &world;
    let flat = |p: &[Vec3]| -> Vec<f64> { p.iter().flat_map(|q| q.to_array()).collect() };
    let wireframe: Vec<f64> = world_wireframe(w).iter().flat_map(|s| flat(s)).collect();
    let outlines: Vec<Vec<f64>> = object_outlines(w).iter().map(|l| flat(l)).collect();
    let (lo, hi) = w.bounds();
    Ok(Reply::json(&json!({
        "wireframe": wireframe,
        "outlines": outlines,
        "bounds": [lo.x, lo.y, lo.z, hi.x, hi.y, hi.z],
        "observer": description.observer.map_or(Value::Null, |o| vec_json(o.position)),
        // The layers, bottom first, so that the page shows the scene's own liquid values.
        "liquids": description.liquids.iter().map(|l| json!({
            "name": l.name, "index": l.index, "top": l.top,
            "tint": l.tint.map(|[r, g, b]| format!("#{r:02x}{g:02x}{b:02x}")),
        })).collect::<Vec<_>>(),
        // The room the liquids fill, so that the maps can tint each layer.
        "container": container_json(&description.container),
        // Every key of the file with its value (defaults written out), for the page's controls.
        "form": serde_json::to_value(description.form()).expect("a scene form is plain data"),
        "lesson": lesson_json(description.lesson.as_ref()),
    })))
}

/// A scene's lesson for the page, in each language it is written in (`{"en": {title, text,
/// questions}, "fr": …}`), or null.
pub fn lesson_json(lesson: Option<&Lesson>) -> Value {
    let Some(l) = lesson else { return Value::Null };
    let text = |t: &Option<LessonText>| {
        t.as_ref().map_or(
            Value::Null,
            |t| json!({"title": t.title, "text": t.text, "questions": t.questions}),
        )
    };
    json!({"en": text(&l.en), "fr": text(&l.fr)})
}

/// `GET /api/scene-text?form=JSON`: a scene file's text from its keys and values (the `form` of
/// a sketch, edited by the page's controls). No rule is checked here: the text is then read as any
/// scene file is, so that a control and the text box are refused by the same rules, key by key.
pub fn scene_text_reply(q: &HashMap<String, String>) -> Result<Reply, String> {
    let form = required(q, "form")?;
    if form.len() as u64 > MAX_SCENE_FILE_BYTES {
        return Err(format!(
            "the scene's form is {} bytes: a scene file is at most {MAX_SCENE_FILE_BYTES} bytes (1 MB)",
            form.len()
        ));
    }
    let form: SceneForm = serde_json::from_str(form)
        .map_err(|e| format!("the scene's form is not a scene file's keys and values: {e}"))?;
    let mut r = Reply::bytes("application/toml", form.to_toml().into_bytes());
    r.file_name = Some(PAGE_SCENE_FILE.into());
    Ok(r)
}

/// The inside of a scene's container, which its liquids fill: a glass's inner radius, a tank's
/// half widths (both centred on the z axis) or a glass of revolution's profiles, and the
/// floor's height.
fn container_json(container: &Container) -> Value {
    match container {
        Container::Glass(g) => json!({
            "shape": "glass",
            "radius": g.radius - g.wall,
            "floor": container.floor(),
        }),
        Container::Tank(t) => json!({
            "shape": "tank",
            "half_x": t.half_x,
            "half_y": t.half_y,
            "floor": container.floor(),
        }),
        // The page draws it by its profiles; liquids fill the inner one.
        Container::Revolution(v) => json!({
            "shape": "revolution",
            "outer": v.outer,
            "inner": v.inner,
            "radius": v.reach(),
            "floor": container.floor(),
        }),
    }
}

/// The most characters a link's QR code holds (version 40, low error correction, bytes): a
/// longer link is refused, with what fits.
pub const QR_MAX_LINK: usize = 2953;

/// `GET /api/qr?text=LINK`: the link as a QR code, an SVG picture (black on white, its quiet zone
/// round it), for a class to scan from a projector.
pub fn qr_reply(q: &HashMap<String, String>) -> Result<Reply, String> {
    let text = required(q, "text")?;
    let n = text.chars().count();
    let code = (n <= QR_MAX_LINK)
        .then(|| qrcode::QrCode::with_error_correction_level(text.as_bytes(), qrcode::EcLevel::L).ok())
        .flatten()
        .ok_or_else(|| {
            format!(
                "the link is {n} characters: a QR code holds at most {QR_MAX_LINK}; a gallery scene's link fits, or save the scene file and share it"
            )
        })?;
    let svg = code
        .render::<qrcode::render::svg::Color>()
        .min_dimensions(256, 256)
        .build();
    Ok(Reply::bytes("image/svg+xml", svg.into_bytes()))
}

/// `GET /api/scenes`: the gallery's scenes: name, what it shows, its own observer.
pub fn scenes_reply() -> Reply {
    let list: Vec<Value> = GALLERY
        .iter()
        .filter_map(|(stem, text)| {
            let w = gallery_setup(stem, text, DEFAULT_MAX_EVENTS).ok()?;
            Some(json!({
                "name": stem,
                "title": stem.replace('-', " "),
                "shows": opening_comment(text),
                "observer": vec_json(w.observer),
                "lesson": lesson_json(w.description.lesson.as_ref()),
            }))
        })
        .collect();
    Reply::json(&Value::Array(list))
}

/// `GET /api/defaults`: the view's defaults as the engine holds them, so that a page states none
/// of its own: the image points, the picture (mode, backdrop, samples, pruning weight, size), the
/// scene's (event limit, water's index), the classic first view, the four reference views, the
/// assignment's glass and straw, and a coin's radius.
pub fn defaults_reply() -> Reply {
    let picture = PictureSpec::default();
    let references: Vec<Value> = REFERENCES
        .iter()
        .map(|r| {
            json!({
                "number": r.number,
                "observer": vec_json(r.observer),
                "straw": [r.straw.0, r.straw.1],
                "waterHeight": r.water_height,
            })
        })
        .collect();
    Reply::json(&json!({
        "points": DEFAULT_POINTS,
        "maxPoints": MAX_POINTS,
        "mode": picture.mode(),
        "modes": MODES,
        "backdrop": picture.backdrop(),
        "backdrops": BACKDROPS,
        "light": picture.light(),
        "lights": bentstraw_optics::view::LIGHTS,
        "samples": picture.samples,
        "maxSamples": MAX_SAMPLES,
        "prune": picture.prune,
        "size": DEFAULT_SIZE,
        "maxEvents": DEFAULT_MAX_EVENTS,
        "nWater": WATER_INDEX,
        "wavelength": {
            "d": bentstraw_optics::dispersion::D_LINE_NM,
            "min": bentstraw_optics::dispersion::VISIBLE_MIN_NM,
            "max": bentstraw_optics::dispersion::VISIBLE_MAX_NM,
        },
        "classic": {
            "observer": CLASSIC_OBSERVER,
            "straw": CLASSIC_STRAW,
            "waterHeight": CLASSIC_WATER_HEIGHT,
        },
        "references": references,
        "glass": {"radius": GLASS_RADIUS, "height": GLASS_HEIGHT},
        "straw": {"radius": STRAW_RADIUS, "height": STRAW_HEIGHT},
        "coin": {"radius": DEFAULT_COIN_RADIUS},
        // What the assignment's glass teaches, as a gallery scene's lesson.
        "lesson": lesson_json(
            parse_scene_text(bentstraw_io::gallery::SPEC.0, bentstraw_io::gallery::SPEC.1)
                .ok()
                .and_then(|d| d.lesson)
                .as_ref()
        ),
    }))
}

fn get<'a>(q: &'a HashMap<String, String>, name: &str) -> Option<&'a str> {
    q.get(name).map(String::as_str)
}

impl View {
    /// The view described by the query `q` (names as the command line's flags), or the command
    /// line's message for the first value that breaks a rule.
    pub fn from_query(q: &HashMap<String, String>) -> Result<View, String> {
        View::checked(q).map_err(|r| r.message)
    }

    /// [`View::from_query`], its refusal with the broken rules as data: the query read
    /// ([`ViewSpec::from_query`]), then its scene loaded, its camera aimed and its picture checked
    /// as the command line does, within the explorer's own limits.
    pub fn checked(q: &HashMap<String, String>) -> Result<View, Refused> {
        let spec = ViewSpec::from_query(q)?;
        // As `--scene FILE --observer X,Y,Z` reads it: the file's rules, the eye moved.
        let scene = spec.load()?;
        let observer = scene.observer;
        if let Some((w, h)) = spec.camera.size {
            if w as u64 * h as u64 > MAX_PICTURE_PIXELS {
                return Err(format!(
                    "--size {w}x{h} is too large for the explorer: at most {MAX_PICTURE_PIXELS} pixels (3840x2160)"
                )
                .into());
            }
        }
        let camera = scene_camera(&scene, &spec.camera).map_err(|e| e.to_string())?;
        checked_shading(&spec.picture).map_err(|e| e.to_string())?;
        if spec.points > MAX_POINTS {
            return Err(format!(
                "--points {} is too many for the explorer: at most {MAX_POINTS}",
                spec.points
            )
            .into());
        }
        let view = View {
            spec,
            scene: Arc::new(scene),
            observer,
            camera,
        };
        let work = view.work();
        if work > MAX_WORK {
            let (w, h) = (view.camera.width, view.camera.height);
            return Err(format!(
                "this view asks too much work of the explorer: {w}x{h} pixels with {s}x{s} samples and \
                 {p} points, through {n} surfaces with up to {e} events each, is {work:.1e} \
                 ray-surface tests at worst, and the explorer does at most {MAX_WORK:.0e}: ask for \
                 fewer pixels, samples, points or events (the command line has no such limit)",
                s = view.spec.picture.samples,
                p = view.spec.points,
                n = view.surfaces(),
                e = view.scene.world.max_events(),
            )
            .into());
        }
        Ok(view)
    }

    /// The surfaces a ray of this view may meet: the boundaries between media and the objects.
    fn surfaces(&self) -> usize {
        let world = &self.scene.world;
        (world.boundaries().len() + world.objects().len()).max(1)
    }

    /// The most work any answer for this view may take, in ray-surface tests: every ray of the
    /// picture (`samples²` per pixel) and of the points (16 per point asked, for the sampling's
    /// coarse levels and the models), times the events each may make, times the surfaces each
    /// event tests; twice that in Fresnel mode, whose rays branch. The explorer refuses a view
    /// beyond [`MAX_WORK`] and computes one beyond [`HEAVY_WORK`] at a time.
    pub fn work(&self) -> f64 {
        let pixels = self.camera.width as f64 * self.camera.height as f64;
        let samples = self.spec.picture.samples.max(1) as f64;
        let rays = pixels * samples * samples + 16.0 * self.spec.points as f64;
        let branches = if self.spec.picture.fresnel { 2.0 } else { 1.0 };
        rays * self.scene.world.max_events().max(1) as f64 * self.surfaces() as f64 * branches
    }

    /// At least `points` image points of the view's scene, as `simulate` traces them; none if
    /// `stop` is set meanwhile.
    fn sample(&self, points: usize, stop: &AtomicBool) -> Option<ImageCloud> {
        let white = self.spec.picture.white;
        sample_image_until(
            &self.scene.world,
            self.observer,
            points,
            white,
            &|_| {},
            stop,
        )
    }

    fn shading(&self) -> ShadingOptions {
        self.spec.picture.shading()
    }

    /// The arguments of the `bentstraw simulate` command that writes this view's points (or
    /// `model`'s) into `view.csv`.
    pub fn simulate_args(&self, model: ImageModel) -> Vec<String> {
        let mut s = self.spec.args(Verb::Simulate(model));
        s.extend(["--output".into(), "view.csv".into()]);
        s
    }

    /// The `bentstraw simulate` command line that writes this view's points.
    pub fn simulate_command(&self, model: ImageModel) -> String {
        format!("bentstraw {}", self.simulate_args(model).join(" "))
    }

    /// What names this view's points: its `simulate` command, and its scene file's text (two
    /// files of the page are both called [`PAGE_SCENE_FILE`]).
    fn points_key(&self) -> String {
        let file = self.spec.scene.as_ref().map_or("", |f| f.text.as_str());
        format!("{}\n{file}", self.simulate_command(ImageModel::Course))
    }

    /// The `bentstraw render` command line that draws this view's picture.
    pub fn render_command(&self) -> String {
        let args = self.spec.args(Verb::Render).join(" ");
        format!("bentstraw {args} --output view.png")
    }
}

/// The colour's name of section `code`.
fn color_name(code: u8) -> &'static str {
    COLOR_NAMES[code as usize - 1]
}

/// `GET /api/frame`: the picture (RGBA) and the points (f32 xyz, colour codes, path kinds) in one
/// binary answer: `u32` length of a JSON header, the header (padded with spaces to 4 bytes), then
/// `width × height × 4` bytes, `3n` little-endian `f32`, `n` colour bytes, `n` path-kind bytes
/// (indices into the header's `paths`), and in white light `n` band bytes (indices into the
/// header's `bands`).
pub fn frame_reply(view: &View, frame: &mut Frame, memory: &Memory) -> Reply {
    let request = FrameRequest {
        camera: view.camera,
        shading: view.shading(),
        min_points: view.spec.points,
    };
    // WebAssembly in a page has no clock here: the worker times its own calls.
    #[cfg(not(target_arch = "wasm32"))]
    let started = std::time::Instant::now();
    // The colour codes a scene can show: the straw's five, or all eight in a scene file.
    let codes = view.scene.colour_names().len();
    draw_frame(&view.scene.world, &request, frame);
    // Abandoned half-way: its points are not this view's, and are not remembered as such.
    if frame.stop_flag().load(Ordering::Relaxed) {
        return stopped();
    }
    #[cfg(not(target_arch = "wasm32"))]
    let ms = started.elapsed().as_secs_f64() * 1e3;
    #[cfg(target_arch = "wasm32")]
    let ms = 0.0;
    *memory.points.lock().unwrap_or_else(|e| e.into_inner()) =
        Some((view.points_key(), Arc::new(frame.points.clone())));
    let counts = frame.path_counts();
    let kinds: Vec<LightPathType> = counts.iter().map(|c| c.0).collect();
    let mut per_color = vec![0usize; codes];
    let mut per_band = [0usize; WHITE_BANDS];
    for p in &frame.points {
        per_color[p.color as usize - 1] += 1;
        if let Some(k) = p.band {
            per_band[k as usize] += 1;
        }
    }
    let white = view.spec.picture.white;
    let header = json!({
        "width": view.camera.width,
        "height": view.camera.height,
        "n": frame.points.len(),
        "rays_traced": frame.rays_traced,
        "points_per_color": per_color,
        "paths": counts.iter().map(|(k, n)| json!({"key": k.key(), "words": k.to_string(), "count": n, "rgb": k.hex()})).collect::<Vec<_>>(),
        "fov_deg": 2.0 * libm::atan(view.camera.tan_half_fov).to_degrees(),
        // The picture's pinhole camera, so that the page draws 3D points (a clicked ray) where
        // the picture shows them.
        "camera": {
            "eye": vec_json(view.camera.eye),
            "forward": vec_json(view.camera.forward),
            "right": vec_json(view.camera.right),
            "up": vec_json(view.camera.up),
            "tan_half_fov": view.camera.tan_half_fov,
        },
        "ms": ms,
        "simulate": view.simulate_command(ImageModel::Course),
        "simulate_args": view.simulate_args(ImageModel::Course),
        // Sizes that read like centimetres written as metres (the command line's hints).
        "hints": view.scene.description.size_hints().iter().map(|(key, v)| json!({
            "key": key,
            "value": number_text(*v),
            "metres": number_text(*v / 100.0),
        })).collect::<Vec<_>>(),
        "render": view.render_command(),
        // White light: the bands the points' rays carried, violet first, each in its colour.
        "bands": white.then(|| white_bands().iter().zip(per_band).map(|(b, n)| json!({
            "nm": b.nm,
            "rgb": css_hex(wavelength_rgb8(b.nm)),
            "count": n,
        })).collect::<Vec<_>>()),
    });
    let kind_of = frame
        .paths
        .iter()
        .map(|k| kinds.binary_search(k).unwrap_or(0) as u8);
    frame_body(&header, &frame.picture, &frame.points, kind_of, white)
}

/// A frame's binary answer: the header, the picture as RGBA, the points, their path kinds, and
/// their bands if the light is `white`.
fn frame_body(
    header: &Value,
    picture: &RgbPicture,
    points: &[ImagePoint],
    kinds: impl Iterator<Item = u8>,
    white: bool,
) -> Reply {
    let mut head = header.to_string().into_bytes();
    while head.len() & 3 != 0 {
        head.push(b' ');
    }
    let n = points.len();
    let pixels = picture.pixels.len() / 3;
    let mut body = Vec::with_capacity(4 + head.len() + 4 * pixels + 14 * n);
    body.extend_from_slice(&(head.len() as u32).to_le_bytes());
    body.extend_from_slice(&head);
    for rgb in picture.pixels.chunks_exact(3) {
        body.extend_from_slice(&[rgb[0], rgb[1], rgb[2], 255]);
    }
    for p in points {
        for v in p.position.to_array() {
            body.extend_from_slice(&(v as f32).to_le_bytes());
        }
    }
    body.extend(points.iter().map(|p| p.color));
    body.extend(kinds);
    if white {
        body.extend(points.iter().map(|p| p.band.unwrap_or(0)));
    }
    Reply::bytes("application/octet-stream", body)
}

/// What the explorer remembers between requests: the course points of the last frame drawn (a
/// model asked for the view just drawn starts from them instead of tracing them again) and the
/// models' last answers (a whole answer reuses a quick one's points). One value per engine, passed
/// to each request: the server's workers share one, each of the page's workers keeps its own.
#[derive(Debug, Default)]
pub struct Memory {
    /// The last frame's course points, with the `simulate` command that gives them.
    points: Mutex<Option<(String, Arc<Vec<ImagePoint>>)>>,
    /// The models' last answers.
    models: Mutex<Vec<ModelAnswer>>,
    /// How many model requests started from a frame's points.
    reused: AtomicUsize,
}

impl Memory {
    /// How many model requests started from a frame's points instead of tracing them again.
    pub fn points_reused(&self) -> usize {
        self.reused.load(Ordering::Relaxed)
    }
}

/// Most points skipped between two a model places (`every`).
pub const MAX_EVERY: usize = 64;

/// The course image points of `view`: the last frame's when it was this view's (then `true`).
fn course_points(
    view: &View,
    memory: &Memory,
    stop: &AtomicBool,
) -> Option<(Arc<Vec<ImagePoint>>, bool)> {
    let key = view.points_key();
    let last = memory.points.lock().unwrap_or_else(|e| e.into_inner());
    if let Some((k, points)) = last.as_ref() {
        if *k == key {
            memory.reused.fetch_add(1, Ordering::Relaxed);
            return Some((Arc::clone(points), true));
        }
    }
    drop(last);
    let cloud = view.sample(view.spec.points.max(1), stop)?;
    Some((Arc::new(cloud.points), false))
}

/// A model's answers for the last few views asked: the view and model, the step `every`, and
/// where the model places each of those course points. The page asks for every 4th point first,
/// then for all: the second answer does not place the first one's points again.
type ModelAnswer = (String, usize, Arc<Vec<Option<(Vec3, u8)>>>);

/// The answer to a request abandoned half-way (its stop flag set): what was computed is not
/// what was asked for.
fn stopped() -> Reply {
    Reply::text(409, "stale: this request was abandoned")
}

/// Where `model` places each of `points` (`None`: not placed), or the refusal of an unknown model
/// (or of one abandoned because `stop` was set).
fn place(
    view: &View,
    model: &str,
    points: &[ImagePoint],
    stop: &AtomicBool,
) -> Result<Vec<Option<(Vec3, u8)>>, Reply> {
    let (world, eye) = (&view.scene.world, view.observer);
    match model {
        "eye" => Ok(eye_model_points_until(world, eye, points, stop)
            .ok_or_else(stopped)?
            .iter()
            .map(|p| Some((p.position?, p.image.color)))
            .collect()),
        "stereo" => Ok(stereo_point_each_until(world, eye, points, stop)
            .ok_or_else(stopped)?
            .iter()
            .map(|p| {
                let p = p.as_ref()?;
                Some((p.position?, p.image.color))
            })
            .collect()),
        other => Err(Reply::text(
            400,
            refuse_choice("--image-model", other, &["eye", "stereo"]),
        )),
    }
}

/// `GET /api/model?model=eye|stereo[&every=K]`: the model's points as `u32` count, `3n` `f32`, `n`
/// colours (the points the model places; the others are left out). With `every=K`, only every
/// K-th course point is placed: a quick first answer the page refines. Setting `stop` abandons it
/// (a 409 answer). The answer says whether it started from the last frame's points
/// ([`Reply::reused_points`]).
pub fn model_reply(
    view: &View,
    model: &str,
    every: usize,
    stop: &AtomicBool,
    memory: &Memory,
) -> Reply {
    let Some((all, reused_points)) = course_points(view, memory, stop) else {
        return stopped();
    };
    let every = every.max(1);
    let key = format!("{} {model}", view.points_key());
    // A coarser answer for this view, if one was given: its points are taken from it.
    let coarser = memory
        .models
        .lock()
        .unwrap_or_else(|e| e.into_inner())
        .iter()
        .find(|(k, step, _)| *k == key && *step > every && step.is_multiple_of(every))
        .map(|(_, step, placed)| (*step, Arc::clone(placed)));
    let known = |i: usize| {
        coarser
            .as_ref()
            .is_some_and(|(step, _)| i.is_multiple_of(*step))
    };
    let wanted: Vec<usize> = (0..all.len()).step_by(every).collect();
    let todo: Vec<ImagePoint> = wanted
        .iter()
        .filter(|&&i| !known(i))
        .map(|&i| all[i])
        .collect();
    let mut fresh = match place(view, model, &todo, stop) {
        Ok(p) => p.into_iter(),
        Err(refusal) => return refusal,
    };
    let placed_each: Vec<Option<(Vec3, u8)>> = wanted
        .iter()
        .map(|&i| match &coarser {
            Some((step, earlier)) if known(i) => earlier[i / step],
            _ => fresh.next().flatten(),
        })
        .collect();
    let placed_each = Arc::new(placed_each);
    {
        let mut last = memory.models.lock().unwrap_or_else(|e| e.into_inner());
        last.retain(|(k, step, _)| !(*k == key && *step == every));
        last.push((key, every, Arc::clone(&placed_each)));
        // Two models, each a coarse and a whole answer.
        if last.len() > 4 {
            last.remove(0);
        }
    }
    let placed: Vec<(Vec3, u8)> = placed_each.iter().flatten().copied().collect();
    let mut body = Vec::with_capacity(4 + 13 * placed.len());
    body.extend_from_slice(&(placed.len() as u32).to_le_bytes());
    for (q, _) in &placed {
        for v in q.to_array() {
            body.extend_from_slice(&(v as f32).to_le_bytes());
        }
    }
    body.extend(placed.iter().map(|p| p.1));
    Reply {
        reused_points,
        ..Reply::bytes("application/octet-stream", body)
    }
}

fn vec_json(v: Vec3) -> Value {
    json!([v.x, v.y, v.z])
}

fn focus_json(f: &Focus) -> Value {
    json!({"kind": f.kind(), "distance": f.signed_distance()})
}

/// `GET /api/ray?row=R&col=C` (a point of the picture, in its pixels) or `?point=K` (the K-th
/// image point, as `simulate` numbers them): the ray's broken path, its events, and the course's,
/// eye model's and stereo model's points.
pub fn ray_reply(
    view: &View,
    q: &HashMap<String, String>,
    stop: &AtomicBool,
) -> Result<Reply, String> {
    let u0 = if let Some(k) = get(q, "point") {
        let k: usize = number(k, "point")?;
        let Some(cloud) = view.sample(view.spec.points.max(1), stop) else {
            return Ok(stopped());
        };
        let Some(p) = cloud.points.get(k) else {
            return Err(format!(
                "point {k} does not exist: the view has {} image points",
                cloud.points.len()
            ));
        };
        p.direction
    } else {
        pixel_direction(view, q)?.2
    };
    // JSON has no NaN: a direction that is not a number is refused, never written as null.
    if !(u0.x.is_finite() && u0.y.is_finite() && u0.z.is_finite()) {
        return Err("this ray has no direction: the view's camera is degenerate".into());
    }
    Ok(Reply::json(&ray_json(&view.scene.world, view.observer, u0)))
}

/// The query's pixel `row`, `col` (within the picture) and the unit direction of its ray from
/// the eye.
pub(crate) fn pixel_direction(
    view: &View,
    q: &HashMap<String, String>,
) -> Result<(f64, f64, Vec3), String> {
    let row: f64 = number(required(q, "row")?, "row")?;
    let col: f64 = number(required(q, "col")?, "col")?;
    let (w, h) = (view.camera.width as f64, view.camera.height as f64);
    if !(0.0..=h).contains(&row) || !(0.0..=w).contains(&col) {
        return Err(format!(
            "pixel ({}, {}) is outside the {}x{} picture",
            clip_text(&row.to_string(), 24),
            clip_text(&col.to_string(), 24),
            view.camera.width,
            view.camera.height
        ));
    }
    Ok((row, col, view.camera.direction_at(row, col).normalize()))
}

/// The light path of the ray from `eye` along unit `u0` through `world`, as the page shows it
/// (and the Python package's `trace` returns): each event with its face, angle and indices, the
/// kind of path, and where it ends: the object's point, the path length and the image point of
/// each model, or where it leaves.
pub fn ray_json(world: &World, eye: Vec3, u0: Vec3) -> Value {
    let mut events = Vec::new();
    let mut kind = LightPathType::DIRECT;
    let mut last = (eye, u0);
    let ray = Ray {
        origin: eye,
        direction: u0,
    };
    let outcome = world.trace_with(ray, |e| {
        kind.record_entry(world.entry_of(e), e.totally_reflected);
        let cos = e.incoming.dot(e.normal).abs().min(1.0);
        // The angle the outgoing ray makes with the normal: the refraction angle (Snell), or
        // the reflection angle, equal to the incidence, when totally reflected.
        let cos_out = e.outgoing.dot(e.normal).abs().min(1.0);
        events.push(json!({
            "point": vec_json(e.point),
            "face": world.face_name(e.boundary),
            "event": if e.totally_reflected { "total reflection" } else { "refraction" },
            "incidence_deg": libm::acos(cos).to_degrees(),
            "outgoing_deg": libm::acos(cos_out).to_degrees(),
            "n1": e.n1,
            "n2": e.n2,
            // The geometry of the event, for drawing it: the ray's direction before and after
            // (from the eye), and the surface's unit normal on the side the ray comes from.
            "incoming": vec_json(e.incoming),
            "outgoing": vec_json(e.outgoing),
            "normal": vec_json(if e.incoming.dot(e.normal) > 0.0 { -e.normal } else { e.normal }),
        }));
        last = (e.point, e.outgoing);
    });
    let mut out = json!({
        "observer": vec_json(eye),
        "direction": vec_json(u0),
        "events": events,
        "path": kind.to_string(),
        "path_key": kind.key(),
    });
    match outcome.image_point(eye, u0) {
        Some(image) => reached_json(&mut out, world, eye, &image),
        None => {
            let ends = if outcome == Outcome::Dropped {
                "dropped"
            } else {
                "escaped"
            };
            out["outcome"] = json!(ends);
            out["leaves"] = json!({"from": vec_json(last.0), "direction": vec_json(last.1)});
        }
    }
    out
}

/// The fields of a ray that reached an object: its colour, the object's point, the path length,
/// the image point, and where the eye and stereo models put it.
fn reached_json(out: &mut Value, world: &World, eye: Vec3, image: &ImagePoint) {
    let apparent = world.apparent_point(eye, image);
    let stereo = stereo_points(world, eye, &[*image]);
    out["outcome"] = json!("straw");
    out["color"] = json!(image.color);
    out["color_name"] = json!(color_name(image.color));
    out["straw_point"] = vec_json(image.straw_point);
    out["path_length"] = json!(image.path_length);
    out["image_point"] = vec_json(image.position);
    out["s_h"] = focus_json(&apparent.s_h);
    out["s_v"] = focus_json(&apparent.s_v);
    out["eye_point"] = apparent.position.map_or(Value::Null, vec_json);
    out["gap_eye"] = json!(apparent.gap_to_course());
    let sp = stereo.points.first();
    out["stereo_point"] = sp.and_then(|p| p.position).map_or(Value::Null, vec_json);
    out["gap_stereo"] = json!(sp.and_then(|p| p.gap_to_course()));
}

/// `GET /api/aim`: where the scene's target (its first straw's bottom end, else a coin's centre,
/// else an arrow's tip) appears in the view's picture, for the page's "Predict, then look": the
/// target, and each image's pixel and ray ([`aim::aim_json`]); no image when the eye does not
/// see it there.
pub fn aim_reply(view: &View) -> Reply {
    let world = &view.scene.world;
    let target = aim::scene_target(world, view.observer);
    Reply::json(&aim::aim_json(world, &view.camera, target))
}

/// `GET /api/export?format=csv|ply|png` (`&model=eye|stereo` for the points): the file `simulate`
/// or `render` would write for this view. Setting `stop` abandons the picture or the model's
/// points half-way (a 409 answer).
pub fn export_reply(
    view: &View,
    q: &HashMap<String, String>,
    stop: &Arc<AtomicBool>,
) -> Result<Reply, String> {
    let format = get(q, "format").unwrap_or("csv");
    let model = get(q, "model").unwrap_or("course");
    if format == "png" {
        // In buffers of its own (a 4K picture's are large, and freed after), drawn as `render`
        // draws it, and abandoned row by row like a frame.
        let mut scratch = Frame::with_stop_flag(Arc::clone(stop));
        let request = FrameRequest {
            camera: view.camera,
            shading: view.shading(),
            min_points: 0,
        };
        draw_frame(&view.scene.world, &request, &mut scratch);
        if stop.load(Ordering::Relaxed) {
            return Ok(stopped());
        }
        let picture = scratch.picture;
        let mut r = Reply::bytes("image/png", png_bytes(&picture).map_err(|e| e.to_string())?);
        r.file_name = Some("view.png".into());
        return Ok(r);
    }
    if !["course", "eye", "stereo"].contains(&model) {
        return Err(refuse_choice(
            "--image-model",
            model,
            &["course", "eye", "stereo"],
        ));
    }
    let points = view.spec.points.max(1);
    let Some(cloud) = view.sample(points, stop) else {
        return Ok(stopped());
    };
    let eye;
    let stereo;
    let world = &view.scene.world;
    let set_model = match model {
        "eye" => match eye_model_points_until(world, view.observer, &cloud.points, stop) {
            Some(points) => {
                eye = points;
                ModelPoints::Eye(&eye)
            }
            None => return Ok(stopped()),
        },
        "stereo" => match stereo_points_until(world, view.observer, &cloud.points, stop) {
            Some(points) => {
                stereo = points;
                ModelPoints::Stereo(&stereo)
            }
            None => return Ok(stopped()),
        },
        _ => ModelPoints::Course,
    };
    let set = PointSet {
        scene: &view.scene,
        min_points: points,
        model: set_model,
        cloud: &cloud,
    };
    let mut body = Vec::new();
    let (kind, name) = match format {
        "csv" if model == "course" => (
            write_csv(&mut body, &cloud.points, cloud.white).map(|_| "text/csv"),
            "view.csv",
        ),
        "csv" => (
            write_model_csv(&mut body, &set).map(|_| "text/csv"),
            "view.csv",
        ),
        "ply" => (
            write_ply(&mut body, &set).map(|_| "application/octet-stream"),
            "view.ply",
        ),
        other => return Err(refuse_choice("format", other, &["csv", "ply", "png"])),
    };
    let kind = kind.map_err(|e| format!("cannot write the points: {e}"))?;
    let mut r = Reply::bytes(kind, body);
    r.file_name = Some(name.into());
    Ok(r)
}

/// `GET /api/scene-file`: the view's scene as the text of a scene file, its `[observer]` the
/// view's eye (the assignment's glass too, as a file of its kind).
pub fn scene_file_reply(view: &View) -> Result<Reply, String> {
    let mut description = view.scene.description.clone();
    // Where the camera looks: the file's target, the page's, or the middle of the scene.
    let target = view
        .scene
        .target
        .or(view.spec.camera.target.map(Vec3::from_array))
        .unwrap_or_else(|| view.scene.world.bounding_sphere().0);
    description.observer = Some(Observer {
        position: view.observer,
        target: if target == view.observer {
            view.observer + Vec3::Z
        } else {
            target
        },
    });
    let mut r = Reply::bytes("application/toml", description.to_toml().into_bytes());
    r.file_name = Some(PAGE_SCENE_FILE.into());
    Ok(r)
}

/// The answer to `GET path?query` for the API routes (`/api/...`), with a reusable frame and the
/// engine's memory of earlier answers. Another thread may set the frame's [`Frame::stop_flag`] to
/// abandon the work half-way (frames, models, exports): the answer is then incomplete, and the
/// caller throws it away.
pub fn handle(path: &str, query: &str, frame: &mut Frame, memory: &Memory) -> Reply {
    if path == "/api/scenes" {
        return scenes_reply();
    }
    if path == "/api/defaults" {
        return defaults_reply();
    }
    let q = match parse_query(query) {
        Ok(q) => q,
        Err(e) => return Reply::text(400, e),
    };
    if path == "/api/sketch" {
        return sketch_reply(&q).unwrap_or_else(Refused::reply);
    }
    if path == "/api/scene-text" {
        return scene_text_reply(&q).unwrap_or_else(|e| Reply::text(400, e));
    }
    if path == "/api/qr" {
        return qr_reply(&q).unwrap_or_else(|e| Reply::text(422, e));
    }
    let view = match View::checked(&q) {
        Ok(v) => v,
        Err(e) => return e.reply(),
    };
    let result = match path {
        "/api/frame" => Ok(frame_reply(&view, frame, memory)),
        "/api/model" => match get(&q, "every").map_or(Ok(1), |t| number::<usize>(t, "every")) {
            Ok(k) if (1..=MAX_EVERY).contains(&k) => Ok(model_reply(
                &view,
                get(&q, "model").unwrap_or("eye"),
                k,
                &frame.stop_flag(),
                memory,
            )),
            Ok(k) => Err(format!(
                "every={k} is not allowed: a model places every K-th point, 1 <= K <= {MAX_EVERY}"
            )),
            Err(e) => Err(e),
        },
        "/api/ray" => ray_reply(&view, &q, &frame.stop_flag()),
        "/api/aim" => Ok(aim_reply(&view)),
        "/api/export" => export_reply(&view, &q, &frame.stop_flag()),
        "/api/scene-file" => scene_file_reply(&view),
        "/api/sweep" => sweep::sweep_reply(&view, &q, &frame.stop_flag()),
        _ => return Reply::text(404, format!("no such route: {}", clip_text(path, 60))),
    };
    result.unwrap_or_else(|e| Reply::text(400, e))
}

#[cfg(test)]
mod tests {
    use super::*;
    use bentstraw_optics::sampling::sample_image;
    use bentstraw_optics::scene_file::SceneDescription;

    fn query(s: &str) -> HashMap<String, String> {
        parse_query(s).unwrap()
    }

    const REF2: &str = "observer=0.1,0,0.1&straw=0.02,0.01&water-height=0.15";

    /// A glass of radius 0.3 m with `straws` straws in a grid and `layers` liquids.
    fn crowded_scene(straws: usize, layers: usize) -> String {
        let mut text = String::from("[container]\nshape = \"glass\"\nradius = 0.3\nheight = 0.5\n");
        for k in 0..layers {
            let top = 0.4 * (k + 1) as f64 / layers as f64;
            text += &format!(
                "[[liquid]]\nname = \"l{k}\"\nindex = {}\ntop = {top}\n",
                1.3 + 0.005 * k as f64
            );
        }
        for k in 0..straws {
            let (x, y) = (
                (k % 10) as f64 * 0.03 - 0.135,
                (k / 10) as f64 * 0.03 - 0.135,
            );
            text += &format!("[[straw]]\nx = {x}\ny = {y}\n");
        }
        text + "[observer]\nposition = [1.0, 0.0, 0.3]\n"
    }

    #[test]
    fn work_is_bounded_and_heavy_views_are_told_apart() {
        let classic = |extra: &str| View::checked(&query(&format!("{REF2}{extra}")));
        // The page's full frame: light, far below the line.
        let page = classic("").unwrap();
        assert!(page.work() < HEAVY_WORK / 20.0, "{:e}", page.work());
        // The largest classic picture the explorer draws is allowed, and heavy.
        let largest = classic("&size=3840x2160&samples=16&max-events=1000&mode=fresnel").unwrap();
        assert!(
            largest.work() > HEAVY_WORK && largest.work() <= MAX_WORK,
            "{:e}",
            largest.work()
        );
        // The work grows with every factor: pixels, samples², events, points.
        let w = |extra: &str| classic(extra).unwrap().work();
        let base = w("&size=100x100&samples=2&max-events=10&points=1&mode=course");
        let twice = |extra: &str| w(extra) / base;
        assert!(
            (twice("&size=200x100&samples=2&max-events=10&points=1&mode=course") - 2.0).abs()
                < 1e-3
        );
        assert!(
            (twice("&size=100x100&samples=4&max-events=10&points=1&mode=course") - 4.0).abs()
                < 1e-2
        );
        assert!(
            (twice("&size=100x100&samples=2&max-events=20&points=1&mode=course") - 2.0).abs()
                < 1e-9
        );
        assert!(
            (twice("&size=100x100&samples=2&max-events=10&points=1&mode=fresnel") - 2.0).abs()
                < 1e-9
        );
        assert!(twice("&size=100x100&samples=2&max-events=10&points=2500&mode=course") > 1.9);
        // A hundred straws under 32 layers drawn in 4K with every sample and event: refused,
        // the message naming what to lower.
        let mut q =
            query("observer=1,0,0.3&size=3840x2160&samples=16&max-events=1000&points=1000000");
        q.insert("scene-file".into(), crowded_scene(100, 32));
        let Err(refused) = View::checked(&q) else {
            panic!("a view beyond the work allowed was taken")
        };
        for word in [
            "3840x2160",
            "16x16",
            "1000000 points",
            "1000 events",
            "ray-surface tests",
        ] {
            assert!(
                refused.message.contains(word),
                "{word} in {}",
                refused.message
            );
        }
        // The same scene at the page's size is allowed.
        let mut q = query("observer=1,0,0.3");
        q.insert("scene-file".into(), crowded_scene(100, 32));
        assert!(View::checked(&q).is_ok());
    }

    #[test]
    fn queries_decode_escapes_and_refuse_broken_ones() {
        let q = query("observer=0.1%2C0%2C0.1&a+b=c+d&flag");
        assert_eq!(q["observer"], "0.1,0,0.1");
        assert_eq!(q["a b"], "c d");
        assert_eq!(q["flag"], "");
        assert!(parse_query("x=%G1").is_err());
        assert!(parse_query("x=%").is_err());
        assert!(parse_query("x=%ff").is_err()); // not UTF-8
        let many: Vec<String> = (0..100).map(|k| format!("p{k}=1")).collect();
        assert!(parse_query(&many.join("&")).is_err());
    }

    /// The page gets the command line's own messages for values that break a rule.
    #[test]
    fn invalid_values_get_the_command_lines_messages() {
        let msg = |s: &str| View::from_query(&query(s)).unwrap_err();
        let he = msg("observer=0.1,0,0.1&straw=0.02,0.01&water-height=0.3");
        assert!(
            he.starts_with("water height 0.3 m is outside the glass"),
            "{he}"
        );
        let inside = msg("observer=0,0,0.1&straw=0.02,0.01&water-height=0.1");
        assert!(inside.contains("is inside or on the glass"), "{inside}");
        // One range for the eye whatever gives it: a scene file's thousand kilometres.
        for far in ["1e7", "1e308", "-1000000.5"] {
            let e = msg(&format!(
                "observer={far},0,0.1&straw=0.02,0.01&water-height=0.1"
            ));
            assert!(
                e.starts_with("observer x = ")
                    && e.contains("m is too far: a position must be at most 1000000 m"),
                "{e}"
            );
        }
        assert!(View::from_query(&query(
            "observer=1000000,0,0.1&straw=0.02,0.01&water-height=0.1"
        ))
        .is_ok());
        let n = msg(&format!("{REF2}&n-water=0.5"));
        assert!(n.contains("water index 0.5 is not allowed"), "{n}");
        let ev = msg(&format!("{REF2}&max-events=0"));
        assert!(ev.contains("event limit 0"), "{ev}");
        let nan = msg("observer=nan,0,0.1&straw=0.02,0.01&water-height=0.1");
        assert!(nan.contains("not a finite number"), "{nan}");
        let bad = msg("observer=0.1,0&straw=0.02,0.01&water-height=0.1");
        assert!(bad.contains("expected 3"), "{bad}");
        let size = msg(&format!("{REF2}&size=100000x100000"));
        assert!(size.contains("--size"), "{size}");
        let size = msg(&format!("{REF2}&size=4000x4000"));
        assert!(size.contains("too large"), "{size}");
        let pts = msg(&format!("{REF2}&points=99999999999"));
        assert!(pts.contains("--points"), "{pts}");
        assert!(msg("straw=0.02,0.01&water-height=0.1").contains("'observer'"));
        assert!(msg(&format!("{REF2}&mode=wave")).contains("possible values"));
        assert!(msg(&format!("{REF2}&fov=190")).contains("--fov 190"));
    }

    /// The model's answer places the points of the course cloud `simulate` computes (from the last
    /// frame or traced afresh), every K-th of them when asked.
    #[test]
    fn models_place_every_kth_course_point() {
        let view = View::from_query(&query(&format!("{REF2}&size=40x30&points=800"))).unwrap();
        let cloud = sample_image(&view.scene.world, view.observer, 800, &|_| {}).points;
        let decode = |r: Reply| -> Vec<[f32; 3]> {
            assert_eq!(r.status, 200);
            let n = u32::from_le_bytes(r.body[0..4].try_into().unwrap()) as usize;
            assert_eq!(r.body.len(), 4 + 13 * n);
            (0..n)
                .map(|i| {
                    let f = |k: usize| {
                        let at = 4 + 12 * i + 4 * k;
                        f32::from_le_bytes(r.body[at..at + 4].try_into().unwrap())
                    };
                    [f(0), f(1), f(2)]
                })
                .collect()
        };
        let expect = |every: usize| -> Vec<[f32; 3]> {
            let some: Vec<ImagePoint> = cloud.iter().step_by(every).copied().collect();
            bentstraw_optics::apparent::eye_model_points(&view.scene.world, view.observer, &some)
                .iter()
                .filter_map(|p| p.position)
                .map(|q| [q.x as f32, q.y as f32, q.z as f32])
                .collect()
        };
        // Before any frame (traced afresh) and after this view's frame (its points reused).
        let memory = Memory::default();
        for with_frame in [false, true] {
            if with_frame {
                frame_reply(&view, &mut Frame::default(), &memory);
            }
            // Whole, coarse, then whole again from the coarse answer's points.
            for every in [1, 4, 1] {
                let stop = AtomicBool::new(false);
                let reply = model_reply(&view, "eye", every, &stop, &memory);
                // The answer says where its points came from.
                assert_eq!(reply.reused_points, with_frame, "every {every}");
                let got = decode(reply);
                assert!(got.len() > 800 / every / 2);
                assert_eq!(
                    got,
                    expect(every),
                    "every {every}, after a frame: {with_frame}"
                );
            }
            // The three answers after the frame started from its points, none before it.
            assert_eq!(memory.points_reused(), if with_frame { 3 } else { 0 });
        }
        // Another view than the frame's: its points are traced, and the answer says so.
        let other = View::from_query(&query(&format!("{REF2}&size=40x30&points=900"))).unwrap();
        let stop = AtomicBool::new(false);
        assert!(!model_reply(&other, "eye", 4, &stop, &memory).reused_points);
        assert_eq!(memory.points_reused(), 3);
        let bad = handle(
            "/api/model",
            &format!("{REF2}&model=eye&every=0"),
            &mut Frame::default(),
            &Memory::default(),
        );
        assert_eq!(bad.status, 400);
        assert!(String::from_utf8_lossy(&bad.body).contains("1 <= K <= 64"));
    }

    /// The frame's binary layout: header, RGBA picture, points; the points are `simulate`'s.
    #[test]
    fn frame_reply_layout_and_points() {
        let view = View::from_query(&query(&format!("{REF2}&size=40x30&points=1500"))).unwrap();
        let reply = frame_reply(&view, &mut Frame::default(), &Memory::default());
        assert_eq!(reply.status, 200);
        let b = &reply.body;
        let len = u32::from_le_bytes(b[0..4].try_into().unwrap()) as usize;
        assert_eq!((4 + len) % 4, 0);
        let header: Value = serde_json::from_slice(&b[4..4 + len]).unwrap();
        let n = header["n"].as_u64().unwrap() as usize;
        let expected = sample_image(&view.scene.world, view.observer, 1500, &|_| {}).points;
        assert_eq!(n, expected.len());
        let start = 4 + len + 40 * 30 * 4;
        assert_eq!(b.len(), start + 12 * n + 2 * n);
        let x0 = f32::from_le_bytes(b[start..start + 4].try_into().unwrap());
        assert_eq!(x0, expected[0].position.x as f32);
        assert_eq!(b[start + 12 * n], expected[0].color);
        assert!(header["render"]
            .as_str()
            .unwrap()
            .contains("--size 40x30 --mode fresnel"));
    }

    /// A clicked image point's readout has the numbers of that point in `simulate`'s list.
    #[test]
    fn ray_of_a_point_is_that_point() {
        let view = View::from_query(&query(&format!("{REF2}&points=1000"))).unwrap();
        let pts = sample_image(&view.scene.world, view.observer, 1000, &|_| {}).points;
        let r = ray_reply(&view, &query("point=17"), &AtomicBool::new(false)).unwrap();
        let v: Value = serde_json::from_slice(&r.body).unwrap();
        let p = pts[17];
        assert_eq!(
            v["image_point"],
            json!([p.position.x, p.position.y, p.position.z])
        );
        assert_eq!(v["path_length"], json!(p.path_length));
        assert_eq!(v["color"], json!(p.color));
        assert_eq!(v["events"].as_array().unwrap().len(), p.events as usize);
        assert!(ray_reply(&view, &query("point=99999999"), &AtomicBool::new(false)).is_err());
        assert!(ray_reply(&view, &query("row=-1&col=3"), &AtomicBool::new(false)).is_err());
    }

    /// A link's QR code is an SVG picture whose size grows with the link, up to the longest a
    /// QR code holds; a longer link is refused with what fits.
    #[test]
    fn a_link_becomes_a_qr_code_or_is_refused_when_too_long() {
        let svg = |n: usize| {
            let text = format!("https://example.org/bentstraw/#{}", "a".repeat(n));
            let r = handle(
                "/api/qr",
                &format!("text={text}"),
                &mut Frame::default(),
                &Memory::default(),
            );
            (r.status, String::from_utf8(r.body).unwrap())
        };
        let (short, long) = (svg(10), svg(2000));
        assert_eq!((short.0, long.0), (200, 200));
        assert!(short.1.contains("<svg") && long.1.contains("<svg"));
        // More modules for more text: the picture's view box counts them.
        let width = |s: &str| {
            s.split("viewBox=\"0 0 ")
                .nth(1)
                .and_then(|v| v.split(' ').next())
                .and_then(|v| v.parse::<u32>().ok())
                .unwrap()
        };
        assert!(width(&long.1) > width(&short.1));
        let (status, message) = svg(QR_MAX_LINK);
        assert_eq!(status, 422);
        assert!(message.contains("at most 2953"), "{message}");
    }

    /// Each event's drawing geometry obeys the laws it illustrates, over many rays of a layered
    /// scene: the normal is a unit vector facing the ray; the three directions lie in one plane
    /// (the plane of incidence); a refraction keeps n sin θ (Snell–Descartes) and a total
    /// reflection mirrors the ray; and the angles given agree with the vectors.
    #[test]
    fn ray_events_carry_their_plane_of_incidence() {
        let view = View::from_query(&query(
            "scene=oil-on-water&observer=0.3,0.05,0.12&points=400",
        ))
        .unwrap();
        let world = &view.scene.world;
        let pts = sample_image(world, view.observer, 400, &|_| {}).points;
        let v3 = |x: &Value| {
            Vec3::new(
                x[0].as_f64().unwrap(),
                x[1].as_f64().unwrap(),
                x[2].as_f64().unwrap(),
            )
        };
        let (mut refractions, mut reflections) = (0, 0);
        for p in pts.iter().step_by(7) {
            let u0 = (p.position - view.observer).normalize();
            let r = ray_json(world, view.observer, u0);
            for e in r["events"].as_array().unwrap() {
                let (n, din, dout) = (v3(&e["normal"]), v3(&e["incoming"]), v3(&e["outgoing"]));
                let (n1, n2) = (e["n1"].as_f64().unwrap(), e["n2"].as_f64().unwrap());
                assert!((n.length() - 1.0).abs() < 1e-12 && din.dot(n) < 0.0, "{e}");
                assert!(din.cross(n).dot(dout).abs() < 1e-9, "not in one plane: {e}");
                let (sin_in, sin_out) = (din.cross(n).length(), dout.cross(n).length());
                let deg = |s: f64| s.asin().to_degrees();
                assert!((deg(sin_in) - e["incidence_deg"].as_f64().unwrap()).abs() < 1e-6);
                assert!((deg(sin_out) - e["outgoing_deg"].as_f64().unwrap()).abs() < 1e-6);
                if e["event"] == "refraction" {
                    refractions += 1;
                    assert!((n1 * sin_in - n2 * sin_out).abs() < 1e-9, "Snell: {e}");
                    assert!(dout.dot(n) < 0.0, "goes on across: {e}");
                } else {
                    reflections += 1;
                    let mirrored = din - 2.0 * din.dot(n) * n;
                    assert!((dout - mirrored).length() < 1e-12, "mirror: {e}");
                    assert!(n1 * sin_in > n2, "beyond the critical angle: {e}");
                }
            }
        }
        assert!(
            refractions > 50 && reflections > 0,
            "{refractions} {reflections}"
        );
    }

    /// A gallery scene: its frame holds the objects' points (codes up to 8) and what the page draws
    /// of the scene; its rays, models and exports answer; a wrong name or an eye inside the
    /// container gets the rule's message.
    #[test]
    fn gallery_scenes_are_served() {
        let mut f = Frame::default();
        let q = "scene=reversing-arrow&observer=0.3,0,0.1&size=48x36&points=800";
        let r = handle("/api/frame", q, &mut f, &Memory::default());
        assert_eq!(r.status, 200, "{}", String::from_utf8_lossy(&r.body));
        let len = u32::from_le_bytes(r.body[..4].try_into().unwrap()) as usize;
        let header: Value = serde_json::from_slice(&r.body[4..4 + len]).unwrap();
        assert!(header["n"].as_u64().unwrap() >= 800);
        assert_eq!(header["points_per_color"].as_array().unwrap().len(), 8);
        assert!(
            header["points_per_color"][7].as_u64().unwrap() > 0,
            "the arrow"
        );
        let sketch: Value = serde_json::from_slice(
            &handle(
                "/api/sketch",
                "scene=reversing-arrow",
                &mut f,
                &Memory::default(),
            )
            .body,
        )
        .unwrap();
        assert!(!sketch["wireframe"].as_array().unwrap().is_empty());
        // The inside the liquids fill, for the maps' tints: a thick glass's inner radius and
        // floor, a tank's half widths.
        let mut inside = |scene: &str| -> Value {
            let q = format!("scene={scene}");
            let v: Value =
                serde_json::from_slice(&handle("/api/sketch", &q, &mut f, &Memory::default()).body)
                    .unwrap();
            v["container"].clone()
        };
        let glass = inside("real-glass");
        assert_eq!(glass["shape"], "glass");
        let (r, floor) = (
            glass["radius"].as_f64().unwrap(),
            glass["floor"].as_f64().unwrap(),
        );
        assert!((r - 0.0375).abs() < 1e-12 && floor == 0.008, "{glass}");
        let tank = inside("apparent-depth");
        assert_eq!(tank["shape"], "tank");
        assert_eq!(tank["half_x"].as_f64(), Some(0.10));
        assert_eq!(tank["half_y"].as_f64(), Some(0.05));
        assert_eq!(tank["floor"].as_f64(), Some(0.0));
        assert!(header["simulate"]
            .as_str()
            .unwrap()
            .contains("--scene reversing-arrow --observer 0.3,0,0.1"));
        let ray = handle(
            "/api/ray",
            &format!("{q}&point=10"),
            &mut f,
            &Memory::default(),
        );
        assert_eq!(ray.status, 200);
        let ray: Value = serde_json::from_slice(&ray.body).unwrap();
        assert!(ray["color"].as_u64().unwrap() >= 7);
        for route in ["/api/model", "/api/export"] {
            assert_eq!(
                handle(route, q, &mut f, &Memory::default()).status,
                200,
                "{route}"
            );
        }
        let png = handle(
            "/api/export",
            &format!("{q}&format=png"),
            &mut f,
            &Memory::default(),
        );
        assert!(png.body.starts_with(b"\x89PNG"));
        let scenes: Value =
            serde_json::from_slice(&handle("/api/scenes", "", &mut f, &Memory::default()).body)
                .unwrap();
        assert_eq!(scenes.as_array().unwrap().len(), GALLERY.len());
        let wrong = handle(
            "/api/frame",
            "scene=teapot&observer=1,0,0",
            &mut f,
            &Memory::default(),
        );
        assert_eq!(wrong.status, 400);
        assert!(String::from_utf8_lossy(&wrong.body).contains("leaning-straw"));
        let inside = handle(
            "/api/frame",
            "scene=tank-pencil&observer=0,0,0.05",
            &mut f,
            &Memory::default(),
        );
        assert_eq!(inside.status, 400);
        assert!(String::from_utf8_lossy(&inside.body).contains("inside or on the container"));
    }

    /// A scene file's text in the query is read as `--scene scene.toml` reads the file: the
    /// same points as the gallery's copy of it, its rules' messages, and the view's scene written
    /// back as a file gives the same view.
    #[test]
    fn a_scene_files_text_is_the_scene_of_the_view() {
        let mut f = Frame::default();
        let (stem, text) = GALLERY[3];
        let view = "observer=0.05,-0.35,0.12&points=500";
        let gallery = format!("/api/export?scene={stem}&{view}&format=csv");
        let own = format!("scene-file={}&{view}&format=csv", query_value(text));
        let a = handle(
            "/api/export",
            gallery.split_once('?').unwrap().1,
            &mut f,
            &Memory::default(),
        );
        let b = handle("/api/export", &own, &mut f, &Memory::default());
        assert_eq!(a.status, 200, "{}", String::from_utf8_lossy(&a.body));
        assert_eq!(a.body, b.body);
        // What the view's scene writes back is the same scene.
        let file = handle("/api/scene-file", &own, &mut f, &Memory::default());
        assert_eq!(file.status, 200);
        let written = String::from_utf8(file.body).unwrap();
        let again = format!("scene-file={}&{view}&format=csv", query_value(&written));
        assert_eq!(
            handle("/api/export", &again, &mut f, &Memory::default()).body,
            b.body
        );
        // The assignment's glass is written as a file of its kind: the same points again.
        let glass = format!("{REF2}&points=500&format=csv");
        let file = handle("/api/scene-file", &glass, &mut f, &Memory::default());
        let written = String::from_utf8(file.body).unwrap();
        assert!(written.contains("[[straw]]"), "{written}");
        let from_file = format!(
            "scene-file={}&observer=0.1,0,0.1&points=500&format=csv",
            query_value(&written)
        );
        assert_eq!(
            handle("/api/export", &from_file, &mut f, &Memory::default()).body,
            handle("/api/export", &glass, &mut f, &Memory::default()).body
        );
        // A broken rule: the command line's message, naming the page's file.
        let broken = text.replace("half_x = 0.10", "half_x = -0.10");
        assert_ne!(broken, text);
        let r = handle(
            "/api/frame",
            &format!("scene-file={}&{view}", query_value(&broken)),
            &mut f,
            &Memory::default(),
        );
        assert_eq!(r.status, 400);
        let refusal: Value = serde_json::from_slice(&r.body).unwrap();
        let message = refusal["message"].as_str().unwrap();
        assert!(message.starts_with("scene.toml"), "{message}");
        // Not both a gallery scene and a file.
        let both = format!("scene={stem}&scene-file=x&{view}");
        assert_eq!(
            handle("/api/frame", &both, &mut f, &Memory::default()).status,
            400
        );
    }

    /// A refused scene comes with its broken rules as data, all of them, beside the command
    /// line's message: code, key, value, parameters; an eye inside the assignment's glass too.
    #[test]
    fn refusals_carry_their_rules_as_data() {
        let mut f = Frame::default();
        let text = "[container]\nshape = \"glass\"\nradius = 0.04\nheight = 0.2\n[[liquid]]\nname = \"water\"\nindex = 0.8\ntop = 0.15\n[[straw]]\nx = 0\ny = 0\ntilt = 95\n";
        let r = handle(
            "/api/frame",
            &format!("scene-file={}&observer=0.3,0,0.1", query_value(text)),
            &mut f,
            &Memory::default(),
        );
        assert_eq!((r.status, r.content_type), (400, "application/json"));
        let v: Value = serde_json::from_slice(&r.body).unwrap();
        let expected = parse_scene_text(PAGE_SCENE_FILE, text)
            .unwrap_err()
            .to_string();
        assert_eq!(v["message"], json!(expected));
        assert_eq!(v["file"], json!("scene.toml"));
        let rules = v["rules"].as_array().unwrap();
        assert_eq!(rules.len(), 2);
        assert_eq!(rules[0]["code"], json!("index.range"));
        assert_eq!(rules[0]["key"], json!("liquid[1].index"));
        assert_eq!(rules[0]["value"], json!("0.8"));
        assert_eq!(rules[1]["code"], json!("tilt.range"));
        assert_eq!(rules[1]["value"], json!("95"));
        // The eye inside a scene file's container: refused once the page's eye is applied.
        // (A coin makes it a scene of its own, not the assignment's glass.)
        let good = text
            .replace("index = 0.8", "index = 1.333")
            .replace("tilt = 95", "tilt = 0")
            + "[[coin]]\nx = 0.02\ny = 0\n";
        let r = handle(
            "/api/frame",
            &format!("scene-file={}&observer=0,0,0.1", query_value(&good)),
            &mut f,
            &Memory::default(),
        );
        let v: Value = serde_json::from_slice(&r.body).unwrap();
        assert_eq!(v["flagged"], json!(true));
        assert_eq!(v["rules"][0]["code"], json!("observer.in-container"));
        assert_eq!(v["rules"][0]["params"]["z"], json!("0.1"));
        // The assignment's glass: its own rule, its numbers.
        let r = handle(
            "/api/frame",
            "observer=0,0,0.1&straw=0.02,0.01&water-height=0.15",
            &mut f,
            &Memory::default(),
        );
        let v: Value = serde_json::from_slice(&r.body).unwrap();
        assert_eq!(v["rules"][0]["code"], json!("glass.eye-inside"));
        assert_eq!(v["rules"][0]["params"]["radius"], json!("0.04"));
        assert!(v["message"]
            .as_str()
            .unwrap()
            .contains("inside or on the glass"));
        // Words quoted as they are, marked so.
        let cone = "[container]\nshape = \"co.ne\"\nheight = 0.2\n";
        let r = handle(
            "/api/sketch",
            &format!("scene-file={}", query_value(cone)),
            &mut f,
            &Memory::default(),
        );
        let v: Value = serde_json::from_slice(&r.body).unwrap();
        assert_eq!(v["rules"][0]["params"]["shape"], json!({"text": "co.ne"}));
    }

    /// The page's controls edit a sketch's `form` and get the file's text back: every gallery
    /// scene comes back as the same description, an edited value is the text's value, and the
    /// rules are checked where the text is read (a broken value is refused there by its key).
    #[test]
    fn a_scenes_form_turns_back_into_its_file() {
        let mut f = Frame::default();
        let text_of = |form: &Value, f: &mut Frame| {
            let q = format!("form={}", query_value(&form.to_string()));
            let r = handle("/api/scene-text", &q, f, &Memory::default());
            assert_eq!(r.status, 200, "{}", String::from_utf8_lossy(&r.body));
            String::from_utf8(r.body).unwrap()
        };
        for (stem, text) in GALLERY {
            let sketch = handle(
                "/api/sketch",
                &format!("scene={stem}"),
                &mut f,
                &Memory::default(),
            );
            let v: Value = serde_json::from_slice(&sketch.body).unwrap();
            let back = text_of(&v["form"], &mut f);
            let original = SceneDescription::from_toml(text).unwrap();
            let again = SceneDescription::from_toml(&back).unwrap();
            assert_eq!(again.to_toml(), original.to_toml(), "{stem}");
            assert!(v["form"]["container"]["shape"].is_string(), "{stem}");
        }
        // An edit: the coin moved and a liquid added.
        let sketch = handle(
            "/api/sketch",
            "scene=coin-in-glass",
            &mut f,
            &Memory::default(),
        );
        let mut form = serde_json::from_slice::<Value>(&sketch.body).unwrap()["form"].clone();
        form["coin"][0]["x"] = json!(0.0123);
        let back = SceneDescription::from_toml(&text_of(&form, &mut f)).unwrap();
        assert_eq!(back.coins[0].x, 0.0123);
        // A top above the container: written as asked, refused where the text is read, by key.
        let height = form["container"]["height"].as_f64().unwrap();
        form["liquid"][0]["top"] = json!(height + 0.01);
        let broken = text_of(&form, &mut f);
        let r = handle(
            "/api/sketch",
            &format!("scene-file={}", query_value(&broken)),
            &mut f,
            &Memory::default(),
        );
        assert_eq!(r.status, 400);
        let v: Value = serde_json::from_slice(&r.body).unwrap();
        assert_eq!(v["rules"][0]["key"], json!("liquid[1].top"), "{v}");
        // What is not a scene file's key, or not JSON, or too long, is refused here.
        for bad in [
            r#"{"container":{"shape":"glass","colour":1}}"#,
            "{",
            "[1,2]",
        ] {
            let r = handle(
                "/api/scene-text",
                &format!("form={}", query_value(bad)),
                &mut f,
                &Memory::default(),
            );
            assert_eq!(r.status, 400, "{bad}");
            assert!(String::from_utf8_lossy(&r.body).contains("form"), "{bad}");
        }
        let long = format!("form={}", "x".repeat(MAX_SCENE_FILE_BYTES as usize + 1));
        assert_eq!(
            handle("/api/scene-text", &long, &mut f, &Memory::default()).status,
            400
        );
        assert_eq!(
            handle("/api/scene-text", "", &mut f, &Memory::default()).status,
            400
        );
    }

    /// The page's language tables (i18n.js) say every rule the library can break, in English
    /// exactly as the command line does (its text, `{name}` where each parameter goes) and in
    /// French naming the same parameters.
    #[test]
    fn the_page_says_every_rule_in_english_and_french() {
        let js = include_str!("../page/i18n.js");
        let table = |lang: &str| -> HashMap<String, String> {
            let start = js.find(&format!("\n  {lang}: {{\n")).expect(lang);
            let body = &js[start..];
            let end = body.find("\n  },").expect("table end");
            body[..end]
                .lines()
                .filter_map(|l| {
                    let l = l.trim().strip_suffix(',')?;
                    let (k, v) = l.split_once("\": ")?;
                    Some((
                        k.strip_prefix('"')?.to_string(),
                        serde_json::from_str::<String>(v).ok()?,
                    ))
                })
                .collect()
        };
        let (en, fr) = (table("en"), table("fr"));
        let names = |t: &str| -> Vec<String> {
            let mut v: Vec<String> = t
                .split('{')
                .skip(1)
                .filter_map(|p| p.split_once('}').map(|(n, _)| n.to_string()))
                .collect();
            v.sort();
            v
        };
        for rule in Rule::ALL {
            let key = format!("rule.{}", rule.code());
            assert_eq!(
                en.get(&key).map(String::as_str),
                Some(rule.template()),
                "{key}"
            );
            let french = fr
                .get(&key)
                .unwrap_or_else(|| panic!("no French text for {key}"));
            assert_eq!(names(french), names(rule.template()), "{key}");
            assert_ne!(french, rule.template(), "{key} is not translated");
        }
    }

    /// Work whose stop flag is set is abandoned (409); not set, the PNG is `render`'s picture.
    #[test]
    fn stopped_exports_and_models_are_abandoned() {
        let view = View::from_query(&query(&format!("{REF2}&size=40x30&points=300"))).unwrap();
        let go = Arc::new(AtomicBool::new(false));
        let png = export_reply(&view, &query("format=png"), &go).unwrap();
        let picture = bentstraw_optics::shading::shaded_picture(
            &view.scene.world,
            &view.camera,
            &view.shading(),
        );
        assert_eq!(png.body, png_bytes(&picture).unwrap());
        let stop = Arc::new(AtomicBool::new(true));
        for format in [
            "format=png",
            "format=csv&model=eye",
            "format=ply&model=stereo",
        ] {
            let r = export_reply(&view, &query(format), &stop).unwrap();
            assert_eq!(r.status, 409, "{format}");
        }
        for model in ["eye", "stereo"] {
            assert_eq!(
                model_reply(&view, model, 1, &stop, &Memory::default()).status,
                409,
                "{model}"
            );
            assert_eq!(
                model_reply(&view, model, 1, &go, &Memory::default()).status,
                200,
                "{model}"
            );
        }
        // Through `handle`: the frame's flag.
        let mut frame = Frame::default();
        frame.stop_flag().store(true, Ordering::Relaxed);
        let q = format!("{REF2}&size=40x30&points=300&format=png");
        assert_eq!(
            handle("/api/export", &q, &mut frame, &Memory::default()).status,
            409
        );
    }

    /// The page's defaults are the engine's: the same constants the command line's flags use.
    #[test]
    fn defaults_are_the_engines() {
        let r = handle(
            "/api/defaults",
            "",
            &mut Frame::default(),
            &Memory::default(),
        );
        assert_eq!(r.status, 200);
        let v: Value = serde_json::from_slice(&r.body).unwrap();
        assert_eq!(v["points"], DEFAULT_POINTS);
        assert_eq!(v["samples"], bentstraw_optics::view::DEFAULT_SAMPLES);
        assert_eq!(v["mode"], "fresnel");
        assert_eq!(v["backdrop"], "checker");
        assert_eq!(v["size"], json!([800, 600]));
        assert_eq!(v["classic"]["observer"], json!(CLASSIC_OBSERVER));
        assert_eq!(v["references"].as_array().unwrap().len(), 4);
        assert_eq!(v["references"][1]["observer"], json!([0.1, 0.0, 0.1]));
        // A view made of the defaults alone is the classic one, accepted as the page sends it.
        let c = &v["classic"];
        let q = format!(
            "observer={}&straw={}&water-height={}",
            list(&c["observer"]),
            list(&c["straw"]),
            c["waterHeight"]
        );
        let view = View::from_query(&query(&q)).unwrap();
        assert_eq!(view.spec.picture, PictureSpec::default());
        assert_eq!(view.spec.points, DEFAULT_POINTS);
        assert_eq!(view.spec, ViewSpec::default());
    }

    /// The commands the page shows for a view, byte for byte: the scene's flags (the glass's
    /// values, a gallery scene or the page's file by name, the index and the event limit when not
    /// the defaults), then `simulate`'s points and model, or `render`'s camera and picture.
    #[test]
    fn the_commands_of_a_view() {
        let commands = |q: &str| {
            let view = View::from_query(&query(q)).unwrap();
            (
                view.simulate_command(ImageModel::Course),
                view.simulate_command(ImageModel::Eye),
                view.render_command(),
            )
        };
        let (simulate, eye, render) =
            commands(&format!("{REF2}&n-water=1.4&max-events=5&points=0"));
        let scene = "--observer 0.1,0,0.1 --straw 0.02,0.01 --water-height 0.15 --n-water 1.4 --max-events 5";
        assert_eq!(
            simulate,
            format!("bentstraw simulate {scene} --points 1 --output view.csv")
        );
        assert_eq!(
            eye,
            format!("bentstraw simulate {scene} --points 1 --image-model eye --output view.csv")
        );
        assert_eq!(render, format!("bentstraw render {scene} --size 800x600 --mode fresnel --backdrop checker --output view.png"));
        // Numbers as Rust writes them back, the defaults left out, the camera as given.
        let (simulate, _, render) = commands("observer=1e-1,0,0.10&straw=+0.02,0.010&water-height=.15&n-water=1.333&max-events=10&points=+7&target=0,0.01,0.1&fov=3e1&size=40x30&mode=course&backdrop=none&samples=5");
        let scene = "--observer 0.1,0,0.1 --straw 0.02,0.01 --water-height 0.15";
        assert_eq!(
            simulate,
            format!("bentstraw simulate {scene} --points 7 --output view.csv")
        );
        assert_eq!(render, format!("bentstraw render {scene} --target 0,0.01,0.1 --fov 30 --size 40x30 --mode course --backdrop none --samples 5 --output view.png"));
        // A gallery scene by name, the glass's values it has no use for left out.
        let (simulate, _, render) = commands("scene=tank-pencil&observer=0.3,0,0.1&max-events=7&n-water=1.4&straw=0.01,0&water-height=0.05&points=123");
        let scene = "--scene tank-pencil --observer 0.3,0,0.1 --max-events 7";
        assert_eq!(
            simulate,
            format!("bentstraw simulate {scene} --points 123 --output view.csv")
        );
        assert_eq!(render, format!("bentstraw render {scene} --size 800x600 --mode fresnel --backdrop checker --output view.png"));
        // The page's own file by its name, the assignment's kind too (its values are the file's).
        for (_, text) in [GALLERY[0], bentstraw_io::gallery::SPEC] {
            let (simulate, _, _) = commands(&format!(
                "scene-file={}&observer=0.1,0,0.1&points=300",
                query_value(text)
            ));
            assert_eq!(simulate, "bentstraw simulate --scene scene.toml --observer 0.1,0,0.1 --points 300 --output view.csv");
        }
    }

    fn list(v: &Value) -> String {
        let items: Vec<String> = v.as_array().unwrap().iter().map(Value::to_string).collect();
        items.join(",")
    }

    #[test]
    fn unknown_routes_and_formats_are_refused() {
        let mut f = Frame::default();
        assert_eq!(
            handle("/api/nothing", REF2, &mut f, &Memory::default()).status,
            404
        );
        assert_eq!(
            handle("/api/frame", "observer=1", &mut f, &Memory::default()).status,
            400
        );
        let e = handle(
            "/api/export",
            &format!("{REF2}&format=exe"),
            &mut f,
            &Memory::default(),
        );
        assert_eq!(e.status, 400);
    }

    mod fuzz {
        use super::*;
        use proptest::prelude::*;

        const ROUTES: [&str; 7] = [
            "/api/frame",
            "/api/model",
            "/api/ray",
            "/api/export",
            "/api/scenes",
            "/api/sketch",
            "/api/x",
        ];

        /// A value for a parameter: good ones, and the hostile kinds (not numbers, huge, NaN,
        /// negative, empty, broken escapes, long).
        fn value() -> impl Strategy<Value = String> {
            prop_oneof![
                Just("0.1,0,0.1".to_string()),
                Just("0.02,0.01".to_string()),
                Just("0.15".to_string()),
                Just("16x12".to_string()),
                Just("NaN".to_string()),
                Just("inf,-inf,1e308".to_string()),
                Just("-1".to_string()),
                Just("".to_string()),
                Just("%".to_string()),
                Just("%e2%82".to_string()),
                Just("99999999999999999999999".to_string()),
                Just("0x0".to_string()),
                Just("1e-320".to_string()),
                "[ -~]{0,40}",
                "[0-9.,x+-]{0,12}",
            ]
        }

        fn query() -> impl Strategy<Value = String> {
            let names = prop_oneof![
                Just("observer"),
                Just("straw"),
                Just("water-height"),
                Just("n-water"),
                Just("max-events"),
                Just("size"),
                Just("points"),
                Just("samples"),
                Just("mode"),
                Just("target"),
                Just("fov"),
                Just("row"),
                Just("col"),
                Just("point"),
                Just("format"),
                Just("model"),
            ];
            proptest::collection::vec((names, value()), 0..14).prop_map(|pairs| {
                pairs
                    .iter()
                    .map(|(n, v)| format!("{n}={v}"))
                    .collect::<Vec<_>>()
                    .join("&")
            })
        }

        /// Whether a ray's answer has its observer, direction and every event's point and angles
        /// as numbers.
        fn ray_numbers_finite(v: &Value) -> bool {
            let triple = |x: &Value| {
                x.as_array()
                    .is_some_and(|a| a.len() == 3 && a.iter().all(Value::is_f64))
            };
            triple(&v["observer"])
                && triple(&v["direction"])
                && v["events"].as_array().is_some_and(|events| {
                    events.iter().all(|e| {
                        triple(&e["point"])
                            && e["incidence_deg"].is_f64()
                            && e["outgoing_deg"].is_f64()
                    })
                })
        }

        /// Rays of the farthest, narrowest and widest views the rules allow, through the
        /// picture's corners: every number of the answer is a number.
        #[test]
        fn rays_of_extreme_views_are_numbers() {
            for observer in [
                "1e6,0,0.1",
                "-1e6,1e6,1e6",
                "0,0,-1e6",
                "0.0401,0,0.1",
                "0,0,0.1",
            ] {
                for camera in ["", "&fov=0.01", "&fov=150", "&size=1x1", "&target=0,0,0"] {
                    let q = format!(
                        "observer={observer}&straw=0.02,0.01&water-height=0.15{camera}&size=9x7"
                    );
                    let Ok(view) = View::checked(&super::query(&q)) else {
                        continue;
                    };
                    let (w, h) = (view.camera.width, view.camera.height);
                    for (row, col) in [(0, 0), (h, w), (h / 2, w / 2), (0, w)] {
                        let q = super::query(&format!("{q}&row={row}&col={col}"));
                        let Ok(r) = ray_reply(&view, &q, &AtomicBool::new(false)) else {
                            continue;
                        };
                        let v: Value = serde_json::from_slice(&r.body).unwrap();
                        assert!(ray_numbers_finite(&v), "{v} for {q:?}");
                    }
                }
            }
        }

        proptest! {
            #![proptest_config(ProptestConfig::with_cases(400))]

            /// No query reaches a panic, and every answer is a success or a refusal: the work
            /// each may cause is bounded by the limits (small sizes here keep the run short).
            #[test]
            fn any_query_gets_an_answer(q in query(), route in 0..ROUTES.len()) {
                // Keep accepted work small: the fuzzing is about parsing, not about big frames.
                let q = format!("{q}&points=50&size=16x12");
                let r = handle(ROUTES[route], &q, &mut Frame::default(), &Memory::default());
                prop_assert!([200, 400, 404].contains(&r.status), "{} for {q}", r.status);
                if r.status != 200 {
                    let text = String::from_utf8(r.body).unwrap();
                    prop_assert!(!text.is_empty() && !text.contains('\n'), "{text:?}");
                } else if ROUTES[route] == "/api/ray" {
                    // Numbers stay numbers: a ray's direction and events are never null.
                    let v: Value = serde_json::from_slice(&r.body).unwrap();
                    prop_assert!(ray_numbers_finite(&v), "{v} for {q}");
                }
            }

            /// Raw text, however broken, decodes or is refused.
            #[test]
            fn any_text_parses_or_is_refused(q in "[ -~]{0,300}") {
                let _ = parse_query(&q);
                let _ = handle("/api/frame", &q, &mut Frame::default(), &Memory::default());
            }

            /// Any path with any query (good views among them) gets a success or a refusal of
            /// one line, never a panic.
            #[test]
            fn any_path_gets_an_answer(
                path in prop_oneof![
                    Just("/api/frame".to_string()),
                    Just("/api/scene-file".to_string()),
                    "/api/[a-z-]{0,12}",
                    "[ -~]{0,30}",
                ],
                raw in prop_oneof![Just(REF2.to_string()), "[ -~]{0,120}"],
                q in query(),
            ) {
                let q = format!("{raw}&{q}&points=50&size=16x12&chan=x&seq=1");
                let r = handle(&path, &q, &mut Frame::default(), &Memory::default());
                prop_assert!([200, 400, 404].contains(&r.status), "{} for {path}?{q}", r.status);
                if r.status != 200 {
                    let text = String::from_utf8(r.body).unwrap();
                    prop_assert!(!text.is_empty() && !text.contains('\n'), "{text:?}");
                }
            }
        }
    }
}
