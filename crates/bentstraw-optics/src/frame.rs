//! One frame of a live view, in one call: the observer's picture for people and the image points
//! of every object with the kind of light path that made each, into buffers kept from frame to
//! frame, for the assignment's glass or any scene file's world.
//!
//! The explorer redraws a frame at every input event and `render` draws one picture through the
//! same call, so both get the same speed and the same pixels.

use crate::parallel::*;

use crate::camera::Camera;
use crate::image::ImagePoint;
use crate::light_path_type::LightPathType;
use crate::sampling::{light_path_types, sample_image_until};
use crate::shading::{shaded_picture_into, RgbPicture, ShadingBuffers, ShadingOptions};
use crate::world::World;

/// What one frame shows, beside the scene.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FrameRequest {
    /// The observer's camera (its eye is the observer).
    pub camera: Camera,
    /// How the picture is shaded (mode, backdrop, anti-aliasing, outline).
    pub shading: ShadingOptions,
    /// At least this many image points (0: no points, the picture only).
    pub min_points: usize,
}

/// A frame: the picture and the image points, with the buffers they are drawn into.
#[derive(Clone, Debug, Default)]
pub struct Frame {
    /// What the eye sees.
    pub picture: RgbPicture,
    /// The straw's image points (course convention), in sampling order.
    pub points: Vec<ImagePoint>,
    /// The light path of each point, same order.
    pub paths: Vec<LightPathType>,
    /// Rays traced to find the points (coarse levels included).
    pub rays_traced: u64,
    shading: ShadingBuffers,
}

impl Frame {
    /// A counter of the rows of the picture drawn so far, out of twice its height (see
    /// [`ShadingBuffers::progress`]).
    pub fn picture_progress(&self) -> std::sync::Arc<std::sync::atomic::AtomicU64> {
        self.shading.progress()
    }

    /// A flag another thread may set to abandon the frame being drawn (its input has moved on):
    /// the picture's remaining rows are skipped, so a frame drawn while it was set is incomplete
    /// and must be thrown away. Drawing does not clear it (see [`ShadingBuffers::stop_flag`]).
    pub fn stop_flag(&self) -> std::sync::Arc<std::sync::atomic::AtomicBool> {
        self.shading.stop_flag()
    }

    /// An empty frame with `stop` as its stop flag: a one-off picture (an export) drawn in its
    /// own buffers, freed afterwards, yet abandoned by the same flag as the frame it came from.
    pub fn with_stop_flag(stop: std::sync::Arc<std::sync::atomic::AtomicBool>) -> Frame {
        Frame {
            shading: ShadingBuffers::with_stop_flag(stop),
            ..Frame::default()
        }
    }

    /// Points per kind of light path, sorted by kind (direct first, then by entry face and
    /// number of total reflections).
    pub fn path_counts(&self) -> Vec<(LightPathType, usize)> {
        let mut counts: Vec<(LightPathType, usize)> = Vec::new();
        for p in &self.paths {
            match counts.binary_search_by(|(k, _)| k.cmp(p)) {
                Ok(i) => counts[i].1 += 1,
                Err(i) => counts.insert(i, (*p, 1)),
            }
        }
        counts
    }
}

