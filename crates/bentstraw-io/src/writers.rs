//! Writing image points to files: CSV, JSON and PLY, chosen by the file's extension.
//!
//! Every format stores the coordinates exactly: the shortest decimal form that reads back as the
//! same `f64` (CSV, JSON), or the `f64` bytes themselves (PLY). No timing goes into a file, so the
//! same inputs give byte-identical files.
//!
//! - **CSV**: header `x,y,z,color`, then one point a row; `color` is the straw section's code
//!   (1 = red … 5 = blue). In white light a `wavelength` column follows `color`: the wavelength
//!   (nm) of the band of the spectrum the point's ray carried.
//! - **JSON**: one object, schema `bentstraw-image-points/1`:
//!   ```text
//!   {
//!     "schema": "bentstraw-image-points/1",
//!     "units": "m",
//!     "image_model": "course",
//!     "inputs": {"observer": [x, y, z], "straw": [xp, yp], "water_height": he,
//!                "n_water": n, "max_events": m, "min_points": N},
//!     "stats": {"rays_traced": R, "points": P, "hit_ratio": P / R, "grid_spacing": h,
//!               "points_per_color": {"red": .., "orange": .., "magenta": .., "green": .., "blue": ..}},
//!     "colors": [{"code": 1, "name": "red", "rgb": [1.0, 0.0, 0.0]}, ...],
//!     "point_fields": ["x", "y", "z", "color"],   (white light: "wavelength" after "color")
//!     "points": [[x, y, z, color], ...]
//!   }
//!   ```
//! - **PLY**: `binary_little_endian 1.0`, one `vertex` element with `double x, y, z`, `uchar red,
//!   green, blue` (the section's display colour) and `uchar color` (the section code); in white
//!   light `red, green, blue` are the wavelength's colour and `float wavelength` follows; the
//!   inputs are in `comment` lines. Opens in MeshLab, CloudCompare and Blender.

use std::io::{self, Write};
use std::path::Path;

use bentstraw_optics::apparent::{ApparentPoint, StereoImage};
use bentstraw_optics::camera::Camera;
use bentstraw_optics::image::ImagePoint;
use bentstraw_optics::sampling::ImageCloud;
use bentstraw_optics::scene::SECTION_COUNT;
use bentstraw_optics::text::clip_text;
use bentstraw_optics::world::{World, COLOR_COUNT, COLOR_RGB};
use bentstraw_optics::Vec3;
use rayon::prelude::*;
use serde::Serialize;

use crate::error::{Error, Result};
use crate::files::{shown, write_atomically};
use crate::parse::QUOTED_MAX;
use bentstraw_optics::record::InputValue;
use bentstraw_optics::setup::Setup;
use bentstraw_optics::spectrum::{wavelength_rgb8, white_bands};

/// A file format for image points.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PointFormat {
    /// Comma-separated values, header `x,y,z,color`.
    Csv,
    /// One JSON object with the inputs, the statistics and the points.
    Json,
    /// Stanford polygon format, coloured vertices.
    Ply,
}

impl PointFormat {
    /// The format named by `path`'s extension (`.csv`, `.json`, `.ply`, any case).
    pub fn from_path(path: &Path) -> Result<Self> {
        let ext = path
            .extension()
            .map(|e| e.to_string_lossy().to_ascii_lowercase());
        match ext.as_deref() {
            Some("csv") => Ok(PointFormat::Csv),
            Some("json") => Ok(PointFormat::Json),
            Some("ply") => Ok(PointFormat::Ply),
            Some(other) => Err(Error::Refused(format!(
                "output file {} has extension '.{}': expected .csv, .json or .ply",
                shown(path),
                clip_text(other, QUOTED_MAX)
            ))),
            None => Err(Error::Refused(format!(
                "output file {} has no extension: expected .csv, .json or .ply",
                shown(path)
            ))),
        }
    }

    /// Short upper-case name, for messages.
    pub fn name(self) -> &'static str {
        match self {
            PointFormat::Csv => "CSV",
            PointFormat::Json => "JSON",
            PointFormat::Ply => "PLY",
        }
    }
}

