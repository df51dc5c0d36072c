//! The gallery's part of the report: for each scene file its picture, its image points and its
//! ray diagram.

use bentstraw_optics::view::{DEFAULT_POINTS, DEFAULT_PRUNE};
use std::path::Path;

use bentstraw_optics::sampling::sample_image;
use bentstraw_optics::scene::DEFAULT_MAX_EVENTS;
use bentstraw_optics::shading::shaded_picture;
use bentstraw_optics::shading::{Backdrop, ShadingMode, ShadingOptions};
use rayon::prelude::*;

use crate::camera::{scene_camera, CameraSpec};
use crate::error::Result;
use crate::gallery::{lesson_notes, opening_comment, GALLERY};
use crate::pictures::png_bytes;
use crate::ray_diagram::{write_ray_diagram, Diagram};
use crate::report::{Figure, Section};
use crate::scene_input::gallery_setup;
use crate::words::{self, Lang};
use crate::{files, plot};
use bentstraw_optics::setup::Setup;

/// The files the gallery writes into the report's folder.
pub fn gallery_files() -> Vec<String> {
    GALLERY
        .iter()
        .flat_map(|(stem, _)| {
            [
                format!("gallery_{stem}_observer.png"),
                format!("gallery_{stem}_points.svg"),
                format!("gallery_{stem}_rays.svg"),
            ]
        })
        .collect()
}

/// The report's sections of the gallery, one per scene, its files written into `out`; `done` is
/// called as each scene's section is ready (for a progress bar); its words in `lang`.
pub fn gallery_sections(out: &Path, lang: Lang, done: &(dyn Fn() + Sync)) -> Vec<Section> {
    GALLERY
        .par_iter()
        .map(|(stem, text)| {
            let section =
                match gallery_setup(&format!("scenes/{stem}.toml"), text, DEFAULT_MAX_EVENTS) {
                    Ok(world) => scene_section(out, lang, stem, text, &world),
                    Err(e) => Section {
                        title: lang.fill(words::GALLERY, &[&stem]),
                        figures: vec![Figure {
                            error: Some(e.to_string()),
                            ..Figure::image(&format!("gallery_{stem}_observer.png"), "")
                        }],
                        notes: vec![],
                        side_by_side: false,
                        printed: false,
                        table: vec![],
                    },
                };
            done();
            section
        })
        .collect()
}

/// The section of one gallery scene: its picture and its image points.
fn scene_section(out: &Path, lang: Lang, stem: &str, text: &str, world: &Setup) -> Section {
    let picture_file = format!("gallery_{stem}_observer.png");
    let points_file = format!("gallery_{stem}_points.svg");
    let mut picture = Figure::image(&picture_file, &lang.fill(words::GALLERY_PICTURE, &[&stem]));
    picture.error = write_picture(&out.join(&picture_file), world)
        .err()
        .map(|e| e.to_string());
    let cloud = sample_image(&world.world, world.observer, DEFAULT_POINTS, &|_| {});
    let title = lang.fill(words::GALLERY_POINTS_TITLE, &[&world.name()]);
    let mut points = Figure::image(
        &points_file,
        &lang.fill(words::GALLERY_POINTS, &[&stem, &cloud.points.len()]),
    );
    points.error = plot::write_cloud_figure(
        &out.join(&points_file),
        world,
        world.observer,
        &cloud.points,
        &title,
    )
    .err()
    .map(|e| e.to_string());
    let rays_file = format!("gallery_{stem}_rays.svg");
    let mut rays = Figure::image(&rays_file, lang.of(words::GALLERY_RAYS));
    let diagram = Diagram::new(&world.world, world.observer, &cloud.points);
    rays.error = write_ray_diagram(
        &out.join(&rays_file),
        world,
        &diagram,
        &lang.fill(words::RAY_DIAGRAM_OF, &[&world.name()]),
        lang,
    )
    .err()
    .map(|e| e.to_string());
    // Its lesson's title and words when it has one (every gallery scene has), else its comment.
    let (title, notes) = lesson_notes(text, lang)
        .unwrap_or_else(|| (stem.replace('-', " "), vec![opening_comment(text)]));
    Section {
        title: lang.fill(words::GALLERY, &[&title]),
        figures: vec![picture, points, rays],
        notes,
        side_by_side: true,
        printed: false,
        table: vec![],
    }
}

/// The scene's picture from its own observer, 1000x750, Fresnel, as a PNG: in white light where
/// an index depends on the wavelength (what such a scene is there to show).
pub fn write_picture(path: &Path, world: &Setup) -> Result {
    let camera = scene_camera(
        world,
        &CameraSpec {
            target: None,
            fov: None,
            size: Some((1000, 750)),
        },
    )?;
    let options = ShadingOptions {
        mode: ShadingMode::Fresnel {
            prune_below: DEFAULT_PRUNE,
        },
        backdrop: Backdrop::Checker,
        samples: 3,
        adaptive: true,
        outline: false,
        white: !world.world.white_light().is_empty(),
    };
    files::write_bytes(
        path,
        &png_bytes(&shaded_picture(&world.world, &camera, &options))?,
    )
}