/// Draws the frame of `world` asked for by `request` into `frame`: its picture, and the image
/// points of every object with the kind of light path that made each. The picture and the points
/// are computed side by side (each in parallel itself), the points by
/// [`crate::sampling::sample_image`], so they are exactly `simulate`'s for the same inputs.
pub fn draw_frame(world: &World, request: &FrameRequest, frame: &mut Frame) {
    let Frame {
        picture,
        points,
        paths,
        rays_traced,
        shading,
    } = frame;
    let observer = request.camera.eye;
    // The picture's stop flag abandons the points too (a frame given up is thrown away whole).
    let stop = shading.stop_flag();
    join(
        || shaded_picture_into(world, &request.camera, &request.shading, shading, picture),
        || {
            points.clear();
            paths.clear();
            *rays_traced = 0;
            if request.min_points == 0 {
                return;
            }
            let white = request.shading.white;
            let Some(cloud) =
                sample_image_until(world, observer, request.min_points, white, &|_| {}, &stop)
            else {
                return;
            };
            *points = cloud.points;
            *rays_traced = cloud.rays_traced;
            let ray = |p: &ImagePoint| (p.direction, p.band);
            light_path_types(world, observer, points, ray, paths, &stop);
        },
    );
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::light_path_type::Entry;
    use crate::scene::{REFERENCES, SCENE_CENTRE, WATER_INDEX};
    use crate::shading::{Backdrop, ShadingMode};

    fn request(observer: crate::Vec3, min_points: usize) -> FrameRequest {
        FrameRequest {
            camera: Camera::new(observer, SCENE_CENTRE, 48, 36, 1.4),
            shading: ShadingOptions {
                mode: ShadingMode::Course,
                backdrop: Backdrop::Checker,
                samples: 1,
                adaptive: true,
                outline: true,
                white: false,
            },
            min_points,
        }
    }

    /// Each point's path kind agrees with its own trace: no event means direct, and a point
    /// reached through the water has at least one refraction besides its total reflections.
    #[test]
    fn path_kinds_agree_with_the_points_events() {
        let mut frame = Frame::default();
        for r in REFERENCES {
            let scene = r.scene(WATER_INDEX);
            draw_frame(
                &World::assignment(&scene),
                &request(r.observer, 2000),
                &mut frame,
            );
            assert!(frame.points.len() >= 2000);
            assert_eq!(frame.points.len(), frame.paths.len());
            for (p, k) in frame.points.iter().zip(&frame.paths) {
                if p.events == 0 {
                    assert_eq!(k.entry, Entry::Direct);
                } else {
                    assert_ne!(k.entry, Entry::Direct);
                    assert!(k.total_reflections < p.events, "{p:?} {k:?}");
                }
            }
            let counts = frame.path_counts();
            assert_eq!(
                counts.iter().map(|c| c.1).sum::<usize>(),
                frame.points.len()
            );
            assert!(counts.windows(2).all(|w| w[0].0 < w[1].0));
        }
    }

    /// Reference 3 (eye above the rim) sees the straw through the surface and, beside the glass,
    /// pieces made by total reflection at the wall: both kinds must be found.
    #[test]
    fn reference_three_has_top_and_totally_reflected_paths() {
        let r = REFERENCES[2];
        let mut frame = Frame::default();
        draw_frame(
            &World::assignment(&r.scene(WATER_INDEX)),
            &request(r.observer, 5000),
            &mut frame,
        );
        let counts = frame.path_counts();
        assert!(counts
            .iter()
            .any(|(k, _)| k.entry == Entry::Top && k.total_reflections == 0));
        assert!(counts.iter().any(|(k, _)| k.total_reflections > 0));
    }

    /// A frame whose stop flag is set draws no row of its picture (the live view abandons it);
    /// once cleared, the same buffers draw the whole picture again.
    #[test]
    fn a_stopped_frame_skips_its_picture() {
        let r = REFERENCES[1];
        let scene = r.scene(WATER_INDEX);
        let mut frame = Frame::default();
        frame
            .stop_flag()
            .store(true, std::sync::atomic::Ordering::Relaxed);
        draw_frame(
            &World::assignment(&scene),
            &request(r.observer, 0),
            &mut frame,
        );
        let black = |f: &Frame| {
            f.picture
                .pixels
                .chunks(3)
                .filter(|c| c == &[0, 0, 0])
                .count()
        };
        // The untouched rows stay black.
        assert!(
            black(&frame) > 48 * 36 / 2,
            "{} black pixels",
            black(&frame)
        );
        frame
            .stop_flag()
            .store(false, std::sync::atomic::Ordering::Relaxed);
        draw_frame(
            &World::assignment(&scene),
            &request(r.observer, 0),
            &mut frame,
        );
        assert_eq!(black(&frame), 0);
    }

    /// No points asked: none given, and the picture is still drawn.
    #[test]
    fn picture_only() {
        let r = REFERENCES[0];
        let mut frame = Frame::default();
        draw_frame(
            &World::assignment(&r.scene(WATER_INDEX)),
            &request(r.observer, 0),
            &mut frame,
        );
        assert!(frame.points.is_empty() && frame.paths.is_empty());
        assert_eq!(frame.picture.pixels.len(), 48 * 36 * 3);
    }
}

#[cfg(test)]
mod progress_tests {
    use super::*;
    use crate::camera::Camera;
    use crate::scene::REFERENCES;
    use crate::shading::{Backdrop, ShadingMode};
    use std::sync::atomic::Ordering;

    /// The picture's progress counter ends at twice its height (centres, then edges), every time.
    #[test]
    fn the_progress_counter_counts_the_rows() {
        let r = REFERENCES[1];
        let scene = r.scene(1.333);
        let camera = Camera::new(r.observer, crate::scene::SCENE_CENTRE, 64, 48, 1.2);
        let mut frame = Frame::default();
        let counter = frame.picture_progress();
        for samples in [1, 3] {
            let request = FrameRequest {
                camera,
                shading: ShadingOptions {
                    mode: ShadingMode::Fresnel { prune_below: 1e-4 },
                    backdrop: Backdrop::Checker,
                    samples,
                    adaptive: true,
                    outline: true,
                    white: false,
                },
                min_points: 0,
            };
            draw_frame(&World::assignment(&scene), &request, &mut frame);
            assert_eq!(counter.load(Ordering::Relaxed), 2 * 48);
        }
    }
}