/// Most image points `simulate` traces with the course model: measured at about 220 bytes a point
/// for a CSV and 310 with the figure and the 3D view; at the limit a run takes 2.2–3.1 GB and
/// 27–38 s (two cores).
pub const MAX_POINTS: usize = 10_000_000;
/// Most image points with the eye or stereo model: about 600 bytes and 10–30 µs a point (two
/// cores), so at most ~1.2 GB and a minute.
pub const MAX_MODEL_POINTS: usize = 2_000_000;

/// The number of image points asked for, checked: at least one, and at most what the memory of
/// `models` allows ("course" for the course's points alone, else the models that will run).
pub fn check_points_asked(points: usize, models: &str) -> Result<()> {
    let (most, per_point) = match models {
        "course" => (MAX_POINTS, "about 300 bytes"),
        _ => (MAX_MODEL_POINTS, "about 600 bytes"),
    };
    if points == 0 {
        return Err(Error::Refused(
            "--points 0 is not allowed: ask for at least 1 image point".into(),
        ));
    }
    if points > most {
        return Err(Error::Refused(format!(
            "--points {points} is too many for the {models} model: at most {most} image points, as \
             each takes {per_point} of memory until the files are written"
        )));
    }
    Ok(())
}

/// A simulation's result with the inputs that produced it: everything a points file records.
#[derive(Clone, Copy, Debug)]
pub struct PointSet<'a> {
    /// The scene traced and its observer.
    pub scene: &'a Setup,
    /// The number of points asked for.
    pub min_points: usize,
    /// The apparent-position model's points (the course's are the cloud's own).
    pub model: ModelPoints<'a>,
    /// The traced points and ray count.
    pub cloud: &'a ImageCloud,
}

/// The points of one apparent-position model, as written.
#[derive(Clone, Copy, Debug)]
pub enum ModelPoints<'a> {
    /// The course's convention (`O + L·u0`): the cloud's image points.
    Course,
    /// The eye model: one apparent point per image point, with its two foci.
    Eye(&'a [ApparentPoint]),
    /// The stereo model: the points both eyes see.
    Stereo(&'a StereoImage),
}

impl ModelPoints<'_> {
    /// The model's name as on the command line.
    pub fn name(&self) -> &'static str {
        match self {
            ModelPoints::Course => "course",
            ModelPoints::Eye(_) => "eye",
            ModelPoints::Stereo(_) => "stereo",
        }
    }

    /// Names of the columns of one point in light of one wavelength, in the order the CSV and
    /// JSON write them (white light adds `wavelength` after `color`: [`PointSet::fields`]).
    pub fn fields(&self) -> &'static [&'static str] {
        match self {
            ModelPoints::Course => &["x", "y", "z", "color"],
            ModelPoints::Eye(_) => &[
                "x", "y", "z", "color", "s_h", "s_v", "s_h_kind", "s_v_kind", "gap",
            ],
            ModelPoints::Stereo(_) => &[
                "x",
                "y",
                "z",
                "color",
                "disparity",
                "vertical_disparity",
                "miss_distance",
                "gap",
            ],
        }
    }
}

