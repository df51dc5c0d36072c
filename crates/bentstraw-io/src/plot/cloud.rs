//! The classic figure: the image points in three views (front, side, from above) in a 2 × 2
//! grid under its heading, the legend in the fourth cell.

use std::path::Path;

use bentstraw_optics::image::ImagePoint;

use bentstraw_optics::setup::Setup;
use bentstraw_optics::Vec3;
use plotters::prelude::*;

use super::axis_box::{axis_box, AxisBox};
use super::dots::{draw_dots, visible_dots};
use super::figure::{figure_bytes, AreaOn, FigureFormat, FIGURE_WIDTH};
use super::heading::Heading;
use super::legend::legend_entries;
use super::legend::{common_legend, draw_legend_cell, LegendMark};
use super::numbers::{degrees, whole};
use super::observer::draw_observer;
use super::panel::{grid, Panel};
use super::scales::{draw_axis_labels, draw_panes};
use super::text::register_font;
use super::views::{figure_views, observer_direction, ViewDirection};
use super::wireframe::{draw_straw_outline, draw_water};
use crate::error::Result;
use crate::files;

/// Height of a cell of the three-view figure (px): caption, box, scales.
pub(crate) const CELL_HEIGHT: i32 = 600;

/// The three panels of the classic figure in a 2 × 2 grid under the heading (the fourth cell holds
/// the legend).
pub(crate) fn layout(bx: &AxisBox, views: &[(ViewDirection, Vec<String>)], top: i32) -> Vec<Panel> {
    grid(bx, views, top, 2, CELL_HEIGHT, 2)
}

/// The legend's cell of the classic figure: (left, top, width, height).
pub(crate) fn legend_cell(top: i32) -> (i32, i32, i32, i32) {
    let w = FIGURE_WIDTH as i32 / 2;
    (w, top + CELL_HEIGHT, w, CELL_HEIGHT)
}

/// The size of the classic figure under `heading`.
pub(crate) fn three_view_size(heading: &Heading) -> (u32, u32) {
    (FIGURE_WIDTH, (heading.height() + 2 * CELL_HEIGHT) as u32)
}

/// Draws the classic three-view figure of `points` seen from `observer` into `path`: PNG, SVG or
/// PDF by its extension.
pub fn write_cloud_figure(
    path: &Path,
    scene: &Setup,
    observer: Vec3,
    points: &[ImagePoint],
    title: &str,
) -> Result {
    let bytes = render_cloud_figure(path, scene, observer, points, title)?;
    files::write_bytes(path, &bytes)
}

/// The classic figure as the bytes of its file (format by `path`'s extension).
pub(crate) fn render_cloud_figure(
    path: &Path,
    scene: &Setup,
    observer: Vec3,
    points: &[ImagePoint],
    title: &str,
) -> Result<Vec<u8>> {
    register_font();
    let heading = cloud_heading(observer, points.len(), title);
    let size = three_view_size(&heading);
    figure_bytes(
        path,
        FigureFormat::of(path)?,
        size,
        |root| draw_cloud_figure(root, scene, observer, points, &heading),
        |root| draw_cloud_figure(root, scene, observer, points, &heading),
    )
}

/// The heading of the classic figure: `title`, then the count, the observer's direction, the scale.
pub(crate) fn cloud_heading(observer: Vec3, n: usize, title: &str) -> Heading {
    let o = observer_direction(observer);
    Heading::new(
        title,
        &format!(
            "{n} image points · the observer looks from azimuth {}°, elevation {}° · lengths in \
             metres, one scale for both axes of a panel",
            whole(degrees(o.azimuth)),
            whole(o.elevation.to_degrees())
        ),
    )
}

