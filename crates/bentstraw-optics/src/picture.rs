//! The observer's picture as data, one ray per pixel centre of the observer's (pinhole) camera:
//! colour codes (course mode: refraction or total reflection at each face) or weights per colour
//! code (fresnel mode: each branch weighted by the Fresnel reflectance), row-major, of any world.
//!
//! Traced two ways: in single precision, eight rays at a time ([`crate::packet`], what pictures
//! use), and in double precision, one ray at a time (the `_exact` functions, what raw files hold
//! and the tests compare the packets with).

use crate::parallel::*;

use crate::camera::Camera;
use crate::packet::{FresnelWave, PacketTracer};
use crate::world::{World, COLOR_COUNT, FRESNEL_SEGMENTS_PER_RAY};

/// Most rows one task of a picture traces. Rows differ in cost (air costs nothing, water and the
/// straw much), and rayon splits a loop only into as many pieces as it has threads, re-splitting a
/// piece only when another thread steals it: rows in small tasks let a core that is done take work
/// from the other until the end, at the cost of a few microseconds per task.
const ROWS_PER_TASK: usize = 4;

/// Colour code (0 = nothing) of the ray through each pixel centre, row-major, by the course's law.
///
/// Traced in single precision, eight rays at a time ([`crate::packet`]): the same pixels as
/// [`course_picture_exact`] except, rarely, on a colour boundary.
pub fn course_picture(world: &World, camera: &Camera) -> Vec<u8> {
    let mut codes = vec![0u8; camera.width as usize * camera.height as usize];
    course_picture_into(world, camera, &mut codes);
    codes
}

/// [`course_picture`] into a caller's buffer of `width × height` codes (an interactive view keeps
/// one and redraws into it, with no allocation per picture).
pub fn course_picture_into(world: &World, camera: &Camera, codes: &mut [u8]) {
    let tracer = PacketTracer::new(world);
    let w = camera.width as usize;
    assert_eq!(
        codes.len(),
        w * camera.height as usize,
        "one code per pixel"
    );
    codes
        .par_chunks_mut(w)
        .enumerate()
        .with_max_len(ROWS_PER_TASK)
        .for_each(|(i, row)| {
            tracer.course_row(camera, i as u32, row);
        });
}

/// Colour code (0 = nothing) of the ray through each pixel centre, row-major, by the course's law,
/// traced in double precision: exactly [`World::trace`]'s colours.
pub fn course_picture_exact(world: &World, camera: &Camera) -> Vec<u8> {
    let w = camera.width as usize;
    let mut codes = vec![0u8; w * camera.height as usize];
    codes.par_chunks_mut(w).enumerate().for_each(|(i, row)| {
        for (j, code) in row.iter_mut().enumerate() {
            *code = world.trace(camera.pixel_ray(i as u32, j as u32)).color();
        }
    });
    codes
}

/// The weight reaching each colour code (index 0 = code 1) of the ray through each pixel centre,
/// row-major, in fresnel mode.
///
/// Traced in single precision, breadth first, eight branches at a time ([`crate::packet`]): the
/// weights of [`fresnel_picture_exact`] to about 1e-4, except, rarely, on a boundary.
pub fn fresnel_picture(
    world: &World,
    camera: &Camera,
    prune_below: f64,
) -> Vec<[f64; COLOR_COUNT]> {
    let mut weights = vec![[0.0; COLOR_COUNT]; camera.width as usize * camera.height as usize];
    fresnel_picture_into(world, camera, prune_below, &mut weights);
    weights
}

/// [`fresnel_picture`] into a caller's buffer of `width × height` pixels of the first `N` colour
/// codes (the straw's five bands need no more; codes past `N` are not kept). Every pixel is
/// written.
pub fn fresnel_picture_into<const N: usize>(
    world: &World,
    camera: &Camera,
    prune_below: f64,
    weights: &mut [[f64; N]],
) {
    let tracer = PacketTracer::new(world);
    let w = camera.width as usize;
    assert_eq!(
        weights.len(),
        w * camera.height as usize,
        "one pixel per pixel"
    );
    weights
        .par_chunks_mut(w)
        .enumerate()
        .with_max_len(ROWS_PER_TASK)
        .for_each_init(FresnelWave::pooled, |wave, (i, row)| {
            tracer.fresnel_row(camera, i as u32, prune_below, wave, row);
        });
}

/// The weight reaching each colour code of the ray through each pixel centre, row-major, in
/// fresnel mode, traced in double precision (branches that provably escape are not followed).
pub fn fresnel_picture_exact(
    world: &World,
    camera: &Camera,
    prune_below: f64,
) -> Vec<[f64; COLOR_COUNT]> {
    let w = camera.width as usize;
    let mut weights = vec![[0.0; COLOR_COUNT]; w * camera.height as usize];
    weights.par_chunks_mut(w).enumerate().for_each(|(i, row)| {
        for (j, px) in row.iter_mut().enumerate() {
            let ray = camera.pixel_ray(i as u32, j as u32);
            *px = world.fresnel_steps::<true>(ray, prune_below, FRESNEL_SEGMENTS_PER_RAY, |_| {});
        }
    });
    weights
}