impl PointSet<'_> {
    /// The model's name.
    pub fn image_model(&self) -> &'static str {
        self.model.name()
    }

    /// Names of the columns of one point, in the order the CSV and JSON write them: the model's,
    /// with `wavelength` after `color` in white light.
    pub fn fields(&self) -> Vec<&'static str> {
        let mut fields = self.model.fields().to_vec();
        if self.cloud.white {
            fields.insert(4, "wavelength");
        }
        fields
    }

    /// The points that have a position in this model, as image points at that position (for the
    /// figures), in order.
    pub fn placed_points(&self) -> Vec<ImagePoint> {
        let moved = |image: &ImagePoint, position: Option<Vec3>| {
            position.map(|position| ImagePoint { position, ..*image })
        };
        match self.model {
            ModelPoints::Course => self.cloud.points.clone(),
            ModelPoints::Eye(points) => points
                .iter()
                .filter_map(|p| moved(&p.image, p.position))
                .collect(),
            ModelPoints::Stereo(s) => s
                .points
                .iter()
                .filter_map(|p| moved(&p.image, p.position))
                .collect(),
        }
    }

    /// One row of values per point ([`PointSet::fields`]): each a number, a word, or missing.
    fn rows(&self) -> Vec<Vec<Value>> {
        let mut rows = self.model_rows();
        if self.cloud.white {
            let nms = white_bands().map(|b| b.nm);
            let images: Vec<&ImagePoint> = match self.model {
                ModelPoints::Course => self.cloud.points.iter().collect(),
                ModelPoints::Eye(points) => points.iter().map(|p| &p.image).collect(),
                ModelPoints::Stereo(s) => s.points.iter().map(|p| &p.image).collect(),
            };
            for (row, p) in rows.iter_mut().zip(images) {
                row.insert(
                    4,
                    p.band
                        .map_or(Value::Missing, |k| Value::Num(nms[k as usize])),
                );
            }
        }
        rows
    }

    /// One row of the model's values per point, in light of one wavelength.
    fn model_rows(&self) -> Vec<Vec<Value>> {
        let xyz = |p: Option<Vec3>| match p {
            Some(q) => [Value::Num(q.x), Value::Num(q.y), Value::Num(q.z)],
            None => [Value::Missing, Value::Missing, Value::Missing],
        };
        let num = |v: Option<f64>| v.map_or(Value::Missing, Value::Num);
        match self.model {
            ModelPoints::Course => self
                .cloud
                .points
                .iter()
                .map(|p| {
                    let mut r = xyz(Some(p.position)).to_vec();
                    r.push(Value::Code(p.color));
                    r
                })
                .collect(),
            ModelPoints::Eye(points) => points
                .iter()
                .map(|p| {
                    let mut r = xyz(p.position).to_vec();
                    r.extend([
                        Value::Code(p.image.color),
                        num(p.s_h.signed_distance()),
                        num(p.s_v.signed_distance()),
                        Value::Word(p.s_h.kind()),
                        Value::Word(p.s_v.kind()),
                        num(p.gap_to_course()),
                    ]);
                    r
                })
                .collect(),
            ModelPoints::Stereo(s) => s
                .points
                .iter()
                .map(|p| {
                    let mut r = xyz(p.position).to_vec();
                    r.extend([
                        Value::Code(p.image.color),
                        Value::Num(p.disparity),
                        Value::Num(p.vertical_disparity),
                        Value::Num(p.miss_distance),
                        num(p.gap_to_course()),
                    ]);
                    r
                })
                .collect(),
        }
    }
}

/// One value of a written point.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Value {
    /// A number, written in its shortest exact form (`inf` for an infinite focus).
    Num(f64),
    /// A colour code.
    Code(u8),
    /// A word (the kind of a focus).
    Word(&'static str),
    /// Not defined for this point: empty in CSV, `null` in JSON.
    Missing,
}

impl Value {
    fn csv(&self) -> String {
        match *self {
            Value::Num(v) => format!("{v}"),
            Value::Code(c) => c.to_string(),
            Value::Word(w) => w.to_string(),
            Value::Missing => String::new(),
        }
    }

    fn json(&self) -> String {
        match *self {
            Value::Num(v) if v.is_finite() => json(&v),
            Value::Num(v) => json(if v > 0.0 { "inf" } else { "-inf" }),
            Value::Code(c) => c.to_string(),
            Value::Word(w) => json(w),
            Value::Missing => "null".to_string(),
        }
    }
}

/// Writes `set` to `path` in `format`, all-or-nothing.
pub fn write_points(path: &Path, format: PointFormat, set: &PointSet) -> Result {
    write_atomically(path, |w| match format {
        PointFormat::Csv if matches!(set.model, ModelPoints::Course) => {
            write_csv(w, &set.cloud.points, set.cloud.white)
        }
        PointFormat::Csv => write_model_csv(w, set),
        PointFormat::Json => write_json(w, set),
        PointFormat::Ply => write_ply(w, set),
    })
}