/// The classic figure on any backend.
fn draw_cloud_figure<DB: DrawingBackend>(
    root: &AreaOn<DB>,
    scene: &Setup,
    observer: Vec3,
    points: &[ImagePoint],
    heading: &Heading,
) -> Result<(), String> {
    let e = |x: DrawingAreaErrorKind<DB::ErrorType>| x.to_string();
    root.fill(&WHITE).map_err(e)?;
    heading.draw(root).map_err(e)?;
    let bx = axis_box(scene, observer, points);
    let panels = layout(&bx, &figure_views(observer), heading.height());
    for p in &panels {
        // Back to front: panes, the far half of the water, the straw's outline, the points from far
        // to near, the near half of the water, the scales and the observer.
        draw_panes(root, p, &bx).map_err(e)?;
        draw_water(root, &p.proj, scene, false).map_err(e)?;
        draw_straw_outline(root, &p.proj, scene).map_err(e)?;
        let dots = visible_dots(p, &[], points);
        draw_dots(root, &dots).map_err(e)?;
        draw_water(root, &p.proj, scene, true).map_err(e)?;
        draw_axis_labels(root, p, &bx).map_err(e)?;
        draw_observer(root, p, &bx, observer, &dots).map_err(e)?;
    }
    // The codes the scene's objects show (a straw's sections, coins, cards, pictures), or the
    // bands of white light.
    let by = if points.iter().any(|p| p.band.is_some()) {
        "wavelength"
    } else {
        scene.code_word()
    };
    let mut items = vec![(LegendMark::None, format!("image points by {by}:"))];
    items.extend(legend_entries(scene, points).into_iter().map(|e| {
        (
            LegendMark::Swatch(e.rgb),
            format!("{}: {}", e.name, e.count),
        )
    }));
    items.extend(common_legend(scene, bx.observer_inside));
    draw_legend_cell(root, legend_cell(heading.height()), &items).map_err(e)?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::plot::tests::{decode, panels_have, panels_of, png_of, point};
    use crate::plot::{counts, section_rgb8};
    use bentstraw_optics::sampling::sample_image;
    use bentstraw_optics::scene::{Scene, REFERENCES, SECTION_HEIGHT, STRAW_RADIUS};
    use bentstraw_optics::sketch::CIRCLE_SEGMENTS;

    #[test]
    fn figure_is_a_png_of_the_stated_size_showing_exactly_the_colours_present() {
        let scene = Setup::assignment(Scene::with_defaults(0.0, 0.0, 0.1).unwrap(), Vec3::ZERO);
        // Sections 1, 2 and 4 only, on the straw's surface.
        let points: Vec<ImagePoint> = (0..300)
            .map(|i| {
                let t = i as f64 * 0.1;
                let color = [1u8, 2, 4][i % 3];
                let z = (color as f64 - 0.5) * SECTION_HEIGHT;
                point(
                    Vec3::new(STRAW_RADIUS * t.cos(), STRAW_RADIUS * t.sin(), z),
                    color,
                )
            })
            .collect();
        let observer = Vec3::new(0.1, 0.0, 0.1);
        let img = png_of(&scene, observer, &points);
        let heading = cloud_heading(observer, points.len(), "t");
        assert_eq!(img.dimensions(), three_view_size(&heading));
        let panels = panels_of(&scene, observer, &points);
        for code in [1, 2, 4] {
            assert!(
                panels_have(&img, &panels, section_rgb8(code)),
                "colour {code} missing"
            );
        }
        for code in [3, 5] {
            assert!(
                !panels_have(&img, &panels, section_rgb8(code)),
                "colour {code} drawn without points"
            );
        }
    }

    #[test]
    fn reference_figure_is_written_and_shows_every_colour_seen() {
        let r = REFERENCES[1];
        let scene = Setup::assignment(r.scene(1.333), r.observer);
        let cloud = sample_image(&scene.world, r.observer, 2000, &|_| {});
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("ref.png");
        write_cloud_figure(&path, &scene, r.observer, &cloud.points, "Reference 2").unwrap();
        let img = decode(&std::fs::read(&path).unwrap());
        let panels = panels_of(&scene, r.observer, &cloud.points);
        let n = counts(&cloud.points);
        for code in 1..=5u8 {
            if n[(code - 1) as usize] > 0 {
                assert!(
                    panels_have(&img, &panels, section_rgb8(code)),
                    "colour {code} missing"
                );
            }
        }
        // Nothing else is left in the folder (the write is atomic).
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
        if let Ok(look) = std::env::var("BENTSTRAW_LOOK") {
            std::fs::copy(&path, Path::new(&look).join("cloud2.png")).unwrap();
        }
    }

    #[test]
    fn empty_glass_and_no_points_still_draw() {
        let scene = Setup::assignment(Scene::with_defaults(0.01, 0.0, 0.0).unwrap(), Vec3::ZERO);
        let observer = Vec3::new(0.0, -0.2, 0.3);
        let img = png_of(&scene, observer, &[]);
        assert_eq!(img.width(), FIGURE_WIDTH);
        assert_eq!(scene.wireframe().1.len(), 2 * CIRCLE_SEGMENTS);
    }

    #[test]
    fn same_inputs_give_the_same_bytes() {
        let r = REFERENCES[2];
        let scene = Setup::assignment(r.scene(1.333), r.observer);
        let cloud = sample_image(&scene.world, r.observer, 3000, &|_| {});
        // (A PDF's objects come out in an order that varies from run to run: not compared.)
        for name in ["a.png", "a.svg"] {
            let f =
                || render_cloud_figure(Path::new(name), &scene, r.observer, &cloud.points, "again");
            assert!(
                f().unwrap() == f().unwrap(),
                "{name}: two renderings differ"
            );
        }
    }

    #[test]
    fn unwritable_path_is_an_error_not_a_panic() {
        let scene = Setup::assignment(Scene::with_defaults(0.0, 0.0, 0.1).unwrap(), Vec3::ZERO);
        let path = Path::new("/nonexistent-folder/fig.png");
        assert!(write_cloud_figure(path, &scene, Vec3::new(0.1, 0.0, 0.1), &[], "t").is_err());
    }
}