/// The CSV of [`write_csv`] (light of one wavelength), gzip-compressed, to `path`
/// (all-or-nothing): the same rows in about 40 % of the bytes, read as they are by pandas, numpy,
/// R and `zcat`.
pub fn write_csv_gz(path: &Path, points: &[ImagePoint]) -> Result {
    write_atomically(path, |w| {
        let mut gz = flate2::write::GzEncoder::new(w, flate2::Compression::default());
        write_csv(&mut gz, points, false)?;
        gz.finish().map(|_| ())
    })
}

/// CSV: header `x,y,z,color` (`x,y,z,color,wavelength` for points of `white` light, the
/// wavelength of each point's band in nm), coordinates in the shortest form that reads back
/// exactly.
///
/// Rows are formatted with `ryu` (the shortest round-trip digits, as `{}` prints them, several times
/// faster) into blocks of bytes built in parallel and written in order: a million points in a
/// fraction of a second.
pub fn write_csv(w: &mut dyn Write, points: &[ImagePoint], white: bool) -> io::Result<()> {
    w.write_all(if white {
        b"x,y,z,color,wavelength\n"
    } else {
        b"x,y,z,color\n"
    })?;
    let nms = white_bands().map(|b| b.nm);
    const ROWS_PER_BLOCK: usize = 16_384;
    let blocks: Vec<Vec<u8>> = points
        .par_chunks(ROWS_PER_BLOCK)
        .map(|chunk| {
            let mut out = Vec::with_capacity(chunk.len() * 64);
            let mut digits = ryu::Buffer::new();
            for p in chunk {
                for v in [p.position.x, p.position.y, p.position.z] {
                    out.extend_from_slice(shortest(&mut digits, v).as_bytes());
                    out.push(b',');
                }
                out.push(b'0' + p.color);
                if white {
                    out.push(b',');
                    if let Some(k) = p.band {
                        out.extend_from_slice(shortest(&mut digits, nms[k as usize]).as_bytes());
                    }
                }
                out.push(b'\n');
            }
            out
        })
        .collect();
    for block in blocks {
        w.write_all(&block)?;
    }
    Ok(())
}

/// The shortest decimal form of `v` that reads back as the same `f64`, as Rust's `{}` writes it
/// (`ryu` writes `1.0` for one and `1e-7` for small numbers; both parse back exactly).
fn shortest(digits: &mut ryu::Buffer, v: f64) -> &str {
    if v.is_finite() {
        digits.format_finite(v)
    } else if v.is_nan() {
        "NaN"
    } else if v > 0.0 {
        "inf"
    } else {
        "-inf"
    }
}

/// CSV of a model's points: header from [`ModelPoints::fields`], missing values left empty.
pub fn write_model_csv(w: &mut dyn Write, set: &PointSet) -> io::Result<()> {
    writeln!(w, "{}", set.fields().join(","))?;
    for row in set.rows() {
        let cells: Vec<String> = row.iter().map(Value::csv).collect();
        writeln!(w, "{}", cells.join(","))?;
    }
    Ok(())
}

#[derive(Serialize)]
struct JsonColor {
    code: u8,
    name: &'static str,
    rgb: [f64; 3],
}

/// JSON: the inputs under their documented names, the statistics and the colour legend, then one
/// array of the model's fields a line.
pub fn write_json(w: &mut dyn Write, set: &PointSet) -> io::Result<()> {
    let (scene, cloud) = (set.scene, set.cloud);
    // Objects written by hand: their keys keep the documented order.
    let object = |pairs: Vec<(&str, String)>| {
        let fields: Vec<String> = pairs
            .into_iter()
            .map(|(k, v)| format!("{}:{v}", json(k)))
            .collect();
        format!("{{{}}}", fields.join(","))
    };
    let mut inputs: Vec<(&str, String)> = scene
        .inputs()
        .into_iter()
        .map(|i| (i.key, input_json(&i.value).to_string()))
        .collect();
    inputs.push(("min_points", json(&set.min_points)));
    let names = scene.colour_names();
    let counts = cloud.counts_per_code();
    let per_colour = scene
        .counted_codes()
        .iter()
        .map(|&c| (names[c as usize - 1], json(&counts[c as usize - 1])))
        .collect();
    let stats = object(vec![
        ("rays_traced", json(&cloud.rays_traced)),
        ("points", json(&cloud.points.len())),
        ("hit_ratio", json(&cloud.hit_ratio())),
        ("grid_spacing", json(&cloud.spacing)),
        ("points_per_color", object(per_colour)),
    ]);
    let colors: Vec<JsonColor> = (0..names.len())
        .map(|k| JsonColor {
            code: k as u8 + 1,
            name: names[k],
            rgb: COLOR_RGB[k],
        })
        .collect();
    write_json_object(w, set, &object(inputs), &stats, &json(&colors))
}

/// An input's value as JSON: a point or a pair as an array, a number, a name or text as a string.
pub(crate) fn input_json(value: &InputValue) -> serde_json::Value {
    match value {
        InputValue::Point(p) => p.to_array().into(),
        InputValue::Pair(p) => p.to_vec().into(),
        InputValue::Length(x) | InputValue::Number(x) => (*x).into(),
        InputValue::Count(n) => (*n).into(),
        InputValue::Name(s) | InputValue::Text(s) => s.as_str().into(),
    }
}

/// The JSON object of a point set: its schema, model, inputs, statistics and colours (each
/// already JSON text), then one array of the model's fields a line.
fn write_json_object(
    w: &mut dyn Write,
    set: &PointSet,
    inputs: &str,
    stats: &str,
    colors: &str,
) -> io::Result<()> {
    writeln!(w, "{{")?;
    writeln!(w, "  \"schema\": \"bentstraw-image-points/1\",")?;
    writeln!(w, "  \"units\": \"m\",")?;
    writeln!(w, "  \"image_model\": {},", json(set.image_model()))?;
    writeln!(w, "  \"inputs\": {inputs},")?;
    writeln!(w, "  \"stats\": {stats},")?;
    writeln!(w, "  \"colors\": {colors},")?;
    writeln!(w, "  \"point_fields\": {},", json(&set.fields()))?;
    writeln!(w, "  \"points\": [")?;
    let rows = set.rows();
    let n = rows.len();
    for (i, row) in rows.iter().enumerate() {
        let sep = if i + 1 < n { "," } else { "" };
        let cells: Vec<String> = row.iter().map(Value::json).collect();
        writeln!(w, "    [{}]{sep}", cells.join(","))?;
    }
    writeln!(w, "  ]")?;
    writeln!(w, "}}")
}

/// Compact JSON text of `value` (floats in their shortest exact form).
fn json<T: Serialize + ?Sized>(value: &T) -> String {
    serde_json::to_string(value).expect("plain data always serialises")
}

/// The 8-bit display colour of colour code `code` (1..=5 a straw's sections, 6..=8 a coin, a
/// card and its picture).
pub fn section_rgb8(code: u8) -> [u8; 3] {
    COLOR_RGB[code as usize - 1].map(|c| (c * 255.0).round() as u8)
}

/// PLY, binary little-endian: `double x, y, z`, `uchar red, green, blue`, `uchar color`; the
/// header's comments give the inputs under their documented names.
pub fn write_ply(w: &mut dyn Write, set: &PointSet) -> io::Result<()> {
    let scene = set.scene;
    let o = scene.observer;
    // The header is ASCII by the format's rules.
    writeln!(w, "ply")?;
    writeln!(w, "format binary_little_endian 1.0")?;
    let of = scene
        .subject()
        .map_or(String::new(), |s| format!(" of {s}"));
    writeln!(
        w,
        "comment bentstraw: virtual image points{of} ({} model), metres",
        set.image_model()
    )?;
    writeln!(w, "comment observer {} {} {}", o.x, o.y, o.z)?;
    // A comment is one line: the scene's whole text is left out.
    let inputs: Vec<String> = scene
        .inputs()
        .iter()
        .filter(|i| i.key != "observer")
        .filter_map(|i| Some(format!("{} {}", i.key, i.value.bare()?)))
        .collect();
    writeln!(w, "comment {}", inputs.join(" "))?;
    writeln!(
        w,
        "comment rays_traced {} min_points {}",
        set.cloud.rays_traced, set.min_points
    )?;
    let legend: Vec<String> = scene
        .colour_names()
        .iter()
        .enumerate()
        .map(|(k, n)| format!("{} {n}", k + 1))
        .collect();
    writeln!(
        w,
        "comment color: {} {}",
        scene.code_legend(),
        legend.join(", ")
    )?;
    write_ply_vertices(w, &set.placed_points(), set.cloud.white)
}

/// The PLY header's vertex element and the end of the header, then the points' binary records:
/// `double x, y, z`, `uchar red, green, blue` (the colour code's display colour), `uchar color`;
/// for points of `white` light, the colour of each point's wavelength and `float wavelength`
/// (nm) after them.
fn write_ply_vertices(w: &mut dyn Write, points: &[ImagePoint], white: bool) -> io::Result<()> {
    writeln!(w, "element vertex {}", points.len())?;
    for axis in ["x", "y", "z"] {
        writeln!(w, "property double {axis}")?;
    }
    for channel in ["red", "green", "blue", "color"] {
        writeln!(w, "property uchar {channel}")?;
    }
    if white {
        writeln!(w, "property float wavelength")?;
    }
    writeln!(w, "end_header")?;
    let bands = white_bands();
    let mut record = [0u8; 32];
    let size = if white { 32 } else { 28 };
    for p in points {
        let q = p.position;
        record[0..8].copy_from_slice(&q.x.to_le_bytes());
        record[8..16].copy_from_slice(&q.y.to_le_bytes());
        record[16..24].copy_from_slice(&q.z.to_le_bytes());
        let nm = p.band.map(|k| bands[k as usize].nm);
        record[24..27].copy_from_slice(&nm.map_or(section_rgb8(p.color), wavelength_rgb8));
        record[27] = p.color;
        record[28..32].copy_from_slice(&(nm.unwrap_or(f64::NAN) as f32).to_le_bytes());
        w.write_all(&record[..size])?;
    }
    Ok(())
}

/// Writes one colour code per pixel centre, row-major: `row,col,color`.
pub fn write_raw_codes(path: &Path, camera: &Camera, codes: &[u8]) -> Result {
    let w = camera.width as usize;
    write_atomically(path, |out| {
        writeln!(out, "row,col,color")?;
        for (k, code) in codes.iter().enumerate() {
            writeln!(out, "{},{},{code}", k / w, k % w)?;
        }
        Ok(())
    })
}

/// How many colour codes a raw Fresnel file gives weights for: the five sections where the world
/// holds straws alone, else every code (coins, cards and pictures). `render --raw` and the Python
/// package's raw weights both follow it.
pub fn raw_weight_count(world: &World) -> usize {
    if world.color_codes() <= SECTION_COUNT {
        SECTION_COUNT
    } else {
        COLOR_COUNT
    }
}

/// Writes the weights of each pixel centre's ray on each colour code, row-major:
/// `row,col,w1,…,wN`, each in the shortest form that reads back as the same `f64` (zeros as `0`).
pub fn write_raw_weights<const N: usize>(
    path: &Path,
    camera: &Camera,
    weights: &[[f64; N]],
) -> Result {
    let w = camera.width as usize;
    let mut digits = ryu::Buffer::new();
    write_atomically(path, |out| {
        write!(out, "row,col")?;
        for k in 1..=N {
            write!(out, ",w{k}")?;
        }
        writeln!(out)?;
        for (k, px) in weights.iter().enumerate() {
            write!(out, "{},{}", k / w, k % w)?;
            for v in px {
                if *v == 0.0 {
                    write!(out, ",0")?;
                } else {
                    write!(out, ",{}", digits.format_finite(*v))?;
                }
            }
            writeln!(out)?;
        }
        Ok(())
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    fn point(x: f64, y: f64, z: f64, color: u8) -> ImagePoint {
        ImagePoint {
            position: Vec3::new(x, y, z),
            color,
            direction: Vec3::X,
            path_length: 1.0,
            straw_point: Vec3::ZERO,
            events: 0,
            band: None,
        }
    }

    fn sample() -> (Setup, ImageCloud) {
        let scene = bentstraw_optics::scene::Scene::with_defaults(0.02, 0.01, 0.15).unwrap();
        let cloud = ImageCloud {
            points: vec![
                point(0.1 + 0.2, -1e-7, 0.123_456_789_012_345_68, 1),
                point(1.0 / 3.0, 2.0f64.sqrt(), -0.0, 5),
                point(5e-324, 1e300, 0.05, 3),
            ],
            rays_traced: 12,
            spacing: 0.001,
            white: false,
        };
        (Setup::assignment(scene, Vec3::new(0.0, 0.1, 0.1)), cloud)
    }

    fn set<'a>(scene: &'a Setup, cloud: &'a ImageCloud) -> PointSet<'a> {
        PointSet {
            scene,
            min_points: 3,
            model: ModelPoints::Course,
            cloud,
        }
    }

    /// White light's points: the same columns with each point's wavelength after its colour code
    /// (the middle of its band), in the CSV (both writers), the JSON and the PLY, whose colour
    /// is the wavelength's.
    #[test]
    fn white_light_points_carry_their_wavelength() {
        let (scene, mut cloud) = sample();
        cloud.white = true;
        for (p, band) in cloud.points.iter_mut().zip([0u8, 3, 7]) {
            p.band = Some(band);
        }
        let nms = [405.0, 555.0, 755.0];
        let set = set(&scene, &cloud);
        let mut fast = Vec::new();
        write_csv(&mut fast, &cloud.points, true).unwrap();
        let mut rows = Vec::new();
        write_model_csv(&mut rows, &set).unwrap();
        for csv in [fast, rows] {
            let text = String::from_utf8(csv).unwrap();
            let mut lines = text.lines();
            assert_eq!(lines.next(), Some("x,y,z,color,wavelength"));
            for (line, nm) in lines.zip(nms) {
                let f: Vec<&str> = line.split(',').collect();
                assert_eq!(f.len(), 5, "{line}");
                assert_eq!(f[4].parse::<f64>().unwrap(), nm, "{line}");
            }
        }
        let mut out = Vec::new();
        write_json(&mut out, &set).unwrap();
        let v: serde_json::Value = serde_json::from_slice(&out).unwrap();
        assert_eq!(
            v["point_fields"],
            json!(["x", "y", "z", "color", "wavelength"])
        );
        for (row, nm) in v["points"].as_array().unwrap().iter().zip(nms) {
            assert_eq!(row[4].as_f64(), Some(nm));
        }
        let mut out = Vec::new();
        write_ply(&mut out, &set).unwrap();
        let end = b"end_header\n";
        let at = out.windows(end.len()).position(|w| w == end).unwrap() + end.len();
        let header = std::str::from_utf8(&out[..at]).unwrap();
        assert!(header.contains("property uchar color\nproperty float wavelength\nend_header"));
        let body = &out[at..];
        assert_eq!(body.len(), 32 * cloud.points.len());
        for ((rec, p), nm) in body.chunks(32).zip(&cloud.points).zip(nms) {
            assert_eq!(rec[24..27], wavelength_rgb8(nm));
            assert_eq!(rec[27], p.color);
            assert_eq!(
                f32::from_le_bytes(rec[28..32].try_into().unwrap()),
                nm as f32
            );
        }
    }

    #[test]
    fn format_follows_the_extension() {
        assert_eq!(
            PointFormat::from_path(Path::new("a/b.csv")).unwrap(),
            PointFormat::Csv
        );
        assert_eq!(
            PointFormat::from_path(Path::new("b.JSON")).unwrap(),
            PointFormat::Json
        );
        assert_eq!(
            PointFormat::from_path(Path::new("b.ply")).unwrap(),
            PointFormat::Ply
        );
        let e = PointFormat::from_path(Path::new("b.txt"))
            .unwrap_err()
            .to_string();
        assert!(e.contains("b.txt") && e.contains(".txt"), "{e}");
        assert!(PointFormat::from_path(Path::new("points")).is_err());
    }

    #[test]
    fn csv_reads_back_bit_exactly() {
        let (scene, cloud) = sample();
        let mut out = Vec::new();
        write_csv(&mut out, &set(&scene, &cloud).cloud.points, false).unwrap();
        let text = String::from_utf8(out).unwrap();
        let mut lines = text.lines();
        assert_eq!(lines.next(), Some("x,y,z,color"));
        for (line, p) in lines.zip(&cloud.points) {
            let f: Vec<&str> = line.split(',').collect();
            let q = p.position;
            for (s, v) in f[..3].iter().zip([q.x, q.y, q.z]) {
                assert_eq!(s.parse::<f64>().unwrap().to_bits(), v.to_bits(), "{s}");
            }
            assert_eq!(f[3].parse::<u8>().unwrap(), p.color);
        }
        assert_eq!(text.lines().count(), 1 + cloud.points.len());
    }

    #[test]
    fn json_is_valid_and_exact() {
        let (scene, cloud) = sample();
        let mut out = Vec::new();
        write_json(&mut out, &set(&scene, &cloud)).unwrap();
        let v: serde_json::Value = serde_json::from_slice(&out).unwrap();
        assert_eq!(v["schema"], "bentstraw-image-points/1");
        assert_eq!(v["inputs"]["water_height"], 0.15);
        assert_eq!(v["stats"]["points_per_color"]["blue"], 1);
        assert_eq!(v["stats"]["rays_traced"], 12);
        let pts = v["points"].as_array().unwrap();
        assert_eq!(pts.len(), cloud.points.len());
        for (j, p) in pts.iter().zip(&cloud.points) {
            let q = p.position;
            for (k, c) in [q.x, q.y, q.z].into_iter().enumerate() {
                assert_eq!(j[k].as_f64().unwrap().to_bits(), c.to_bits());
            }
            assert_eq!(j[3].as_u64().unwrap(), p.color as u64);
        }
    }

    #[test]
    fn ply_header_and_records_match() {
        let (scene, cloud) = sample();
        let mut out = Vec::new();
        write_ply(&mut out, &set(&scene, &cloud)).unwrap();
        let end = b"end_header\n";
        let at = out.windows(end.len()).position(|w| w == end).unwrap() + end.len();
        let header = std::str::from_utf8(&out[..at]).unwrap();
        assert!(header.starts_with("ply\nformat binary_little_endian 1.0\n"));
        assert!(header.is_ascii());
        assert!(header.contains("element vertex 3\n"));
        assert!(header.contains("property double x\nproperty double y\nproperty double z\n"));
        assert!(header.contains("property uchar red\nproperty uchar green\nproperty uchar blue\n"));
        let body = &out[at..];
        assert_eq!(body.len(), 28 * cloud.points.len());
        for (rec, p) in body.chunks(28).zip(&cloud.points) {
            let x = f64::from_le_bytes(rec[0..8].try_into().unwrap());
            let z = f64::from_le_bytes(rec[16..24].try_into().unwrap());
            assert_eq!(x.to_bits(), p.position.x.to_bits());
            assert_eq!(z.to_bits(), p.position.z.to_bits());
            assert_eq!(rec[27], p.color);
        }
        // Section 5 is blue, section 2 orange (the sections' display colours).
        assert_eq!(section_rgb8(5), [0, 0, 255]);
        assert_eq!(section_rgb8(2), [237, 177, 32]);
    }
}
